"""Edges of velocity kinematics: damped least squares at singularities, tiny and huge velocities (issue 11, class 3)."""

import itertools

import mpmath
import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from twolink import TwoLinkArm, arms

mpmath.mp.dps = 50


def reference_jacobian(arm, q):
    """``J(q)`` at 50 digits, from the float configuration taken as exact."""
    l1, l2 = mpmath.mpf(float(arm.l1)), mpmath.mpf(float(arm.l2))
    q1, q2 = mpmath.mpf(float(q[0])), mpmath.mpf(float(q[1]))
    s1, c1, s12, c12 = (
        mpmath.sin(q1),
        mpmath.cos(q1),
        mpmath.sin(q1 + q2),
        mpmath.cos(q1 + q2),
    )
    return mpmath.matrix(
        [[-l1 * s1 - l2 * s12, -l2 * s12], [l1 * c1 + l2 * c12, l2 * c12]]
    )


def reference_dls(arm, q, v_tip, damping):
    """``(J^T J + lambda^2 I)^-1 J^T v`` at 50 digits, J from the float configuration."""
    J = reference_jacobian(arm, q)
    v = mpmath.matrix([float(v_tip[0]), float(v_tip[1])])
    normal = J.T * J + mpmath.mpf(float(damping)) ** 2 * mpmath.eye(2)
    qd = mpmath.lu_solve(normal, J.T * v)
    return np.array([float(qd[0]), float(qd[1])])


@pytest.mark.parametrize("q2", [0.0, np.pi, -np.pi, 1e-9, np.pi - 1e-12])
@pytest.mark.parametrize("damping", [1e-12, 1e-8, 1e-4, 0.1, 10.0])
def test_dls_is_exact_at_and_near_singularities_for_any_damping(q2, damping):
    arm = arms.two_metre
    for q1, v_tip in itertools.product(
        (0.3, np.pi / 4, 1.0), ([0.0, 1.0], [1.0, 0.0], [0.3, -0.7])
    ):
        q = [q1, q2]
        got = arm.joint_rates_dls(q, v_tip, damping)
        exact = reference_dls(arm, q, v_tip, damping)
        assert np.linalg.norm(got - exact) <= 1e-9 * np.linalg.norm(exact) + 1e-300
        assert np.linalg.norm(got) <= np.linalg.norm(v_tip) / (2 * damping) * (
            1 + 1e-12
        )


@settings(max_examples=100)
@given(
    q=st.tuples(st.floats(-np.pi, np.pi), st.floats(-np.pi, np.pi)),
    v_tip=st.tuples(st.floats(-10.0, 10.0), st.floats(-10.0, 10.0)),
    log_damping=st.floats(-12.0, 2.0),
)
@example(q=(0.0, 1e-8), v_tip=(0.0, 1.0), log_damping=-8.0)
@example(q=(0.0, 6.402545313897921e-25), v_tip=(1.0, 0.0), log_damping=-10.0)
def test_dls_matches_the_50_digit_normal_equations(q, v_tip, log_damping):
    arm = TwoLinkArm(1.3, 0.7)
    damping = 10.0**log_damping
    got = arm.joint_rates_dls(q, v_tip, damping)
    exact = reference_dls(arm, q, v_tip, damping)
    # The SVD's singular vectors are right to about eps; along the small singular direction DLS
    # multiplies by s / (s^2 + damping^2) <= 1 / (2 damping), so that direction's error can reach
    # eps |v| / (2 damping) (a few 1e-9 at damping 1e-8 near a fold: hypothesis found q = (0, 1e-8)).
    # J itself is rounded: its entries carry errors of eps |J|, so its small singular value s is known only to
    # eps |J|; where s is below that (q2 within round-off of a fold), the DLS gain s / (s^2 + damping^2) of that
    # direction moves by up to eps |J| / damping^2, at most 1 / damping in all (hypothesis: q2 = 6.4e-25,
    # damping 1e-10 gave the right size with the opposite sign).
    eps = np.finfo(float).eps
    speed = np.linalg.norm(v_tip)
    J_size = np.linalg.norm(arm.jacobian(q))
    s_small = arm.l1 * arm.l2 * abs(np.sin(q[1])) / max(J_size, 1e-300)
    rounded_J = (
        min(4 * eps * J_size * speed / damping**2, 2 * speed / damping)
        if s_small <= 4 * eps * J_size
        else 0.0
    )
    bound = (
        1e-9 * (np.linalg.norm(exact) + speed * 1e-3)
        + 4 * eps * speed / damping
        + rounded_J
    )
    assert np.linalg.norm(got - exact) <= bound


def test_dls_with_tiny_damping_at_a_fold_is_not_a_linalg_error():
    for q in (
        [np.pi / 4, 0.0],
        [np.pi / 4, -np.pi],
        [1.0, -np.pi],
    ):  # the normal equations were singular here
        qd = arms.two_metre.joint_rates_dls(q, [0.0, 1.0], 1e-8)
        assert np.allclose(
            qd, reference_dls(arms.two_metre, q, [0.0, 1.0], 1e-8), rtol=1e-9, atol=0.0
        )


@pytest.mark.parametrize("size", [5e-324, 1e-310, 1e-200, 1e200])
def test_tiny_and_huge_velocities_are_solved_to_the_last_bit(size):
    """Both solvers scale v_tip to size one first: no subnormal or overflowing intermediates."""
    arm = TwoLinkArm(1.0, 1.0)
    rng = np.random.default_rng(7)
    for _ in range(50):
        q = np.array([rng.uniform(-3.0, 3.0), rng.uniform(0.3, 2.8)])
        v_tip = np.array([0.0, size * rng.integers(1, 40)])
        exact = mpmath.lu_solve(
            reference_jacobian(arm, q), mpmath.matrix(v_tip.tolist())
        )
        exact = np.array([float(exact[0]), float(exact[1])])
        ulp = np.spacing(np.abs(exact))
        assert np.all(
            np.abs(arm.joint_rates(q, v_tip) - exact)
            <= 1e-14 * np.abs(exact).max() + 2 * ulp
        )
        # DLS with negligible damping: the SVD's few roundings, relative to the largest component,
        # and still no subnormal intermediates (at most a couple of units in the last place below 1e-308)
        got = arm.joint_rates_dls(q, v_tip, 1e-12)
        assert np.all(np.abs(got - exact) <= 1e-14 * np.abs(exact).max() + 2 * ulp)
