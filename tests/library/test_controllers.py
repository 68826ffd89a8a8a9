"""twolink.controllers and twolink.contact: the torque laws, on their own and on the simulated arm."""

import dataclasses

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from conftest import arms as arm_strategy
from conftest import configurations, dynamic_arms
from twolink import TwoLinkArm, arms, ik, simulate, statics
from twolink.contact import SpringWall, TipForce
from twolink.controllers import (
    CartesianSpring,
    ComputedTorque,
    Impedance,
    JointPD,
    JointReference,
    gain_matrix,
)
from twolink.linearization import critical_damping, equilibrium

TIGHT = {"method": "DOP853", "rtol": 1e-10, "atol": 1e-10}
ZERO = np.zeros(2)


@st.composite
def psd_matrices(draw, scale=1000.0):
    """Symmetric positive semi-definite 2x2 matrices L L^T with entries of L in [-sqrt(scale), sqrt(scale)]."""
    root = np.sqrt(scale)
    L = np.array([[draw(st.floats(-root, root)) for _ in range(2)] for _ in range(2)])
    return L @ L.T


points = st.tuples(st.floats(-5.0, 5.0), st.floats(-5.0, 5.0)).map(np.array)


def jacobian_by_differences(arm, q, step=1e-6):
    """d fk / dq by central differences (independent of arm.jacobian)."""
    return np.column_stack(
        [(arm.fk(q + step * e) - arm.fk(q - step * e)) / (2 * step) for e in np.eye(2)]
    )


# ---------------------------------------------------------------- gains
def test_gain_matrix_accepts_scalars_and_psd_matrices():
    assert np.array_equal(gain_matrix(3, "k"), 3.0 * np.eye(2))
    assert np.array_equal(
        gain_matrix([[2.0, 1.0], [1.0, 2.0]], "k"), [[2.0, 1.0], [1.0, 2.0]]
    )
    assert np.array_equal(
        gain_matrix(np.zeros((2, 2)), "k"), np.zeros((2, 2))
    )  # no spring at all is allowed
    assert not gain_matrix(1.0, "k").flags.writeable


@pytest.mark.parametrize(
    "value, message",
    [
        (-1.0, "must be >= 0.0"),
        (float("nan"), "must be finite"),
        (float("inf"), "must be finite"),
        ("stiff", "must be a real number"),
        ([[1.0, 2.0], [0.0, 1.0]], "must be symmetric"),
        ([[1.0, 0.0], [0.0, -1.0]], "positive semi-definite"),
        ([[1.0, 3.0], [3.0, 1.0]], "positive semi-definite"),
        ([[1.0, np.nan], [np.nan, 1.0]], "finite entries"),
        ([1.0, 2.0], "2x2 matrix"),
        (np.eye(3), "2x2 matrix"),
    ],
)
def test_gain_matrix_rejects_bad_gains(value, message):
    with pytest.raises(ValueError, match=message):
        gain_matrix(value, "stiffness K (N/m)")


@pytest.mark.parametrize(
    "build",
    [
        lambda arm: CartesianSpring(arm, -600.0, [3.0, 1.0]),
        lambda arm: CartesianSpring(arm, [[600.0, 10.0], [0.0, 600.0]], [3.0, 1.0]),
        lambda arm: CartesianSpring(arm, 600.0, [3.0, np.nan]),
        lambda arm: CartesianSpring(arm, np.nan, [3.0, 1.0]),
        lambda arm: CartesianSpring(arm, 600.0, [3.0, 1.0, 0.0]),
        lambda arm: CartesianSpring("arm", 600.0, [3.0, 1.0]),
        lambda arm: Impedance(arm, 600.0, -1.0, [3.0, 1.0]),
        lambda arm: Impedance(arm, 600.0, 50.0, [3.0, 1.0], gravity_compensation="yes"),
        lambda arm: JointPD(arm, -1.0, 1.0, [0.0, 0.0]),
        lambda arm: JointPD(arm, 1.0, 1.0, [0.0, np.inf]),
        lambda arm: JointPD(arm, 1.0, 1.0, lambda t: [0.0, 0.0]),
        lambda arm: ComputedTorque(arm, 100.0, [[1.0, 2.0], [3.0, 4.0]], [0.0, 0.0]),
        lambda arm: ComputedTorque(arm, 100.0, 20.0, [0.0, 0.0], model="arm"),
        lambda arm: JointReference(np.sin, np.cos, 3.0),
    ],
)
def test_bad_controller_parameters_raise_value_errors(build):
    with pytest.raises(ValueError):
        build(arms.two_metre)


def test_error_messages_say_what_is_allowed():
    with pytest.raises(
        ValueError, match=r"stiffness K \(N/m\) must be >= 0.0; got -600.0"
    ):
        CartesianSpring(arms.two_metre, -600.0, [3.0, 1.0])
    with pytest.raises(ValueError, match=r"must be symmetric \(K = K\^T\)"):
        Impedance(arms.two_metre, [[600.0, 10.0], [0.0, 600.0]], 10.0, [3.0, 1.0])
    with pytest.raises(ValueError, match="rest_point x0 must be finite numbers"):
        Impedance(arms.two_metre, 600.0, 10.0, [np.nan, 1.0])


# ---------------------------------------------------------------- the spring law
@given(arm_strategy(), configurations(), psd_matrices(), points)
def test_spring_torque_is_J_transpose_K_times_stretch(arm, q, K, rest_point):
    spring = CartesianSpring(arm, K, rest_point)
    J = jacobian_by_differences(arm, q)
    expected = J.T @ K @ (rest_point - arm.fk(q))
    scale = (
        np.linalg.norm(J)
        * np.linalg.norm(K)
        * (np.linalg.norm(rest_point) + arm.l1 + arm.l2)
        + 1.0
    )
    assert np.allclose(spring(0.0, q, ZERO), expected, rtol=0.0, atol=1e-6 * scale)
    assert np.allclose(
        spring.force_on_tip(q),
        K @ (rest_point - arm.fk(q)),
        rtol=1e-12,
        atol=1e-9 * scale,
    )


@given(arm_strategy(), configurations(), psd_matrices(), points)
def test_spring_torque_is_minus_the_gradient_of_its_energy(arm, q, K, rest_point):
    """tau = -dV/dq: the virtual spring is conservative (checked without the Jacobian)."""
    spring = CartesianSpring(arm, K, rest_point)
    step = 1e-6
    gradient = np.array(
        [
            (
                spring.potential_energy(q + step * e)
                - spring.potential_energy(q - step * e)
            )
            / (2 * step)
            for e in np.eye(2)
        ]
    )
    scale = (
        np.linalg.norm(K) * (np.linalg.norm(rest_point) + arm.l1 + arm.l2) ** 2 + 1.0
    )
    assert np.allclose(spring.torque(q), -gradient, rtol=0.0, atol=1e-6 * scale)


@pytest.mark.parametrize(
    "build",
    [
        lambda arm: CartesianSpring(arm, [[600.0, 100.0], [100.0, 300.0]], [2.5, 1.5]),
        lambda arm: Impedance(
            arm,
            [[600.0, 100.0], [100.0, 300.0]],
            [[40.0, 5.0], [5.0, 20.0]],
            [2.5, 1.5],
        ),
        lambda arm: Impedance(arm, 600.0, 30.0, [2.5, 1.5], gravity_compensation=False),
        lambda arm: JointPD(
            arm, [[80.0, 10.0], [10.0, 40.0]], [[9.0, 1.0], [1.0, 4.0]], [0.2, 0.9]
        ),
        lambda arm: ComputedTorque(
            arm,
            100.0,
            12.0,
            JointReference(
                lambda t: np.array([0.2 + np.sin(t), 0.9]),
                lambda t: np.array([np.cos(t), 0.0]),
                lambda t: np.array([-np.sin(t), 0.3]),
            ),
        ),
    ],
    ids=[
        "spring",
        "impedance",
        "impedance without compensation",
        "joint PD",
        "computed torque",
    ],
)
@pytest.mark.parametrize("q", [[0.4, 1.3], [-2.0, -0.5], [1.0, 2.5]])
def test_torque_derivatives_are_the_derivatives_of_the_torque(build, q):
    """Each controller's analytic (dtau/dq, dtau/dqd) at qd = 0 against central differences of its torque."""
    arm = TwoLinkArm(1.0, 0.6, m1=3.0, m2=1.0, I2=0.1, g=-4.0)
    controller, q, t, step = build(arm), np.array(q), 0.7, 1e-6
    by_q, by_qd = controller.torque_derivatives(t, q)
    columns_q = [
        (controller(t, q + step * e, ZERO) - controller(t, q - step * e, ZERO))
        / (2 * step)
        for e in np.eye(2)
    ]
    columns_qd = [
        (controller(t, q, step * e) - controller(t, q, -step * e)) / (2 * step)
        for e in np.eye(2)
    ]
    scale = 1.0 + np.max(np.abs(by_q)) + np.max(np.abs(by_qd))
    assert np.allclose(by_q, np.column_stack(columns_q), rtol=0.0, atol=1e-7 * scale)
    assert np.allclose(by_qd, np.column_stack(columns_qd), rtol=0.0, atol=1e-7 * scale)


def test_spring_is_vectorised_and_matches_single_states():
    spring = CartesianSpring(
        arms.two_metre, [[600.0, 100.0], [100.0, 300.0]], [3.0, 1.0]
    )
    q_grid = np.random.default_rng(1).uniform(-np.pi, np.pi, size=(4, 3, 2))
    batch = spring.torque(q_grid)
    assert batch.shape == (4, 3, 2)
    for index in np.ndindex(4, 3):
        assert np.allclose(
            batch[index], spring(0.0, q_grid[index], ZERO), rtol=1e-14, atol=1e-12
        )
    assert spring.potential_energy(q_grid).shape == (4, 3)


def test_the_source_exercise_numbers():
    """k = 600 N/m, rest point (3, 1), tip on x = 3: tau1 = x F_y on both branches, zero at the rest point."""
    arm = arms.two_metre
    spring = CartesianSpring(arm, 600.0, [3.0, 1.0])
    for y in np.linspace(0.0, 2.0, 9):
        for q in ik.closed_form(arm, [3.0, y], elbow="both").q:
            tau = spring(0.0, q, ZERO)
            assert tau[0] == pytest.approx(3.0 * 600.0 * (1.0 - y), abs=1e-9)
            elbow = arm.joint_positions(q)[1]
            assert tau[1] == pytest.approx(
                (3.0 - elbow[0]) * 600.0 * (1.0 - y), abs=1e-9
            )
    assert np.allclose(
        spring(0.0, ik.closed_form(arm, [3.0, 1.0]).q, ZERO), 0.0, atol=1e-9
    )


def test_impedance_torque_adds_damping_and_gravity():
    arm = arms.two_metre
    q, qd = np.array([0.3, 1.1]), np.array([0.5, -0.7])
    D = np.array([[40.0, 5.0], [5.0, 20.0]])
    with_gravity = Impedance(arm, 600.0, D, [3.0, 1.0])
    without = dataclasses.replace(with_gravity, gravity_compensation=False)
    J = arm.jacobian(q)
    expected = J.T @ (600.0 * (np.array([3.0, 1.0]) - arm.fk(q)) - D @ J @ qd)
    assert np.allclose(without(0.0, q, qd), expected, rtol=1e-13)
    assert np.allclose(with_gravity(0.0, q, qd), expected + arm.gravity(q), rtol=1e-13)
    assert np.allclose(
        with_gravity.spring(0.0, q, qd),
        J.T @ (600.0 * (np.array([3.0, 1.0]) - arm.fk(q))),
    )


# ---------------------------------------------------------------- on the simulated arm
@settings(max_examples=15)
@given(
    dynamic_arms(),
    st.floats(0.1, 0.9),
    st.floats(-np.pi, np.pi),
    st.sampled_from(["down", "up"]),
)
def test_at_the_rest_point_with_gravity_compensation_the_arm_stays_at_rest(
    arm, reach_fraction, direction, elbow
):
    r_low, r_high = arm.reach
    rest_point = (r_low + reach_fraction * (r_high - r_low)) * np.array(
        [np.cos(direction), np.sin(direction)]
    )
    q_rest = ik.closed_form(arm, rest_point, elbow=elbow).q
    assume(abs(np.sin(q_rest[1])) > 0.05)
    control = Impedance(
        arm, 100.0 * (arm.m1 + arm.m2), 5.0 * (arm.m1 + arm.m2), rest_point
    )
    result = simulate(arm, q_rest, ZERO, 2.0, torque=control, **TIGHT)
    # Bounds set by the solver's accuracy (atol = 1e-10 on the state), far below the sag of a missing g(q)
    # (the next test): the tip stays put to 1e-8 of the arm's size and the joints barely stir.
    assert np.max(np.linalg.norm(arm.fk(result.q) - rest_point, axis=-1)) < 1e-8 * (
        arm.l1 + arm.l2
    )
    assert np.max(np.abs(result.qd)) < 1e-6


def test_without_gravity_compensation_the_arm_sags():
    """The same test fails when the weight is not carried: the check above can fail."""
    arm = arms.two_metre
    q_rest = ik.closed_form(arm, [3.0, 1.0]).q
    control = Impedance(arm, 600.0, 60.0, [3.0, 1.0], gravity_compensation=False)
    result = simulate(arm, q_rest, ZERO, 2.0, torque=control, **TIGHT)
    assert np.max(np.abs(result.q - q_rest)) > 1e-3


@pytest.mark.parametrize(
    "arm", [arms.two_metre, dataclasses.replace(arms.two_metre, g=0.0)]
)
@pytest.mark.parametrize("start", [[3.0, 2.0], [2.0, 0.5], [3.5, 1.5]])
def test_the_critically_damped_loop_settles_at_the_rest_point(arm, start):
    rest_point = np.array([3.0, 1.0])
    q_rest = ik.closed_form(arm, rest_point).q
    control = Impedance(arm, 600.0, critical_damping(arm, q_rest, 600.0), rest_point)
    result = simulate(
        arm,
        ik.closed_form(arm, start).q,
        ZERO,
        3.0,
        torque=control,
        t_eval=[0.0, 0.2, 3.0],
        **TIGHT,
    )
    p_end = arm.fk(result.q[-1])
    assert np.linalg.norm(p_end - rest_point) < 1e-6  # metres, after 3 s
    assert np.linalg.norm(arm.tip_velocity(result.q[-1], result.qd[-1])) < 1e-5  # m/s
    assert (
        np.linalg.norm(arm.fk(result.q[1]) - rest_point) > 1e-2
    )  # it was still on its way at 0.2 s


def test_without_compensation_it_settles_where_spring_and_weight_balance():
    arm = arms.two_metre
    rest_point = np.array([3.0, 1.0])
    q_rest = ik.closed_form(arm, rest_point).q
    control = Impedance(
        arm,
        600.0,
        critical_damping(arm, q_rest, 600.0),
        rest_point,
        gravity_compensation=False,
    )
    q_balance = equilibrium(arm, control, q_rest)
    result = simulate(
        arm,
        ik.closed_form(arm, [3.0, 2.0]).q,
        ZERO,
        4.0,
        torque=control,
        t_eval=[0.0, 4.0],
        **TIGHT,
    )
    assert np.allclose(result.q[-1], q_balance, atol=1e-6)
    sag = rest_point - arm.fk(q_balance)
    assert sag[1] > 0.01  # below the rest point by more than a centimetre
    # Statics: the spring's pull on the tip carries the weight: J^T K (x0 - x) = g(q)
    assert np.allclose(
        arm.jacobian(q_balance).T @ (600.0 * sag), arm.gravity(q_balance), atol=1e-8
    )


def test_the_pure_spring_conserves_arm_plus_spring_energy():
    arm = arms.two_metre
    spring = CartesianSpring(arm, 600.0, [3.0, 1.0])
    result = simulate(
        arm, ik.closed_form(arm, [3.0, 2.0]).q, ZERO, 2.0, torque=spring, **TIGHT
    )
    kinetic, potential = result.energy()
    total = kinetic + potential + spring.potential_energy(result.q)
    assert np.max(kinetic) > 100.0  # it really swings
    assert np.max(np.abs(total - total[0])) < 1e-8 * np.max(kinetic)
    # and without the spring's energy the books do not balance
    assert np.max(np.abs(kinetic + potential - (kinetic[0] + potential[0]))) > 100.0


# ---------------------------------------------------------------- references and tracking
def wave_reference(centre, amplitude, omega):
    centre, amplitude = np.asarray(centre), np.asarray(amplitude)
    return JointReference(
        lambda t: centre + amplitude * np.sin(omega * t),
        lambda t: amplitude * omega * np.cos(omega * t),
        lambda t: -amplitude * omega**2 * np.sin(omega * t),
    )


@pytest.mark.parametrize(
    "arm", [arms.two_metre, TwoLinkArm(1.0, 0.6, m1=3.0, m2=1.0, I2=0.1)]
)
def test_computed_torque_tracks_a_smooth_trajectory(arm):
    """Started on the reference, the error stays below 1e-7 rad (only the solver's error);
    started off it, each joint's error stays inside the critically damped envelope e0 (1 + wn t) exp(-wn t)."""
    reference = wave_reference([0.3, 1.2], [0.8, -0.6], omega=2.0)
    omega_n = 10.0
    control = ComputedTorque(arm, kp=omega_n**2, kd=2 * omega_n, reference=reference)
    t_eval = np.linspace(0.0, 3.0, 301)
    on_track = simulate(
        arm,
        reference(0.0)[0],
        reference(0.0)[1],
        3.0,
        torque=control,
        t_eval=t_eval,
        **TIGHT,
    )
    error = np.array([reference(t)[0] for t in t_eval]) - on_track.q
    assert np.max(np.abs(error)) < 1e-7

    e0 = np.array([0.2, -0.15])
    off_track = simulate(
        arm,
        reference(0.0)[0] - e0,
        reference(0.0)[1],
        3.0,
        torque=control,
        t_eval=t_eval,
        **TIGHT,
    )
    error = np.array([reference(t)[0] for t in t_eval]) - off_track.q
    envelope = (
        np.abs(e0) * ((1 + omega_n * t_eval) * np.exp(-omega_n * t_eval))[:, None]
    )
    assert np.max(np.abs(error) - envelope) < 1e-7
    assert np.max(np.abs(error[-1])) < 1e-9


def test_model_errors_and_pd_control_leave_tracking_errors():
    """The tracking test can fail: a wrong model, or PD without the model, tracks visibly worse."""
    arm = arms.two_metre
    reference = wave_reference([0.3, 1.2], [0.8, -0.6], omega=2.0)
    t_eval = np.linspace(0.0, 3.0, 61)
    q0, qd0, _ = reference(0.0)

    def worst_error(control):
        result = simulate(arm, q0, qd0, 3.0, torque=control, t_eval=t_eval, **TIGHT)
        return np.max(np.abs(np.array([reference(t)[0] for t in t_eval]) - result.q))

    wrong_model = dataclasses.replace(arm, m2=2.0 * arm.m2)
    assert (
        worst_error(ComputedTorque(arm, 100.0, 20.0, reference, model=wrong_model))
        > 1e-3
    )
    M_mid = arm.mass_matrix([0.3, 1.2])
    assert worst_error(JointPD(arm, 100.0 * M_mid, 20.0 * M_mid, reference)) > 1e-2


def test_joint_pd_holds_its_reference_and_tracks_one_from_samples():
    arm = arms.two_metre
    q_ref = np.array([0.4, 0.9])
    hold = simulate(
        arm, q_ref, ZERO, 2.0, torque=JointPD(arm, 200.0, 30.0, q_ref), **TIGHT
    )
    assert np.max(np.abs(hold.q - q_ref)) < 1e-9
    t = np.linspace(0.0, 2.0, 41)
    samples = JointReference.from_samples(
        t, np.column_stack([0.4 + 0.1 * t, 0.9 - 0.05 * t**2])
    )
    follow = simulate(
        arm,
        q_ref,
        samples(0.0)[1],
        2.0,
        torque=JointPD(arm, 400.0, 40.0, samples),
        **TIGHT,
    )
    assert np.max(np.abs(follow.q[-1] - samples(2.0)[0])) < 0.05


# ---------------------------------------------------------------- impedance against a wall
WALL = statics.Wall.through([4.0, 0.0], [0.0, 4.0])


def test_impedance_pushing_on_a_stiff_wall_reproduces_the_statics_answer():
    """Chapter 4's wall (x + y = 4, 500 N): the rest point behind the wall by F/k + F/k_wall makes the
    simulated arm settle pushing with 500 N, in the configuration and with the torques of statics.wall_contact."""
    arm = arms.two_metre
    k, k_wall, push = 600.0, 1e5, 500.0
    normal = WALL.into_wall()
    depth = push / k_wall
    pressed_wall = statics.Wall(
        WALL.point + depth * normal, normal
    )  # where the tip will rest
    statics_answer = statics.wall_contact(arm, pressed_wall, push, include_gravity=True)
    p_contact = statics_answer.p_contact[statics_answer.branch("down")]
    rest_point = p_contact + (push / k) * normal
    q_start = ik.closed_form(arm, p_contact - 0.3 * normal).q
    control = Impedance(arm, k, 80.0, rest_point)
    world = TipForce(arm, control, SpringWall(WALL, k_wall, damping=2000.0))
    result = simulate(arm, q_start, ZERO, 3.0, torque=world, t_eval=[0.0, 3.0], **TIGHT)
    q_end = result.q[-1]
    contact_force = (
        -world.force_on_tip_at(3.0, q_end, result.qd[-1]) @ normal
    )  # what the tip exerts on the wall
    assert contact_force == pytest.approx(push, rel=1e-6)
    assert np.allclose(
        q_end, statics_answer.q[statics_answer.branch("down")], atol=1e-7
    )
    assert np.allclose(
        control(3.0, q_end, ZERO),
        statics_answer.tau[statics_answer.branch("down")],
        rtol=1e-6,
        atol=1e-4,
    )


# ----------------------------------------------------------------- edges: shapes named, batches of states
def test_joint_pd_and_computed_torque_take_a_batch_of_states_row_by_row():
    rng = np.random.default_rng(0)
    q, qd = rng.normal(size=(5, 2)), rng.normal(size=(5, 2))
    for control in (
        JointPD(arms.two_metre, 100.0, 20.0, [0.5, 0.5]),
        ComputedTorque(arms.two_metre, 100.0, 20.0, [0.5, 0.5]),
    ):
        rows = np.array([control(0.3, q_row, qd_row) for q_row, qd_row in zip(q, qd)])
        assert np.allclose(control(0.3, q, qd), rows, rtol=1e-13, atol=1e-12)


@pytest.mark.parametrize(
    "control",
    [
        JointPD(arms.two_metre, 100.0, 20.0, [0.5, 0.5]),
        ComputedTorque(arms.two_metre, 100.0, 20.0, [0.5, 0.5]),
        Impedance(arms.two_metre, 600.0, 50.0, [3.0, 1.0]),
    ],
    ids=["JointPD", "ComputedTorque", "Impedance"],
)
def test_wrong_shapes_are_named_not_left_to_numpy_matmul(control):
    with pytest.raises(
        ValueError, match=r"^q must have shape \(\.\.\., 2\) .*got shape \(3,\)"
    ):
        control(0.0, [0.1, 0.2, 0.3], [0.0, 0.0])
    with pytest.raises(
        ValueError,
        match=r"^q of shape \(3, 2\) and qd of shape \(4, 2\) do not broadcast together",
    ):
        control(0.0, np.zeros((3, 2)), np.zeros((4, 2)))


def test_a_reference_returning_the_wrong_shape_is_named():
    three = JointReference(
        lambda t: [1.0, 2.0, 3.0], lambda t: [0.0, 0.0], lambda t: [0.0, 0.0]
    )
    with pytest.raises(
        ValueError,
        match=r"the reference's position\(t\) must return two numbers \(rad\), shape \(2,\); got \[1.0, 2.0, 3.0\] at t = 0.0",
    ):
        JointPD(arms.two_metre, 100.0, 20.0, three)(0.0, [0.0, 0.0], [0.0, 0.0])


@pytest.mark.parametrize("flag", ["False", 0, None])
def test_gravity_compensation_takes_only_true_or_false(flag):
    with pytest.raises(ValueError, match=r"gravity_compensation must be True or False"):
        JointPD(arms.two_metre, 100.0, 20.0, [0.5, 0.5], gravity_compensation=flag)


def test_a_shape_mismatch_of_the_impedance_force_names_the_arguments_and_their_shapes():
    impedance = Impedance(arms.two_metre, 600.0, 50.0, [3.0, 1.0])
    with pytest.raises(
        ValueError,
        match=r"q of shape \(3, 2\) and qd of shape \(4, 2\) do not broadcast",
    ):
        impedance.force_on_tip(np.zeros((3, 2)), np.zeros((4, 2)))


ONE_STATE_CONTROLLERS = {
    "spring": lambda: CartesianSpring(arms.two_metre, 600.0, [3.0, 1.0]),
    "impedance": lambda: Impedance(arms.two_metre, 600.0, 50.0, [3.0, 1.0]),
    "joint PD": lambda: JointPD(arms.two_metre, 100.0, 20.0, [0.3, 0.6]),
    "computed torque": lambda: ComputedTorque(arms.two_metre, 100.0, 20.0, [0.3, 0.6]),
    "tip force": lambda: TipForce(
        arms.two_metre, Impedance(arms.two_metre, 600.0, 50.0, [3.0, 1.0]), [1.0, -2.0]
    ),
}


@pytest.mark.parametrize(
    "build", ONE_STATE_CONTROLLERS.values(), ids=ONE_STATE_CONTROLLERS
)
@given(q=configurations(), qd=configurations())
@settings(max_examples=25, deadline=None)
def test_one_state_as_a_simulation_passes_it_gets_the_torque_of_any_other_form(
    build, q, qd
):
    control = build()
    as_arrays = control(0.1, np.array(q, dtype=float), np.array(qd, dtype=float))
    as_lists = control(0.1, list(map(float, q)), list(map(float, qd)))
    assert np.array_equal(as_arrays, as_lists)
    if isinstance(control, TipForce):  # one state only
        return
    as_a_batch = control(0.1, np.array([q], dtype=float), np.array([qd], dtype=float))
    assert np.allclose(as_arrays, np.reshape(as_a_batch, 2), rtol=1e-12, atol=1e-9)


@pytest.mark.parametrize(
    "build", ONE_STATE_CONTROLLERS.values(), ids=ONE_STATE_CONTROLLERS
)
def test_a_non_finite_state_in_float_arrays_is_refused_as_in_a_list(build):
    control = build()
    for bad in ([np.nan, 0.2], [0.1, np.inf]):
        with pytest.raises(ValueError) as from_array:
            control(0.0, np.array(bad), np.zeros(2))
        with pytest.raises(ValueError) as from_list:
            control(0.0, bad, [0.0, 0.0])
        assert str(from_array.value) == str(from_list.value)
        assert "finite" in str(from_array.value)
