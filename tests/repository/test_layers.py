"""The packages' layers: no import of the library or the kit hides in a function.

The two layers themselves (the library ``twolink`` never imports the course
kit ``twolink_course``; no import cycle inside either) are import-linter's
contracts in ``pyproject.toml``, which ``make test`` runs (``lint-imports``).
Here every module of both packages is parsed (``ast``, nothing imported).  An
import under ``if TYPE_CHECKING:`` is for the type checker only and is left
out; any other import of a module of either package must sit at module level,
where import-linter sees it.  (A function-level ``import scipy...`` keeps
``import twolink`` light and is allowed: only the two packages' own modules
are checked.)
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PACKAGES = (ROOT / "twolink", ROOT / "twolink_course")


def _module_name(path: Path) -> str:
    parts = path.relative_to(ROOT).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


MODULES = {
    _module_name(path): path
    for package in PACKAGES
    for path in sorted(package.rglob("*.py"))
}


def _is_type_checking(node: ast.If) -> bool:
    test = node.test
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"
    )


def _targets(module: str, node: ast.Import | ast.ImportFrom) -> list[str]:
    """The modules of the two packages an import statement loads (a name imported from a package may be a module)."""
    is_package = MODULES[module].name == "__init__.py"
    if isinstance(node, ast.Import):
        names = [alias.name for alias in node.names]
    else:
        if node.level:
            base = module.split(".") if is_package else module.split(".")[:-1]
            base = base[: len(base) - (node.level - 1)]
            origin = ".".join(base + ([node.module] if node.module else []))
        else:
            origin = node.module or ""
        names = [origin] + [f"{origin}.{alias.name}" for alias in node.names]
    return [name for name in names if name in MODULES]


def _imports(module: str) -> tuple[set[str], list[tuple[int, str]]]:
    """(module-level imports of the packages' modules, [(line, target)] of function-level ones)."""
    tree = ast.parse(MODULES[module].read_text(encoding="utf-8"))
    top: set[str] = set()
    late: list[tuple[int, str]] = []

    def visit(node: ast.AST, in_function: bool) -> None:
        for child in ast.iter_child_nodes(node):
            if isinstance(child, ast.If) and _is_type_checking(child):
                continue
            if isinstance(child, (ast.Import, ast.ImportFrom)):
                for target in _targets(module, child):
                    if in_function:
                        late.append((child.lineno, target))
                    else:
                        top.add(target)
            visit(
                child,
                in_function
                or isinstance(
                    child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)
                ),
            )

    visit(tree, False)
    # importing a submodule runs its package's __init__ first
    for target in list(top):
        parts = target.split(".")
        top.update(
            ".".join(parts[:i])
            for i in range(1, len(parts))
            if ".".join(parts[:i]) in MODULES
        )
    top.discard(module)
    return top, late


def test_the_walk_sees_both_packages():
    top, _ = _imports("twolink.ik.analytic")
    assert "twolink.ik.result" in top and "twolink.kinematics" in top
    top, _ = _imports("twolink_course.diagrams")
    assert {"twolink_course.plot", "twolink._validate"} <= top


def test_the_walk_finds_a_late_import(tmp_path, monkeypatch):
    path = tmp_path / "late_example.py"
    path.write_text("import numpy\n\n\ndef f():\n    from twolink import dh\n")
    monkeypatch.setitem(MODULES, "twolink_course.late_example", path)
    top, late = _imports("twolink_course.late_example")
    assert top == set() and (5, "twolink.dh") in late


@pytest.mark.parametrize("module", sorted(MODULES))
def test_no_function_level_import_of_a_twolink_module(module):
    _, late = _imports(module)
    assert late == [], (
        f"{module} imports modules of the packages inside functions (line, module): {late}"
    )


def _imported_modules() -> list:
    import importlib

    return [importlib.import_module(name) for name in sorted(MODULES)]


def test_no_attribute_hides_a_module():
    """``twolink.X`` is the module ``twolink/X.py`` (a function of the same name
    would make ``import twolink.X`` hand back the function)."""
    import importlib

    hidden = []
    for module in _imported_modules():
        if "." not in module.__name__:
            continue
        parent_name, short = module.__name__.rsplit(".", 1)
        if getattr(importlib.import_module(parent_name), short) is not module:
            hidden.append(module.__name__)
    assert hidden == []


# The symbolic mirror of a numeric formula keeps its name (``symbolic.dh_matrix`` is
# ``dh.dh_matrix`` with symbols); each source module keeps the names its source used.
SAME_NAME_ALLOWED = ("twolink.symbolic", "twolink_course.sources.")


def test_one_public_name_one_object():
    """A name in two modules' ``__all__`` is the same object re-exported, not two
    different functions that happen to share a name."""
    owners: dict[str, dict[int, str]] = {}
    for module in _imported_modules():
        if module.__name__.startswith(SAME_NAME_ALLOWED):
            continue
        for name in getattr(module, "__all__", ()):
            owners.setdefault(name, {})[id(getattr(module, name))] = module.__name__
    clashes = {name: sorted(by.values()) for name, by in owners.items() if len(by) > 1}
    assert clashes == {}


def test_only_the_cache_module_touches_the_arms_cache():
    """A TwoLinkArm's cache of derived constants is read and written in one place,
    ``twolink._derived``; every other module goes through its functions."""
    import re

    from twolink import _derived

    name = re.escape(_derived.CACHE_ATTRIBUTE)
    # the attribute read on an object (arm._derived) or named in a string ("_derived")
    use = re.compile(rf"\w\.{name}\b|[\"']{name}[\"']")
    touching = [
        module
        for module, path in MODULES.items()
        if module != "twolink._derived" and use.search(path.read_text(encoding="utf-8"))
    ]
    assert touching == []


def test_the_cache_is_filled_once_and_ignored_by_equality():
    from twolink import TwoLinkArm, _derived, dynamics, ik

    arm, twin = (
        TwoLinkArm(l1=2.0, l2=1.0, m1=1.0, m2=1.0),
        TwoLinkArm(2.0, 1.0, 1.0, 1.0),
    )
    ik.closed_form(arm, [2.0, 1.0])
    dynamics.mass_matrix(arm, [0.3, 0.4])
    cache = getattr(arm, _derived.CACHE_ATTRIBUTE)
    assert set(cache) == {"closed_form", "dynamics"}
    first = dict(cache)
    ik.closed_form(arm, [1.0, 2.0])
    dynamics.mass_matrix(arm, [0.5, 0.1])
    assert all(cache[key] is first[key] for key in first)
    assert arm == twin and hash(arm) == hash(twin) and repr(arm) == repr(twin)
    assert _derived.has_cache(arm) and not _derived.has_cache(object())
