"""twolink.engine: MuJoCo integrates the same equations as twolink (accelerations, motion, wall force)."""

import dataclasses
import sys

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from conftest import acceleration_scale, dynamic_arms
from twolink import SimulationError, TwoLinkArm, arms, ik, simulate
from twolink.controllers import Impedance
from twolink.statics import Wall

mujoco = pytest.importorskip("mujoco")
from twolink import engine  # noqa: E402

WALL = Wall.through([4.0, 0.0], [0.0, 4.0])


pytestmark = pytest.mark.usefixtures("mujoco_log_in_tmp")


@settings(max_examples=30, deadline=None)
@given(
    arm=dynamic_arms(),
    q=st.tuples(st.floats(-np.pi, np.pi), st.floats(-np.pi, np.pi)),
    qd=st.tuples(st.floats(-5.0, 5.0), st.floats(-5.0, 5.0)),
    tau=st.tuples(st.floats(-50.0, 50.0), st.floats(-50.0, 50.0)),
)
def test_joint_accelerations_equal_forward_dynamics(arm, q, qd, tau):
    got = engine.joint_accelerations(engine.build_model(arm), q, qd, tau)
    expected = arm.forward_dynamics(q, qd, tau)
    assert np.max(np.abs(got - expected)) <= 1e-9 * acceleration_scale(arm, q, qd, tau)


@pytest.mark.parametrize(
    "arm, q0, qd0",
    [
        (arms.two_metre, [np.pi / 4, 0.0], [0.0, 0.0]),
        (TwoLinkArm(1.0, 0.5, m1=3.0, m2=0.5, I2=0.05), [-0.3, 2.0], [1.0, -2.0]),
        (TwoLinkArm(2.0, 2.0, g=0.0), [0.0, 1.0], [1.5, -3.0]),
    ],
)
def test_free_motion_matches_twolink_simulate(arm, q0, qd0):
    mj = engine.simulate_in_mujoco(arm, q0, qd0, 1.0, timestep=1e-3, sample_every=10)
    reference = simulate(arm, q0, qd0, 1.0, t_eval=mj.t, rtol=1e-11, atol=1e-11)
    assert np.ptp(mj.q[:, 1]) > 0.1  # it moved
    assert np.max(np.abs(mj.q - reference.q)) < 1e-7
    assert np.max(np.abs(mj.qd - reference.qd)) < 1e-6
    assert np.allclose(
        mj.p_tip_mujoco, arm.fk(mj.q), atol=1e-12
    )  # MuJoCo's tip site is twolink's fk
    assert np.array_equal(mj.p_tip, arm.fk(mj.q))
    assert np.all(mj.force_by_tip == 0.0)


def test_rk4_error_shrinks_with_the_step():
    arm = arms.two_metre
    coarse = engine.simulate_in_mujoco(
        arm, [np.pi / 4, 0.0], [0.0, 0.0], 0.5, timestep=4e-3, sample_every=125
    )
    fine = engine.simulate_in_mujoco(
        arm, [np.pi / 4, 0.0], [0.0, 0.0], 0.5, timestep=2e-3, sample_every=250
    )
    reference = simulate(
        arm,
        [np.pi / 4, 0.0],
        [0.0, 0.0],
        0.5,
        t_eval=[0.0, 0.5],
        rtol=1e-12,
        atol=1e-12,
    )
    error_coarse = np.max(np.abs(coarse.q[-1] - reference.q[-1]))
    error_fine = np.max(np.abs(fine.q[-1] - reference.q[-1]))
    assert 8.0 < error_coarse / error_fine < 32.0  # fourth order: about 16


def test_constant_torques_equal_to_gravity_hold_the_arm():
    arm = arms.two_metre
    q0 = np.array([0.7, -0.4])
    held = engine.simulate_in_mujoco(
        arm, q0, [0.0, 0.0], 0.2, torque=arm.gravity(q0), timestep=1e-3
    )
    assert np.allclose(held.q, q0, atol=1e-12)
    assert np.allclose(held.tau, arm.gravity(q0))


def test_the_same_impedance_controller_drives_both_and_mujoco_converges_with_the_step():
    arm = arms.two_metre
    control = Impedance(arm, stiffness=600.0, damping=50.0, rest_point=[3.0, 1.0])
    q0 = ik.closed_form(arm, [2.5, 0.5]).q
    reference = simulate(
        arm, q0, [0.0, 0.0], 0.4, torque=control, t_eval=[0.0, 0.2, 0.4]
    )
    errors = []
    for timestep in (1e-3, 5e-4):
        mj = engine.simulate_in_mujoco(
            arm,
            q0,
            [0.0, 0.0],
            0.4,
            torque=control,
            timestep=timestep,
            sample_every=int(round(0.2 / timestep)),
        )
        assert np.allclose(mj.tau[0], control(0.0, q0, [0.0, 0.0]))
        errors.append(np.max(np.abs(mj.p_tip_mujoco - arm.fk(reference.q))))
    assert (
        np.linalg.norm(arm.fk(reference.q[-1]) - arm.fk(q0)) > 0.1
    )  # the tip really moved
    assert errors[1] < 2e-3
    assert (
        1.5 < errors[0] / errors[1] < 2.5
    )  # the torque is held over a step: first-order error


def test_a_blow_up_is_a_simulation_error_naming_the_time():
    def shove(t, q, qd):  # MuJoCo refuses torques above 1e10 (zeroes them and warns)
        return [1e300, -1e300]

    with pytest.raises(
        SimulationError, match=r"mjWARN_BADCTRL at or before t = 0.001 s"
    ):
        engine.simulate_in_mujoco(
            arms.two_metre, [0.0, 0.0], [0.0, 0.0], 0.01, torque=shove, timestep=1e-3
        )

    def negative_damping(t, q, qd):  # pumps energy in: the state grows without bound
        return 1e4 * np.asarray(qd)

    with pytest.raises(SimulationError, match=r"at or before t = "):
        engine.simulate_in_mujoco(
            arms.two_metre,
            [0.0, 0.0],
            [0.1, 0.0],
            10.0,
            torque=negative_damping,
            timestep=1e-3,
        )


@pytest.mark.parametrize(
    "kwargs, message",
    [
        ({"t_end": -1.0}, "t_end"),
        ({"sample_every": 0}, "sample_every"),
        ({"sample_every": 1000}, "at most the number of steps"),
        ({"timestep": 1e-9}, "steps; allowed"),
        ({"torque": lambda t, q, qd: [1.0, 2.0, 3.0]}, r"shape \(2,\)"),
        ({"torque": [1.0]}, "torque"),
    ],
)
def test_simulate_rejects_bad_arguments(kwargs, message):
    arguments = {"t_end": 0.01, "timestep": 1e-3} | kwargs
    with pytest.raises(ValueError, match=message):
        engine.simulate_in_mujoco(arms.two_metre, [0.0, 0.0], [0.0, 0.0], **arguments)


@pytest.mark.parametrize(
    "arm", [arms.two_metre, dataclasses.replace(arms.two_metre, g=0.0)]
)
@pytest.mark.parametrize("elbow", ["down", "up"])
def test_wall_push_gives_the_statics_force(arm, elbow):
    push = engine.wall_push(arm, WALL, 500.0, elbow=elbow)
    assert push.elbow == elbow
    assert np.allclose(
        push.force_by_tip_expected, 500.0 * np.array([1.0, 1.0]) / np.sqrt(2.0)
    )
    assert push.relative_error < 1e-5
    assert abs(push.force_by_tip_tangential) < 0.05
    assert push.force_by_tip_normal == pytest.approx(500.0, rel=1e-5)
    assert 0.0 < push.penetration < 1e-4
    # MuJoCo's force is the one that balances the torques at its own (settled) configuration
    assert np.max(np.abs(push.force_by_tip - push.force_by_tip_balancing)) < 1e-2
    assert np.max(np.abs(push.qd_settled)) < 1e-6 and push.normal_drift < 1e-3


def test_mujoco_default_contact_sinks_further_and_reads_further_from_the_statics():
    stiff = engine.wall_push(arms.two_metre, WALL, 500.0)
    default = engine.wall_push(
        arms.two_metre,
        WALL,
        500.0,
        contact_solref=(0.02, 1.0),
        contact_solimp=(0.9, 0.95, 0.001, 0.5, 2.0),
        impratio=1.0,
    )
    assert default.penetration > 100.0 * stiff.penetration
    assert default.relative_error > 10.0 * stiff.relative_error
    # still the force that balances the torques where MuJoCo's arm came to rest
    assert np.max(np.abs(default.force_by_tip - default.force_by_tip_balancing)) < 0.1


def test_wall_push_rejects_a_word_outside_the_vocabulary_both_and_an_unreachable_wall():
    with pytest.raises(
        ValueError, match=r"elbow must be one of \('down', 'up', 'auto'\); got 'left'"
    ):
        engine.wall_push(arms.two_metre, WALL, 500.0, elbow="left")
    with pytest.raises(
        ValueError, match=r"got 'both' \(wall_push simulates one configuration\)"
    ):
        engine.wall_push(arms.two_metre, WALL, 500.0, elbow="both")
    with pytest.raises(ValueError, match="the wall is"):
        engine.wall_push(arms.two_metre, Wall.through([9.0, 0.0], [0.0, 9.0]), 500.0)
    with pytest.raises(
        ValueError, match="wall must be a twolink.statics.Wall or two points"
    ):
        engine.wall_push(arms.two_metre, None, 500.0)


def test_wall_push_auto_is_down_and_a_wall_at_full_reach_has_one_configuration_on_both_branches():
    auto = engine.wall_push(arms.two_metre, WALL, 100.0, elbow="auto", duration=0.01)
    assert auto.elbow == "down" and np.array_equal(
        auto.q_contact,
        engine.wall_push(arms.two_metre, WALL, 100.0, duration=0.01).q_contact,
    )
    far = Wall(
        [4.0, 0.0], [1.0, 0.0]
    )  # x = 4: only the stretched arm touches it with link 2 perpendicular
    pushes = [
        engine.wall_push(arms.two_metre, far, 100.0, elbow=word, duration=0.01)
        for word in ("down", "up", "auto")
    ]
    assert {push.elbow for push in pushes} == {"stretched"}
    assert all(np.array_equal(push.q_contact, [0.0, 0.0]) for push in pushes)


def test_without_mujoco_the_error_names_the_function_and_the_install(monkeypatch):
    monkeypatch.setitem(sys.modules, "mujoco", None)
    with pytest.raises(
        ImportError,
        match=r'twolink.engine.simulate_in_mujoco needs mujoco.*pip install "twolink\[mujoco\]"',
    ):
        engine.simulate_in_mujoco(arms.two_metre, [0.0, 0.0], [0.0, 0.0], 0.01)
