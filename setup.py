"""Builds the `tandem` Python package with CMake, for pip (no network needed):

    /usr/bin/python3 -m pip install --no-build-isolation .

build_ext configures this project with the running interpreter as Python3_EXECUTABLE, builds
only the extension (the library linked in statically, no tests, benchmarks or renderer) and puts
it into the package. Extra CMake arguments come from the CMAKE_ARGS environment variable
(e.g. CMAKE_ARGS="-DCMAKE_CXX_COMPILER_LAUNCHER=ccache"); setuptools' own files go under
build/pip (or TANDEM_PIP_BUILD_DIR).
"""

import os
import pathlib
import re
import shlex
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

SOURCE_DIR = pathlib.Path(__file__).resolve().parent
BUILD_BASE = os.environ.get("TANDEM_PIP_BUILD_DIR", str(SOURCE_DIR / "build" / "pip"))


def project_version():
    text = (SOURCE_DIR / "CMakeLists.txt").read_text()
    match = re.search(r"project\(\s*tandem\s+VERSION\s+([0-9.]+)", text)
    if not match:
        sys.exit("setup.py: no `project(tandem VERSION x.y.z)` in CMakeLists.txt")
    return match.group(1)


class CMakeBuild(build_ext):
    """Builds the extension with the project's CMake instead of setuptools' compiler calls."""

    def build_extension(self, ext):
        if shutil.which("cmake") is None:
            raise RuntimeError("tandem: building the Python module needs cmake (Debian: apt-get install cmake)")
        build_dir = pathlib.Path(self.build_temp).resolve() / "cmake"
        package_dir = build_dir / "python" / "tandem"
        configure = [
            "cmake", "-S", str(SOURCE_DIR), "-B", str(build_dir),
            "-DCMAKE_BUILD_TYPE=Release",
            f"-DPython3_EXECUTABLE={sys.executable}",
            f"-DTANDEM_PYTHON_PACKAGE_DIR={package_dir}",
            "-DBUILD_SHARED_LIBS=OFF",
            "-DTANDEM_BUILD_PYTHON=ON",
            "-DTANDEM_BUILD_TESTS=OFF",
            "-DTANDEM_BUILD_BENCHMARKS=OFF",
            "-DTANDEM_BUILD_RENDER=OFF",
        ]
        if shutil.which("ninja"):
            configure += ["-G", "Ninja"]
        configure += shlex.split(os.environ.get("CMAKE_ARGS", ""))
        parallel = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        subprocess.run(configure, check=True)
        subprocess.run(["cmake", "--build", str(build_dir), "--target", "tandem_python", "--parallel", parallel],
                       check=True)
        built = list(package_dir.glob("_tandem*.so"))
        if len(built) != 1:
            raise RuntimeError(f"tandem: expected one _tandem*.so in {package_dir}, found {built}")
        destination = pathlib.Path(self.get_ext_fullpath(ext.name))
        destination.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[0], destination)


setup(
    name="tandem",
    version=project_version(),
    description="Rigid (Bullet) and deformable bodies simulated together with two-way coupling",
    long_description=(SOURCE_DIR / "docs" / "python.md").read_text(),
    long_description_content_type="text/markdown",
    license="MIT",
    python_requires=">=3.9",
    install_requires=["numpy"],
    packages=["tandem"],
    package_dir={"tandem": "python/tandem"},
    ext_modules=[Extension("tandem._tandem", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": BUILD_BASE}, "egg_info": {"egg_base": BUILD_BASE}},
    zip_safe=False,
)
