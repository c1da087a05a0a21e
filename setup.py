"""Builds the extension mechflow._mechflow with CMake (pyproject.toml has
the rest). The libraries are compiled in a CMake build tree of their own
(build-python/, some minutes on two cores), or in the tree named by the
environment variable MECHFLOW_BUILD_DIR: one already configured with
-DMECHFLOW_PYTHON=ON for this interpreter, where only what changed is
rebuilt."""

import glob
import os
import shutil
import subprocess
import sys
import sysconfig

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

SOURCE = os.path.dirname(os.path.abspath(__file__))


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = os.environ.get("MECHFLOW_BUILD_DIR")
        if build:
            build = os.path.abspath(build)
            if not os.path.exists(os.path.join(build, "CMakeCache.txt")):
                sys.exit(f"MECHFLOW_BUILD_DIR={build} is not a configured CMake build tree "
                         "(configure it with -DMECHFLOW_PYTHON=ON, or leave the variable unset)")
        else:
            build = os.path.join(SOURCE, "build-python")
            subprocess.check_call(["cmake", "-S", SOURCE, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
                                   "-DMECHFLOW_PYTHON=ON", "-DMECHFLOW_BUILD_TESTS=OFF",
                                   "-DMECHFLOW_BUILD_BENCH=OFF", f"-DPython_EXECUTABLE={sys.executable}"])
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
        subprocess.check_call(["cmake", "--build", build, "--target", "mechflow_python", "-j", jobs])
        # the module for this interpreter (a tree configured for another Python builds another suffix)
        suffix = sysconfig.get_config_var("EXT_SUFFIX")
        built = os.path.join(build, "python", "mechflow", "_mechflow" + suffix)
        if not os.path.exists(built):
            found = glob.glob(os.path.join(build, "python", "mechflow", "_mechflow*"))
            sys.exit(f"{build} built {', '.join(found) or 'no module'}, not _mechflow{suffix} for "
                     f"{sys.executable}: configure it with -DPython_EXECUTABLE={sys.executable}")
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(built, target)


setup(ext_modules=[Extension("mechflow._mechflow", sources=[])], cmdclass={"build_ext": CMakeBuild},
      options={"build": {"build_base": "build-python/setuptools"}, "egg_info": {"egg_base": "build-python"}})
