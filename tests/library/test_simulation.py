"""twolink.simulation: free and driven motion, energy conservation, failures, the result object."""

import dataclasses
import importlib.util
import inspect
import re
import time

import matplotlib.pyplot as plt
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp

from conftest import dynamic_arms
from twolink import (
    SimulationError,
    SimulationResult,
    TwoLinkArm,
    arms,
    contact,
    controllers,
    dynamics,
    ik,
    simulate,
    simulation,
    statics,
    trajectory,
)
from twolink._integration import RECENT_EVALUATIONS, BudgetSpent, budgeted
from twolink.budgets import EvaluationBudget
from twolink.errors import InputTypeError
from twolink.simulation import simulate_quick
from twolink_course import plot

TIGHT = {"method": "DOP853", "rtol": 1e-10, "atol": 1e-10}


def relative_energy_drift(result):
    """max |E(t) - E(0)| over the largest kinetic energy, computed here from arm.energy."""
    kinetic, potential = result.arm.energy(result.q, result.qd)
    total = kinetic + potential
    return np.max(np.abs(total - total[0])) / np.max(kinetic)


@pytest.mark.parametrize(
    "arm, q0, qd0",
    [
        (
            arms.two_metre,
            [np.pi / 4, 0.0],
            [0.0, 0.0],
        ),  # the benchmark's start: a chaotic swing
        (TwoLinkArm(1.0, 0.5, m1=3.0, m2=0.5), [-0.3, 2.0], [1.0, -2.0]),
        (
            TwoLinkArm(2.0, 2.0, g=0.0),
            [0.0, 1.0],
            [1.5, -3.0],
        ),  # horizontal arm, spinning
    ],
)
def test_energy_is_conserved_in_free_motion(arm, q0, qd0):
    result = simulate(arm, q0, qd0, 10.0, **TIGHT)
    assert result.status == 0 and result.t[-1] == 10.0
    assert np.ptp(result.q[:, 1]) > 0.5  # it really moved (the elbow swung)
    drift = relative_energy_drift(result)
    assert drift < 1e-8
    assert result.energy_drift() == pytest.approx(drift, rel=1e-12)


def test_loose_tolerances_do_drift():
    """The drift test can fail: a loose RK45 run loses energy visibly."""
    loose = simulate(
        arms.two_metre,
        [np.pi / 4, 0.0],
        [0.0, 0.0],
        10.0,
        method="RK45",
        rtol=1e-3,
        atol=1e-6,
    )
    assert relative_energy_drift(loose) > 1e-6


def test_horizontal_arm_conserves_angular_momentum_about_the_base():
    """With g = 0 nothing turns the whole arm: p1 = dL/dqd1 = (M qd)[0] stays constant."""
    arm = TwoLinkArm(1.0, 1.5, m1=2.0, m2=1.0, g=0.0)
    result = simulate(arm, [0.2, 0.4], [2.0, -5.0], 5.0, **TIGHT)
    momentum = np.einsum("nij,nj->ni", arm.mass_matrix(result.q), result.qd)[:, 0]
    assert np.ptp(result.q[:, 1]) > 1.0
    assert np.max(np.abs(momentum - momentum[0])) < 1e-8 * abs(momentum[0])


def test_matches_an_independent_right_hand_side():
    """The lean RHS agrees with one built from M, C, g and numpy.linalg.solve."""
    arm = TwoLinkArm(1.2, 0.9, m1=1.5, m2=0.8, I2=0.1)

    def torque(t, q, qd):
        return np.array([2.0 * np.sin(3.0 * t), -1.0 - 0.5 * qd[1]])

    def reference_rhs(t, state):
        q, qd = state[:2], state[2:]
        qdd = np.linalg.solve(
            arm.mass_matrix(q),
            torque(t, q, qd) - arm.coriolis(q, qd) @ qd - arm.gravity(q),
        )
        return np.concatenate([qd, qdd])

    t_eval = np.linspace(0.0, 3.0, 61)
    result = simulate(
        arm, [0.5, -0.5], [0.0, 1.0], 3.0, torque=torque, t_eval=t_eval, **TIGHT
    )
    reference = solve_ivp(
        reference_rhs, (0.0, 3.0), [0.5, -0.5, 0.0, 1.0], t_eval=t_eval, **TIGHT
    )
    assert np.allclose(result.q, reference.y[:2].T, atol=1e-8)
    assert np.allclose(result.qd, reference.y[2:].T, atol=1e-8)
    expected_tau = np.array(
        [torque(t, q, qd) for t, q, qd in zip(result.t, result.q, result.qd)]
    )
    assert np.array_equal(result.tau, expected_tau)


def test_torques_equal_to_gravity_hold_the_arm():
    arm = arms.two_metre
    q0 = np.array([0.7, -1.2])
    result = simulate(
        arm,
        q0,
        [0.0, 0.0],
        3.0,
        torque=lambda t, q, qd: arm.gravity(q),
        t_eval=[0.0, 1.5, 3.0],
    )
    assert np.allclose(result.q, q0, atol=1e-9)
    assert np.allclose(result.qd, 0.0, atol=1e-9)
    assert np.allclose(result.tau, arm.gravity(q0), atol=1e-9)


def test_feedforward_of_inverse_dynamics_reproduces_the_trajectory():
    """Open-loop torques from inverse dynamics drive the arm along the planned motion."""
    arm = arms.two_metre
    q_start, q_goal, duration = np.array([-1.2, 0.3]), np.array([0.6, 1.4]), 2.0

    def planned(t):
        s = np.clip(t / duration, 0.0, 1.0)
        blend = 10 * s**3 - 15 * s**4 + 6 * s**5
        rate = (30 * s**2 - 60 * s**3 + 30 * s**4) / duration
        accel = (60 * s - 180 * s**2 + 120 * s**3) / duration**2
        delta = q_goal - q_start
        return q_start + blend * delta, rate * delta, accel * delta

    result = simulate(
        arm,
        q_start,
        [0.0, 0.0],
        duration,
        torque=lambda t, q, qd: arm.inverse_dynamics(*planned(t)),
    )
    assert np.allclose(result.q[-1], q_goal, atol=1e-6)
    assert np.allclose(result.qd[-1], 0.0, atol=1e-5)


@settings(max_examples=10)
@given(dynamic_arms(), st.floats(-np.pi, np.pi), st.floats(-np.pi, np.pi))
def test_free_motion_of_random_arms_keeps_its_energy(arm, q1, q2):
    result = simulate(arm, [q1, q2], [0.5, -0.5], 1.0, **TIGHT)
    assert result.status == 0
    assert relative_energy_drift(result) < 1e-8


# ----------------------------------------------------------------- result object
def test_result_shapes_t_eval_and_read_only():
    t_eval = np.linspace(0.0, 2.0, 41)
    result = simulate(arms.two_metre, [0.1, 0.2], [0.0, 0.0], 2.0, t_eval=t_eval)
    assert isinstance(result, SimulationResult)
    assert np.array_equal(result.t, t_eval)
    assert result.q.shape == result.qd.shape == result.tau.shape == (41, 2)
    assert np.array_equal(result.q[0], [0.1, 0.2]) and np.array_equal(
        result.qd[0], [0.0, 0.0]
    )
    assert np.all(result.tau == 0.0)
    assert result.status == 0 and "reached the end" in result.message
    assert result.nfev > 0
    with pytest.raises(ValueError):
        result.q[0, 0] = 1.0
    with pytest.raises(dataclasses.FrozenInstanceError):
        result.status = 1


def test_default_solver_is_tight_and_options_pass_through():
    arm = arms.two_metre
    default = simulate(arm, [np.pi / 4, 0.0], [0.0, 0.0], 2.0)
    tight = simulate(arm, [np.pi / 4, 0.0], [0.0, 0.0], 2.0, **TIGHT)
    assert np.array_equal(default.q, tight.q)
    radau = simulate(
        arm, [np.pi / 4, 0.0], [0.0, 0.0], 2.0, method="Radau", rtol=1e-6, atol=1e-8
    )
    assert radau.nfev != tight.nfev
    assert np.allclose(radau.q[-1], tight.q[-1], atol=1e-3)
    capped = simulate(arm, [np.pi / 4, 0.0], [0.0, 0.0], 2.0, max_step=0.01)
    assert np.all(np.diff(capped.t) <= 0.01 + 1e-12)


def test_terminal_event_is_reported_not_hidden():
    """A terminal event stops early with status 1 and says so."""

    def elbow_straight(t, state):
        return state[1]

    elbow_straight.terminal = True
    elbow_straight.direction = 1
    result = simulate(
        arms.two_metre, [np.pi / 4, -0.5], [0.0, 0.0], 10.0, events=elbow_straight
    )
    assert result.status == 1
    assert result.t[-1] < 10.0
    assert len(result.t_events[0]) == 1
    assert abs(result.q[-1, 1]) < 1e-8


def test_frames_pick_evenly_with_first_and_last():
    result = simulate(
        arms.two_metre, [0.3, 0.3], [0.0, 0.0], 5.0, t_eval=np.linspace(0.0, 5.0, 501)
    )
    frames = result.frames(50)
    assert len(frames) == 50 and frames[0] == 0 and frames[-1] == 500
    assert np.all(np.diff(frames) > 0)
    assert len(result.frames(1000)) == 501
    with pytest.raises(ValueError, match="max_frames must be an integer >= 2"):
        result.frames(1)


def test_animate_simulation_has_at_most_50_frames_and_a_clock():
    result = simulate(
        arms.two_metre, [0.3, 0.3], [0.0, 0.0], 5.0, t_eval=np.linspace(0.0, 5.0, 501)
    )
    anim = plot.animate_simulation(result)
    frames = list(anim.new_frame_seq())
    assert len(frames) == 50
    assert anim._interval == pytest.approx(5000.0 / 49)  # real time
    anim._func(len(frames) - 1)
    clock = [text.get_text() for text in anim._fig.axes[0].texts]
    assert "t = 5.00 s" in clock
    plt.close(anim._fig)
    with pytest.raises(ValueError, match="speed must be > 0"):
        plot.animate_simulation(result, speed=0.0)


# ----------------------------------------------------------------- failures and bad input
def test_solver_failure_raises_instead_of_returning_a_partial_result():
    """A torque that grows like qd^3 makes the speed blow up in finite time: the solver gives up."""
    with pytest.raises(
        SimulationError, match="integration failed at t = .* Required step size"
    ):
        simulate(
            arms.two_metre,
            [0.0, 0.0],
            [1.0, 0.0],
            5.0,
            torque=lambda t, q, qd: [50.0 * qd[0] ** 3, 0.0],
        )


@pytest.mark.parametrize(
    "kwargs, error, fragment",
    [
        ({"q0": [0.0, 0.0, 0.0]}, ValueError, r"q0 must have shape \(\.\.\., 2\)"),
        (
            {"q0": [[0.0, 0.0], [1.0, 1.0]]},
            ValueError,
            r"q0 must be one configuration of shape \(2,\) \(radians\); got shape \(2, 2\)",
        ),
        ({"qd0": [0.0]}, ValueError, r"qd0 must have shape \(\.\.\., 2\)"),
        (
            {"qd0": [[0.0, 0.0]]},
            ValueError,
            r"qd0 must be one pair of joint rates of shape \(2,\) \(rad/s\); got shape \(1, 2\)",
        ),
        ({"qd0": [np.nan, 0.0]}, ValueError, "qd0 must be finite"),
        (
            {"t_end": 0.0},
            ValueError,
            r"t_end \(s\) must be in \[1e-50, 1e\+50\]; got 0",
        ),
        ({"t_end": 1e-300}, ValueError, r"t_end \(s\) must be in \[1e-50, 1e\+50\]"),
        ({"t_end": np.inf}, ValueError, r"t_end \(s\) must be finite"),
        ({"torque": [1.0, 2.0]}, ValueError, "torque must be None or a callable"),
        ({"torque": lambda t, q, qd: [np.nan, 0.0]}, ValueError, "non-finite torques"),
        (
            {"torque": lambda t, q, qd: [1.0, 2.0, 3.0]},
            ValueError,
            r"must return shape \(2,\)",
        ),
        ({"torque": lambda t, q, qd: "strong"}, ValueError, "must return two numbers"),
        ({"method": "Euler"}, ValueError, "method must be one of"),
        (
            {"rtoll": 1e-6},
            ValueError,
            r"'rtoll' is not an option .*did you mean 'rtol'",
        ),
        (
            {"method": "RK45", "jac": None},
            ValueError,
            "'jac' is not an option of .*'RK45'",
        ),
        (
            {"max_step": 1e-300},
            ValueError,
            r"max_step = 1e-300 s would take at least 1e\+300 steps",
        ),
        ({"max_step": -1.0}, ValueError, r"max_step \(s\) must be > 0.0"),
        ({"first_step": 5.0}, ValueError, r"first_step \(s\) must be at most .* 1 s"),
        ({"rtol": "tight"}, TypeError, "rtol must be positive numbers"),
        ({"atol": 0.0}, ValueError, "atol must be a positive finite number"),
    ],
)
def test_bad_input_raises(kwargs, error, fragment):
    arguments = {
        "arm": arms.two_metre,
        "q0": [0.0, 0.0],
        "qd0": [0.0, 0.0],
        "t_end": 1.0,
    }
    arguments.update(kwargs)
    with pytest.raises(error, match=fragment):
        simulate(**arguments)


def test_arm_with_a_singular_mass_matrix_is_refused():
    with pytest.raises(ValueError, match="mass matrix is singular"):
        simulate(TwoLinkArm(1.0, 1.0, m2=0.0), [0.0, 0.0], [0.0, 0.0], 1.0)


# ----------------------------------------------------------------- energy with a spring
@pytest.mark.parametrize("g", [0.0, 9.81])
def test_a_spring_controlled_undamped_arm_conserves_arm_plus_spring_energy(g):
    """T + V_gravity + V_spring is constant to solver tolerance; T + V_gravity alone is not."""
    arm = dataclasses.replace(arms.two_metre, g=g)
    spring = controllers.CartesianSpring(arm, stiffness=600.0, rest_point=[3.0, 1.0])
    q0 = ik.closed_form(arm, [3.0, 2.0]).q
    result = simulate(
        arm,
        q0,
        [0.0, 0.0],
        1.0,
        torque=spring,
        t_eval=np.linspace(0.0, 1.0, 401),
        **TIGHT,
    )
    kinetic, potential = result.energy(extra_potential=spring.potential_energy)
    kinetic_arm, potential_arm = result.energy()
    assert np.array_equal(kinetic, kinetic_arm)
    assert np.allclose(
        potential,
        potential_arm + spring.potential_energy(result.q),
        rtol=0,
        atol=1e-12 * 600.0,
    )
    total = kinetic + potential
    by_hand = np.max(np.abs(total - total[0])) / np.max(kinetic)
    drift = result.energy_drift(extra_potential=spring.potential_energy)
    assert drift == pytest.approx(by_hand, rel=1e-12)
    assert drift < 1e-8
    assert (
        result.energy_drift() > 0.1
    )  # the spring's energy is most of what changes form


def test_extra_potential_must_be_a_vectorised_callable_of_finite_energies():
    result = simulate(
        arms.two_metre, [0.3, 0.4], [0.0, 0.0], 0.5, t_eval=[0.0, 0.25, 0.5]
    )
    with pytest.raises(TypeError, match="extra_potential must be None or a callable V"):
        result.energy(extra_potential=3.0)
    with pytest.raises(
        ValueError,
        match=r"must be vectorised: q of shape \(3, 2\) in, energies of shape \(3,\) .* got shape \(\)",
    ):
        result.energy_drift(extra_potential=lambda q: 1.0)
    with pytest.raises(ValueError, match=r"returned nan J at t = 0.25 s \(sample 1\)"):
        result.energy(
            extra_potential=lambda q: np.where(q[:, 0] == result.q[1, 0], np.nan, 0.0)
        )
    with pytest.raises(ValueError, match="must return energies in joules"):
        result.energy(extra_potential=lambda q: ["a", "b", "c"])


# ----------------------------------------------------------------- tip and tracking error
def test_p_tip_and_tracking_error_read_like_a_joint_trajectorys():
    arm = arms.two_metre
    line = trajectory.LinePath([-3.5, 1.0], [-1.0, 3.5], duration=2.0, law="quintic")
    motion = trajectory.ik_trajectory(arm, line, n=41)
    control = controllers.JointPD(
        arm, kp=400.0, kd=40.0, reference=motion.joint_reference()
    )
    run = simulate(
        arm, motion.q[0] + [0.02, 0.0], [0.0, 0.0], 2.0, torque=control, t_eval=motion.t
    )
    assert np.array_equal(run.p_tip, arm.fk(run.q))
    by_hand = np.linalg.norm(arm.fk(run.q) - line.at(run.t)[0], axis=-1)
    assert by_hand[0] > 0.01
    for path in (line, motion, motion.p_ref):
        assert np.allclose(run.tracking_error(path), by_hand, rtol=0, atol=1e-12)
    assert np.allclose(
        run.tracking_error(line.p_end), np.linalg.norm(run.p_tip - line.p_end, axis=-1)
    )
    assert inspect.signature(SimulationResult.tracking_error) == inspect.signature(
        trajectory.JointTrajectory.tracking_error
    )


def test_a_simulation_has_no_path_of_its_own():
    run = simulate(
        arms.two_metre, [0.3, 0.4], [0.0, 0.0], 1.0, t_eval=np.linspace(0.0, 1.0, 11)
    )
    with pytest.raises(
        ValueError,
        match="a simulation has no path of its own: pass what the tip should follow",
    ):
        run.tracking_error()
    motion = trajectory.ik_trajectory(
        arms.two_metre, trajectory.LinePath([3.0, 0.5], [3.0, 1.0], 1.0), n=12
    )
    with pytest.raises(
        ValueError,
        match=r"sampled at 12 times .* simulate with t_eval=trajectory.t, or pass the path",
    ):
        run.tracking_error(motion)


# ----------------------------------------------------------------- edges: a slow torque function, bad t_eval
def sleepy(seconds):
    def torque(t, q, qd):
        time.sleep(seconds)
        return [0.0, 0.0]

    return torque


def test_a_slow_torque_function_stops_at_the_wall_time_budget_and_is_named_as_the_cause():
    started = time.monotonic()
    with pytest.raises(
        SimulationError,
        match=r"max_wall_time = 0.5 s .*the torque function is the likely cause: .*evaluated only \d+ times",
    ):
        simulate(
            arms.two_metre,
            [0.3, 0.2],
            [0.0, 0.0],
            1.0,
            torque=sleepy(0.2),
            max_wall_time=0.5,
        )
    assert (
        time.monotonic() - started < 0.5 + 3 * 0.2
    )  # the clock is read at every call, not every 64th


def test_events_are_timed_too():
    def slow_event(t, state):
        time.sleep(0.05)
        return state[1] - 10.0

    with pytest.raises(SimulationError, match=r"max_wall_time = 0.3 s"):
        simulate(
            arms.two_metre,
            [0.3, 0.2],
            [0.0, 0.0],
            10.0,
            max_wall_time=0.3,
            events=slow_event,
        )


def test_the_torques_at_the_output_times_are_within_the_budget_too():
    calls = []

    def slow_after_the_integration(t, q, qd):
        calls.append(t)
        if (
            len(calls) > 200
        ):  # the integration takes a few dozen calls; the output times 2001
            time.sleep(0.01)
        return [0.0, 0.0]

    with pytest.raises(
        SimulationError,
        match=r"recomputing the torques at the 2001 output times used up the budget",
    ):
        simulate(
            arms.two_metre,
            [0.3, 0.2],
            [0.0, 0.0],
            0.01,
            torque=slow_after_the_integration,
            max_wall_time=1.0,
            t_eval=np.linspace(0.0, 0.01, 2001),
            method="RK45",
            rtol=1e-3,
            atol=1e-3,
        )


@pytest.mark.parametrize(
    "bad", [[0.0, True], np.ma.masked_array([0.0, 0.5], mask=[False, True]), ["0", "1"]]
)
def test_t_eval_refuses_bools_masked_arrays_and_strings(bad):
    with pytest.raises(
        InputTypeError, match=r"t_eval must be times in seconds \(real numbers\)"
    ):
        simulate(arms.two_metre, [0.3, 0.2], [0.0, 0.0], 1.0, t_eval=bad)


def _nan_from(t_start):
    return lambda t, q, qd: [np.nan, 0.0] if t >= t_start else [0.0, 0.0]


@pytest.mark.parametrize(
    "t_start", [0.0, 0.5, 1.0], ids=["at the start", "mid-motion", "at the end"]
)
def test_a_non_finite_torque_gives_a_public_error(t_start):
    """The private NonFiniteTorque never reaches users: a ValueError or a SimulationError, named as such."""
    from twolink import dynamics

    calls = [
        lambda: simulate(
            arms.two_metre, [0.3, 0.2], [0.0, 0.0], 1.0, _nan_from(t_start)
        ),
        lambda: dynamics.state_derivative(arms.two_metre, _nan_from(t_start))(
            t_start, np.zeros(4)
        ),
    ]
    if importlib.util.find_spec("mujoco") is not None:
        from twolink import engine

        calls.append(
            lambda: engine.simulate_in_mujoco(
                arms.two_metre, [0.3, 0.2], [0.0, 0.0], 1.0, _nan_from(t_start)
            )
        )
    for call in calls:
        with pytest.raises(
            (ValueError, SimulationError), match="non-finite torques"
        ) as error:
            call()
        assert type(error.value) in (ValueError, SimulationError), type(error.value)


# ----------- stiff loops never hang; blow-ups are SimulationErrors; t_eval is checked
ARM = arms.two_metre


def timed(function):
    start = time.monotonic()
    try:
        return function(), time.monotonic() - start
    except Exception as exc:  # noqa: BLE001 - re-raised with its duration for the assertions
        exc.seconds = time.monotonic() - start
        raise


def test_a_stiff_loop_on_the_default_method_is_refused_at_once_not_switched():
    """simulate integrates with the method it is given (DOP853 by default): no silent switch to Radau."""
    stiff = controllers.JointPD(ARM, kp=1e8, kd=1e8, reference=[0.5, 0.5])
    with pytest.raises(
        SimulationError,
        match=r"stiff at t = 0 in the state q = \(0.3, 0.4\) rad.*'DOP853' would need "
        r"about .*method='Radau' or method='LSODA'",
    ) as error:
        timed(lambda: simulate(ARM, [0.3, 0.4], [0.0, 0.0], 0.5, torque=stiff))
    assert error.value.seconds < 5.0


def test_a_stiff_loop_runs_to_the_end_with_the_implicit_method_asked_for():
    stiff = controllers.JointPD(ARM, kp=1e8, kd=1e8, reference=[0.5, 0.5])
    ends = []
    for method in ("Radau", "LSODA", "BDF"):
        result, seconds = timed(
            lambda: simulate(
                ARM,
                [0.3, 0.4],
                [0.0, 0.0],
                0.5,
                torque=stiff,
                method=method,
                rtol=1e-8,
                atol=1e-8,
            )
        )
        assert result.status == 0 and seconds < 10.0 and "stiff" not in result.message
        ends.append(result.q[-1])
    # overdamped (time constant kd / kp = 1 s): part of the way to the reference, alike by every method
    assert np.all((ends[0] > [0.3, 0.4]) & (ends[0] < [0.5, 0.5]))
    assert np.allclose(ends, ends[0], rtol=0.0, atol=1e-5)


def test_stiff_impedance_damping_runs_to_the_end_with_radau():
    control = controllers.Impedance(ARM, 600.0, 1e6, [3.0, 1.0])
    with pytest.raises(SimulationError, match="method='Radau'"):
        simulate(ARM, [0.3, 0.4], [0.0, 0.0], 0.5, torque=control)
    result = simulate(ARM, [0.3, 0.4], [0.0, 0.0], 0.5, torque=control, method="Radau")
    assert result.status == 0


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


def test_a_spent_budget_carries_the_states_of_the_evaluations_just_before_it():
    budget = EvaluationBudget(30, 30.0)
    spending = budgeted(lambda t, state: state, budget)
    for k in range(30):
        spending(float(k), np.array([float(k), 0.0, 0.0, 0.0]))
    with pytest.raises(BudgetSpent) as stop:
        spending(30.0, np.array([30.0, 0.0, 0.0, 0.0]))
    assert stop.value.which == "max_evaluations" and stop.value.state[0] == 30.0
    assert [state[0] for state in stop.value.recent] == list(
        range(30 - RECENT_EVALUATIONS, 30)
    )


def test_the_advice_judges_stiffness_over_the_last_evaluations_not_only_the_very_last():
    """A tip bouncing on a stiff wall can be off it at the last evaluation: the few before decide too.

    Which evaluation is the last depends on the machine's rounding (the
    contact loop of ``test_a_loop_that_becomes_stiff_on_contact_...`` stopped
    off the wall with OpenBLAS's SkylakeX kernels, on the wall with Haswell's),
    so the advice is checked here on states given by hand.
    """
    wall = contact.SpringWall(
        statics.Wall.through([3.0, 0.0], [3.0, 1.0]), stiffness=1e8
    )
    pressed = contact.TipForce(
        ARM, controllers.Impedance(ARM, 600.0, 50.0, [3.5, 1.0]), wall
    )
    inner = dynamics.state_derivative(ARM, pressed)
    off_the_wall = np.concatenate([ik.closed_form(ARM, [2.999, 1.0]).q, [0.0, 0.0]])
    in_the_wall = np.concatenate([ik.closed_form(ARM, [3.0001, 1.0]).q, [0.0, 0.0]])
    budget = EvaluationBudget(3000, 30.0)
    budget.evaluations = 3001

    def advice(recent):
        stop = BudgetSpent(0.09, off_the_wall, "max_evaluations", recent)
        return simulation._budget_advice(
            inner, stop, budget, "DOP853", 0.5, pressed, np.inf
        )

    assert "if the loop is stiff" in advice([off_the_wall] * 3)
    assert re.search(
        r"stiff there \(fastest rate [0-9.]+e\+04 1/s.*method='Radau'",
        advice([in_the_wall, off_the_wall, off_the_wall]),
    )


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

    module = __import__("twolink.simulation", fromlist=["DEFAULT_MAX_EVALUATIONS"])
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
        SimulationError,
        match=r"the motion failed at t = 0\.1\d* s in the state q = \(.*\) rad, qd = .*"
        r"returned non-finite torques",
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


# ------------------------------------------- the quick run: odeint for a picture
FREE_STARTS = [
    (arms.two_metre, [np.pi / 4, 0.0], [0.0, 0.0]),  # the benchmark's chaotic swing
    (TwoLinkArm(1.0, 0.5, m1=3.0, m2=0.5), [-0.3, 2.0], [1.0, -2.0]),
    (TwoLinkArm(2.0, 2.0, g=0.0), [0.0, 1.0], [1.5, -3.0]),  # horizontal, spinning
]
FIVE_SECONDS = np.linspace(
    0.0, 5.0, 251
)  # the explorers' release: a sample every 0.02 s


@pytest.mark.parametrize("arm, q0, qd0", FREE_STARTS)
def test_the_quick_run_follows_the_exact_run_in_free_motion(arm, q0, qd0):
    """At its default tolerances (1e-6) the tip stays within 2 mm of the exact run over 5 s
    (measured: at most 0.5 mm on the chaotic swing) and the energy drifts by less than 1e-4
    (measured: at most 2e-5)."""
    quick = simulate_quick(arm, q0, qd0, FIVE_SECONDS)
    exact = simulate(arm, q0, qd0, 5.0, t_eval=FIVE_SECONDS, **TIGHT)
    assert np.ptp(exact.q[:, 1]) > 0.5  # it really moved
    assert np.array_equal(quick.t, FIVE_SECONDS) and quick.status == 0
    assert np.max(exact.tracking_error(quick.p_tip)) < 2e-3
    assert np.all(quick.tau == 0.0)
    assert quick.energy_drift() < 1e-4
    assert quick.energy_drift() == pytest.approx(
        relative_energy_drift(quick), rel=1e-12
    )
    assert quick.message.startswith("odeint (LSODA) reached t = 5 s at rtol = 1e-06")


def test_the_quick_runs_bounds_can_fail():
    """Looser tolerances break both bounds of the test above: they measure the solver."""
    arm, q0, qd0 = FREE_STARTS[0]
    loose = simulate_quick(arm, q0, qd0, FIVE_SECONDS, rtol=1e-2, atol=1e-2)
    exact = simulate(arm, q0, qd0, 5.0, t_eval=FIVE_SECONDS, **TIGHT)
    assert np.max(exact.tracking_error(loose.p_tip)) > 2e-3
    assert loose.energy_drift() > 1e-4


@pytest.mark.parametrize(
    "stiffness, damping, q0", [(600.0, 20.0, [0.3, 0.6]), (2000.0, 5.0, [0.1, 1.0])]
)
def test_the_quick_run_follows_the_exact_run_under_impedance_control(
    stiffness, damping, q0
):
    """A controlled release (the spring pulls the tip to (3, 1)): tip within 0.1 mm over
    5 s (measured: at most 5e-3 mm), torques reported at the output times."""
    law = controllers.Impedance(ARM, stiffness, damping, [3.0, 1.0])
    quick = simulate_quick(ARM, q0, [0.0, 0.0], FIVE_SECONDS, torque=law)
    exact = simulate(ARM, q0, [0.0, 0.0], 5.0, t_eval=FIVE_SECONDS, torque=law, **TIGHT)
    assert np.max(exact.tracking_error(quick.p_tip)) < 1e-4
    assert np.allclose(quick.tau, law(0.0, quick.q, quick.qd), rtol=0.0, atol=1e-9)
    assert (
        np.max(quick.tracking_error([3.0, 1.0])[-10:]) < 1e-2
    )  # it came to rest there


def test_the_quick_run_reports_at_t_eval_only_and_is_read_only():
    later = simulate_quick(ARM, [0.3, 0.4], [0.0, 0.0], [0.5, 1.0])
    exact = simulate(ARM, [0.3, 0.4], [0.0, 0.0], 1.0, t_eval=[0.0, 0.5, 1.0], **TIGHT)
    assert np.array_equal(later.t, [0.5, 1.0]) and later.q.shape == (2, 2)
    assert np.allclose(later.q, exact.q[1:], atol=1e-5)  # integrated from t = 0
    only_start = simulate_quick(ARM, [0.3, 0.4], [0.1, 0.0], [0.0])
    assert np.array_equal(only_start.q, [[0.3, 0.4]]) and only_start.nfev == 0
    for array in (later.t, later.q, later.qd, later.tau):
        assert not array.flags.writeable


def test_the_quick_run_stops_at_its_evaluation_budget_naming_it_and_the_remedies():
    calls = []

    def counted(t, q, qd):
        calls.append(t)
        return [0.0, 0.0]

    with pytest.raises(SimulationError) as error:
        simulate_quick(
            ARM,
            [np.pi / 4, 0.0],
            [0.0, 0.0],
            FIVE_SECONDS,
            counted,
            max_evaluations=100,
        )
    message = str(error.value)
    assert (
        "the quick run used up its budget of max_evaluations = 100 evaluations"
        in message
    )
    assert " of 5 s (state q = (" in message
    assert "raise max_evaluations, loosen rtol/atol, or run it with simulate" in message
    assert len(calls) == 100  # the 101st evaluation stops it before calling the torque
    enough = simulate_quick(
        ARM, [np.pi / 4, 0.0], [0.0, 0.0], FIVE_SECONDS, max_evaluations=2000
    )
    assert enough.nfev <= 2000


@pytest.mark.parametrize(
    "kwargs",
    [
        {"q0": [0.0, 0.0, 0.0]},
        {"q0": [[0.0, 0.0], [1.0, 1.0]]},
        {"q0": [np.inf, 0.0]},
        {"qd0": [[0.0, 0.0]]},
        {"qd0": [np.nan, 0.0]},
        {"qd0": ["a", "b"]},
        {"t_eval": []},
        {"t_eval": [[0.0, 0.5]]},
        {"t_eval": [0.0, np.nan]},
        {"t_eval": [0.0, np.inf]},
        {"t_eval": [0.5, 0.2]},
        {"t_eval": [0.0, 0.0, 0.5]},
        {"t_eval": [-0.1, 0.5]},
        {"t_eval": ["a", "b"]},
        {"t_eval": [0.0, True]},
        {"torque": [1.0, 2.0]},
        {"torque": lambda t, q, qd: [np.nan, 0.0]},
        {"torque": lambda t, q, qd: [1.0, 2.0, 3.0]},
        {"torque": lambda t, q, qd: "strong"},
        {"arm": TwoLinkArm(1.0, 1.0, m2=0.0)},
        {"max_evaluations": 0},
        {"max_evaluations": 2.5},
        {"max_evaluations": "10"},
    ],
)
def test_the_quick_run_refuses_bad_input_with_the_exact_runs_messages(kwargs):
    """The same checks, the same messages: t_end of simulate is the last of t_eval."""
    arguments = {"arm": ARM, "q0": [0.3, 0.4], "qd0": [0.0, 0.0], "t_eval": [0.0, 0.5]}
    arguments.update(kwargs)
    with pytest.raises((ValueError, TypeError)) as exact:
        simulate(t_end=0.5, **arguments)
    with pytest.raises((ValueError, TypeError)) as quick:
        simulate_quick(**arguments)
    assert type(quick.value) is type(exact.value)
    assert str(quick.value) == str(exact.value)


@pytest.mark.parametrize(
    "kwargs, fragment",
    [
        ({"rtol": 0.0}, r"rtol must be > 0.0; got 0.0"),
        ({"atol": np.nan}, "atol must be finite"),
        ({"rtol": "tight"}, "rtol"),
    ],
)
def test_the_quick_runs_tolerances_are_positive_numbers(kwargs, fragment):
    with pytest.raises(ValueError, match=fragment):
        simulate_quick(ARM, [0.3, 0.4], [0.0, 0.0], [0.0, 0.5], **kwargs)


def test_the_quick_run_turns_a_blow_up_into_a_simulation_error_with_time_and_state():
    with pytest.raises(
        SimulationError,
        match=r"failed at t = 0\.[5-9]\d* s in the state q = \(.*: torque.*non-finite torques",
    ):
        simulate_quick(ARM, [0.3, 0.2], [0.0, 0.0], [0.0, 1.0], _nan_from(0.5))
    with pytest.raises(
        SimulationError, match=r"at t = .* q = \(.*\) rad, qd = \(.*\) rad/s"
    ):  # as simulate's test of overflowing torques
        simulate_quick(
            ARM,
            [0.3, 0.4],
            [0.0, 0.0],
            [0.0, 0.5],
            lambda t, q, qd: [1e300 * (1.0 + qd[0] ** 2), 0.0],
        )


# ----------- one budget mechanism: every run reads the wall clock at every evaluation
def test_the_quick_run_stops_a_slow_torque_function_at_its_wall_time_naming_it():
    """simulate_quick spends the budget simulate spends: a slow torque stops within the wall time, named."""
    started = time.monotonic()
    with pytest.raises(
        SimulationError,
        match=r"the quick run used up its budget of max_wall_time = 0.3 s at t = .*"
        r"the torque function is the likely cause",
    ):
        simulate_quick(
            ARM,
            [0.3, 0.2],
            [0.0, 0.0],
            np.linspace(0.0, 5.0, 11),
            sleepy(0.05),
            max_wall_time=0.3,
        )
    assert time.monotonic() - started < 0.3 + 3 * 0.05


def test_the_engine_stops_a_slow_torque_function_at_its_wall_time():
    pytest.importorskip("mujoco")
    from twolink import engine

    started = time.monotonic()
    with pytest.raises(
        SimulationError,
        match=r"simulate_in_mujoco used up its budget of max_wall_time = 0.3 s at t = .* is slow",
    ):
        engine.simulate_in_mujoco(
            ARM, [0.3, 0.2], [0.0, 0.0], 1.0, sleepy(0.05), max_wall_time=0.3
        )
    assert time.monotonic() - started < 0.3 + 3 * 0.05


def test_a_budget_spent_under_a_small_max_step_blames_max_step_not_stiffness():
    """Free motion is not stiff: when max_step limits the steps, the message says so."""
    with pytest.raises(
        SimulationError,
        match=r"max_evaluations = 12001 .*max_step = 0.001 s limited the steps .*give a larger max_step",
    ) as error:
        simulate(ARM, [0.3, 0.2], [0.0, 0.0], 1.0, max_step=1e-3, max_evaluations=12001)
    assert "stiff" not in str(error.value) and "Radau" not in str(error.value)


@pytest.mark.parametrize(
    "options",
    [{"method": "Radau", "jac_sparsity": None}, {"method": "LSODA", "min_step": 0.0}],
)
def test_each_methods_own_options_pass(options):
    if options.get("min_step") == 0.0:
        with pytest.raises(ValueError, match=r"min_step \(s\) must be > 0.0"):
            simulate(ARM, [0.3, 0.2], [0.0, 0.0], 0.5, **options)
        options = {**options, "min_step": 1e-12}
    assert simulate(ARM, [0.3, 0.2], [0.0, 0.0], 0.5, **options).status == 0
