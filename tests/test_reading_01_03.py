"""Chapters 1 and 3 as a reader sees them: labelled figures, stated scales, one name per matrix.

The figure checks run each chapter's code cells in this process (matplotlib's
Agg backend) and look at every figure when the chapter calls ``plt.show()``:
every axes shows a quantity with a unit in brackets on both axes, and a figure
that draws velocity ellipses or velocity arrows on position axes says, in its
own text, how many metres of figure one m/s is.  Cells marked
``# NBVAL_IGNORE_OUTPUT`` (sliders and timings: they redraw what a checked
cell already drew) are skipped.
"""

import json
import pathlib
import re

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pytest  # noqa: E402
from matplotlib.quiver import Quiver  # noqa: E402

import twolink.plot  # noqa: E402

NOTEBOOK_DIR = pathlib.Path(__file__).resolve().parent.parent / "notebooks"
CHAPTERS = ["01_dh_forward_kinematics.ipynb", "03_jacobian_velocity.ipynb"]

LABEL_WITH_UNIT = re.compile(r"\S.*\[[^\]]+\]")  # "x [m]", "joint rate [rad/s]"
SCALE_STATEMENT = re.compile(r"\d+(\.\d+)? m per m/s")


def code_sources(name):
    content = json.loads((NOTEBOOK_DIR / name).read_text(encoding="utf-8"))
    return ["".join(cell["source"]) for cell in content["cells"] if cell["cell_type"] == "code"]


def figure_texts(figure):
    texts = [figure.get_suptitle(), *(text.get_text() for text in figure.texts)]
    for ax in figure.axes:
        texts += [ax.get_title(), *(text.get_text() for text in ax.texts)]
    return " ".join(texts)


def problems_in(figure, ellipse_axes):
    found = []
    for ax in figure.axes:
        if not ax.axison or ax.get_label() == "<colorbar>":
            continue
        for which, label in (("x", ax.get_xlabel()), ("y", ax.get_ylabel())):
            if not LABEL_WITH_UNIT.match(label):
                found.append(f"axes {ax.get_title()!r}: {which} label {label!r} has no quantity [unit]")
        has_arrows = any(isinstance(artist, Quiver) for artist in ax.collections)
        if (ax in ellipse_axes or has_arrows) and not SCALE_STATEMENT.search(figure_texts(figure)):
            found.append(f"axes {ax.get_title()!r}: ellipses or arrows on position axes without 'N m per m/s'")
    return found


def run_chapter(name, monkeypatch):
    """Run the chapter's checked code cells; return the figure problems, one string each."""
    problems, ellipse_axes, shown = [], set(), []
    draw_ellipse = twolink.plot.draw_ellipse

    def recording_draw_ellipse(ellipse, ax, *args, **kwargs):
        ellipse_axes.add(ax)
        return draw_ellipse(ellipse, ax, *args, **kwargs)

    def checking_show(*args, **kwargs):
        for number in plt.get_fignums():
            figure = plt.figure(number)
            shown.append(figure)
            problems.extend(f"code cell {cell_index}: {problem}" for problem in problems_in(figure, ellipse_axes))
            plt.close(figure)

    monkeypatch.setattr(twolink.plot, "draw_ellipse", recording_draw_ellipse)
    monkeypatch.setattr(plt, "show", checking_show)
    monkeypatch.chdir(NOTEBOOK_DIR)
    namespace = {"__name__": "__chapter__"}
    for cell_index, source in enumerate(code_sources(name)):
        if source.startswith("# NBVAL_IGNORE_OUTPUT"):
            continue
        exec(compile(source, f"{name} code cell {cell_index}", "exec"), namespace)  # noqa: S102
    cell_index = "end"
    checking_show()  # figures left open (an animation's) are checked too
    return problems, shown


@pytest.mark.parametrize("name", CHAPTERS)
def test_every_figure_has_labelled_axes_and_states_its_scale(name, monkeypatch, capsys):
    problems, shown = run_chapter(name, monkeypatch)
    capsys.readouterr()  # the chapter's own printed output is not under test
    assert len(shown) >= 3, f"{name}: only {len(shown)} figures were checked"
    assert not problems, f"{name}: " + "; ".join(problems)


def test_the_check_catches_an_unlabelled_axis_and_an_unstated_scale():
    from twolink import arms, velocity

    figure, (ax_plain, ax_arm) = plt.subplots(1, 2)
    ax_plain.plot([0, 1], [0, 1])
    ax_plain.set_xlabel("t [s]")
    twolink.plot.setup_axes(arms.osake, ax_arm)
    twolink.plot.draw_ellipse(velocity.velocity_ellipse(arms.osake, [0.3, 1.0]), ax_arm, scale=0.4)
    problems = problems_in(figure, {ax_arm})
    assert any("y label ''" in problem for problem in problems)
    assert any("without 'N m per m/s'" in problem for problem in problems)
    ax_plain.set_ylabel("speed [m/s]")
    ax_arm.text(0.0, 0.0, "ellipse drawn at 0.4 m per m/s")
    assert problems_in(figure, {ax_arm}) == []
    plt.close(figure)


def test_chapter_1_names_the_transform_T_0_2_in_its_own_code():
    # the OSAKE source's name H_0^2 may appear in prose that attributes it; the course's own output says T_0^2
    offending = [source.splitlines()[0] for source in code_sources(CHAPTERS[0]) if re.search(r"H_0|H_\{?0|\bH_0?2", source)]
    assert not offending, f"chapter 1 code still writes H_0^2 for T_0^2: {offending}"
