"""Reading Python without running it: the values a plain reading of a ROS 2 launch file or a ``setup.py`` gives.

ROS 2 launch files and ament_python packages' ``setup.py`` are Python programs. worldgen never runs or imports
them: it parses them with :mod:`ast` and works out what can be known by reading — constants, names assigned in
order, ``+`` on strings and lists, f-strings, ``%`` and ``.format``, ``os.path`` and ``pathlib`` arithmetic,
``os.environ`` look-ups, calls of functions defined in the same file (followed, a few levels deep), and the calls
the caller teaches it (``Ctx.calls``: ``LaunchConfiguration``, ``get_package_share_directory``, ``glob`` …; the
standard library's part is :mod:`.stdlib`). Whatever else — a call it does not know, a name bound in a loop, a
condition it cannot tell — is an :class:`Unknown` that says what and at which line, never a guess.

Code that is not run (a loop's body, both branches of a condition that cannot be told, ``except`` blocks,
comprehensions) is handed to the caller's ``Ctx.on_skip``, which says whether it matters; names it assigns become
:class:`Unknown`. A caller may ask for comprehensions to be run (``Ctx.comprehensions``: setup.py's ``sorted(p for
p in glob(…) if os.path.isfile(p))``) when every iterable and condition in them can be known. Work is bounded: nesting depth, followed calls and the size of built strings and lists.
"""

from __future__ import annotations

import ast
from pathlib import Path
from typing import Any, List

from ..core.errors import WorldFileError
from .stdlib import binary, call_method, call_named, compare, format_value, module_attribute, subscript, \
    value_attribute
from .values import (MAX_CALL_DEPTH, MAX_CALLS, MAX_DEPTH, MAX_ITERATIONS, MAX_PYTHON_BYTES, MAX_SIZE, MAX_WORK,
                     Call, Ctx, Frame, Function, Returned, Symbol, Unknown, describe, first_unknown, not_run, shown,
                     sized, truth)
from ..core.inputs import read_capped


# ------------------------------------------------------------------------------------------- expressions

def evaluate(ctx: Ctx, node, frame: Frame):
    """The value of the expression ``node`` in ``frame`` (an :class:`Unknown` when it cannot be known)."""
    ctx.depth += 1
    try:
        if ctx.depth > MAX_DEPTH:
            return Unknown("the expression is nested too deeply to read", getattr(node, "lineno", None))
        handler = EXPRESSIONS.get(type(node).__name__)
        if handler is None:
            return Unknown(f"a {type(node).__name__} expression is not read here", getattr(node, "lineno", None))
        value = handler(ctx, node, frame)
        ctx.work += 1 + (len(value) if isinstance(value, (str, list, tuple, dict)) else 0)
        if ctx.work > MAX_WORK:
            raise WorldFileError(f"the file takes more work to read than worldgen does ({MAX_WORK:,} steps)",
                                 path=ctx.path, line=getattr(node, "lineno", None),
                                 hint="a launch file or setup.py builds few, small values; simplify it")
        return value
    finally:
        ctx.depth -= 1


def _constant(ctx, node, frame):
    value = node.value
    return value if isinstance(value, (str, int, float, bool, type(None))) else \
        Unknown("a bytes or complex constant is not read here", node.lineno)


def _name(ctx, node, frame):
    if node.id == "__file__":
        return str(ctx.path)
    return frame.lookup(node.id)


def _attribute(ctx, node, frame):
    base = evaluate(ctx, node.value, frame)
    if isinstance(base, Symbol):
        return module_attribute(ctx, f"{base.name}.{node.attr}", node.lineno)
    return value_attribute(ctx, base, node.attr, node.lineno)


def _sequence(ctx, node, frame):
    items: list = []
    for element in node.elts:
        if isinstance(element, ast.Starred):
            inner = evaluate(ctx, element.value, frame)
            if not isinstance(inner, (list, tuple)):
                return Unknown("a *starred value that is not a known list", node.lineno)
            items.extend(inner)
        else:
            items.append(evaluate(ctx, element, frame))
    return tuple(items) if isinstance(node, ast.Tuple) else items


def _dict(ctx, node, frame):
    out: dict = {}
    for key, value in zip(node.keys, node.values):
        if key is None:   # {**other}
            inner = evaluate(ctx, value, frame)
            if not isinstance(inner, dict):
                return Unknown("a **mapping that is not a known dict", node.lineno)
            out.update(inner)
            continue
        k = evaluate(ctx, key, frame)
        if isinstance(k, (str, int, float, bool)) or k is None:
            out[k] = evaluate(ctx, value, frame)
        else:
            return Unknown("a dict key that cannot be known", node.lineno)
    return out


def _joined(ctx, node, frame):
    parts = []
    for value in node.values:
        part = evaluate(ctx, value, frame)
        parts.append(part)
    unknown = first_unknown(parts)
    if unknown is not None:
        return unknown.like("".join(shown(p) for p in parts))
    return sized("".join(parts), node.lineno)


def _formatted(ctx, node, frame):
    value = evaluate(ctx, node.value, frame)
    spec = evaluate(ctx, node.format_spec, frame) if node.format_spec is not None else ""
    if isinstance(value, Unknown):
        return value
    if isinstance(spec, Unknown):
        return spec
    conversion = {115: "s", 114: "r", 97: "a"}.get(node.conversion)
    return format_value(value, spec, conversion, node.lineno)


def _binop(ctx, node, frame):
    return binary(evaluate(ctx, node.left, frame), type(node.op).__name__, evaluate(ctx, node.right, frame),
                  node.lineno)


def _unary(ctx, node, frame):
    value = evaluate(ctx, node.operand, frame)
    if isinstance(node.op, ast.Not):
        known = truth(value)
        return value if known is None else not known
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return -value if isinstance(node.op, ast.USub) else +value if isinstance(node.op, ast.UAdd) else \
            Unknown("~ is not read here", node.lineno)
    return value if isinstance(value, Unknown) else Unknown("a sign on something that is no number", node.lineno)


def _boolop(ctx, node, frame):
    is_and = isinstance(node.op, ast.And)
    value = None
    for operand in node.values:
        value = evaluate(ctx, operand, frame)
        known = truth(value)
        if known is None:
            return value if isinstance(value, Unknown) else Unknown("a condition that cannot be told", node.lineno)
        if known != is_and:
            return value
    return value


def _compare(ctx, node, frame):
    left = evaluate(ctx, node.left, frame)
    for op, right_node in zip(node.ops, node.comparators):
        right = evaluate(ctx, right_node, frame)
        outcome = compare(left, type(op).__name__, right, node.lineno)
        if outcome is not True:
            return outcome
        left = right
    return True


def _ifexp(ctx, node, frame):
    test = evaluate(ctx, node.test, frame)
    known = truth(test)
    if known is None:
        reason = test.reason if isinstance(test, Unknown) else "it cannot be told"
        if ctx.on_skip is not None:
            ctx.on_skip(ctx, "if", node, frame, reason)
        return Unknown(f"the condition at line {node.lineno} cannot be told: {reason}", node.lineno, skipped=True)
    return evaluate(ctx, node.body if known else node.orelse, frame)


def _subscript(ctx, node, frame):
    index = node.slice
    if type(index).__name__ == "Index":   # Python 3.8: the index is wrapped
        index = index.value
    base = evaluate(ctx, node.value, frame)
    if isinstance(index, ast.Slice):
        bounds = [evaluate(ctx, b, frame) if b is not None else None for b in (index.lower, index.upper, index.step)]
        if first_unknown(bounds) is not None or not all(b is None or isinstance(b, int) for b in bounds):
            return Unknown("a slice that cannot be known", node.lineno)
        key: Any = slice(*bounds)
    else:
        key = evaluate(ctx, index, frame)
    return subscript(ctx, base, key, node.lineno)


def _comprehension(ctx, node, frame):
    if ctx.comprehensions:
        value = _run_comprehension(ctx, node, frame)
        if value is not None:
            return value
    if ctx.on_skip is not None:
        ctx.on_skip(ctx, "comprehension", node, frame, None)
    return Unknown(f"{not_run('comprehension', node)} is not run here", node.lineno, skipped=True)


def _run_comprehension(ctx, node, frame):
    """The value of a comprehension whose every iterable and condition can be known (a list for a list, set or
    generator; a dict), its names bound in a frame of its own as Python does; None when one cannot be known or
    it would build more than MAX_SIZE items or go through more than MAX_ITERATIONS in the file's comprehensions."""
    inner = Frame(frame)
    items: list = []

    def walk(generators) -> bool:
        if not generators:
            if isinstance(node, ast.DictComp):
                items.append((evaluate(ctx, node.key, inner), evaluate(ctx, node.value, inner)))
            else:
                items.append(evaluate(ctx, node.elt, inner))
            return len(items) <= MAX_SIZE
        first = generators[0]
        source = evaluate(ctx, first.iter, inner)
        if getattr(first, "is_async", 0) or not isinstance(source, (list, tuple, str, dict)):
            return False
        for item in list(source):
            ctx.iterations += 1
            if ctx.iterations > MAX_ITERATIONS:
                return False
            bind(ctx, first.target, item, inner)
            kept = True
            for test in first.ifs:
                known = truth(evaluate(ctx, test, inner))
                if known is None:
                    return False
                if not known:
                    kept = False
                    break
            if kept and not walk(generators[1:]):
                return False
        return True

    if not walk(list(node.generators)):
        return None
    if not isinstance(node, ast.DictComp):
        return items
    keys = [k for k, _ in items]
    if not all(isinstance(k, (str, int, float, bool)) or k is None for k in keys):
        return None
    return dict(items)


def _lambda(ctx, node, frame):
    return Unknown(f"the lambda at line {node.lineno} is not run here", node.lineno)


def _namedexpr(ctx, node, frame):
    value = evaluate(ctx, node.value, frame)
    bind(ctx, node.target, value, frame)
    return value


def _call(ctx, node, frame):
    args: list = []
    for arg in node.args:
        if isinstance(arg, ast.Starred):
            inner = evaluate(ctx, arg.value, frame)
            if not isinstance(inner, (list, tuple)):
                return Unknown(f"{describe(node.func)}(*…): the starred arguments cannot be known", node.lineno)
            args.extend(inner)
        else:
            args.append(evaluate(ctx, arg, frame))
    kwargs: dict = {}
    for keyword in node.keywords:
        value = evaluate(ctx, keyword.value, frame)
        if keyword.arg is None:
            if not isinstance(value, dict):
                return Unknown(f"{describe(node.func)}(**…): the keyword arguments cannot be known", node.lineno)
            kwargs.update(value)
        else:
            kwargs[keyword.arg] = value
    func = node.func
    if isinstance(func, ast.Attribute):
        base = evaluate(ctx, func.value, frame)
        if not isinstance(base, Symbol):
            return call_method(ctx, base, func.attr, Call(func.attr, args, kwargs, node.lineno, node))
        target: Any = Symbol(f"{base.name}.{func.attr}")
    else:
        target = evaluate(ctx, func, frame)
    if isinstance(target, Function):
        return call_function(ctx, target, args, kwargs, node.lineno)
    if isinstance(target, Symbol):
        return call_named(ctx, Call(target.name, args, kwargs, node.lineno, node))
    if isinstance(target, Unknown):
        return Unknown(f"{describe(func)}() calls something that cannot be known: {target.reason}", node.lineno)
    return Unknown(f"{describe(func)}() cannot be called here", node.lineno)


EXPRESSIONS = {
    "Constant": _constant, "Name": _name, "Attribute": _attribute, "List": _sequence, "Tuple": _sequence,
    "Set": _sequence, "Dict": _dict, "JoinedStr": _joined, "FormattedValue": _formatted, "BinOp": _binop,
    "UnaryOp": _unary, "BoolOp": _boolop, "Compare": _compare, "IfExp": _ifexp, "Subscript": _subscript,
    "ListComp": _comprehension, "SetComp": _comprehension, "DictComp": _comprehension,
    "GeneratorExp": _comprehension, "Lambda": _lambda, "NamedExpr": _namedexpr, "Call": _call,
}


# -------------------------------------------------------------------------------------------- statements

def call_function(ctx: Ctx, fn: Function, args: list, kwargs: dict, line: int | None):
    """Follow a call of a function the file defines: its parameters bound, its body run, its return value."""
    name = fn.node.name
    if ctx.call_depth >= MAX_CALL_DEPTH or ctx.calls_made >= MAX_CALLS:
        return Unknown(f"{name}() calls nest too deeply to follow", line)
    spec = fn.node.args
    frame = Frame(fn.frame)
    positional = list(getattr(spec, "posonlyargs", [])) + list(spec.args)
    defaults = dict(zip([a.arg for a in positional][len(positional) - len(fn.defaults):], fn.defaults))
    for i, param in enumerate(positional):
        if i < len(args):
            frame.names[param.arg] = args[i]
        elif param.arg in kwargs:
            frame.names[param.arg] = kwargs[param.arg]
        elif param.arg in defaults:
            frame.names[param.arg] = defaults[param.arg]
        else:
            frame.names[param.arg] = Unknown(f"{name}() is called without its argument {param.arg}", line)
    if spec.vararg is not None:
        frame.names[spec.vararg.arg] = tuple(args[len(positional):])
    for param, default in zip(spec.kwonlyargs, fn.kw_defaults):
        frame.names[param.arg] = kwargs.get(param.arg, default)
    if spec.kwarg is not None:
        known = {a.arg for a in positional + list(spec.kwonlyargs)}
        frame.names[spec.kwarg.arg] = {k: v for k, v in kwargs.items() if k not in known}
    ctx.call_depth += 1
    ctx.calls_made += 1
    try:
        out = run(ctx, fn.node.body, frame)
    finally:
        ctx.call_depth -= 1
    return out.value if out is not None else None


def run(ctx: Ctx, body, frame: Frame) -> Returned | None:
    """Run the statements ``body`` in ``frame`` as far as they can be read; their ``return``, if one is reached."""
    for stmt in body:
        out = statement(ctx, stmt, frame)
        if out is not None:
            return out
    return None


def statement(ctx: Ctx, stmt, frame: Frame) -> Returned | None:
    kind = type(stmt).__name__
    if kind == "Assign":
        value = evaluate(ctx, stmt.value, frame)
        for target in stmt.targets:
            bind(ctx, target, value, frame)
    elif kind == "AnnAssign" and stmt.value is not None:
        bind(ctx, stmt.target, evaluate(ctx, stmt.value, frame), frame)
    elif kind == "AugAssign":
        current = evaluate(ctx, stmt.target, frame) if isinstance(stmt.target, ast.Name) else \
            Unknown("an augmented assignment to an attribute or item", stmt.lineno)
        bind(ctx, stmt.target, binary(current, type(stmt.op).__name__, evaluate(ctx, stmt.value, frame),
                                      stmt.lineno), frame)
    elif kind == "Expr":
        evaluate(ctx, stmt.value, frame)
    elif kind == "Return":
        return Returned(evaluate(ctx, stmt.value, frame) if stmt.value is not None else None)
    elif kind == "Raise":   # reached: the function ends there, as the file would stop when run
        return Returned(Unknown(f"an exception is raised at line {stmt.lineno} (the file stops there when it runs)",
                                stmt.lineno))
    elif kind == "If":
        test = evaluate(ctx, stmt.test, frame)
        known = truth(test)
        if known is None:
            reason = test.reason if isinstance(test, Unknown) else "it cannot be told"
            skip(ctx, "if", stmt, frame, reason)
            return None
        return run(ctx, stmt.body if known else stmt.orelse, frame)
    elif kind in ("For", "AsyncFor", "While"):
        skip(ctx, "while" if kind == "While" else "for", stmt, frame, None)
    elif kind in ("With", "AsyncWith"):
        for item in stmt.items:
            value = evaluate(ctx, item.context_expr, frame)
            if item.optional_vars is not None:
                bind(ctx, item.optional_vars, value if isinstance(value, Unknown) else
                     Unknown(f"the value of the with at line {stmt.lineno}", stmt.lineno), frame)
        return run(ctx, stmt.body, frame)
    elif kind in ("Try", "TryStar"):
        out = run(ctx, stmt.body, frame)
        for handler in stmt.handlers:
            skip(ctx, "except", handler, frame, None)
        return out or run(ctx, stmt.orelse, frame) or run(ctx, stmt.finalbody, frame)
    elif kind in ("FunctionDef", "AsyncFunctionDef"):
        spec = stmt.args
        frame.names[stmt.name] = Function(stmt, frame, tuple(evaluate(ctx, d, frame) for d in spec.defaults),
                                          tuple(evaluate(ctx, d, frame) if d is not None else
                                                Unknown(f"{stmt.name}() needs this keyword", stmt.lineno)
                                                for d in spec.kw_defaults))
    elif kind == "ClassDef":
        frame.names[stmt.name] = Unknown(f"the class {stmt.name} is not read here", stmt.lineno)
    elif kind == "Import":
        for alias in stmt.names:
            if alias.asname:
                frame.names[alias.asname] = Symbol(alias.name)
            else:
                top = alias.name.split(".")[0]
                frame.names[top] = Symbol(top)
    elif kind == "ImportFrom":
        module = "." * (stmt.level or 0) + (stmt.module or "")
        for alias in stmt.names:
            if alias.name != "*":
                frame.names[alias.asname or alias.name] = Symbol(f"{module}.{alias.name}")
    elif kind == "Match":
        skip(ctx, "match", stmt, frame, None)
    return None


def skip(ctx: Ctx, kind: str, node, frame: Frame, reason: str | None) -> None:
    """Code that is not run: the hook is told, and every name it assigns becomes Unknown."""
    if ctx.on_skip is not None:
        ctx.on_skip(ctx, kind, node, frame, reason)
    why = f"it is set in {not_run(kind, node)}, which is not run here" + (f" ({reason})" if reason else "")
    for inner in ast.walk(node):
        targets: List[Any] = []
        if isinstance(inner, (ast.Assign,)):
            targets = list(inner.targets)
        elif isinstance(inner, (ast.AugAssign, ast.AnnAssign, ast.For, ast.AsyncFor)):
            targets = [inner.target]
        elif isinstance(inner, ast.NamedExpr):
            targets = [inner.target]
        for target in targets:
            for name in ast.walk(target):
                if isinstance(name, ast.Name):
                    frame.names[name.id] = Unknown(f"{name.id}: {why}", getattr(node, "lineno", None),
                                                   skipped=True)


def bind(ctx: Ctx, target, value, frame: Frame) -> None:
    """Assign ``value`` to an assignment target: a name, a tuple of names, or an item of a known dict or list."""
    if isinstance(target, ast.Name):
        frame.names[target.id] = value
    elif isinstance(target, (ast.Tuple, ast.List)):
        plain = all(isinstance(e, (ast.Name, ast.Tuple, ast.List)) for e in target.elts)
        if plain and isinstance(value, (list, tuple)) and len(value) == len(target.elts):
            for element, item in zip(target.elts, value):
                bind(ctx, element, item, frame)
            return
        why = value if isinstance(value, Unknown) else Unknown("unpacking that cannot be followed",
                                                                getattr(target, "lineno", None))
        for name in ast.walk(target):
            if isinstance(name, ast.Name):
                frame.names[name.id] = why
    elif isinstance(target, ast.Subscript):
        base = evaluate(ctx, target.value, frame)
        index = target.slice.value if type(target.slice).__name__ == "Index" else target.slice
        key = evaluate(ctx, index, frame)
        if isinstance(base, dict) and isinstance(key, (str, int, float, bool)):
            base[key] = value
        elif isinstance(base, list) and isinstance(key, int) and -len(base) <= key < len(base):
            base[key] = value


def read_module(ctx: Ctx, tree) -> Frame:
    """Run a parsed module's top level (imports, assignments, definitions) into a fresh frame."""
    frame = Frame()
    run(ctx, tree.body, frame)
    return frame


def parse_python(path: Path, what: str = "file"):
    """The module the Python file ``path`` holds, parsed (never run); WorldFileError when it cannot be read or
    parsed (``what`` names the file in the message: "launch file", "setup.py")."""
    try:
        text = read_capped(path, MAX_PYTHON_BYTES, what=what).decode("utf-8")
    except OSError as err:
        raise WorldFileError(f"cannot read the {what}: {err.strerror or err}", path=path,
                             hint="check the path") from None
    except UnicodeDecodeError:
        raise WorldFileError(f"the {what} is not UTF-8 text", path=path, hint="save it as UTF-8") from None
    try:
        return ast.parse(text, filename=str(path))
    except SyntaxError as err:
        raise WorldFileError(f"Python cannot parse the {what}: {err.msg}", path=path, line=err.lineno,
                             hint="fix the syntax (python3 -m py_compile FILE shows where)") from None
    except (ValueError, RecursionError, MemoryError) as err:
        raise WorldFileError(f"Python cannot parse the {what} ({type(err).__name__})", path=path,
                             hint="fix the file") from None
