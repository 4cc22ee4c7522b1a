"""Build geomint._core against libgeomint.

The static library comes from the project's CMake build: GEOMINT_BUILD_DIR if set, else
../build next to this folder; when neither holds libgeomint.a, the library is configured and
built here (build-lib/, Release) with CMake, so `pip install ./python` works from a fresh clone.
Linking the static archive makes the installed module independent of the build tree.
"""
import os
import shlex
import subprocess
import sys

import numpy
from setuptools import Extension, setup

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.environ.get("GEOMINT_SOURCE_DIR") or os.path.dirname(HERE)


def pkg_libs(*names):
    """Linker flags of pkg-config packages that exist (others are skipped)."""
    flags = []
    for name in names:
        try:
            out = subprocess.run(["pkg-config", "--libs", name], check=True,
                                 capture_output=True, text=True).stdout
        except (OSError, subprocess.CalledProcessError):
            continue
        flags += shlex.split(out)
    return flags


def library_dir():
    build = os.environ.get("GEOMINT_BUILD_DIR") or os.path.join(SOURCE, "build")
    if os.path.exists(os.path.join(build, "libgeomint.a")):
        return build
    build = os.path.join(HERE, "build-lib")
    print(f"geomint: no libgeomint.a found; building it in {build}", file=sys.stderr)
    subprocess.run(["cmake", "-S", SOURCE, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
                    "-DGM_BUILD_TESTS=OFF"], check=True)
    subprocess.run(["cmake", "--build", build, "--target", "geomint_static", "-j",
                    str(os.cpu_count() or 2)], check=True)
    return build


def cmake_option(build, name):
    """Value of a cache entry of the CMake build (None when absent)."""
    try:
        with open(os.path.join(build, "CMakeCache.txt")) as f:
            for line in f:
                if line.startswith(name + ":"):
                    return line.split("=", 1)[1].strip()
    except OSError:
        pass
    return None


build = library_dir()
if cmake_option(build, "GM_SANITIZE") == "ON":
    sys.exit(f"geomint: {build} is a sanitizer build (GM_SANITIZE=ON); an ASan-instrumented "
             "library cannot be loaded into python without LD_PRELOAD of libasan. Point "
             "GEOMINT_BUILD_DIR at a build without GM_SANITIZE.")

libs = pkg_libs("lapacke", "libcjson", "harminv", "fftw3", "hdf5") + \
    ["-lcholmod", "-lumfpack", "-lsuitesparseconfig", "-fopenmp", "-lm"]
# hypre (src/dec/hypre.c, reached through gm_mesh_poisson_solve) and the MPI it is built with,
# when the CMake build found them.
hypre, mpi = cmake_option(build, "HYPRE_LIB"), cmake_option(build, "MPI_mpi_LIBRARY")
if hypre and not hypre.endswith("NOTFOUND") and cmake_option(build, "GM_MPI") == "ON" and mpi:
    libs += [hypre, mpi]

core = Extension(
    "geomint._core",
    sources=["src/geomint/_core.c", "src/geomint/_fields.c"],
    depends=["src/geomint/_core.h"],
    include_dirs=[os.path.join(SOURCE, "include"), numpy.get_include()],
    extra_compile_args=["-std=c11", "-O2", "-ffp-contract=off", "-Wall", "-Wextra",
                        "-Wno-missing-field-initializers", "-Wno-cast-function-type"],
    extra_objects=[os.path.join(build, "libgeomint.a")],
    extra_link_args=libs,
)

setup(ext_modules=[core])
