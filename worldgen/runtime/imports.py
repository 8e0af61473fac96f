"""What a student's node imports, read from its source with :mod:`ast` (the node is never run).

:func:`read_node` gives every absolute import with its line, as :class:`Import`:

* ``import a.b`` and ``from a.b import c`` both record module ``a.b``; what has to be installed is its top-level
  name ``a`` (:attr:`Import.top`).
* **Optional** imports are not gaps: the node has said what to do without them. An import is optional when it sits
  in the ``try`` body of a ``try`` with a handler for ``ImportError``, ``ModuleNotFoundError``, ``Exception``,
  ``BaseException`` or a bare ``except`` — unless that handler gives up (re-raises, ``sys.exit()``, ``exit()``)
  — or in such a handler (the fallback of ``try: import cPickle … except ImportError: import pickle``), or
  under an ``if`` on the Python version (``sys.version_info``, ``six.PY2``) or ``TYPE_CHECKING``.
* Imports **inside functions and methods count**: they run when the function is called (a scan callback that
  imports numpy crashes on the first scan, mid-run); :attr:`Import.function` names the function.
* ``from __future__ import …`` and relative imports (``from . import x``: a script run as a file has no
  package) are skipped; so are dynamic ones (``importlib.import_module(name)``), which cannot be read.

A file that does not parse is no crash: :attr:`NodeSource.error` holds the line and Python's message (a Python 2
``print "x"`` is the usual one: ROS Noetic runs nodes with Python 3), and its imports are read line by line instead
— only those at the start of a line count as needed (indented ones may be guarded), so that fixing the syntax is
not followed by a surprise missing module.
"""

from __future__ import annotations

import ast
import re
from dataclasses import dataclass, field
from pathlib import Path

GUARDS = frozenset({"ImportError", "ModuleNotFoundError", "Exception", "BaseException"})
VERSION_NAMES = frozenset({"version_info", "PY2", "PY3", "PY34", "TYPE_CHECKING"})   # and sys.version
EXITS = frozenset({"exit", "quit", "_exit", "signal_shutdown"})


@dataclass(frozen=True)
class Import:
    """One import statement's module: ``module`` (dotted), the ``line`` it is on, whether the node runs without
    it (``optional``), and the function it is inside (``""`` at module level)."""

    module: str
    line: int
    optional: bool = False
    function: str = ""

    @property
    def top(self) -> str:
        """The top-level name that has to be importable: ``tf`` for ``tf.transformations``."""
        return self.module.split(".", 1)[0]


@dataclass
class NodeSource:
    """A node file's imports in source order, or, when it does not parse, ``error`` as (line, message)."""

    path: Path
    imports: list[Import] = field(default_factory=list)
    error: tuple[int, str] | None = None

    def needed(self) -> dict[str, Import]:
        """Each top-level module the node cannot run without, at its first required import."""
        found: dict[str, Import] = {}
        for item in self.imports:
            if not item.optional and item.top not in found:
                found[item.top] = item
        return found


def read_node(path: str | Path) -> NodeSource:
    """The imports of the file at ``path`` (see the module docstring). OSError when it cannot be read."""
    path = Path(path)
    return read_source(path.read_bytes(), path)


def read_source(source: str | bytes, path: str | Path = "<node>") -> NodeSource:
    """The imports of ``source`` (text, or bytes with an optional coding cookie)."""
    node = NodeSource(Path(path))
    try:
        tree = ast.parse(source, filename=str(path))
    except SyntaxError as err:
        node.error = (err.lineno or 1, _syntax_message(err))
        node.imports = _scan_lines(source)
        return node
    except ValueError as err:   # Python 3.8: "source code string cannot contain null bytes"
        node.error = (1, str(err))
        return node
    _Walker(node.imports).visit(tree)
    return node


_IMPORT_LINE = re.compile(r"^(\s*)(?:import\s+([\w.]+(?:\s*,\s*[\w.]+)*)|from\s+([\w.]+)\s+import\b)")


def _scan_lines(source: str | bytes) -> list[Import]:
    """The imports of a file that does not parse, line by line (see the module docstring)."""
    text = source.decode("utf-8", errors="replace") if isinstance(source, bytes) else source
    found = []
    for number, line in enumerate(text.splitlines(), 1):
        match = _IMPORT_LINE.match(line)
        if match is None:
            continue
        modules = [m.strip() for m in match.group(2).split(",")] if match.group(2) else [match.group(3)]
        for module in modules:
            if module != "__future__":
                found.append(Import(module.split(" as ")[0], number, optional=bool(match.group(1))))
    return found


def _syntax_message(err: SyntaxError) -> str:
    message = err.msg or "invalid syntax"
    text = (err.text or "").strip()
    if text.startswith(("print ", "print\t", "exec ")) and "(...)" not in message and "print(" not in message:
        message += " (Python 2's print statement: Python 3 needs print(...))"
    elif text.startswith("except ") and "," in text and " as " not in text:
        message += " (Python 2's except E, e: Python 3 needs except E as e)"
    return message


def _names(node: ast.expr | None) -> set[str]:
    """The plain and attribute names in an exception type expression (``(ImportError, errors.Bad)``)."""
    if node is None:
        return set()
    return {n.id for n in ast.walk(node) if isinstance(n, ast.Name)} | \
        {n.attr for n in ast.walk(node) if isinstance(n, ast.Attribute)}


def _on_version(test: ast.expr) -> bool:
    """Whether an ``if`` test asks which Python this is (``sys.version_info``, ``sys.version``, ``six.PY2``) or
    whether a type checker reads the file (``TYPE_CHECKING``)."""
    sys_version = any(isinstance(n, ast.Attribute) and n.attr == "version" and isinstance(n.value, ast.Name)
                      and n.value.id == "sys" for n in ast.walk(test))
    return sys_version or bool(_names(test) & VERSION_NAMES)


def _gives_up(handler: ast.ExceptHandler) -> bool:
    """Whether an ``except`` body stops the node: a ``raise`` or an exit call among its statements."""
    for statement in handler.body:
        if isinstance(statement, ast.Raise):
            return True
        if isinstance(statement, ast.Expr) and isinstance(statement.value, ast.Call):
            func = statement.value.func
            name = func.id if isinstance(func, ast.Name) else func.attr if isinstance(func, ast.Attribute) else ""
            if name in EXITS:
                return True
    return False


def _guards(handler: ast.ExceptHandler) -> bool:
    return (handler.type is None or bool(_names(handler.type) & GUARDS)) and not _gives_up(handler)


class _Walker(ast.NodeVisitor):
    """Collects imports, keeping track of optional regions and the enclosing function."""

    def __init__(self, out: list[Import]):
        self.out = out
        self.optional = 0
        self.scopes: list[str] = []   # enclosing classes and functions, outermost first
        self.depth = 0                # how many of them are functions

    def _add(self, module: str, line: int) -> None:
        self.out.append(Import(module, line, self.optional > 0, ".".join(self.scopes) if self.depth else ""))

    def visit_Import(self, node: ast.Import) -> None:   # noqa: N802  (ast.NodeVisitor's naming)
        for alias in node.names:
            self._add(alias.name, node.lineno)

    def visit_ImportFrom(self, node: ast.ImportFrom) -> None:   # noqa: N802
        if node.level or not node.module or node.module == "__future__":
            return
        self._add(node.module, node.lineno)

    def _function(self, node) -> None:
        for item in node.decorator_list + [node.args]:
            self.visit(item)
        self.scopes.append(node.name)
        self.depth += 1
        for statement in node.body:
            self.visit(statement)
        self.depth -= 1
        self.scopes.pop()

    visit_FunctionDef = visit_AsyncFunctionDef = _function   # noqa: N815

    def visit_ClassDef(self, node: ast.ClassDef) -> None:   # noqa: N802
        self.scopes.append(node.name)
        self.generic_visit(node)
        self.scopes.pop()

    def _optional(self, statements) -> None:
        self.optional += 1
        for statement in statements:
            self.visit(statement)
        self.optional -= 1

    def visit_Try(self, node) -> None:   # noqa: N802
        guarded = [h for h in node.handlers if _guards(h)]
        if guarded:
            self._optional(node.body)
        else:
            for statement in node.body:
                self.visit(statement)
        for handler in node.handlers:   # a guard's fallback is optional too; other handlers run as written
            if handler in guarded:
                self._optional(handler.body)
            else:
                self.visit(handler)
        for statement in node.orelse + node.finalbody:
            self.visit(statement)

    visit_TryStar = visit_Try   # noqa: N815  (Python 3.11's except*)

    def visit_If(self, node: ast.If) -> None:   # noqa: N802
        if _on_version(node.test):
            self._optional(node.body + node.orelse)
        else:
            self.generic_visit(node)
