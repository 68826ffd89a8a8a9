"""Inverse kinematics: every solver, both branches, the reach boundary, bad input."""

import dataclasses
import pickle
import re

import numpy as np
import pytest
from _cases import BAD_PAIRS
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from conftest import angles, unit
from conftest import arms as arm_strategy
from twolink import (
    TwoLinkArm,
    UnreachableError,
    arms,
    ik,
    kinematics,
    workspace,
    wrap_angle,
)
from twolink.conventions import ELBOW_WORDS
from twolink.errors import InputTypeError
from twolink.ik.grid_search import grid_axis
from twolink.ik.iterative import _lm_step
from twolink.ik.result import assemble_result


def target_at(radius, heading):
    return np.array([radius * np.cos(heading), radius * np.sin(heading)])


@given(arm=arm_strategy(), fraction=unit, heading=angles)
def test_closed_form_round_trip_over_the_annulus(arm, fraction, heading):
    r_min, r_max = arm.reach
    p = target_at(r_min + fraction * (r_max - r_min), heading)
    for elbow in ("down", "up"):
        q = ik.closed_form(arm, p, elbow=elbow).q
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
    q_both = ik.closed_form(arm, p, elbow="both").q
    assert np.all(np.isfinite(q_both))
    for q in q_both:
        assert np.linalg.norm(arm.fk(q) - p) <= 1e-9 * r_max


def test_full_stretch_cos_q2_rounds_above_one_and_is_clipped():
    arm = TwoLinkArm(10.0, 10.0)
    p = np.array([10 * np.sqrt(2), 10 * np.sqrt(2)])
    c2 = (p @ p - 200.0) / 200.0
    assert c2 > 1.0  # the round-off that would make acos fail
    q = ik.closed_form(arm, p).q
    assert np.allclose(q, [np.pi / 4, 0.0], atol=1e-7)
    assert np.allclose(
        ik.closed_form(arm, p, elbow="up").q,
        ik.closed_form(arm, p, elbow="down").q,
        atol=1e-7,
    )


def test_full_fold_with_equal_links_reaches_the_base():
    q = ik.closed_form(arms.ten, [0.0, 0.0]).q
    assert q[1] == pytest.approx(np.pi)
    assert np.allclose(arms.ten.fk(q), 0.0, atol=1e-12)


@given(
    arm=arm_strategy(),
    fraction=st.floats(min_value=0.01, max_value=0.99),
    heading=angles,
)
def test_branches_have_the_documented_signs(arm, fraction, heading):
    r_min, r_max = arm.reach
    p = target_at(r_min + fraction * (r_max - r_min), heading)
    q_both = ik.closed_form(arm, p, elbow="both").q
    assert q_both.shape == (2, 2)
    assert q_both[0, 1] >= 0.0 and q_both[1, 1] <= 0.0
    assert np.allclose(q_both[0], ik.closed_form(arm, p, elbow="down").q)
    assert np.allclose(q_both[1], ik.closed_form(arm, p, elbow="up").q)
    assert np.all(np.abs(q_both) <= np.pi + 1e-12)


def test_elbow_down_puts_the_elbow_below_the_base_to_tip_line():
    p = np.array([1.5, 0.0])
    for elbow, sign in (("down", -1.0), ("up", 1.0)):
        elbow_point = arms.two_metre.joint_positions(
            ik.closed_form(arms.two_metre, p, elbow=elbow).q
        )[1]
        assert np.sign(elbow_point[1]) == sign


def test_closed_form_is_vectorised_over_leading_axes():
    rng = np.random.default_rng(3)
    q_true = rng.uniform(-np.pi, np.pi, (4, 5, 2))
    p = arms.osake.fk(q_true)
    result = ik.closed_form(arms.osake, p)
    q = result.q
    assert q.shape == (4, 5, 2)
    assert (
        result.success.shape
        == result.residual.shape
        == result.within_limits.shape
        == (4, 5)
    )
    both = ik.closed_form(arms.osake, p, elbow="both")
    assert both.q.shape == (
        2,
        4,
        5,
        2,
    )  # the branches on a new leading axis, down first
    assert (
        both.success.shape == both.residual.shape == both.iterations.shape == (2, 4, 5)
    )
    assert np.allclose(arms.osake.fk(q), p, atol=1e-12)
    # q_true is recovered on the branch matching the sign of its q2
    q_both = both.q
    q_matching = np.where((q_true[..., 1] >= 0)[..., None], q_both[0], q_both[1])
    assert np.allclose(np.cos(q_matching - q_true), 1.0)


def test_source_example_double_root():
    q_both = ik.closed_form(
        arms.ten, [10 * np.sqrt(2), 10 * np.sqrt(2)], elbow="both"
    ).q
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
    with pytest.raises(
        UnreachableError,
        match=re.escape(
            "is 1 m from the base; this arm reaches distances in [1.5, 2.5] m"
        ),
    ):
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


@given(
    arm=arm_strategy(ratio_max=5.0),
    fraction=st.floats(min_value=0.05, max_value=0.95),
    heading=angles,
)
def test_newton_agrees_with_a_closed_form_branch(arm, fraction, heading):
    r_min, r_max = arm.reach
    p = target_at(r_min + fraction * (r_max - r_min), heading)
    result = ik.newton(arm, p, q0=(0.5, 1.0))
    assert result.success and result.method == "newton"
    assert result.residual <= 1e-12 * r_max
    down, up = ik.closed_form(arm, p, elbow="both").q
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
    assert result.residual == pytest.approx(
        np.linalg.norm(arms.ten.fk(result.q) - [-15.0, 5.0])
    )


@pytest.mark.parametrize("constrained", [False, True])
def test_minimize_agrees_with_closed_form(constrained):
    rng = np.random.default_rng(11)
    arm = arms.two_metre
    q_true = rng.uniform([-3.0, 0.3], [3.0, 2.8], (12, 2))
    p = arm.fk(q_true)
    result = ik.minimize(arm, p, q0=(0.4, 1.0), constrained=constrained)
    assert result.all_success, result.message
    assert np.all(result.residual <= 1e-9 * 4.0)
    q_both = ik.closed_form(arm, p, elbow="both").q
    for q, down, up in zip(result.q, *q_both):
        assert same_angles(q, down, 1e-5) or same_angles(q, up, 1e-5)


def test_constrained_minimize_respects_relative_limits():
    result = ik.minimize(arms.ten, [10.0, 12.0], q0=(0.4, 0.5), constrained=True)
    assert result.success, result.message
    assert arms.ten.within_limits(result.q)
    # (5, 12) is 13 m away: it needs |q2| = 98.9 deg, beyond the 90 deg limit.
    beyond = ik.minimize(arms.ten, [5.0, 12.0], q0=(0.4, 0.5), constrained=True)
    assert not beyond.success and "failed for 1 of 1" in beyond.message
    assert arms.ten.within_limits(beyond.q)


# fractions from 0.72: arms.ten reaches within its limits only at |p| >= 10 sqrt 2 = 0.707 * 20 (fewer targets
# filtered out by assume below; hypothesis refused a run that drew too many from below)
@given(
    fraction=st.floats(min_value=0.72, max_value=0.95),
    heading=st.floats(min_value=0.0, max_value=np.pi / 2),
)
def test_brute_force_agrees_with_closed_form_to_its_grid_step(fraction, heading):
    arm = arms.ten
    p = target_at(fraction * 20.0, heading)
    step = np.radians(1.0)
    result = ik.brute_force(arm, p, step=step)
    q_both = ik.closed_form(arm, p, elbow="both").q
    inside = [q for q in q_both if arm.within_limits(q)]
    assume(inside)
    assert result.success
    assert result.residual <= (arm.l1 + 2 * arm.l2) * step / 2
    assert arm.within_limits(result.q)
    # the grid point is no worse than the grid point nearest the exact solution
    nearest = [np.round(q / step) * step for q in inside]
    assert (
        result.residual <= min(np.linalg.norm(arm.fk(q) - p) for q in nearest) + 1e-12
    )


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


# ---------------------------------------------------------------- one result type
SOLVERS = {
    "closed_form": lambda arm, p: ik.closed_form(arm, p),
    "closed_form both": lambda arm, p: ik.closed_form(arm, p, elbow="both"),
    "closed_form auto": lambda arm, p: ik.closed_form(arm, p, elbow="auto"),
    "newton": lambda arm, p: ik.newton(arm, p, q0=(0.5, 1.0)),
    "minimize": lambda arm, p: ik.minimize(arm, p, q0=(0.5, 1.0)),
    "brute_force": lambda arm, p: ik.brute_force(arm, p, step=np.radians(2.0)),
}


@pytest.mark.parametrize("name", SOLVERS)
@pytest.mark.parametrize(
    "p", [[12.0, 9.0], [[12.0, 9.0], [5.0, 12.0], [-10.0, 10.0]]], ids=["one", "batch"]
)
def test_every_solver_returns_an_ik_result_with_the_documented_fields(name, p):
    result = SOLVERS[name](arms.ten, p)
    assert isinstance(result, ik.IKResult)
    lead = np.shape(p)[:-1]
    if name == "closed_form both":
        lead = (2,) + lead
    assert (
        isinstance(result.q, np.ndarray)
        and result.q.dtype == np.float64
        and result.q.shape == lead + (2,)
    )
    for field, kind, plain in (
        ("success", "b", bool),
        ("within_limits", "b", bool),
        ("iterations", "i", int),
        ("residual", "f", float),
    ):
        value = getattr(result, field)
        if lead:  # a batch: arrays of the batch's shape
            assert (
                isinstance(value, np.ndarray)
                and value.shape == lead
                and value.dtype.kind == kind
            ), field
        else:  # one answer: a plain Python number
            assert type(value) is plain, field
    assert isinstance(result.message, str) and isinstance(result.method, str)
    assert isinstance(result.all_success, bool)
    assert result.all_success == bool(np.all(result.success))
    assert np.array_equal(result.within_limits, arms.ten.within_limits(result.q))


def test_closed_form_returns_a_result_whose_residual_is_recomputed_from_q():
    p = np.array([[12.0, 9.0], [5.0, 12.0]])
    result = ik.closed_form(arms.ten, p)
    assert result.method == "closed-form" and np.all(result.iterations == 0)
    # forward kinematics of q (with q2's cosine and sine from the unit vector q2 is the atan2 of)
    assert np.allclose(
        result.residual, np.hypot(*(arms.ten.fk(result.q) - p).T), rtol=0, atol=1e-14
    )
    assert result.all_success and np.all(result.residual < 1e-12)


#: Link lengths as unequal as the arm allows them to be, both ways round.
UNEQUAL = [
    (1e-9, 1e9),
    (1e9, 1e-9),
    (1e-3, 1e9),
    (1e9, 1e-3),
    (1e-50, 1.0),
    (1.0, 1e-50),
]


@settings(max_examples=200, deadline=None)
@given(
    lengths=st.sampled_from(UNEQUAL),
    direction=st.floats(-np.pi, np.pi),
    depth=st.floats(0.0, 1.0),
    elbow=st.sampled_from(["down", "up", "both"]),
    batch=st.booleans(),
)
def test_closed_form_reaches_every_target_of_very_unequal_arms(
    lengths, direction, depth, elbow, batch
):
    """Links of 1e-9 and 1e9 m: the annulus is thinner than r^2's round-off; the closed form used to
    report failure with the opposite point (1 - cos q2 and 1 + cos q2 both rounded to 0)."""
    arm = TwoLinkArm(*lengths)
    r_min, r_max = arm.reach
    radius = r_min + depth * (r_max - r_min)
    target = radius * np.array([np.cos(direction), np.sin(direction)])
    result = ik.closed_form(arm, [target, target] if batch else target, elbow=elbow)
    assert np.all(result.success), result.message
    q = result.q.reshape(-1, 2)
    tips = arm.fk(q)
    assert np.all(np.hypot(*(tips - target).T) <= 1e-14 * r_max)
    assert np.allclose(
        np.ravel(result.residual),
        np.hypot(*(tips - target).T),
        rtol=0,
        atol=1e-14 * r_max,
    )


def test_the_unequal_arm_of_the_finding_is_solved_not_sent_to_the_opposite_point():
    arm = TwoLinkArm(1e-9, 1e9)
    result = ik.closed_form(arm, [1e9, 0.0])
    assert result.success and result.residual <= 1e-14 * sum(arm.reach)
    assert arm.fk(result.q)[0] > 0.0  # the opposite point was (-1e9, 0)


def test_assemble_result_judges_the_answers_by_forward_kinematics_when_built():
    p = np.array([[12.0, 9.0], [5.0, 12.0]])
    q = ik.closed_form(arms.ten, p).q.copy()
    q[1, 0] += 0.1  # a wrong answer: the solver's claim does not matter
    result = assemble_result(arms.ten, p, q, 0, 1e-9, "mine", "solved")
    assert result.residual[1] == pytest.approx(
        np.linalg.norm(arms.ten.fk(q[1]) - p[1]), abs=1e-15
    )
    assert result.residual[1] > 1.0 and not result.success[1] and not result.all_success
    assert result.message.startswith(
        "failed for 1 of 2 targets (first: flat index 1, residual"
    )
    one = assemble_result(
        arms.ten,
        p[1].tolist(),
        q[1],
        7,
        1e-9,
        "mine",
        "solved",
        lambda i, r: f"{r:.1f} m off",
    )
    assert (one.success, one.iterations, one.residual) == (False, 7, result.residual[1])
    assert (
        one.message.startswith("failed for 1 of 1 targets (first: flat index 0, ")
        and "m off" in one.message
    )


def test_a_result_keeps_its_own_targets():
    p = np.array([[12.0, 9.0], [5.0, 12.0]])
    for result in (
        ik.closed_form(arms.ten, p),
        ik.newton(arms.ten, p),
        ik.closed_form(arms.ten, p[0]),
    ):
        p[...] = 0.0  # the caller reuses its array before reading the fields
        assert result.all_success, result.message
        p[...] = [[12.0, 9.0], [5.0, 12.0]]


def test_an_unreachable_target_has_no_closed_form_result():
    with pytest.raises(
        UnreachableError, match=re.escape("target (30, 40) is 50 m from the base")
    ):
        ik.closed_form(arms.ten, [30.0, 40.0], elbow="auto")
    with pytest.raises(
        UnreachableError,
        match=re.escape("target (0, 25) (index (1,), first of 1) is 25 m"),
    ):
        ik.closed_form(arms.ten, [[10.0, 10.0], [0.0, 25.0]], elbow="both")


def test_ik_result_is_a_frozen_dataclass_and_not_an_array():
    result = ik.closed_form(arms.ten, [12.0, 9.0])
    assert dataclasses.is_dataclass(result)
    assert [field.name for field in dataclasses.fields(result)] == [
        "q",
        "success",
        "residual",
        "within_limits",
        "iterations",
        "method",
        "message",
    ]
    for field in (
        "q",
        "success",
        "iterations",
        "residual",
        "method",
        "message",
        "within_limits",
        "all_success",
    ):
        with pytest.raises(
            dataclasses.FrozenInstanceError, match=f"cannot assign to field '{field}'"
        ):
            setattr(result, field, 1.0)
        with pytest.raises(
            dataclasses.FrozenInstanceError, match=f"cannot delete field '{field}'"
        ):
            delattr(result, field)
    with pytest.raises(
        dataclasses.FrozenInstanceError, match="cannot assign to field 'anything'"
    ):
        result.anything = 1.0  # no new attributes either
    # every field was computed when the result was built: a plain dataclass holding values
    assert set(vars(result)) == {field.name for field in dataclasses.fields(result)}
    with pytest.raises(TypeError, match=r"use its \.q"):
        np.asarray(result)
    with pytest.raises(TypeError):
        down, up = ik.closed_form(
            arms.ten, [12.0, 9.0], elbow="both"
        )  # the branches are its .q


def test_ik_result_repr_names_the_method_and_the_outcome():
    one = repr(ik.closed_form(arms.ten, [12.0, 4.0]))
    assert (
        one.startswith("IKResult(method='closed-form', q=array([")
        and "success=True" in one
    )
    assert "within_limits=False" in one and "violate the joint limits" in one
    batch = repr(ik.newton(arms.ten, [[12.0, 9.0], [5.0, 12.0]]))
    assert "q of shape (2, 2), success 2 of 2" in batch and "max iterations" in batch


def test_ik_result_survives_pickling_and_copying():
    import copy
    import pickle

    for result in (
        ik.closed_form(arms.ten, [12.0, 4.0]),
        ik.newton(arms.ten, [[12.0, 9.0], [5.0, 12.0]]),
    ):
        for twin in (
            pickle.loads(pickle.dumps(result)),
            copy.deepcopy(result),
            copy.copy(result),
        ):
            assert (
                type(twin) is ik.IKResult
                and twin.method == result.method
                and twin.message == result.message
            )
            for field in ("q", "success", "iterations", "residual", "within_limits"):
                assert np.array_equal(getattr(twin, field), getattr(result, field)), (
                    field
                )
                assert type(getattr(twin, field)) is type(getattr(result, field)), field
    # pickled as a dataclass is: its class and its fields, nothing else (no callbacks, no arm)
    assert b"twolink.arm" not in pickle.dumps(ik.newton(arms.ten, [12.0, 9.0]))


def test_assemble_result_checks_its_shapes():
    made = assemble_result(
        arms.ten,
        np.array([[20.0, 0.0]]),
        np.array([[0.0, 0.0]]),
        [3],
        1e-9,
        "mine",
        "done",
    )
    assert (
        made.all_success and made.iterations.tolist() == [3] and made.message == "done"
    )
    with pytest.raises(ValueError, match="one answer per target"):
        assemble_result(
            arms.ten,
            np.array([[20.0, 0.0]]),
            np.array([[0.0, 0.0], [1.0, 0.0]]),
            0,
            1e-9,
            "mine",
            "done",
        )
    with pytest.raises(
        ValueError,
        match=re.escape("iterations must be one value or one per answer (1)"),
    ):
        assemble_result(
            arms.ten,
            np.array([20.0, 0.0]),
            np.array([0.0, 0.0]),
            [1, 2],
            1e-9,
            "mine",
            "done",
        )


FIELDS = ("success", "iterations", "residual", "within_limits", "message")


@settings(max_examples=60)
@given(
    arm=st.sampled_from([arms.ten, arms.two_metre, arms.two_metre_limited, arms.osake]),
    fractions=st.lists(st.tuples(unit, angles), min_size=1, max_size=4),
    one=st.booleans(),
    solver=st.sampled_from(
        ["closed_form", "closed_form both", "closed_form auto", "newton"]
    ),
    order=st.permutations(FIELDS),
)
def test_fields_are_judged_by_forward_kinematics(arm, fractions, one, solver, order):
    r_min, r_max = arm.reach
    p = np.array(
        [target_at(r_min + f * (r_max - r_min), heading) for f, heading in fractions]
    )
    p = p[0] if one else p
    result = SOLVERS[solver](arm, p.tolist() if one else p)
    read = {
        field: getattr(result, field) for field in order
    }  # in any order: plain values
    for field in FIELDS:
        assert getattr(result, field) is read[field]
    # forward kinematics of q, against the solver's documented threshold
    residual = np.hypot(*np.moveaxis(arm.fk(result.q) - p, -1, 0))
    if solver == "newton":
        threshold = 1e-12 * r_max + kinematics.distance_outside_reach(arm, p)
    else:
        threshold = ik.analytic.CLOSED_FORM_RTOL * r_max
    np.testing.assert_allclose(read["residual"], residual, rtol=0, atol=1e-15 * r_max)
    assert np.array_equal(read["success"], residual <= threshold)
    assert np.array_equal(read["within_limits"], arm.within_limits(result.q))
    shapes = {
        np.shape(read[field])
        for field in ("residual", "success", "iterations", "within_limits")
    }
    assert shapes == {result.q.shape[:-1]}
    # one target on floats gives what the same target in a batch of one gives
    if one:
        batch = SOLVERS[solver](arm, p[None, :])
        for field in ("success", "iterations", "within_limits"):
            assert np.array_equal(
                read[field], np.take(getattr(batch, field), 0, axis=-1)
            ), field
        assert read["message"] == batch.message
        np.testing.assert_allclose(
            read["residual"],
            np.take(batch.residual, 0, axis=-1),
            rtol=0,
            atol=1e-12 * r_max,
        )


# ---------------------------------------------------------------- the elbow words
@pytest.mark.parametrize("elbow", [None, "elbow-up", "Down", 1, ["down"]], ids=repr)
@pytest.mark.parametrize("p", [[10.0, 10.0], [[10.0, 10.0]]], ids=["one", "batch"])
def test_closed_form_names_the_elbow_words_it_accepts(elbow, p):
    with pytest.raises(
        ValueError,
        match=re.escape("elbow must be one of ('down', 'up', 'both', 'auto')"),
    ):
        ik.closed_form(arms.ten, p, elbow=elbow)


def test_auto_is_down_for_an_arm_without_limits():
    rng = np.random.default_rng(2)
    p = arms.two_metre.fk(rng.uniform(-np.pi, np.pi, (50, 2)))
    assert np.array_equal(
        ik.closed_form(arms.two_metre, p, elbow="auto").q,
        ik.closed_form(arms.two_metre, p).q,
    )
    for target in p[:5]:
        assert np.array_equal(
            ik.closed_form(arms.two_metre, target.tolist(), elbow="auto").q,
            ik.closed_form(arms.two_metre, target.tolist()).q,
        )


@pytest.mark.parametrize(
    "arm", [arms.ten, arms.two_metre_limited], ids=["ten", "two_metre_limited"]
)
def test_auto_picks_a_branch_within_the_limits_down_first(arm):
    from twolink import workspace

    rng = np.random.default_rng(4)
    r_max = arm.reach[1]
    p = rng.uniform(-r_max, r_max, (4000, 2))
    p = p[np.hypot(*p.T) <= r_max]
    auto = ik.closed_form(arm, p, elbow="auto")
    down, up = ik.closed_form(arm, p, elbow="both").q
    down_ok, up_ok = (
        arm.within_limits(down, tol=ik.LIMIT_TOL),
        arm.within_limits(up, tol=ik.LIMIT_TOL),
    )
    assert down_ok.sum() > 100 and (~down_ok & ~up_ok).sum() > 100
    # equal links with equal absolute limits: a branch and its mirror take the same two link angles
    assert (~down_ok & up_ok).sum() > 100 or arm is arms.two_metre_limited
    assert np.array_equal(
        auto.q[down_ok], down[down_ok]
    )  # down preferred (its angles exactly)
    assert np.array_equal(auto.q[~down_ok & up_ok], up[~down_ok & up_ok])
    assert np.array_equal(
        auto.q[~down_ok & ~up_ok], down[~down_ok & ~up_ok]
    )  # neither: down, and said so
    assert np.array_equal(arm.within_limits(auto.q, tol=ik.LIMIT_TOL), down_ok | up_ok)
    assert np.array_equal(down_ok | up_ok, workspace.is_reachable(arm, p))
    assert auto.all_success and np.all(auto.residual < 1e-12 * r_max)
    assert "with neither branch within them" in auto.message
    # one target at a time takes the same branch
    for index in np.flatnonzero(~down_ok & up_ok)[:5]:
        assert np.array_equal(
            ik.closed_form(arm, p[index].tolist(), elbow="auto").q, up[index]
        )


def test_auto_moves_angles_by_a_turn_into_limits_beyond_pi():
    arm = TwoLinkArm(
        1.0, 1.0, q_min=(np.pi / 2, 0.0), q_max=(1.75 * np.pi, np.pi)
    )  # q1 up to 315 deg
    p = arm.fk([1.5 * np.pi, 0.5])  # q1 = 270 deg: the closed form gives -90 deg
    auto = ik.closed_form(arm, p, elbow="auto")
    assert auto.within_limits and np.allclose(auto.q, [1.5 * np.pi, 0.5])
    assert not ik.closed_form(arm, p, elbow="down").within_limits


# ---------------------------------------------------------------- one target on floats, a batch on arrays
# The closed form and Newton evaluate one formula each (the cosine rule and its branches; the tip, the
# Jacobian and the damped step): with math for a pair of floats, with numpy for a batch.
ONE_ARM = TwoLinkArm(1.0, 0.7, m1=2.0, m2=1.2)
wide_angles = st.floats(-4.0, 4.0, allow_nan=False)
short_lengths = st.floats(0.05, 5.0, allow_nan=False)


def outcome(call):
    """What a call did: its value, or the type and message of what it raised."""
    try:
        return "value", call()
    except Exception as error:  # noqa: BLE001 - the point is to compare any refusal
        return "error", (type(error), str(error))


@pytest.mark.parametrize("bad", BAD_PAIRS, ids=repr)
def test_single_bad_target_is_refused_as_the_vectorised_path_refuses_it(bad):
    from twolink._validate import as_pairs

    for solve in (
        lambda p: ik.closed_form(ONE_ARM, p).q,
        lambda p: ik.newton(ONE_ARM, p).q,
    ):
        fast = outcome(lambda: solve(bad))
        slow = outcome(lambda: solve(as_pairs(bad, "target p")[None, :])[0])
        assert fast[0] == slow[0] == "error" and fast[1] == slow[1]


def test_single_bad_start_and_settings_of_newton_are_refused_as_before():
    with pytest.raises(ValueError, match="q0"):
        ik.newton(ONE_ARM, [1.0, 0.5], q0=[np.nan, 0.0])
    with pytest.raises(ValueError, match="tol"):
        ik.newton(ONE_ARM, [1.0, 0.5], tol=-1.0)
    with pytest.raises(ValueError, match="max_iter"):
        ik.newton(ONE_ARM, [1.0, 0.5], max_iter=0)


@pytest.mark.parametrize("tol", [1e308, 2.0, 0.5, ik.iterative.TOL_MAX * 1.01])
@pytest.mark.parametrize("p", [[1.0, 0.5], [[1.0, 0.5]]], ids=["one", "batch"])
def test_newton_refuses_a_tol_that_would_call_a_miss_success(tol, p):
    """tol = 1e308 reported success 2 m from the target: tol is bounded by what a miss can mean."""
    with pytest.raises(
        ValueError,
        match=r"tol = .* would count a tip up to .* m from the target as success",
    ) as raised:
        ik.newton(ONE_ARM, p, q0=(3.0, -2.0), tol=tol)
    assert "tol must be in (0, 0.01]" in str(raised.value) and "l1 + l2 = 1.7 m" in str(
        raised.value
    )
    assert ik.newton(
        ONE_ARM, p, tol=ik.iterative.TOL_MAX
    ).all_success  # the bound itself is allowed


@pytest.mark.parametrize("distance", [1.7 * (1 + 1e-9), 3.0, 0.3 * (1 - 1e-9), 0.0])
def test_single_unreachable_target_raises_the_vectorised_message(distance):
    target = [distance * np.cos(0.3), distance * np.sin(0.3)]
    with pytest.raises(UnreachableError) as expected:
        kinematics.require_within_reach(ONE_ARM, np.array(target))
    for solve in (ik.closed_form, ik.newton):
        with pytest.raises(UnreachableError) as raised:
            solve(ONE_ARM, target)
        assert str(raised.value) == str(expected.value)


def boundary_targets(l1, l2, angle):
    """Targets at full stretch and full fold, just inside, on, and just outside within REACH_RTOL."""
    r_min, r_max = abs(l1 - l2), l1 + l2
    radii = [
        r_max,
        r_max * (1 - 1e-13),
        r_max * (1 + 0.5 * kinematics.REACH_RTOL),
        r_min,
        r_min * (1 + 1e-13),
    ]
    radii += (
        [r_min - 0.5 * kinematics.REACH_RTOL * r_max]
        if r_min > kinematics.REACH_RTOL * r_max
        else []
    )
    return [[radius * np.cos(angle), radius * np.sin(angle)] for radius in radii]


@settings(max_examples=200, deadline=None)
@given(
    short_lengths, short_lengths, wide_angles, wide_angles, st.sampled_from(ELBOW_WORDS)
)
def test_closed_form_paths_agree_inside_and_on_the_reach_boundary(
    l1, l2, q1, q2, elbow
):
    arm = TwoLinkArm(l1, l2)
    targets = [arm.fk([q1, q2]).tolist()] + boundary_targets(l1, l2, q1)
    for target in targets:
        fast = ik.closed_form(arm, target, elbow=elbow)
        slow = ik.closed_form(arm, np.array([target]), elbow=elbow)
        assert fast.q.shape == np.take(slow.q, 0, axis=-2).shape
        np.testing.assert_allclose(
            fast.q, np.take(slow.q, 0, axis=-2), rtol=0, atol=1e-12
        )
        assert (
            np.array_equal(fast.success, np.take(slow.success, 0, axis=-1))
            and fast.message == slow.message
        )


@settings(max_examples=150, deadline=None)
@given(short_lengths, short_lengths, wide_angles, wide_angles, wide_angles, wide_angles)
def test_newton_paths_agree(l1, l2, q1, q2, start1, start2):
    arm = TwoLinkArm(l1, l2)
    target = arm.fk([q1, q2]).tolist()
    fast = ik.newton(arm, target, q0=(start1, start2))
    slow = ik.newton(arm, np.array([target]), q0=(start1, start2))
    assert (
        fast.q.shape == (2,)
        and type(fast.success) is bool
        and type(fast.iterations) is int
    )
    assert type(fast.residual) is float and type(fast.within_limits) is bool
    assert fast.method == slow.method == "newton"
    assert fast.success == bool(slow.success[0])
    assert fast.within_limits == bool(slow.within_limits[0])
    if fast.success:
        scale = l1 + l2
        assert fast.residual <= 1e-12 * scale and slow.residual[0] <= 1e-12 * scale
        # The same iteration on numbers that differ in the last bits (math vs numpy trig): both stop
        # within 1e-12 (l1 + l2) of the target, so the answers differ by at most that over the
        # smallest singular value of J (to first order): 1e-12 in a well-conditioned pose.
        sigma_min = np.linalg.svd(arm.jacobian(slow.q[0]), compute_uv=False)[-1]
        bound = 1e-12 + 2e-12 * scale / max(
            sigma_min, 1e-300
        )  # no bound at an exactly singular answer
        difference = np.abs(wrap_angle(fast.q - slow.q[0]))
        assert np.all(difference <= bound), (difference, bound)
        if sigma_min > 0.1 * scale:
            np.testing.assert_allclose(fast.q, slow.q[0], rtol=0, atol=1e-12)


@pytest.mark.parametrize(
    "arm, target, q0",
    [
        (arms.two_metre, [4.0, 0.0], (0.3, 0.2)),  # full stretch
        (arms.two_metre, [4.0, 0.0], (0.0, 0.0)),  # starts at the solution
        (
            arms.two_metre,
            [3.0, 0.0],
            (0.0, 0.0),
        ),  # zero gradient: stalls, success false
        (
            TwoLinkArm(1.0, 1.0),
            [0.0, 0.0],
            (0.5, 1.0),
        ),  # the base of an equal-link arm (folded)
        (TwoLinkArm(1.0, 0.5), [0.5 * (1 + 1e-13), 0.0], (0.5, 2.0)),  # full fold
        (arms.ten, [10.0, 10.0], (0.5, 1.0)),  # joint limits
        (arms.ten, [-5.0, 12.0], (0.5, 1.0)),  # an answer outside the joint limits
    ],
)
def test_newton_paths_agree_at_singular_and_limited_poses(arm, target, q0):
    fast = ik.newton(arm, target, q0=q0)
    slow = ik.newton(arm, np.array([target]), q0=q0)
    assert fast.success == bool(slow.success[0])
    assert fast.iterations == int(slow.iterations[0])
    np.testing.assert_allclose(fast.q, slow.q[0], rtol=0, atol=1e-12)
    np.testing.assert_allclose(fast.residual, slow.residual[0], rtol=0, atol=1e-12)
    assert fast.within_limits == bool(slow.within_limits[0])
    assert fast.message == slow.message


def test_newton_stalls_honestly_at_a_zero_gradient_on_the_float_path():
    result = ik.newton(arms.two_metre, [3.0, 0.0], q0=(0.0, 0.0))
    assert not result.success
    assert "did not converge" in result.message


@settings(max_examples=200, deadline=None)
@given(
    st.floats(1e-3, 10.0),
    st.floats(1e-3, 10.0),
    st.floats(-1.0, 1.0),
    st.floats(-1.0, 1.0),
    st.floats(1e-12, 10.0),
    wide_angles,
)
def test_lm_step_formula_solves_the_damped_normal_equations(
    l1, l2, rx, ry, damping, q1
):
    """The adjugate solve of (J^T J + lam I) dq = -J^T r equals numpy's solve, floats and arrays alike."""
    for q2 in (0.0, 1e-9, 0.7, np.pi):  # singular poses included
        J = TwoLinkArm(l1, l2).jacobian([q1, q2])
        normal = J.T @ J + damping * np.eye(2)
        expected = np.linalg.solve(normal, -(J.T @ [rx, ry]))
        det_j = l1 * l2 * np.sin(q2)
        step = _lm_step(*J.ravel().tolist(), float(det_j), rx, ry, damping)
        # round-off of the adjugate's products: the size of its terms, |J^T J + lam I| |J^T r| / det(J^T J + lam I)
        # (plus 1e-250: a step below 1e-262 rad, whose products underflow, counts as zero)
        scale = (
            np.linalg.norm(normal)
            * np.linalg.norm(J.T @ [rx, ry])
            / np.linalg.det(normal)
            + 1e-250
        )
        assert np.allclose(
            step, expected, rtol=1e-8 * np.linalg.cond(normal), atol=1e-12 * scale
        )
        arrays = _lm_step(
            *(np.full(3, value) for value in (*J.ravel(), det_j, rx, ry, damping))
        )
        assert np.array_equal(arrays[0], np.full(3, step[0])) and np.array_equal(
            arrays[1], np.full(3, step[1])
        )


@given(wide_angles, wide_angles)
@settings(max_examples=50, deadline=None)
def test_a_results_arrays_are_its_own(q1, q2):
    result = ik.newton(ONE_ARM, ONE_ARM.fk([q1, q2]).tolist())
    result.q[0] = 5.0
    assert ik.newton(ONE_ARM, ONE_ARM.fk([q1, q2]).tolist()).q[0] != 5.0


def test_a_result_compares_by_value_pickles_and_refuses_a_hash_saying_why():
    result = ik.closed_form(ONE_ARM, [[1.2, 0.3], [0.5, 1.1]], elbow="both")
    again = ik.closed_form(ONE_ARM, [[1.2, 0.3], [0.5, 1.1]], elbow="both")
    assert result == again and result == pickle.loads(pickle.dumps(result))
    assert result != ik.closed_form(ONE_ARM, [[1.2, 0.3], [0.5, 1.0]], elbow="both")
    with pytest.raises(TypeError, match="an IKResult has no hash: its arrays"):
        hash(result)


@pytest.mark.parametrize("not_an_arm", [None, 3.0, "arm"], ids=repr)
def test_single_target_with_something_that_is_not_an_arm_is_refused_as_in_a_batch(
    not_an_arm,
):
    for call in (
        lambda p: ik.closed_form(not_an_arm, p),
        lambda p: ik.newton(not_an_arm, p),
    ):
        fast, slow = (
            outcome(lambda: call([0.3, 0.4])),
            outcome(lambda: call(np.array([[0.3, 0.4]]))),
        )
        assert fast[0] == slow[0] == "error"
        assert fast[1] == slow[1]
        assert "arm" in fast[1][1]


# --------------------------------------------------------------------- honest results
LIMITED = TwoLinkArm(1.0, 1.0, q_min=(0.0, 0.0), q_max=(np.pi / 2, np.pi / 2))


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


# -------------------------------------------------------------- empty and odd batches
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


@pytest.mark.parametrize("solve", [ik.newton, ik.minimize], ids=["newton", "minimize"])
def test_a_start_of_the_wrong_shape_names_both_shapes(solve):
    with pytest.raises(
        ValueError,
        match=r"q0 of shape \(3, 2\) does not match target p of shape \(2, 2\)",
    ):
        solve(arms.ten, [[10.0, 10.0], [5.0, 12.0]], q0=np.full((3, 2), 0.5))


# ------------------------------------------------------- grid and optimiser arguments
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


def test_a_grid_beyond_the_memory_budget_is_refused_up_front_naming_points_and_limit():
    with pytest.raises(
        ValueError, match=r"would hold .* points, more than MAX_AXIS_POINTS"
    ):
        ik.brute_force(arms.two_metre, [3.0, 1.0], step=1e-12)
    with pytest.raises(
        ValueError,
        match=r"grid of \d+ x \d+ = .* points per target, more than MAX_GRID_POINTS",
    ):
        ik.brute_force(arms.two_metre, [3.0, 1.0], step=1e-4)


@pytest.mark.parametrize("convention", ["relative", "absolute"])
@given(q1=angles, q2=st.floats(0.1, 3.0))
@settings(max_examples=30, deadline=None)
def test_brute_force_finds_joint_limits_that_are_a_single_angle(convention, q1, q2):
    """Limits of one angle each hold no point of a grid of q2 for absolute limits
    (link 2's absolute angle q1 + q2 falls between its grid values): link 2 is tried along them."""
    relative = np.array([q1, q2])
    limits = relative if convention == "relative" else np.array([q1, q1 + q2])
    arm = TwoLinkArm(1.0, 0.7, q_min=limits, q_max=limits, limit_convention=convention)
    result = ik.brute_force(arm, arm.fk(relative))
    assert result.success and result.within_limits
    assert np.allclose(wrap_angle(result.q - relative), 0.0, atol=1e-9)


def test_minimize_constrained_with_limits_that_fix_every_joint():
    """scipy fixes both joints and runs no iteration (its result has no ``nit``: it was an AttributeError)."""
    arm = TwoLinkArm(1.0, 1.0, q_min=(0.3, 0.5), q_max=(0.3, 0.5))
    result = ik.minimize(arm, arm.fk([0.3, 0.5]), constrained=True)
    assert result.success and np.array_equal(result.q, [0.3, 0.5])
    assert result.iterations == 0
    missed = ik.minimize(arm, [1.0, 1.0], constrained=True)
    assert not missed.success and "fixed by bounds" in missed.message
