#!/usr/bin/env python3
"""PhysPix's API described once (plugin/api/physpix_api.json), written out for every host, checked against the header.

usage: gen_api.py [--check] [--root DIR] [--header PATH] [--description PATH]

Without --check it writes the generated files (GENERATED below) from the description. With --check (make
check-api, run by make test) it writes them into a temporary folder and compares them with the committed ones,
checks the description against include/physpix.h (every PP_API function with its argument names and types, every
struct field, every enum value, the callback typedefs), that every numeric argument and def field has a range (or a
reason it has none) in "ranges", that every field of a def in "def_fields" has a kind or a
reason not to be set, and that each function reaches the plugin and the Godot adapter or is listed in "not_exposed"
with a reason. Python 3 standard library only.
"""
import argparse
import difflib
import json
import re
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import api_header  # noqa: E402  (beside this file)
from api_ranges import check_ranges  # noqa: E402
from api_targets import GENERATED, check_def_fields, host_sources  # noqa: E402

HERE = Path(__file__).resolve().parent


def load(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def generate(desc, out_root):
    """Write every generated file under out_root; returns their paths relative to it."""
    for rel, make in GENERATED.items():
        path = Path(out_root) / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(make(desc), encoding="utf-8")
    return list(GENERATED)


def _signature(name, sig):
    ret, args = sig
    return f"{ret} {name}({', '.join(f'{t} {n}' for n, t in args) or 'void'})"


def check_header(desc, header_path):
    """Differences between the description and the header, as messages that say what to do."""
    hdr = api_header.parse(Path(header_path).read_text(encoding="utf-8"))
    where = f"{header_path}"
    fix = "describe it in plugin/api/physpix_api.json"
    errors = []
    for name, sig in hdr["functions"].items():
        if name not in desc["functions"]:
            errors.append(f"{where} declares {_signature(name, sig)}, which the description lacks: {fix} "
                          "(\"functions\", and each host or \"not_exposed\")")
        elif desc["functions"][name] != sig:
            errors.append(f"{name}: the header says {_signature(name, sig)}, the description "
                          f"{_signature(name, desc['functions'][name])}")
    errors += [f"the description has {n}, which {where} does not declare" for n in desc["functions"]
               if n not in hdr["functions"]]
    for name, fields in hdr["structs"].items():
        mine = desc["structs"].get(name)
        if mine is None:
            errors.append(f"{where} defines struct {name}, which the description lacks: {fix} (\"structs\")")
            continue
        theirs, ours = dict(map(tuple, fields)), dict(map(tuple, mine))
        errors += [f"{name}.{f} ({t}) is in {where} but not in the description's \"structs\"" for f, t in fields
                   if f not in ours]
        errors += [f"{name}.{f} is in the description but not in {where}" for f in ours if f not in theirs]
        errors += [f"{name}.{f}: the header says {theirs[f]}, the description {ours[f]}" for f in ours
                   if f in theirs and theirs[f] != ours[f]]
        if not errors and [f for f, _ in fields] != [f for f, _ in mine]:
            errors.append(f"{name}: the fields are in another order in the description than in {where}")
    errors += [f"the description has struct {n}, which {where} does not define" for n in desc["structs"]
               if n not in hdr["structs"]]
    for name, values in hdr["enums"].items():
        values = {k: v for k, v in values.items() if not k.endswith("_FORCE_U32")}
        if desc["enums"].get(name) != values:
            errors.append(f"enum {name}: the header has {values}, the description {desc['enums'].get(name)}")
    if hdr["callbacks"] != desc["callbacks"]:
        errors.append(f"callbacks: the header has {hdr['callbacks']}, the description {desc['callbacks']}")
    return errors


def _used_functions(text, functions):
    """The described functions a C source names (outside comments)."""
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    text = re.sub(r"//[^\n]*", "", text)
    return set(re.findall(r"\bpp_\w+\b", text)) & set(functions)


def check_hosts(desc, root):
    """Every function reaches each host or is listed, with a reason, in not_exposed; listed ones are not used."""
    errors = []
    for host, sources in host_sources(Path(root)).items():
        used = set()
        for path in sources:
            used |= _used_functions(path.read_text(encoding="utf-8"), desc["functions"])
        skipped = desc["not_exposed"].get(host, {})
        for name in desc["functions"]:
            if name not in used and not str(skipped.get(name, "")).strip():
                errors.append(f"{name} reaches no {host} method: expose it in \"{host}\" of "
                              f"plugin/api/physpix_api.json, or list it in \"not_exposed\".\"{host}\" with a reason")
            elif name in used and name in skipped:
                errors.append(f"{name} is used by the {host} host but listed in \"not_exposed\".\"{host}\"")
        errors += [f"\"not_exposed\".\"{host}\" lists {n}, which is no described function" for n in skipped
                   if n not in desc["functions"]]
    return errors


def check_generated(desc, root):
    """Committed generated files that differ from what the description gives now."""
    errors = []
    with tempfile.TemporaryDirectory() as tmp:
        for rel in generate(desc, tmp):
            fresh = (Path(tmp) / rel).read_text(encoding="utf-8")
            committed_path = Path(root) / rel
            committed = committed_path.read_text(encoding="utf-8") if committed_path.exists() else ""
            if fresh != committed:
                diff = list(difflib.unified_diff(committed.splitlines(), fresh.splitlines(), f"{rel} (committed)",
                                                 f"{rel} (from the description)", lineterm="", n=1))
                errors.append(f"{rel} is stale: run python3 plugin/api/gen_api.py and commit it\n" +
                              "\n".join(diff[:24]))
    return errors


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="check instead of writing")
    parser.add_argument("--root", default=str(HERE.parents[1]), help="the repository root")
    parser.add_argument("--header", help="the public header (default ROOT/include/physpix.h)")
    parser.add_argument("--description", help="the description (default ROOT/plugin/api/physpix_api.json)")
    args = parser.parse_args(argv)
    root = Path(args.root)
    desc_path = Path(args.description or root / "plugin/api/physpix_api.json")
    try:
        desc = load(desc_path)
    except (OSError, ValueError) as exc:
        print(f"gen_api: cannot read {desc_path}: {exc}", file=sys.stderr)
        return 1
    try:
        if not args.check:
            for rel in generate(desc, root):
                print(f"gen_api: wrote {rel}")
            return 0
        errors = check_header(desc, args.header or root / "include/physpix.h")
        errors += check_ranges(desc, api_header.parse(Path(args.header or root / "include/physpix.h").read_text(encoding="utf-8")))
        unclassified = check_def_fields(desc)  # the def fields' file cannot be generated then
        errors += unclassified + (check_generated(desc, root) if not unclassified else []) + check_hosts(desc, root)
    except ValueError as exc:  # a description the generator cannot turn into bindings
        print(f"gen_api: {desc_path}: {exc}", file=sys.stderr)
        return 1
    for e in errors:
        print(f"gen_api: {e}", file=sys.stderr)
    if errors:
        print(f"gen_api: {len(errors)} problem(s); the description is plugin/api/physpix_api.json", file=sys.stderr)
        return 1
    print(f"gen_api: {len(desc['functions'])} functions, {len(desc['structs'])} structs and the generated files "
          "agree with include/physpix.h and the hosts")
    return 0


if __name__ == "__main__":
    sys.exit(main())
