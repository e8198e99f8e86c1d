"""`pip install .`: the package softtrace, its native module built by CMake (python/CMakeLists.txt)
for the interpreter pip runs, with the same compiler flags as the CMake build. The Python files,
stubs and py.typed come from python/softtrace/."""
import os
import re
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))


def version():
    """The project's version, from CMakeLists.txt's project()."""
    text = open(os.path.join(ROOT, "CMakeLists.txt")).read()
    return re.search(r"project\(softtrace VERSION ([0-9.]+)", text).group(1)


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        # SOFTTRACE_CMAKE_BUILD names a CMake build folder already configured for this
        # interpreter (the test python.pip_install uses the test build's): pip then only brings
        # its module up to date instead of building the project again.
        build_dir = os.environ.get("SOFTTRACE_CMAKE_BUILD")
        if not build_dir:
            build_dir = os.path.abspath(os.path.join(self.build_temp, "cmake"))
            configure = ["cmake", "-S", ROOT, "-B", build_dir, "-DCMAKE_BUILD_TYPE=Release",
                         "-DBUILD_TESTING=OFF", "-DPython3_EXECUTABLE=" + sys.executable]
            if shutil.which("ninja"):
                configure += ["-G", "Ninja"]
            subprocess.run(configure, check=True)
        subprocess.run(["cmake", "--build", build_dir, "--target", "softtrace_python", "-j",
                        os.environ.get("SOFTTRACE_JOBS", str(os.cpu_count() or 1))], check=True)
        built = os.path.join(build_dir, "python", "softtrace",
                             os.path.basename(self.get_ext_filename(ext.name)))
        if not os.path.exists(built):
            sys.exit("CMake built no %s: is pybind11 (Debian's pybind11-dev) installed?" % built)
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(built, target)


setup(
    version=version(),
    packages=["softtrace"],
    package_dir={"softtrace": "python/softtrace"},
    package_data={"softtrace": ["py.typed", "*.pyi"]},
    ext_modules=[Extension("softtrace._native", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    # Beside, not inside, the CMake build folder `build/`.
    options={"build": {"build_base": "build-pip"}},
)
