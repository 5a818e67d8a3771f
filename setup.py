"""Builds the extension module trionet._trionet with CMake (python/CMakeLists.txt), for
`pip install --no-build-isolation .`; the package's metadata is in pyproject.toml.

Needs cmake, a C++17 compiler and pybind11 (Debian: apt-get install cmake g++ python3-dev python3-pybind11).
TRIONET_CMAKE_ARGS adds CMake options; TRIONET_BUILD_JOBS sets the parallel jobs (default 2).
"""

import os
import shlex
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


class CMakeExtension(Extension):
    def __init__(self, name: str) -> None:
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext: Extension) -> None:
        target = Path(self.get_ext_fullpath(ext.name)).resolve()
        build = Path(self.build_temp).resolve() / "cmake"
        build.mkdir(parents=True, exist_ok=True)
        configure = [
            "cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
            "-DTRIONET_PYTHON=ON", "-DTRIONET_BUILD_TOOLS=OFF", "-DTRIONET_BUILD_TESTS=OFF",
            "-DTRIONET_BUILD_EXAMPLES=OFF", f"-DPython3_EXECUTABLE={sys.executable}",
            f"-DTRIONET_PYTHON_PACKAGE_DIR={target.parent}",
        ]
        try:
            import pybind11  # the Debian package's, found through --system-site-packages

            configure.append(f"-Dpybind11_DIR={pybind11.get_cmake_dir()}")
        except ImportError:
            pass  # CMake looks for pybind11Config.cmake itself
        configure += shlex.split(os.environ.get("TRIONET_CMAKE_ARGS", ""))
        subprocess.run(configure, check=True)
        jobs = os.environ.get("TRIONET_BUILD_JOBS", "2")
        subprocess.run(["cmake", "--build", str(build), "--target", "trionet_python", "-j", jobs], check=True)
        built = list(target.parent.glob("_trionet*" + Path(target.name).suffix))
        if not built:
            raise RuntimeError(f"CMake built no _trionet module in {target.parent}")


setup(ext_modules=[CMakeExtension("trionet._trionet")], cmdclass={"build_ext": CMakeBuild})
