"""Edges of simulate: stiff loops never hang, blow-ups are SimulationErrors, t_eval is checked (issue 11, class 2)."""

import time

import numpy as np
import pytest

from twolink import (
    SimulationError,
    arms,
    contact,
    controllers,
    ik,
    simulate,
    statics,
    trajectory,
)

ARM = arms.two_metre


def timed(function):
    start = time.monotonic()
    try:
        return function(), time.monotonic() - start
    except Exception as exc:  # noqa: BLE001 - re-raised with its duration for the assertions
        exc.seconds = time.monotonic() - start
        raise


def test_stiff_joint_pd_runs_to_the_end_with_an_implicit_method_chosen():
    stiff = controllers.JointPD(ARM, kp=1e8, kd=1e8, reference=[0.5, 0.5])
    result, seconds = timed(
        lambda: simulate(ARM, [0.3, 0.4], [0.0, 0.0], 0.5, torque=stiff)
    )
    assert result.status == 0 and seconds < 10.0
    assert "Radau" in result.message and "stiff" in result.message
    assert np.all(np.isfinite(result.q))


def test_stiff_impedance_damping_runs_to_the_end():
    control = controllers.Impedance(ARM, 600.0, 1e6, [3.0, 1.0])
    result = simulate(ARM, [0.3, 0.4], [0.0, 0.0], 0.5, torque=control)
    assert result.status == 0 and "Radau" in result.message


def test_an_explicit_method_on_a_stiff_loop_is_refused_at_once_naming_the_methods_to_use():
    stiff = controllers.JointPD(ARM, kp=1e8, kd=1e8, reference=[0.5, 0.5])
    with pytest.raises(
        SimulationError, match=r"stiff at t = 0 .*method='Radau' or method='LSODA'"
    ) as error:
        timed(
            lambda: simulate(
                ARM, [0.3, 0.4], [0.0, 0.0], 0.5, torque=stiff, method="RK45"
            )
        )
    assert error.value.seconds < 5.0


def test_a_loop_that_becomes_stiff_on_contact_stops_within_the_evaluation_budget():
    """Free of the 1e8 N/m wall at the start, pressed into it later: the budget stops it and names the fix."""
    wall = contact.SpringWall(
        statics.Wall.through([3.0, 0.0], [3.0, 1.0]), stiffness=1e8
    )
    pressed = contact.TipForce(
        ARM, controllers.Impedance(ARM, 600.0, 50.0, [3.5, 1.0]), wall
    )
    q0 = ik.closed_form(ARM, [2.5, 1.0]).q
    with pytest.raises(
        SimulationError,
        match=r"max_evaluations = 3000 .*stiff.*method='Radau' or method='LSODA'",
    ) as error:
        timed(
            lambda: simulate(
                ARM, q0, [0.0, 0.0], 0.5, torque=pressed, max_evaluations=3000
            )
        )
    assert error.value.seconds < 10.0
    assert "at t = " in str(error.value) and "state q = " in str(error.value)


def test_the_wall_time_budget_stops_a_slow_loop():
    def slow(t, q, qd):
        time.sleep(0.002)
        return [0.0, 0.0]

    with pytest.raises(
        SimulationError, match=r"max_wall_time = 0.3 s at t = "
    ) as error:
        timed(
            lambda: simulate(
                ARM, [0.3, 0.4], [0.0, 0.0], 10.0, torque=slow, max_wall_time=0.3
            )
        )
    assert error.value.seconds < 3.0


def test_default_budget_is_documented_and_finite():
    from twolink import simulate as simulate_module

    module = __import__("twolink.simulate", fromlist=["DEFAULT_MAX_EVALUATIONS"])
    assert (
        0 < module.DEFAULT_MAX_EVALUATIONS < 1e8
        and 0 < module.DEFAULT_MAX_WALL_TIME <= 60
    )
    assert "DEFAULT_MAX_EVALUATIONS" in simulate_module.__doc__


def test_overflowing_torques_are_a_simulation_error_with_time_and_state():
    with pytest.raises(
        SimulationError, match=r"at t = .* q = \(.*\) rad, qd = \(.*\) rad/s"
    ):
        simulate(
            ARM,
            [0.3, 0.4],
            [0.0, 0.0],
            0.5,
            torque=lambda t, q, qd: [1e300 * (1.0 + qd[0] ** 2), 0.0],
        )


def test_torques_that_turn_nan_during_the_motion_are_a_simulation_error_not_a_value_error():
    with pytest.raises(
        SimulationError, match=r"blew up at t = 0\.1.* q = \(.*\) rad, qd = "
    ):
        simulate(
            ARM,
            [0.3, 0.4],
            [0.0, 0.0],
            0.5,
            torque=lambda t, q, qd: [np.nan if t > 0.1 else 0.0, 0.0],
        )


@pytest.mark.parametrize("bad", [[np.inf, 0.0], [np.nan, 0.0]])
def test_a_non_finite_state_is_a_simulation_error_never_a_math_domain_error(bad):
    from twolink import dynamics

    right_hand_side = dynamics.state_derivative(ARM)
    with pytest.raises(
        SimulationError,
        match=r"blew up at t = 0.25 s: the state is not finite .* q = \(",
    ):
        right_hand_side(0.25, np.array([*bad, 0.0, 0.0]))


@pytest.mark.parametrize(
    "t_eval, fragment",
    [
        ([], "non-empty"),
        ([[0.0, 0.5]], "1-D"),
        ([0.0, np.nan], "finite"),
        ([0.0, np.inf], "finite"),
        ([0.5, 0.2], r"strictly increasing; t_eval\[1\] = 0.2 s"),
        ([0.0, 0.0, 0.5], "strictly increasing"),
        ([-0.1, 0.5], r"lie in \[0, t_end\]"),
        ([0.0, 1.5], r"lie in \[0, t_end\]"),
        (["a", "b"], "times in seconds"),
        ([0.0, 1j], "times in seconds"),
    ],
)
def test_t_eval_is_validated(t_eval, fragment):
    with pytest.raises(ValueError, match=fragment):
        simulate(ARM, [0.3, 0.4], [0.0, 0.0], 1.0, t_eval=t_eval)


@pytest.mark.parametrize(
    "budget, error",
    [(0, ValueError), (2.5, ValueError), ("10", TypeError), (None, TypeError)],
)
def test_the_evaluation_budget_is_a_positive_integer(budget, error):
    with pytest.raises(error, match="max_evaluations"):
        simulate(ARM, [0.3, 0.4], [0.0, 0.0], 1.0, max_evaluations=budget)


def test_resolved_rate_with_a_huge_gain_runs_in_seconds():
    line = trajectory.LinePath([-3.5, 1.0], [-1.0, 3.5], duration=1.0)
    motion, seconds = timed(
        lambda: trajectory.resolved_rate_trajectory(ARM, line, n=20, gain=1e6)
    )
    assert seconds < 10.0
    assert motion.tracking_error().max() < 1e-6


def test_tracking_error_after_a_terminal_event_reads_the_path_at_the_times_reached():
    def elbow_straight(t, state):
        return state[1]

    elbow_straight.terminal = True
    elbow_straight.direction = 1
    line = trajectory.LinePath([3.0, 1.0], [3.0, 1.0 + 1e-9], duration=5.0)
    run = simulate(
        ARM,
        [np.pi / 4, -0.5],
        [0.0, 0.0],
        5.0,
        events=elbow_straight,
        t_eval=np.linspace(0.0, 5.0, 501),
    )
    assert run.status == 1 and len(run.t) < 501
    assert np.allclose(
        run.tracking_error(line), np.linalg.norm(run.p_tip - line.at(run.t)[0], axis=-1)
    )
