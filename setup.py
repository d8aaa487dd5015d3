"""pip install --no-build-isolation .  builds the voronoimesh Python module with CMake
(the library and python/) and installs the package; offline, with Debian's setuptools.
VM_CMAKE_ARGS adds CMake arguments (e.g. "-DCMAKE_BUILD_TYPE=Debug")."""
import os
import shlex
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        # The package goes where setuptools collects extensions: the folder above the module's.
        package_root = os.path.abspath(os.path.dirname(os.path.dirname(self.get_ext_fullpath(ext.name))))
        build = os.path.abspath(os.path.join(self.build_temp, "cmake"))
        configure = ["cmake", "-S", os.path.dirname(os.path.abspath(__file__)), "-B", build,
                     "-DCMAKE_BUILD_TYPE=Release", f"-DPython3_EXECUTABLE={sys.executable}",
                     f"-DVM_PYTHON_INSTALL_DIR={package_root}", "-DVORONOIMESH_BUILD_TESTS=OFF",
                     "-DVORONOIMESH_BUILD_BENCH=OFF"] + shlex.split(os.environ.get("VM_CMAKE_ARGS", ""))
        subprocess.run(configure, check=True)
        subprocess.run(["cmake", "--build", build, "--target", "_voronoimesh", "-j", str(os.cpu_count() or 2)],
                       check=True)
        subprocess.run(["cmake", "--install", build, "--component", "python"], check=True)


setup(
    name="voronoimesh",
    version="0.1.0",
    description="Meshes of interconnected surfaces (Saye's Voronoi implicit interface method)",
    packages=["voronoimesh"],
    package_dir={"": "python"},
    package_data={"voronoimesh": ["__init__.pyi", "py.typed"]},
    ext_modules=[Extension("voronoimesh._voronoimesh", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    python_requires=">=3.9",
    install_requires=["numpy"],
    zip_safe=False,
)
