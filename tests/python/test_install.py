"""The Python module as a user installs it (docs/python.md): `pip wheel .` in a bare venv that
has neither setuptools' `wheel` nor numpy nor an index to download from (the position of a
pyenv or conda Python), the wheel installed into a fresh venv, and the installed module (not the
build tree's) imported and run; and a missing build dependency told in one line."""
import base64
import hashlib
import os
import pathlib
import subprocess
import sys
import zipfile

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
PYTHON = os.environ.get("CERTIPOSE_INSTALL_PYTHON", sys.executable)
BACKEND = ROOT / "python" / "backend"
sys.path.insert(0, str(BACKEND))
import certipose_build  # noqa: E402

CHECK = r"""
import pathlib, sys
import certipose
source = pathlib.Path(sys.argv[1])
where = pathlib.Path(certipose.__file__).resolve()
assert where.is_relative_to(pathlib.Path(sys.prefix).resolve()) and "site-packages" in where.parts, where
mesh = certipose.Mesh.read(source / "examples" / "data" / "fixture_plate.off")
r = certipose.solve_facet(mesh, str(source / "examples" / "data" / "camera.json"), 6)
assert len(r) > 0 and r.bounds.shape == (len(r), 6, 2), r
part = certipose.sample_part()
first = certipose.solve_facet(part, certipose.example_camera(), 900, position_eps=0.1, orientation_eps=0.38)
assert part.num_faces == 2300 and first.valid.sum() > 0 and certipose.__version__, (part, first)
assert (where.parent / "__init__.pyi").stat().st_size > 0 and (where.parent / "py.typed").exists()
print(" ".join(certipose.available_formats()))
"""


def venv(path, *flags):
    subprocess.run([PYTHON, "-m", "venv", *flags, str(path)], check=True)
    return path / "bin" / "python"


def clean_env(**extra):
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}
    env.update(extra)
    return env


@pytest.fixture(scope="module")
def wheel(tmp_path_factory):
    work = tmp_path_factory.mktemp("wheel")
    bare = venv(work / "bare")  # its own pip; no system packages: no `wheel`, no numpy
    missing = subprocess.run([bare, "-c", "import wheel"], capture_output=True, cwd=work)
    assert missing.returncode != 0, "the bare venv must not see a `wheel` package"
    out = subprocess.run([bare, "-m", "pip", "wheel", "--no-index", "--no-deps", "-v", "-w", str(work / "dist"),
                          str(ROOT)], capture_output=True, text=True, cwd=work, env=clean_env())
    assert out.returncode == 0, out.stdout[-4000:] + out.stderr[-4000:]
    wheels = list((work / "dist").glob("certipose-*.whl"))
    assert len(wheels) == 1, wheels
    return wheels[0], out.stdout + out.stderr


def test_the_wheel_builds_offline_and_says_what_it_does(wheel):
    path, log = wheel
    tag = subprocess.run([PYTHON, "-c", "import sys; print(f'cp{sys.version_info[0]}{sys.version_info[1]}')"],
                         capture_output=True, text=True, check=True).stdout.strip()
    assert path.name.startswith(f"certipose-0.1.0-{tag}-{tag}-linux_"), path.name
    # progress, as pip -v shows it
    assert "certipose: configuring with CMake" in log and "certipose: compiling the module" in log, log[-2000:]


def test_the_wheel_is_well_formed(wheel):
    path, _ = wheel
    with zipfile.ZipFile(path) as z:
        names = set(z.namelist())
        info = "certipose-0.1.0.dist-info"
        assert {f"certipose/{f}" for f in ("__init__.py", "__init__.pyi", "_errors.py", "py.typed")} <= names
        assert any(n.startswith("certipose/_core.") and n.endswith(".so") for n in names), names
        meta = z.read(f"{info}/METADATA").decode()
        assert "Name: certipose" in meta and "Requires-Dist: numpy" in meta and "Requires-Python: >=3.9" in meta
        record = z.read(f"{info}/RECORD").decode().splitlines()
        listed = {line.split(",")[0] for line in record}
        assert listed == names, listed ^ names
        for line in record:
            name, digest, size = line.split(",")
            if name.endswith("RECORD"):
                continue
            data = z.read(name)
            want = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
            assert digest == f"sha256={want}" and int(size) == len(data), name


def test_the_wheel_installs_into_a_fresh_venv_and_runs(wheel, tmp_path):
    path, _ = wheel
    fresh = venv(tmp_path / "fresh", "--system-site-packages")  # numpy from the machine
    subprocess.run([fresh, "-m", "pip", "install", "--no-index", "-q", str(path)], check=True, cwd=tmp_path,
                   env=clean_env())
    out = subprocess.run([fresh, "-c", CHECK, str(ROOT)], capture_output=True, text=True, cwd=tmp_path, env=clean_env())
    assert out.returncode == 0, out.stdout + out.stderr
    formats = out.stdout.split()
    assert {"csv", "urdf", "glb", "sheet"} <= set(formats)
    # Node.js and web/node_modules are here (README's install), so the pip build has the viewer
    assert "html" in formats, formats


def test_no_cmake_is_one_line(tmp_path):
    out = subprocess.run([PYTHON, "-c", "import sys, certipose_build; certipose_build.build_wheel(sys.argv[1])",
                          str(tmp_path)], capture_output=True, text=True, cwd=tmp_path,
                         env=clean_env(PATH=str(tmp_path / "nothing"), PYTHONPATH=str(BACKEND),
                                       CERTIPOSE_BUILD_DIR=str(tmp_path / "build")))
    assert out.returncode != 0
    assert out.stderr.strip().splitlines()[-1] == "certipose: the build needs CMake 3.22 or later: apt-get install cmake"
    assert not list(tmp_path.glob("*.whl*"))  # no wheel, not even half of one


@pytest.mark.parametrize("log, line", [
    ("CMake Error at CMakeLists.txt:60 (find_package):\n  Could NOT find GMP (missing: GMP_LIBRARIES GMP_INCLUDE_DIR)",
     "the build needs GMP: apt-get install libgmp-dev"),
    ('CMake Error at python/CMakeLists.txt:16 (find_package):\n  Could not find a package configuration file provided by\n'
     '  "pybind11" (requested version 2.10) with any of the following names:',
     "the build needs pybind11: apt-get install pybind11-dev"),
    ("CMake Error at python/CMakeLists.txt:9 (message):\n  certipose: CERTIPOSE_BUILD_PYTHON needs GLPK (Debian libglpk-dev) for plan()",
     "the build needs GLPK (Debian libglpk-dev) for plan()"),
    ("CMake Error at /usr/share/cmake-3.25/Modules/FindPackageHandleStandardArgs.cmake:230 (message):\n"
     "  Could NOT find Python3 (missing: Python3_INCLUDE_DIRS Development.Module)",
     "the build needs this Python's C headers (Python.h): apt-get install python3-dev for Debian's Python; "
     "pyenv and conda Pythons carry them"),
    ("CMake Error at CMakeLists.txt:14 (project):\n  No CMAKE_CXX_COMPILER could be found.",
     "the build needs a C++20 compiler: apt-get install g++"),
    ("CMake Error: something else entirely", None),
])
def test_a_missing_dependency_is_named(log, line):
    assert certipose_build.missing_dependency(log) == line
