"""A small, tolerant reader of include/physpix.h: its PP_API functions, structs, enums and callback typedefs.

The header is regular (one declaration a statement, no macros in declarations), so comments are dropped and
each statement is matched with a pattern. C types come back normalised: tokens joined by one space
("const pp_world_def *", "void * (*)(uint64_t, void *)"), so the description compares them as strings.
"""
import re

_BLOCK_COMMENT = re.compile(r"/\*.*?\*/", re.S)
_LINE_COMMENT = re.compile(r"//[^\n]*")
_FUNCTION = re.compile(r"\bPP_API\s+([^;()]*?)\b(pp_\w+)\s*\(([^;]*?)\)\s*;", re.S)
_STRUCT = re.compile(r"\btypedef\s+struct\s+(\w+)\s*\{([^{}]*)\}\s*(\w+)\s*;", re.S)
_ENUM = re.compile(r"\btypedef\s+enum\s+(\w+)\s*\{([^{}]*)\}\s*(\w+)\s*;", re.S)
_CALLBACK = re.compile(r"\btypedef\s+([^;(){}]*?)\(\s*\*\s*(\w+)\s*\)\s*\(([^;]*?)\)\s*;", re.S)
_FIELD_FN = re.compile(r"^(.*?)\(\s*\*\s*(\w+)\s*\)\s*\((.*)\)$", re.S)


def c_type(text):
    """A C type with its tokens joined by single spaces: 'const  uint8_t*' -> 'const uint8_t *'."""
    return " ".join(re.findall(r"\w+|\*|\(|\)|,", text)).replace("( ", "(").replace(" )", ")").replace(" ,", ",").replace(") (", ")(")


def _declarator(text):
    """(name, type) of one parameter or field such as 'const pp_body_def *def' or 'void *(*alloc)(uint64_t, void *)'."""
    text = " ".join(text.split())
    fn = _FIELD_FN.match(text)
    if fn:
        params = [p for _, p in _params(fn.group(3))]
        return fn.group(2), c_type(f"{fn.group(1)} (*)({', '.join(params)})")
    m = re.match(r"^(.*?)(\w+)$", text)
    if not m or not m.group(1).strip():
        raise ValueError(f"cannot read the declaration '{text}'")
    return m.group(2), c_type(m.group(1))


def _params(text):
    """[(name, type)] of a parameter list; '(void)' is none. Unnamed parameters get their position as a name."""
    text = text.strip()
    if text in ("", "void"):
        return []
    out = []
    for i, part in enumerate(text.split(",")):
        part = part.strip()
        if re.match(r"^[\w\s*]*\*$", part) or re.match(r"^(const\s+)?\w+$", part):  # a type alone
            out.append((f"arg{i}", c_type(part)))
        else:
            out.append(_declarator(part))
    return out


def parse(text):
    """{'functions': {name: [return type, [[arg, type], ...]]}, 'structs': {name: [[field, type], ...]},
    'enums': {name: {VALUE: int}}, 'callbacks': {name: type}} of a header's text, in declaration order."""
    text = _LINE_COMMENT.sub("", _BLOCK_COMMENT.sub("", text))
    text = "\n".join(line for line in text.splitlines() if not line.lstrip().startswith("#"))
    functions = {m.group(2): [c_type(m.group(1)), [list(p) for p in _params(m.group(3))]]
                 for m in _FUNCTION.finditer(text)}
    structs = {}
    for m in _STRUCT.finditer(text):
        fields = [list(_declarator(d)) for d in m.group(2).split(";") if d.strip()]
        structs[m.group(3)] = fields
    enums = {}
    for m in _ENUM.finditer(text):
        values = {}
        for item in m.group(2).split(","):
            if item.strip():
                name, _, value = item.partition("=")
                values[name.strip()] = int(value.strip(), 0)
        enums[m.group(3)] = values
    callbacks = {m.group(2): c_type(f"{m.group(1)} (*)({', '.join(t for _, t in _params(m.group(3)))})")
                 for m in _CALLBACK.finditer(text)}
    return {"functions": functions, "structs": structs, "enums": enums, "callbacks": callbacks}
