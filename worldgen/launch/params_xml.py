"""roslaunch's rules for the parameters a launch file sets, as plain functions: what type a ``<param value>``
becomes, where a ``<param>``/``<rosparam>`` name lands (global, in a ``<group ns>``, or a node's private ``~``
namespace), and what a ``<rosparam>`` YAML document sets.

The rules, as roslaunch applies them (ROS 1 Noetic):

- ``<param type="auto">`` (the default): a value with a ``.`` that reads as a number is a double, one without
  that reads as an integer is an int, ``true``/``false`` (any case, surrounding space ignored) a bool, anything
  else the string as written. ``str``/``string``, ``int``, ``double``, ``bool``/``boolean`` (``true``/``1``,
  ``false``/``0``) and ``yaml`` force a type; a value that is not of it is an error roslaunch stops on.
- A name is resolved in the namespace of the element holding it: inside a ``<node>`` relative and ``~`` names are
  the node's private ones (``/ns/node_name/NAME``); elsewhere relative names are in the group's namespace and a
  ``~`` name is an error. Absolute names stay.
- ``<rosparam>`` loads a YAML document (inline text, or ``file=``): with ``param=`` the whole document is that
  parameter's value; without, it must be a mapping, each key a parameter under ``ns``. ``!degrees`` and
  ``!radians`` tags give radians, as rosparam's loader does.
"""

from __future__ import annotations

import math
from typing import Any, Dict, List, Tuple

from .model import join_ns

TRUE_WORDS = ("true", "1")
FALSE_WORDS = ("false", "0")
XMLRPC_INT = 2 ** 31   # the master's XML-RPC carries 32-bit integers


class ParamError(ValueError):
    """A parameter roslaunch would refuse (the message says what is wrong with it)."""


def typed_value(text: str, kind: str | None) -> Any:
    """``<param value=text type=kind>`` as roslaunch stores it (see the module docstring); ParamError when the
    text is not of a forced type."""
    kind = (kind or "auto").strip().lower()
    if kind == "auto":
        number = _number(text)
        if number is not None:
            return number
        if text.strip().lower() in ("true", "false"):
            return text.strip().lower() == "true"
        return text
    if kind in ("str", "string"):
        return text
    if kind == "int":
        try:
            return int(text.strip())
        except ValueError:
            raise ParamError(f"{text!r} is not an int") from None
    if kind == "double":
        try:
            return float(text.strip())
        except ValueError:
            raise ParamError(f"{text!r} is not a double") from None
    if kind in ("bool", "boolean"):
        word = text.strip().lower()
        if word in TRUE_WORDS or word in FALSE_WORDS:
            return word in TRUE_WORDS
        raise ParamError(f"{text!r} is not a bool (true, false, 1 or 0)")
    if kind == "yaml":
        return load_yaml(text)
    raise ParamError(f"unknown type {kind!r} (str, int, double, bool or yaml)")


def _number(text: str) -> int | float | None:
    try:
        return float(text) if "." in text else int(text)
    except ValueError:
        return None


def param_name(name: str, ns: str, node: str | None) -> str:
    """The full name a ``<param>``/``<rosparam>`` ``name`` sets: in the private namespace of the node whose full
    name is ``node`` when inside a ``<node>``, else in ``ns``. ParamError for a ``~`` name outside a node."""
    if name.startswith("/"):
        return join_ns("/", name)
    if node is not None:
        return join_ns(node, name[1:] if name.startswith("~") else name)
    if name.startswith("~"):
        raise ParamError(f"private parameter {name!r} outside a <node> (roslaunch refuses it)")
    return join_ns(ns, name)


def _angle(text: str) -> float:
    """An angle expression as rosparam reads one (``pi/2``, ``rad(pi/4)``, ``deg(90)``, ``-1.5``): numbers,
    ``pi``, ``+ - * /``, ``rad()`` and ``deg()``, evaluated from its syntax tree (nothing is run). ValueError
    for anything else."""
    import ast

    def value(node) -> float:
        if isinstance(node, ast.Expression):
            return value(node.body)
        if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)) and \
                not isinstance(node.value, bool):
            return float(node.value)
        if isinstance(node, ast.Name) and node.id == "pi":
            return math.pi
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
            return -value(node.operand) if isinstance(node.op, ast.USub) else value(node.operand)
        if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Add, ast.Sub, ast.Mult, ast.Div)):
            a, b = value(node.left), value(node.right)
            return {ast.Add: a + b, ast.Sub: a - b, ast.Mult: a * b}.get(type(node.op)) \
                if not isinstance(node.op, ast.Div) else a / b
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in ("rad", "deg") and \
                len(node.args) == 1 and not node.keywords:
            inner = value(node.args[0])
            return inner if node.func.id == "rad" else math.radians(inner)
        raise ValueError(f"{text!r} is not an angle (numbers, pi, + - * /, rad() or deg())")

    if len(text) > 200:
        raise ValueError("an angle expression of more than 200 characters")
    try:
        return value(ast.parse(text.strip(), mode="eval"))
    except (SyntaxError, ZeroDivisionError, RecursionError):
        raise ValueError(f"{text!r} is not an angle (numbers, pi, + - * /, rad() or deg())") from None


def _angle_loader():
    import re

    import yaml

    class AngleLoader(yaml.SafeLoader):
        """PyYAML's safe loader with rosparam's angles: the ``!degrees`` and ``!radians`` tags, and plain
        ``rad(…)``/``deg(…)`` values."""

    def unwrapped(text: str, call: str) -> str:   # "deg(90)" under !degrees is 90 degrees, as rosparam reads it
        text = text.strip()
        return text[len(call) + 1:-1] if text.startswith(call + "(") and text.endswith(")") else text

    def degrees(loader, node):
        return math.radians(_angle(unwrapped(loader.construct_scalar(node), "deg")))

    def radians(loader, node):
        return _angle(unwrapped(loader.construct_scalar(node), "rad"))

    AngleLoader.add_constructor("!degrees", degrees)
    AngleLoader.add_constructor("!radians", radians)
    AngleLoader.add_implicit_resolver("!radians", re.compile(r"^rad\([^)]*\)$"), ["r"])
    AngleLoader.add_implicit_resolver("!degrees", re.compile(r"^deg\([^)]*\)$"), ["d"])
    return AngleLoader


MAX_YAML_DEPTH = 64          # lists and mappings nested in one another, as in a spec
MAX_YAML_VALUES = 200_000    # values once every alias is expanded, as in a spec


def _bounded(node, memo: dict, depth: int) -> int:
    """How many values the YAML node ``node`` stands for once its aliases are expanded; ParamError past
    :data:`MAX_YAML_DEPTH` levels or :data:`MAX_YAML_VALUES` values (a few lines of aliases can stand for
    billions)."""
    if depth > MAX_YAML_DEPTH:
        raise ParamError(f"the YAML nests more than {MAX_YAML_DEPTH} levels deep")
    if id(node) in memo:
        return memo[id(node)]
    items = node.value if isinstance(node.value, list) else []
    size = 1
    for item in items:
        for child in (item if isinstance(item, tuple) else (item,)):
            size += _bounded(child, memo, depth + 1)
            if size > MAX_YAML_VALUES:
                raise ParamError(f"the YAML stands for more than {MAX_YAML_VALUES:,} values once its aliases are "
                                 "expanded")
    memo[id(node)] = size
    return size


def load_yaml(text: str) -> Any:
    """A rosparam YAML document's value; ParamError (with the YAML's own message) when it does not parse, nests
    or expands past the limits, or holds an angle rosparam could not read."""
    import yaml

    loader = _angle_loader()(text)
    try:
        node = loader.get_single_node()
        if node is None:
            return None
        _bounded(node, {}, 0)
        return loader.construct_document(node)
    except ParamError:
        raise
    except yaml.YAMLError as err:
        raise ParamError(f"not YAML: {' '.join(str(err).split())}") from None
    except RecursionError:
        raise ParamError(f"the YAML nests more than {MAX_YAML_DEPTH} levels deep") from None
    except (ValueError, TypeError, OverflowError) as err:
        raise ParamError(f"not a value rosparam loads: {err}") from None
    finally:
        loader.dispose()


def rosparam_sets(value: Any, ns: str, param: str | None) -> List[Tuple[str, Any]]:
    """What ``<rosparam>`` loading ``value`` sets: ``(full name, value)`` pairs. ``ns`` is the resolved namespace
    (a node's private one inside a ``<node>``); ``param`` the ``param=`` attribute, resolved by the caller or None.
    ParamError for a document that is not a mapping when no ``param`` is given."""
    if param is not None:
        return [(param, value)]
    if value is None:
        return []
    if not isinstance(value, dict):
        raise ParamError("a <rosparam> without param= must hold a YAML mapping (name: value)")
    return [(join_ns(ns, str(key)), item) for key, item in value.items()]


STORABLE = (bool, int, float, str, bytes, list, tuple, dict)   # what the master's XML-RPC carries


def storable(value: Any, budget: list | None = None) -> str | None:
    """Why the master cannot hold ``value`` (None when it can): XML-RPC has no null, no integer past 32 bits, only
    string keys, and none of YAML's dates or sets."""
    budget = [MAX_YAML_VALUES] if budget is None else budget
    budget[0] -= 1
    if budget[0] < 0:
        return f"more than {MAX_YAML_VALUES:,} values"
    if value is None:
        return "a YAML null (the master holds no empty value)"
    if not isinstance(value, STORABLE):
        return f"{value!r} is a {type(value).__name__}, which the master cannot hold (quote it as a string)"
    if isinstance(value, int) and not isinstance(value, bool) and not -XMLRPC_INT <= value < XMLRPC_INT:
        return f"{value} does not fit a 32-bit integer"
    if isinstance(value, dict):
        for key, item in value.items():
            if not isinstance(key, str):
                return f"the key {key!r} is not a string (the master's names are)"
            why = storable(item, budget)
            if why is not None:
                return f"{key}: {why}"
    if isinstance(value, (list, tuple)):
        for item in value:
            why = storable(item, budget)
            if why is not None:
                return why
    return None


def set_value(params: Dict[str, Any], name: str, value: Any) -> None:
    """Set ``name`` in ``params`` (full name → value) as roslaunch does: a mapping is unrolled into one parameter
    per leaf (so two mappings under one name merge, as on the master), and a later value for a name, or for one
    of its parents, wins."""
    if isinstance(value, dict) and value:
        for key, item in value.items():
            set_value(params, join_ns(name, str(key)), item)
        return
    prefix = name.rstrip("/") + "/"
    for key in [k for k in params if k == name or k.startswith(prefix)]:
        del params[key]
    params[name] = value
