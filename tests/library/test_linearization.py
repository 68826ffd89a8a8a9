"""twolink.linearization: linear models of the closed loop and the tip mass."""

import dataclasses

import control
import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st
from scipy.optimize import linear_sum_assignment

from conftest import dynamic_arms
from twolink import SingularityError, TwoLinkArm, arms, dynamics, ik
from twolink.contact import SpringWall, TipForce
from twolink.controllers import CartesianSpring, ComputedTorque, Impedance, JointPD
from twolink.linearization import (
    INPUTS,
    OUTPUTS,
    STATES,
    closed_loop_matrices,
    closed_loop_system,
    critical_damping,
    equilibrium,
    linearize,
    tip_mass,
)

ZERO = np.zeros(2)


def state_jacobian_by_differences(arm, controller, q_eq, step=1e-6):
    """d f / d x of the nonlinear closed loop (dynamics.state_derivative), by central differences."""
    rhs = dynamics.state_derivative(arm, controller)
    x_eq = np.concatenate([q_eq, ZERO])
    columns = []
    for index in range(4):
        offset = np.zeros(4)
        offset[index] = step
        columns.append(
            (np.asarray(rhs(0.0, x_eq + offset)) - np.asarray(rhs(0.0, x_eq - offset)))
            / (2 * step)
        )
    return np.column_stack(columns)


def pole_distance(got, expected):
    """Largest distance between two sets of poles, paired so that the total distance is least."""
    distances = np.abs(np.subtract.outer(np.asarray(got), np.asarray(expected)))
    rows, columns = linear_sum_assignment(distances)
    return np.max(distances[rows, columns])


def assert_same_poles(A, A_reference, rtol=1e-5):
    expected = np.linalg.eigvals(A_reference)
    scale = max(1.0, np.max(np.abs(expected)))
    assert pole_distance(np.linalg.eigvals(A), expected) < rtol * scale


@st.composite
def impedance_setups(draw):
    """An arm, a reachable non-singular rest point on a branch, a stiffness and an under-critical damping."""
    arm = draw(dynamic_arms())
    r_low, r_high = arm.reach
    fraction = draw(st.floats(0.15, 0.85))
    direction = draw(st.floats(-np.pi, np.pi))
    rest_point = (r_low + fraction * (r_high - r_low)) * np.array(
        [np.cos(direction), np.sin(direction)]
    )
    q_rest = ik.closed_form(
        arm, rest_point, elbow=draw(st.sampled_from(["down", "up"]))
    ).q
    assume(abs(np.sin(q_rest[1])) > 0.1)
    scale = arm.m1 + arm.m2
    L = np.array(
        [
            [draw(st.floats(1.0, 30.0)), 0.0],
            [draw(st.floats(-10.0, 10.0)), draw(st.floats(1.0, 30.0))],
        ]
    )
    K = scale * L @ L.T
    typical = np.sqrt(scale * np.max(np.abs(K)))  # N s/m of about critical damping
    D = np.diag(
        [draw(st.floats(0.0, 0.5)) * typical, draw(st.floats(0.0, 0.5)) * typical]
    )
    return arm, q_rest, rest_point, K, D


# ---------------------------------------------------------------- poles against a finite-difference Jacobian
@given(impedance_setups(), st.booleans())
def test_impedance_poles_match_a_finite_difference_jacobian(setup, compensate):
    arm, q_rest, rest_point, K, D = setup
    controller = Impedance(arm, K, D, rest_point, gravity_compensation=compensate)
    if compensate:
        q_eq = q_rest
    else:
        try:
            q_eq = equilibrium(arm, controller, q_rest)
        except ValueError:
            assume(False)
        assume(abs(np.sin(q_eq[1])) > 0.1)
    A, _, _, _ = closed_loop_matrices(arm, controller, q_eq)
    A_fd = state_jacobian_by_differences(arm, controller, q_eq)
    scale = np.max(np.abs(A_fd))
    assert np.allclose(A, A_fd, rtol=0.0, atol=1e-5 * scale)
    assert_same_poles(A, A_fd)


@pytest.mark.parametrize(
    "build",
    [
        lambda arm, q: CartesianSpring(
            arm, [[600.0, 100.0], [100.0, 300.0]], arm.fk(q)
        ),
        lambda arm, q: JointPD(
            arm, [[80.0, 10.0], [10.0, 40.0]], [[9.0, 1.0], [1.0, 4.0]], q
        ),
        lambda arm, q: JointPD(arm, 80.0, 9.0, q + 0.1, gravity_compensation=False),
        lambda arm, q: ComputedTorque(arm, 100.0, 12.0, q),
        lambda arm, q: ComputedTorque(
            arm, 100.0, 12.0, q, model=dataclasses.replace(arm, m2=1.5)
        ),
    ],
    ids=[
        "cartesian spring",
        "joint PD",
        "joint PD without compensation",
        "computed torque",
        "computed torque, wrong model",
    ],
)
@pytest.mark.parametrize(
    "arm", [arms.two_metre, TwoLinkArm(1.0, 0.6, m1=3.0, m2=1.0, I2=0.1, g=-4.0)]
)
def test_every_controller_linearises_like_its_finite_difference_jacobian(build, arm):
    q_near = np.array([0.4, 1.3])
    controller = build(arm, q_near)
    q_eq = equilibrium(arm, controller, q_near)
    A, B, C, D = closed_loop_matrices(arm, controller, q_eq)
    A_fd = state_jacobian_by_differences(arm, controller, q_eq)
    assert np.allclose(A, A_fd, rtol=0.0, atol=1e-5 * np.max(np.abs(A_fd)))
    assert_same_poles(A, A_fd)
    # a plain callable takes the finite-difference path and agrees with the analytic one
    A_numeric, _, _, _ = closed_loop_matrices(
        arm, lambda t, q, qd: controller(t, q, qd), q_eq
    )
    assert np.allclose(A_numeric, A, rtol=0.0, atol=1e-6 * np.max(np.abs(A)))


def test_computed_torque_poles_are_those_of_the_error_equation():
    """s^2 + kd s + kp = 0 for each joint, whatever the pose: the model cancels the arm's dynamics."""
    for q in [[0.4, 1.3], [-2.0, -0.5], [1.0, 2.5]]:
        loop = linearize(
            arms.two_metre, ComputedTorque(arms.two_metre, 100.0, 12.0, q), q
        )
        expected = np.roots([1.0, 12.0, 100.0])
        assert pole_distance(control.poles(loop), np.repeat(expected, 2)) < 1e-6


def test_python_controls_own_linearisation_agrees():
    arm = arms.two_metre
    q_rest = ik.closed_form(arm, [3.0, 1.0], elbow="up").q
    impedance = Impedance(arm, [[600.0, 0.0], [0.0, 900.0]], 40.0, [3.0, 1.0])
    analytic = linearize(arm, impedance, q_rest)
    numerical = closed_loop_system(arm, impedance).linearize(
        np.concatenate([q_rest, ZERO]), ZERO
    )
    for mine, theirs in [
        (analytic.A, numerical.A),
        (analytic.B, numerical.B),
        (analytic.C, numerical.C),
    ]:
        assert np.allclose(mine, theirs, rtol=1e-4, atol=1e-4 * np.max(np.abs(theirs)))
    assert list(analytic.state_labels) == list(STATES)
    assert list(analytic.input_labels) == list(INPUTS) and list(
        analytic.output_labels
    ) == list(OUTPUTS)


def test_the_linear_model_predicts_small_motions_of_the_nonlinear_arm():
    """A 1 cm push-off from the rest point: the linear response agrees with the simulation to a fraction of a percent."""
    from twolink import simulate

    arm = arms.two_metre
    q_rest = ik.closed_form(arm, [3.0, 1.0]).q
    impedance = Impedance(arm, 600.0, 20.0, [3.0, 1.0])
    loop = linearize(arm, impedance, q_rest)
    q_start = ik.closed_form(arm, [3.0, 1.01]).q
    t = np.linspace(0.0, 0.5, 101)
    nonlinear = simulate(
        arm, q_start, ZERO, 0.5, torque=impedance, t_eval=t, rtol=1e-10, atol=1e-12
    )
    linear = control.initial_response(loop, t, np.concatenate([q_start - q_rest, ZERO]))
    deviation = arm.fk(nonlinear.q) - arm.fk(q_rest)
    assert np.max(np.abs(linear.outputs.T - deviation)) < 0.005 * 0.01


# ---------------------------------------------------------------- equilibrium checks
def test_linearize_refuses_a_point_that_is_not_an_equilibrium():
    arm = arms.two_metre
    impedance = Impedance(arm, 600.0, 50.0, [3.0, 1.0], gravity_compensation=False)
    q_rest = ik.closed_form(arm, [3.0, 1.0]).q
    with pytest.raises(ValueError, match="is not an equilibrium of the closed loop"):
        linearize(
            arm, impedance, q_rest
        )  # gravity pulls the arm away from the rest point
    linearize(
        arm, impedance, equilibrium(arm, impedance, q_rest)
    )  # the sagged point is one


def test_equilibrium_raises_when_there_is_none():
    arm = arms.two_metre
    with pytest.raises(ValueError, match="no equilibrium found"):
        equilibrium(
            arm, lambda t, q, qd: np.array([1000.0, 0.0]), [0.3, 0.3]
        )  # more than any weight


def test_wall_contact_linearises_through_finite_differences():
    """A TipForce with a spring wall has no analytic derivatives: the numeric path gives the Jacobian's poles."""
    from twolink import statics

    arm = arms.two_metre
    wall = statics.Wall.through([4.0, 0.0], [0.0, 4.0])
    normal = wall.into_wall()
    contact = statics.wall_contact(arm, wall, 500.0)
    q_contact = contact.q[contact.branch("down")]
    world = TipForce(
        arm,
        Impedance(arm, 600.0, 50.0, arm.fk(q_contact) + 0.5 * normal),
        SpringWall(wall, 1e4),
    )
    q_eq = equilibrium(arm, world, q_contact)
    A, _, _, _ = closed_loop_matrices(arm, world, q_eq)
    assert_same_poles(A, state_jacobian_by_differences(arm, world, q_eq), rtol=1e-5)


# ---------------------------------------------------------------- tip mass and critical damping
@given(
    dynamic_arms(),
    st.floats(-np.pi, np.pi),
    st.floats(0.2, np.pi - 0.2),
    st.tuples(st.floats(-10, 10), st.floats(-10, 10)),
)
def test_tip_mass_turns_a_tip_force_into_the_tip_acceleration(arm, q1, q2, push):
    """At rest, with gravity off, a push F accelerates the tip at Lambda^-1 F (the arm's own dynamics say so)."""
    arm = dataclasses.replace(arm, g=0.0)
    q = np.array([q1, q2])
    qdd = dynamics.forward_dynamics(
        arm, q, ZERO, ZERO, force_by_tip=-np.array(push)
    )  # the tip exerts -F when pushed with F
    tip_acceleration = arm.jacobian(q) @ qdd
    expected = np.linalg.solve(tip_mass(arm, q), push)
    assert np.allclose(
        tip_acceleration,
        expected,
        rtol=1e-7,
        atol=1e-9 * (1 + np.max(np.abs(expected))),
    )


def test_tip_mass_is_refused_at_a_singularity():
    with pytest.raises(SingularityError, match="stretched or folded"):
        tip_mass(arms.two_metre, [0.3, 0.0])


@pytest.mark.parametrize("elbow", ["down", "up"])
@pytest.mark.parametrize("rest_point", [[3.0, 1.0], [1.0, 2.5], [-2.0, -0.5]])
def test_critical_damping_gives_real_poles_and_less_does_not(rest_point, elbow):
    arm = arms.two_metre
    q_rest = ik.closed_form(arm, rest_point, elbow=elbow).q

    def zeta(damping):
        return control.damp(
            linearize(arm, Impedance(arm, 600.0, damping, rest_point), q_rest),
            doprint=False,
        )[1]

    d_critical = critical_damping(arm, q_rest, 600.0)
    assert np.min(zeta(d_critical)) == pytest.approx(1.0, abs=1e-6)
    assert (
        np.min(zeta(0.95 * d_critical)) < 0.99
    )  # a bit less damping and a mode oscillates
    assert np.min(zeta(1.05 * d_critical)) == pytest.approx(1.0, abs=1e-9)
    D_matrix = critical_damping(arm, q_rest, 600.0, kind="matrix")
    assert np.allclose(zeta(D_matrix), 1.0, atol=1e-6)  # every mode critical
    assert np.max(np.linalg.eigvalsh(D_matrix)) <= d_critical * (
        1 + 1e-12
    )  # never more than the scalar


def test_critical_damping_checks_its_arguments():
    q_rest = ik.closed_form(arms.two_metre, [3.0, 1.0]).q
    with pytest.raises(ValueError, match="use kind='matrix'"):
        critical_damping(arms.two_metre, q_rest, [[600.0, 0.0], [0.0, 300.0]])
    with pytest.raises(ValueError, match="kind must be one of"):
        critical_damping(arms.two_metre, q_rest, 600.0, kind="joint")
    with pytest.raises(ValueError, match="must be >= 0.0"):
        critical_damping(arms.two_metre, q_rest, -600.0)


# ---------------------------------------------------------------- stiffness felt at the tip
