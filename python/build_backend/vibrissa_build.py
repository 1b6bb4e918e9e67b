"""PEP 517 build backend of the `vibrissa` Python package: it drives the project's CMake.

Why in-tree and standard-library only: pip builds a package in an isolated environment and would download
its build requirements (setuptools, scikit-build, ...) from an index; vibrissa must install offline
(`pip install .` on a machine that reaches only Debian's archive), so the backend needs nothing but Python
and the Debian packages that scripts/setup-debian.sh installs (CMake, a compiler, pybind11, HDF5, matio).

build_wheel configures the project with the interpreter that runs the build, builds the extension module and
the command line, and packs the importable package that CMake assembles in <build>/python/vibrissa (pure-Python
layer, type stubs, figure scripts, the compiled `_vibrissa`) with the CLI's two executables
(vibrissa/bin/vibrissa and vibrissa/libexec/vibrissa/vibrissa-full, the build tree's layout) into a wheel whose
console script `vibrissa` runs them (vibrissa._cli), as does `python -m vibrissa`. It builds with every CPU
(ninja; ccache when installed) and prints each step; pip shows the steps with `pip install -v`. Environment:
VIBRISSA_BUILD_DIR (reuse a build directory; default: a fresh temporary one), VIBRISSA_BUILD_JOBS (default:
the number of CPUs), VIBRISSA_CMAKE_ARGS (extra configure arguments, split on spaces).
"""

from __future__ import annotations

import base64
import hashlib
import io
import os
import pathlib
import re
import shutil
import subprocess
import sys
import sysconfig
import tarfile
import tempfile
import zipfile

ROOT = pathlib.Path(__file__).resolve().parents[2]
NAME = "vibrissa"
SUMMARY = "Quasi-static 3D mechanics of rodent whiskers (vibrissae) touching objects"
SDIST_EXCLUDE = re.compile(r"^(build[^/]*|\.git|dist|.*\.egg-info)(/|$)|(^|/)__pycache__(/|$)")


def _version() -> str:
    text = (ROOT / "CMakeLists.txt").read_text()
    found = re.search(r"project\(vibrissa VERSION ([0-9.]+)", text)
    if not found:
        raise RuntimeError("vibrissa build backend: no 'project(vibrissa VERSION x.y.z' in CMakeLists.txt")
    return found.group(1)


def _tag() -> str:
    python = f"cp{sys.version_info.major}{sys.version_info.minor}"
    platform = sysconfig.get_platform().replace("-", "_").replace(".", "_")
    return f"{python}-{python}-{platform}"


def _metadata() -> str:
    return "\n".join([
        "Metadata-Version: 2.1",
        f"Name: {NAME}",
        f"Version: {_version()}",
        f"Summary: {SUMMARY}",
        "Requires-Python: >=3.9",
        "Requires-Dist: numpy",
        "Provides-Extra: plots",
        "Requires-Dist: matplotlib; extra == 'plots'",
        "Requires-Dist: h5py; extra == 'plots'",
        "Provides-Extra: sweeps",
        "Requires-Dist: distributed; extra == 'sweeps'",
        "Requires-Dist: xarray; extra == 'sweeps'",
        "Requires-Dist: h5netcdf; extra == 'sweeps'",
        "",
        "The C++ engine of vibrissa with NumPy in and out, and its `vibrissa` command; see docs/python.md.",
        "",
    ])


# The console script: the same command line as the CMake build's (vibrissa._cli).
ENTRY_POINTS = "[console_scripts]\nvibrissa = vibrissa._cli:main\n"
# The CLI's executables, from the build tree into the package, keeping their relative layout (bin/vibrissa
# hands the file commands to ../libexec/vibrissa/vibrissa-full).
EXECUTABLES = ("bin/vibrissa", "libexec/vibrissa/vibrissa-full")


def _say(message: str) -> None:
    print(f"vibrissa build backend: {message}", flush=True)


def _run(command: list[str]) -> None:
    _say(" ".join(command))
    subprocess.run(command, check=True, cwd=ROOT)


def _build_package() -> pathlib.Path:
    """Configures and builds the extension and the CLI; returns the build directory."""
    build = pathlib.Path(os.environ.get("VIBRISSA_BUILD_DIR") or tempfile.mkdtemp(prefix="vibrissa-wheel-"))
    configure = ["cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                 "-DVIBRISSA_BUILD_TESTS=OFF", "-DVIBRISSA_BUILD_BENCHMARKS=OFF", "-DVIBRISSA_BUILD_PYTHON=ON",
                 f"-DPython3_EXECUTABLE={sys.executable}"]
    fresh = not (build / "CMakeCache.txt").exists()
    if shutil.which("ninja") and fresh:
        configure += ["-G", "Ninja"]
    if shutil.which("ccache") and fresh:
        configure += ["-DCMAKE_CXX_COMPILER_LAUNCHER=ccache", "-DCMAKE_C_COMPILER_LAUNCHER=ccache"]
    configure += os.environ.get("VIBRISSA_CMAKE_ARGS", "").split()
    _say(f"configuring the C++ project in {build}")
    _run(configure)
    jobs = os.environ.get("VIBRISSA_BUILD_JOBS") or str(os.cpu_count() or 1)
    _say(f"building the library, the Python extension and the command line with {jobs} parallel jobs "
         "(a fresh build takes minutes)")
    _run(["cmake", "--build", str(build), "--parallel", jobs,
          "--target", "_vibrissa", "vibrissa_python_files", "vibrissa_cli", "vibrissa_cli_full"])
    package = build / "python" / NAME
    if not any(package.glob("_vibrissa*.so")):
        raise RuntimeError(f"vibrissa build backend: no extension module in {package}")
    for executable in EXECUTABLES:
        if not (build / executable).is_file():
            raise RuntimeError(f"vibrissa build backend: no {build / executable}")
    return build


def _record_line(arcname: str, data: bytes) -> str:
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return f"{arcname},sha256={digest},{len(data)}"


def _dist_info(directory: pathlib.Path) -> str:
    info = directory / f"{NAME}-{_version()}.dist-info"
    info.mkdir(parents=True, exist_ok=True)
    (info / "METADATA").write_text(_metadata())
    (info / "entry_points.txt").write_text(ENTRY_POINTS)
    (info / "WHEEL").write_text(f"Wheel-Version: 1.0\nGenerator: vibrissa_build\nRoot-Is-Purelib: false\n"
                                f"Tag: {_tag()}\n")
    return info.name


# --- PEP 517 hooks ---

def get_requires_for_build_wheel(config_settings=None):
    return []


def get_requires_for_build_sdist(config_settings=None):
    return []


def prepare_metadata_for_build_wheel(metadata_directory, config_settings=None):
    return _dist_info(pathlib.Path(metadata_directory))


def _add(wheel: zipfile.ZipFile, records: list, arcname: str, file: pathlib.Path) -> None:
    """Adds `file` as `arcname`, keeping its permission bits (pip installs executables as executables)."""
    info = zipfile.ZipInfo(arcname, date_time=(1980, 1, 1, 0, 0, 0))
    info.compress_type = zipfile.ZIP_DEFLATED
    info.external_attr = (file.stat().st_mode & 0o777 | 0o100000) << 16
    data = file.read_bytes()
    wheel.writestr(info, data)
    records.append(_record_line(arcname, data))


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    build = _build_package()
    package = build / "python" / NAME
    name = f"{NAME}-{_version()}-{_tag()}.whl"
    path = pathlib.Path(wheel_directory) / name
    _say(f"packing {name}")
    records = []
    with zipfile.ZipFile(path, "w", compression=zipfile.ZIP_DEFLATED) as wheel:
        for file in sorted(p for p in package.rglob("*") if p.is_file() and "__pycache__" not in p.parts):
            _add(wheel, records, f"{NAME}/{file.relative_to(package).as_posix()}", file)
        for executable in EXECUTABLES:
            _add(wheel, records, f"{NAME}/{executable}", build / executable)
        with tempfile.TemporaryDirectory() as scratch:
            info = _dist_info(pathlib.Path(scratch))
            for file in sorted((pathlib.Path(scratch) / info).iterdir()):
                data = file.read_bytes()
                wheel.writestr(f"{info}/{file.name}", data)
                records.append(_record_line(f"{info}/{file.name}", data))
        records.append(f"{info}/RECORD,,")
        wheel.writestr(f"{info}/RECORD", "\n".join(records) + "\n")
    return name


def build_sdist(sdist_directory, config_settings=None):
    base = f"{NAME}-{_version()}"
    name = f"{base}.tar.gz"
    with tarfile.open(pathlib.Path(sdist_directory) / name, "w:gz") as sdist:
        for file in sorted(ROOT.rglob("*")):
            relative = file.relative_to(ROOT).as_posix()
            if file.is_file() and not SDIST_EXCLUDE.search(relative):
                sdist.add(file, arcname=f"{base}/{relative}")
        info = tarfile.TarInfo(f"{base}/PKG-INFO")
        data = _metadata().encode()
        info.size = len(data)
        sdist.addfile(info, io.BytesIO(data))
    return name
