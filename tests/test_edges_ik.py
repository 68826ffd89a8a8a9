"""Edges of inverse kinematics: honest results (class 5), empty and odd batches (class 6)."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from twolink import TwoLinkArm, arms, ik, workspace
from twolink.errors import InputTypeError
from twolink.ik.grid_search import grid_axis

LIMITED = TwoLinkArm(1.0, 1.0, q_min=(0.0, 0.0), q_max=(np.pi / 2, np.pi / 2))


# ----------------------------------------------------------------- class 5: honest results
def test_brute_force_never_claims_a_target_outside_the_limited_workspace():
    p_outside = LIMITED.fk(
        np.radians([-1.0, 60.0])
    )  # 1 deg below q1's limit, closer than the grid bound
    assert not workspace.is_reachable(LIMITED, p_outside)
    result = ik.brute_force(LIMITED, p_outside, step=np.radians(2.0))
    assert not result.success
    assert "outside the workspace the joint limits leave" in result.message


@settings(max_examples=60)
@given(
    q=st.tuples(st.floats(-np.pi, np.pi), st.floats(-np.pi, np.pi)),
    step_deg=st.floats(0.5, 10.0),
    which=st.sampled_from(["ten", "two_metre_limited", "limited"]),
)
def test_brute_force_success_implies_within_limits_reachable_and_within_the_bound(
    q, step_deg, which
):
    arm = {
        "ten": arms.ten,
        "two_metre_limited": arms.two_metre_limited,
        "limited": LIMITED,
    }[which]
    p = arm.fk(np.array(q))
    result = ik.brute_force(arm, p, step=np.radians(step_deg))
    assert bool(result.within_limits) == bool(arm.within_limits(result.q))
    if result.success:
        assert arm.within_limits(result.q) and workspace.is_reachable(arm, p)
        assert result.residual <= (arm.l1 + 2 * arm.l2) * np.radians(step_deg) / 2 * (
            1 + 1e-9
        )
    elif workspace.is_reachable(arm, p) and arm.limit_convention == "relative":
        pytest.fail(f"a reachable target was not solved: {result.message}")


@pytest.mark.parametrize("step_deg", [7.0, 13.0, 40.0, 89.0])
def test_the_grid_includes_both_ends_of_each_joint_range_whatever_the_step(step_deg):
    result = ik.brute_force(
        arms.ten, [10.0, 10.0], step=np.radians(step_deg)
    )  # exactly (0, 90) deg: two range ends
    assert np.allclose(np.degrees(result.q), [0.0, 90.0], atol=1e-9)
    assert result.success and result.residual < 1e-12
    axis = ik.grid_search.grid_axis(0.0, 1.0, 0.3)
    assert axis[0] == 0.0 and axis[-1] == 1.0 and np.all(np.diff(axis) <= 0.3 + 1e-15)


def test_newton_and_minimize_say_whether_they_respect_the_limits():
    p = [10.0, -5.0]  # reachable by the annulus, not within arms.ten's limits
    for result in (
        ik.newton(arms.ten, p, q0=[-0.5, 1.0]),
        ik.minimize(arms.ten, p, q0=[-0.5, 1.0]),
    ):
        assert result.success  # the tip is there ...
        assert not result.within_limits  # ... but with angles the arm cannot take
        assert "violate the joint limits" in result.message
    ok = ik.newton(arms.ten, [10.0, 10.0], q0=[0.5, 1.0])
    assert ok.within_limits and "violate" not in ok.message


def test_newton_from_a_stretched_start_pointing_at_the_target_does_not_claim_success():
    """The zero-gradient start the docstring used to deny: the result says it failed."""
    result = ik.newton(arms.two_metre, [3.0, 0.0], q0=[0.0, 0.0])
    assert not result.success and "did not converge" in result.message
    assert "converge from any start" not in ik.newton.__doc__


# ----------------------------------------------------------------- class 6: empty and odd batches
EMPTY_SHAPES = [(0, 2), (3, 0, 2), (0, 0, 2)]


@pytest.mark.parametrize("shape", EMPTY_SHAPES)
@pytest.mark.parametrize(
    "solve",
    [
        lambda p: ik.closed_form(arms.ten, p),
        lambda p: ik.closed_form(arms.ten, p, elbow="auto"),
        lambda p: ik.newton(arms.ten, p),
        lambda p: ik.minimize(arms.ten, p),
        lambda p: ik.minimize(arms.ten, p, constrained=True),
        lambda p: ik.brute_force(arms.ten, p, step=np.radians(5.0)),
    ],
    ids=[
        "closed-form",
        "closed-form-auto",
        "newton",
        "minimize",
        "minimize-constrained",
        "brute-force",
    ],
)
def test_an_empty_batch_gives_an_empty_result(solve, shape):
    result = solve(np.empty(shape))
    assert result.q.shape == shape and result.success.shape == shape[:-1]
    assert (
        result.residual.shape == shape[:-1] and result.within_limits.shape == shape[:-1]
    )
    assert result.all_success


@pytest.mark.parametrize("shape", EMPTY_SHAPES)
def test_empty_batches_through_the_vectorised_functions(shape):
    from twolink import velocity

    arm, empty = arms.ten, np.empty(shape)
    lead = shape[:-1]
    assert ik.closed_form(arm, empty).q.shape == shape
    assert ik.closed_form(arm, empty, elbow="both").q.shape == (2,) + shape
    assert arm.fk(empty).shape == shape and arm.jacobian(empty).shape == lead + (2, 2)
    assert arm.forward_dynamics(empty, empty, empty).shape == shape
    assert arm.forward_dynamics(empty, empty, empty, empty).shape == shape
    assert arm.inverse_dynamics(empty, empty, empty).shape == shape
    assert arm.joint_rates(empty, empty).shape == shape
    assert arm.joint_rates_dls(empty, empty, 0.1).shape == shape
    assert velocity.velocity_ellipse(arm, empty).semi_axes.shape == shape
    assert workspace.is_reachable(arm, empty).shape == lead


@pytest.mark.parametrize("solve", [ik.newton, ik.minimize], ids=["newton", "minimize"])
def test_a_start_of_the_wrong_shape_names_both_shapes(solve):
    with pytest.raises(
        ValueError,
        match=r"q0 of shape \(3, 2\) does not match target p of shape \(2, 2\)",
    ):
        solve(arms.ten, [[10.0, 10.0], [5.0, 12.0]], q0=np.full((3, 2), 0.5))


def test_timing_an_empty_batch_is_refused_clearly():
    from twolink import timing

    with pytest.raises(ValueError, match=r"n >= 1"):
        timing.compare_ik_methods(
            arms.ten, np.empty((0, 2)), methods=["closed form"], repeat=1
        )


# ----------------------------------------------------------------- grid and optimiser arguments
@pytest.mark.parametrize(
    ("step", "message"),
    [
        (0.0, r"step \(radians\) must be > 0.0; got 0.0"),
        (-0.1, r"step \(radians\) must be > 0.0; got -0.1"),
        (float("inf"), r"step \(radians\) must be finite; got inf"),
    ],
)
def test_grid_axis_refuses_a_step_that_is_not_finite_and_positive(step, message):
    with pytest.raises(ValueError, match=message):
        grid_axis(0.0, 1.0, step)


@pytest.mark.parametrize("bad", [b"ab", "ab", (True, 1.0)])
def test_brute_force_refuses_a_range_that_is_not_two_angles(bad):
    with pytest.raises(
        InputTypeError,
        match=r"q1_range must be None or a pair \(low, high\) of angles in radians",
    ):
        ik.brute_force(arms.two_metre, [3.0, 1.0], q1_range=bad)


@pytest.mark.parametrize("bad", [[0.0, 1.0, 2.0], (0.0, float("inf")), [[0.0, 1.0]]])
def test_brute_force_refuses_a_range_of_another_shape_or_not_finite(bad):
    with pytest.raises(
        ValueError,
        match=r"q2_range must be None or a pair \(low, high\) of finite angles in radians",
    ):
        ik.brute_force(arms.two_metre, [3.0, 1.0], q2_range=bad)


@pytest.mark.parametrize("bad", ["False", "True", 1, None])
def test_minimize_takes_only_a_bool_for_constrained(bad):
    with pytest.raises(
        InputTypeError, match=r"constrained must be True or False; got "
    ):
        ik.minimize(arms.two_metre, [3.0, 1.0], constrained=bad)
