"""Velocity kinematics: tip velocity, joint rates (exact and damped), manipulability, ellipses, resolved rate."""

import inspect
import itertools

import mpmath
import numpy as np
import pytest
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st

from conftest import angles, configurations
from conftest import arms as arm_strategy
from twolink import (
    SingularityError,
    TwoLinkArm,
    arms,
    kinematics,
    stiffness,
    velocity,
)

rates = st.floats(
    min_value=-10.0, max_value=10.0, allow_nan=False, allow_infinity=False
)


@st.composite
def pairs(draw, elements=rates):
    return np.array([draw(elements), draw(elements)])


def away_from_singularity(q, margin=0.05):
    return abs(np.sin(q[1])) > margin


@given(arm=arm_strategy(), q=configurations(), qd=pairs())
def test_tip_velocity_is_the_derivative_of_fk(arm, q, qd):
    h = 1e-6
    v_fd = (arm.fk(q + h * qd) - arm.fk(q - h * qd)) / (2 * h)
    assert np.allclose(
        arm.tip_velocity(q, qd),
        v_fd,
        atol=1e-7 * (arm.l1 + arm.l2) * (1 + np.abs(qd).max()),
    )


@given(arm=arm_strategy(), q=configurations(), qd=pairs())
def test_joint_rates_invert_tip_velocity_away_from_singularities(arm, q, qd):
    assume(away_from_singularity(q))
    v_tip = arm.tip_velocity(q, qd)
    qd_back = arm.joint_rates(q, v_tip)
    # the error grows with the condition number of J, at most (l1 + l2)^2 / (l1 l2 |sin q2|)
    condition = (arm.l1 + arm.l2) ** 2 / (arm.l1 * arm.l2 * abs(np.sin(q[1])))
    assert np.allclose(qd_back, qd, atol=1e-12 * condition * (1 + np.abs(qd).max()))


@given(arm=arm_strategy(), q=configurations(), v_tip=pairs())
def test_tip_velocity_of_joint_rates_gives_back_the_wanted_velocity(arm, q, v_tip):
    assume(away_from_singularity(q))
    qd = arm.joint_rates(q, v_tip)
    assert np.allclose(
        arm.tip_velocity(q, qd), v_tip, atol=1e-9 * (1 + np.abs(v_tip).max())
    )


@given(
    arm=arm_strategy(),
    q=configurations(),
    qd=pairs(),
    force=pairs(st.floats(-1e3, 1e3)),
)
def test_power_balance_tau_dot_qd_equals_force_dot_v(arm, q, qd, force):
    """Virtual work: the joints deliver tau . qd, the tip delivers F . v_tip."""
    tau = arm.joint_torques(q, force)
    v_tip = arm.tip_velocity(q, qd)
    scale = (arm.l1 + arm.l2) * (1 + np.abs(qd).max()) * (1 + np.abs(force).max())
    assert tau @ qd == pytest.approx(force @ v_tip, abs=1e-12 * scale)


@given(arm=arm_strategy(), q1=angles)
def test_manipulability_is_exactly_zero_at_sin_q2_zero(arm, q1):
    assert arm.manipulability([q1, 0.0]) == 0.0
    assert (
        arm.manipulability([q1, np.pi]) <= 1e-15 * arm.l1 * arm.l2
    )  # sin(pi) is 1.2e-16 in floats


@given(arm=arm_strategy(), q=configurations())
def test_manipulability_is_yoshikawas_sqrt_det_j_jt(arm, q):
    J = arm.jacobian(q)
    gram = J @ J.T
    det_gram = gram[0, 0] * gram[1, 1] - gram[0, 1] * gram[1, 0]
    # compare squares: sqrt of a determinant that rounds to 1e-16 at a singularity would be 1e-8
    assert arm.manipulability(q) ** 2 == pytest.approx(
        det_gram, abs=1e-12 * (arm.l1 + arm.l2) ** 4
    )
    assert arm.manipulability(q) <= arm.l1 * arm.l2 * (1 + 1e-12)


def test_manipulability_is_largest_with_the_links_at_right_angles():
    arm = TwoLinkArm(0.6, 0.4)
    q2 = np.linspace(-np.pi, np.pi, 3601)
    w = arm.manipulability(np.stack([np.full_like(q2, 0.3), q2], axis=-1))
    assert w.shape == (3601,)
    assert np.isclose(abs(q2[np.argmax(w)]), np.pi / 2)
    assert w.max() == pytest.approx(0.6 * 0.4)


@pytest.mark.parametrize("q2", [0.0, np.pi, -np.pi, 1e-8, np.pi - 1e-9])
def test_joint_rates_refuse_singular_configurations_with_the_distance(q2):
    with pytest.raises(
        SingularityError, match=r"\|sin q2\| = .* <= tol = 1e-06 \(\|det J\| = .* m\^2"
    ):
        arms.two_metre.joint_rates([0.4, q2], [0.1, 0.0])


def test_singularity_error_is_a_value_error_and_names_the_first_bad_row():
    q = np.array([[0.1, 1.0], [0.2, 0.0], [0.3, 0.0]])
    with pytest.raises(ValueError, match=r"index \(1,\), first of 2"):
        arms.two_metre.joint_rates(q, [0.0, 1.0])


def test_joint_rates_tolerance_is_adjustable():
    q = [0.4, 0.01]
    assert np.all(np.isfinite(arms.two_metre.joint_rates(q, [0.0, 1.0])))
    with pytest.raises(SingularityError, match="tol = 0.02"):
        arms.two_metre.joint_rates(q, [0.0, 1.0], tol=0.02)
    with pytest.raises(ValueError, match="tol"):
        arms.two_metre.joint_rates(q, [0.0, 1.0], tol=-1.0)


@given(
    arm=arm_strategy(), q=configurations(), v_tip=pairs(), damping=st.floats(1e-3, 10.0)
)
def test_dls_solves_its_normal_equations_and_stays_bounded(arm, q, v_tip, damping):
    """DLS minimises |J qd - v|^2 + lambda^2 |qd|^2: (J^T J + lambda^2 I) qd = J^T v."""
    qd = arm.joint_rates_dls(q, v_tip, damping)
    J = arm.jacobian(q)
    lhs = (J.T @ J + damping**2 * np.eye(2)) @ qd
    scale = (np.abs(J).max() + damping) ** 2 * (1 + np.abs(qd).max())
    assert np.allclose(lhs, J.T @ v_tip, atol=1e-10 * scale)
    assert (
        np.linalg.norm(qd) <= np.linalg.norm(v_tip) / (2 * damping) * (1 + 1e-9) + 1e-12
    )


@given(arm=arm_strategy(), q=configurations(), v_tip=pairs())
@example(
    arm=TwoLinkArm(1.0, 1.0), q=np.array([0.3, 1.0]), v_tip=np.array([0.0, 5e-324])
)
@example(
    arm=TwoLinkArm(1.0, 1.0), q=np.array([-2.0, 0.5]), v_tip=np.array([0.0, 5e-324])
)
def test_dls_tends_to_the_exact_inverse_away_from_singularities(arm, q, v_tip):
    assume(away_from_singularity(q, margin=0.2))
    sigma_min = np.linalg.svd(arm.jacobian(q), compute_uv=False)[-1]
    damping = 1e-4 * sigma_min
    exact = arm.joint_rates(q, v_tip)
    # Both solvers scale v_tip to size one and multiply back, so each result is correct to
    # rtol plus one rounding of the final product; for a subnormal v_tip that rounding is
    # absolute (results are multiples of 5e-324): the two may round to neighbouring values.
    representation = np.abs(np.spacing(np.abs(exact))).max()
    assert np.allclose(
        arm.joint_rates_dls(q, v_tip, damping),
        exact,
        rtol=1e-6,
        atol=1e-6 * np.abs(exact).max() + representation,
    )


def test_dls_at_a_singularity_is_finite_and_zero_damping_is_the_exact_inverse():
    q_stretched = [0.3, 0.0]
    qd = arms.two_metre.joint_rates_dls(
        q_stretched, [np.cos(0.3), np.sin(0.3)], damping=0.1
    )
    assert np.allclose(
        qd, 0.0
    )  # along the stretched arm the tip cannot move: DLS does nothing
    with pytest.raises(SingularityError):
        arms.two_metre.joint_rates_dls(q_stretched, [0.0, 1.0], damping=0.0)
    q = [0.3, 1.1]
    assert np.array_equal(
        arms.two_metre.joint_rates_dls(q, [0.0, 1.0], 0.0),
        arms.two_metre.joint_rates(q, [0.0, 1.0]),
    )
    with pytest.raises(ValueError, match="damping"):
        arms.two_metre.joint_rates_dls(q, [0.0, 1.0], damping=-0.1)


def test_vectorised_and_broadcast():
    rng = np.random.default_rng(3)
    q = rng.uniform(-np.pi, np.pi, (4, 3, 2))
    q[..., 1] = rng.uniform(0.3, 2.8, (4, 3))
    arm = arms.osake
    v_tip = arm.tip_velocity(q, [0.1, -0.2])
    assert v_tip.shape == (4, 3, 2)
    assert np.allclose(v_tip[2, 1], arm.tip_velocity(q[2, 1], [0.1, -0.2]))
    qd = arm.joint_rates(q, v_tip)
    assert np.allclose(qd, np.broadcast_to([0.1, -0.2], q.shape))
    assert arm.joint_rates_dls(q, v_tip, 0.01).shape == (4, 3, 2)
    assert arm.manipulability(q).shape == (4, 3)
    ellipse = velocity.velocity_ellipse(arm, q)
    assert ellipse.semi_axes.shape == (4, 3, 2) and ellipse.directions.shape == (
        4,
        3,
        2,
        2,
    )
    assert ellipse.points(n=10).shape == (4, 3, 10, 2)


@pytest.mark.parametrize("bad", [[np.nan, 0.0], [0.0, np.inf], [1.0, 2.0, 3.0]])
def test_bad_input_raises(bad):
    arm = arms.two_metre
    with pytest.raises(ValueError):
        arm.tip_velocity(bad, [0.0, 1.0])
    with pytest.raises(ValueError):
        arm.tip_velocity([0.1, 1.0], bad)
    with pytest.raises(ValueError):
        arm.joint_rates([0.1, 1.0], bad)
    with pytest.raises(ValueError):
        arm.joint_rates_dls(bad, [0.0, 1.0], 0.1)
    with pytest.raises(ValueError):
        arm.manipulability(bad)
    with pytest.raises(ValueError, match="do not broadcast"):
        arm.tip_velocity(np.zeros((3, 2)), np.zeros((4, 2)))


def _inside(points, matrix, centre):
    offset = points - centre
    return np.einsum("...i,ij,...j->...", offset, np.linalg.inv(matrix), offset)


@given(arm=arm_strategy(), q=configurations(), qd=pairs())
def test_velocity_ellipse_is_the_image_of_the_unit_circle(arm, q, qd):
    assume(away_from_singularity(q, margin=0.05))
    J = arm.jacobian(q)
    ellipse = velocity.velocity_ellipse(arm, q)
    eigenvalues = np.linalg.eigvalsh(J @ J.T)[::-1]
    assert np.allclose(
        ellipse.semi_axes**2,
        eigenvalues,
        rtol=1e-9,
        atol=1e-12 * (arm.l1 + arm.l2) ** 2,
    )
    assert np.prod(ellipse.semi_axes) == pytest.approx(arm.manipulability(q), rel=1e-9)
    assert np.allclose(ellipse.centre, arm.fk(q))
    # boundary points are on the ellipse x^T (J J^T)^-1 x = 1; J of a unit joint rate lies on it too
    boundary = ellipse.points(n=16)
    assert np.allclose(_inside(boundary, J @ J.T, ellipse.centre), 1.0, rtol=1e-6)
    assume(np.linalg.norm(qd) > 1e-3)
    v_unit = J @ (qd / np.linalg.norm(qd))
    assert _inside(ellipse.centre + v_unit, J @ J.T, ellipse.centre) == pytest.approx(
        1.0, rel=1e-6
    )


@given(arm=arm_strategy(), q=configurations())
def test_force_ellipse_holds_unit_torque_on_its_boundary(arm, q):
    assume(away_from_singularity(q, margin=0.05))
    J = arm.jacobian(q)
    ellipse = velocity.force_ellipse(arm, q)
    assert ellipse.semi_axes[0] >= ellipse.semi_axes[1]
    forces = ellipse.points(n=16) - ellipse.centre
    torque_norms = np.linalg.norm(forces @ J, axis=-1)  # |J^T F| per boundary force
    assert np.allclose(torque_norms, 1.0, rtol=1e-6)
    velocity_axes = velocity.velocity_ellipse(arm, q).semi_axes
    assert np.allclose(ellipse.semi_axes, 1.0 / velocity_axes[::-1], rtol=1e-9)


def test_force_ellipse_is_unbounded_at_a_singularity_and_drawing_needs_a_clip():
    ellipse = velocity.force_ellipse(arms.two_metre, [0.0, 0.0])
    assert ellipse.semi_axes[0] > 1e12
    major = ellipse.directions[:, 0]
    assert abs(major[0]) == pytest.approx(1.0)  # along the stretched arm
    points = ellipse.points(n=8, scale=0.01, clip=2.0)
    assert (
        np.all(np.isfinite(points))
        and np.abs(points - ellipse.centre).max() <= 2.0 + 1e-12
    )
    exact = velocity.Ellipse(np.zeros(2), np.array([np.inf, 1.0]), np.eye(2))
    with pytest.raises(ValueError, match="clip"):
        exact.points()


def test_ellipse_angle_is_the_major_axis_direction():
    ellipse = velocity.velocity_ellipse(TwoLinkArm(1.0, 1.0), [0.0, np.pi / 2])
    major = ellipse.directions[:, 0]
    assert -np.pi / 2 < ellipse.angle <= np.pi / 2
    assert (
        abs(np.cos(ellipse.angle) * major[1] - np.sin(ellipse.angle) * major[0]) < 1e-12
    )


# ---------------------------------------------------------------- one singularity test, one tolerance


def test_velocity_singularity_tol_is_the_kinematics_one():
    assert velocity.SINGULARITY_TOL is kinematics.SINGULARITY_TOL


@pytest.mark.parametrize("q", [[0.4, 0.0], [[0.1, 1.0], [0.2, np.pi]]])
def test_joint_rates_refuse_with_the_kinematics_message_and_advise_dls(q):
    with pytest.raises(SingularityError) as shared:
        kinematics.require_nonsingular(arms.two_metre, q, "solving for the joint rates")
    with pytest.raises(SingularityError) as refused:
        arms.two_metre.joint_rates(q, [0.0, 1.0])
    assert (
        str(refused.value)
        == f"{shared.value}; the joint rates are unbounded there: use joint_rates_dls"
    )
    assert refused.value.__cause__ is None and refused.value.__suppress_context__


def test_tip_stiffness_refuses_with_the_kinematics_message_and_says_why():
    with pytest.raises(SingularityError) as shared:
        kinematics.require_nonsingular(
            arms.two_metre, [0.5, np.pi], "the tip stiffness"
        )
    with pytest.raises(SingularityError) as refused:
        stiffness.tip_stiffness(arms.two_metre, [0.5, np.pi], 100.0)
    assert (
        str(refused.value)
        == f"{shared.value}; along the arm the tip stiffness is unbounded"
    )


@pytest.mark.parametrize(
    "function",
    [stiffness.joint_stiffness, stiffness.tip_stiffness, stiffness.stiffness_ellipse],
)
def test_stiffness_takes_one_configuration_with_the_shared_message(function):
    with pytest.raises(
        ValueError,
        match=r"^q must be one configuration of shape \(2,\) \(radians\); got shape \(1, 2\)$",
    ):
        function(arms.two_metre, [[0.5, 1.0]], 100.0)


@pytest.mark.parametrize(
    "function",
    [
        getattr(velocity, name)
        for name in velocity.__all__
        if callable(getattr(velocity, name))
    ]
    + [velocity.Ellipse.points, velocity.Ellipse.angle.fget]
    + [getattr(stiffness, name) for name in stiffness.__all__],
)
def test_public_functions_are_fully_annotated(function):
    signature = inspect.signature(function)
    assert all(
        p.annotation is not inspect.Parameter.empty
        for p in signature.parameters.values()
        if p.name != "self"
    )
    assert signature.return_annotation is not inspect.Signature.empty


def test_ellipse_spells_centre():
    ellipse = velocity.Ellipse(
        centre=np.array([1.0, 2.0]), semi_axes=np.ones(2), directions=np.eye(2)
    )
    assert np.allclose(
        ellipse.points(n=5).mean(axis=0), [1.0 + 0.2, 2.0]
    )  # the repeated first point (1, 0) shifts the mean
    with pytest.raises(TypeError):
        velocity.Ellipse(center=np.zeros(2), semi_axes=np.ones(2), directions=np.eye(2))


# -------------------- damped least squares at singularities; tiny and huge velocities
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


def test_overflowing_joint_rates_are_reported_not_returned_as_inf():
    with pytest.raises(
        OverflowError, match=r"joint rates qd \(rad/s\) overflow float64"
    ):
        arms.two_metre.joint_rates([0.3, 1e-5], [0.0, 1e305])
    with pytest.raises(OverflowError, match="joint rates"):
        arms.two_metre.joint_rates_dls([0.3, 1e-5], [0.0, 1e305], 1e-300)
    with pytest.raises(OverflowError, match="tip velocities"):
        arms.two_metre.tip_velocity([0.3, 1.0], [1e308, 1e308])
