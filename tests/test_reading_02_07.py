"""Chapters 2 and 7 as a reader sees them: labelled figures, names defined before use, clean prose cells.

The figure checks run each chapter's checked code cells in this process
(matplotlib's Agg backend) and look at every figure when the chapter calls
``plt.show()`` or hands an animation to ``plot.animation_html``: every axes
shows a quantity with a unit in brackets on both axes.  Cells marked
``# NBVAL_IGNORE_OUTPUT`` (sliders and timings: they redraw what a checked
cell already drew, or only measure) are skipped.  The text checks read the
committed JSON.
"""

import json
import pathlib
import re

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pytest  # noqa: E402

import twolink.plot  # noqa: E402

NOTEBOOK_DIR = pathlib.Path(__file__).resolve().parent.parent / "notebooks"
CHAPTER_2 = "02_inverse_kinematics.ipynb"
CHAPTER_7 = "07_workspace_trajectories.ipynb"
CHAPTERS = [CHAPTER_2, CHAPTER_7]

LABEL_WITH_UNIT = re.compile(r"\S.*\[[^\]]+\]")  # "x [m]", "time per point [µs]"
SOLVER_NAMES = ("fminunc", "fmincon", "BFGS", "SLSQP", "Levenberg-Marquardt")


def cells(name):
    return json.loads((NOTEBOOK_DIR / name).read_text(encoding="utf-8"))["cells"]


def text(cell):
    return "".join(cell["source"])


def unlabelled_axes(figure):
    found = []
    for ax in figure.axes:
        if not ax.axison or ax.get_label() == "<colorbar>":
            continue
        for which, label in (("x", ax.get_xlabel()), ("y", ax.get_ylabel())):
            if not LABEL_WITH_UNIT.match(label):
                found.append(f"axes {ax.get_title()!r}: {which} label {label!r} has no quantity [unit]")
    return found


def run_chapter(name, monkeypatch):
    """Run the chapter's checked code cells; return (problems, number of figures checked)."""
    problems, checked = [], []
    where = {"cell": None}

    def check_open_figures(*args, **kwargs):
        for number in plt.get_fignums():
            figure = plt.figure(number)
            checked.append(figure)
            problems.extend(f"code cell {where['cell']}: {problem}" for problem in unlabelled_axes(figure))
            plt.close(figure)

    def checking_animation_html(anim):
        check_open_figures()  # the animation's figure is still open here; no video is encoded
        return None

    monkeypatch.setattr(plt, "show", check_open_figures)
    monkeypatch.setattr(twolink.plot, "animation_html", checking_animation_html)
    monkeypatch.chdir(NOTEBOOK_DIR)
    namespace = {"__name__": "__chapter__"}
    code = [text(cell) for cell in cells(name) if cell["cell_type"] == "code"]
    for index, source in enumerate(code):
        if source.startswith("# NBVAL_IGNORE_OUTPUT"):
            continue
        where["cell"] = index
        exec(compile(source, f"{name} code cell {index}", "exec"), namespace)  # noqa: S102
    where["cell"] = "end"
    check_open_figures()
    return problems, len(checked)


@pytest.mark.parametrize("name", CHAPTERS)
def test_every_figure_has_labelled_axes(name, monkeypatch, capsys):
    problems, figures = run_chapter(name, monkeypatch)
    capsys.readouterr()  # the chapter's own printed output is not under test
    assert figures >= 5, f"{name}: only {figures} figures were checked"
    assert not problems, f"{name}: " + "; ".join(problems)


def test_the_label_check_catches_a_missing_unit():
    figure, ax = plt.subplots()
    ax.set_xlabel("t [s]")
    ax.set_ylabel("angle")
    assert unlabelled_axes(figure) == ["axes '': y label 'angle' has no quantity [unit]"]
    ax.set_ylabel("angle [deg]")
    assert unlabelled_axes(figure) == []
    plt.close(figure)


def test_chapter_2_defines_the_branch_names_before_using_them():
    content = cells(CHAPTER_2)
    definition = next(index for index, cell in enumerate(content)
                      if cell["cell_type"] == "markdown" and "**down** is the" in text(cell))
    first_use = next(index for index, cell in enumerate(content)
                     if cell["cell_type"] == "code" and re.search(r"\bdown\b|\bup\b", text(cell)))
    assert definition < first_use, f"'down'/'up' used in cell {first_use}, defined in cell {definition}"


def test_chapter_2_explains_each_solver_name_before_the_chapter_relies_on_it():
    content = [text(cell) for cell in cells(CHAPTER_2) if cell["cell_type"] == "markdown"]
    glossary = next((index for index, cell in enumerate(content) if all(f"**{name}" in cell for name in SOLVER_NAMES[2:])), None)
    assert glossary is not None, f"no markdown cell explains {', '.join(SOLVER_NAMES[2:])} (each in bold)"
    for name in SOLVER_NAMES:
        first = next(index for index, cell in enumerate(content) if name in cell)
        explained_there = first == glossary or (name == "fminunc" and "MATLAB's minimiser `fminunc`" in content[first])
        assert explained_there, f"{name} first appears in markdown cell {first}, explained only in cell {glossary}"


def test_chapter_7_has_no_set_unpacking_and_names_the_circle_it_draws():
    code = [text(cell) for cell in cells(CHAPTER_7) if cell["cell_type"] == "code"]
    assert not [line for source in code for line in source.splitlines() if re.match(r"\s*\(\w+,\)\s*=", line)]
    assert not [source.splitlines()[0] for source in code if re.search(r"""["'][^"']*source circle""", source)]


@pytest.mark.parametrize("name", CHAPTERS)
def test_the_introduction_says_where_real_robots_use_the_idea(name):
    assert "On real robots" in text(cells(name)[0]), f"{name}: the introduction says nowhere where the idea is used"


@pytest.mark.parametrize("name", CHAPTERS)
def test_no_markdown_cell_repeats_its_own_lines(name):
    content = cells(name)
    for index, cell in enumerate(content):
        if cell["cell_type"] != "markdown":
            continue
        lines = [line.strip() for line in text(cell).splitlines() if len(line.strip()) > 30]
        repeated = {line for line in lines if lines.count(line) > 1}
        assert not repeated, f"{name} markdown cell {index} repeats itself: {sorted(repeated)[:2]}"
