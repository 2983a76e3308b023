"""Builds the module with the project's CMake (pyproject.toml says how to run it)."""
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

HERE = Path(__file__).resolve().parent
SOURCE = HERE.parent  # the repository: the module is built from it, not copied


def project_version():
    text = (SOURCE / "CMakeLists.txt").read_text()
    match = re.search(r"project\(\s*rigflex\s+VERSION\s+([0-9.]+)", text)
    if not match:
        raise RuntimeError("no project(rigflex VERSION ...) in CMakeLists.txt")
    return match.group(1)


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = Path(self.build_temp).resolve() / "cmake"
        target = Path(self.get_ext_fullpath(ext.name)).resolve()
        configure = ["cmake", "-S", str(SOURCE), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                     "-DRIGFLEX_PYTHON=ON", "-DRIGFLEX_BUILD_TESTS=OFF", "-DRIGFLEX_BUILD_BENCH=OFF",
                     f"-DPython3_EXECUTABLE={sys.executable}"]
        if shutil.which("ninja"):
            configure += ["-G", "Ninja"]
        subprocess.run(configure, check=True)
        subprocess.run(["cmake", "--build", str(build), "--target", "_rigflex", "-j", os.environ.get("JOBS", "2")],
                       check=True)
        built = sorted((build / "python" / "rigflex").glob("_rigflex*.so"))
        if not built:
            raise RuntimeError(f"the build made no _rigflex module in {build / 'python' / 'rigflex'}")
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(built[0], target)


setup(
    version=project_version(),
    packages=["rigflex"],
    ext_modules=[CMakeExtension("rigflex._rigflex")],
    cmdclass={"build_ext": CMakeBuild},
)
