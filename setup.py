"""Builds the compiled half of the Python package `tumble` with CMake, for the interpreter running
pip, and installs it with the pure-Python half (python/tumble/*.py), its type stubs and py.typed.

    python3 -m venv --system-site-packages .venv && . .venv/bin/activate
    pip install --no-build-isolation .

The library's own build directory is reused when it exists (build/release, made by
scripts/build.sh), so that pip only links the module; otherwise CMake configures build/pip. Set
TUMBLE_CMAKE_BUILD_DIR to choose another.
"""
import os
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

HERE = os.path.dirname(os.path.abspath(__file__))


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = os.environ.get("TUMBLE_CMAKE_BUILD_DIR")
        if not build:
            release = os.path.join(HERE, "build", "release")
            build = release if os.path.exists(os.path.join(release, "CMakeCache.txt")) else os.path.join(HERE, "build", "pip")
        if not os.path.exists(os.path.join(build, "CMakeCache.txt")):
            subprocess.run(["cmake", "-S", HERE, "-B", build, "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
                            "-DTUMBLE_BUILD_TESTS=OFF", "-DTUMBLE_BUILD_APPS=OFF",
                            f"-DPython3_EXECUTABLE={sys.executable}"], check=True)
        subprocess.run(["cmake", "--build", build, "--target", "tumble_python", "-j", str(os.cpu_count() or 1)],
                       check=True)
        package = os.path.join(build, "python", "tumble")
        built = [f for f in os.listdir(package) if f.startswith("_tumble") and f.endswith(".so")]
        if len(built) != 1:
            sys.exit(f"setup.py: expected one _tumble*.so in {package}, found {built}")
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(os.path.join(package, built[0]), target)


setup(
    packages=["tumble"],
    package_dir={"tumble": "python/tumble"},
    package_data={"tumble": ["*.pyi", "py.typed"]},
    ext_modules=[Extension("tumble._tumble", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
)
