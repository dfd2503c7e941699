#!/usr/bin/env python3
"""Writes the GDNative API struct declarations (core and chosen extensions) from
Godot's gdnative_api.json, so the adapter's view of the engine's function tables is
derived from the engine's own description rather than typed in by hand.

usage: gen_gdnative_api.py API_JSON OUT_HEADER [--ext NAME ...]

The build reads the committed output (plugin/godot/gdnative_api_structs.h); `make godot-api
GODOT_API_JSON=...` runs this on a godot-headers checkout's gdnative_api.json to regenerate it.

The JSON lists function pointers in struct order; it does not describe the value
types, so their sizes (checked against Godot 3.2.3 on x86-64) live in the tables
below. A type not in the tables is never guessed: behind a pointer it is an opaque void typedef (or plain void), and a function
that passes or returns it by value becomes a plain void * member (same size, not
callable without a cast).
"""
import argparse
import json
import os
import re
import sys

# Engine value types, kept as opaque byte arrays of the engine's sizes: the engine's
# own headers declare them so, and the x86-64 calling convention classifies a struct
# by its members, so a float-based declaration would return in the wrong register.
OPAQUE_SIZES = {
    "godot_variant": 24,
    "godot_string": 8, "godot_char_string": 8, "godot_string_name": 8,
    "godot_array": 8, "godot_dictionary": 8, "godot_node_path": 8, "godot_rid": 8,
    "godot_pool_byte_array": 8, "godot_pool_int_array": 8, "godot_pool_real_array": 8,
    "godot_pool_string_array": 8, "godot_pool_vector2_array": 8,
    "godot_pool_vector3_array": 8, "godot_pool_color_array": 8,
    "godot_vector2": 8, "godot_vector3": 12, "godot_rect2": 16, "godot_transform2d": 24,
    "godot_plane": 16, "godot_quat": 16, "godot_aabb": 24, "godot_basis": 36,
    "godot_transform": 48, "godot_color": 16,
}

# Scalars and enums (C enums are int-sized on this ABI).
SCALARS = {
    "void": "void", "bool": "bool", "char": "char", "signed char": "signed char",
    "int": "int", "double": "double", "size_t": "size_t", "wchar_t": "wchar_t",
    "int64_t": "int64_t", "uint64_t": "uint64_t", "uint32_t": "uint32_t", "uint8_t": "uint8_t",
    "godot_bool": "bool", "godot_int": "int32_t", "godot_real": "float",
    "godot_error": "int32_t", "godot_variant_type": "int32_t",
    "godot_variant_operator": "int32_t", "godot_vector3_axis": "int32_t",
}

# Small structs and callbacks the engine passes by value, declared in full (sizes from
# the README; _Static_assert below checks them).
VALUE_STRUCTS = [
    ("godot_variant_call_error", 12,
     "typedef struct godot_variant_call_error {\n"
     "    int32_t error;    /* godot_variant_call_error_error; 0 is OK */\n"
     "    int32_t argument; /* index of the offending argument */\n"
     "    int32_t expected; /* godot_variant_type it wanted */\n"
     "} godot_variant_call_error;"),
    ("godot_method_attributes", 4,
     "typedef struct godot_method_attributes {\n"
     "    int32_t rpc_type; /* godot_method_rpc_mode; 0 is disabled */\n"
     "} godot_method_attributes;"),
    ("godot_instance_create_func", 24,
     "typedef struct godot_instance_create_func {\n"
     "    void *(*create_func)(godot_object *instance, void *method_data);\n"
     "    void *method_data;\n"
     "    void (*free_func)(void *method_data);\n"
     "} godot_instance_create_func;"),
    ("godot_instance_destroy_func", 24,
     "typedef struct godot_instance_destroy_func {\n"
     "    void (*destroy_func)(godot_object *instance, void *method_data, void *user_data);\n"
     "    void *method_data;\n"
     "    void (*free_func)(void *method_data);\n"
     "} godot_instance_destroy_func;"),
    ("godot_instance_method", 24,
     "typedef struct godot_instance_method {\n"
     "    godot_variant (*method)(godot_object *instance, void *method_data, void *user_data,\n"
     "                            int num_args, godot_variant **args);\n"
     "    void *method_data;\n"
     "    void (*free_func)(void *method_data);\n"
     "} godot_instance_method;"),
    ("godot_class_constructor", 8, "typedef godot_object *(*godot_class_constructor)(void);"),
]

# Types only ever reached through a pointer.
POINTER_ONLY = ["godot_object", "godot_method_bind"]

# Other engine types met behind a pointer while emitting (e.g. godot_pool_byte_array_read_access).
OPAQUE_POINTEES = set()

TYPE_RE = re.compile(r"^\s*(const\s+)?([A-Za-z_][A-Za-z0-9_ ]*?)\s*(\**)\s*$")


class Unmapped(Exception):
    pass


def known_value_type(base):
    if base in SCALARS:
        return SCALARS[base]
    if base in OPAQUE_SIZES or base in POINTER_ONLY or any(base == n for n, _, _ in VALUE_STRUCTS):
        return base
    return None


def map_type(text):
    """C spelling of a JSON type string; raises Unmapped for an unknown by-value type."""
    m = TYPE_RE.match(text)
    if not m:
        raise Unmapped(text)
    const, base, stars = m.group(1) or "", m.group(2), m.group(3)
    mapped = known_value_type(base)
    if mapped is None:
        if not stars:
            raise Unmapped(base)
        # A pointer to something we do not model is still a pointer: an engine type keeps
        # its name as an opaque void typedef, anything else (JNIEnv, ...) becomes void.
        mapped = base if base.startswith("godot_") else "void"
        if mapped != "void":
            OPAQUE_POINTEES.add(base)
    return f"{const}{mapped} {stars}".rstrip() if stars else f"{const}{mapped}"


def declarator(ctype, name):
    return f"{ctype}{name}" if ctype.endswith("*") else f"{ctype} {name}"


def member(fn):
    """One struct member for a function: a typed pointer, or void * if a type is unknown."""
    try:
        ret = map_type(fn["return_type"])
        args = [declarator(map_type(t), name) for t, name in fn["arguments"]]
    except Unmapped as e:
        return f"    void *{fn['name']}; /* not callable here: unmapped type {e} */"
    return f"    {ret} (*{fn['name']})({', '.join(args) or 'void'});"


def versions(api):
    """The api node and its `next` chain, oldest first."""
    while api:
        yield api
        api = api.get("next")


def struct_name(kind, name, version, first):
    suffix = "" if first else f"_{version['major']}_{version['minor']}"
    return f"godot_gdnative_{kind}{suffix}_api_struct" if kind == "core" else \
        f"godot_gdnative_ext_{name}{suffix}_api_struct"


def emit_chain(out, asserts, kind, name, api):
    for i, node in enumerate(versions(api)):
        sname = struct_name(kind, name, node["version"], i == 0)
        v = node["version"]
        out.append(f"/* {node['type']} {v['major']}.{v['minor']}: {len(node['api'])} functions. */")
        out.append(f"typedef struct {sname} {{")
        out.append("    unsigned int type;")
        out.append("    godot_gdnative_api_version version;")
        out.append("    const godot_gdnative_api_struct *next;")
        header_end = 24
        if kind == "core" and i == 0:
            out.append("    unsigned int num_extensions;")
            out.append("    const godot_gdnative_api_struct **extensions;")
            header_end = 40
            asserts.append((sname, "num_extensions", 24))
            asserts.append((sname, "extensions", 32))
        out.extend(member(fn) for fn in node["api"])
        out.append(f"}} {sname};")
        out.append("")
        asserts.append((sname, "type", 0))
        asserts.append((sname, "version", 4))
        asserts.append((sname, "next", 16))
        if node["api"]:
            asserts.append((sname, node["api"][0]["name"], header_end))
            last = len(node["api"]) - 1
            asserts.append((sname, node["api"][-1]["name"], header_end + 8 * last))


def generate(data, json_path, exts):
    by_name = {e["name"]: e for e in data["extensions"]}
    missing = [e for e in exts if e not in by_name]
    if missing:
        raise SystemExit(f"gen_gdnative_api: no extension {missing} in {json_path}; "
                         f"it has {sorted(by_name)}")
    out = [
        f"/* Generated by plugin/godot/gen_gdnative_api.py (make godot-api) from {os.path.basename(json_path)},",
        " * the GDNative API description of godot-headers (MIT licence, (c) Godot Engine contributors);",
        " * do not edit. */",
        "#ifndef GDNATIVE_API_STRUCTS_H",
        "#define GDNATIVE_API_STRUCTS_H",
        "",
        "#include <stdbool.h>",
        "#include <stddef.h>",
        "#include <stdint.h>",
        "#include <wchar.h>",
        "",
        "/* Values of the `type` field of an API struct: core, then the extensions in file order. */",
        "enum GDNATIVE_API_TYPES {",
        f"    GDNATIVE_{data['core']['type']} = 0,",
    ]
    out += [f"    GDNATIVE_EXT_{e['type']} = {i + 1}," for i, e in enumerate(data["extensions"])]
    out += ["};", ""]
    out += [f"typedef struct {n} {{ uint8_t _opaque[{s}]; }} {n};" for n, s in OPAQUE_SIZES.items()]
    out += [f"typedef void {n};" for n in POINTER_ONLY]
    out.append("")
    out += [decl + "\n" for _, _, decl in VALUE_STRUCTS]
    out += [
        "typedef struct godot_gdnative_api_version { unsigned int major, minor; } godot_gdnative_api_version;",
        "",
        "/* The header every API struct starts with; `next` leads to the next minor version. */",
        "typedef struct godot_gdnative_api_struct {",
        "    unsigned int type;",
        "    godot_gdnative_api_version version;",
        "    const struct godot_gdnative_api_struct *next;",
        "} godot_gdnative_api_struct;",
        "",
    ]
    asserts = []
    structs = []
    emit_chain(structs, asserts, "core", "core", data["core"])
    for e in exts:
        emit_chain(structs, asserts, "ext", e, by_name[e])
    out += [f"typedef void {n};" for n in sorted(OPAQUE_POINTEES)]
    out += [""] + structs
    out += [f"_Static_assert(sizeof({n}) == {s}, \"{n} is {s} bytes in Godot 3.2\");"
            for n, s, _ in VALUE_STRUCTS]
    out += [f"_Static_assert(offsetof({s}, {f}) == {o}, \"{s}.{f} at {o}\");" for s, f, o in asserts]
    out += ["", "#endif /* GDNATIVE_API_STRUCTS_H */", ""]
    return "\n".join(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("api_json")
    ap.add_argument("out_header")
    ap.add_argument("--ext", action="append", default=[],
                    help="extension to emit by its JSON name (e.g. nativescript); repeatable")
    a = ap.parse_args()
    try:
        with open(a.api_json, encoding="utf-8") as f:
            data = json.load(f)
    except (OSError, ValueError) as e:
        sys.exit(f"gen_gdnative_api: cannot read {a.api_json}: {e}\n"
                 "  point GODOT_API_JSON at gdnative_api.json (godot-headers, Godot 3.2)")
    text = generate(data, a.api_json, a.ext)
    with open(a.out_header, "w", encoding="utf-8") as f:
        f.write(text)


if __name__ == "__main__":
    main()
