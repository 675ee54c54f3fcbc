"""PEP 517 build backend of dtmf-teleop: a wheel of src/dtmf_teleop plus gRPC stubs.

The stubs are generated here, at every build, from the repository's proto/ (or the copy an
sdist carries) with protoc and grpc_python_plugin (Debian: protobuf-compiler,
protobuf-compiler-grpc), so they are never edited by hand and never stale. The backend
needs nothing from PyPI: `pip install clients/python` works offline with Debian's pip.

Stubs land in dtmf_teleop/_stubs/, and their imports are rewritten to point there (protoc
writes `from dtmf.v1 import ...`, which would need a top-level `dtmf` package, and
`from grpc.health.v1 import ...`, which would clash with the grpc package itself).
"""

from __future__ import annotations

import base64
import hashlib
import io
import os
import re
import shutil
import subprocess
import tarfile
import tempfile
import tomllib
import zipfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PACKAGE = "dtmf_teleop"
# The service, and the standard health service the server also offers.
PROTOS = [("dtmf/v1/teleop.proto", "proto"), ("grpc/health/v1/health.proto", "grpc-proto")]
GRPC_PROTO_DIR = Path(os.environ.get("DTMF_GRPC_PROTO_DIR", "/usr/share/grpc-proto"))


def _project() -> dict:
    with open(ROOT / "pyproject.toml", "rb") as f:
        return tomllib.load(f)["project"]


def _dist_name() -> str:
    return re.sub(r"[-_.]+", "_", _project()["name"]).lower()


def _proto_dir() -> Path:
    """proto/ of an sdist, else of the repository this folder sits in."""
    for candidate in (ROOT / "proto", ROOT.parent.parent / "proto"):
        if (candidate / "dtmf/v1/teleop.proto").is_file():
            return candidate
    raise RuntimeError(f"dtmf/v1/teleop.proto not found under {ROOT / 'proto'} or {ROOT.parent.parent / 'proto'}: "
                       "build from a checkout of the dtmf-teleop repository or from its sdist")


def _tool(name: str, package: str) -> str:
    path = shutil.which(name)
    if not path:
        raise RuntimeError(f"{name} not found: install it with `apt-get install {package}`")
    return path


def _generate_stubs(out: Path) -> None:
    protoc = _tool("protoc", "protobuf-compiler")
    plugin = _tool("grpc_python_plugin", "protobuf-compiler-grpc")
    include = {"proto": _proto_dir(), "grpc-proto": GRPC_PROTO_DIR}
    for proto, where in PROTOS:
        if not (include[where] / proto).is_file():
            raise RuntimeError(f"{include[where] / proto} not found: install it with `apt-get install grpc-proto`")
        subprocess.run([protoc, f"--proto_path={include[where]}", f"--python_out={out}", f"--grpc_python_out={out}",
                        f"--plugin=protoc-gen-grpc_python={plugin}", str(include[where] / proto)], check=True)
    for py in out.rglob("*.py"):
        text = py.read_text()
        text = re.sub(r"^from (dtmf|grpc)\.(\S+) import", rf"from {PACKAGE}._stubs.\1.\2 import", text, flags=re.M)
        py.write_text(text)
    for folder in [out, *[p for p in out.rglob("*") if p.is_dir()]]:
        (folder / "__init__.py").touch()


def _metadata() -> str:
    p = _project()
    lines = ["Metadata-Version: 2.1", f"Name: {p['name']}", f"Version: {p['version']}",
             f"Summary: {p.get('description', '')}"]
    if "requires-python" in p:
        lines.append(f"Requires-Python: {p['requires-python']}")
    lines += [f"Requires-Dist: {d}" for d in p.get("dependencies", [])]
    for extra, deps in p.get("optional-dependencies", {}).items():
        lines.append(f"Provides-Extra: {extra}")
        lines += [f'Requires-Dist: {d}; extra == "{extra}"' for d in deps]
    readme = ROOT / p.get("readme", "README.md")
    body = readme.read_text() if readme.is_file() else ""
    if body:
        lines.append("Description-Content-Type: text/markdown")
    return "\n".join(lines) + "\n\n" + body


def _record_line(name: str, data: bytes) -> str:
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return f"{name},sha256={digest},{len(data)}"


# --- PEP 517 hooks -----------------------------------------------------------------------

def get_requires_for_build_wheel(config_settings=None):
    return []


def get_requires_for_build_sdist(config_settings=None):
    return []


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    version = _project()["version"]
    dist_info = f"{_dist_name()}-{version}.dist-info"
    wheel_path = Path(wheel_directory) / f"{_dist_name()}-{version}-py3-none-any.whl"
    with tempfile.TemporaryDirectory() as tmp:
        stubs = Path(tmp) / "_stubs"
        stubs.mkdir()
        _generate_stubs(stubs)
        files: list[tuple[str, bytes]] = []
        for path in sorted((ROOT / "src" / PACKAGE).rglob("*.py")):
            files.append((f"{PACKAGE}/{path.relative_to(ROOT / 'src' / PACKAGE).as_posix()}", path.read_bytes()))
        for path in sorted(stubs.rglob("*.py")):
            files.append((f"{PACKAGE}/_stubs/{path.relative_to(stubs).as_posix()}", path.read_bytes()))
        files.append((f"{dist_info}/METADATA", _metadata().encode()))
        files.append((f"{dist_info}/WHEEL", b"Wheel-Version: 1.0\nGenerator: dtmf_build\n"
                                            b"Root-Is-Purelib: true\nTag: py3-none-any\n"))
        record = [_record_line(name, data) for name, data in files] + [f"{dist_info}/RECORD,,"]
        files.append((f"{dist_info}/RECORD", ("\n".join(record) + "\n").encode()))
        with zipfile.ZipFile(wheel_path, "w", zipfile.ZIP_DEFLATED) as wheel:
            for name, data in files:
                wheel.writestr(name, data)
    return wheel_path.name


def build_sdist(sdist_directory, config_settings=None):
    """Source, backend and a copy of proto/, so the sdist builds on its own."""
    base = f"{_dist_name()}-{_project()['version']}"
    sdist_path = Path(sdist_directory) / f"{base}.tar.gz"
    members = [(p, p.relative_to(ROOT)) for p in ROOT.rglob("*")
               if p.is_file() and "__pycache__" not in p.parts and p.suffix != ".pyc"]
    members += [(p, Path("proto") / p.relative_to(_proto_dir())) for p in _proto_dir().rglob("*.proto")]
    with tarfile.open(sdist_path, "w:gz") as sdist:
        for path, name in sorted(members, key=lambda m: str(m[1])):
            sdist.add(path, arcname=f"{base}/{name.as_posix()}")
        pkg_info = _metadata().encode()
        info = tarfile.TarInfo(f"{base}/PKG-INFO")
        info.size = len(pkg_info)
        sdist.addfile(info, io.BytesIO(pkg_info))
    return sdist_path.name
