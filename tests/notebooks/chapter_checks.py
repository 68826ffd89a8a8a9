"""The chapter checks: what needs a chapter's state, checked in nbval's own run of it.

nbval executes each chapter once (``make test``); this plugin (registered by
the root ``conftest.py``) rides along in that run instead of executing the
chapter again:

- before the chapter's first cell it sends ``chapter_kernel.py`` to the
  chapter's kernel and starts recording there (figures, explorers, self-check
  verdicts; nothing the cells output changes);
- after the last cell it adds two tests to the chapter,
  ``notebooks/NN_x.ipynb::figures`` (every figure a reader sees has labelled
  axes and states its scale; every explorer follows its controls to their
  ends) and ``notebooks/NN_x.ipynb::exercises`` (each worked solution passes
  its self-check, its student-edition stub says "not solved yet", a function
  passes hidden cases), which ask the same kernel for its record.

A chapter is a notebook ``tools/course_map.chapters`` names.  The checks are
added only when every cell of the chapter is selected (``-k`` or a single cell
leaves them out), and report a chapter whose cell failed as skipped: the
failing cell says why.  ``-p no:chapter_checks`` turns them off
(``tools/portable.py`` does: it compares stored outputs only).
"""

import ast
import json
import pathlib
import sys
from queue import Empty

import nbformat
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
KERNEL_CODE = pathlib.Path(__file__).with_name("chapter_kernel.py")
sys.path.insert(0, str(ROOT / "tools"))
import course_map  # noqa: E402
import editions  # noqa: E402
import nbgrader_cells  # noqa: E402

#: A seed the notebooks never hold (the grader has its own): hidden cases of function parts.
HIDDEN_TEST_SEED = 5_318_008
#: The name of the module the kernel gets (``sys.modules``), holding what it recorded.
KERNEL_MODULE = "_twolink_chapter_checks"
#: Seconds the kernel may take to install the checks or to answer for a chapter.
KERNEL_BUDGET = 600
#: The checks a chapter gets, in the order they run.
CHECKS = ("exercises", "figures")


def _nbval_cell_class():
    try:
        from nbval.plugin import IPyNbCell
    except ImportError:  # pragma: no cover - nbval is a test requirement
        return None
    return IPyNbCell


IPyNbCell = _nbval_cell_class()


def _is_chapter(path):
    return any(path == chapter for chapter in course_map.chapters(path.parent))


def run_in_kernel(kernel, code, expression, budget=KERNEL_BUDGET):
    """Run ``code`` quietly in nbval's kernel, then return ``expression``'s value (JSON) there.

    Quietly: no execution count, no history; the messages the run sends are
    read here, so the next cell's comparison never sees them.
    """
    message = kernel.kc.execute(
        code,
        silent=True,
        store_history=False,
        user_expressions={"result": f"__import__('json').dumps({expression})"},
        allow_stdin=False,
    )
    try:
        while True:
            reply = kernel.get_message(stream="shell", timeout=budget)
            if reply["parent_header"].get("msg_id") == message:
                break
        kernel.await_idle(message, budget)
    except Empty:
        raise AssertionError(
            f"the chapter's kernel did not answer within {budget} s "
            "(chapter_checks.KERNEL_BUDGET)"
        ) from None
    content = reply["content"]
    if content["status"] != "ok":
        raise AssertionError(
            f"the chapter checks raised in the kernel: {content.get('ename')}: "
            f"{content.get('evalue')}\n" + "\n".join(content.get("traceback", []))
        )
    result = content["user_expressions"]["result"]
    if result["status"] != "ok":
        raise AssertionError(
            f"the chapter checks raised in the kernel: {result.get('ename')}: "
            f"{result.get('evalue')}\n" + "\n".join(result.get("traceback", []))
        )
    return json.loads(ast.literal_eval(result["data"]["text/plain"]))


def _install_code():
    source = KERNEL_CODE.read_text(encoding="utf-8")
    return (
        "import sys as _sys, types as _types\n"
        f"_module = _types.ModuleType({KERNEL_MODULE!r})\n"
        f"exec(compile({source!r}, {str(KERNEL_CODE)!r}, 'exec'), _module.__dict__)\n"
        f"_sys.modules[{KERNEL_MODULE!r}] = _module\n"
        "_module.install()\n"
        "del _sys, _types, _module\n"
    )


def _recorded(call):
    """An expression calling ``call`` on what the kernel recorded."""
    return f"__import__('sys').modules[{KERNEL_MODULE!r}].{call}"


def _solution_cell(cells, number):
    wanted = nbgrader_cells.grade_id("solution", number)
    for cell in cells:
        if cell.get("metadata", {}).get("nbgrader", {}).get("grade_id") == wanted:
            return cell
    for cell in cells:
        if cell["cell_type"] == "code" and (
            cell["source"].startswith(f"# Exercise {number}")
            and editions.BEGIN in cell["source"]
        ):
            return cell
    raise AssertionError(f"no solution cell for exercise {number}")


def exercise_plan(path):
    """What :func:`chapter_kernel.exercise_report` needs for each exercise of the chapter at ``path``."""
    from twolink_course import exercises

    cells = nbformat.read(path, as_version=4).cells
    plan = []
    for exercise in exercises.all_exercises():
        if exercise.chapter != path.stem:
            continue
        parts = [part.name for part in exercise.parts]
        solution = _solution_cell(cells, exercise.number).source
        plan.append(
            {
                "number": exercise.number,
                "parts": parts,
                "stub": editions.stub_source(solution, set(parts)),
                "functions": [
                    part.name
                    for part in exercise.parts
                    if getattr(part, "kind", None) == "function"
                ],
            }
        )
    return plan


class ChapterCheck(pytest.Item):
    """One check of a chapter, asked of the kernel nbval ran it in, after its last cell."""

    def __init__(self, *, check, **kwargs):
        super().__init__(**kwargs)
        self.check = check

    def runtest(self):
        chapter = self.parent
        plugin = self.config.pluginmanager.get_plugin("chapter_checks")
        if chapter.nodeid in plugin.failed:
            pytest.skip("a cell of the chapter failed (see it): nothing to check")
        kernel = chapter.kernel
        if kernel is None or not kernel.is_alive():
            raise AssertionError("the chapter's kernel is gone")
        if self.check == "figures":
            report = run_in_kernel(kernel, "", _recorded("figure_report()"))
            assert report["figures"] >= 3, (
                f"only {report['figures']} figures were checked"
            )
            assert not report["problems"], "; ".join(report["problems"])
        else:
            plan = exercise_plan(self.path)
            problems = run_in_kernel(
                kernel,
                "",
                _recorded(
                    f"exercise_report({plan!r}, {str(ROOT)!r}, {HIDDEN_TEST_SEED})"
                ),
            )
            assert not problems, "; ".join(problems)

    def repr_failure(self, excinfo):
        if isinstance(excinfo.value, AssertionError):
            return f"{self.parent.name} {self.check}: {excinfo.value}"
        return super().repr_failure(excinfo)

    def reportinfo(self):
        return self.path, None, f"{self.parent.name}::{self.name}"


class ChapterChecks:
    """The plugin: adds the checks to each chapter, installs the recording, remembers failed cells."""

    def __init__(self):
        self.checked = set()  # node ids of the chapters that get the checks
        self.installed = set()  # node ids of chapters whose kernel records
        self.failed = set()  # node ids of chapters with a failed cell

    @pytest.hookimpl(trylast=True)
    def pytest_collection_modifyitems(self, session, config, items):
        if IPyNbCell is None:
            return
        cells = {}
        for item in items:
            if isinstance(item, IPyNbCell):
                cells.setdefault(item.parent, []).append(item)
        for notebook, selected in cells.items():
            if not _is_chapter(notebook.path):
                continue
            if len(selected) != sum(
                cell.cell_type == "code" for cell in notebook.nb.cells
            ):
                continue  # part of the chapter only
            last = items.index(selected[-1])
            checks = [
                ChapterCheck.from_parent(notebook, name=check, check=check)
                for check in CHECKS
            ]
            items[last + 1 : last + 1] = checks
            self.checked.add(notebook.nodeid)

    @pytest.hookimpl(hookwrapper=True)
    def pytest_runtest_setup(self, item):
        yield
        if IPyNbCell is None or not isinstance(item, IPyNbCell):
            return
        chapter = item.parent
        if chapter.nodeid not in self.checked or chapter.nodeid in self.installed:
            return
        self.installed.add(chapter.nodeid)
        run_in_kernel(chapter.kernel, _install_code(), "None")

    @pytest.hookimpl(hookwrapper=True)
    def pytest_runtest_makereport(self, item, call):
        outcome = yield
        if IPyNbCell is not None and isinstance(item, IPyNbCell):
            if outcome.get_result().failed:
                self.failed.add(item.parent.nodeid)
