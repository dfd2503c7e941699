"""World def fields at creation, as the API description lists them (issue 24): every pp_world_def field of
plugin/api/physpix_api.json is a World keyword and a key of World.settings, the settings go back through World(),
and misuse gets the exact exception naming the field."""
import json
import math
from pathlib import Path

import pytest

import physpix
from physpix import _native
from pphelpers import rect

DESCRIPTION = Path(__file__).resolve().parents[2] / "plugin" / "api" / "physpix_api.json"


def described_world_fields():
    fields = json.loads(DESCRIPTION.read_text(encoding="utf-8"))["structs"]["pp_world_def"]
    return [name for name, _ in fields if name != "struct_size"]


def test_the_ctypes_mirror_is_the_description():
    described = json.loads(DESCRIPTION.read_text(encoding="utf-8"))
    assert set(_native.SIGNATURES) == set(described["functions"])
    for name, fields in described["structs"].items():
        assert [f for f, _ in getattr(_native, name)._fields_] == [f for f, _ in fields], name


def test_every_described_world_field_is_a_keyword_and_goes_back_through_world():
    with physpix.World(backend="cpu", substeps=3, allow_sleep=False) as w:
        settings = w.settings
    assert list(settings) == described_world_fields()
    with physpix.World(**settings) as again:
        assert again.settings == settings


def test_a_world_made_without_gravity_keeps_a_body_at_rest_and_its_substeps():
    with physpix.World(gravity=(0, 0), substeps=2, allow_sleep=False, backend="cpu") as w:
        box = rect(w, 16, 16, position=(40, 40))
        for _ in range(60):
            w.step(1 / 60)
        assert box.position == (40.0, 40.0) and box.velocity == (0.0, 0.0) and box.awake
        assert w.settings["substeps"] == 2 and w.settings["gravity"] == (0.0, 0.0)


def test_misuse_of_world_fields_gets_the_exact_exception():
    # Unknown keywords and enum names: test_errors.py.
    with pytest.raises(TypeError, match="substeps: expected an integer, got float 2.5"):
        physpix.World(substeps=2.5)
    with pytest.raises(physpix.InvalidArgumentError, match="gravity must be finite"):
        physpix.World(gravity=(math.nan, 0))
    with pytest.raises(physpix.InvalidArgumentError, match="substeps must be 1..64, got 99"):
        physpix.World(substeps=99)
