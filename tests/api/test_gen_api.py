"""plugin/api/gen_api.py --check catches drift: a call, a field or an enum value added to the header without being
described, an argument whose type changed, a def field with neither a kind nor a reason not to be set, a generated
file left stale, a numeric argument or def field without a range, a function that reaches no host, and a function
listed as not exposed that a host uses. Each case runs the checker on a changed copy in a temporary folder and asserts the message; the committed tree itself passes.
Standard library only (make check-api runs it)."""
import contextlib
import io
import json
import shutil
import sys
import tempfile
import unittest
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "plugin" / "api"))
import gen_api  # noqa: E402

HEADER = ROOT / "include" / "physpix.h"
DESCRIPTION = ROOT / "plugin" / "api" / "physpix_api.json"
LAST_BODY_FIELD = "    pp_vec2 one_way_direction;"


def run_check(header=HEADER, description=DESCRIPTION):
    """(exit code, stderr) of gen_api.py --check on the repository with this header and description."""
    err = io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        rc = gen_api.main(["--check", "--root", str(ROOT), "--header", str(header), "--description", str(description)])
    return rc, err.getvalue()


class Drift(unittest.TestCase):
    def setUp(self):
        self.tmp = Path(tempfile.mkdtemp(prefix="pp_api_"))
        self.addCleanup(shutil.rmtree, self.tmp)

    def header_with(self, old, new):
        text = HEADER.read_text(encoding="utf-8")
        self.assertIn(old, text)
        path = self.tmp / "physpix.h"
        path.write_text(text.replace(old, new, 1), encoding="utf-8")
        return path

    def description_with(self, change):
        desc = json.loads(DESCRIPTION.read_text(encoding="utf-8"))
        change(desc)
        path = self.tmp / "physpix_api.json"
        path.write_text(json.dumps(desc), encoding="utf-8")
        return path

    def assert_fails_saying(self, says, **kwargs):
        rc, err = run_check(**kwargs)
        self.assertEqual(rc, 1, err)
        self.assertIn(says, err)

    def test_the_committed_description_generated_files_and_hosts_agree_with_the_header(self):
        rc, err = run_check()
        self.assertEqual(rc, 0, err)

    def test_a_call_added_to_the_header_alone_is_named_with_its_signature(self):
        header = self.header_with("/// Set the world's gravity",
                                  "/// Bullet mode at run time.\nPP_API pp_status pp_body_set_bullet(pp_world w, pp_body b,\n"
                                  "                                   uint32_t bullet);\n/// Set the world's gravity")
        self.assert_fails_saying("declares pp_status pp_body_set_bullet(pp_world w, pp_body b, uint32_t bullet), which "
                                 "the description lacks", header=header)

    def test_an_argument_whose_type_changed_is_named(self):
        header = self.header_with("pp_world_step(pp_world w, float dt)", "pp_world_step(pp_world w, double dt)")
        self.assert_fails_saying("pp_world_step: the header says pp_status pp_world_step(pp_world w, double dt), the "
                                 "description pp_status pp_world_step(pp_world w, float dt)", header=header)

    def test_a_struct_field_added_to_the_header_alone_is_named(self):
        header = self.header_with("    int32_t exact_island_rows;", "    float wind;\n    int32_t exact_island_rows;")
        self.assert_fails_saying("pp_world_def.wind (float) is in", header=header)

    def test_a_field_dropped_from_the_description_is_named(self):
        description = self.description_with(lambda d: d["structs"]["pp_body_def"].pop())
        self.assert_fails_saying("pp_body_def.one_way_direction (pp_vec2) is in", description=description)

    def test_a_body_def_field_described_but_not_classified_is_named(self):
        header = self.header_with(LAST_BODY_FIELD, LAST_BODY_FIELD + "\n    uint32_t sticky;")

        def change(d):
            d["structs"]["pp_body_def"].append(["sticky", "uint32_t"])
        self.assert_fails_saying("pp_body_def.sticky (uint32_t) is not classified: give it a kind",
                                 header=header, description=self.description_with(change))

    def test_a_body_def_field_added_to_the_header_alone_is_named(self):
        header = self.header_with(LAST_BODY_FIELD, LAST_BODY_FIELD + "\n    uint32_t sticky;")
        self.assert_fails_saying("pp_body_def.sticky (uint32_t) is in", header=header)

    def test_a_def_field_not_set_without_a_reason_is_named(self):
        def change(d):
            d["def_fields"]["pp_joint_def"]["not_set"]["reserved"] = ""
        self.assert_fails_saying("pp_joint_def.reserved is in \"not_set\"", description=self.description_with(change))

    def test_an_enum_value_added_to_the_header_alone_is_named(self):
        header = self.header_with("    PP_BACKEND_GPU = 2,", "    PP_BACKEND_GPU = 2,\n    PP_BACKEND_VULKAN = 3,")
        self.assert_fails_saying("enum pp_backend:", header=header)

    def test_a_generated_file_left_stale_is_named(self):
        def change(d):
            d["plugin"]["PhysPixWorld"][0]["doc"] += " (changed)"
        self.assert_fails_saying("plugin/classes_gen.h is stale", description=self.description_with(change))

    def test_a_described_call_that_reaches_no_host_is_named_for_each_host(self):
        header = self.header_with("/// Set the world's gravity",
                                  "PP_API pp_status pp_world_wake_all(pp_world w);\n/// Set the world's gravity")

        def change(d):
            d["functions"]["pp_world_wake_all"] = ["pp_status", [["w", "pp_world"]]]
        rc, err = run_check(header=header, description=self.description_with(change))
        self.assertEqual(rc, 1, err)
        self.assertIn("pp_world_wake_all reaches no plugin method", err)
        self.assertIn("pp_world_wake_all reaches no godot method", err)
        self.assertIn("plugin/python/physpix/_api.py is stale", err)  # Python binds every call: its module changes

    def test_a_call_listed_as_not_exposed_that_a_host_uses_is_named(self):
        def change(d):
            d["not_exposed"]["godot"]["pp_world_step"] = "no reason"
        self.assert_fails_saying("pp_world_step is used by the godot host but listed",
                                 description=self.description_with(change))


    def test_a_numeric_argument_without_a_range_is_named(self):
        header = self.header_with("/// Set the world's gravity",
                                  "PP_API pp_status pp_body_set_bounce_speed(pp_world w, pp_body b, float speed);\n"
                                  "/// Set the world's gravity")

        def change(d):
            d["functions"]["pp_body_set_bounce_speed"] = ["pp_status", [["w", "pp_world"], ["b", "pp_body"],
                                                                         ["speed", "float"]]]
        self.assert_fails_saying("pp_body_set_bounce_speed.speed (float) has no range", header=header,
                                 description=self.description_with(change))

    def test_a_def_field_whose_range_was_dropped_is_named(self):
        description = self.description_with(lambda d: d["ranges"]["args"].pop("pp_body_def.density"))
        self.assert_fails_saying("pp_body_def.density (float) has no range", description=description)

    def test_a_flag_without_a_reason_is_no_range(self):
        def change(d):
            d["ranges"]["args"]["pp_body_set_awake.awake"] = {"not_a_range": " "}
        self.assert_fails_saying("pp_body_set_awake.awake: its entry in \"ranges\".\"args\" of plugin/api/"
                                 "physpix_api.json gives neither a range", description=self.description_with(change))

    def test_a_range_naming_no_argument_is_named(self):
        def change(d):
            d["ranges"]["args"]["pp_body_set_density.dens"] = {"min": 0}
        self.assert_fails_saying("has pp_body_set_density.dens, which is no numeric argument",
                                 description=self.description_with(change))

    def test_a_changed_range_leaves_the_generated_boundary_test_stale(self):
        def change(d):
            d["ranges"]["args"]["pp_body_set_gravity_scale.scale"]["max"] = 2000
        self.assert_fails_saying("tests/c/ranges_gen.h is stale", description=self.description_with(change))

if __name__ == "__main__":
    unittest.main()
