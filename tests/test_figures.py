"""Every figure a reader sees, in every chapter: labelled axes, stated scales.

Each chapter's checked code cells run in this process (matplotlib's Agg
backend; IPython syntax such as ``%pip`` is translated as IPython would) and
every figure is inspected when the chapter calls ``plt.show()`` or hands an
animation to ``plot.animation_html`` (no video is encoded): both axes show a
quantity with a unit in brackets, and a figure that draws velocity ellipses or
velocity arrows on position axes says in its own text how many metres of
figure one m/s is.  An explorer (``twolink_course.explorer.Explorer``) is checked as
it is built, after every control was moved to its ends (and every option
chosen) without an error.  Cells nbval ignores (``# NBVAL_IGNORE_OUTPUT`` or the
tag ``nbval-ignore-output``: sliders and timings, which redraw what a checked
cell already drew, or only measure) are skipped.
"""

import json
import pathlib
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pytest  # noqa: E402
from IPython.core.inputtransformer2 import TransformerManager  # noqa: E402
from matplotlib.quiver import Quiver  # noqa: E402

import twolink_course.explorer  # noqa: E402
import twolink_course.plot  # noqa: E402
from twolink import arms, velocity  # noqa: E402

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "tools"))
import course_map  # noqa: E402

NOTEBOOK_DIR = pathlib.Path(__file__).resolve().parent.parent / "notebooks"
NOTEBOOKS = [path.name for path in course_map.chapters(NOTEBOOK_DIR)]

LABEL_WITH_UNIT = re.compile(r"\S.*\[[^\]]+\]")  # "x [m]", "joint rate [rad/s]"
# "0.4 m per m/s", "600 N/m = 0.4 m", "1 N drawn as 2 m"
SCALE_STATEMENT = re.compile(r"\d+(\.\d+)? m per \S+|(=|drawn as)\s*\d+(\.\d+)?\s*m\b")


def code_sources(name):
    """The chapter's code cells that nbval compares: a cell it ignores (a first-line
    ``# NBVAL_IGNORE_OUTPUT`` or the tag ``nbval-ignore-output``) is left out."""
    content = json.loads((NOTEBOOK_DIR / name).read_text(encoding="utf-8"))
    return [
        "".join(cell["source"])
        for cell in content["cells"]
        if cell["cell_type"] == "code"
        and "nbval-ignore-output" not in cell.get("metadata", {}).get("tags", [])
        and not "".join(cell["source"]).startswith("# NBVAL_IGNORE_OUTPUT")
    ]


def figure_texts(figure):
    texts = [figure.get_suptitle(), *(text.get_text() for text in figure.texts)]
    for ax in figure.axes:
        texts += [ax.get_title(), *(text.get_text() for text in ax.texts)]
    return " ".join(texts)


def labelled_by_a_sibling(ax, which):
    """True when ``ax`` shares that axis with a neighbour whose label states quantity and unit (subplots(sharey=True))."""
    shared = ax.get_shared_x_axes() if which == "x" else ax.get_shared_y_axes()
    labels = [
        sibling.get_xlabel() if which == "x" else sibling.get_ylabel()
        for sibling in shared.get_siblings(ax)
    ]
    return any(LABEL_WITH_UNIT.match(label) for label in labels)


def problems_in(figure, ellipse_axes):
    """What a reader would miss in ``figure``: unlabelled axes, ellipses or arrows without a scale."""
    found = []
    for ax in figure.axes:
        if not ax.axison or ax.get_label() == "<colorbar>":
            continue
        for which, label in (("x", ax.get_xlabel()), ("y", ax.get_ylabel())):
            if not LABEL_WITH_UNIT.match(label) and not labelled_by_a_sibling(
                ax, which
            ):
                found.append(
                    f"axes {ax.get_title()!r}: {which} label {label!r} has no quantity [unit]"
                )
        has_arrows = any(isinstance(artist, Quiver) for artist in ax.collections)
        if (ax in ellipse_axes or has_arrows) and not SCALE_STATEMENT.search(
            figure_texts(figure)
        ):
            found.append(
                f"axes {ax.get_title()!r}: ellipses or arrows on position axes without a scale such as '0.4 m per m/s'"
            )
    return found


def _extreme_values(control):
    """The values a hand can reach at the ends of a control (and every option of a choice)."""
    if hasattr(control, "options"):
        return list(control.options)
    if isinstance(control.value, tuple):  # a range slider
        return [
            (control.min, control.min),
            (control.max, control.max),
            (control.min, control.max),
        ]
    return [control.min, control.max]


def run_chapter(name, monkeypatch):
    """Run the chapter's checked code cells; return (problems, number of figures checked)."""
    problems, ellipse_axes, checked = [], set(), []
    where = {"cell": None}
    draw_ellipse = twolink_course.plot.draw_ellipse

    def recording_draw_ellipse(ellipse, *args, ax=None, **kwargs):
        ellipse_axes.add(plt.gca() if ax is None else ax)
        return draw_ellipse(ellipse, *args, ax=ax, **kwargs)

    def check_open_figures(*args, **kwargs):
        for number in plt.get_fignums():
            figure = plt.figure(number)
            checked.append(figure)
            problems.extend(
                f"code cell {where['cell']}: {problem}"
                for problem in problems_in(figure, ellipse_axes)
            )
            plt.close(figure)

    def checking_animation_html(anim, *args, **kwargs):
        check_open_figures()  # the animation's figure is still open here
        return None

    explorer_init = twolink_course.explorer.Explorer.__init__

    def checking_explorer(self, *args, **kwargs):
        """Build the explorer, then move every control to its ends and back:
        the figure must follow without an error and stay labelled."""
        explorer_init(self, *args, **kwargs)
        start = self.values
        for name, control in self.controls.items():
            for value in _extreme_values(control):
                try:
                    self.set(**{name: value})
                except Exception as error:  # noqa: BLE001 - reported with the value
                    problems.append(
                        f"code cell {where['cell']}: explorer control {name} = {value!r}: "
                        f"{type(error).__name__}: {error}"
                    )
            self.set(**start)
        checked.append(self.figure)
        problems.extend(
            f"code cell {where['cell']}: explorer: {problem}"
            for problem in problems_in(self.figure, ellipse_axes)
        )

    monkeypatch.setattr(twolink_course.plot, "draw_ellipse", recording_draw_ellipse)
    monkeypatch.setattr(twolink_course.plot, "animation_html", checking_animation_html)
    monkeypatch.setattr(twolink_course.explorer.Explorer, "__init__", checking_explorer)
    monkeypatch.setattr(plt, "show", check_open_figures)
    monkeypatch.chdir(NOTEBOOK_DIR)
    to_python = TransformerManager().transform_cell
    namespace = {"__name__": "__chapter__", "get_ipython": lambda: None}
    for index, source in enumerate(code_sources(name)):
        where["cell"] = index
        exec(compile(to_python(source), f"{name} code cell {index}", "exec"), namespace)  # noqa: S102
    where["cell"] = "end"
    check_open_figures()
    return problems, len(checked)


@pytest.mark.parametrize("name", NOTEBOOKS)
def test_every_figure_has_labelled_axes_and_states_its_scale(name, monkeypatch, capsys):
    problems, figures = run_chapter(name, monkeypatch)
    capsys.readouterr()  # the chapter's own printed output is not under test
    assert figures >= 3, f"{name}: only {figures} figures were checked"
    assert not problems, f"{name}: " + "; ".join(problems)


def test_the_check_catches_an_unlabelled_axis_and_an_unstated_scale():
    figure, (ax_plain, ax_arm) = plt.subplots(1, 2)
    ax_plain.plot([0, 1], [0, 1])
    ax_plain.set_xlabel("t [s]")
    ax_plain.set_ylabel("angle")
    twolink_course.plot.setup_axes(arms.osake, ax=ax_arm)
    twolink_course.plot.draw_ellipse(
        velocity.velocity_ellipse(arms.osake, [0.3, 1.0]), ax=ax_arm, scale=0.4
    )
    problems = problems_in(figure, {ax_arm})
    assert any(
        "y label 'angle' has no quantity [unit]" in problem for problem in problems
    )
    assert any(
        "without a scale such as '0.4 m per m/s'" in problem for problem in problems
    )
    ax_plain.set_ylabel("angle [deg]")
    ax_arm.text(0.0, 0.0, "ellipse drawn at 0.4 m per m/s")
    assert problems_in(figure, {ax_arm}) == []
    plt.close(figure)
