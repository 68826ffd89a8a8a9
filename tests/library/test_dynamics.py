"""Dynamics of the 2R arm: symbolic derivation, numeric M, C, g, inverse/forward dynamics, energy."""

import dataclasses
import functools

import mpmath
import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from conftest import configurations, dynamic_arms, rates
from twolink import TwoLinkArm, arms, dynamics
from twolink.symbolic import dynamics_symbols, equations_of_motion, lambdify_dynamics


@functools.cache
def numeric(model):
    """The derived equations of ``model``, made numeric once, when a test first asks
    (not at import: every test worker imports this file to collect it)."""
    return lambdify_dynamics(model)


# Absolute link angles theta = T q and torques tau = T^T u (virtual work) for T below.
TO_ABSOLUTE = np.array([[1.0, 0.0], [1.0, 1.0]])

pairs = st.tuples(rates, rates).map(np.array)


def mass_scale(arm):
    """The largest entry M can have (M11 stretched out), for relative tolerances."""
    return float(arm.mass_matrix([0.0, 0.0])[0, 0])


def gravity_scale(arm):
    """Upper bound of |g_i(q)|: the weights times their largest moment arms."""
    return abs(arm.g) * (arm.m1 * arm.l1 / 2 + arm.m2 * (arm.l1 + arm.l2 / 2))


def assert_within(actual, expected, tolerance):
    tolerance = max(
        tolerance, 1e-300
    )  # relative tolerances of exact zeros (g = 0) stay meaningful
    error = float(np.max(np.abs(np.asarray(actual) - np.asarray(expected))))
    assert error <= tolerance, (
        f"max error {error:.3e} > {tolerance:.3e}\nactual {actual}\nexpected {expected}"
    )


# ----------------------------------------------------------------- symbolic derivation
@pytest.mark.parametrize("model", ["relative", "absolute"])
def test_m_c_g_reproduce_the_euler_lagrange_equations(model):
    assert equations_of_motion(model).residual() == sp.zeros(2, 1)


@pytest.mark.parametrize("model", ["relative", "absolute"])
def test_symbolic_mass_matrix_is_symmetric_and_coriolis_skew_property_holds(model):
    eom = equations_of_motion(model)
    assert sp.simplify(eom.M - eom.M.T) == sp.zeros(2, 2)
    M_dot = sp.Matrix(
        2,
        2,
        lambda i, j: sum(sp.diff(eom.M[i, j], q) * qd for q, qd in zip(eom.q, eom.qd)),
    )
    N = M_dot - 2 * eom.C
    assert sp.simplify(N + N.T) == sp.zeros(2, 2)


def test_relative_model_matches_the_textbook_uniform_rod_form():
    s = dynamics_symbols()
    eom = equations_of_motion("relative")
    rods = {s["I1"]: s["m1"] * s["l1"] ** 2 / 12, s["I2"]: s["m2"] * s["l2"] ** 2 / 12}
    l1, l2, m1, m2, q2 = s["l1"], s["l2"], s["m1"], s["m2"], s["q2"]
    expected_M = sp.Matrix(
        [
            [
                m1 * l1**2 / 3 + m2 * (l1**2 + l2**2 / 3 + l1 * l2 * sp.cos(q2)),
                m2 * (l2**2 / 3 + l1 * l2 * sp.cos(q2) / 2),
            ],
            [m2 * (l2**2 / 3 + l1 * l2 * sp.cos(q2) / 2), m2 * l2**2 / 3],
        ]
    )
    assert sp.simplify(eom.M.subs(rods) - expected_M) == sp.zeros(2, 2)


def test_the_two_models_are_the_same_machine():
    """theta = (q1, q1 + q2) turns the absolute model into the relative one, with tau = T^T u."""
    s = dynamics_symbols()
    relative, absolute = (
        equations_of_motion("relative"),
        equations_of_motion("absolute"),
    )
    substitution = {
        s["theta1"]: s["q1"],
        s["theta2"]: s["q1"] + s["q2"],
        s["thetad1"]: s["qd1"],
        s["thetad2"]: s["qd1"] + s["qd2"],
        s["thetadd1"]: s["qdd1"],
        s["thetadd2"]: s["qdd1"] + s["qdd2"],
    }
    T = sp.Matrix(TO_ABSOLUTE.astype(int))
    absolute_lhs = (
        absolute.M * absolute.qdd + absolute.C * absolute.qd + absolute.g
    ).subs(substitution)
    relative_lhs = relative.M * relative.qdd + relative.C * relative.qd + relative.g
    assert sp.simplify(T.T * absolute_lhs - relative_lhs) == sp.zeros(2, 1)
    assert sp.simplify(
        T.T * absolute.M.subs(substitution) * T - relative.M
    ) == sp.zeros(2, 2)
    assert sp.simplify(
        T.T * absolute.Q - sp.Matrix([s["u1"] + s["u2"], s["u2"]])
    ) == sp.zeros(2, 1)
    # The energies are the same function of the motion.
    assert sp.simplify(absolute.kinetic.subs(substitution) - relative.kinetic) == 0
    assert sp.simplify(absolute.potential.subs(substitution) - relative.potential) == 0


def test_relative_generalised_forces_are_the_motor_torques():
    s = dynamics_symbols()
    assert equations_of_motion("relative").Q == sp.Matrix([s["tau1"], s["tau2"]])


def test_derivation_is_cached_and_immutable():
    eom = equations_of_motion("relative")
    assert equations_of_motion("relative") is eom
    with pytest.raises(TypeError):
        eom.M[0, 0] = 0
    with pytest.raises(dataclasses.FrozenInstanceError):
        eom.model = "absolute"


def test_unknown_model_raises():
    with pytest.raises(ValueError, match="model must be one of"):
        equations_of_motion("polar")


# ----------------------------------------------------------------- numeric == symbolic
@given(dynamic_arms(), configurations(), pairs)
def test_numeric_matches_symbolic_relative_model(arm, q, qd):
    symbolic = numeric("relative")
    scale = mass_scale(arm)
    assert_within(arm.mass_matrix(q), symbolic.mass_matrix(arm, q), 1e-12 * scale)
    assert_within(
        arm.coriolis(q, qd),
        symbolic.coriolis(arm, q, qd),
        1e-12 * scale * (1 + np.abs(qd).sum()),
    )
    assert_within(arm.gravity(q), symbolic.gravity(arm, q), 1e-12 * gravity_scale(arm))


@given(dynamic_arms(), configurations(), pairs, pairs)
def test_numeric_matches_symbolic_absolute_model_after_change_of_variables(
    arm, q, qd, qdd
):
    """The absolute model's torques u, mapped by tau = T^T u, are the DH torques of the same motion."""
    symbolic = numeric("absolute")
    theta, thetad, thetadd = q @ TO_ABSOLUTE.T, qd @ TO_ABSOLUTE.T, qdd @ TO_ABSOLUTE.T
    u = (
        symbolic.mass_matrix(arm, theta) @ thetadd
        + symbolic.coriolis(arm, theta, thetad) @ thetad
        + symbolic.gravity(arm, theta)
    )
    tau = arm.inverse_dynamics(q, qd, qdd)
    scale = mass_scale(arm) * (
        np.abs(qdd).sum() + np.abs(qd).sum() ** 2
    ) + gravity_scale(arm)
    assert_within(TO_ABSOLUTE.T @ u, tau, 1e-12 * scale)
    assert_within(
        TO_ABSOLUTE.T @ symbolic.mass_matrix(arm, theta) @ TO_ABSOLUTE,
        arm.mass_matrix(q),
        1e-12 * mass_scale(arm),
    )


# ----------------------------------------------------------------- properties of M and C
@given(dynamic_arms(), configurations())
def test_mass_matrix_is_symmetric_positive_definite(arm, q):
    M = arm.mass_matrix(q)
    assert M[0, 1] == M[1, 0]
    assert np.all(np.linalg.eigvalsh(M) > 0)
    np.linalg.cholesky(M)  # raises LinAlgError unless positive definite


def test_mass_matrix_of_known_bodies():
    """Stretched out, equal rods are one rod of length 2l about its end; link 2 alone is a rod about its end."""
    arm = TwoLinkArm(1.5, 1.5, m1=2.0, m2=2.0)
    M = arm.mass_matrix([0.3, 0.0])
    assert M[0, 0] == pytest.approx(4.0 * 3.0**2 / 3.0, rel=1e-14)
    assert M[1, 1] == pytest.approx(2.0 * 1.5**2 / 3.0, rel=1e-14)
    # Inertia override: a point mass m2 at the centre of link 2 (I2 = 0).
    point = TwoLinkArm(1.0, 2.0, m1=1.0, m2=3.0, I2=0.0)
    assert point.mass_matrix([0.0, 0.0])[1, 1] == pytest.approx(3.0 * 1.0**2, rel=1e-14)


@given(dynamic_arms(), configurations(), pairs)
def test_m_dot_minus_2c_is_skew_symmetric(arm, q, qd):
    step = 1e-6
    M_dot = (arm.mass_matrix(q + step * qd) - arm.mass_matrix(q - step * qd)) / (
        2 * step
    )
    N = M_dot - 2 * arm.coriolis(q, qd)
    tolerance = 1e-8 * mass_scale(arm) * (1 + np.abs(qd).sum())
    assert_within(N + N.T, np.zeros((2, 2)), tolerance)
    assert abs(qd @ N @ qd) <= tolerance * (1 + qd @ qd)


def test_skew_test_rejects_another_valid_coriolis_factorisation():
    """C' below gives the same C' qd but dM/dt - 2C' is not skew: the property picks the Christoffel C."""
    arm, q, qd = arms.two_metre, np.array([0.2, 0.9]), np.array([0.7, -1.3])
    h = -arm.m2 * arm.l1 * arm.l2 / 2 * np.sin(q[1])
    other_C = np.array([[2 * h * qd[1], h * qd[1]], [-h * qd[0], 0.0]])
    assert np.allclose(other_C @ qd, arm.coriolis(q, qd) @ qd, atol=1e-12)
    step = 1e-6
    M_dot = (arm.mass_matrix(q + step * qd) - arm.mass_matrix(q - step * qd)) / (
        2 * step
    )
    assert np.abs((M_dot - 2 * other_C) + (M_dot - 2 * other_C).T).max() > 0.1


# ----------------------------------------------------------------- inverse / forward dynamics
@given(dynamic_arms(), configurations(), pairs, pairs)
def test_inverse_then_forward_returns_the_acceleration(arm, q, qd, qdd):
    tau = arm.inverse_dynamics(q, qd, qdd)
    M = arm.mass_matrix(q)
    # Error of the round trip: rounding of tau (scale of its terms) amplified by M^-1.
    tau_scale = mass_scale(arm) * (
        np.abs(qdd).sum() + np.abs(qd).sum() ** 2
    ) + gravity_scale(arm)
    tolerance = 1e-13 * np.abs(np.linalg.inv(M)).max() * tau_scale
    assert_within(arm.forward_dynamics(q, qd, tau), qdd, tolerance)


@given(dynamic_arms(), configurations(), pairs, pairs)
def test_closed_form_solve_agrees_with_numpy_solve(arm, q, qd, tau):
    M = arm.mass_matrix(q)
    rhs = tau - arm.coriolis(q, qd) @ qd - arm.gravity(q)
    expected = np.linalg.solve(M, rhs)
    tolerance = (
        1e-13
        * np.linalg.cond(M)
        * (np.abs(expected).max() + np.abs(np.linalg.inv(M)).max() * np.abs(rhs).max())
    )
    assert_within(arm.forward_dynamics(q, qd, tau), expected, tolerance)


def test_vectorised_and_single_state_paths_agree():
    rng = np.random.default_rng(4)
    arm = TwoLinkArm(1.3, 0.8, m1=2.0, m2=0.7, g=9.81)
    q, qd, tau = rng.normal(size=(3, 50, 2))
    batch = arm.forward_dynamics(q, qd, tau)
    one_by_one = np.array([arm.forward_dynamics(*state) for state in zip(q, qd, tau)])
    lists = np.array(
        [
            arm.forward_dynamics(list(a), tuple(b), list(c))
            for a, b, c in zip(q, qd, tau)
        ]
    )
    assert np.allclose(batch, one_by_one, rtol=1e-14, atol=1e-12)
    assert np.allclose(batch, lists, rtol=1e-14, atol=1e-12)
    tau_batch = arm.inverse_dynamics(q, qd, batch)
    tau_one = np.array([arm.inverse_dynamics(*state) for state in zip(q, qd, batch)])
    assert np.allclose(tau_batch, tau_one, rtol=1e-14, atol=1e-12)
    assert np.allclose(tau_batch, tau, rtol=1e-12, atol=1e-12)
    weight_batch = arm.gravity(q)
    for weight_one in (
        np.array([arm.gravity(one) for one in q]),
        np.array([arm.gravity(list(one)) for one in q]),
    ):
        # the same terms; math.cos and numpy's cos may differ in the last bit
        assert np.allclose(weight_batch, weight_one, rtol=1e-14, atol=1e-12)


def test_leading_axes_broadcast():
    arm = arms.two_metre
    q = np.zeros((3, 4, 2))
    qd = np.ones(2)
    assert arm.mass_matrix(q).shape == (3, 4, 2, 2)
    assert arm.coriolis(q, qd).shape == (3, 4, 2, 2)
    assert arm.coriolis(qd, q).shape == (3, 4, 2, 2)
    assert arm.gravity(q).shape == (3, 4, 2)
    assert arm.inverse_dynamics(q, qd, qd).shape == (3, 4, 2)
    assert arm.forward_dynamics(qd, q, qd).shape == (3, 4, 2)
    kinetic, potential = arm.energy(qd, q)
    assert kinetic.shape == potential.shape == (3, 4)
    assert arm.forward_dynamics([0, 0], [0, 0], [0, 0]).shape == (
        2,
    )  # ints take the checked path


def test_arm_methods_delegate_to_the_dynamics_module():
    arm, q, qd, qdd = (
        arms.osake,
        np.array([0.4, -1.1]),
        np.array([2.0, 0.5]),
        np.array([-1.0, 3.0]),
    )
    assert np.array_equal(arm.mass_matrix(q), dynamics.mass_matrix(arm, q))
    assert np.array_equal(arm.coriolis(q, qd), dynamics.coriolis(arm, q, qd))
    assert np.array_equal(arm.gravity(q), dynamics.gravity(arm, q))
    assert np.array_equal(
        arm.inverse_dynamics(q, qd, qdd), dynamics.inverse_dynamics(arm, q, qd, qdd)
    )
    tau = arm.inverse_dynamics(q, qd, qdd)
    assert np.array_equal(
        arm.forward_dynamics(q, qd, tau), dynamics.forward_dynamics(arm, q, qd, tau)
    )
    assert np.array_equal(
        np.array(arm.energy(q, qd)), np.array(dynamics.energy(arm, q, qd))
    )


# ----------------------------------------------------------------- gravity and statics
def test_gravity_direction_and_switch():
    arm = arms.two_metre
    # Straight out along +x the weights pull down: the motors must push up (positive torques).
    assert np.all(arm.gravity([0.0, 0.0]) > 0)
    # Released there, link 1 falls (clockwise, qdd1 < 0).
    assert arm.forward_dynamics([0.0, 0.0], [0.0, 0.0], [0.0, 0.0])[0] < 0
    # Hanging straight down or standing straight up needs no torque.
    assert np.allclose(
        arm.gravity([[-np.pi / 2, 0.0], [np.pi / 2, 0.0]]), 0.0, atol=1e-12
    )
    horizontal = dataclasses.replace(arm, g=0.0)
    q = np.random.default_rng(1).uniform(-np.pi, np.pi, (20, 2))
    assert np.all(horizontal.gravity(q) == 0.0)
    assert np.all(horizontal.forward_dynamics(q, np.zeros(2), np.zeros(2)) == 0.0)


@given(dynamic_arms(), configurations())
def test_gravity_is_the_statics_of_the_link_weights(arm, q):
    """Free-body check: each motor holds the moments, about its joint, of the weights beyond it."""
    q1, q12 = q[0], q[0] + q[1]
    elbow = arm.l1 * np.array([np.cos(q1), np.sin(q1)])
    centre_1 = elbow / 2
    centre_2 = elbow + arm.l2 / 2 * np.array([np.cos(q12), np.sin(q12)])

    def moment(arm_vector, force):
        return arm_vector[0] * force[1] - arm_vector[1] * force[0]

    weight_1, weight_2 = (
        np.array([0.0, -arm.m1 * arm.g]),
        np.array([0.0, -arm.m2 * arm.g]),
    )
    # The motors balance the weights' moments: tau = -(moments of the weights).
    tau_shoulder = -(moment(centre_1, weight_1) + moment(centre_2, weight_2))
    tau_elbow = -moment(centre_2 - elbow, weight_2)
    assert_within(arm.gravity(q), [tau_shoulder, tau_elbow], 1e-12 * gravity_scale(arm))


@given(dynamic_arms(), configurations(), pairs)
def test_gravity_is_the_gradient_of_the_potential_energy(arm, q, direction):
    step = 1e-6
    _, v_plus = arm.energy(q + step * direction, [0.0, 0.0])
    _, v_minus = arm.energy(q - step * direction, [0.0, 0.0])
    assert abs(
        (v_plus - v_minus) / (2 * step) - arm.gravity(q) @ direction
    ) <= 1e-7 * gravity_scale(arm) * (1 + np.abs(direction).sum())


@given(dynamic_arms(), configurations(), pairs)
def test_static_torques_plus_gravity_equal_inverse_dynamics_at_rest(arm, q, force):
    """Chapter 4's tau = J^T F plus the weight is what inverse dynamics asks for at rest."""
    held = arm.joint_torques(q, force) + arm.gravity(q)
    at_rest = np.zeros(2)
    scale = gravity_scale(arm) + (arm.l1 + arm.l2) * np.abs(force).sum()
    assert_within(
        dynamics.inverse_dynamics(arm, q, at_rest, at_rest, force_by_tip=force),
        held,
        1e-12 * scale,
    )
    # Forward: with those torques the arm pushing with F stays at rest.
    M_inverse = np.abs(np.linalg.inv(arm.mass_matrix(q))).max()
    assert_within(
        dynamics.forward_dynamics(arm, q, at_rest, held, force_by_tip=force),
        at_rest,
        1e-13 * M_inverse * scale,
    )


# ----------------------------------------------------------------- energy
def test_energy_values():
    arm = TwoLinkArm(2.0, 2.0, m1=3.0, m2=3.0, g=10.0)
    kinetic, potential = arm.energy([0.0, 0.0], [1.0, 0.0])
    # One 4 m, 6 kg rod spinning about its end at 1 rad/s; lying along x, so V = 0.
    assert float(kinetic) == pytest.approx(0.5 * 6.0 * 4.0**2 / 3.0, rel=1e-14)
    assert float(potential) == 0.0
    kinetic, potential = arm.energy([np.pi / 2, 0.0], [0.0, 0.0])
    assert float(kinetic) == 0.0
    assert float(potential) == pytest.approx(
        3.0 * 10.0 * 1.0 + 3.0 * 10.0 * 3.0, rel=1e-14
    )


@given(dynamic_arms(), configurations(), pairs, pairs)
def test_power_balance(arm, q, qd, tau):
    """d/dt (T + V) = qd . tau along the motion the dynamics predict."""
    qdd = arm.forward_dynamics(q, qd, tau)
    step = 1e-6
    e_plus = sum(arm.energy(q + step * qd, qd + step * qdd))
    e_minus = sum(arm.energy(q - step * qd, qd - step * qdd))
    power = (e_plus - e_minus) / (2 * step)
    scale = (
        mass_scale(arm) * (1 + np.abs(qd).sum() + np.abs(qdd).sum()) ** 2
        + gravity_scale(arm)
    ) * (1 + np.abs(qd).sum())
    assert abs(power - qd @ tau) <= 1e-7 * scale


# ----------------------------------------------------------------- bad input
@pytest.mark.parametrize(
    "call, fragment",
    [
        (
            lambda arm: arm.mass_matrix([0.0, 1.0, 2.0]),
            r"q must have shape \(\.\.\., 2\)",
        ),
        (lambda arm: arm.mass_matrix([np.nan, 1.0]), "q must be finite"),
        (lambda arm: arm.coriolis([0.0, 0.0], [1.0]), "qd must have shape"),
        (lambda arm: arm.gravity("up"), "q must be real numbers"),
        (
            lambda arm: arm.inverse_dynamics([0.0, 0.0], [0.0, np.inf], [0.0, 0.0]),
            "qd must be finite",
        ),
        (
            lambda arm: arm.inverse_dynamics([0.0, 0.0], [0.0, 0.0], [[1.0, 2.0, 3.0]]),
            "qdd must have shape",
        ),
        (
            lambda arm: arm.forward_dynamics([0.0, 0.0], [0.0, 0.0], [np.nan, 0.0]),
            "tau must be finite",
        ),
        (
            lambda arm: arm.forward_dynamics([0.0, np.nan], [0.0, 0.0], [0.0, 0.0]),
            "q must be finite",
        ),
        (
            lambda arm: arm.forward_dynamics(
                np.zeros((3, 2)), np.zeros((4, 2)), np.zeros(2)
            ),
            "broadcast",
        ),
        (
            lambda arm: dynamics.forward_dynamics(
                arm, [0.0, 0.0], [0.0, 0.0], [0.0, 0.0], force_by_tip=[1.0]
            ),
            "force_by_tip must have shape",
        ),
        (lambda arm: arm.energy([0.0, 0.0], [[0.0, 0.0, 0.0]]), "qd must have shape"),
    ],
)
def test_bad_input_raises_a_clear_value_error(call, fragment):
    with pytest.raises(ValueError, match=fragment):
        call(arms.two_metre)


@pytest.mark.parametrize(
    "kwargs",
    [{"m2": 0.0}, {"m1": 0.0, "I1": 0.0, "m2": 1.0, "I2": 0.0}, {"m1": 0.0, "m2": 0.0}],
)
def test_singular_mass_matrix_is_refused_by_forward_dynamics(kwargs):
    arm = TwoLinkArm(1.0, 1.0, **kwargs)
    with pytest.raises(ValueError, match="mass matrix is singular"):
        arm.forward_dynamics([0.0, 0.5], [0.0, 0.0], [0.0, 0.0])
    with pytest.raises(ValueError, match="mass matrix is singular"):
        arm.forward_dynamics(np.zeros((3, 2)), np.zeros(2), np.zeros(2))


def test_a_massless_link_1_is_fine_when_link_2_has_inertia():
    arm = TwoLinkArm(1.0, 1.0, m1=0.0, m2=2.0)
    qdd = arm.forward_dynamics([0.3, 0.5], [0.1, 0.2], [1.0, -1.0])
    assert np.all(np.isfinite(qdd))
    assert np.allclose(
        arm.inverse_dynamics([0.3, 0.5], [0.1, 0.2], qdd), [1.0, -1.0], atol=1e-12
    )


def test_lambdify_takes_a_derivation_or_a_model_name():
    arm, q, qd = arms.osake, np.array([0.3, -0.4]), np.array([1.0, 2.0])
    from_derivation = lambdify_dynamics(equations_of_motion("absolute"))
    assert from_derivation.model == numeric("absolute").model == "absolute"
    assert np.array_equal(
        from_derivation.coriolis(arm, q, qd), numeric("absolute").coriolis(arm, q, qd)
    )
    assert numeric("relative").gravity(arm, q).shape == (2,)


# ----------------------------------------------------------------- derivatives of M and g
@functools.cache
def symbolic_derivatives():
    """dM/dq (index k last) and dg/dq from the Euler-Lagrange derivation, as functions of (q, parameters);
    derived when a test first asks, not when each worker imports this file."""
    eom = equations_of_motion("relative")
    q = list(eom.q)
    dM = [
        [[sp.diff(eom.M[i, j], q[k]) for k in range(2)] for j in range(2)]
        for i in range(2)
    ]
    dg = eom.g.jacobian(q)
    arguments = (*q, *eom.parameters)
    return sp.lambdify(arguments, dM, "numpy"), sp.lambdify(arguments, dg, "numpy")


def parameters(arm):
    """The arm's values of EquationsOfMotion.parameters: (l1, l2, m1, m2, I1, I2, g)."""
    return (arm.l1, arm.l2, arm.m1, arm.m2, *arm.inertias, arm.g)


@given(dynamic_arms(), configurations())
def test_mass_matrix_derivative_is_sympys_derivative_of_M(arm, q):
    expected = np.array(symbolic_derivatives()[0](*q, *parameters(arm)), dtype=float)
    assert_within(
        dynamics.mass_matrix_derivative(arm, q), expected, 1e-12 * mass_scale(arm)
    )


@given(dynamic_arms(), configurations())
def test_gravity_jacobian_is_sympys_derivative_of_g(arm, q):
    expected = np.array(symbolic_derivatives()[1](*q, *parameters(arm)), dtype=float)
    assert_within(
        dynamics.gravity_jacobian(arm, q), expected, 1e-12 * gravity_scale(arm)
    )


@given(dynamic_arms(), configurations())
def test_derivatives_of_M_and_g_match_finite_differences(arm, q):
    step = 1e-6
    dM = np.stack(
        [
            (arm.mass_matrix(q + step * e) - arm.mass_matrix(q - step * e)) / (2 * step)
            for e in np.eye(2)
        ],
        axis=-1,
    )
    assert_within(dynamics.mass_matrix_derivative(arm, q), dM, 1e-8 * mass_scale(arm))
    dg = np.column_stack(
        [
            (arm.gravity(q + step * e) - arm.gravity(q - step * e)) / (2 * step)
            for e in np.eye(2)
        ]
    )
    G = dynamics.gravity_jacobian(arm, q)
    assert_within(G, dg, 1e-8 * gravity_scale(arm))
    assert np.array_equal(G, G.T)  # the Hessian of the potential energy


def test_derivatives_of_M_and_g_are_vectorised():
    arm = arms.two_metre
    q = np.random.default_rng(4).uniform(-np.pi, np.pi, (5, 3, 2))
    dM, G = dynamics.mass_matrix_derivative(arm, q), dynamics.gravity_jacobian(arm, q)
    assert dM.shape == (5, 3, 2, 2, 2) and G.shape == (5, 3, 2, 2)
    for index in np.ndindex(5, 3):
        assert np.array_equal(dM[index], dynamics.mass_matrix_derivative(arm, q[index]))
        assert np.array_equal(G[index], dynamics.gravity_jacobian(arm, q[index]))
    with pytest.raises(ValueError, match=r"q must have shape \(\.\.\., 2\)"):
        dynamics.gravity_jacobian(arm, [0.0, 1.0, 2.0])


@given(dynamic_arms(), configurations(), pairs)
def test_coriolis_is_built_from_the_mass_matrix_derivative(arm, q, qd):
    """C_ij = sum_k (dM_ij/dq_k + dM_ik/dq_j - dM_jk/dq_i) qd_k / 2 (Christoffel symbols of dM/dq)."""
    dM = dynamics.mass_matrix_derivative(arm, q)
    christoffel = 0.5 * (dM + np.swapaxes(dM, 1, 2) - np.transpose(dM, (2, 0, 1)))
    assert_within(
        arm.coriolis(q, qd),
        christoffel @ qd,
        1e-12 * mass_scale(arm) * (1 + np.abs(qd).sum()),
    )


# ----------------------------------------------------------------- one state on floats, a batch on arrays
# Forward and inverse dynamics evaluate one formula each (_forward; _inverse from the terms of M, C and g):
# with math for one state, with numpy for a batch.
ONE_ARM = TwoLinkArm(1.0, 0.7, m1=2.0, m2=1.2)
wide_angles = st.floats(-4.0, 4.0, allow_nan=False)
wide_rates = st.floats(-5.0, 5.0, allow_nan=False)


def outcome(call):
    """What a call did: its value, or the type and message of what it raised."""
    try:
        return "value", call()
    except Exception as error:  # noqa: BLE001 - the point is to compare any refusal
        return "error", (type(error), str(error))


@given(
    wide_angles,
    wide_angles,
    wide_rates,
    wide_rates,
    wide_rates,
    wide_rates,
    st.sampled_from([ONE_ARM, arms.two_metre, TwoLinkArm(1e-3, 2.0, m1=0.1)]),
)
def test_dynamics_paths_agree(q1, q2, qd1, qd2, u1, u2, arm):
    q, qd, u = [q1, q2], [qd1, qd2], [u1, u2]
    for function in (dynamics.forward_dynamics, dynamics.inverse_dynamics):
        one = function(arm, q, qd, u)
        batch = function(arm, np.array([q]), np.array([qd]), np.array([u]))[0]
        np.testing.assert_allclose(one, batch, rtol=1e-12, atol=1e-12)
    assert arm.forward_dynamics(tuple(q), np.array(qd), u).shape == (2,)
    # the inverse dynamics is M qdd + C qd + g, term by term
    expected = arm.mass_matrix(q) @ u + arm.coriolis(q, qd) @ qd + arm.gravity(q)
    np.testing.assert_allclose(
        dynamics.inverse_dynamics(arm, q, qd, u), expected, rtol=1e-12, atol=1e-12
    )


@pytest.mark.parametrize(
    "bad",
    [
        [float("nan"), 1.0],
        [0.0, float("inf")],
        ["a", 1.0],
        [None, 1.0],
        [1.0, 2.0, 3.0],
        [True, False],
        np.array([np.nan, 1.0]),
    ],
    ids=repr,
)
def test_single_bad_state_is_refused_as_the_vectorised_path_refuses_it(bad):
    from twolink._validate import as_pairs

    one_zero, batch_zero = [0.0, 0.0], np.zeros((1, 2))
    fast = outcome(lambda: dynamics.forward_dynamics(ONE_ARM, bad, one_zero, one_zero))
    slow = outcome(
        lambda: dynamics.forward_dynamics(
            ONE_ARM, as_pairs(bad, "q")[None, :], batch_zero, batch_zero
        )
    )
    assert fast[0] == slow[0] == "error" and fast[1] == slow[1]
    fast = outcome(lambda: dynamics.inverse_dynamics(ONE_ARM, one_zero, one_zero, bad))
    slow = outcome(
        lambda: dynamics.inverse_dynamics(
            ONE_ARM, batch_zero, batch_zero, as_pairs(bad, "qdd")[None, :]
        )
    )
    assert fast[0] == slow[0] == "error" and fast[1] == slow[1]


@pytest.mark.parametrize("not_an_arm", [None, 3.0, "arm"], ids=repr)
def test_single_state_with_something_that_is_not_an_arm_is_refused_as_in_a_batch(
    not_an_arm,
):
    for function in (dynamics.forward_dynamics, dynamics.inverse_dynamics):
        fast = outcome(lambda: function(not_an_arm, [0.3, 0.4], [0.3, 0.4], [0.3, 0.4]))
        slow = outcome(lambda: function(not_an_arm, *[np.array([[0.3, 0.4]])] * 3))
        assert (
            fast[0] == slow[0] == "error" and fast[1] == slow[1] and "arm" in fast[1][1]
        )
    fast = outcome(lambda: dynamics.gravity(not_an_arm, [0.3, 0.4]))
    slow = outcome(lambda: dynamics.gravity(not_an_arm, np.array([[0.3, 0.4]])))
    assert fast[0] == slow[0] == "error" and fast[1] == slow[1] and "arm" in fast[1][1]


def test_dynamics_constants_are_cached_per_arm_and_follow_replace():
    arm = TwoLinkArm(1.0, 1.0, m1=1.0, m2=1.0)
    heavier = dataclasses.replace(arm, m2=5.0)
    q, qd, tau = [0.3, 0.4], [0.0, 0.0], [0.0, 0.0]
    assert not np.allclose(
        arm.forward_dynamics(q, qd, tau), heavier.forward_dynamics(q, qd, tau)
    )
    np.testing.assert_allclose(
        heavier.forward_dynamics(q, qd, tau),
        TwoLinkArm(1.0, 1.0, m1=1.0, m2=5.0).forward_dynamics(q, qd, tau),
    )
    assert arm == TwoLinkArm(1.0, 1.0, m1=1.0, m2=1.0) and hash(arm) == hash(
        TwoLinkArm(1.0, 1.0, m1=1.0, m2=1.0)
    )


@pytest.mark.parametrize(
    "rates", [[1e200, 1e200], [1e155, -1e155], [3e153, 0.0]], ids=repr
)
def test_overflowing_single_state_is_refused_as_in_a_batch(rates):
    """Finite inputs whose dynamics overflow float64: the same OverflowError (or the same finite answer)."""
    for call in (
        lambda q, qd: dynamics.forward_dynamics(ONE_ARM, q, qd, np.zeros_like(q)),
        lambda q, qd: dynamics.inverse_dynamics(ONE_ARM, q, qd, np.zeros_like(q)),
    ):
        fast = outcome(lambda: call([0.3, 0.4], rates))
        slow = outcome(lambda: call(np.array([[0.3, 0.4]]), np.array([rates]))[0])
        assert fast[0] == slow[0]
        if (
            fast[0] == "error"
        ):  # the messages differ only in the index of the overflowing entry
            assert fast[1][0] is slow[1][0] is OverflowError
        else:
            np.testing.assert_allclose(fast[1], slow[1], rtol=0, atol=1e-12)


DYNAMICS_CALLS = {
    "forward_dynamics": lambda q: dynamics.forward_dynamics(
        ONE_ARM, q, [0.2, -0.1], [1.0, 0.5]
    ),
    "inverse_dynamics": lambda q: dynamics.inverse_dynamics(
        ONE_ARM, q, [0.2, -0.1], [1.0, 0.5]
    ),
    "mass_matrix": lambda q: dynamics.mass_matrix(ONE_ARM, q),
    "coriolis": lambda q: dynamics.coriolis(ONE_ARM, q, [0.2, -0.1]),
    "gravity": lambda q: dynamics.gravity(ONE_ARM, q),
    "gravity_jacobian": lambda q: dynamics.gravity_jacobian(ONE_ARM, q),
    "energy": lambda q: np.array(dynamics.energy(ONE_ARM, q, [0.2, -0.1])).T,
}


@settings(max_examples=60)
@given(
    q1=st.floats(-1.7e308, 1.7e308),
    q2=st.floats(-1.7e308, 1.7e308),
    batch=st.booleans(),
)
@pytest.mark.parametrize("name", sorted(DYNAMICS_CALLS))
def test_large_angles_are_reduced_exactly_never_rounded_in_a_sum(name, q1, q2, batch):
    """Before, q1 + q2 was formed: 1e17 + 0.5 lost its 0.5, and 1e308 + 1e308 was refused."""
    call = DYNAMICS_CALLS[name]
    reduced = [float(np.arctan2(np.sin(angle), np.cos(angle))) for angle in (q1, q2)]
    got = np.asarray(call([[q1, q2]] * 2)[1] if batch else call([q1, q2]))
    assert np.allclose(got, call(reduced), rtol=1e-12, atol=1e-12)


# ----------------------------------------------------------------- the right-hand side of an ODE solver
@given(state=st.lists(rates, min_size=4, max_size=4), driven=st.booleans())
def test_state_derivative_takes_any_sequence_of_four_numbers_as_the_array(
    state, driven
):
    torque = (lambda t, q, qd: [0.5 * q[0], -qd[1]]) if driven else None
    rhs = dynamics.state_derivative(arms.ten, torque)
    from_array = rhs(0.0, np.array(state))
    assert rhs(0.0, state) == from_array
    assert rhs(0.0, tuple(state)) == from_array
    assert rhs(0.0, [int(value) for value in state]) == rhs(
        0.0, np.array([int(value) for value in state], float)
    )


@pytest.mark.parametrize("driven", [False, True])
@pytest.mark.parametrize(
    "state, fragment",
    [
        ([0.1, 0.2, 0.0], "got shape (3,)"),
        ([0.1, 0.2, 0.0, 0.0, 0.0], "got shape (5,)"),
        ([[0.1, 0.2], [0.0, 0.0]], "got shape (2, 2)"),
        (np.zeros((4, 1)), "got shape (4, 1)"),
        (np.zeros(3), "got shape (3,)"),
        ("abcd", "(str)"),
        ([0.1, "0.2", 0.0, 0.0], "entry (1,) is str"),
        (np.array(["0.1", "0.2", "0", "0"]), "<U3 entries"),
        ([True, 0.2, 0.0, 0.0], "entry (0,) is bool"),
        ([0.1, float("nan"), 0.0, 0.0], "got [0.1, nan, 0.0, 0.0]"),
        ([0.1, 0.2, float("inf"), 0.0], "got [0.1, 0.2, inf, 0.0]"),
        (None, "(NoneType)"),
    ],
)
def test_state_derivative_refuses_junk_naming_state_and_the_allowed_shape(
    state, fragment, driven
):
    rhs = dynamics.state_derivative(
        arms.ten, (lambda t, q, qd: [0.0, 0.0]) if driven else None
    )
    with pytest.raises((ValueError, TypeError)) as caught:
        rhs(0.0, state)
    message = str(caught.value)
    assert message.startswith(
        "state must be four finite real numbers (q1, q2, qd1, qd2), shape (4,)"
    )
    assert fragment in message


# --------------------------- very unequal arms: forward dynamics without cancellation
mpmath.mp.dps = 50


def reference_forward_dynamics(arm, q, qd, tau):
    """``M^-1 (tau - C qd - g)`` at 50 digits from the arm's float parameters (taken as exact)."""
    m = mpmath.mpf
    l1, l2, m1, m2, g = (m(float(v)) for v in (arm.l1, arm.l2, arm.m1, arm.m2, arm.g))
    I1, I2 = (m(float(v)) for v in arm.inertias)
    q1, q2, qd1, qd2, tau1, tau2 = (m(float(v)) for v in (*q, *qd, *tau))
    lc1, lc2 = l1 / 2, l2 / 2
    alpha = I1 + I2 + m1 * lc1**2 + m2 * (l1**2 + lc2**2)
    beta = m2 * l1 * lc2
    delta = I2 + m2 * lc2**2
    M = mpmath.matrix(
        [
            [alpha + 2 * beta * mpmath.cos(q2), delta + beta * mpmath.cos(q2)],
            [delta + beta * mpmath.cos(q2), delta],
        ]
    )
    h = -beta * mpmath.sin(q2)
    bias = mpmath.matrix(
        [
            h * qd2 * qd1
            + h * (qd1 + qd2) * qd2
            + (m1 * lc1 + m2 * l1) * g * mpmath.cos(q1)
            + m2 * lc2 * g * mpmath.cos(q1 + q2),
            -h * qd1 * qd1 + m2 * lc2 * g * mpmath.cos(q1 + q2),
        ]
    )
    qdd = mpmath.lu_solve(M, mpmath.matrix([tau1, tau2]) - bias)
    return np.array([float(qdd[0]), float(qdd[1])])


def test_sympy_expansion_of_the_determinant_is_a_sum_of_non_negative_terms():
    l1, l2, m1, m2, I1, I2, q2 = sp.symbols("l1 l2 m1 m2 I1 I2 q2", positive=True)
    lc1, lc2 = l1 / 2, l2 / 2
    alpha = I1 + I2 + m1 * lc1**2 + m2 * (l1**2 + lc2**2)
    beta = m2 * l1 * lc2
    delta = I2 + m2 * lc2**2
    m11, m12, m22 = alpha + 2 * beta * sp.cos(q2), delta + beta * sp.cos(q2), delta
    det_min = (I1 + m1 * lc1**2) * delta + m2 * l1**2 * I2
    assert (
        sp.simplify(
            sp.expand(m11 * m22 - m12**2 - (det_min + (beta * sp.sin(q2)) ** 2))
        )
        == 0
    )
    # the package's constants are this expansion, evaluated for one arm
    from twolink.dynamics import _constants

    arm = TwoLinkArm(0.7, 1.3, m1=2.0, m2=3.0, I1=0.4, I2=0.25)
    values = {l1: 0.7, l2: 1.3, m1: 2.0, m2: 3.0, I1: 0.4, I2: 0.25}
    assert _constants(arm).det_min == pytest.approx(
        float(det_min.subs(values)), rel=1e-15
    )


@pytest.mark.parametrize("ratio", [1e-9, 1e-8, 1e-6, 1e-3, 1.0, 1e3, 1e6, 1e8, 1e9])
def test_forward_dynamics_matches_50_digit_reference_for_length_ratios(ratio):
    arm = TwoLinkArm(1.0 * np.sqrt(ratio), 1.0 / np.sqrt(ratio), m1=1.3, m2=0.7, g=9.81)
    rng = np.random.default_rng(int(-np.log10(ratio) * 10) + 100)
    for _ in range(20):
        q = rng.uniform(-np.pi, np.pi, 2)
        qd = rng.uniform(-3.0, 3.0, 2)
        tau = rng.uniform(-5.0, 5.0, 2)
        exact = reference_forward_dynamics(arm, q, qd, tau)
        for got in (
            arm.forward_dynamics(q, qd, tau),
            arm.forward_dynamics(q[None], qd[None], tau[None])[0],
        ):
            assert np.linalg.norm(got - exact) <= 1e-12 * np.linalg.norm(exact)


@settings(max_examples=100)
@given(
    log_ratio=st.floats(-9.0, 9.0),
    masses=st.tuples(st.floats(0.1, 10.0), st.floats(0.1, 10.0)),
    custom_inertias=st.booleans(),
    state=st.lists(st.floats(-3.0, 3.0), min_size=6, max_size=6),
)
def test_forward_dynamics_is_accurate_for_any_length_ratio(
    log_ratio, masses, custom_inertias, state
):
    ratio = 10.0**log_ratio
    l1, l2 = np.sqrt(ratio), 1.0 / np.sqrt(ratio)
    inertias = (
        {"I1": masses[0] * l1**2 / 7.0, "I2": masses[1] * l2**2 / 5.0}
        if custom_inertias
        else {}
    )
    arm = TwoLinkArm(l1, l2, m1=masses[0], m2=masses[1], g=9.81, **inertias)
    q, qd, tau = np.array(state[:2]), np.array(state[2:4]), np.array(state[4:])
    exact = reference_forward_dynamics(arm, q, qd, tau)
    got = arm.forward_dynamics(q, qd, tau)
    # the right-hand side itself is a sum of terms of mixed sign: bound by its size, not by qdd's
    assert np.linalg.norm(got - exact) <= 1e-11 * np.linalg.norm(exact) + 1e-300


def test_very_unequal_arm_simulates_in_few_evaluations():
    """At (1e-3, 1e3) half a second needed millions of evaluations with the cancelling determinant."""
    from twolink import simulate

    arm = TwoLinkArm(1e-3, 1e3)
    result = simulate(arm, [0.3, 0.4], [0.0, 0.0], 0.5, rtol=1e-8, atol=1e-8)
    assert result.status == 0
    assert result.nfev < 20000


def test_overflowing_dynamics_are_reported():
    arm = TwoLinkArm(1.0, 1.0)
    with pytest.raises(OverflowError, match="joint accelerations"):
        arm.forward_dynamics([0.3, 0.4], [1e160, 0.0], [0.0, 0.0])
    with pytest.raises(OverflowError, match="joint accelerations"):
        arm.forward_dynamics(np.array([[0.3, 0.4]]), [1e160, 0.0], [0.0, 0.0])
    with pytest.raises(OverflowError, match="joint torques"):
        arm.inverse_dynamics([0.3, 0.4], [0.0, 0.0], [1e308, 1e308])


# ---------------------------------------------------------------- shape mismatches name the arguments
A3, A4 = np.zeros((3, 2)), np.zeros((4, 2))


@pytest.mark.parametrize(
    "call, fragment",
    [
        (
            lambda: arms.two_metre.coriolis(A3, A4),
            r"q of shape \(3, 2\) and qd of shape \(4, 2\) do not broadcast",
        ),
        (
            lambda: arms.two_metre.energy(A3, A4),
            r"q of shape \(3, 2\) and qd of shape \(4, 2\) do not broadcast",
        ),
        (
            lambda: arms.two_metre.inverse_dynamics(A3, A3, A3, A4),
            r"qdd of shape \(3, 2\) and force_by_tip of shape \(4, 2\)",
        ),
        (
            lambda: arms.two_metre.inverse_dynamics(A3, A4, A3),
            r"q of shape \(3, 2\), qd of shape \(4, 2\) and qdd of shape",
        ),
        (
            lambda: arms.two_metre.forward_dynamics(A3, A3, A3, A4),
            r"tau of shape \(3, 2\) and force_by_tip of shape \(4, 2\)",
        ),
    ],
)
def test_shape_mismatches_name_the_arguments_and_their_shapes(call, fragment):
    with pytest.raises(ValueError, match=fragment):
        call()
