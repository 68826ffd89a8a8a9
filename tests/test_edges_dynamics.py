"""Edges of the dynamics: cancellation-free forward dynamics for very unequal arms (issue 11, class 1)."""

import mpmath
import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from twolink import TwoLinkArm

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
