"""YAML text composed into line-numbered nodes.

The text is composed into YAML nodes (not constructed straight to Python) so that every value keeps the line it
came from; each check of the spec reader (:mod:`worldgen.spec.values` and the modules reading a spec's parts) then
names the file and line of the value to change.
"""

from __future__ import annotations

import yaml

from ..core.errors import SpecError

MAX_DEPTH = 64            # lists and mappings nested in one another
MAX_VALUES = 200_000      # values once every alias (*name) and merge key (<<:) is expanded
FAST_DEPTH = 200          # libyaml's composer recurses without a check: deeper text goes to the pure parser


class Node:
    """A YAML value with its line (1-based): ``value`` is a dict of key → Node, a list of Node, or a scalar."""

    __slots__ = ("value", "line", "key_lines", "style")

    def __init__(self, value, line: int, key_lines: dict[str, int] | None = None, style: str | None = None):
        self.value, self.line, self.key_lines, self.style = value, line, key_lines or {}, style


def compose(text: str, source: str | None) -> Node | None:
    """The spec text as Nodes. libyaml's parser (``yaml.CSafeLoader``, when PyYAML was built with it) is several
    times faster on big specs; text it refuses is parsed again by the pure-Python parser, whose messages and
    marks the errors below are worded for, so an error reads the same (same line) with or without libyaml."""
    fast = getattr(yaml, "CSafeLoader", None)
    if fast is not None and _depth_bound(text) > FAST_DEPTH:
        fast = None   # the pure parser's recursion is checked (RecursionError, below); libyaml's is not
    try:
        if fast is not None:
            try:
                return _nodes(fast(text), source)
            except yaml.YAMLError:
                pass   # reported by the pure-Python parser, below
        return _nodes(yaml.SafeLoader(text), source)
    except yaml.MarkedYAMLError as err:
        mark = err.problem_mark or err.context_mark
        problem = err.problem or "the text is not valid YAML"
        hint = "check the indentation and brackets on this line and the one above"
        if "\\t" in problem or "\t" in problem:
            hint = "indent with spaces, not tabs"
        elif "another document" in problem:
            hint = "a spec is one YAML document: remove this '---' and what follows, or put it in its own file"
        # PyYAML words some errors as context then problem ("expected a single document … but found another")
        parts = (err.context, problem) if problem.startswith("but ") else (problem, err.context)
        raise SpecError(f"invalid YAML: {' '.join(p for p in parts if p)}", path=source,
                        line=mark.line + 1 if mark else None, hint=hint) from None
    except yaml.YAMLError as err:
        raise SpecError(f"invalid YAML: {err}", path=source) from None
    except RecursionError:
        raise SpecError(f"lists or blocks are nested too deeply (more than {MAX_DEPTH} levels)", path=source,
                        hint="a spec nests a few levels at most; check the brackets") from None


def _depth_bound(text: str) -> int:
    """At least as deep as the text's nesting can be: the deepest run of open brackets plus the widest
    indentation (dashes included). Cheap: no parsing."""
    import re

    import numpy as np

    data = np.frombuffer(text.encode("utf-8", "replace"), dtype=np.uint8)
    opened = np.isin(data, (ord("["), ord("{"))).astype(np.int64) - np.isin(data, (ord("]"), ord("}")))
    brackets = int(np.cumsum(opened).max()) if len(data) else 0
    indent = max((len(m) for m in re.findall(r"(?m)^[ \t?:-]*", text)), default=0)
    return brackets + indent


def _expanded_size(node, memo: dict, depth: int, source) -> int:
    """How many values ``node`` stands for once its aliases and merge keys are expanded (each alias counted
    every time it is used); SpecError past MAX_DEPTH levels or MAX_VALUES values."""
    key = id(node)
    if key in memo:
        memo["aliased"] = True   # a node met again: an alias (or a merge key) uses it
        if memo[key] is None:
            raise SpecError("a YAML alias refers to itself", path=source, line=node.start_mark.line + 1,
                            hint="remove the recursive *alias")
        return memo[key]
    if depth > MAX_DEPTH:
        raise SpecError(f"lists or blocks are nested too deeply (more than {MAX_DEPTH} levels)", path=source,
                        line=node.start_mark.line + 1, hint="a spec nests a few levels at most; check the brackets")
    memo[key] = None
    size = 1
    if isinstance(node, yaml.SequenceNode):
        size += sum(_expanded_size(child, memo, depth + 1, source) for child in node.value)
    elif isinstance(node, yaml.MappingNode):
        for k, v in node.value:
            size += _expanded_size(k, memo, depth + 1, source) + _expanded_size(v, memo, depth + 1, source)
    if size > MAX_VALUES and memo.get("aliased"):
        raise SpecError(f"the YAML stands for more than {MAX_VALUES:,} values once its aliases (*name) and merge "
                        "keys (<<:) are expanded", path=source, line=node.start_mark.line + 1,
                        hint="write the values out, or use fewer nested aliases (see Limits in the README)")
    if size > MAX_VALUES:
        raise SpecError(f"the YAML holds more than {MAX_VALUES:,} values (every item of its lists and mappings), "
                        "more than worldgen reads from one spec", path=source, line=node.start_mark.line + 1,
                        hint="a floorplan needs a few hundred; draw a big plan as a grid (grid: or a .txt) or a "
                             "map (map:), see Limits in the README")
    memo[key] = size
    return size


def _nodes(loader, source: str | None) -> Node | None:
    """The single document ``loader`` reads, as Nodes (None when the text holds none)."""
    try:
        root = loader.get_single_node()
        if root is not None:
            _expanded_size(root, {}, 0, source)
        return None if root is None else _convert(root, loader, {}, set(), source)
    finally:
        loader.dispose()


def _convert(node, loader, memo: dict, active: set, source) -> Node:
    """YAML node → Node. Aliases share one converted value; a recursive alias is refused."""
    if id(node) in memo:
        return memo[id(node)]
    line = node.start_mark.line + 1
    if id(node) in active:
        raise SpecError("a YAML alias refers to itself", path=source, line=line, hint="remove the recursive *alias")
    if isinstance(node, yaml.ScalarNode):
        out = Node(_scalar(node, loader, line, source), line, style=node.style or None)   # libyaml: '' for plain
    elif isinstance(node, yaml.SequenceNode):
        active.add(id(node))
        out = Node([_convert(child, loader, memo, active, source) for child in node.value], line)
        active.discard(id(node))
    else:
        own = {id(k) for k, _ in node.value}
        loader.flatten_mapping(node)   # applies YAML merge keys (<<: *defaults): merged pairs come first
        active.add(id(node))
        values, lines, merged = {}, {}, set()
        for key_node, value_node in node.value:
            key_line = key_node.start_mark.line + 1
            if not isinstance(key_node, yaml.ScalarNode):
                raise SpecError("a key must be a plain word", path=source, line=key_line,
                                hint="write keys like `name:` or `walls:`")
            key = str(key_node.value)
            if id(key_node) not in own:
                merged.add(key)
            elif key in values and key not in merged:
                raise SpecError(f"key '{key}' is given twice in the same block", path=source, line=key_line,
                                hint=f"keep one; the first is on line {lines[key]}")
            else:
                merged.discard(key)   # the block's own value overrides the merged one; a third is a duplicate
            values[key] = _convert(value_node, loader, memo, active, source)
            lines[key] = key_line
        active.discard(id(node))
        out = Node(values, line, lines)
    memo[id(node)] = out
    return out


def _scalar(node, loader, line: int, source):
    """A scalar's value; SpecError for one its tag cannot make (``!!int abc``, a date like 2001-13-45)."""
    try:
        return loader.construct_object(node)
    except yaml.YAMLError:
        raise
    except (ValueError, TypeError, OverflowError, ArithmeticError) as err:
        tag = node.tag.rsplit(":", 1)[-1] if node.tag else "value"
        raise SpecError(f"'{node.value}' is not a valid {tag} ({err})", path=source, line=line,
                        hint="quote it to keep it as text, or write a valid value") from None
