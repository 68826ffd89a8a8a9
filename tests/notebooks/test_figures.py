"""Every figure a reader sees, in every chapter: labelled axes, stated scales.

The chapters are checked in nbval's own run of them (``make test`` executes
each chapter once): ``tests/notebooks/chapter_checks.py`` records in the
chapter's kernel every figure it displays and every animation's figure, and
adds ``notebooks/NN_x.ipynb::figures``, which fails when one of them has an
axis without a quantity and a unit in brackets, or draws velocity ellipses or
arrows on position axes without saying how many metres of figure one m/s is,
or when an explorer fails or loses its labels with a control at one of its
ends (``tests/notebooks/chapter_kernel.py``).  Here: the rule itself.
"""

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from chapter_kernel import problems_in  # noqa: E402

import twolink_course.plot  # noqa: E402
from twolink import arms, velocity  # noqa: E402


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
