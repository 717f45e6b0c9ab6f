"""Builds the Python package with CMake (pyproject.toml names setuptools as the backend).

CMake builds the extension mechgraph._core, libmechgraph and the built-in plugins in build-pip/
beside this file; they are then laid into the package as

    mechgraph/_core.cpython-*.so                 RUNPATH $ORIGIN/_lib
    mechgraph/_lib/libmechgraph.so.X.Y           (the library's soname; RUNPATH $ORIGIN)
    mechgraph/_lib/libmechgraph_sdk.so.N         (the SDK library libmechgraph links, its soname)
    mechgraph/_lib/mechgraph/plugins/*.so        found by libmechgraph beside itself

so that an installed package (or an editable one, python/mechgraph) is whole on its own.
Environment: MECHGRAPH_CMAKE_ARGS adds CMake options; CMAKE_BUILD_PARALLEL_LEVEL the jobs.
"""
import os
import pathlib
import re
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

SOURCE = pathlib.Path(__file__).resolve().parent
PLUGINS = ["followers", "cams", "springs", "valvetrain", "fits", "joints", "backlash"]


def project_version() -> str:
    text = (SOURCE / "CMakeLists.txt").read_text(encoding="utf-8")
    found = re.search(r"project\(mechgraph VERSION ([0-9.]+)", text)
    if not found:
        raise RuntimeError("CMakeLists.txt: no 'project(mechgraph VERSION X.Y.Z'")
    return found.group(1)


class CMakeExtension(Extension):
    def __init__(self, name: str):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext: Extension) -> None:
        build = SOURCE / "build-pip"
        env = dict(os.environ)
        # Compiler cache hits across build folders at the same depth (build/, build-pip/).
        env.setdefault("CCACHE_BASEDIR", str(SOURCE))
        env.setdefault("CCACHE_NOHASHDIR", "1")
        configure = ["cmake", "-S", str(SOURCE), "-B", str(build), "-G", "Ninja", "-DCMAKE_BUILD_TYPE=RelWithDebInfo",
                     "-DMECHGRAPH_BUILD_TESTS=OFF", "-DMECHGRAPH_PYTHON=ON", f"-DPython3_EXECUTABLE={sys.executable}",
                     "-DMECHGRAPH_PYTHON_RPATH=$ORIGIN/_lib"]
        configure += os.environ.get("MECHGRAPH_CMAKE_ARGS", "").split()
        subprocess.run(configure, check=True, env=env)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        subprocess.run(["cmake", "--build", str(build), "--parallel", jobs, "--target", "mechgraph_python", *PLUGINS],
                       check=True, env=env)

        package = pathlib.Path(self.get_ext_fullpath(ext.name)).resolve().parent
        built = sorted(build.glob("lib/python3*/dist-packages/mechgraph/_core*.so"))
        if not built:
            raise RuntimeError(f"CMake built no extension under {build}")
        package.mkdir(parents=True, exist_ok=True)
        shutil.copy2(built[-1], self.get_ext_fullpath(ext.name))
        # libmechgraph under its soname (a wheel holds no symbolic links), then the plugins.
        lib = package / "_lib"
        shutil.rmtree(lib, ignore_errors=True)
        (lib / "mechgraph" / "plugins").mkdir(parents=True)
        library = next(p for p in (build / "lib").glob("libmechgraph.so.*.*.*"))
        soname = ".".join(library.name.split(".")[:4])  # libmechgraph.so.X.Y
        shutil.copy2(library, lib / soname)
        sdk_library = next(p for p in (build / "lib").glob("libmechgraph_sdk.so.*.*.*"))
        shutil.copy2(sdk_library, lib / ".".join(sdk_library.name.split(".")[:3]))  # libmechgraph_sdk.so.N
        for plugin in sorted((build / "lib" / "mechgraph" / "plugins").glob("*.so")):
            shutil.copy2(plugin, lib / "mechgraph" / "plugins" / plugin.name)
        for path in [lib, *lib.rglob("*")]:
            path.chmod(0o755 if path.is_dir() else 0o644)  # a plugin others can write is refused

    def copy_extensions_to_source(self) -> None:
        """Editable install (pip install -e): the extension goes into python/mechgraph, and its _lib with it."""
        super().copy_extensions_to_source()
        build_py = self.get_finalized_command("build_py")
        for ext in self.extensions:
            inplace_file, regular_file = self._get_inplace_equivalent(build_py, ext)
            built = pathlib.Path(regular_file).resolve().parent / "_lib"
            inplace = pathlib.Path(inplace_file).resolve().parent / "_lib"
            if built != inplace:
                shutil.rmtree(inplace, ignore_errors=True)
                shutil.copytree(built, inplace, symlinks=False)


setup(
    version=project_version(),
    packages=["mechgraph"],
    package_dir={"": "python"},
    package_data={"mechgraph": ["py.typed", "__init__.pyi"]},
    ext_modules=[CMakeExtension("mechgraph._core")],
    cmdclass={"build_ext": CMakeBuild},
    zip_safe=False,
)
