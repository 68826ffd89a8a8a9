"""twolink.contact: the spring wall's force and the tip force added to a controller's torques."""

import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

from conftest import configurations, dynamic_arms
from twolink import arms, dynamics, statics
from twolink.contact import SpringWall, TipForce
from twolink.controllers import (
    CartesianSpring,
)

WALL = statics.Wall.through([4.0, 0.0], [0.0, 4.0])
ZERO = np.zeros(2)


def test_spring_wall_pushes_out_only_from_inside():
    wall = SpringWall(WALL, stiffness=1e4, damping=100.0)
    normal = np.array([1.0, 1.0]) / np.sqrt(2.0)
    outside, on_wall, inside = [2.0, 1.0], [2.0, 2.0], [2.0, 2.0] + 0.01 * normal
    assert np.array_equal(wall.force_on_tip(outside, [5.0, 5.0]), ZERO)
    assert np.array_equal(wall.force_on_tip(on_wall, ZERO), ZERO)
    assert np.allclose(
        wall.force_on_tip(inside, ZERO), -100.0 * normal
    )  # k s = 1e4 * 0.01
    assert np.allclose(
        wall.force_on_tip(inside, 0.5 * normal), -150.0 * normal
    )  # moving in: damping adds
    assert np.array_equal(
        wall.force_on_tip(inside, -5.0 * normal), ZERO
    )  # leaving fast: never pulls
    assert wall.penetration([[2.0, 1.0], inside]).tolist() == pytest.approx([0.0, 0.01])


@given(
    dynamic_arms(),
    configurations(),
    st.tuples(st.floats(-50, 50), st.floats(-50, 50)).map(np.array),
)
def test_a_constant_force_on_tip_is_the_dynamics_force_by_tip_of_the_opposite_sign(
    arm, q, push
):
    """A push F on the tip is the same as the tip exerting -F (dynamics' convention)."""
    qd = np.array([0.3, -0.2])
    pushed = TipForce(arm, lambda t, q_now, qd_now: arm.gravity(q_now), push)
    via_tip_force = arm.forward_dynamics(q, qd, pushed(0.0, q, qd))
    via_dynamics = dynamics.forward_dynamics(
        arm, q, qd, arm.gravity(q), force_by_tip=-push
    )
    assert np.allclose(via_tip_force, via_dynamics, rtol=1e-9, atol=1e-9)
    assert np.array_equal(pushed.force_on_tip_at(0.0, q, qd), push)


@given(
    dynamic_arms(),
    configurations(),
    st.tuples(st.floats(-3, 3), st.floats(-3, 3)).map(np.array),
    st.floats(0.05, 0.5),
    st.floats(1.0, 1e4),
    st.floats(0.0, 100.0),
)
def test_a_spring_walls_force_on_tip_and_force_by_tip_give_the_same_dynamics(
    arm, q, qd, depth, k, c
):
    """The two conventions agree: the wall's force_on_tip F enters as + J^T F, force_by_tip = -F as - J^T (-F)."""
    p_tip = arm.fk(q)
    distance = float(np.hypot(*p_tip))
    assume(distance > 1e-3 * (arm.l1 + arm.l2))
    normal = (
        p_tip / distance
    )  # the wall across the radius, the tip depth * |p| inside it
    wall = SpringWall(
        statics.Wall(p_tip - depth * distance * normal, normal), stiffness=k, damping=c
    )
    v_tip = arm.jacobian(q) @ qd
    F = wall.force_on_tip(p_tip, v_tip)
    assume(np.any(F != 0.0))
    assert F @ normal < 0.0  # the wall pushes the tip back out, towards the base's side
    world = TipForce(arm, None, wall)
    assert np.array_equal(world.force_on_tip_at(0.0, q, qd), F)
    tau_motor = np.array([0.7, -0.4]) * (1.0 + np.abs(arm.gravity(q)))
    scale = 1.0 + np.abs(tau_motor).sum() + (arm.l1 + arm.l2) * np.abs(F).sum()
    # forward: the surroundings' push adds J^T F to the motors' torques ...
    with_push = arm.forward_dynamics(q, qd, tau_motor + world(0.0, q, qd))
    as_exerted = dynamics.forward_dynamics(arm, q, qd, tau_motor, force_by_tip=-F)
    M_inverse = np.abs(np.linalg.inv(arm.mass_matrix(q))).max()
    assert np.allclose(with_push, as_exerted, rtol=0.0, atol=1e-12 * M_inverse * scale)
    # ... and inverse: that motion needs the motors' torques less J^T F
    qdd = np.array([0.5, -1.5])
    needed = dynamics.inverse_dynamics(arm, q, qd, qdd, force_by_tip=-F)
    assert np.allclose(
        needed,
        arm.inverse_dynamics(q, qd, qdd) - world(0.0, q, qd),
        rtol=0.0,
        atol=1e-12 * scale,
    )
    # statics: the motors hold a force_on_tip F with tau = -J^T F = J^T force_by_tip
    held = arm.joint_torques(q, -F) + arm.gravity(q)
    at_rest = np.zeros(2)
    still = arm.forward_dynamics(
        q, at_rest, held + TipForce(arm, None, F)(0.0, q, at_rest)
    )
    assert np.allclose(still, 0.0, atol=1e-12 * M_inverse * scale)


def test_bad_contact_parameters_raise():
    with pytest.raises(ValueError, match="wall stiffness"):
        SpringWall(WALL, stiffness=-1.0)
    with pytest.raises(ValueError, match="wall damping"):
        SpringWall(WALL, stiffness=1.0, damping=np.nan)
    with pytest.raises(ValueError, match="must be a twolink.statics.Wall"):
        SpringWall("x + y = 4", stiffness=1.0)
    with pytest.raises(ValueError, match="TipForce's arm must be a twolink.TwoLinkArm"):
        TipForce("arm", None, [1.0, 2.0])
    with pytest.raises(
        ValueError, match="CartesianSpring's arm must be a twolink.TwoLinkArm"
    ):
        CartesianSpring(None, 600.0, [3.0, 1.0])
    with pytest.raises(ValueError, match=r"force_on_tip must have shape \(\.\.\., 2\)"):
        TipForce(arms.two_metre, None, [1.0, 2.0, 3.0])
    with pytest.raises(
        ValueError,
        match=r"force_on_tip must be one force \(Fx, Fy\) of shape \(2,\) \(N\); got shape \(1, 2\)",
    ):
        TipForce(arms.two_metre, None, [[1.0, 2.0]])
    with pytest.raises(ValueError, match="controller must be None or a callable"):
        TipForce(arms.two_metre, 3.0, [1.0, 2.0])


# ---------------------------------------------------------------- shape mismatches name the arguments
@pytest.mark.parametrize(
    "call, fragment",
    [
        (
            lambda: TipForce(arms.two_metre, None, [1.0, 0.0])(
                0.0, np.zeros((3, 2)), np.zeros((3, 2))
            ),
            r"q must be one configuration of shape \(2,\) \(radians\); got shape \(3, 2\)",
        ),
        (
            lambda: TipForce(arms.two_metre, None, lambda t, p, v: [1.0, 2.0, 3.0])(
                0.0, [0.1, 0.2], [0.0, 0.0]
            ),
            r"force_on_tip\(t, p_tip, v_tip\) must have shape \(\.\.\., 2\)",
        ),
        (
            lambda: TipForce(arms.two_metre, None, lambda t, p, v: np.zeros((2, 2)))(
                0.0, [0.1, 0.2], [0.0, 0.0]
            ),
            r"force_on_tip\(t, p_tip, v_tip\) must return shape \(2,\)",
        ),
        (
            lambda: TipForce(
                arms.two_metre, lambda t, q, qd: np.zeros((3, 2)), [1.0, 0.0]
            )(0.0, [0.1, 0.2], [0.0, 0.0]),
            r"controller\(t, q, qd\) must return shape \(2,\)",
        ),
    ],
)
def test_shape_mismatches_name_the_arguments_and_their_shapes(call, fragment):
    with pytest.raises(ValueError, match=fragment):
        call()


def test_a_spring_wall_in_tip_force_still_works():
    wall = SpringWall(WALL, stiffness=1e5)
    pushed = TipForce(arms.two_metre, None, wall)
    assert pushed(0.0, np.array([0.0, 0.0]), np.zeros(2)).shape == (2,)


# ---------------------------------------------------------------- the wall's force
@given(
    st.floats(-1.0, 1.0),
    st.floats(-5.0, 5.0),
    st.floats(-5.0, 5.0),
    st.floats(1.0, 1e6),
    st.floats(0.0, 1e4),
)
def test_a_spring_wall_never_pulls_and_pushes_k_s_plus_c_v_along_the_normal(
    depth, along, speed_in, k, c
):
    assume(abs(depth) > 1e-9)  # on the surface itself, round-off decides inside or out
    wall = SpringWall(WALL, stiffness=k, damping=c)
    normal = wall.normal
    tangent = np.array([-normal[1], normal[0]])
    p = WALL.point + depth * normal + along * tangent
    v = speed_in * normal + 3.0 * tangent
    force = wall.force_on_tip(p, v)
    assert force @ normal <= 0.0  # pushes the tip out, or not at all
    assert abs(force @ tangent) <= 1e-9 * (1.0 + np.abs(force).max())  # no friction
    expected = max(0.0, k * depth + c * speed_in) if depth > 0.0 else 0.0
    assert -(force @ normal) == pytest.approx(expected, rel=1e-9, abs=1e-6)
    assert float(wall.penetration(p)) == pytest.approx(max(depth, 0.0), abs=1e-12)


def test_a_spring_wall_takes_two_points_and_a_batch_of_tips():
    wall = SpringWall([[4.0, 0.0], [0.0, 4.0]], stiffness=1e3)
    tips = np.array([[[2.0, 2.0], [2.1, 2.0]], [[0.0, 0.0], [2.0, 2.1]]])
    forces = wall.force_on_tip(tips, np.zeros_like(tips))
    assert forces.shape == (2, 2, 2)
    assert np.allclose(
        wall.penetration(tips), [[0.0, 0.1 / np.sqrt(2)], [0.0, 0.1 / np.sqrt(2)]]
    )
    assert np.array_equal(wall(0.0, tips, np.zeros_like(tips)), forces)


# ---------------------------------------------------------------- the tip force in the torques
@given(dynamic_arms(), configurations(), configurations())
def test_tip_force_adds_j_transpose_f_to_the_controllers_torque(arm, q, qd):
    recorded = {}

    def force_on_tip(t, p_tip, v_tip):
        recorded.update(t=t, p_tip=p_tip, v_tip=v_tip)
        return [2.0 * t, -3.0]

    def controller(t, q_now, qd_now):
        return [1.0, t]

    pushed = TipForce(arm, controller, force_on_tip)
    tau = pushed(0.5, q, qd)
    J = arm.jacobian(q)
    scale = 1e-9 * (1.0 + np.abs(J).max() * 3.0)
    assert np.allclose(tau, [1.0, 0.5] + J.T @ [1.0, -3.0], atol=scale)
    assert np.array_equal(pushed.motor_torque(0.5, q, qd), [1.0, 0.5])
    assert recorded["t"] == 0.5
    assert np.allclose(recorded["p_tip"], arm.fk(q))
    assert np.allclose(recorded["v_tip"], J @ qd)


def test_tip_force_without_a_controller_has_no_motor_torque_and_keeps_its_force():
    force = [1.0, 2.0]
    pushed = TipForce(arms.two_metre, None, force)
    force[0] = 99.0  # the caller's list changes later: the TipForce does not
    assert np.array_equal(pushed.motor_torque(0.0, [0.3, 0.4], ZERO), ZERO)
    assert np.array_equal(pushed.force_on_tip_at(0.0, [0.3, 0.4], ZERO), [1.0, 2.0])
    with pytest.raises(ValueError, match="read-only"):
        pushed.force_on_tip[0] = 5.0
