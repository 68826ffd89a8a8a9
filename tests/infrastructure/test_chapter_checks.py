"""The chapter checks ride along in nbval's run: a figure without a unit fails the chapter's ``::figures``.

A nested pytest (pytest's own, in this process: ``pytester``) runs a small
chapter with the repository's pytest set-up (pyproject.toml, the root
conftest.py, tests/notebooks/chapter_checks.py), from the copy's root: it
gets its ``::figures`` and ``::exercises`` tests after its last cell, asked of
the kernel nbval ran it in; its last figure has an axis without a unit, so
``::figures`` fails, naming the cell and the axis, while the cells themselves
pass (nbval compares no picture) and ``::exercises`` passes (it has none).
"""

import pathlib
import shutil

import nbformat

pytest_plugins = ["pytester"]

ROOT = pathlib.Path(__file__).resolve().parents[2]

FIGURE = (
    "figure, ax = plt.subplots()\n"
    "ax.plot([0.0, 1.0], [0.0, 1.0])\n"
    'ax.set_xlabel("t [s]")\n'
    "ax.set_ylabel({label!r})\n"
    "plt.show()"
)


def _chapter(path, last_label):
    cells = [nbformat.v4.new_code_cell("import matplotlib.pyplot as plt")]
    for label in ("q [rad]", "q [rad]", last_label):  # three figures: the least checked
        cells.append(nbformat.v4.new_code_cell(FIGURE.format(label=label)))
    kernel = {"name": "python3", "display_name": "Python 3", "language": "python"}
    nbformat.write(
        nbformat.v4.new_notebook(cells=cells, metadata={"kernelspec": kernel}), path
    )


def test_a_figure_without_a_unit_fails_its_chapter_in_the_one_run(
    pytester, monkeypatch
):
    tmp_path = pytester.path
    shutil.copy(ROOT / "pyproject.toml", tmp_path)
    shutil.copy(ROOT / "conftest.py", tmp_path)
    (tmp_path / "tests").mkdir()
    shutil.copy(ROOT / "tests" / "nbval_sanitize.cfg", tmp_path / "tests")
    shutil.copytree(ROOT / "tests" / "notebooks", tmp_path / "tests" / "notebooks")
    (tmp_path / "tools").symlink_to(ROOT / "tools")
    (tmp_path / "notebooks").mkdir()
    _chapter(tmp_path / "notebooks" / "01_unlabelled.ipynb", "q")
    monkeypatch.chdir(tmp_path)
    # nbval's budgets: the kernel's start (60 s), each cell's (60 s); the chapter checks have their own
    options = ["-n", "0", "-p", "no:cacheprovider", "--nbval-cell-timeout", "60"]
    done = pytester.runpytest_inprocess(*options, "--nbval-lax", "-rA", "notebooks")
    said = done.stdout.str()
    assert done.ret == 1, said[-3000:] + done.stderr.str()[-2000:]
    assert "PASSED notebooks/01_unlabelled.ipynb::exercises" in said, said[-3000:]
    assert "FAILED notebooks/01_unlabelled.ipynb::figures" in said, said[-3000:]
    assert "code cell 3: figure: axes '': y label 'q' has no quantity [unit]" in said
    assert "1 failed, 5 passed" in said, said[-3000:]
