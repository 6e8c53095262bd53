"""The Python module pkm for `pip install .`: the compiled part is built by the project's CMake build (target
pkm_python, python/CMakeLists.txt), the pure-Python files come from python/pkm.

PKM_CMAKE_BUILD_DIR: an already configured build folder to build in (`make python` leaves one in build/);
unset, a Release build of its own under build/pip. CMAKE_BUILD_PARALLEL_LEVEL sets the jobs as for cmake."""
import os
import pathlib
import re
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent


def project_version():
    # CMake's project(pkm VERSION …) is the one place the version is set.
    text = (ROOT / "CMakeLists.txt").read_text(encoding="utf-8")
    return re.search(r"project\(pkm VERSION ([0-9.]+)", text).group(1)


class BuildWithCMake(build_ext):
    def build_extension(self, ext):
        build_dir = pathlib.Path(os.environ.get("PKM_CMAKE_BUILD_DIR") or ROOT / "build" / "pip").resolve()
        if not (build_dir / "CMakeCache.txt").exists():
            subprocess.run(["cmake", "-S", str(ROOT), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=Release",
                            "-DBUILD_TESTING=OFF", "-DPKM_BUILD_BENCH=OFF", "-DPKM_UNITY_LIB=ON",
                            f"-DPython3_EXECUTABLE={sys.executable}"], check=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
        subprocess.run(["cmake", "--build", str(build_dir), "--target", "pkm_python", "-j", jobs], check=True)
        built = sorted((build_dir / "python" / "pkm").glob("_pkm*.so"))
        if not built:
            raise RuntimeError(f"the CMake build in {build_dir} made no python/pkm/_pkm*.so")
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[-1], target)


setup(
    version=project_version(),
    packages=["pkm"],
    package_dir={"": "python"},
    package_data={"pkm": ["py.typed", "_pkm.pyi"]},
    ext_modules=[Extension("pkm._pkm", sources=[])],
    cmdclass={"build_ext": BuildWithCMake},
    options={"build": {"build_base": "build/pip/setuptools"}, "egg_info": {"egg_base": "build/pip"}},
    zip_safe=False,
)
