#!/usr/bin/env python3
"""docker.runtime_packages: every runtime image of docker/Dockerfile installs the Debian
package of each library its programs load. The image build checks this itself (its build
stage runs docker/runtime-packages.sh), but only inside Docker, which the suite has not: a
dtmf-migrate that began linking spdlog broke `up --build` unseen (issue 59). So the same
derivation, offline, on this build's programs:
  - each runtime stage's programs are what it copies from the build stage (COPY --from=build
    /stage/COMPONENT/...), its packages the *_PACKAGES ARG it installs: both read from the
    Dockerfile, as is the build stage's own check, which must cover the same programs;
  - this build's components are installed into a scratch /stage as the build stage does
    (DESTDIR=/stage/COMPONENT cmake --install --component), so those paths hold its programs;
  - docker/runtime-packages.sh maps their libraries to packages (dpkg-shlibdeps) and names
    any the image would lack, counting what the base image has from bookworm-slim-packages.
  runtime_packages_test.py REPO BUILD_DIR"""
import os, re, shlex, subprocess, sys, tempfile

repo, build = (os.path.realpath(a) for a in sys.argv[1:3])
dockerfile = os.path.join(repo, "docker/Dockerfile")
errors = []


def fail(message):
    errors.append(message)
    print(f"docker.runtime_packages: FAIL: {message}", file=sys.stderr)


# The Dockerfile's instructions (continuations joined): global ARG defaults, and each stage's
# ARGs, RUNs and the sources it copies from the build stage.
with open(dockerfile) as f:
    text = re.sub(r"\\\n", " ", f.read())
defaults, stages, stage = {}, {}, None
for line in text.splitlines():
    word, _, rest = line.strip().partition(" ")
    word = word.upper()
    if word == "FROM":
        m = re.search(r"\sAS\s+(\S+)", line, re.I)
        stage = stages.setdefault(m.group(1) if m else str(len(stages)), {"args": [], "runs": [], "copies": []})
    elif word == "ARG" and stage is None:
        name, _, value = rest.partition("=")
        defaults[name.strip()] = " ".join(shlex.split(value))
    elif word == "ARG":
        stage["args"].append(rest.partition("=")[0].strip())
    elif word == "RUN":
        stage["runs"].append(rest)
    elif word == "COPY" and re.search(r"--from=build\b", rest):
        stage["copies"] += [w.rstrip("/") for w in rest.split()[:-1] if not w.startswith("--")]

build_runs = " ".join(r for s in stages.values() for r in s["runs"] if "cmake --install" in r)
m = re.search(r"cmake --install \S+ --prefix (\S+)", build_runs)
prefix = m.group(1) if m else "/usr"
# The build stage's own check: runtime-packages IMAGE "$VAR" PATH...
checked = {m.group(1): (m.group(2), {p.rstrip("/") for p in m.group(3).split()})
           for r in (r for s in stages.values() for r in s["runs"])
           for m in re.finditer(r'runtime-packages\s+(\S+)\s+"\$(\w+)"((?:\s+/stage\S*)+)', r)}

images = {name: s for name, s in stages.items() if s["copies"]}
if not images:
    fail(f"{dockerfile}: no stage copies programs from the build stage (COPY --from=build)")
scratch = tempfile.TemporaryDirectory()  # removed at exit
tmp = scratch.name
stage_dir = os.path.join(tmp, "stage")
base = os.path.join(tmp, "base-packages")
with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "bookworm-slim-packages")) as f, open(base, "w") as out:
    out.writelines(line for line in f if not line.startswith("#"))

for component in sorted({p.split("/")[2] for s in images.values() for p in s["copies"] if p.startswith("/stage/")}):
    r = subprocess.run(["cmake", "--install", build, "--prefix", prefix, "--component", component],
                       env=dict(os.environ, DESTDIR=os.path.join(stage_dir, component)), capture_output=True, text=True)
    if r.returncode != 0:
        fail(f"cmake --install {build} --component {component} failed (are its programs built? "
             f"scripts/test builds them all):\n{(r.stdout + r.stderr)[-1500:].strip()}")
if errors:  # a partial stage would only add misleading findings
    sys.exit(1)

running = {}
for image, s in images.items():
    var = [a for a in s["args"] if a.endswith("_PACKAGES")]
    if len(var) != 1 or not any(f"${var[0]}" in r for r in s["runs"]):
        fail(f"stage {image} copies {' '.join(s['copies'])} from the build stage, but does not install one "
             "*_PACKAGES list (ARG NAME_PACKAGES, then apt-get install $NAME_PACKAGES) for their libraries")
        continue
    var, copies = var[0], set(s["copies"])
    if checked.get(image) != (var, copies):
        got = checked.get(image)
        fail(f"the build stage's runtime-packages check of {image} "
             + (f"takes ${got[0]} on {' '.join(sorted(got[1]))}" if got else "is missing")
             + f", but stage {image} installs ${var} and copies {' '.join(sorted(copies))}: make them the same")
    paths = [stage_dir + p[len("/stage"):] for p in sorted(copies)]
    # Side by side: dpkg-shlibdeps takes seconds on each image's programs.
    running[image] = subprocess.Popen(
        ["bash", os.path.join(repo, "docker/runtime-packages.sh"), image, defaults.get(var, ""), *paths],
        env=dict(os.environ, BASE_PACKAGES_FILE=base), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
for image, proc in running.items():
    out, err = proc.communicate()
    print(out.replace(stage_dir, "/stage"), end="")
    if proc.returncode != 0:
        fail(err.replace(stage_dir, "/stage").strip().replace("runtime-packages: FAIL: ", ""))

print(f"docker.runtime_packages: {len(images)} images, " + ("FAIL" if errors else "PASS"))
sys.exit(1 if errors else 0)
