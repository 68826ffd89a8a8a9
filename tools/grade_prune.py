"""Only what the answers depend on: a graded notebook cut to the statements its answers need.

The grader reads a notebook's answers, never its figures, videos or
derivations.  :func:`needed` finds, by the names statements bind and read
(Python's own parser, after IPython's transformations of magics), the
top-level statements the *roots* depend on: the answer, inputs, check and
probe cells, whole; every other cell keeps only the statements that bind a
name a needed statement reads, found backwards to a fixed point (a function
defined early may call one defined later).

A statement binds the names it assigns, imports, defines (``def``,
``class``), deletes, changes in place (``x[0] = ...``, ``x.a = ...``,
``x += ...``) or calls a method of for its effect (a statement
``q.sort()``; a module's functions are not taken to change the module, but
a ``seed``); a statement of a cell the student wrote or changed also binds
every name whose methods it calls or that it passes to a call
(``helper(q)`` may change ``q``: the course's own cells are trusted not to).  A plain assignment, import or definition at a
statement's top level surely rebinds its names, so an earlier binding of
them is not needed by what comes after; one in a branch, a loop or a
handler may not.  A name read in a function's body is read whenever the
function is called: every binding of it is kept.  A needed statement of a
cell the student wrote or changed that reads the namespace by other means
(``globals()``, ``exec``, ``eval``, ``get_ipython``, ``In``, ``Out``,
``_``...) keeps the whole notebook.

>>> cells = ["import numpy as np\\nimport matplotlib.pyplot as plt",
...          "fig = plt.figure()\\nfig.suptitle('the zeros')",
...          "q = np.zeros(2)\\nlabel = 'zeros'",
...          "answer = q + 1"]
>>> needed(cells, roots={3}, names=set(), release=set(cells))
['import numpy as np', '', 'q = np.zeros(2)', 'answer = q + 1']
"""

from __future__ import annotations

import ast
import symtable
import threading
from collections.abc import Collection, Sequence

from IPython.core.inputtransformer2 import TransformerManager

#: Names whose use reads or changes the namespace in ways names cannot follow.
DYNAMIC = frozenset(
    {
        "globals", "locals", "vars", "exec", "eval", "get_ipython", "__builtins__",
        "__import__", "In", "Out", "_ih", "_oh", "_dh", "_i", "_ii", "_iii",
        "_", "__", "___", "__name__",
    }
)  # fmt: skip
#: Method names that change a module's hidden state (a random generator's seed).
STATEFUL = frozenset({"seed", "set_state", "set_printoptions"})


class Unit:
    """One top-level statement: its lines; the names it binds (``full``: surely rebinds, so an
    earlier binding is not needed after it), reads now, and reads later (in function bodies)."""

    def __init__(
        self,
        lines: tuple[int, int],
        binds: set[str],
        full: set[str],
        reads: set[str],
        late: set[str],
    ) -> None:
        self.lines = lines
        self.binds = binds
        self.full = full
        self.reads = reads
        self.late = late


def _root(node: ast.AST) -> str | None:
    """The name at the root of ``a.b[c].d``, or None."""
    while isinstance(node, (ast.Attribute, ast.Subscript, ast.Starred)):
        node = node.value
    return node.id if isinstance(node, ast.Name) else None


class _Names(ast.NodeVisitor):
    """The names a top-level statement binds (top-level scope only) and reads (anywhere in it)."""

    def __init__(self, modules: Collection[str], strict: bool) -> None:
        self.binds: set[str] = set()
        self.reads: set[str] = set()
        self.modules = modules
        self.strict = strict
        self.depth = 0  # inside a function, class body, lambda or comprehension

    def _bind(self, name: str | None) -> None:
        if name is not None and self.depth == 0:
            self.binds.add(name)

    def visit_Name(self, node: ast.Name) -> None:
        if isinstance(node.ctx, ast.Load):
            if not self.depth:  # in a nested scope: see _scoped_reads
                self.reads.add(node.id)
        else:
            self._bind(node.id)

    def _target(self, node: ast.AST) -> None:
        if isinstance(node, (ast.Attribute, ast.Subscript)):
            self._bind(_root(node))  # changed in place
        self.visit(node)

    def visit_Assign(self, node: ast.Assign) -> None:
        for target in node.targets:
            self._target(target)
        self.visit(node.value)

    def visit_AugAssign(self, node: ast.AugAssign) -> None:
        self._bind(_root(node.target))
        self.reads.add(_root(node.target) or "")  # x += 1 reads x
        self._target(node.target)
        self.visit(node.value)

    def visit_AnnAssign(self, node: ast.AnnAssign) -> None:
        self._target(node.target)
        if node.value is not None:
            self.visit(node.value)

    def visit_Delete(self, node: ast.Delete) -> None:
        for target in node.targets:
            self._bind(_root(target))
            self.visit(target)

    def visit_Import(self, node: ast.Import) -> None:
        for alias in node.names:
            self._bind(alias.asname or alias.name.split(".")[0])

    def visit_ImportFrom(self, node: ast.ImportFrom) -> None:
        for alias in node.names:
            self._bind("*" if alias.name == "*" else alias.asname or alias.name)

    def _scope(self, node: ast.AST, name: str | None = None) -> None:
        self._bind(name)
        for decorator in getattr(node, "decorator_list", []):
            self.visit(decorator)
        self.depth += 1
        for child in ast.iter_child_nodes(node):
            if child not in getattr(node, "decorator_list", []):
                self.visit(child)
        self.depth -= 1

    def visit_FunctionDef(self, node: ast.FunctionDef) -> None:
        self._scope(node, node.name)

    def visit_AsyncFunctionDef(self, node: ast.AsyncFunctionDef) -> None:
        self._scope(node, node.name)

    def visit_ClassDef(self, node: ast.ClassDef) -> None:
        self._scope(node, node.name)

    def visit_Lambda(self, node: ast.Lambda) -> None:
        self._scope(node)

    visit_ListComp = visit_SetComp = visit_DictComp = visit_GeneratorExp = visit_Lambda

    def visit_Call(self, node: ast.Call) -> None:
        function = node.func
        if isinstance(function, ast.Attribute):
            owner = _root(function)
            if function.attr in STATEFUL or (
                self.strict and owner is not None and owner not in self.modules
            ):
                self._bind(owner)  # a method may change its object
        if self.strict:
            for argument in [*node.args, *(k.value for k in node.keywords)]:
                name = _root(argument)
                if name is not None and name not in self.modules:
                    self._bind(name)  # a function may change what it is given
        self.generic_visit(node)

    def visit_Expr(self, node: ast.Expr) -> None:
        call = node.value
        if isinstance(call, ast.Call) and isinstance(call.func, ast.Attribute):
            owner = _root(call.func)
            if owner is not None and owner not in self.modules:
                self._bind(owner)  # a method called for its effect changes its object
        self.generic_visit(node)

    def visit_Global(self, node: ast.Global) -> None:
        for name in node.names:
            self.binds.add(name)


_COMPREHENSIONS = ("listcomp", "setcomp", "dictcomp", "genexpr")


def _scoped_reads(source: str) -> tuple[set[str], set[str]]:
    """The module-level names a statement's nested scopes read: now (comprehensions, class
    bodies) and later (function and lambda bodies, whenever called), by Python's own symbol tables."""
    now: set[str] = set()
    late: set[str] = set()

    def walk(table: symtable.SymbolTable, deferred: bool) -> None:
        for child in table.get_children():
            called_later = deferred or (
                child.get_type() == "function"
                and child.get_name() not in _COMPREHENSIONS
            )
            names = {
                symbol.get_name()
                for symbol in child.get_symbols()
                if symbol.is_referenced() and symbol.is_global()
            }
            (late if called_later else now).update(names)
            walk(child, called_later)

    walk(symtable.symtable(source, "<cell>", "exec"), False)
    return now, late


def _full(node: ast.stmt) -> set[str]:
    """The names a top-level statement surely rebinds (not in a branch, a loop or a handler)."""
    if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
        return {node.name}
    if isinstance(node, ast.Import):
        return {a.asname or a.name.split(".")[0] for a in node.names}
    if isinstance(node, ast.ImportFrom):
        return {a.asname or a.name for a in node.names if a.name != "*"}
    targets: list[ast.expr] = []
    if isinstance(node, ast.Assign):
        targets = list(node.targets)
    elif isinstance(node, ast.AnnAssign) and node.value is not None:
        targets = [node.target]
    found: set[str] = set()
    while targets:
        target = targets.pop()
        if isinstance(target, ast.Name):
            found.add(target.id)
        elif isinstance(target, (ast.Tuple, ast.List)):
            targets += target.elts
        elif isinstance(target, ast.Starred):
            targets.append(target.value)
    return found


_TRANSFORMER = TransformerManager()


def parse(source: str) -> ast.Module | None:
    """A cell's source parsed as Python after IPython's transformations (magics), or None."""
    try:
        return ast.parse(_TRANSFORMER.transform_cell(source))
    except (SyntaxError, ValueError):
        return None


def imported(cells: Sequence[str]) -> set[str]:
    """The names any cell binds by ``import`` (modules: calling them changes no object of the notebook)."""
    found: set[str] = set()
    for source in cells:
        tree = parse(source)
        for node in tree.body if tree else []:
            if isinstance(node, ast.Import):
                found |= {a.asname or a.name.split(".")[0] for a in node.names}
            elif isinstance(node, ast.ImportFrom):
                found |= {a.asname or a.name for a in node.names}
    return found


def units(source: str, modules: Collection[str], strict: bool) -> list[Unit] | None:
    """The top-level statements of a cell (None: it does not parse)."""
    tree = parse(source)
    if tree is None:
        return None
    found = []
    for node in tree.body:
        names = _Names(modules, strict)
        names.visit(node)
        now, late = _scoped_reads(ast.unparse(node))
        first = min(
            [node.lineno, *(d.lineno for d in getattr(node, "decorator_list", []))]
        )
        found.append(
            Unit(
                (first, node.end_lineno or node.lineno),
                names.binds,
                _full(node) & names.binds,
                names.reads | now,
                late,
            )
        )
    return found


#: make grade prunes notebooks in several threads (JOBS); CPython 3.11's AST conversion is
#: not safe across threads ("SystemError: AST constructor recursion depth mismatch",
#: CPython issue gh-106905), so one notebook is pruned at a time: milliseconds beside
#: the seconds its kernel runs.
_AST_LOCK = threading.Lock()


def needed(
    cells: Sequence[str],
    roots: Collection[int],
    names: Collection[str],
    release: Collection[str],
) -> list[str]:
    """Each cell's source cut to what ``roots`` (cell indices, kept whole) and ``names`` (read by
    the grader at the end) depend on; ``release``: the sources of the course's own cells and
    the grader's (their reads of the namespace are known).  A cell with nothing needed
    becomes ``""``.  One call at a time (``_AST_LOCK``)."""
    with _AST_LOCK:
        return _needed(cells, roots, names, release)


def _needed(
    cells: Sequence[str],
    roots: Collection[int],
    names: Collection[str],
    release: Collection[str],
) -> list[str]:
    """:func:`needed`, under the lock."""
    modules = imported(cells)
    split = [units(source, modules, strict=source not in release) for source in cells]
    late: set[str] = set()  # read by a needed function's body: whenever it is called
    keep: set[tuple[int, int]] = set()
    while True:
        before = (len(late), len(keep))
        wanted = set(names)
        for index in range(len(cells) - 1, -1, -1):
            found = split[index]
            if found is None:
                continue
            for position in range(len(found) - 1, -1, -1):
                unit = found[position]
                if index in roots or unit.binds & (wanted | late) or "*" in unit.binds:
                    keep.add((index, position))
                    wanted = (wanted - unit.full) | unit.reads
                    late |= unit.late
        if (len(late), len(keep)) == before:
            break
    if any(
        (split[index][position].reads | split[index][position].late)  # type: ignore[index]
        & DYNAMIC
        for index, position in keep
        if cells[index] not in release
    ):  # a student's needed statement reads the namespace by other means: everything runs
        return list(cells)
    cut = []
    for index, source in enumerate(cells):
        found = split[index]
        if index in roots:
            cut.append(source)
            continue
        if found is None:
            cut.append("")  # it would only raise a SyntaxError
            continue
        lines = _TRANSFORMER.transform_cell(source).splitlines()
        kept = sorted(
            {
                line
                for position, unit in enumerate(found)
                if (index, position) in keep
                for line in range(unit.lines[0], unit.lines[1] + 1)
            }
        )
        cut.append("\n".join(lines[line - 1] for line in kept))
    return cut
