"""The ctypes mirror has the layout the C compiler gives every public struct of physpix.h."""
import ctypes
import json
import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from physpix import _native

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[1]


@pytest.fixture(scope="module")
def c_layout(tmp_path_factory):
    """The layout table printed by tests/python/layout.c (built by `make test-python`, else compiled here)."""
    helper = os.environ.get("PHYSPIX_LAYOUT_HELPER")
    if not helper:
        cc = shutil.which(os.environ.get("CC", "cc"))
        if not cc:
            pytest.skip("no C compiler to build tests/python/layout.c and PHYSPIX_LAYOUT_HELPER is unset")
        helper = str(tmp_path_factory.mktemp("layout") / "pp_layout")
        subprocess.run([cc, "-std=c11", "-I", str(REPO / "include"), "-o", helper, str(HERE / "layout.c")], check=True)
    return json.loads(subprocess.run([helper], check=True, capture_output=True, text=True).stdout)


@pytest.mark.parametrize("name", sorted(_native.STRUCTS))
def test_struct_size_and_every_field_offset(c_layout, name):
    cls = _native.STRUCTS[name]
    c = c_layout[name]
    assert ctypes.sizeof(cls) == c["size"], f"sizeof({name})"
    py_fields = [(f, getattr(cls, f).offset, getattr(cls, f).size) for f, _ in cls._fields_]
    c_fields = [tuple(f) for f in c["fields"]]
    assert [f[0] for f in py_fields] == [f[0] for f in c_fields], f"{name}: field names or order differ"
    for (field, py_off, py_size), (_, c_off, c_size) in zip(py_fields, c_fields):
        assert (py_off, py_size) == (c_off, c_size), f"{name}.{field}: ctypes offset/size {py_off}/{py_size}, C {c_off}/{c_size}"


def test_every_public_struct_is_mirrored(c_layout):
    assert set(_native.STRUCTS) == {k for k, v in c_layout.items() if v["fields"]}


def test_enums_are_32_bit(c_layout):
    for name in ("pp_status", "pp_backend", "pp_normal_method", "pp_contact_mode", "pp_body_type", "pp_event_type",
                 "pp_edit_type", "pp_joint_type"):
        assert c_layout[name]["size"] == ctypes.sizeof(_native.c_enum), name


def test_struct_size_from_the_default_functions():
    assert _native.lib.pp_world_def_default().struct_size == ctypes.sizeof(_native.pp_world_def)
    assert _native.lib.pp_body_def_default().struct_size == ctypes.sizeof(_native.pp_body_def)
    assert _native.lib.pp_joint_def_default(1).struct_size == ctypes.sizeof(_native.pp_joint_def)


def test_every_function_of_the_header_has_a_signature():
    header = (REPO / "include" / "physpix.h").read_text()
    declared = set(re.findall(r"^PP_API[^;(]*?\b(pp_\w+)\s*\(", header, re.M))
    assert declared, "no PP_API declarations found in physpix.h"
    bound = set(_native.SIGNATURES)
    assert declared == bound, (f"declared in physpix.h but not bound in physpix/_native.py: {sorted(declared - bound)}; "
                               f"bound but not declared: {sorted(bound - declared)}")
