"""Markers follow folders: every test carries the markers of the folder it lives in.

The root ``conftest.py`` marks each collected test by its folder
(``FOLDER_MARKERS``: ``library``, ``course``, ``notebooks``,
``infrastructure``, ``browser``, ``repository``), so ``pytest -m library``
selects the library's tests and ``pytest -m "not infrastructure"`` is the
quick part; nobody keeps a list of tests.  The slow work is infrastructure:
a test that (itself, or through a helper function or fixture of its own
module or of ``tests/conftest.py``, transitively) builds a virtual
environment (``_venvs.bare_venv``, ``_venvs.pip``) or a wheel (``pip wheel``,
``editions.build_wheel``, ``editions.build_student_edition``), runs a nested
pytest (``python -m pytest``, pytester's ``runpytest_inprocess`` and the like,
``portable.main``), drives the browser (the ``page``, ``browser`` or
``jupyterlab`` fixtures) or runs a whole edition
(``grade.grade_folder``, ``editions.build_site``, a ``HeadlessClient``) lives
in an infrastructure folder (``tests/infrastructure``, ``tests/browser``).
The source of every test file is read; nothing is run.
"""

import ast
import importlib.util
import pathlib
import tomllib

ROOT = pathlib.Path(__file__).resolve().parents[2]
TEST_FILES = sorted((ROOT / "tests").rglob("test_*.py"))
PYTEST_OPTIONS = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))[
    "tool"
]["pytest"]["ini_options"]


def _root_conftest():
    spec = importlib.util.spec_from_file_location("root_conftest", ROOT / "conftest.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


ROOT_CONFTEST = _root_conftest()

VENV_OR_EDITION_CALLS = {
    "_venvs.bare_venv": "builds a venv",
    "_venvs.pip": "runs pip in a venv",
    "pytester.runpytest": "runs nested pytest",
    "pytester.runpytest_inprocess": "runs nested pytest",
    "pytester.runpytest_subprocess": "runs nested pytest",
    "pytester.inline_run": "runs nested pytest",
    "portable.main": "runs nested pytest (nbval)",
    "portable.run_nbval": "runs nested pytest (nbval)",
    "grade.grade_folder": "runs a whole edition (grading)",
    "grade.grade_notebook": "runs a whole edition (grading)",
    "editions.build_site": "renders the whole static edition",
    "editions.build_wheel": "builds a wheel",
    "editions.build_student_edition": "builds a wheel",
    "HeadlessClient": "executes a whole edition",
}
BROWSER_FIXTURES = {"page", "browser", "jupyterlab"}


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


def _functions(tree):
    return {
        node.name: node
        for node in tree.body
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef))
    }


#: The fixtures every test can ask for (tests/conftest.py: the student edition, built once per run).
SHARED_FIXTURES = _functions(
    ast.parse((ROOT / "tests" / "conftest.py").read_text(encoding="utf-8"))
)


def infrastructure_tests(path):
    """``{test name: (reasons, marks)}`` for the tests of one file that do infrastructure work."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    functions = {**SHARED_FIXTURES, **_functions(tree)}
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


def _in_an_infrastructure_folder(path):
    return "infrastructure" in ROOT_CONFTEST.folder_markers(
        path.relative_to(ROOT).as_posix()
    )


def _found():
    return {
        f"{path.relative_to(ROOT)}::{name}": (reasons, marks)
        for path in TEST_FILES
        for name, (reasons, marks) in infrastructure_tests(path).items()
    }


def test_infrastructure_work_is_in_an_infrastructure_folder():
    elsewhere = [
        f"{test} ({', '.join(sorted(reasons))})"
        for test, (reasons, _) in _found().items()
        if not _in_an_infrastructure_folder(ROOT / test.split("::")[0])
    ]
    assert not elsewhere, (
        "move these to tests/infrastructure/ (its folder marks them infrastructure: "
        f"make test runs them, the quick part leaves them out): {elsewhere}"
    )


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
            "tests/infrastructure/test_grade.py::test_an_untouched_notebook_is_not_solved_in_every_part"
        ]
    )
    assert (
        "runs nested pytest"
        in found[
            "tests/infrastructure/test_pytest_anywhere.py::test_without_the_root_conftest_the_run_from_notebooks_fails"
        ]
    )
    # through a fixture of tests/conftest.py (the wheel of the edition built once per run)
    assert (
        "builds a wheel"
        in found[
            "tests/infrastructure/test_packaging.py::test_the_wheel_works_with_only_the_librarys_three_dependencies"
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


# ------------------------------------------------------------------ markers by folder


def test_each_folder_maps_to_its_markers():
    markers = ROOT_CONFTEST.folder_markers
    assert markers("tests/library/test_kinematics.py") == ("library",)
    assert markers("twolink/kinematics.py") == ("library",)  # its doctests
    assert markers("tests/course/test_plot.py") == ("course",)
    assert markers("notebooks/01_dh_forward_kinematics.ipynb") == ("notebooks",)
    assert markers("tests/browser/test_static_site.py") == ("infrastructure", "browser")
    assert markers("tests/infrastructure/test_grade.py") == ("infrastructure",)
    assert markers("tests/repository/test_markers.py") == ("repository",)
    assert markers("tests/benchmarks/test_benchmarks_run.py") == ("benchmarks",)
    assert markers("tests/conftest.py") == ()
    assert markers("tests/libraryx/test_a.py") == ()  # a folder, not a prefix


def test_this_test_carries_its_folders_marker(request):
    """The hook ran on the collected tests: this one is marked by tests/repository/."""
    assert request.node.get_closest_marker("repository") is not None
    assert request.node.get_closest_marker("library") is None


def test_every_folder_marker_is_registered_and_every_registered_marker_used():
    registered = {marker.split(":")[0] for marker in PYTEST_OPTIONS["markers"]}
    used = {
        marker
        for markers in ROOT_CONFTEST.FOLDER_MARKERS.values()
        for marker in markers
    }
    assert used == registered


def test_every_place_pytest_collects_from_is_marked():
    for path in PYTEST_OPTIONS["testpaths"]:
        assert ROOT_CONFTEST.folder_markers(path), f"{path} has no markers"


def test_make_test_collects_every_folder_of_tests_but_the_benchmarks():
    folders = {
        folder for folder in ROOT_CONFTEST.FOLDER_MARKERS if folder.startswith("tests/")
    }
    assert folders - set(PYTEST_OPTIONS["testpaths"]) == {"tests/benchmarks"}


def test_the_quick_part_is_documented():
    makefile = (ROOT / "Makefile").read_text(encoding="utf-8")
    assert 'pytest -m \\"not infrastructure\\"' in makefile
