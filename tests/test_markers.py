"""Slow infrastructure tests carry the ``infrastructure`` marker, so the quick part can leave them out.

``make test`` runs everything; ``pytest -m "not infrastructure and not browser"``
is the quick part.  A test is infrastructure when it (or a helper function or
fixture of its own module that it uses, transitively) builds a virtual
environment (``_venvs.bare_venv``, ``_venvs.pip``) or a wheel (``pip wheel``, ``editions.build_wheel``),
runs a nested pytest (``python -m pytest``, ``portable.main``), drives the
browser (the ``page``, ``browser`` or ``jupyterlab`` fixtures) or runs a whole
edition (``grade.grade_folder``, ``editions.build_site``, a ``HeadlessClient``).
The source of every test file is read; nothing is run.
"""

import ast
import pathlib
import tomllib

ROOT = pathlib.Path(__file__).resolve().parent.parent
TEST_FILES = sorted((ROOT / "tests").rglob("test_*.py"))

VENV_OR_EDITION_CALLS = {
    "_venvs.bare_venv": "builds a venv",
    "_venvs.pip": "runs pip in a venv",
    "portable.main": "runs nested pytest (nbval)",
    "portable.run_nbval": "runs nested pytest (nbval)",
    "grade.grade_folder": "runs a whole edition (grading)",
    "grade.grade_notebook": "runs a whole edition (grading)",
    "editions.build_site": "renders the whole static edition",
    "editions.build_wheel": "builds a wheel",
    "HeadlessClient": "executes a whole edition",
}
BROWSER_FIXTURES = {"page", "browser", "jupyterlab"}
#: Tests that call such a function but stop before anything slow runs.
NOT_INFRASTRUCTURE = {
    "tests/test_grade.py::test_make_grade_needs_a_folder": "refused: not a folder",
    "tests/test_grade.py::test_grading_refuses_without_a_sandbox_unless_told": "refused: no sandbox",
    "tests/test_grade.py::test_names_cannot_forge_a_formula_or_a_summary_line": "an unreadable file: nothing runs",
    "tests/test_grade.py::test_a_notebook_of_no_chapter_says_so": "no chapter: nothing runs",
    "tests/test_grade.py::test_a_notebook_that_is_not_valid_nbformat_is_reported_unread": "refused unread",
    "tests/test_portable.py::test_an_unknown_notebook_is_refused_by_name": "refused: no such notebook",
    "tests/test_portable.py::test_a_kernel_that_did_not_start_is_run_again_once": "run_nbval replaced",
    "tests/test_portable.py::test_a_mismatch_is_never_run_again": "run_nbval replaced",
}


def _call_name(node):
    try:
        return ast.unparse(node.func)
    except (AttributeError, ValueError):  # pragma: no cover - defensive
        return ""


def _constant_strings(node):
    return [
        element.value
        for element in node.elts
        if isinstance(element, ast.Constant) and isinstance(element.value, str)
    ]


def _own_reasons(function):
    """What a function's body does that is infrastructure, and the module-level names it calls."""
    reasons, called = set(), set()
    for node in ast.walk(function):
        if isinstance(node, ast.Call):
            name = _call_name(node)
            if name in VENV_OR_EDITION_CALLS:
                reasons.add(VENV_OR_EDITION_CALLS[name])
            if isinstance(node.func, ast.Name):
                called.add(node.func.id)
        elif isinstance(node, ast.List):
            words = _constant_strings(node)
            if "-m" in words and "pytest" in words:
                reasons.add("runs nested pytest")
            if "pip" in words and "wheel" in words:
                reasons.add("builds a wheel")
    return reasons, called


def _marks(decorators):
    return {
        ast.unparse(decorator).removeprefix("pytest.mark.").split("(")[0]
        for decorator in decorators
    }


def _module_marks(tree):
    for node in tree.body:
        if isinstance(node, ast.Assign) and any(
            isinstance(target, ast.Name) and target.id == "pytestmark"
            for target in node.targets
        ):
            values = (
                node.value.elts
                if isinstance(node.value, (ast.List, ast.Tuple))
                else [node.value]
            )
            return _marks(values)
    return set()


def infrastructure_tests(path):
    """``{test name: (reasons, marks)}`` for the tests of one file that do infrastructure work."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    functions = {
        node.name: node
        for node in tree.body
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef))
    }
    own = {name: _own_reasons(function) for name, function in functions.items()}

    def reasons_of(name, seen):
        if name in seen or name not in functions:
            return set()
        seen.add(name)
        reasons, called = own[name]
        used = called | {argument.arg for argument in functions[name].args.args}
        found = set(reasons)
        for other in used:
            found |= reasons_of(other, seen)
        return found

    module_marks = _module_marks(tree)
    found = {}
    for name, function in functions.items():
        if not name.startswith("test_"):
            continue
        reasons = reasons_of(name, set())
        arguments = {argument.arg for argument in function.args.args}
        if arguments & BROWSER_FIXTURES:
            reasons.add("drives the browser")
        if reasons:
            found[name] = (reasons, module_marks | _marks(function.decorator_list))
    return found


def _found():
    return {
        f"{path.relative_to(ROOT)}::{name}": (reasons, marks)
        for path in TEST_FILES
        for name, (reasons, marks) in infrastructure_tests(path).items()
    }


def test_every_infrastructure_test_carries_the_marker():
    unmarked = [
        f"{test} ({', '.join(sorted(reasons))})"
        for test, (reasons, marks) in _found().items()
        if "infrastructure" not in marks and test not in NOT_INFRASTRUCTURE
    ]
    assert not unmarked, (
        "mark these @pytest.mark.infrastructure (make test still runs them; the quick "
        f"part leaves them out): {unmarked}"
    )


def test_the_exceptions_are_found_and_unmarked():
    found = _found()
    for test, why in NOT_INFRASTRUCTURE.items():
        assert test in found, f"{test} ({why}) no longer calls such a function: drop it"
        assert "infrastructure" not in found[test][1], f"{test} is marked after all"


def test_the_check_finds_each_kind_of_infrastructure():
    found = {test: reasons for test, (reasons, _) in _found().items()}
    kinds = set().union(*found.values())
    for kind in (
        "builds a venv",
        "builds a wheel",
        "runs nested pytest",
        "drives the browser",
        "executes a whole edition",
        "runs a whole edition (grading)",
    ):
        assert kind in kinds, f"nothing found that {kind}: the check has gone blind"
    # through a fixture of the module (test_grade's `graded`) and a helper (`pytest_in`)
    assert (
        "runs a whole edition (grading)"
        in found[
            "tests/test_grade.py::test_an_untouched_notebook_is_not_solved_in_every_part"
        ]
    )
    assert (
        "runs nested pytest"
        in found[
            "tests/test_pytest_anywhere.py::test_without_the_root_conftest_the_run_from_notebooks_fails"
        ]
    )


def test_an_unmarked_venv_test_is_reported(tmp_path):
    path = tmp_path / "test_example.py"
    path.write_text(
        "import _venvs, pytest\n"
        "def helper(tmp_path):\n    return _venvs.bare_venv(tmp_path, [])\n"
        "def test_quick():\n    assert True\n"
        "def test_slow(tmp_path):\n    helper(tmp_path)\n"
        "@pytest.mark.infrastructure\ndef test_marked(tmp_path):\n    helper(tmp_path)\n",
        encoding="utf-8",
    )
    found = infrastructure_tests(path)
    assert set(found) == {"test_slow", "test_marked"}
    assert "infrastructure" not in found["test_slow"][1]
    assert "infrastructure" in found["test_marked"][1]


def test_the_marker_is_registered_and_the_quick_part_documented():
    pyproject = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    markers = pyproject["tool"]["pytest"]["ini_options"]["markers"]
    assert any(marker.startswith("infrastructure: ") for marker in markers)
    makefile = (ROOT / "Makefile").read_text(encoding="utf-8")
    assert 'pytest -m \\"not infrastructure and not browser\\"' in makefile
