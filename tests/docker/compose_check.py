"""The checks of tests/docker/compose_test.sh on `docker-compose config`'s resolved file.

compose_check.py REPO RESOLVED_YAML PACKAGES_FILE: prints each failure and a count, exits 1
on any failure. Parses the Dockerfiles itself (stages, FROM chains, USER, EXPOSE,
HEALTHCHECK, COPY, RUN, ENTRYPOINT): there is no engine here to ask.
"""
import os, re, sys, yaml

from checks import check, read, report

repo, resolved, packages = sys.argv[1:4]
services = yaml.safe_load(open(resolved))["services"]

def parse_dockerfile(path):
    """Stages in order, each with its parent and the instructions this test looks at."""
    stages = {}
    text = re.sub(r"\\\n", " ", read(path))
    for line in text.splitlines():
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        instr, _, rest = line.partition(" ")
        instr = instr.upper()
        if instr == "FROM":
            m = re.match(r"(?:--\S+\s+)*(\S+)(?:\s+AS\s+(\S+))?", rest, re.I)
            cur = stages.setdefault(m.group(2) or str(len(stages)), dict(
                parent=m.group(1), user=None, expose=set(), health=None, copies=[], runs=[], entry=None))
        elif instr == "USER":
            cur["user"] = rest.split(":")[0].strip()
        elif instr == "EXPOSE":
            cur["expose"] |= {p.split("/")[0] for p in rest.split()}
        elif instr == "HEALTHCHECK":
            cur["health"] = not rest.upper().startswith("NONE")
        elif instr in ("COPY", "ADD"):
            cur["copies"].append(rest)
        elif instr == "RUN":
            cur["runs"].append(rest)
        elif instr == "ENTRYPOINT":
            m = re.match(r'\[\s*"([^"]+)"', rest)
            cur["entry"] = m.group(1) if m else rest.split()[0]
    return stages

def chain(stages, name):
    """The stage and the stages it is built FROM, nearest first."""
    while name in stages:
        yield stages[name]
        name = stages[name]["parent"]

def effective(stages, name, key):
    return next((s[key] for s in chain(stages, name) if s[key] is not None), None)

def copy_parts(copy):
    words = copy.strip("[]").replace('"', "").replace(",", " ").split()
    flags = [w for w in words if w.startswith("--")]
    rest = [w for w in words if not w.startswith("--")]
    return flags, rest[:-1], rest[-1]

# Programs per install component: install(TARGETS prog ... COMPONENT c) in any CMake file.
component_programs = {}
for root, dirs, files in os.walk(repo):
    dirs[:] = [d for d in dirs if not (d.startswith(".") or d.startswith("build"))]
    for f in files:
        if f == "CMakeLists.txt" or f.endswith(".cmake"):
            for m in re.finditer(r"install\(TARGETS\s+([\w.+\- ]+?)\s+RUNTIME[^)]*?COMPONENT\s+(\w+)", read(os.path.join(root, f))):
                component_programs.setdefault(m.group(2), set()).update(m.group(1).split())

# Every service built from a Dockerfile: the file, its target stage, a non-root user.
dockerfiles = {}
for name, svc in services.items():
    build = svc.get("build")
    if not build:
        continue
    path = os.path.join(build["context"], build.get("dockerfile", "Dockerfile"))
    check(os.path.isfile(path), f"service {name}: Dockerfile {path} does not exist")
    if not os.path.isfile(path):
        continue
    stages = dockerfiles.setdefault(path, parse_dockerfile(path))
    target = build.get("target", list(stages)[-1])
    check(target in stages, f"service {name}: {path} has no stage '{target}'")
    svc["_stages"], svc["_target"] = stages, target
    user = svc.get("user") or effective(stages, target, "user")
    check(user not in (None, "root", "0"), f"service {name}: runs as root (no USER in stage '{target}' or its parents)")

# Runtime stages (compose targets, the last stage, any stage copying from another): non-root.
for path, stages in dockerfiles.items():
    used = {s["_target"] for s in services.values() if s.get("_stages") is stages}
    for name, stage in stages.items():
        runtime = name in used or name == list(stages)[-1] or any("--from" in c for c in stage["copies"])
        if runtime:
            user = effective(stages, name, "user")
            check(user not in (None, "root", "0"), f"{path}: runtime stage '{name}' has no non-root USER")

    # Programs: the build stage installs CMake components (cmake --install --component, into
    # /stage/COMPONENT); the images copy a component's tree, or programs from it.
    staged = set()
    for stage in stages.values():
        for run in stage["runs"]:
            if "cmake --install" not in run:
                continue
            staged |= set(re.findall(r"--component\s+(\w+)", run))
            for m in re.finditer(r"for\s+(\w+)\s+in\s+([\w ]+?);\s*do(.*?)done", run):
                if "--component $" + m.group(1) in m.group(3) or "--component ${" + m.group(1) + "}" in m.group(3):
                    staged |= set(m.group(2).split())
    for c in sorted(staged):
        check(c in component_programs, f"{path}: installs component {c}, which no install(TARGETS ...) names")
    for sname, stage in stages.items():
        provided = set()
        for copy in stage["copies"]:
            flags, sources, dest = copy_parts(copy)
            if any(f.startswith("--from") for f in flags):
                for src in sources:
                    m = re.match(r"/stage/(\w+)(/.*)?$", src)
                    check(m is not None, f"{path}: stage '{sname}' copies {src}, not from an installed component (/stage/COMPONENT)")
                    if not m:
                        continue
                    component, inner = m.group(1), (m.group(2) or "/").rstrip("/")
                    check(component in staged, f"{path}: stage '{sname}' copies component {component}, which the build stage does not install")
                    programs = component_programs.get(component, set())
                    if inner in ("", "/usr", "/usr/bin"):
                        provided |= programs
                    else:
                        b = os.path.basename(inner)
                        check(b in programs, f"{path}: stage '{sname}' copies {src}: component {component} installs no program {b}")
                        provided.add(b)
            else:
                for src in sources:
                    check(os.path.exists(os.path.join(repo, src)), f"{path}: COPY source {src} does not exist")
                    provided.add(os.path.basename(src))
                provided.add(os.path.basename(dest.rstrip("/")))
        stage["_provided"] = provided
    for sname in stages:
        entry = effective(stages, sname, "entry")
        if entry and not entry.startswith("/"):
            have = set().union(*(s.get("_provided", set()) for s in chain(stages, sname)))
            check(entry in have, f"{path}: stage '{sname}' ENTRYPOINT {entry} is not copied into it")

    # The build stage must copy every directory the top-level CMakeLists.txt adds.
    copied = {src.rstrip("/") for s in stages.values() for c in s["copies"]
              for src in copy_parts(c)[1] if not any(f.startswith("--from") for f in copy_parts(c)[0])}
    # Not what only the tests need: the images build with BUILD_TESTING=OFF.
    top = re.sub(r"if\(BUILD_TESTING\)(.*?)\nendif\(\)", "", read(os.path.join(repo, "CMakeLists.txt")), flags=re.S)
    for sub in re.findall(r"add_subdirectory\(\s*([\w/.-]+)", top):
        check(any(sub == c or sub.startswith(c + "/") or c == "." for c in copied),
              f"{path}: add_subdirectory({sub}) but the build stage does not COPY {sub}")

    # What the build stage installs must be in the project's list (catches typos, renames).
    known = set(read(packages).split())
    for sname, stage in stages.items():
        if any("cmake --install" in run for run in stage["runs"]):
            for run in stage["runs"]:
                for m in re.finditer(r"apt-get install((?:\s+[^\s&;|]+)+)", run):
                    for pkg in (w for w in m.group(1).split() if not w.startswith("-")):
                        check(pkg in known, f"{path}: stage '{sname}' installs {pkg}, which DTMF_PACKAGES lacks")

def container_ports(svc):
    for p in svc.get("ports", []):
        if isinstance(p, dict):
            yield str(p.get("target"))
        else:
            yield str(p).split("/")[0].rsplit(":", 1)[-1]

def has_health(svc):
    hc = svc.get("healthcheck")
    if hc is not None:
        return not hc.get("disable") and hc.get("test") not in (["NONE"], "NONE")
    return bool(svc.get("_stages") and effective(svc["_stages"], svc["_target"], "health"))

# A service that runs another program than its image's entrypoint must not keep the image's
# health check, which asks that program (the console, in the server's image, never turned
# healthy under the server's `dtmfctl health`).
for name, svc in services.items():
    if svc.get("_stages") and svc.get("entrypoint") and effective(svc["_stages"], svc["_target"], "health"):
        own = str(svc["entrypoint"][0] if isinstance(svc["entrypoint"], list) else svc["entrypoint"]).split()[0]
        image_entry = effective(svc["_stages"], svc["_target"], "entry")
        check(own == image_entry or "healthcheck" in svc,
              f"service {name} runs {own}, not its image's {image_entry}, yet keeps the image's health check: give it its own")

server = services.get("server")
check(server is not None, "no service 'server'")
if server:
    check("50051" in set(container_ports(server)), "service server does not publish port 50051")
    if server.get("_stages"):
        check("50051" in set().union(*(s["expose"] for s in chain(server["_stages"], server["_target"]))),
              "the server image does not EXPOSE 50051")

pg = services.get("postgres")
check(pg is not None, "no service 'postgres'")
if pg:
    check("pg_isready" in str((pg.get("healthcheck") or {}).get("test")), "service postgres has no pg_isready healthcheck")

# depends_on conditions that compose would only discover at `up`.
for name, svc in services.items():
    for dep, spec in (svc.get("depends_on") or {}).items():
        check(dep in services, f"service {name} depends on unknown service {dep}")
        if spec.get("condition") == "service_healthy" and dep in services:
            check(has_health(services[dep]), f"service {name} waits for {dep} to be healthy, but {dep} has no healthcheck")

# Migrations before the programs log: a migrate service they wait for.
migrators = [n for n, s in services.items() if s.get("_stages") and effective(s["_stages"], s["_target"], "entry") == "dtmf-migrate"]
check(migrators, "no service runs dtmf-migrate")
for name, svc in services.items():
    if "DTMF_DB_URL" in (svc.get("environment") or {}) and migrators:
        cond = ((svc.get("depends_on") or {}).get(migrators[0]) or {}).get("condition")
        check(cond == "service_completed_successfully",
              f"service {name} logs to the database without waiting for {migrators[0]} to complete")

# The air: its socket directory, volume and sink as the audio services expect them.
air_sh, scripts_air = read(os.path.join(repo, "docker/air.sh")), read(os.path.join(repo, "scripts/air"))
sink_args = "module-null-sink sink_name=air rate=48000 channels=1"
check(sink_args in air_sh and sink_args in scripts_air, f"docker/air.sh and scripts/air differ on '{sink_args}'")
check("--latency-msec=20" in air_sh and "--latency-msec=20" in scripts_air, "docker/air.sh and scripts/air differ on the silent stream")
m = re.search(r"DTMF_AIR_DIR:-([^}]+)\}", air_sh)
check(m, "docker/air.sh no longer says where its socket goes (DTMF_AIR_DIR:-...)")
air_dir = m.group(1) if m else None

def mounts(svc):
    for v in svc.get("volumes", []):
        if isinstance(v, dict):
            yield v.get("source"), v.get("target")
        else:
            parts = v.split(":")
            yield parts[0], parts[1] if len(parts) > 1 else parts[0]

air = services.get("air")
check(air is not None, "no service 'air'")
air_sources = {src for src, dst in mounts(air or {}) if dst == air_dir}
check(air_sources, f"service air mounts no volume at {air_dir}, where docker/air.sh puts its socket")
for name, svc in services.items():
    env = svc.get("environment") or {}
    if "PULSE_SERVER" not in env:
        continue
    sock_dir = os.path.dirname(env["PULSE_SERVER"].removeprefix("unix:"))
    src = {s for s, d in mounts(svc) if d == sock_dir}
    check(src and src <= air_sources, f"service {name}: PULSE_SERVER's directory {sock_dir} is not the air's volume")
    check(env.get("PULSE_SINK") == "air", f"service {name}: PULSE_SINK is not the air's sink 'air'")
    check("air" in (svc.get("depends_on") or {}), f"service {name} uses the air but does not depend on it")

ignore = os.path.join(repo, ".dockerignore")
check(os.path.exists(ignore) and re.search(r"^/?build/?$", read(ignore), re.M),
      ".dockerignore is missing or does not exclude build/")

sys.exit(report())
