"""Inverse kinematics: every solver, both branches, the reach boundary, bad input."""

import re

import numpy as np
import pytest
from conftest import angles, unit
from conftest import arms as arm_strategy
from hypothesis import assume, given
from hypothesis import strategies as st

from twolink import TwoLinkArm, UnreachableError, arms, ik, wrap_angle


def target_at(radius, heading):
    return np.array([radius * np.cos(heading), radius * np.sin(heading)])


@given(arm=arm_strategy(), fraction=unit, heading=angles)
def test_closed_form_round_trip_over_the_annulus(arm, fraction, heading):
    r_min, r_max = arm.reach
    p = target_at(r_min + fraction * (r_max - r_min), heading)
    for elbow in ("down", "up"):
        q = ik.closed_form(arm, p, elbow=elbow)
        assert np.linalg.norm(arm.fk(q) - p) <= 1e-9 * r_max


@given(
    arm=arm_strategy(),
    offset=st.floats(min_value=-1e-12, max_value=1e-12),
    heading=angles,
    outer=st.booleans(),
)
def test_closed_form_within_1e12_of_either_reach_circle(arm, offset, heading, outer):
    """Full stretch and full fold: cos q2 rounds past +-1 there and must be clipped, not rejected."""
    r_min, r_max = arm.reach
    radius = (r_max if outer else r_min) + offset * r_max
    assume(radius >= 0.0)
    p = target_at(radius, heading)
    q_both = ik.closed_form(arm, p, elbow="both")
    assert np.all(np.isfinite(q_both))
    for q in q_both:
        assert np.linalg.norm(arm.fk(q) - p) <= 1e-9 * r_max


def test_full_stretch_cos_q2_rounds_above_one_and_is_clipped():
    arm = TwoLinkArm(10.0, 10.0)
    p = np.array([10 * np.sqrt(2), 10 * np.sqrt(2)])
    c2 = (p @ p - 200.0) / 200.0
    assert c2 > 1.0  # the round-off the issue warns about
    q = ik.closed_form(arm, p)
    assert np.allclose(q, [np.pi / 4, 0.0], atol=1e-7)
    assert np.allclose(ik.closed_form(arm, p, elbow="up"), ik.closed_form(arm, p, elbow="down"), atol=1e-7)


def test_full_fold_with_equal_links_reaches_the_base():
    q = ik.closed_form(arms.ten, [0.0, 0.0])
    assert q[1] == pytest.approx(np.pi)
    assert np.allclose(arms.ten.fk(q), 0.0, atol=1e-12)


@given(arm=arm_strategy(), fraction=st.floats(min_value=0.01, max_value=0.99), heading=angles)
def test_branches_have_the_documented_signs(arm, fraction, heading):
    r_min, r_max = arm.reach
    p = target_at(r_min + fraction * (r_max - r_min), heading)
    q_both = ik.closed_form(arm, p, elbow="both")
    assert q_both.shape == (2, 2)
    assert q_both[0, 1] >= 0.0 and q_both[1, 1] <= 0.0
    assert np.allclose(q_both[0], ik.closed_form(arm, p, elbow="down"))
    assert np.allclose(q_both[1], ik.closed_form(arm, p, elbow="up"))
    assert np.all(np.abs(q_both) <= np.pi + 1e-12)


def test_elbow_down_puts_the_elbow_below_the_base_to_tip_line():
    p = np.array([1.5, 0.0])
    for elbow, sign in (("down", -1.0), ("up", 1.0)):
        elbow_point = arms.two_metre.joint_positions(ik.closed_form(arms.two_metre, p, elbow=elbow))[1]
        assert np.sign(elbow_point[1]) == sign


def test_closed_form_is_vectorised_over_leading_axes():
    rng = np.random.default_rng(3)
    q_true = rng.uniform(-np.pi, np.pi, (4, 5, 2))
    p = arms.osake.fk(q_true)
    q = ik.closed_form(arms.osake, p)
    assert q.shape == (4, 5, 2)
    assert ik.closed_form(arms.osake, p, elbow="both").shape == (4, 5, 2, 2)
    assert np.allclose(arms.osake.fk(q), p, atol=1e-12)
    # q_true is recovered on the branch matching the sign of its q2
    q_both = ik.closed_form(arms.osake, p, elbow="both")
    q_matching = np.where((q_true[..., 1] >= 0)[..., None], q_both[..., 0, :], q_both[..., 1, :])
    assert np.allclose(np.cos(q_matching - q_true), 1.0)


def test_source_example_double_root():
    q_both = ik.closed_form(arms.ten, [10 * np.sqrt(2), 10 * np.sqrt(2)], elbow="both")
    assert np.allclose(q_both, [[np.pi / 4, 0.0], [np.pi / 4, 0.0]], atol=1e-7)


@pytest.mark.parametrize("solver", ["closed_form", "newton", "minimize", "brute_force"])
def test_unreachable_target_names_distance_and_reach(solver):
    with pytest.raises(UnreachableError) as info:
        getattr(ik, solver)(arms.ten, [30.0, 40.0])
    message = str(info.value)
    assert "50 m from the base" in message
    assert "[0, 20] m" in message
    assert isinstance(info.value, ValueError)


def test_unreachable_inside_the_hole():
    arm = TwoLinkArm(2.0, 0.5)
    with pytest.raises(UnreachableError, match=re.escape("is 1 m from the base; this arm reaches distances in [1.5, 2.5] m")):
        ik.closed_form(arm, [[2.0, 0.0], [0.0, 1.0]])


def test_unreachable_in_a_batch_names_the_first_offender():
    with pytest.raises(UnreachableError, match=r"index \(2,\), first of 2"):
        ik.closed_form(arms.two_metre, [[1.0, 1.0], [2.0, 0.0], [5.0, 0.0], [0.0, 9.0]])


@pytest.mark.parametrize("solver", ["closed_form", "newton", "minimize", "brute_force"])
@pytest.mark.parametrize("bad", [[np.nan, 1.0], [1.0, np.inf], [1.0, 2.0, 3.0]])
def test_non_finite_or_misshapen_targets_raise_value_error(solver, bad):
    with pytest.raises(ValueError, match="target p must"):
        getattr(ik, solver)(arms.ten, bad)


def test_unknown_elbow_raises():
    with pytest.raises(ValueError, match="elbow must be one of"):
        ik.closed_form(arms.ten, [10.0, 10.0], elbow="left")


def same_angles(q_a, q_b, atol):
    return np.allclose(wrap_angle(np.asarray(q_a) - np.asarray(q_b)), 0.0, atol=atol)


@given(arm=arm_strategy(ratio_max=5.0), fraction=st.floats(min_value=0.05, max_value=0.95), heading=angles)
def test_newton_agrees_with_a_closed_form_branch(arm, fraction, heading):
    r_min, r_max = arm.reach
    p = target_at(r_min + fraction * (r_max - r_min), heading)
    result = ik.newton(arm, p, q0=(0.5, 1.0))
    assert result.success and result.method == "newton"
    assert result.residual <= 1e-12 * r_max
    down, up = ik.closed_form(arm, p, elbow="both")
    assert same_angles(result.q, down, 1e-6) or same_angles(result.q, up, 1e-6)


def test_newton_converges_from_the_cold_start_on_a_batch():
    rng = np.random.default_rng(7)
    p = arms.ten.fk(rng.uniform(-np.pi, np.pi, (2000, 2)))
    result = ik.newton(arms.ten, p, q0=(0.5, 1.0))
    assert result.all_success, result.message
    assert result.q.shape == (2000, 2) and result.residual.shape == (2000,)
    assert np.all(np.abs(arms.ten.fk(result.q) - p) <= 1e-11 * 20)


def test_newton_reports_failure_honestly_when_capped():
    result = ik.newton(arms.ten, [-15.0, 5.0], q0=(0.5, 1.0), max_iter=1)
    assert not result.success
    assert "did not converge" in result.message
    assert result.residual == pytest.approx(np.linalg.norm(arms.ten.fk(result.q) - [-15.0, 5.0]))


@pytest.mark.parametrize("constrained", [False, True])
def test_minimize_agrees_with_closed_form(constrained):
    rng = np.random.default_rng(11)
    arm = arms.two_metre
    q_true = rng.uniform([-3.0, 0.3], [3.0, 2.8], (12, 2))
    p = arm.fk(q_true)
    result = ik.minimize(arm, p, q0=(0.4, 1.0), constrained=constrained)
    assert result.all_success, result.message
    assert np.all(result.residual <= 1e-9 * 4.0)
    q_both = ik.closed_form(arm, p, elbow="both")
    for q, (down, up) in zip(result.q, q_both):
        assert same_angles(q, down, 1e-5) or same_angles(q, up, 1e-5)


def test_constrained_minimize_respects_relative_limits():
    result = ik.minimize(arms.ten, [10.0, 12.0], q0=(0.4, 0.5), constrained=True)
    assert result.success, result.message
    assert arms.ten.within_limits(result.q)
    # (5, 12) is 13 m away: it needs |q2| = 98.9 deg, beyond the 90 deg limit.
    beyond = ik.minimize(arms.ten, [5.0, 12.0], q0=(0.4, 0.5), constrained=True)
    assert not beyond.success and "failed for 1 of 1" in beyond.message
    assert arms.ten.within_limits(beyond.q)


@given(fraction=st.floats(min_value=0.05, max_value=0.95), heading=st.floats(min_value=0.0, max_value=np.pi / 2))
def test_brute_force_agrees_with_closed_form_to_its_grid_step(fraction, heading):
    arm = arms.ten
    p = target_at(fraction * 20.0, heading)
    step = np.radians(1.0)
    result = ik.brute_force(arm, p, step=step)
    q_both = ik.closed_form(arm, p, elbow="both")
    inside = [q for q in q_both if arm.within_limits(q)]
    assume(inside)
    assert result.success
    assert result.residual <= (arm.l1 + 2 * arm.l2) * step / 2
    assert arm.within_limits(result.q)
    # the grid point is no worse than the grid point nearest the exact solution
    nearest = [np.round(q / step) * step for q in inside]
    assert result.residual <= min(np.linalg.norm(arm.fk(q) - p) for q in nearest) + 1e-12


def test_brute_force_fails_honestly_outside_its_limits():
    result = ik.brute_force(arms.ten, [-12.0, -5.0], step=np.radians(2.0))
    assert not result.success
    assert "outside the workspace the joint limits leave" in result.message


def test_brute_force_respects_absolute_limits():
    arm = arms.two_metre_limited
    result = ik.brute_force(arm, [0.0, 3.0], step=np.radians(1.0))
    assert result.success and arm.within_limits(result.q)


def test_brute_force_memory_is_bounded_for_a_fine_grid():
    """A 0.05 deg grid over the limits has 6.5 million points (52 MB per float array)."""
    import tracemalloc

    step = np.radians(0.05)
    tracemalloc.start()
    try:
        result = ik.brute_force(arms.ten, [10.0, 10.0], step=step)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert int(result.iterations) > 6_000_000
    assert peak < 12e6, f"peak {peak / 1e6:.1f} MB"
    assert result.success and result.residual <= (10 + 20) * step / 2


def test_brute_force_rejects_bad_steps_and_ranges():
    with pytest.raises(ValueError, match="step"):
        ik.brute_force(arms.ten, [10.0, 10.0], step=0.0)
    with pytest.raises(ValueError, match="is empty"):
        ik.brute_force(arms.ten, [10.0, 10.0], q1_range=(2.0, 3.0))


def test_ik_result_fields():
    result = ik.newton(arms.ten, [[10.0, 10.0]], q0=(0.5, 1.0))
    assert result.q.shape == (1, 2)
    assert result.success.dtype == bool
    assert result.iterations.dtype.kind == "i"
    assert isinstance(result.message, str)
