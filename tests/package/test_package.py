"""What a user meets outside the build tree (make test-package): a fresh clone that builds, the installed
prefix, the Python package from a checkout and from the prefix, the exported symbols, one version, the
licence and the README.

Run from the repository root after `make all`; BUILD names the build folder and PYTHON the interpreter
fresh virtual environments are made from (the Makefile passes both). The fresh-clone test clones the
committed HEAD, so it checks what a push would publish, not uncommitted edits.
"""
import json
import os
import re
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
BUILD = ROOT / os.environ.get("BUILD", "build")
BASE_PYTHON = os.environ.get("PYTHON", getattr(sys, "_base_executable", sys.executable))
WHEELHOUSE = BUILD / "wheelhouse"


def run(cmd, cwd=ROOT, env=None, check=True, timeout=300):
    """Runs cmd; on failure the assertion shows its output."""
    proc = subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True, timeout=timeout)
    if check:
        assert proc.returncode == 0, f"{cmd} exited {proc.returncode}:\n{proc.stdout}\n{proc.stderr}"
    return proc


def clean_env(**extra):
    """The environment with nothing that points Python or the loader at the checkout, and no make state."""
    drop = ("PHYSPIX_LIBRARY", "PYTHONPATH", "LD_LIBRARY_PATH", "MAKEFLAGS", "MFLAGS", "MAKELEVEL", "VIRTUAL_ENV")
    env = {k: v for k, v in os.environ.items() if k not in drop}
    env.update(extra)
    return env


def header_version():
    text = (ROOT / "include" / "physpix.h").read_text()
    return ".".join(re.search(rf"^#define PHYSPIX_VERSION_{k} (\d+)$", text, re.M).group(1)
                    for k in ("MAJOR", "MINOR", "PATCH"))


def defined_globals(nm_args, path):
    out = run(["nm", *nm_args, "--defined-only", str(path)]).stdout
    return sorted({line.split()[-1] for line in out.splitlines() if len(line.split()) == 3})


def fresh_venv(where):
    """A new virtual environment from the base interpreter, seeing the system's packages as build/venv does."""
    run([BASE_PYTHON, "-m", "venv", "--system-site-packages", str(where)], env=clean_env())
    return where / "bin" / "python"


def pip_install(python, *args):
    """pip install offline: dependencies come from the wheels `make deps` kept, or the system's packages."""
    offline = [str(python), "-m", "pip", "install", "--quiet", "--no-index", "--find-links", str(WHEELHOUSE)]
    run(offline + ["setuptools>=61", "wheel"], env=clean_env())   # the build backend, for --no-build-isolation
    return run(offline + ["--no-build-isolation", *args], env=clean_env())


PROBE = """
import importlib.metadata, json, physpix
w = physpix.World(backend="cpu")
b = w.create_body(mask=__import__("numpy").ones((8, 8)), position=(0, 0))
w.step(1 / 60)
print(json.dumps({"path": physpix.library_path, "version": physpix.__version__, "library": physpix.library_version,
                  "dist": importlib.metadata.version("physpix"), "file": physpix.__file__, "y": b.position[1]}))
w.close()
"""


def probe(python, cwd, **env):
    """Imports physpix in python from cwd, makes a world with a falling body, and reports where it came from."""
    return json.loads(run([str(python), "-c", PROBE], cwd=cwd, env=clean_env(**env)).stdout)


# --- one version, one licence -------------------------------------------------------------------------


def test_every_version_is_the_headers():
    version = header_version()
    assert run(["make", "-s", "--no-print-directory", "print-version"], env=clean_env()).stdout.strip() == version
    assert (BUILD / f"libphyspix.so.{version}").is_file()
    pc = (BUILD / "physpix.pc").read_text()
    assert re.search(rf"^Version: {re.escape(version)}$", pc, re.M), pc
    pyproject = (ROOT / "plugin" / "python" / "pyproject.toml").read_text()
    for cfg in (ROOT / "plugin/godot/addons/physpix/plugin.cfg", BUILD / "addons/physpix/plugin.cfg"):
        assert re.search(rf'^version="{re.escape(version)}"$', cfg.read_text(), re.M), f"the Godot addon's {cfg}"
    assert 'dynamic = ["version"]' in pyproject and not re.search(r"^version\s*=", pyproject, re.M)
    init = (ROOT / "plugin" / "python" / "physpix" / "__init__.py").read_text()
    assert not re.search(r"__version__\s*=\s*['\"]\d", init), "a version literal in __init__.py"


def test_mit_licence_is_named_everywhere():
    assert (ROOT / "LICENSE").read_text().startswith("MIT License\n")
    assert "LICENSE" in (ROOT / "README.md").read_text() and "MIT" in (ROOT / "README.md").read_text()
    assert 'license = {text = "MIT"}' in (ROOT / "plugin" / "python" / "pyproject.toml").read_text()
    assert re.search(r"^License: MIT$", (BUILD / "physpix.pc").read_text(), re.M)


# --- symbols --------------------------------------------------------------------------------------------


def test_shared_and_static_libraries_export_only_pp_symbols():
    shared = defined_globals(["-D"], BUILD / "libphyspix.so")
    static = defined_globals(["-g"], BUILD / "libphyspix.a")
    assert shared and all(s.startswith("pp_") for s in shared), [s for s in shared if not s.startswith("pp_")]
    assert [s for s in static if not s.startswith("pp_")] == []
    assert static == shared


def test_plugin_and_godot_adapter_export_only_their_entry_points():
    assert defined_globals(["-D"], BUILD / "libphyspix_plugin.so") == ["pp_plugin_entry"]
    assert defined_globals(["-D"], BUILD / "libphyspix_godot.so") == [
        "godot_gdnative_init", "godot_gdnative_terminate", "godot_nativescript_init"]


# --- the installed prefix -------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def prefix(tmp_path_factory):
    prefix = tmp_path_factory.mktemp("prefix") / "opt" / "physpix"
    run(["make", "--no-print-directory", "install", f"PREFIX={prefix}"], env=clean_env())
    return prefix


# The Godot addon as plugin/godot/README.md lists it, libraries beside its .gdnlib.
GODOT_ADDON = ["plugin.cfg", "plugin.gd", "physpix.gdnlib", "physpix_world.gdns", "physpix_world_2d.gd",
               "physpix_body_2d.gd", "physpix_joint_2d.gd", "physpix_character_2d.gd", "libphyspix_godot.so",
               "libphyspix.so.0"]


def test_install_puts_every_piece_under_the_prefix(prefix):
    version = header_version()
    expected = [f"lib/libphyspix.so.{version}", "lib/libphyspix.so.0", "lib/libphyspix.so", "lib/libphyspix.a",
                "lib/pkgconfig/physpix.pc", "include/physpix.h", "include/physpix_plugin.h",
                "lib/libphyspix_plugin.so", "lib/physpix.plugin",
                *(f"share/physpix/godot/addons/physpix/{f}" for f in GODOT_ADDON),
                "share/physpix/python/pyproject.toml", "share/physpix/python/setup.py",
                "share/physpix/python/physpix/__init__.py", "share/physpix/python/physpix/py.typed",
                "share/physpix/LICENSE"]
    assert [p for p in expected if not (prefix / p).exists()] == []
    assert (prefix / "lib/pkgconfig/physpix.pc").read_text().startswith(f"prefix={prefix}\n")
    # The addon is self-contained: the adapter finds the library beside it.
    addon = prefix / "share/physpix/godot/addons/physpix"
    ldd = run(["ldd", str(addon / "libphyspix_godot.so")]).stdout
    assert f"libphyspix.so.0 => {addon}/libphyspix.so.0" in ldd, ldd


def pkg_config(prefix, *args):
    env = clean_env(PKG_CONFIG_PATH=str(prefix / "lib" / "pkgconfig"))
    return run(["pkg-config", *args, "physpix"], env=env).stdout.split()


def test_a_program_built_against_the_prefix_runs_with_rpath_or_library_path(prefix, tmp_path):
    assert pkg_config(prefix, "--modversion") == [header_version()]
    flags = pkg_config(prefix, "--cflags", "--libs")
    app = tmp_path / "app"
    run(["cc", "-std=c11", "-Wall", "-Werror", str(ROOT / "tests/package/app.c"), "-o", str(app), *flags])
    # Without being told where the prefix's lib/ is, the loader does not find it: the README says why.
    bare = run([str(app)], env=clean_env(), check=False)
    assert bare.returncode != 0 and "libphyspix.so.0: cannot open shared object file" in bare.stderr
    via_path = run([str(app)], env=clean_env(LD_LIBRARY_PATH=str(prefix / "lib")))
    assert via_path.stdout.startswith(f"physpix {header_version()} crate y ")
    rpath_app = tmp_path / "app_rpath"
    run(["cc", "-std=c11", str(ROOT / "tests/package/app.c"), "-o", str(rpath_app), *flags,
         f"-Wl,-rpath,{prefix / 'lib'}"])
    assert run([str(rpath_app)], env=clean_env()).stdout == via_path.stdout


def test_static_linking_leaves_the_programs_own_names_alone(prefix, tmp_path):
    flags = pkg_config(prefix, "--static", "--cflags", "--libs")
    # -l:libphyspix.a picks the archive though the prefix also holds the .so.
    flags = ["-l:libphyspix.a" if f == "-lphyspix" else f for f in flags]
    app = tmp_path / "clash"
    run(["cc", "-std=c11", "-Wall", "-Werror", str(ROOT / "tests/package/clash.c"), "-o", str(app), *flags])
    assert "libphyspix" not in run(["ldd", str(app)]).stdout
    assert run([str(app)], env=clean_env()).stdout == "210 PP_ERR_IO\n"


def test_the_installed_plugin_manifest_loads_in_the_reference_host(prefix):
    host = BUILD / "demo" / "host"
    out = run([str(host), str(prefix / "lib" / "physpix.plugin")], env=clean_env()).stdout
    assert "host scene: PASS" in out, out


# --- Python ---------------------------------------------------------------------------------------------


def test_pip_install_from_a_checkout_imports_anywhere(tmp_path):
    python = fresh_venv(tmp_path / "venv")
    pip_install(python, str(ROOT / "plugin" / "python"))
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    got = probe(python, elsewhere)
    site = Path(got["file"]).parent
    assert Path(got["path"]) == site / "libphyspix.so" and str(tmp_path / "venv") in got["path"]
    assert got["version"] == got["dist"] == header_version() == ".".join(map(str, got["library"]))
    assert got["y"] > 0, "the body did not fall"
    assert (site / "py.typed").is_file() and (site / "LICENSE").read_text().startswith("MIT License")
    meta = run([str(python), "-m", "pip", "show", "physpix"], env=clean_env()).stdout
    assert "License: MIT" in meta, meta
    # PHYSPIX_LIBRARY still overrides the bundled copy.
    own = str((BUILD / "libphyspix.so").resolve())
    assert probe(python, elsewhere, PHYSPIX_LIBRARY=own)["path"] == own


@pytest.fixture(scope="module")
def wheel():
    """The one wheel `make wheel` writes."""
    run(["make", "--no-print-directory", "wheel"], env=clean_env())
    wheels = list((BUILD / "wheel").glob("*.whl"))
    assert len(wheels) == 1, list((BUILD / "wheel").iterdir())
    return wheels[0]


def test_make_wheel_is_manylinux_and_carries_its_libraries(wheel):
    assert wheel.name == f"physpix-{header_version()}-py3-none-manylinux_2_35_x86_64.whl"
    names = zipfile.ZipFile(wheel).namelist()
    for member in ("physpix/libphyspix.so", "physpix/py.typed", "physpix/_version.py", "physpix/LICENSE"):
        assert member in names, names
    # auditwheel renames what it grafts (libode-<hash>.so.8...), so no system library can stand in for it.
    bundled = sorted(re.sub(r"-[0-9a-f]{8}\.so[.0-9]*$", "", Path(n).name) for n in names
                     if n.startswith("physpix.libs/") and not n.endswith("/"))
    assert bundled == ["libccd", "libcjson", "libode", "libpng16"], names


# Reads which libode files the process maps once a world has stepped.
MAPS_PROBE = PROBE.replace("w.close()", "") + """
maps = [line.split()[-1] for line in open("/proc/self/maps") if "libode" in line]
print(json.dumps(sorted(set(maps))))
"""


def test_the_wheel_in_a_fresh_venv_maps_its_own_libode(wheel, tmp_path):
    python = fresh_venv(tmp_path / "venv")
    pip_install(python, str(wheel))
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    out = run([str(python), "-c", MAPS_PROBE], cwd=elsewhere, env=clean_env()).stdout.splitlines()
    got, maps = json.loads(out[0]), json.loads(out[1])
    site = Path(got["file"]).parent.parent
    assert Path(got["path"]) == site / "physpix" / "libphyspix.so" and got["y"] > 0, got
    assert maps and all(Path(m).parent == site / "physpix.libs" for m in maps), maps
    # The system has its own libode (libode8, which the build links against); the process never maps it.
    assert not any(m.startswith("/usr/") for m in maps), maps


def test_pip_install_from_the_installed_prefix_bundles_its_library(prefix, tmp_path):
    python = fresh_venv(tmp_path / "venv")
    # pip builds in the source folder; build a copy so the prefix stays as make install left it.
    source = tmp_path / "share" / "physpix" / "python"
    shutil.copytree(prefix / "share" / "physpix", source.parent)
    for d in ("lib", "include"):
        shutil.copytree(prefix / d, tmp_path / d, symlinks=True)
    pip_install(python, str(source))
    got = probe(python, tmp_path)
    bundled = Path(got["path"]).read_bytes()
    assert bundled == (prefix / "lib" / "libphyspix.so.0").read_bytes()
    assert got["version"] == got["dist"] == header_version()


# --- a fresh clone --------------------------------------------------------------------------------------


def test_a_fresh_clone_builds_with_nothing_beside_it(tmp_path):
    if run(["git", "-C", str(ROOT), "rev-parse", "--is-inside-work-tree"], check=False).returncode != 0:
        pytest.skip(f"{ROOT} is not a git checkout, so there is nothing to clone")
    clone = tmp_path / "empty" / "physpix"
    clone.parent.mkdir()
    run(["git", "clone", "--quiet", "--no-local", str(ROOT), str(clone)])
    run(["make", "--no-print-directory", "-j2", "all"], cwd=clone, env=clean_env(), timeout=900)
    built = ["libphyspix.so.0", "libphyspix.a", "physpix.pc", "libphyspix_plugin.so", "libphyspix_godot.so"]
    assert [b for b in built if not (clone / "build" / b).exists()] == []
    assert sorted(p.name for p in clone.parent.iterdir()) == ["physpix"], "the build wrote beside the clone"
    # The README's first command leaves the clone as it was (-o deps: the packages and venv are this checkout's
    # business, checked by make deps itself).
    run(["make", "--no-print-directory", "-o", "deps", "demo"], cwd=clone, env=clean_env(), timeout=600)
    assert run(["git", "status", "--porcelain", "--ignored=no"], cwd=clone).stdout == "", "make demo changed the clone"
    assert sorted(p.name for p in clone.parent.iterdir()) == ["physpix"], "the demo wrote beside the clone"


# --- the README -----------------------------------------------------------------------------------------


def readme():
    return (ROOT / "README.md").read_text()


def test_readme_is_short_and_links_the_figures():
    assert len(readme().encode()) <= 16 * 1024, f"README.md is {len(readme().encode())} bytes"
    assert "tests/bench/README.md" in readme() and (ROOT / "tests/bench/README.md").is_file()


def test_readme_names_only_files_in_the_repository():
    tops = ("lib/", "include/", "glsl/", "plugin/", "demo/", "tests/", ".ci/")
    missing = []
    for token in re.findall(r"`([^`\s]+)`", readme()) + re.findall(r"\]\(([^)\s]+)\)", readme()):
        path = token.rstrip(".,:;")
        if path.startswith(tops) or path in ("Makefile", "LICENSE", "README.md"):
            if "<" not in path and not list(ROOT.glob(path)):
                missing.append(path)
    assert missing == []


def test_readme_first_program_compiles_as_printed_and_runs(tmp_path):
    section = readme().split("\n## A first program", 1)
    assert len(section) == 2, "README.md has no '## A first program' section"
    code = re.search(r"```c\n(.*?)```", section[1], re.S)
    assert code, "no ```c block in the first-program section"
    source = tmp_path / "first.c"
    source.write_text(code.group(1))
    exe = tmp_path / "first"
    run(["cc", "-std=c11", "-Wall", "-Wextra", "-Werror", f"-I{ROOT / 'include'}", str(source), "-o", str(exe),
         f"-L{BUILD}", "-lphyspix", f"-Wl,-rpath,{BUILD}", "-lm"])
    run([str(exe)], cwd=tmp_path, env=clean_env())
