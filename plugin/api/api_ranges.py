"""The description's "ranges": every numeric argument and def field has one, and the boundary cases they give.

check_ranges() names each numeric argument of a header function, and each numeric field of a struct in
"ranges"."structs", that has no entry (or an entry with neither a range nor a reason it has none).
ranges_test_header() writes tests/c/ranges_gen.h: for each argument the tests feed, its boundary values (0, the
limits and the floats just either side, ±FLT_MAX, NaN, ±inf, the smallest subnormal, the integer type's extremes)
with the status each must get, and a function that makes the call on a fixture of tests/c/test_ranges.c.
"""
import math
import struct

INTS = {"int32_t": (-2**31, 2**31 - 1), "int64_t": (-2**63, 2**63 - 1), "uint32_t": (0, 2**32 - 1),
        "uint8_t": (0, 255), "uint64_t": (0, 2**64 - 1)}
FLOATS = {"float", "double", "pp_vec2"}
NUMERIC = FLOATS | set(INTS)
RANGE_KEYS = {"min", "max", "values", "finite", "length_max", "nonzero"}
FLT_MAX = struct.unpack("<f", struct.pack("<I", 0x7F7FFFFF))[0]
FLT_TRUE_MIN = struct.unpack("<f", struct.pack("<I", 1))[0]


def numbers(hdr, desc):
    """{"function.argument" or "struct.field": C type} of every number that needs a range, in header order."""
    out = {}
    for fn, (_, args) in hdr["functions"].items():
        out.update({f"{fn}.{n}": t for n, t in args if t in NUMERIC})
    for s in desc["ranges"]["structs"]:
        out.update({f"{s}.{n}": t for n, t in hdr["structs"].get(s, []) if t in NUMERIC})
    return out


def check_ranges(desc, hdr):
    """Messages for numbers without a range, entries naming nothing, and fixtures or untested names naming nothing."""
    if "ranges" not in desc:
        return ["the description has no \"ranges\": give every numeric argument and def field a range"]
    spec, where = desc["ranges"], "\"ranges\".\"args\" of plugin/api/physpix_api.json"
    nums, args = numbers(hdr, desc), spec["args"]
    errors = [f"{s} in \"ranges\".\"structs\" is no struct of the header" for s in spec["structs"]
              if s not in hdr["structs"]]
    for key, ctype in nums.items():
        entry = args.get(key)
        if entry is None:
            errors.append(f"{key} ({ctype}) has no range: add \"{key}\" to {where} (\"min\", \"max\", \"finite\", ... "
                          "as the library checks it), or \"not_a_range\" with the reason (a flag, a bit mask)")
        elif not RANGE_KEYS & set(entry) and not str(entry.get("not_a_range", "")).strip():
            errors.append(f"{key}: its entry in {where} gives neither a range nor a \"not_a_range\" reason")
    errors += [f"{where} has {k}, which is no numeric argument or field of the header" for k in args if k not in nums]
    known = set(hdr["functions"]) | set(spec["structs"])
    errors += [f"\"ranges\".\"fixtures\" names {n}, which is no function or ranged struct" for n in spec["fixtures"]
               if n not in known]
    errors += [f"\"ranges\".\"untested\" names {n}, which is no function, ranged struct or entry" for n in spec["untested"]
               if n not in known and n not in args]
    return errors


def _f32(x):
    """x rounded to the nearest float."""
    if math.isnan(x) or math.isinf(x) or abs(x) > FLT_MAX * (1 + 2**-25):
        return x if (math.isnan(x) or math.isinf(x)) else math.copysign(math.inf, x)
    return struct.unpack("<f", struct.pack("<f", x))[0]


def _next32(x, toward):
    """The float after float x toward +inf (toward > 0) or -inf."""
    if x == 0:
        return math.copysign(FLT_TRUE_MIN, toward)
    bits = struct.unpack("<i", struct.pack("<f", x))[0]
    bits += 1 if (x > 0) == (toward > 0) else -1
    return struct.unpack("<f", struct.pack("<i", bits))[0]


def _around32(limit):
    """The floats just below, at (if one is) and just above a real limit."""
    f = _f32(limit)
    below = f if f < limit else _next32(f, -1)
    above = f if f > limit else _next32(f, 1)
    return {below, above, f} if abs(f) <= FLT_MAX else {below, above}


def _float_values(rng, ctype):
    vals = {0.0, 1.0, -1.0, FLT_MAX, -FLT_MAX, math.inf, -math.inf, math.nan, FLT_TRUE_MIN, -FLT_TRUE_MIN}
    if ctype == "double":
        vals |= {1.7976931348623157e308, -1.7976931348623157e308}
    for k in ("min", "max", "length_max"):
        if k in rng:
            vals |= _around32(rng[k]) | (_around32(-rng[k]) if k == "length_max" else set())
    return vals


def _accepts(rng, v, other=0.0):
    """Whether the library takes v (the other component of a pp_vec2 being `other`)."""
    if math.isnan(v):
        return False
    if rng.get("finite") and math.isinf(v):
        return False
    if "values" in rng and v not in rng["values"]:
        return False
    if "min" in rng and not (v > rng["min"] if rng.get("min_exclusive") else v >= rng["min"]):
        return False
    if "max" in rng and not (v < rng["max"] if rng.get("max_exclusive") else v <= rng["max"]):
        return False
    length = math.hypot(v, other)
    if "length_max" in rng and not length <= rng["length_max"]:
        return False
    return not (rng.get("nonzero") and not length > 0)


def _want(rng, v, other=0.0):
    if _accepts(rng, v, other):
        return "PP_OK"
    if "max" in rng and "past_max" in rng and v > rng["max"]:
        return rng["past_max"]
    return "PP_ERR_INVALID_ARGUMENT"


def _c_number(v):
    if math.isnan(v):
        return "NAN"
    if math.isinf(v):
        return "INFINITY" if v > 0 else "-INFINITY"
    if v == int(v) and abs(v) < 2**53:
        return f"{int(v)}.0"
    return v.hex()


def cases(key, ctype, rng):
    """[(component, value, C literal, status)] of an argument's boundary cases; component is "", "x" or "y"."""
    if ctype in INTS:
        lo, hi = INTS[ctype]
        vals = {0, 1, -1, lo, hi} | {v + d for k in ("min", "max") if k in rng for v in [rng[k]] for d in (-1, 0, 1)}
        vals |= {v + d for v in rng.get("values", []) for d in (-1, 0, 1)}
        vals = sorted(v for v in vals if lo <= v <= hi and abs(v) <= 2**53)  # a double carries them exactly
        return [("", float(v), f"{v}.0", _want(rng, v)) for v in vals]
    vals = sorted(_float_values(rng, ctype), key=lambda v: (math.isnan(v), v))
    if ctype != "pp_vec2":
        return [("", v, _c_number(v), _want(rng, v)) for v in vals]
    ok = rng.get("ok", [0, 0])
    return [(c, v, _c_number(v), _want(rng, _f32(v), other)) for c, other in (("x", ok[1]), ("y", ok[0])) for v in vals]


def _call(desc, fn, key, ctype, comp):
    """The C statement that calls fn with argument key's value v and every other argument valid."""
    spec, args = desc["ranges"]["args"], desc["functions"][fn][1]
    pre, call, bodies = [], [], iter(["f->b", "f->other"])
    for name, t in args:
        entry = spec.get(f"{fn}.{name}", {})
        if f"{fn}.{name}" == key:
            if t == "pp_vec2":
                ok = entry.get("ok", [0, 0])
                call.append(f"(pp_vec2){{(float)v, {float(ok[1])}f}}" if comp == "x" else
                            f"(pp_vec2){{{float(ok[0])}f, (float)v}}")
            else:
                call.append(f"({t})v")
        elif t == "pp_world":
            call.append("f->w")
        elif t == "pp_body":
            call.append(next(bodies))
        elif t == "pp_joint":
            call.append("f->j")
        elif t == "pp_vec2":
            ok = entry.get("ok", [0, 0])
            call.append(f"(pp_vec2){{{float(ok[0])}f, {float(ok[1])}f}}")
        elif t in NUMERIC:
            call.append(f"({t}){entry.get('ok', 1 if name == 'capacity' else 0)}")
        elif t == "const char *" and name == "path":
            call.append("f->path")
        elif t == "const uint8_t *":
            call.append("range_plane")
        elif t.endswith(" *") and not t.startswith("const "):
            items = spec.get(f"{fn}.capacity", {}).get("buffer", 4)
            pre.append(f"{t[:-2]} {name}[{items}]; memset({name}, 0, sizeof {name});")
            call.append(name)
        else:
            raise ValueError(f"{fn}: the generated range test cannot pass its argument {name} ({t}); list it in "
                             "\"ranges\".\"untested\" with a reason")
    return " ".join(pre + [f"return {fn}({', '.join(call)});"])


def _set_field(desc, struct_name, key, ctype, comp, fixture):
    spec = desc["ranges"]["args"][key]
    field = key.split(".", 1)[1]
    lines = [f"{struct_name} d = range_{fixture}(f);"]
    lines += [f"d.{k} = {v};" for k, v in spec.get("test_with", {}).items()]
    if ctype == "pp_vec2":
        ok = spec.get("ok", [0, 0])
        other = "y" if comp == "x" else "x"
        lines.append(f"d.{field}.{comp} = (float)v; d.{field}.{other} = {float(ok[1] if comp == 'x' else ok[0])}f;")
    else:
        lines.append(f"d.{field} = ({ctype})v;")
    return " ".join(lines + [f"return range_try_{fixture}(f, &d);"])


def ranges_test_header(desc):
    """tests/c/ranges_gen.h: the boundary cases and the calls that feed them."""
    from api_targets import BANNER  # noqa: E402  (beside this file; imported late: api_targets imports this module)
    spec = desc["ranges"]
    fixtures = spec["fixtures"]
    variants = [(key, dict(rng, **also)) for key, rng in spec["args"].items()
                for also in [rng.get("tested_as", {})] + rng.get("also", [])]
    kinds = sorted(set(fixtures.values()) | {r["test_fixture"] for _, r in variants if "test_fixture" in r})
    rows, calls = [], []
    types = {f"{fn}.{n}": t for fn, (_, args) in desc["functions"].items() for n, t in args}
    types.update({f"{s}.{n}": t for s in spec["structs"] for n, t in desc["structs"][s]})
    for key, rng in variants:  # each entry (or its "tested_as" range), then each "also" range under another fixture
        owner = key.split(".", 1)[0]
        ctype = types.get(key)  # an entry naming nothing is check_ranges' to report
        if (ctype is None or "not_a_range" in rng or owner not in fixtures or owner in spec["untested"]
                or key in spec["untested"]):
            continue
        fixture = rng.get("test_fixture", fixtures[owner])
        for comp in (["x", "y"] if ctype == "pp_vec2" else [""]):
            target = len(calls)
            body = (_set_field(desc, owner, key, ctype, comp, fixture) if owner in spec["structs"] else
                    _call(desc, owner, key, ctype, comp))
            calls.append(f"    case {target}: {{ {body} }}")
            name = key + (f".{comp}" if comp else "")
            rows += [f"    {{\"{name}\", RANGE_{fixture.upper()}, {target}, {lit}, {want}}},"
                     for c, _, lit, want in cases(key, ctype, rng) if c == comp]
    enum = ", ".join(f"RANGE_{k.upper()}" for k in kinds)
    return "\n".join([
        f"/* The boundary cases of every numeric argument the range test feeds. {BANNER}",
        " * Included by tests/c/test_ranges.c, which defines range_fixture, range_<fixture>() for the struct fixtures",
        " * and range_try_<fixture>(). Each case: the argument (\".x\"/\".y\": a pp_vec2's component), the fixture it",
        " * needs, the call that feeds it, the value, and the status the description's range gives it. */",
        "#ifndef PP_RANGES_GEN_H", "#define PP_RANGES_GEN_H", "",
        f"enum range_fixture_kind {{ {enum} }};", "",
        "typedef struct range_case {", "    const char *arg;", "    int fixture;", "    int target;",
        "    double value;", "    pp_status want;", "} range_case;", "",
        "static const range_case range_cases[] = {", *rows, "};", "",
        "static pp_status range_feed(range_fixture *f, int target, double v)", "{", "    switch (target) {",
        *calls, "    default: return PP_ERR_UNSUPPORTED;", "    }", "}", "", "#endif", ""])
