"""Builds the physpix package with libphyspix.so inside it, so it imports from any folder.

The library and the version (PHYSPIX_VERSION_* in physpix.h, the one version source) come from, in order:
PHYSPIX_LIBRARY (a built libphyspix.so to bundle; the header is still looked for as below), a PhysPix
checkout two folders up (the library is built there with make), or an installed prefix three folders up
(`make install` puts this package in PREFIX/share/physpix/python, beside PREFIX/lib and PREFIX/include).
"""
import os
import re
import shutil
import subprocess
from pathlib import Path

from setuptools import setup
from setuptools.command.build_py import build_py
from setuptools.dist import Distribution

try:
    from setuptools.command.bdist_wheel import bdist_wheel
except ImportError:  # setuptools < 70.1 keeps it in the wheel package
    from wheel.bdist_wheel import bdist_wheel

HERE = Path(__file__).resolve().parent
CHECKOUT = HERE.parents[1]   # plugin/python -> the repository
PREFIX = HERE.parents[2]     # PREFIX/share/physpix/python -> PREFIX


def _find_header():
    for header in (CHECKOUT / "include" / "physpix.h", PREFIX / "include" / "physpix.h"):
        if header.is_file():
            return header
    raise SystemExit("physpix: cannot find physpix.h; build from a PhysPix checkout (plugin/python) "
                     "or from an installed PREFIX/share/physpix/python")


def _version():
    text = _find_header().read_text(encoding="utf-8")
    parts = [re.search(rf"^#define PHYSPIX_VERSION_{k} (\d+)", text, re.M) for k in ("MAJOR", "MINOR", "PATCH")]
    if not all(parts):
        raise SystemExit("physpix: physpix.h has no PHYSPIX_VERSION_MAJOR/MINOR/PATCH")
    return ".".join(p.group(1) for p in parts)


def _library():
    """The libphyspix.so to bundle, built first when this is a checkout."""
    env = os.environ.get("PHYSPIX_LIBRARY")
    if env:
        if not Path(env).is_file():
            raise SystemExit(f"physpix: PHYSPIX_LIBRARY={env} is not a file")
        return Path(env)
    if (CHECKOUT / "Makefile").is_file() and (CHECKOUT / "lib").is_dir():
        # A clean environment for make: pip may run us from inside another make's jobserver.
        env = {k: v for k, v in os.environ.items() if k not in ("MAKEFLAGS", "MFLAGS", "MAKELEVEL")}
        subprocess.run(["make", "-C", str(CHECKOUT), "--no-print-directory", "lib"], check=True, env=env)
        return (CHECKOUT / "build" / "libphyspix.so").resolve()
    installed = PREFIX / "lib" / "libphyspix.so.0"
    if installed.exists():
        return installed.resolve()
    raise SystemExit("physpix: no libphyspix to bundle: build from a PhysPix checkout, from an installed "
                     "PREFIX/share/physpix/python, or set PHYSPIX_LIBRARY to a built libphyspix.so")


def _licence():
    for licence in (CHECKOUT / "LICENSE", HERE.parent / "LICENSE"):  # a checkout, or PREFIX/share/physpix
        if licence.is_file():
            return licence
    raise SystemExit("physpix: cannot find the LICENSE file beside the sources")


class BuildWithLibrary(build_py):
    """Copies the library and the licence into the package and records the version beside them."""

    def run(self):
        super().run()
        package = Path(self.build_lib) / "physpix"
        shutil.copyfile(_library(), package / "libphyspix.so")
        shutil.copyfile(_licence(), package / "LICENSE")
        (package / "_version.py").write_text(f'"""Written by setup.py from physpix.h."""\nversion = "{_version()}"\n')


class BinaryDistribution(Distribution):
    """The package holds a compiled library, so it is built and installed as platform-specific."""

    def has_ext_modules(self):
        return True


class PlatformWheel(bdist_wheel):
    """Tagged for this platform but any Python 3: the library is reached through ctypes, not the C-API."""

    def get_tag(self):
        return "py3", "none", super().get_tag()[2]


setup(version=_version(), distclass=BinaryDistribution,
      cmdclass={"build_py": BuildWithLibrary, "bdist_wheel": PlatformWheel})
