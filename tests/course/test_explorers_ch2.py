"""Chapter 2's explorer and figures (twolink_course.explorers.ch2): both IK branches, the tip-error map."""

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from twolink import TwoLinkArm, arms, ik  # noqa: E402
from twolink_course import alttext  # noqa: E402
from twolink_course.explorers import ch2  # noqa: E402

SLIDER = st.integers(-44, 44).map(lambda half_metres: half_metres / 2)  # -22 to 22 m


@pytest.fixture(scope="module")
def view():
    return ch2.TargetBranches(arms.ten)


@settings(max_examples=60, deadline=None)
@given(x=SLIDER, y=SLIDER)
def test_a_move_shows_both_branches_or_says_why_there_are_none(view, x, y):
    view.update(x=x, y=y)
    sentence = view.describe(x=x, y=y)
    assert np.allclose(view.target_mark.get_xydata(), [[x, y]])
    reachable = arms.ten.reach[0] <= np.hypot(x, y) <= arms.ten.reach[1]
    if not reachable:
        assert not any(line.get_visible() for line in view.branch_lines)
        assert sentence.startswith("No solution: target")
        assert sum(note.get_visible() for note in view.notes.values()) == 1
        return
    q_both = ik.closed_form(arms.ten, [x, y], elbow="both").q
    for line, q, role in zip(view.branch_lines, q_both, ch2.BRANCH_ROLES):
        assert line.get_visible()
        assert np.allclose(line.get_xydata(), arms.ten.joint_positions(q))
        within = bool(arms.ten.within_limits(q))
        assert line.get_linestyle() == (
            "--" if role.linestyle == "--" and within else line.get_linestyle()
        )
        assert (line.get_linestyle() == ":") == (not within)
        assert ("within limits" if within else "outside limits") in sentence
    assert not any(note.get_visible() for note in view.notes.values())


def test_the_note_for_a_target_out_of_reach_sits_in_the_corner_away_from_it(view):
    view.update(x=18.0, y=12.0)
    assert (
        view.notes["lower left"].get_visible()
        and "21.63 m" in view.notes["lower left"].get_text()
    )
    view.update(x=-18.0, y=-12.0)
    assert (
        view.notes["upper right"].get_visible()
        and not view.notes["lower left"].get_visible()
    )


def test_the_axes_and_the_legend_never_move(view):
    before = view.ax.get_xlim(), view.ax.get_ylim()
    for x, y in ((22.0, 22.0), (-22.0, -22.0), (5.0, 15.0), (0.0, 0.0)):
        view.update(x=x, y=y)
    assert (view.ax.get_xlim(), view.ax.get_ylim()) == before
    assert view.ax.get_legend().get_zorder() < min(
        line.get_zorder() for line in view.branch_lines
    )


def test_draw_branches_draws_each_target_s_two_branches():
    fig, axes = plt.subplots(1, 2)
    try:
        found = ch2.draw_branches(
            arms.ten, [(15.0, 10.0), (-15.0, 10.0)], ["a", "b"], axes
        )
        for q_both, p in zip(found, [(15.0, 10.0), (-15.0, 10.0)]):
            assert np.allclose(arms.ten.fk(q_both), [p, p])
            assert q_both[0, 1] >= 0 >= q_both[1, 1]
        said = alttext.describe(fig)
        assert "The target at (15.00, 10.00) m" in said and "(-15.00, 10.00)" in said
    finally:
        plt.close(fig)


@pytest.mark.parametrize(
    "lengths, p",
    [
        ((10.0, 10.0), (15.0, 10.0)),
        ((6.0, 12.0), (10.0, 12.0)),
        ((12.0, 5.0), (12.0, 9.0)),
    ],
)
def test_the_error_map_is_smallest_at_a_closed_form_branch_within_the_limits(
    lengths, p
):
    arm = TwoLinkArm(*lengths, q_min=arms.ten.q_min, q_max=arms.ten.q_max)
    q_both = ik.closed_form(arm, p, elbow="both").q
    assert arm.within_limits(q_both).any()
    fig, ax = plt.subplots()
    try:
        answer = ik.brute_force(arm, p, step=np.radians(2.0))
        errors = ch2.draw_tip_error_map(arm, p, answer.q, np.radians(2.0), ax=ax)
        assert errors.shape == (181, 361) and errors.min() >= 0
        # the map's spacing is half a degree: some point lies within a quarter degree of a root
        assert errors.min() <= (arm.l1 + 2 * arm.l2) * np.radians(0.5) / 2
        assert "tip error [m]" in [other.get_ylabel() for other in fig.axes]
        said = alttext.describe(fig)
        assert "two basins of small error" in said and "0.5, 1 and 2 m" in said
    finally:
        plt.close(fig)


def test_the_error_map_needs_joint_limits():
    fig, ax = plt.subplots()
    try:
        with pytest.raises(ValueError, match="arm must have joint limits"):
            ch2.draw_tip_error_map(arms.two_metre, [1.0, 1.0], [0.0, 0.0], 0.1, ax=ax)
    finally:
        plt.close(fig)
