"""The part of Python and its standard library that :mod:`.evaluate` reads: operators, comparisons, indexing,
string methods and formatting, ``os.path``, ``pathlib``, ``os.environ``/``os.getenv`` and a few builtins.

Only plain values take part (strings, numbers, booleans, None, lists, tuples, dicts, paths); anything else is an
:class:`~.evaluate.Unknown` saying why. Formatting refuses field widths over 1000 and attribute look-ups in format
fields, so a hostile file cannot make a huge string or reach Python's internals; nothing here touches the file
system, runs a program or imports a module.
"""

from __future__ import annotations

import posixpath
import re
import string
from pathlib import PurePosixPath

from .values import MAX_NESTING, MAX_SIZE, Call, Ctx, Located, Symbol, Unknown, first_unknown, shown, sized

PLAIN = (str, int, float, bool, type(None))
WIDTH = re.compile(r"\d+")
PERCENT = re.compile(r"%(?:\([^)]*\))?[-+ #0]*(\*|\d+)?(?:\.(\*|\d+))?[a-zA-Z%]")


class EnvMap:
    """``os.environ``: look-ups answered from the read's environment and recorded in ``ctx.env_reads``."""

    def __repr__(self) -> str:
        return "os.environ"


def env_value(ctx: Ctx, name, line: int | None, default=None, required: bool = False):
    """The environment variable ``name``, ``default`` when unset, or an Unknown when it is required
    (``os.environ[NAME]``) or its name cannot be known. The value it gives (a string, else None) is recorded in
    ``ctx.env_reads`` at its first read."""
    if not isinstance(name, str):
        return Unknown("an environment variable whose name cannot be known", line)
    value = ctx.environ.get(name)
    ctx.env_reads.setdefault(name, (value if value is not None else default if isinstance(default, str) else None,
                                    line))
    if value is not None:
        return value
    if required:
        return Unknown(f"environment variable {name} is not set (os.environ[{name!r}] fails when the file runs)",
                       line, f"‹${name}›", env=name)
    return default


def plain(value, depth: int = 0) -> bool:
    """Whether ``value`` is a plain Python value (nested lists, tuples and dicts of them too, at most
    :data:`MAX_NESTING` deep)."""
    if isinstance(value, PLAIN):
        return True
    if depth >= MAX_NESTING:
        return False
    if isinstance(value, (list, tuple)):
        return all(plain(v, depth + 1) for v in value)
    if isinstance(value, dict):
        return all(plain(k, depth + 1) and plain(v, depth + 1) for k, v in value.items())
    return False


def _safe_spec(spec: str) -> bool:
    """A format spec with no nested field (``{:{width}}``) and no width or precision past 1000."""
    return "{" not in spec and all(int(w) <= 1000 for w in WIDTH.findall(spec))


def format_value(value, spec, conversion, line):
    """``format(value, spec)`` after ``!r``/``!s``/``!a`` for plain values (an f-string's field)."""
    if not plain(value) and not isinstance(value, PurePosixPath):
        return Unknown(f"an f-string of {_kind(value)} gives its Python text, not its value, when the file runs (put "
                       "launch substitutions in a list instead)", line)
    if not isinstance(spec, str) or not _safe_spec(spec):
        return Unknown("an f-string field whose format is not read here", line)
    if isinstance(value, PurePosixPath):
        value = str(value)
    if conversion == "r":
        value = repr(value)
    elif conversion == "a":
        value = ascii(value)
    elif conversion == "s":
        value = str(value)
    try:
        return sized(format(value, spec), line)
    except (ValueError, TypeError) as err:
        return Unknown(f"formatting fails: {err}", line)


def str_format(text: str, args: list, kwargs: dict, line):
    """``text.format(*args, **kwargs)`` for plain arguments and simple fields."""
    try:
        fields = list(string.Formatter().parse(text))
    except ValueError as err:
        return Unknown(f"a bad format string: {err}", line)
    for _, name, spec, _ in fields:
        if name is not None and (re.search(r"[.\[]", name) or not _safe_spec(spec or "")):
            return Unknown("a format field that is not read here", line)
    if not plain(list(args)) or not plain(kwargs):
        return Unknown(first_unknown(list(args) + list(kwargs.values())).reason if
                       first_unknown(list(args) + list(kwargs.values())) else "formatting non-plain values", line)
    try:
        return sized(text.format(*args, **kwargs), line)
    except (IndexError, KeyError, ValueError, TypeError) as err:
        return Unknown(f"formatting fails: {err!r}", line)


def percent_format(text: str, args, line):
    if any(m.group(1) == "*" or m.group(2) == "*" or int(m.group(1) or 0) > 1000 or int(m.group(2) or 0) > 1000
           for m in PERCENT.finditer(text)) or not plain(args):
        return Unknown("%-formatting that is not read here", line)
    try:
        return sized(text % args, line)
    except (TypeError, ValueError, KeyError) as err:
        return Unknown(f"%-formatting fails: {err}", line)


def _number(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def binary(left, op: str, right, line):
    """``left OP right`` (``op`` an ast operator's class name)."""
    unknown = first_unknown((left, right))
    if unknown is not None:
        return unknown.like(shown(left) + shown(right)) if op == "Add" else unknown
    if op == "Add":
        if isinstance(left, str) and isinstance(right, str):
            joined = sized(left + right, line)
            return Located.make(joined, left.package) if isinstance(left, Located) and isinstance(joined, str) \
                else joined
        if (isinstance(left, list) and isinstance(right, list)) or (isinstance(left, tuple) and
                                                                     isinstance(right, tuple)):
            return sized(left + right, line)
        if _number(left) and _number(right):
            return sized(left + right, line)
        return Unknown(f"'+' between {_kind(left)} and {_kind(right)} fails when the file runs (TypeError)"
                       + ("; put substitutions in a list instead" if not plain(left) or not plain(right) else ""),
                       line, shown(left) + shown(right))
    if op == "Div" and isinstance(left, PurePosixPath) and isinstance(right, (str, PurePosixPath)):
        return left / right
    if op == "Div" and isinstance(left, str) and isinstance(right, PurePosixPath):
        return PurePosixPath(left) / right
    if op == "Mod" and isinstance(left, str):
        return percent_format(left, right, line)
    if op == "Mult" and isinstance(left, (str, list)) and isinstance(right, int) and not isinstance(right, bool):
        return sized(left * right, line) if len(left) * max(right, 0) <= MAX_SIZE else \
            Unknown(f"a value of over {MAX_SIZE} items is not built here", line)
    if _number(left) and _number(right):
        try:
            if op == "Pow" and (abs(right) > 64 or abs(left) > MAX_SIZE):
                return Unknown("a power this large is not computed here", line)
            compute = {"Sub": lambda a, b: a - b, "Mult": lambda a, b: a * b, "Div": lambda a, b: a / b,
                       "FloorDiv": lambda a, b: a // b, "Mod": lambda a, b: a % b, "Pow": lambda a, b: a ** b}
            if op in compute:
                return sized(compute[op](left, right), line)
        except (ZeroDivisionError, OverflowError) as err:
            return Unknown(f"arithmetic fails: {err}", line)
    return Unknown(f"{op} of {_kind(left)} and {_kind(right)} is not computed here", line)


def _kind(value) -> str:
    if isinstance(value, str):
        return "a string"
    if _number(value):
        return "a number"
    if isinstance(value, (list, tuple)):
        return "a list"
    what = getattr(value, "what", None)   # launch values name themselves: "a LaunchConfiguration"
    if isinstance(what, str):
        return what
    return type(value).__name__ if not isinstance(value, Symbol) else value.name


COMPARE = {"Eq": lambda a, b: a == b, "NotEq": lambda a, b: a != b, "Lt": lambda a, b: a < b,
           "LtE": lambda a, b: a <= b, "Gt": lambda a, b: a > b, "GtE": lambda a, b: a >= b,
           "In": lambda a, b: a in b, "NotIn": lambda a, b: a not in b}


def compare(left, op: str, right, line):
    unknown = first_unknown((left, right))
    if unknown is not None:
        return unknown
    if op in ("Is", "IsNot") and (left is None or right is None or isinstance(left, bool)):
        return (left is right) == (op == "Is")
    if plain(left) and plain(right) and op in COMPARE:
        try:
            return bool(COMPARE[op](left, right))
        except TypeError:
            return Unknown("a comparison that fails when the file runs", line)
    return Unknown(f"a comparison of {_kind(left)} and {_kind(right)} is not made here", line)


def subscript(ctx: Ctx, base, key, line):
    if isinstance(base, Unknown):
        return base
    if isinstance(key, Unknown):
        return key
    if isinstance(base, EnvMap):
        return env_value(ctx, key, line, required=True)
    if isinstance(base, dict):
        if isinstance(key, (str, int, float, bool)) and key in base:
            return base[key]
        return Unknown(f"the key {key!r} is not in the dict (KeyError when the file runs)", line)
    if isinstance(base, (list, tuple, str)) and (isinstance(key, slice) or
                                                 (isinstance(key, int) and not isinstance(key, bool))):
        try:
            return base[key]
        except IndexError:
            return Unknown(f"index {key} is out of range", line)
    if isinstance(base, tuple) is False and isinstance(base, PurePosixPath) and isinstance(key, int):
        return Unknown("a path cannot be indexed", line)
    return Unknown(f"indexing {_kind(base)} is not read here", line)


def module_attribute(ctx: Ctx, dotted: str, line):
    """``module.name`` for a module the file imports: ``os.environ``, ``os.sep``; other names stay names."""
    if dotted == "os.environ":
        return EnvMap()
    if dotted in ("os.sep", "os.path.sep"):
        return "/"
    if dotted in ("os.pathsep", "os.path.pathsep"):
        return ":"
    return Symbol(dotted)


def value_attribute(ctx: Ctx, base, attr: str, line):
    if isinstance(base, Unknown):
        return base
    if isinstance(base, PurePosixPath) and attr in ("parent", "name", "stem", "suffix", "parents"):
        value = getattr(base, attr)
        return tuple(value) if attr == "parents" else value
    hook = getattr(base, "attribute", None)
    if callable(hook):
        return hook(attr, line)
    return Unknown(f".{attr} of {_kind(base)} is not read here", line)


STR_METHODS = ("split", "rsplit", "strip", "lstrip", "rstrip", "lower", "upper", "replace", "startswith",
               "endswith", "splitlines", "title", "capitalize", "casefold", "removeprefix", "removesuffix")


def call_method(ctx: Ctx, base, name: str, call: Call):
    """``base.name(...)`` for a value the file holds."""
    line = call.line
    if isinstance(base, Unknown):
        return base
    if isinstance(base, EnvMap) and name == "get":
        return env_value(ctx, call.arg(0, "key"), line, call.arg(1, "default"))
    if isinstance(base, str):
        if name == "format":
            return str_format(base, call.args, call.kwargs, line)
        if name == "join" and isinstance(call.arg(0, "iterable"), (list, tuple)):
            parts = list(call.arg(0, "iterable"))
            unknown = first_unknown(parts)
            if unknown is not None:
                return unknown.like(base.join(shown(p) for p in parts))
            if not all(isinstance(p, str) for p in parts):
                return Unknown("str.join() of something that is no string", line)
            if sum(map(len, parts)) + len(base) * max(0, len(parts) - 1) > MAX_SIZE:   # measured before it is built
                return Unknown(f"a value of over {MAX_SIZE} items is not built here", line)
            return base.join(parts)
        if name in STR_METHODS and hasattr(str, name) and plain(call.args) and plain(call.kwargs):
            if name == "replace" and len(call.args) >= 2 and all(isinstance(a, str) for a in call.args[:2]):
                old, new = call.args[:2]
                if len(base) + (base.count(old) if old else len(base) + 1) * (len(new) - len(old)) > MAX_SIZE:
                    return Unknown(f"a value of over {MAX_SIZE} items is not built here", line)
            try:
                return sized(getattr(str(base), name)(*call.args, **call.kwargs), line)
            except (TypeError, ValueError) as err:
                return Unknown(f"str.{name}() fails: {err}", line)
    if isinstance(base, list) and name in ("append", "extend", "insert"):
        if name == "append":
            base.append(call.arg(0, "object"))
        elif name == "extend" and isinstance(call.arg(0, "iterable"), (list, tuple)):
            base.extend(call.arg(0, "iterable"))
        elif name == "insert" and isinstance(call.arg(0, "index"), int):
            base.insert(call.arg(0, "index"), call.arg(1, "object"))
        else:
            base.append(Unknown(f"list.{name}() of something that cannot be known", line))
        return None
    if isinstance(base, (list, dict)) and name == "copy":
        return base.copy()
    if isinstance(base, dict):
        if name == "items":
            return [(k, v) for k, v in base.items()]
        if name in ("keys", "values"):
            return list(getattr(base, name)())
        if name == "get":
            key = call.arg(0, "key")
            return base.get(key, call.arg(1, "default")) if plain(key) else Unknown("a dict key unknown", line)
        if name == "update" and isinstance(call.arg(0, "other"), dict):
            base.update(call.arg(0, "other"))
            return None
    if isinstance(base, PurePosixPath):
        return _path_method(base, name, call)
    hook = getattr(base, "method", None)
    if callable(hook):
        return hook(ctx, name, call)
    return Unknown(f".{name}() of {_kind(base)} is a call worldgen does not follow", line)


def _path_method(base: PurePosixPath, name: str, call: Call):
    args = call.args
    if name == "joinpath" and all(isinstance(a, (str, PurePosixPath)) for a in args):
        return base.joinpath(*args)
    if name in ("resolve", "absolute"):
        if not base.is_absolute():
            return Unknown(f"Path.{name}() of a relative path depends on where the file runs", call.line)
        return PurePosixPath(posixpath.normpath(str(base)))
    if name in ("as_posix", "__str__"):
        return str(base)
    if name in ("with_name", "with_suffix") and args and isinstance(args[0], str):
        try:
            return getattr(base, name)(args[0])
        except ValueError as err:
            return Unknown(f"Path.{name}() fails: {err}", call.line)
    return Unknown(f"Path.{name}() is not followed (it may look at the file system)", call.line)


def _path_text(value):
    if isinstance(value, PurePosixPath):
        return str(value)
    return value


def _os_path(call: Call):
    name = call.name.rsplit(".", 1)[-1]
    args = [_path_text(a) for a in call.args]
    unknown = first_unknown(args)
    if unknown is not None:
        return unknown.like("/".join(shown(a) for a in args)) if name == "join" else unknown
    if not all(isinstance(a, str) for a in args) or not args:
        return Unknown(f"os.path.{name}() of something that is no string fails when the file runs (TypeError); "
                       "use PathJoinSubstitution for launch substitutions", call.line,
                       "/".join(shown(a) for a in args))
    if name == "join":
        joined = posixpath.join(*args)
        first = call.args[0]
        keep = isinstance(first, Located) and not any(posixpath.isabs(a) for a in args[1:])
        return Located.make(joined, first.package) if keep else joined
    if name == "abspath":
        return posixpath.normpath(args[0]) if posixpath.isabs(args[0]) else \
            Unknown("os.path.abspath() of a relative path depends on where the file runs", call.line)
    function = {"dirname": posixpath.dirname, "basename": posixpath.basename, "normpath": posixpath.normpath,
                "realpath": posixpath.normpath, "splitext": posixpath.splitext}.get(name)
    if function is None:
        return Unknown(f"os.path.{name}() is not followed (it may look at the file system)", call.line)
    return function(args[0]) if name != "realpath" or posixpath.isabs(args[0]) else \
        Unknown("os.path.realpath() of a relative path depends on where the file runs", call.line)


def _builtin(call: Call):
    name, args, line = call.name, call.args, call.line
    unknown = first_unknown(args)
    if unknown is not None and name not in ("print",):
        return unknown
    value = args[0] if args else None
    if name == "print":
        return None
    if name == "str" and len(args) == 1:
        if isinstance(value, PurePosixPath) or plain(value):
            return str(value)
        return Unknown(f"str() of {_kind(value)} is not its value (substitutions are evaluated when the file "
                       "runs)", line)
    if name in ("int", "float", "bool") and len(args) == 1 and plain(value):
        try:
            return {"int": int, "float": float, "bool": bool}[name](value)
        except (TypeError, ValueError) as err:
            return Unknown(f"{name}() fails: {err}", line)
    if name == "len" and isinstance(value, (str, list, tuple, dict)):
        return len(value)
    if name in ("list", "tuple") and isinstance(value, (list, tuple, str)):
        return list(value) if name == "list" else tuple(value)
    if name == "list" and not args:
        return []
    if name == "dict":
        return dict(call.kwargs) if not args else (dict(value) if isinstance(value, dict) else
                                                    Unknown("dict() of something unknown", line))
    if name in ("min", "max", "sorted", "reversed", "abs", "round") and plain(args):
        try:
            result = {"min": min, "max": max, "sorted": sorted, "abs": abs, "round": round,
                      "reversed": lambda v: list(reversed(v))}[name](*args)
            return list(result) if name == "sorted" else result
        except (TypeError, ValueError) as err:
            return Unknown(f"{name}() fails: {err}", line)
    if name == "os.fspath" and isinstance(value, (str, PurePosixPath)):
        return str(value)
    if name in ("pathlib.Path", "pathlib.PurePath", "pathlib.PurePosixPath", "Path", "PurePath", "PurePosixPath"):
        if all(isinstance(a, (str, PurePosixPath)) for a in args):
            return PurePosixPath(*args) if args else PurePosixPath(".")
        return Unknown("Path() of something that is no string", line)
    return None


BUILTINS = ("print", "str", "int", "float", "bool", "len", "list", "tuple", "dict", "min", "max", "sorted",
            "reversed", "abs", "round", "os.fspath", "pathlib.Path", "pathlib.PurePath", "pathlib.PurePosixPath",
            "Path", "PurePath", "PurePosixPath")


def call_named(ctx: Ctx, call: Call):
    """A call of a name the file does not define: the caller's calls first (dotted, then the last part), then
    the standard library's, else an Unknown saying it is not followed."""
    handler = ctx.calls.get(call.name) or ctx.calls.get(call.name.rsplit(".", 1)[-1])
    if handler is not None:
        return handler(ctx, call)
    if call.name.startswith("os.path."):
        return _os_path(call)
    if call.name == "os.getenv":
        return env_value(ctx, call.arg(0, "key"), call.line, call.arg(1, "default"))
    if call.name in BUILTINS:
        value = _builtin(call)
        if value is not None or call.name == "print":
            return value
    return Unknown(f"{call.name}() is a call worldgen does not follow (launch files are read, never run)",
                   call.line, f"‹{call.name}()›")
