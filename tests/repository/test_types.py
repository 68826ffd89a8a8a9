"""Typing of the package: make test runs mypy, every public function is annotated, the typed marker ships.

Also the one rule on private names: no module reaches into another module's
``_private`` names (``twolink._validate`` and ``twolink._optional`` are private
modules whose public names are the package's internal API).

The walks use :mod:`ast` on the source files, so a function added later is
checked too, and nothing is imported (course-only dependencies need not be
installed).
"""

from __future__ import annotations

import ast
import pathlib
import sys
import tomllib
from collections.abc import Iterator

ROOT = pathlib.Path(__file__).resolve().parents[2]
PACKAGE = ROOT / "twolink"
#: The library and the course kit: both typed, both walked.
PACKAGES = (PACKAGE, ROOT / "twolink_course")

#: Private modules whose public names the other modules may import.
INTERNAL_API_MODULES = {"twolink._validate", "twolink._optional"}

#: Dunder methods that are part of a class's public interface (the others are Python's protocol).
PUBLIC_DUNDERS = {"__init__", "__call__"}


def _module_name(path: pathlib.Path) -> str:
    parts = path.relative_to(ROOT).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _source_files() -> list[pathlib.Path]:
    return sorted(path for package in PACKAGES for path in package.rglob("*.py"))


def _is_public_module(path: pathlib.Path) -> bool:
    """No part of the path starts with ``_``, except the file name ``__init__.py``."""
    parts = path.relative_to(ROOT).parts
    return not any(part.startswith("_") for part in parts[:-1]) and (
        parts[-1] == "__init__.py" or not parts[-1].startswith("_")
    )


def _is_private(name: str) -> bool:
    """``_name`` is private; ``__dunder__`` names are not."""
    return name.startswith("_") and not (name.startswith("__") and name.endswith("__"))


FunctionNode = ast.FunctionDef | ast.AsyncFunctionDef


def _definitions(
    body: list[ast.stmt], prefix: str = ""
) -> Iterator[tuple[str, FunctionNode, bool]]:
    """``(qualified name, node, is_method)`` of the public functions and methods in ``body``.

    Looks through ``if``/``try``/``with`` blocks, into public classes (nested
    ones too), never into function bodies.
    """
    for node in body:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            method = bool(prefix)
            if not _is_private(node.name) and not (
                node.name.startswith("__") and node.name not in PUBLIC_DUNDERS
            ):
                yield prefix + node.name, node, method
        elif isinstance(node, ast.ClassDef):
            if not node.name.startswith("_"):
                yield from _definitions(node.body, f"{prefix}{node.name}.")
        elif isinstance(node, (ast.If, ast.Try)):
            blocks = [node.body, node.orelse] + (
                [node.finalbody] + [h.body for h in node.handlers]
                if isinstance(node, ast.Try)
                else []
            )
            for block in blocks:
                yield from _definitions(block, prefix)
        elif isinstance(node, ast.With):
            yield from _definitions(node.body, prefix)


def _missing_annotations(node: FunctionNode, method: bool) -> list[str]:
    """What ``node`` leaves unannotated: parameter names, and ``return``."""
    arguments = node.args
    parameters = [*arguments.posonlyargs, *arguments.args, *arguments.kwonlyargs]
    parameters += [
        argument
        for argument in (arguments.vararg, arguments.kwarg)
        if argument is not None
    ]
    is_static = any(
        isinstance(d, ast.Name) and d.id == "staticmethod" for d in node.decorator_list
    )
    missing = []
    for index, parameter in enumerate(parameters):
        if method and not is_static and index == 0 and parameter.arg in ("self", "cls"):
            continue
        if parameter.annotation is None:
            missing.append(parameter.arg)
    if node.returns is None and node.name != "__init__":
        missing.append("return")
    return missing


def public_functions() -> dict[str, list[str]]:
    """``{"module:qualified.name": [unannotated parameters and "return"]}`` for every public function."""
    found = {}
    for path in _source_files():
        if not _is_public_module(path):
            continue
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
        for name, node, method in _definitions(tree.body):
            found[f"{_module_name(path)}:{name}"] = _missing_annotations(node, method)
    return found


def test_mypy_checks_both_packages():
    """``make test`` runs mypy once, as a command (tests/repository/test_style.py), on both packages."""
    files = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))[
        "tool"
    ]["mypy"]["files"]
    assert set(files) == {package.name for package in PACKAGES}


def test_the_walk_finds_the_public_functions():
    found = public_functions()
    assert "twolink.arm:TwoLinkArm.fk" in found
    assert (
        "twolink.arm:TwoLinkArm.__init__" not in found
    )  # a dataclass: no __init__ in the source
    assert "twolink.kinematics:fk" in found
    assert "twolink_course.exercises.judging:judge" in found  # in a subpackage
    assert not any(
        name.startswith("twolink._validate:") for name in found
    )  # private module
    assert "twolink.controllers:JointPD.__call__" in found
    qualified_parts = [part for name in found for part in name.split(":")[1].split(".")]
    assert not [
        part
        for part in qualified_parts
        if part.startswith("_") and part not in PUBLIC_DUNDERS
    ]


def test_every_public_function_is_fully_annotated():
    """Every parameter (but ``self``/``cls``) and the return (but of ``__init__``) of every public function."""
    found = public_functions()
    missing = {name: gaps for name, gaps in found.items() if gaps}
    lines = [f"{name}: {', '.join(gaps)}" for name, gaps in sorted(missing.items())]
    assert not missing, (
        f"{len(missing)} of {len(found)} public functions lack annotations:\n"
        + "\n".join(lines)
    )


def test_the_typed_marker_ships_in_the_wheel():
    """PEP 561: each package's py.typed exists and is package data, so users' type checkers read the annotations."""
    pyproject = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    setuptools = pyproject["tool"]["setuptools"]
    for package in PACKAGES:
        assert (package / "py.typed").is_file()
        assert "py.typed" in setuptools["package-data"][package.name]
        assert package.name in setuptools["packages"]["find"]["include"]


# ----------------------------------------------------------------------------- private names


def _resolve(module: str, is_package: bool, level: int, target: str | None) -> str:
    """The absolute name of ``from <level dots><target> import ...`` written in ``module``."""
    if level == 0:
        return target or ""
    parts = module.split(".")
    base = parts if is_package else parts[:-1]
    base = base[: len(base) - (level - 1)]
    return ".".join(base + ([target] if target else []))


def _is_twolink_module(name: str) -> bool:
    relative = pathlib.Path(*name.split("."))
    return name.split(".")[0] in ("twolink", "twolink_course") and (
        (ROOT / relative).with_suffix(".py").is_file()
        or (ROOT / relative / "__init__.py").is_file()
    )


def _dotted(node: ast.expr) -> str | None:
    if isinstance(node, ast.Name):
        return node.id
    if isinstance(node, ast.Attribute):
        base = _dotted(node.value)
        return None if base is None else f"{base}.{node.attr}"
    return None


def private_name_uses() -> list[str]:
    """Every ``from X import _name`` and ``X._name`` in twolink/ where X is another twolink module."""
    offences = []
    for path in _source_files():
        module = _module_name(path)
        is_package = path.name == "__init__.py"
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
        modules_bound = {}  # local name -> the twolink module it is bound to
        for node in ast.walk(tree):
            if isinstance(node, ast.Import):
                for alias in node.names:
                    if _is_twolink_module(alias.name):
                        if alias.asname:
                            modules_bound[alias.asname] = alias.name
                        else:
                            modules_bound[alias.name.split(".")[0]] = alias.name.split(
                                "."
                            )[0]
            elif isinstance(node, ast.ImportFrom):
                source = _resolve(module, is_package, node.level, node.module)
                if not source.startswith("twolink"):
                    continue
                for alias in node.names:
                    full = f"{source}.{alias.name}"
                    if _is_twolink_module(full):
                        modules_bound[alias.asname or alias.name] = full
                    if (
                        not _is_private(alias.name)
                        or source == module
                        or full in INTERNAL_API_MODULES
                    ):
                        continue
                    offences.append(
                        f"{module} (line {node.lineno}): from {source} import {alias.name}"
                    )
        for node in ast.walk(tree):
            if isinstance(node, ast.Attribute) and _is_private(node.attr):
                owner = _dotted(node.value)
                if owner is None or owner.split(".")[0] not in modules_bound:
                    continue
                head, _, rest = owner.partition(".")
                target = modules_bound[head] + (f".{rest}" if rest else "")
                if (
                    _is_twolink_module(target)
                    and target != module
                    and f"{target}.{node.attr}" not in INTERNAL_API_MODULES
                ):
                    offences.append(
                        f"{module} (line {node.lineno}): {owner}.{node.attr} ({target})"
                    )
    return offences


def test_the_private_name_walk_sees_both_forms(tmp_path, monkeypatch):
    """The walk catches ``from X import _name`` and ``X._name`` and lets internal-API imports pass."""
    package = tmp_path / "twolink"
    package.mkdir()
    (package / "__init__.py").write_text("")
    (package / "_validate.py").write_text("def as_pairs(x):\n    return x\n")
    (package / "kinematics.py").write_text(
        "def _lengths(arm):\n    return arm\n\ndef fk(arm):\n    return _lengths(arm)\n"
    )
    (package / "user.py").write_text(
        "from . import kinematics\n"
        "from ._validate import as_pairs\n"
        "from .kinematics import _lengths\n"
        "import twolink.kinematics as kin\n"
        "x = kinematics._lengths(1) + kin._lengths(2)\n"
    )
    monkeypatch.setattr(sys.modules[__name__], "ROOT", tmp_path)
    monkeypatch.setattr(sys.modules[__name__], "PACKAGES", (package,))
    assert private_name_uses() == [
        "twolink.user (line 3): from twolink.kinematics import _lengths",
        "twolink.user (line 5): kinematics._lengths (twolink.kinematics)",
        "twolink.user (line 5): kin._lengths (twolink.kinematics)",
    ]


def test_no_module_uses_another_modules_private_names():
    offences = private_name_uses()
    assert not offences, (
        "private names used across modules (make them public, or move the code):\n"
        + "\n".join(offences)
    )
