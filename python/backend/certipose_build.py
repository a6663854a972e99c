"""The build backend of the Python module (PEP 517; pyproject.toml names it).

`pip install .` and `pip wheel .` call build_wheel here. It runs this project's CMake
(CERTIPOSE_BUILD_PYTHON) for the interpreter running pip and zips python/certipose/ and the
compiled certipose._core into a wheel, with the standard library alone: no setuptools, no
`wheel` package, nothing to download. That is why it is ours and not setuptools': a venv of a
pyenv or conda Python sees neither Debian's setuptools nor its `wheel`, and pip's isolated
build cannot download them on a machine without PyPI.

What the build needs from the machine (a C++20 compiler, CMake, Ninja or make, and the
libraries of README's install script) is checked by CMake; when something is missing, the
build ends with one line naming it and the Debian package that provides it. Environment:
CMAKE_BUILD_PARALLEL_LEVEL (default 2) sets the build's jobs; CERTIPOSE_BUILD_DIR the folder
CMake builds in (default build/python-<interpreter>-<hash of its installation> in the checkout,
so a rebuild is quick).
Node.js and npm make the web viewer part of the module (Plan.export("html")): web/'s locked
packages are installed with `npm ci` if they are not there yet.
"""

import base64
import hashlib
import os
import pathlib
import re
import shutil
import subprocess
import sys
import sysconfig
import zipfile

ROOT = pathlib.Path(__file__).resolve().parents[2]
NAME = "certipose"

#: What CMake reports missing -> (what it is, the Debian 12 package that provides it).
PACKAGES = {
    "Eigen3": ("Eigen 3.4", "libeigen3-dev"),
    "Boost": ("Boost", "libboost-dev"),
    "TBB": ("oneTBB", "libtbb-dev"),
    "CGAL": ("CGAL 5.5", "libcgal-dev"),
    "GMP": ("GMP", "libgmp-dev"),
    "MPFR": ("MPFR", "libmpfr-dev"),
    "nlohmann_json": ("nlohmann-json", "nlohmann-json3-dev"),
    "CLI11": ("CLI11", "libcli11-dev"),
    "yaml-cpp": ("yaml-cpp", "libyaml-cpp-dev"),
    "TinyGLTF": ("TinyGLTF", "libtinygltf-dev"),
    "pybind11": ("pybind11", "pybind11-dev"),
    "GLPK": ("GLPK", "libglpk-dev"),
    "Python3": ("this Python's C headers (Python.h)", "python3-dev for Debian's Python; pyenv and conda Pythons carry them"),
}


def _say(line):
    """A line of progress (pip shows it with -v, or when the build fails)."""
    print(f"certipose: {line}", file=sys.stderr, flush=True)


class BuildError(SystemExit):
    """The build cannot go on: one line saying why (pip prints it last)."""


def missing_dependency(log):
    """The line telling what a failed CMake configure lacks, from its output; None if unknown."""
    if re.search(r"No CMAKE_CXX_COMPILER could be found|CMAKE_CXX_COMPILER not set", log):
        return "the build needs a C++20 compiler: apt-get install g++"
    if "does not support C++20" in log or "CXX_STANDARD is set to invalid value '20'" in log:
        return "the build needs a C++20 compiler (GCC 12 or Clang 14 and later): apt-get install g++"
    m = re.search(r"certipose: (CERTIPOSE_BUILD_PYTHON needs [^\n]*)", log)
    if m:
        return "the build " + m.group(1).split(" ", 1)[1]
    for pattern in (r"Could NOT find (\w[\w-]*)", r'provided by\s+"(\w[\w-]*)"', r"Could not find a package configuration file provided by\s+\"(\w[\w-]*)\""):
        m = re.search(pattern, log)
        if m:
            what, package = PACKAGES.get(m.group(1), (m.group(1), None))
            return f"the build needs {what}: " + (f"apt-get install {package}" if package else "install it, or see README's install")
    return None


def _run(command, log, **kwargs):
    """Runs `command`, echoing its output (pip -v shows it) and appending it to `log`; returns
    (exit code, output)."""
    with subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, errors="replace",
                          **kwargs) as p:
        out = []
        for line in p.stdout:
            sys.stderr.write(line)
            out.append(line)
    text = "".join(out)
    with open(log, "a", encoding="utf-8") as f:
        f.write(text)
    return p.returncode, text


def _version():
    m = re.search(r"project\(certipose VERSION ([0-9.]+)", (ROOT / "CMakeLists.txt").read_text(encoding="utf-8"))
    return m.group(1)


def _tag():
    """The wheel's tag for the interpreter running pip: cp311-cp311-linux_x86_64."""
    impl = "cp" if sys.implementation.name == "cpython" else sys.implementation.name[:2]
    py = f"{impl}{sys.version_info.major}{sys.version_info.minor}"
    abi = py + getattr(sys, "abiflags", "")
    platform = sysconfig.get_platform().replace("-", "_").replace(".", "_")
    return f"{py}-{abi}-{platform}"


def _generator(build):
    """CMake's generator: a minimal Debian has Ninja (the install script's) and no make; a
    CMAKE_GENERATOR the user set wins, and a folder already configured keeps its own."""
    if os.environ.get("CMAKE_GENERATOR") or (build / "CMakeCache.txt").exists():
        return []
    if shutil.which("ninja"):
        return ["-G", "Ninja"]
    if shutil.which("make"):
        return []
    raise BuildError("certipose: the build needs Ninja or make: apt-get install ninja-build (or set CMAKE_GENERATOR)")


def _viewer():
    """Makes web/node_modules ready for the web viewer when Node.js is there; says what happens."""
    web = ROOT / "web"
    if not shutil.which("node"):
        _say("no Node.js: the module is built without the web viewer (Plan.export(\"html\"); "
             "certipose.available_formats() lists what it has)")
        return
    if (web / "node_modules" / "three").exists() and (web / "node_modules" / "esbuild").exists():
        return
    npm = shutil.which("npm")
    if npm is None:
        _say("Node.js but no npm: the module is built without the web viewer (apt-get install npm)")
        return
    _say("installing the web viewer's locked packages (npm ci in web/)")
    if subprocess.run([npm, "ci", "--no-audit", "--no-fund"], cwd=web, stdout=sys.stderr).returncode != 0:
        _say("npm ci failed: the module is built without the web viewer")


def _build_core():
    """Configures and builds certipose._core with CMake; returns the built shared object."""
    if shutil.which("cmake") is None:
        raise BuildError("certipose: the build needs CMake 3.22 or later: apt-get install cmake")
    # One folder per Python installation (venvs of one share it): CMake caches what it found of
    # the interpreter, so Debian's 3.11 and pyenv's 3.11 must not share a folder.
    where = hashlib.sha256(os.path.realpath(sys.base_prefix).encode()).hexdigest()[:8]
    default = ROOT / "build" / f"python-{sys.implementation.cache_tag}-{where}"
    build = pathlib.Path(os.environ.get("CERTIPOSE_BUILD_DIR") or default).resolve()
    build.mkdir(parents=True, exist_ok=True)
    log = build / "certipose-build.log"
    log.write_text("", encoding="utf-8")
    _viewer()
    _say(f"configuring with CMake in {build} (log: {log})")
    code, out = _run(["cmake", "-S", str(ROOT), "-B", str(build), *_generator(build), "-DCMAKE_BUILD_TYPE=Release",
                      "-DCMAKE_CXX_FLAGS_RELEASE=-O2 -DNDEBUG", "-DCERTIPOSE_BUILD_PYTHON=ON",
                      "-DCERTIPOSE_BUILD_TESTS=OFF", "-DCERTIPOSE_BUILD_EXAMPLES=OFF",
                      f"-DPython3_EXECUTABLE={sys.executable}"], log)
    if code != 0:
        why = missing_dependency(out)
        raise BuildError(f"certipose: {why} (CMake's log: {log})" if why else
                         f"certipose: CMake could not configure the build; its log: {log}")
    jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", "2")
    _say(f"compiling the module on {jobs} jobs (several minutes the first time; seconds with ccache after)")
    code, out = _run(["cmake", "--build", str(build), "--target", "certipose_python", "-j", jobs], log)
    if code != 0:
        raise BuildError(f"certipose: the module did not compile; the compiler's messages are above and in {log}")
    return next((build / "python" / "certipose").glob("_core*.so"))


def _metadata():
    return "\n".join([
        "Metadata-Version: 2.1", f"Name: {NAME}", f"Version: {_version()}",
        "Summary: Certified camera pose boxes for inspecting the facets of a triangle mesh",
        "License: MPL-2.0 (the module links CGAL's GPL-3.0-or-later parts and GLPK, GPL-3.0-or-later; see docs/python.md)",
        "Requires-Python: >=3.9", "Requires-Dist: numpy", "Description-Content-Type: text/markdown", "",
        (ROOT / "docs" / "python.md").read_text(encoding="utf-8")])


def _record_line(name, data):
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return f"{name},sha256={digest},{len(data)}"


# ---- PEP 517 hooks ----------------------------------------------------------------------------

def get_requires_for_build_wheel(config_settings=None):
    return []


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    core = _build_core()
    package = ROOT / "python" / NAME
    files = [(f"{NAME}/{f}", (package / f).read_bytes()) for f in ("__init__.py", "__init__.pyi", "_errors.py", "py.typed")]
    files.append((f"{NAME}/{core.name}", core.read_bytes()))
    info = f"{NAME}-{_version()}.dist-info"
    tag = _tag()
    files += [(f"{info}/METADATA", _metadata().encode()),
              (f"{info}/WHEEL", f"Wheel-Version: 1.0\nGenerator: certipose_build\nRoot-Is-Purelib: false\nTag: {tag}\n".encode()),
              (f"{info}/top_level.txt", f"{NAME}\n".encode())]
    record = "\n".join([_record_line(n, d) for n, d in files] + [f"{info}/RECORD,,", ""])
    name = f"{NAME}-{_version()}-{tag}.whl"
    out = pathlib.Path(wheel_directory) / name
    partial = out.with_suffix(".whl.partial")
    with zipfile.ZipFile(partial, "w", zipfile.ZIP_DEFLATED) as z:
        for n, d in files + [(f"{info}/RECORD", record.encode())]:
            entry = zipfile.ZipInfo(n, date_time=(2020, 1, 1, 0, 0, 0))
            entry.external_attr = 0o644 << 16
            z.writestr(entry, d, zipfile.ZIP_DEFLATED)
    os.replace(partial, out)
    _say(f"built {out}")
    return name
