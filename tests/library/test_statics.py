"""Statics: the wall problem solved in closed form, its torques, and bad input."""

import dataclasses

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from conftest import angles, unit
from conftest import arms as arm_strategy
from twolink import TwoLinkArm, UnreachableError, Wall, arms, wall_contact

forces = st.floats(min_value=0.0, max_value=1e4, allow_nan=False, allow_infinity=False)


def cross(a, b):
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


@st.composite
def reachable_walls(draw, arm):
    """A wall at a distance the condition allows, any direction, given by any of its points and either normal sign."""
    r_low, r_high = abs(arm.l2 - arm.l1), arm.l1 + arm.l2
    distance = r_low + draw(unit) * (r_high - r_low)
    heading = draw(angles)
    normal = np.array([np.cos(heading), np.sin(heading)])
    along = np.array([-normal[1], normal[0]])
    point = distance * normal + draw(st.floats(-10.0, 10.0)) * along
    sign = draw(st.sampled_from([1.0, -1.0]))
    return Wall(point, sign * draw(st.floats(0.1, 10.0)) * normal), normal, distance


def expected_push_direction(contact, normal, distance, scale):
    """Away from the base; for a wall (within round-off) through the base either side is right."""
    if distance > 1e-9 * scale:
        return normal
    return normal if contact.wall.into_wall() @ normal >= 0 else -normal


@given(data=st.data(), arm=arm_strategy(), force=forces)
def test_the_contact_lies_on_the_wall_with_link_2_perpendicular(data, arm, force):
    wall, normal, distance = data.draw(reachable_walls(arm))
    contact = wall_contact(arm, wall, force)
    scale = arm.l1 + arm.l2
    normal_in = expected_push_direction(contact, normal, distance, scale)
    assert len(contact.elbow) == len(contact.q) in (1, 2)
    assert np.allclose(
        contact.force_by_tip, force * normal_in, atol=1e-12 * (1 + force)
    )
    points = arm.joint_positions(contact.q)
    for elbow_point, tip in zip(points[:, 1], points[:, 2]):
        assert (
            abs(wall.signed_distance(tip)) <= 1e-9 * scale
        )  # the tip touches the wall
        link_2 = (tip - elbow_point) / arm.l2
        assert np.allclose(
            link_2, normal_in, atol=1e-9 * scale / min(arm.l1, arm.l2)
        )  # and pushes straight into it
    assert np.allclose(contact.p_contact, points[:, 2])


@given(data=st.data(), arm=arm_strategy(), force=forces)
def test_both_branches_mirror_each_other_about_the_normal_through_the_base(
    data, arm, force
):
    wall, normal, distance = data.draw(reachable_walls(arm))
    contact = wall_contact(arm, wall, force)
    normal_in = expected_push_direction(contact, normal, distance, arm.l1 + arm.l2)
    if len(contact.q) == 2:
        assert contact.elbow == ("down", "up")
        assert contact.q[0, 1] > 0 > contact.q[1, 1]
        assert contact.q[0, 1] == pytest.approx(-contact.q[1, 1])
        offsets = cross(
            normal_in, contact.p_contact
        )  # signed position along the wall, from the foot of the normal
        assert offsets[0] == pytest.approx(-offsets[1], abs=1e-9 * (arm.l1 + arm.l2))


@given(data=st.data(), arm=arm_strategy(), force=forces)
def test_torques_are_the_free_body_moments(data, arm, force):
    """tau1 = moment of F about the base, tau2 = about the elbow (zero: F acts along link 2)."""
    wall, _, _ = data.draw(reachable_walls(arm))
    contact = wall_contact(arm, wall, force)
    points = arm.joint_positions(contact.q)
    tau1 = cross(points[:, 2], contact.force_by_tip)
    tau2 = cross(points[:, 2] - points[:, 1], contact.force_by_tip)
    tolerance = 1e-9 * (arm.l1 + arm.l2) * (1 + force)
    assert np.allclose(contact.tau_wall[:, 0], tau1, atol=tolerance)
    assert np.allclose(contact.tau_wall[:, 1], tau2, atol=tolerance)
    assert np.allclose(contact.tau_wall[:, 1], 0.0, atol=tolerance)
    assert np.allclose(
        contact.tau_wall,
        arm.joint_torques(
            contact.q, np.broadcast_to(contact.force_by_tip, contact.q.shape)
        ),
    )
    assert (
        np.array_equal(contact.tau, contact.tau_wall) and not contact.tau_gravity.any()
    )


def test_the_course_wall_by_hand():
    """x + y = 4, l1 = l2 = 2 m, 500 N: cos(q1 - 45 deg) = (2 sqrt2 - 2) / 2 = sqrt2 - 1."""
    contact = wall_contact(arms.two_metre, Wall.through([4.0, 0.0], [0.0, 4.0]), 500.0)
    angle = np.arccos(np.sqrt(2.0) - 1.0)
    assert np.allclose(
        contact.q, [[np.pi / 4 - angle, angle], [np.pi / 4 + angle, -angle]]
    )
    assert np.allclose(contact.p_contact.sum(axis=1), 4.0)
    assert np.allclose(
        contact.force_by_tip, 500.0 / np.sqrt(2.0) * np.ones(2)
    )  # into the wall, away from the base
    tau1 = 500.0 * 2.0 * np.sin(angle)  # F times the lever arm l1 sin(angle) of link 1
    assert np.allclose(contact.tau, [[tau1, 0.0], [-tau1, 0.0]], atol=1e-9)
    assert contact.within_limits.tolist() == [True, True]
    assert contact.q[contact.branch("up"), 1] < 0
    with pytest.raises(ValueError, match="elbow must be one of .* got 'stretched'"):
        contact.branch("stretched")


def test_wall_given_by_point_and_normal_or_two_points_or_either_normal_sign():
    reference = wall_contact(
        arms.two_metre, Wall.through([4.0, 0.0], [0.0, 4.0]), 500.0
    )
    for wall in (
        Wall([2.0, 2.0], [1.0, 1.0]),
        Wall([0.0, 4.0], [-3.0, -3.0]),
        Wall.through([0.0, 4.0], [4.0, 0.0]),
    ):
        contact = wall_contact(arms.two_metre, wall, 500.0)
        assert np.allclose(contact.q, reference.q) and np.allclose(
            contact.tau, reference.tau
        )


def test_the_wall_at_full_reach_gives_one_stretched_configuration_without_torque():
    contact = wall_contact(arms.two_metre, Wall([0.0, 4.0], [0.0, 1.0]), 100.0)
    assert contact.elbow == ("stretched",)
    assert np.allclose(contact.q, [[np.pi / 2, 0.0]])
    assert np.allclose(
        contact.tau, 0.0, atol=1e-9
    )  # the straight arm carries the force in compression
    round_off = wall_contact(
        arms.two_metre, Wall([4.0 / np.sqrt(2.0)] * 2, [1.0, 1.0]), 100.0
    )
    assert (
        Wall([4.0 / np.sqrt(2.0)] * 2, [1.0, 1.0]).distance_from_base() != 4.0
    )  # 1 ulp short of the reach
    assert round_off.elbow == ("stretched",) and np.allclose(
        round_off.q, [[np.pi / 4, 0.0]]
    )
    folded = wall_contact(TwoLinkArm(1.0, 3.0), Wall([2.0, 0.0], [1.0, 0.0]), 100.0)
    assert folded.elbow == ("folded",) and np.allclose(folded.p_contact, [[2.0, 0.0]])


def test_a_wall_through_the_base_uses_the_given_normal():
    contact = wall_contact(TwoLinkArm(2.0, 1.0), Wall([0.0, 0.0], [0.0, -1.0]), 10.0)
    assert np.allclose(contact.force_by_tip, [0.0, -10.0])
    assert np.allclose(contact.p_contact[:, 1], 0.0, atol=1e-12)


def test_joint_limits_are_reported_per_branch():
    limited = dataclasses.replace(
        arms.two_metre, q_min=(-np.pi, 0.0), q_max=(np.pi, np.pi)
    )
    contact = wall_contact(limited, Wall.through([4.0, 0.0], [0.0, 4.0]), 500.0)
    assert contact.within_limits.tolist() == [True, False]


def test_gravity_torques_are_added_when_asked():
    arm = TwoLinkArm(2.0, 2.0, m1=3.0, m2=2.0, g=9.81)
    if not hasattr(arm, "gravity"):
        pytest.skip("TwoLinkArm.gravity (the dynamics chapter) is not there yet")
    wall = Wall.through([4.0, 0.0], [0.0, 4.0])
    contact = wall_contact(arm, wall, 500.0, include_gravity=True)
    q1, q12 = contact.q[:, 0], contact.q.sum(axis=1)
    # uniform rods: the weights m g act at mid-link; g_i is the moment of the weights about joint i
    g2 = arm.m2 * arm.g * arm.l2 / 2 * np.cos(q12)
    g1 = (arm.m1 / 2 + arm.m2) * arm.g * arm.l1 * np.cos(q1) + g2
    assert np.allclose(contact.tau_gravity, np.stack([g1, g2], axis=1))
    assert np.allclose(contact.tau, contact.tau_wall + contact.tau_gravity)
    assert np.allclose(contact.tau_wall, wall_contact(arm, wall, 500.0).tau)


@pytest.mark.parametrize(
    ("wall", "message"),
    [
        (
            Wall([5.0, 0.0], [1.0, 0.0]),
            r"the wall is 5 m from the base; .* distances in \[0, 4\] m",
        ),
        (Wall([0.0, -4.5], [0.0, 1.0]), r"4.5 m from the base"),
    ],
)
def test_a_wall_out_of_reach_raises_unreachable(wall, message):
    with pytest.raises(UnreachableError, match=message):
        wall_contact(arms.two_metre, wall, 100.0)


def test_a_wall_too_close_for_a_long_link_2_raises_unreachable():
    with pytest.raises(UnreachableError, match=r"0.5 m from the base; .* \[1, 5\] m"):
        wall_contact(TwoLinkArm(2.0, 3.0), Wall([0.5, 0.0], [1.0, 0.0]), 100.0)


@pytest.mark.parametrize(
    ("point", "normal", "message"),
    [
        ([1.0, 0.0], [0.0, 0.0], "non-zero"),
        ([np.nan, 0.0], [1.0, 0.0], "finite"),
        ([1.0, 0.0], [np.inf, 0.0], "finite"),
        ([1.0, 0.0, 2.0], [1.0, 0.0], "shape"),
        ([[1.0, 0.0]], [1.0, 0.0], "shape"),
    ],
)
def test_bad_walls_raise_value_error(point, normal, message):
    with pytest.raises(ValueError, match=message):
        Wall(point, normal)


def test_bad_arguments_raise_value_error():
    wall = Wall.through([4.0, 0.0], [0.0, 4.0])
    for force in (-1.0, np.nan, np.inf, "big"):
        with pytest.raises(ValueError, match="force_magnitude"):
            wall_contact(arms.two_metre, wall, force)
    with pytest.raises(ValueError, match="distinct points"):
        Wall.through([1.0, 1.0], [1.0, 1.0])
    with pytest.raises(ValueError, match="must be a twolink.statics.Wall"):
        wall_contact(arms.two_metre, ([4.0, 0.0], [0.0, 4.0]), 500.0)
