"""The checks of tests/docker/compose_test.sh on what the build stage installs and on the
database image: build_stage_check.py REPO COMPOSE_FILE TMP (TMP holds the resolved compose
files). Prints each failure and a count, exits 1 on any failure."""
import glob, os, re, subprocess, sys, yaml

from checks import check, read, report

repo, compose, tmp = sys.argv[1:4]

# ---- postgres: ${DTMF_POSTGRES_IMAGE:-postgres:15}, and a stand-in that matches compose ----
raw = yaml.safe_load(read(compose))["services"].get("postgres") or {}
check(raw.get("image") == "${DTMF_POSTGRES_IMAGE:-postgres:15}",
      f"service postgres: image is {raw.get('image')!r}, not '${{DTMF_POSTGRES_IMAGE:-postgres:15}}' (the official "
      "image by default, a stand-in such as docker/postgres where it cannot be pulled)")
for name, want in (("resolved.yaml", "postgres:15"), ("resolved-stand-in.yaml", "stand-in:1")):
    got = yaml.safe_load(read(os.path.join(tmp, name)))["services"]["postgres"].get("image")
    check(got == want, f"service postgres resolves to image {got!r}, expected {want!r}")
stand_in = os.path.join(repo, "docker/postgres")
entry = os.path.join(stand_in, "entrypoint.sh")
check(os.path.isfile(os.path.join(stand_in, "Dockerfile")) and os.path.isfile(entry),
      "docker/postgres (Dockerfile, entrypoint.sh): the stand-in for postgres:15 is missing")
if os.path.isfile(entry):
    text = read(entry) + read(os.path.join(stand_in, "Dockerfile"))
    for var in sorted(set(re.findall(r"\$\{?(POSTGRES_[A-Z]+)", yaml.dump(raw.get("environment") or {})))
                      | {k for k in (raw.get("environment") or {}) if k.startswith("POSTGRES_")}):
        check(var in text, f"docker/postgres does not honour {var}, which service postgres sets")
    for v in raw.get("volumes") or []:
        target = v.split(":")[1] if isinstance(v, str) else v.get("target")
        check(target in text, f"docker/postgres keeps its data elsewhere than {target}, where compose mounts the volume")
    check("pg_isready" not in str((raw.get("healthcheck") or {}).get("test")) or "postgresql-15" in text,
          "service postgres checks health with pg_isready, which docker/postgres does not install (postgresql-15)")

# ---- the build stage: what it installs, what it copies ----
services = yaml.safe_load(read(os.path.join(tmp, "resolved.yaml")))["services"]
dockerfiles = sorted({os.path.join(s["build"]["context"], s["build"].get("dockerfile", "Dockerfile"))
                      for s in services.values() if s.get("build")})

def stages(path):
    out, cur = {}, None
    for line in re.sub(r"\\\n", " ", read(path)).splitlines():
        line = line.strip()
        word, _, rest = line.partition(" ")
        if word.upper() == "FROM":
            m = re.match(r"(?:--\S+\s+)*(\S+)(?:\s+AS\s+(\S+))?", rest, re.I)
            cur = out.setdefault(m.group(2) or str(len(out)), {"runs": [], "copies": []})
        elif cur is not None and word.upper() == "RUN":
            cur["runs"].append(rest)
        elif cur is not None and word.upper() in ("COPY", "ADD") and "--from" not in rest:
            cur["copies"].append(rest.replace('"', "").strip("[]").replace(",", " ").split()[:-1])
    return out

# This machine's dpkg: each installed package's Depends (+ Pre-Depends) and what provides what.
fmt = "${Package}\t${db:Status-Abbrev}\t${Essential}\t${Depends}, ${Pre-Depends}\t${Provides}\n"
installed, provides, essential = {}, {}, set()
for line in subprocess.run(["dpkg-query", "-W", "-f=" + fmt], capture_output=True, text=True).stdout.splitlines():
    pkg, status, ess, depends, provided = line.split("\t")
    if not status.startswith("ii"):
        continue
    installed[pkg] = depends
    if ess == "yes":
        essential.add(pkg)
    for p in provided.split(","):
        p = re.sub(r"\(.*?\)", "", p).strip().split(":")[0]
        if p:
            provides.setdefault(p, []).append(pkg)
def resolve(name):
    return name if name in installed else next(iter(provides.get(name, [])), None)
def closure(names):
    seen, todo = set(), list(names)
    while todo:
        pkg = resolve(todo.pop())
        if not pkg or pkg in seen:
            continue
        seen.add(pkg)
        for group in installed[pkg].split(","):
            alts = [a for a in (re.sub(r"\(.*?\)", "", a).strip().split(":")[0] for a in group.split("|")) if a]
            if alts:  # apt takes the first alternative it can
                todo.append(next((a for a in alts if resolve(a)), alts[0]))
    return seen

def owners(paths):
    """path -> the packages dpkg says own it (trying the /usr-merged twin too)."""
    twins = {}
    for p in paths:
        cands = [p, os.path.realpath(p)]
        cands += [c.replace("/usr/lib/", "/lib/", 1) for c in cands if c.startswith("/usr/lib/")]
        cands += [c.replace("/usr/bin/", "/bin/", 1) for c in cands if c.startswith("/usr/bin/")]
        twins[p] = list(dict.fromkeys(cands))
    found = {}
    out = subprocess.run(["dpkg", "-S"] + sorted({c for cs in twins.values() for c in cs}),
                         capture_output=True, text=True).stdout
    for line in out.splitlines():
        m = re.match(r"^(.+?): (/.*)$", line)
        if m and not line.startswith("diversion"):
            found.setdefault(m.group(2), set()).update(o.strip().split(":")[0] for o in m.group(1).split(","))
    return {p: set().union(*(found.get(c, set()) for c in cs)) for p, cs in twins.items()}

CALL = re.compile(r"^[ \t]*(find_package|pkg_check_modules|pkg_search_module|find_library|find_program)\s*\(([^)]*)\)", re.M | re.I)
def without_testing(text):
    """The file less its if(BUILD_TESTING) ... endif() blocks (the images build without tests)."""
    out, depth = [], 0
    for line in text.splitlines():
        if depth:
            depth += len(re.findall(r"^\s*if\s*\(", line, re.I)) - len(re.findall(r"^\s*endif\s*\(", line, re.I))
            out.append("")
        elif re.match(r"^\s*if\s*\(\s*BUILD_TESTING\s*\)", line, re.I):
            depth = 1
            out.append("")
        else:
            out.append(line)
    return "\n".join(out)

for dockerfile in dockerfiles:
    build = [s for s in stages(dockerfile).values() if any("cmake --build" in r or "cmake --install" in r for r in s["runs"])]
    check(build, f"{dockerfile}: no stage runs cmake --build")
    if not build:
        continue
    build = build[0]
    named = [w for r in build["runs"] for m in re.finditer(r"apt-get install((?:\s+[^\s&;|]+)+)", r)
             for w in m.group(1).split() if not w.startswith("-")]
    have = closure(named) | essential
    # The CMake files the build stage copies, in the order CMake would meet them (roughly).
    files = []
    for srcs in build["copies"]:
        for src in srcs:
            path = os.path.join(repo, src)
            if os.path.isfile(path) and (src.endswith("CMakeLists.txt") or src.endswith(".cmake")):
                files.append(path)
            elif os.path.isdir(path):
                for root, dirs, names in os.walk(path):
                    dirs.sort()
                    files += [os.path.join(root, n) for n in sorted(names) if n == "CMakeLists.txt" or n.endswith(".cmake")]
    calls, settings = [], []
    for f in files:
        text = without_testing(read(f))
        settings += re.findall(r"^[ \t]*(set\s*\(\s*CURSES_NEED_\w+[^)]*\))", text, re.M)
        for m in CALL.finditer(text):
            args = m.group(2).split()
            if "REQUIRED" not in args and m.group(1).lower() != "pkg_check_modules":
                continue
            where = f"{os.path.relpath(f, repo)}:{text.count(chr(10), 0, m.start()) + 1}"
            calls.append((where, f"{m.group(1)}({' '.join(args)})", m.group(1).lower(), args))
    check(calls, f"{dockerfile}: found no find_package(...) in the CMake files its build stage copies")

    # A scratch project makes the same calls here and lists the cache entries each one added.
    scratch = os.path.join(tmp, "finds")
    os.makedirs(scratch, exist_ok=True)
    dump = os.path.join(scratch, "found.txt")
    body = ["cmake_minimum_required(VERSION 3.25)", "project(finds C CXX)", "find_package(PkgConfig REQUIRED)"] + settings
    for i, (_, call, _, _) in enumerate(calls):
        body += ["get_cmake_property(before CACHE_VARIABLES)", call,
                 "get_cmake_property(after CACHE_VARIABLES)", "list(REMOVE_ITEM after ${before})",
                 f'foreach(v IN LISTS after)\n  file(APPEND "{dump}" "{i}\t${{v}}\t${{${{v}}}}\\n")\nendforeach()']
    body += ["get_cmake_property(all CACHE_VARIABLES)",
             f'foreach(v IN LISTS all)\n  file(APPEND "{dump}" "all\t${{v}}\t${{${{v}}}}\\n")\nendforeach()']
    with open(os.path.join(scratch, "CMakeLists.txt"), "w") as f:
        f.write("\n".join(body) + "\n")
    r = subprocess.run(["cmake", "-S", scratch, "-B", os.path.join(scratch, "build")], capture_output=True, text=True)
    check(r.returncode == 0, "a scratch CMake project making the build's find_package calls failed on this machine "
          "(install DTMF_PACKAGES: scripts/test does):\n" + r.stderr[-1500:])
    if r.returncode != 0:
        continue
    # Each call's files: those of its own cache entries (a package's NAME_*, a pkg-config
    # prefix's pkgcfg_lib_PREFIX_*, find_library's variable), found by it or earlier; else
    # whatever the call added.
    def files_of(var, value):
        out = []
        for v in value.split(";"):
            if v.endswith("-NOTFOUND") or not v.startswith("/"):
                continue
            if var.endswith("_DIR") and os.path.isdir(v):  # a package's config file
                out += glob.glob(v + "/*onfig.cmake") + glob.glob(v + "/*-config.cmake")
            elif os.path.isfile(v):
                out.append(v)
        return out
    added, cache = {}, {}
    for line in (read(dump) if os.path.exists(dump) else "").splitlines():
        i, var, value = (line.split("\t") + ["", ""])[:3]
        if i == "all":
            cache[var] = value
        else:
            added.setdefault(int(i), []).extend(files_of(var, value))
    found = {}
    for i, (_, _, kind, args) in enumerate(calls):
        if kind == "find_package":
            own = lambda var: var.lower().startswith(args[0].lower() + "_")
        elif kind in ("pkg_check_modules", "pkg_search_module"):
            own = lambda var: var.startswith(f"pkgcfg_lib_{args[0]}_")
        else:
            own = lambda var: var == args[0]
        paths = [p for var, value in sorted(cache.items()) if own(var) for p in files_of(var, value)]
        if kind in ("pkg_check_modules", "pkg_search_module"):  # pkg-config's own file of each module
            for mod in args[1:]:
                mod = re.split(r"[<>=]", mod)[0]
                if not mod or mod in ("REQUIRED", "QUIET", "IMPORTED_TARGET", "GLOBAL", "NO_CMAKE_PATH",
                                      "NO_CMAKE_ENVIRONMENT_PATH"):
                    continue
                d = subprocess.run(["pkg-config", "--variable=pcfiledir", mod], capture_output=True, text=True).stdout.strip()
                if d and os.path.isfile(f"{d}/{mod}.pc"):
                    paths.append(f"{d}/{mod}.pc")
        found[i] = list(dict.fromkeys(paths or added.get(i, [])))
    owned = owners({p for ps in found.values() for p in ps})
    for i, (where, call, _, _) in enumerate(calls):
        paths = found.get(i, [])
        pkgs = [o for p in paths for o in sorted(owned.get(p, ()))]
        if os.environ.get("COMPOSE_TEST_VERBOSE"):
            print(f"  {where}: {call}: {' '.join(sorted(set(pkgs))) or '(no files)'}")
        if not pkgs:
            continue  # nothing on disk to own (Threads): nothing to install
        check(any(p in have for p in pkgs),
              f"{where}: {call} finds {paths[0]} of {max(sorted(set(pkgs)), key=pkgs.count)}, which the build "
              f"stage of {os.path.relpath(dockerfile, repo)} does not install: add it to that stage's "
              "apt-get install (and to DTMF_PACKAGES)")

sys.exit(report("the build stage's libraries, postgres"))
