"""twolink.ik.turns: joint angles moved by whole turns into the limits; the free q1 at the base."""

import numpy as np
import pytest
from _cases import limited_arms
from hypothesis import example, given
from hypothesis import strategies as st

from twolink import (
    TwoLinkArm,
    arms,
    ik,
)
from twolink.ik import turns


@given(arm=limited_arms(), q1=st.floats(-10.0, 10.0), q2=st.floats(-10.0, 10.0))
@example(  # the representative is on the lower limit, the angle a hair below it
    arm=TwoLinkArm(1.0, 1.0, q_min=(1e-7, 0.0), q_max=(1.0000001, 1.0)),
    q1=-1.8935882091744493e-290,
    q2=0.0,
)
def test_move_into_limits_turns_angles_by_whole_turns_only_where_that_helps(
    arm, q1, q2
):
    q = np.array([q1, q2])
    moved, inside = turns.move_into_limits(arm, q)
    assert np.allclose(
        arm.fk(moved), arm.fk(q), atol=1e-12 * arm.reach[1] + 1e-12
    )  # the same pose
    whole_turns = (moved - q) / (2 * np.pi)
    assert np.allclose(whole_turns, np.round(whole_turns), atol=1e-9)
    assert bool(inside) == bool(arm.within_limits(moved, tol=ik.LIMIT_TOL))
    if arm.within_limits(q, tol=ik.LIMIT_TOL):
        assert np.array_equal(moved, q)  # already inside: exactly as given


def test_an_arm_without_limits_keeps_every_configuration():
    q = np.array([[7.0, -9.0], [0.1, 0.2]])
    moved, inside = turns.move_into_limits(arms.two_metre, q)
    assert np.array_equal(moved, q) and moved is not q
    assert inside.tolist() == [True, True]


def test_absolute_limits_turn_link_angles():
    """Link 2 at 35 deg + a whole turn is turned back to 35 deg; q1 is untouched."""
    arm = arms.two_metre_limited
    q = np.radians([40.0, 355.0])  # link 2 at 395 deg
    moved, inside = turns.move_into_limits(arm, q)
    assert bool(inside)
    assert np.allclose(np.degrees(moved), [40.0, -5.0])


@pytest.mark.parametrize("tol", [-1e-3, np.nan, "0.1"], ids=repr)
def test_move_into_limits_refuses_a_tolerance_that_is_no_slack(tol):
    with pytest.raises(ValueError, match="tol"):
        turns.move_into_limits(arms.ten, [0.1, 0.2], tol=tol)


@given(arm=limited_arms())
def test_the_q1_chosen_at_the_base_folds_the_arm_within_its_limits(arm):
    equal = TwoLinkArm(
        arm.l1,
        arm.l1,
        q_min=arm.q_min,
        q_max=arm.q_max,
        limit_convention=arm.limit_convention,
    )
    at_base, q1 = turns.free_q1_at_base(equal, np.zeros((1, 2)))
    assert at_base.tolist() == [True]
    if q1 is not None:
        folded = np.array([q1, np.pi])
        assert bool(turns.move_into_limits(equal, folded)[1])
        assert np.allclose(equal.fk(folded), 0.0, atol=1e-12 * equal.l1)


def test_free_q1_at_base_only_for_equal_links_and_points_at_the_base():
    at_base, q1 = turns.free_q1_at_base(TwoLinkArm(1.0, 1.5), np.zeros((2, 2)))
    assert at_base.tolist() == [False, False] and q1 is None
    at_base, q1 = turns.free_q1_at_base(
        arms.two_metre, np.array([[0.0, 0.0], [0.1, 0.0]])
    )
    assert at_base.tolist() == [True, False] and q1 is None  # no limits: any q1


def test_the_limit_tolerance_is_the_one_of_ik():
    assert turns.LIMIT_TOL == ik.LIMIT_TOL
