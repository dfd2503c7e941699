"""The public API keeps its type hints: every exported function and every public method, property and __init__
of an exported class carries a return annotation and annotations on its parameters (self, cls, *args and **kwargs
aside), the hints resolve at run time, and the package ships py.typed."""
import inspect
import typing
from pathlib import Path

import physpix

# Parameters that need no annotation besides a method's self or cls: the catch-alls.
_UNANNOTATED_KINDS = (inspect.Parameter.VAR_POSITIONAL, inspect.Parameter.VAR_KEYWORD)


def _ours(obj):
    module = getattr(obj, "__module__", None) or ""
    return module == "physpix" or module.startswith("physpix.")


def _public(name):
    return name == "__init__" or not name.startswith("_")


def _missing(fn, bound):
    """What fn lacks: 'return' and/or its unannotated parameter names. bound: its first parameter is self/cls."""
    sig = inspect.signature(fn)
    params = list(sig.parameters.values())
    if bound and params and params[0].kind in (inspect.Parameter.POSITIONAL_ONLY,
                                               inspect.Parameter.POSITIONAL_OR_KEYWORD):
        params = params[1:]
    lacks = [p.name for p in params if p.kind not in _UNANNOTATED_KINDS and p.annotation is inspect.Parameter.empty]
    if sig.return_annotation is inspect.Signature.empty:
        lacks.append("return")
    return lacks


def _callables():
    """(qualified name, function, whether bound) for every public callable of physpix.__all__ defined in physpix."""
    out = {}
    for export in physpix.__all__:
        obj = getattr(physpix, export)
        if inspect.isclass(obj) and _ours(obj):
            # The class's own members and those it inherits from the package's classes (PhysPixError.__init__),
            # each under the name of the class that defines it.
            for klass in reversed([k for k in obj.__mro__ if _ours(k)]):
                for name, member in vars(klass).items():
                    if not _public(name):
                        continue
                    if isinstance(member, property):
                        parts = [("getter", member.fget), ("setter", member.fset), ("deleter", member.fdel)]
                        for role, fn in parts:
                            if fn is not None:
                                out[f"{klass.__name__}.{name} ({role})"] = (fn, True)
                    elif isinstance(member, staticmethod):
                        out[f"{klass.__name__}.{name}"] = (member.__func__, False)
                    elif isinstance(member, classmethod):
                        out[f"{klass.__name__}.{name}"] = (member.__func__, True)
                    elif inspect.isfunction(member):
                        out[f"{klass.__name__}.{name}"] = (member, True)
        elif inspect.isfunction(obj) and _ours(obj):
            out[export] = (obj, False)
    return out


def test_the_checker_sees_missing_hints():
    def bare(self, a, b: int, *args, c=1, **kwargs):
        pass

    def full(self, a: int, *args: int, c: int = 1, **kwargs: int) -> None:
        pass

    assert _missing(bare, True) == ["a", "c", "return"]
    assert _missing(bare, False) == ["self", "a", "c", "return"]
    assert _missing(full, True) == []


def test_the_public_api_is_collected():
    names = set(_callables())
    # A sample of each kind: a function, a method, a classmethod, a property, a dataclass and an exception __init__.
    for name in ("load_png", "set_log_hook", "World.__init__", "World.step", "World.from_preset",
                 "Body.position (getter)", "Body.position (setter)", "Contact.__init__", "PhysPixError.__init__"):
        assert name in names


def test_every_public_callable_is_annotated():
    missing = {}
    for name, (fn, bound) in sorted(_callables().items()):
        lacks = _missing(fn, bound)
        if lacks:
            missing[name] = lacks
    assert not missing, "public callables without type hints (name: what lacks one):\n" + "\n".join(
        f"  {name}: {', '.join(lacks)}" for name, lacks in missing.items())


def test_the_hints_resolve():
    """typing.get_type_hints evaluates every hint (a name the module lacks, or syntax this Python cannot evaluate
    such as list[int] before 3.9, fails here), as documentation tools and runtime checkers will."""
    broken = {}
    targets = {name: fn for name, (fn, _) in _callables().items()}
    targets.update((export, getattr(physpix, export)) for export in physpix.__all__
                   if inspect.isclass(getattr(physpix, export)) and _ours(getattr(physpix, export)))
    for name, target in sorted(targets.items()):
        try:
            typing.get_type_hints(target)
        except Exception as exc:  # noqa: BLE001 - NameError, TypeError, SyntaxError: all mean the same here
            broken[name] = f"{type(exc).__name__}: {exc}"
    assert not broken, "hints that do not resolve:\n" + "\n".join(f"  {k}: {v}" for k, v in broken.items())


def test_the_package_ships_py_typed():
    marker = Path(physpix.__file__).parent / "py.typed"
    assert marker.is_file(), f"{marker} is missing: type checkers ignore the hints of a package without it (PEP 561)"
