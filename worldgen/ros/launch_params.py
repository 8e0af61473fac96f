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

from .launch import join_ns

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


def _angle_loader():
    import yaml

    class AngleLoader(yaml.SafeLoader):
        """PyYAML's safe loader with rosparam's ``!degrees`` and ``!radians`` tags."""

    def degrees(loader, node):
        return math.radians(float(loader.construct_scalar(node)))

    def radians(loader, node):
        return float(loader.construct_scalar(node))

    AngleLoader.add_constructor("!degrees", degrees)
    AngleLoader.add_constructor("!radians", radians)
    return AngleLoader


def load_yaml(text: str) -> Any:
    """A rosparam YAML document's value; ParamError (with the YAML's own message) when it does not parse."""
    import yaml

    try:
        return yaml.load(text, Loader=_angle_loader())   # noqa: S506 - a SafeLoader subclass
    except yaml.YAMLError as err:
        raise ParamError(f"not YAML: {' '.join(str(err).split())}") from None


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


def storable(value: Any) -> str | None:
    """Why the master cannot hold ``value`` (None when it can): XML-RPC has no null, no integer past 32 bits, and
    only string keys."""
    if value is None:
        return "a YAML null (the master holds no empty value)"
    if isinstance(value, bool):
        return None
    if isinstance(value, int) and not -XMLRPC_INT <= value < XMLRPC_INT:
        return f"{value} does not fit a 32-bit integer"
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if isinstance(value, dict):
        for key, item in value.items():
            why = storable(item)
            if why is not None:
                return f"{key}: {why}"
    if isinstance(value, (list, tuple)):
        for item in value:
            why = storable(item)
            if why is not None:
                return why
    return None


def set_value(params: Dict[str, Any], name: str, value: Any) -> None:
    """Set ``name`` in ``params`` (full name → value) as the master would: a mapping replaces what was under the
    name, and a later value for a name, or for one of its parents, wins."""
    prefix = name.rstrip("/") + "/"
    for key in [k for k in params if k == name or k.startswith(prefix)]:
        del params[key]
    params[name] = value
