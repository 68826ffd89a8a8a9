"""Where tests live: a folder per part of the project, one file per public module, no grab-bag files, no issue numbers.

- tests live in the folders of the root ``conftest.py``'s ``FOLDER_MARKERS``
  (``tests/library``, ``tests/course``, ``tests/notebooks``,
  ``tests/infrastructure``, ``tests/browser``, ``tests/repository``), which mark
  them; ``tests/`` itself holds only the shared helpers;
- ``twolink/<module>.py`` (the library) is tested in ``tests/library/test_<module>.py``
  and ``twolink_course/<module>.py`` (the course kit) in
  ``tests/course/test_<module>.py`` (no module name is in both);
- ``<package>/<subpackage>/<module>.py`` in ``test_<subpackage>_<module>.py``, or,
  when the package's ``__init__.py`` imports it (its names are the package's),
  in ``test_<package>.py`` with the package, in the package's folder;
- every test file's name is unique across the folders (pytest imports them by
  their names);
- no ``test_edges_*.py``: a test of an edge case goes to the file of the
  module it exercises (a table spanning many modules to ``tests/library/test_validate.py``);
- no issue numbers in tests or the package: history lives in git and CHANGELOG.md.
"""

import ast
import importlib.util
import pathlib
import re

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
PACKAGES = (ROOT / "twolink", ROOT / "twolink_course")
TESTS = ROOT / "tests"
#: The folder of tests/ each package's modules are tested in.
TEST_FOLDER = {"twolink": "library", "twolink_course": "course"}
#: What tests/ itself may hold: the helpers shared by the folders.
SHARED = {"conftest.py", "_cases.py", "_venvs.py", "nbval_sanitize.cfg", "__pycache__"}


def _root_conftest():
    spec = importlib.util.spec_from_file_location("root_conftest", ROOT / "conftest.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


#: Public modules without a test file of their own, and why.
NO_TEST_FILE = {
    "twolink": "the package as a whole: tests/library/test_import.py",
    "twolink_course": "a docstring only: the kit's modules have their test files",
    "twolink_course.sources": "a docstring only: each source has its tests/course/test_sources_*.py",
    "twolink_course.explorers": "a docstring only: each chapter's module has its tests/course/test_explorers_chN.py",
}

#: "issue 12", "issues 11 and 12", "issue #21", " #21" (not "owner/repo#312", not a
#: colour "#1f4e79", not a regex's "[ #0]"): a reference to this project's tracker.
ISSUE_NUMBER = re.compile(
    r"\bissues?\s+#?\d+|(?:^|(?<=[\s(]))#\d{1,5}\b(?![\w\]-])", re.IGNORECASE
)


def _module_name(path: pathlib.Path) -> str:
    parts = path.relative_to(ROOT).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def public_modules() -> list[str]:
    """Every module of the two packages with no part of its path starting with ``_``."""
    names = []
    for package in PACKAGES:
        for path in sorted(package.rglob("*.py")):
            parts = path.relative_to(package).parts
            if any(part.startswith("_") for part in parts[:-1]):
                continue
            if parts[-1].startswith("_") and parts[-1] != "__init__.py":
                continue
            names.append(_module_name(path))
    return names


def test_no_module_name_is_in_both_packages():
    """``test_<module>.py`` names one module only."""
    library, kit = (
        {
            name.partition(".")[2]
            for name in public_modules()
            if name.split(".")[0] == top
        }
        for top in ("twolink", "twolink_course")
    )
    assert library & kit - {""} == set()


def imported_by_its_package(module: str) -> bool:
    """Whether ``package/__init__.py`` imports ``module`` (``from .module import ...``)."""
    package, _, leaf = module.rpartition(".")
    init = ROOT.joinpath(*package.split("."), "__init__.py")
    for node in ast.walk(ast.parse(init.read_text())):
        if isinstance(node, ast.ImportFrom) and node.level == 1:
            if node.module == leaf:
                return True
            if node.module is None and any(a.name == leaf for a in node.names):
                return True
    return False


def expected_test_files(module: str) -> list[str]:
    """The test files (from ``tests/``) any one of which holds ``module``'s tests."""
    package, *parts = module.split(".")
    folder = TEST_FOLDER[package]
    own = f"{folder}/test_" + "_".join(parts) + ".py"
    if len(parts) == 2 and imported_by_its_package(module):
        return [own, f"{folder}/test_{parts[0]}.py"]
    return [own]


@pytest.mark.parametrize("module", public_modules())
def test_every_public_module_has_its_test_file(module):
    if module in NO_TEST_FILE:
        return
    candidates = expected_test_files(module)
    assert any((TESTS / name).is_file() for name in candidates), (
        f"{module} has no test file: write tests/{candidates[0]}"
        + (f" (or tests/{candidates[1]})" if len(candidates) > 1 else "")
    )


def test_tests_live_in_the_marked_folders_only():
    """A file put in tests/ itself, or in a folder without markers, would run unmarked."""
    marked = {
        folder.removeprefix("tests/")
        for folder in _root_conftest().FOLDER_MARKERS
        if folder.startswith("tests/")
    }
    loose = sorted(
        path.name
        for path in TESTS.iterdir()
        if path.name not in SHARED and path.name not in marked
    )
    assert not loose, (
        f"tests/ holds {loose}: put each test file in one of the folders {sorted(marked)} "
        "(or give a new folder its markers in the root conftest.py's FOLDER_MARKERS)"
    )
    assert all((TESTS / folder).is_dir() for folder in marked), (
        "a marked folder is gone"
    )


def test_every_test_file_name_is_unique():
    """pytest imports a test file by its name (no __init__.py): two files of one name collide."""
    names = {}
    for path in sorted(TESTS.rglob("test_*.py")):
        if (path.parent / "__init__.py").exists():
            continue  # a package's modules are imported by their dotted names
        names.setdefault(path.name, []).append(str(path.relative_to(TESTS)))
    clashes = {name: paths for name, paths in names.items() if len(paths) > 1}
    assert not clashes, clashes


def test_the_modules_without_a_test_file_still_exist():
    """An entry of NO_TEST_FILE for a module that is gone or has a file is stale."""
    modules = set(public_modules())
    for module in NO_TEST_FILE:
        assert module in modules, module
        assert not any((TESTS / name).is_file() for name in expected_test_files(module))


def test_the_rule_maps_modules_to_the_files_a_newcomer_would_look_for():
    assert expected_test_files("twolink.kinematics") == ["library/test_kinematics.py"]
    assert expected_test_files("twolink.ik.turns") == ["library/test_ik_turns.py"]
    assert expected_test_files("twolink.ik.analytic") == [
        "library/test_ik_analytic.py",
        "library/test_ik.py",
    ]
    assert expected_test_files("twolink_course.sources.osake") == [
        "course/test_sources_osake.py"
    ]
    assert "twolink._validate" not in public_modules()
    assert "twolink.ik" in public_modules()


def test_no_grab_bag_test_files():
    grab_bags = sorted(path.name for path in TESTS.rglob("test_edges_*.py"))
    assert not grab_bags, (
        f"{grab_bags}: put each test in test_<module>.py of the module it exercises"
    )


def _files_to_keep_free_of_issue_numbers() -> list[pathlib.Path]:
    return sorted(
        [*TESTS.rglob("*.py"), *(path for p in PACKAGES for path in p.rglob("*.py"))]
    )


@pytest.mark.parametrize(
    "text, found",
    [
        ("# energy with a spring (issue 12)", True),
        ('"""Edges of simulate (Issue 11, class 2)."""', True),
        ("retired by issues 11 and 12", True),
        ("see #21 for why", True),
        ("the tracker's (#7)", True),
        ("jupyter/nbclient#312 upstream", False),
        ('LINK_COLOR = "#1f4e79"', False),
        ('COLOR = "#123456"', False),
        ('re.compile(r"%[-+ #0]*")', False),
        ("the issue warns about round-off", False),
        ("# ----- section", False),
    ],
)
def test_the_issue_number_pattern(text, found):
    assert bool(ISSUE_NUMBER.search(text)) is found


def test_no_issue_numbers_in_tests_or_the_package():
    found = [
        f"{path.relative_to(ROOT)}:{number}: {line.strip()}"
        for path in _files_to_keep_free_of_issue_numbers()
        if path.name != "test_layout.py"  # its own examples
        for number, line in enumerate(path.read_text().splitlines(), start=1)
        if ISSUE_NUMBER.search(line)
    ]
    assert not found, (
        "history lives in git and CHANGELOG.md, not in code:\n" + "\n".join(found)
    )
