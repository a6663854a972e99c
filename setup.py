# Builds certipose._core with this project's CMake for `pip install --no-build-isolation .`
# (pyproject.toml holds the metadata). Release at -O2, as the programs; ccache when present.
# CMAKE_BUILD_PARALLEL_LEVEL (default 2) sets the build's jobs.
import os
import pathlib
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


def generator(build):
    """The CMake generator to configure with, as arguments.

    CMake's default, Unix Makefiles, needs `make`, which a minimal Debian lacks; our install
    script installs Ninja (ninja-build). A CMAKE_GENERATOR the user set wins, and a build folder
    already configured keeps its generator (CMake refuses to switch)."""
    if os.environ.get("CMAKE_GENERATOR") or (build / "CMakeCache.txt").exists():
        return []
    if shutil.which("ninja"):
        return ["-G", "Ninja"]
    if shutil.which("make"):
        return []
    sys.exit("certipose: building the Python module needs Ninja or make: "
             "apt-get install ninja-build (or pip install ninja), or set CMAKE_GENERATOR")


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        out = pathlib.Path(self.get_ext_fullpath(ext.name)).resolve()
        build = pathlib.Path(self.build_temp).resolve() / "cmake"
        subprocess.run(["cmake", "-S", str(ROOT), "-B", str(build), *generator(build), "-DCMAKE_BUILD_TYPE=Release",
                        "-DCMAKE_CXX_FLAGS_RELEASE=-O2 -DNDEBUG", "-DCERTIPOSE_BUILD_PYTHON=ON",
                        "-DCERTIPOSE_BUILD_TESTS=OFF", "-DCERTIPOSE_BUILD_EXAMPLES=OFF",
                        f"-DPython3_EXECUTABLE={sys.executable}"], check=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", "2")
        subprocess.run(["cmake", "--build", str(build), "--target", "certipose_python", "-j", jobs], check=True)
        built = next((build / "python" / "certipose").glob("_core*.so"))
        out.parent.mkdir(parents=True, exist_ok=True)
        self.copy_file(str(built), str(out))


setup(ext_modules=[CMakeExtension("certipose._core")], cmdclass={"build_ext": CMakeBuild})
