"""What the chapter checks do inside a chapter's own kernel, while nbval runs it.

``tests/notebooks/chapter_checks.py`` sends this file's source to the kernel
nbval starts for a chapter, before the chapter's first cell, and calls
:func:`install`; after the last cell it asks for :func:`figure_report` and
:func:`exercise_report`.  The chapter runs once, as nbval runs it: nothing here
prints, displays or changes what a cell outputs.

Figures a reader sees: every figure the chapter displays (``plt.show()``, a
figure as a cell's value, the end of a cell) is checked as IPython formats it,
and an animation's figure when it is handed to ``plot.animation_html``: both
axes show a quantity with a unit in brackets, and a figure that draws velocity
ellipses or velocity arrows on position axes says in its own text how many
metres of figure one m/s is.  An explorer (``twolink_course.explorer.Explorer``)
is remembered when it is built; at the end every control is moved to its ends
(and every option chosen): the figure must follow without an error and stay
labelled.

Exercises: every self-check the chapter calls is recorded, and at the end each
exercise's worked solution must have been checked "correct" in every part, its
student-edition stub (run in the chapter's final state) must make the check say
"not solved yet" in every part, and a function part's worked solution must pass
hidden cases drawn with a seed the notebook never holds.
"""

import contextlib
import io
import re
import sys

LABEL_WITH_UNIT = re.compile(r"\S.*\[[^\]]+\]")  # "x [m]", "joint rate [rad/s]"
# "0.4 m per m/s", "600 N/m = 0.4 m", "1 N drawn as 2 m"
SCALE_STATEMENT = re.compile(r"\d+(\.\d+)? m per \S+|(=|drawn as)\s*\d+(\.\d+)?\s*m\b")


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
    from matplotlib.quiver import Quiver

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


def extreme_values(control):
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


class _Record:
    """What the chapter did so far: the cell it is in, figures checked, problems, explorers, verdicts."""

    def __init__(self):
        self.cell = (
            -1
        )  # the code cell running (nbval's "Cell N"), counted by IPython's pre_run_cell
        self.figures = 0
        self.problems = []
        self.ellipse_axes = set()
        self.explorers = []
        self.verdicts = {}  # exercise number -> [status of each part], as its check cell said
        self.originals = {}


RECORD = _Record()


def _check_figure(figure, what="figure"):
    RECORD.figures += 1
    RECORD.problems.extend(
        f"code cell {RECORD.cell}: {what}: {problem}"
        for problem in problems_in(figure, RECORD.ellipse_axes)
    )


def install():
    """Start recording (before the chapter's first cell): wrap what the chapter calls, change nothing it shows."""
    import matplotlib.pyplot as plt
    from IPython import get_ipython
    from matplotlib.figure import Figure

    import twolink_course.explorer
    import twolink_course.plot
    import twolink_course.selfcheck

    shell = get_ipython()

    def count_cell(info):
        RECORD.cell += 1

    shell.events.register("pre_run_cell", count_cell)

    formatter = shell.display_formatter
    format_object = formatter.format

    def format_checking_figures(obj, *args, **kwargs):
        if isinstance(obj, Figure):
            _check_figure(obj)
        return format_object(obj, *args, **kwargs)

    formatter.format = format_checking_figures

    plot = twolink_course.plot
    draw_ellipse, animation_html = plot.draw_ellipse, plot.animation_html

    def recording_draw_ellipse(ellipse, *args, ax=None, **kwargs):
        RECORD.ellipse_axes.add(plt.gca() if ax is None else ax)
        return draw_ellipse(ellipse, *args, ax=ax, **kwargs)

    def checking_animation_html(anim, *args, **kwargs):
        for number in plt.get_fignums():  # the animation's figure is still open here
            _check_figure(plt.figure(number), "animation")
        return animation_html(anim, *args, **kwargs)

    plot.draw_ellipse = recording_draw_ellipse
    plot.animation_html = checking_animation_html

    explorer_class = twolink_course.explorer.Explorer
    explorer_init = explorer_class.__init__

    def remembering_init(self, *args, **kwargs):
        explorer_init(self, *args, **kwargs)
        RECORD.explorers.append((RECORD.cell, self))

    explorer_class.__init__ = remembering_init

    selfcheck = twolink_course.selfcheck
    check = selfcheck.check
    RECORD.originals["check"] = check

    def recording_check(exercise, *answers, **named_answers):
        report = check(exercise, *answers, **named_answers)
        RECORD.verdicts[exercise] = [result.status for result in report]
        return report

    selfcheck.check = recording_check


def _sweep(cell, explorer):
    """Move every control of ``explorer`` to its ends and back, then check its figure."""
    start = explorer.values
    for name, control in explorer.controls.items():
        for value in extreme_values(control):
            try:
                explorer.set(**{name: value})
            except Exception as error:  # noqa: BLE001 - reported with the value
                RECORD.problems.append(
                    f"code cell {cell}: explorer control {name} = {value!r}: "
                    f"{type(error).__name__}: {error}"
                )
    explorer.set(**start)
    RECORD.figures += 1
    RECORD.problems.extend(
        f"code cell {cell}: explorer: {problem}"
        for problem in problems_in(explorer.figure, RECORD.ellipse_axes)
    )


def figure_report():
    """After the last cell: sweep the explorers; ``{"figures": count checked, "problems": [...]}``."""
    for cell, explorer in RECORD.explorers:
        _sweep(cell, explorer)
    RECORD.explorers.clear()
    return {"figures": RECORD.figures, "problems": sorted(set(RECORD.problems))}


def exercise_report(exercises, root, seed, namespace=None):
    """After the last cell: what is wrong with each exercise's solution, stub and hidden cases.

    ``exercises`` lists ``{"number", "parts", "stub", "functions"}``: the part
    names in order, the solution cell as the student edition stubs it, and the
    function parts; ``root`` is the repository (for ``answers``), ``seed`` the
    hidden cases' seed; ``namespace`` the chapter's (the kernel's by default).
    """
    import matplotlib.pyplot as plt

    from twolink_course import exercises as exercise_specs
    from twolink_course.exercises import judging

    if namespace is None:
        from IPython import get_ipython

        namespace = get_ipython().user_ns
    check = RECORD.originals["check"]
    problems = []
    for exercise in exercises:
        number, parts = exercise["number"], exercise["parts"]
        said = RECORD.verdicts.get(number)
        if said is None:
            problems.append(f"exercise {number}: its self-check never ran")
        elif set(said) != {"correct"}:
            problems.append(
                f"exercise {number}: the worked solution's self-check said {said}"
            )
        student = dict(namespace)
        with contextlib.redirect_stdout(io.StringIO()):
            exec(compile(exercise["stub"], f"stub of {number}", "exec"), student)  # noqa: S102
            report = check(number, *(student.get(name, ...) for name in parts))
        plt.close("all")
        statuses = [result.status for result in report]
        if set(statuses) != {"not solved yet"}:
            problems.append(
                f"exercise {number}: the student edition's stub made the check say {statuses}"
            )
        for name in exercise["functions"]:
            if root not in sys.path:
                sys.path.insert(0, root)
            import answers

            part = next(p for p in exercise_specs.get(number).parts if p.name == name)
            hidden = answers.hidden_cases(number, name, seed=seed)
            verdict = judging.judge_function(part, namespace[name], hidden)
            if not verdict.right:
                problems.append(
                    f"exercise {number}: {name} fails hidden cases: {verdict.message}"
                )
    return problems
