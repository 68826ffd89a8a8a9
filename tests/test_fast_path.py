"""One input at a time: the lean float path agrees with the vectorised path.

Every public function that takes one configuration, target or state (shape
``(2,)``) reads plain pairs of numbers on Python floats (issue 13).  These
tests hold the two paths to the same answers (to 1e-12, at the reach
boundary and at singular poses too) and the same refusals (a bad single
input raises exactly what the vectorised checks raise).
"""

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from twolink import TwoLinkArm, arms, dynamics, ik, kinematics, wrap_angle
from twolink.conventions import ELBOW_WORDS
from twolink._validate import as_pairs, pair_floats
from twolink.errors import UnreachableError
from twolink.ik.iterative import _lm_step

angles = st.floats(-4.0, 4.0, allow_nan=False)
rates = st.floats(-5.0, 5.0, allow_nan=False)
lengths = st.floats(0.05, 5.0, allow_nan=False)
ARM = TwoLinkArm(1.0, 0.7, m1=2.0, m2=1.2)


def batch(function, *pairs, **options):
    """``function`` on the pairs as batches of one (the vectorised path), first row."""
    return function(*(np.asarray(pair, dtype=float)[None, :] for pair in pairs), **options)


# ---------------------------------------------------------------- which inputs take the fast path
@pytest.mark.parametrize(
    "value, expected",
    [
        ([1.0, 2.0], (1.0, 2.0)),
        ((1, 2), (1.0, 2.0)),
        ([np.float64(0.5), np.float32(0.25)], (0.5, 0.25)),
        ([np.int64(3), 4], (3.0, 4.0)),
        (np.array([0.5, -1.5]), (0.5, -1.5)),
    ],
)
def test_pair_floats_reads_plain_pairs(value, expected):
    pair = pair_floats(value)
    assert pair == expected
    assert all(type(number) is float for number in pair)


@pytest.mark.parametrize(
    "value",
    [
        [True, 1.0],
        [1.0, np.bool_(False)],
        [1 + 2j, 0.0],
        [None, 1.0],
        ["1", 2.0],
        [float("nan"), 1.0],
        [1.0, float("inf")],
        [10**400, 1.0],
        [1.0, 2.0, 3.0],
        [[1.0, 2.0]],
        np.array([1.0, 2.0], dtype=np.float32),
        np.array([[1.0, 2.0]]),
        np.array([1, 2]),
        "12",
        None,
        3.0,
    ],
)
def test_pair_floats_leaves_everything_else_to_the_vectorised_checks(value):
    assert pair_floats(value) is None


def outcome(call):
    """What a call did: its value, or the type and message of what it raised."""
    try:
        return "value", call()
    except Exception as error:  # noqa: BLE001 - the point is to compare any refusal
        return "error", (type(error), str(error))


def assert_same_outcome(fast, slow):
    kind_fast, fast_value = fast
    kind_slow, slow_value = slow
    assert kind_fast == kind_slow, (fast_value, slow_value)
    if kind_fast == "error":
        assert fast_value == slow_value
    else:
        np.testing.assert_allclose(fast_value, slow_value, rtol=0, atol=1e-12)


BAD_PAIRS = [
    [float("nan"), 1.0],
    [0.0, float("inf")],
    ["a", 1.0],
    [None, 1.0],
    [1 + 2j, 0.0],
    [1.0, 2.0, 3.0],
    [],
    [True, False],
    [10**400, 0.0],
    np.array([np.nan, 1.0]),
]


@pytest.mark.parametrize("bad", BAD_PAIRS, ids=repr)
def test_single_bad_input_is_refused_as_the_vectorised_path_refuses_it(bad):
    """The fast path refuses nothing itself: anything it does not read is checked by as_pairs."""

    def slow(function, name):
        def call():
            return function(as_pairs(bad, name)[None, :])[0]

        return call

    assert_same_outcome(outcome(lambda: kinematics.fk(ARM, bad)), outcome(slow(lambda q: kinematics.fk(ARM, q), "q")))
    assert_same_outcome(outcome(lambda: ARM.jacobian(bad)), outcome(slow(ARM.jacobian, "q")))
    assert_same_outcome(
        outcome(lambda: ik.closed_form(ARM, bad).q), outcome(slow(lambda p: ik.closed_form(ARM, p).q, "target p"))
    )
    assert_same_outcome(
        outcome(lambda: ik.newton(ARM, bad).q), outcome(slow(lambda p: ik.newton(ARM, p).q, "target p"))
    )
    assert_same_outcome(
        outcome(lambda: dynamics.forward_dynamics(ARM, bad, [0.0, 0.0], [0.0, 0.0])),
        outcome(slow(lambda q: dynamics.forward_dynamics(ARM, q, np.zeros((1, 2)), np.zeros((1, 2))), "q")),
    )
    assert_same_outcome(
        outcome(lambda: dynamics.inverse_dynamics(ARM, [0.0, 0.0], [0.0, 0.0], bad)),
        outcome(slow(lambda qdd: dynamics.inverse_dynamics(ARM, np.zeros((1, 2)), np.zeros((1, 2)), qdd), "qdd")),
    )


def test_single_bad_start_and_settings_of_newton_are_refused_as_before():
    with pytest.raises(ValueError, match="q0"):
        ik.newton(ARM, [1.0, 0.5], q0=[np.nan, 0.0])
    with pytest.raises(ValueError, match="tol"):
        ik.newton(ARM, [1.0, 0.5], tol=-1.0)
    with pytest.raises(ValueError, match="max_iter"):
        ik.newton(ARM, [1.0, 0.5], max_iter=0)


@pytest.mark.parametrize("distance", [1.7 * (1 + 1e-9), 3.0, 0.3 * (1 - 1e-9), 0.0])
def test_single_unreachable_target_raises_the_vectorised_message(distance):
    target = [distance * math.cos(0.3), distance * math.sin(0.3)]
    with pytest.raises(UnreachableError) as expected:
        kinematics.require_within_reach(ARM, np.array(target))
    for solve in (ik.closed_form, ik.newton):
        with pytest.raises(UnreachableError) as raised:
            solve(ARM, target)
        assert str(raised.value) == str(expected.value)


# ---------------------------------------------------------------- same answers
@settings(max_examples=200, deadline=None)
@given(lengths, lengths, angles, angles)
def test_fk_and_jacobian_paths_agree(l1, l2, q1, q2):
    arm = TwoLinkArm(l1, l2)
    for q in ([q1, q2], (q1, q2), np.array([q1, q2])):
        np.testing.assert_allclose(arm.fk(q), batch(arm.fk, [q1, q2])[0], rtol=0, atol=1e-12)
        np.testing.assert_allclose(arm.jacobian(q), batch(arm.jacobian, [q1, q2])[0], rtol=0, atol=1e-12)
    assert arm.fk([q1, q2]).shape == (2,) and arm.jacobian([q1, q2]).shape == (2, 2)


def boundary_targets(l1, l2, angle):
    """Targets at full stretch and full fold, just inside, on, and just outside within REACH_RTOL."""
    r_min, r_max = abs(l1 - l2), l1 + l2
    radii = [r_max, r_max * (1 - 1e-13), r_max * (1 + 0.5 * kinematics.REACH_RTOL), r_min, r_min * (1 + 1e-13)]
    radii += [r_min - 0.5 * kinematics.REACH_RTOL * r_max] if r_min > kinematics.REACH_RTOL * r_max else []
    return [[radius * math.cos(angle), radius * math.sin(angle)] for radius in radii]


@settings(max_examples=200, deadline=None)
@given(lengths, lengths, angles, angles, st.sampled_from(ELBOW_WORDS))
def test_closed_form_paths_agree_inside_and_on_the_reach_boundary(l1, l2, q1, q2, elbow):
    arm = TwoLinkArm(l1, l2)
    targets = [arm.fk([q1, q2]).tolist()] + boundary_targets(l1, l2, q1)
    for target in targets:
        fast = ik.closed_form(arm, target, elbow=elbow).q
        slow = np.take(ik.closed_form(arm, np.array([target]), elbow=elbow).q, 0, axis=-2)
        assert fast.shape == slow.shape
        np.testing.assert_allclose(fast, slow, rtol=0, atol=1e-12)


@settings(max_examples=150, deadline=None)
@given(lengths, lengths, angles, angles, angles, angles)
def test_newton_paths_agree(l1, l2, q1, q2, start1, start2):
    arm = TwoLinkArm(l1, l2)
    target = arm.fk([q1, q2]).tolist()
    fast = ik.newton(arm, target, q0=(start1, start2))
    slow = ik.newton(arm, np.array([target]), q0=(start1, start2))
    assert fast.q.shape == (2,) and fast.success.shape == fast.iterations.shape == fast.residual.shape == ()
    assert fast.method == slow.method == "newton"
    assert bool(fast.success) == bool(slow.success[0])
    assert bool(fast.within_limits) == bool(slow.within_limits[0])
    if fast.success:
        scale = l1 + l2
        assert fast.residual <= 1e-12 * scale and slow.residual[0] <= 1e-12 * scale
        # The same iteration on numbers that differ in the last bits (math vs numpy trig): both stop
        # within 1e-12 (l1 + l2) of the target, so the answers differ by at most that over the
        # smallest singular value of J (to first order): 1e-12 in a well-conditioned pose.
        sigma_min = np.linalg.svd(arm.jacobian(slow.q[0]), compute_uv=False)[-1]
        bound = 1e-12 + 2e-12 * scale / max(sigma_min, 1e-300)  # no bound at an exactly singular answer
        difference = np.abs(wrap_angle(fast.q - slow.q[0]))
        assert np.all(difference <= bound), (difference, bound)
        if sigma_min > 0.1 * scale:
            np.testing.assert_allclose(fast.q, slow.q[0], rtol=0, atol=1e-12)


@pytest.mark.parametrize(
    "arm, target, q0",
    [
        (arms.two_metre, [4.0, 0.0], (0.3, 0.2)),  # full stretch
        (arms.two_metre, [4.0, 0.0], (0.0, 0.0)),  # starts at the solution
        (arms.two_metre, [3.0, 0.0], (0.0, 0.0)),  # zero gradient: stalls, success false
        (TwoLinkArm(1.0, 1.0), [0.0, 0.0], (0.5, 1.0)),  # the base of an equal-link arm (folded)
        (TwoLinkArm(1.0, 0.5), [0.5 * (1 + 1e-13), 0.0], (0.5, 2.0)),  # full fold
        (arms.ten, [10.0, 10.0], (0.5, 1.0)),  # joint limits
        (arms.ten, [-5.0, 12.0], (0.5, 1.0)),  # an answer outside the joint limits
    ],
)
def test_newton_paths_agree_at_singular_and_limited_poses(arm, target, q0):
    fast = ik.newton(arm, target, q0=q0)
    slow = ik.newton(arm, np.array([target]), q0=q0)
    assert bool(fast.success) == bool(slow.success[0])
    assert int(fast.iterations) == int(slow.iterations[0])
    np.testing.assert_allclose(fast.q, slow.q[0], rtol=0, atol=1e-12)
    np.testing.assert_allclose(fast.residual, slow.residual[0], rtol=0, atol=1e-12)
    assert bool(fast.within_limits) == bool(slow.within_limits[0])
    assert fast.message == slow.message


def test_newton_stalls_honestly_at_a_zero_gradient_on_the_fast_path():
    result = ik.newton(arms.two_metre, [3.0, 0.0], q0=(0.0, 0.0))
    assert not result.success
    assert "did not converge" in result.message


@settings(max_examples=200, deadline=None)
@given(
    st.floats(-1.0, 1.0), st.floats(-1.0, 1.0), st.floats(1e-3, 10.0), st.floats(1e-3, 10.0),
    st.floats(-1.0, 1.0), st.floats(-1.0, 1.0), st.floats(1e-12, 10.0), angles,
)
def test_lm_step_formula_solves_the_damped_normal_equations(c_dummy, s_dummy, l1, l2, rx, ry, damping, q1):
    """The adjugate solve of (J^T J + lam I) dq = -J^T r equals numpy's solve, floats and arrays alike."""
    for q2 in (0.0, 1e-9, 0.7, math.pi):  # singular poses included
        J = TwoLinkArm(l1, l2).jacobian([q1, q2])
        normal = J.T @ J + damping * np.eye(2)
        expected = np.linalg.solve(normal, -(J.T @ [rx, ry]))
        trig = (math.cos(q1), math.sin(q1), math.cos(q1 + q2), math.sin(q1 + q2), math.sin(q2))
        step = _lm_step(l1, l2, *trig, rx, ry, damping)
        scale = np.linalg.norm(expected) + 1e-300
        assert np.allclose(step, expected, rtol=1e-8 * np.linalg.cond(normal), atol=1e-12 * scale)
        arrays = _lm_step(l1, l2, *(np.full(3, value) for value in trig), np.full(3, rx), np.full(3, ry), np.full(3, damping))
        assert np.array_equal(arrays[0], np.full(3, step[0])) and np.array_equal(arrays[1], np.full(3, step[1]))


@settings(max_examples=200, deadline=None)
@given(angles, angles, rates, rates, rates, rates, st.sampled_from([ARM, arms.two_metre, TwoLinkArm(1e-3, 2.0, m1=0.1)]))
def test_dynamics_paths_agree(q1, q2, qd1, qd2, u1, u2, arm):
    q, qd, u = [q1, q2], [qd1, qd2], [u1, u2]
    fast = dynamics.forward_dynamics(arm, q, qd, u)
    slow = batch(lambda *a: dynamics.forward_dynamics(arm, *a), q, qd, u)[0]
    np.testing.assert_allclose(fast, slow, rtol=1e-12, atol=1e-12)
    fast = dynamics.inverse_dynamics(arm, q, qd, u)
    slow = batch(lambda *a: dynamics.inverse_dynamics(arm, *a), q, qd, u)[0]
    np.testing.assert_allclose(fast, slow, rtol=1e-12, atol=1e-12)
    assert arm.forward_dynamics(tuple(q), np.array(qd), u).shape == (2,)


def test_dynamics_constants_are_cached_per_arm_and_follow_replace():
    import dataclasses

    arm = TwoLinkArm(1.0, 1.0, m1=1.0, m2=1.0)
    heavier = dataclasses.replace(arm, m2=5.0)
    q, qd, tau = [0.3, 0.4], [0.0, 0.0], [0.0, 0.0]
    assert not np.allclose(arm.forward_dynamics(q, qd, tau), heavier.forward_dynamics(q, qd, tau))
    np.testing.assert_allclose(
        heavier.forward_dynamics(q, qd, tau), TwoLinkArm(1.0, 1.0, m1=1.0, m2=5.0).forward_dynamics(q, qd, tau)
    )
    assert arm == TwoLinkArm(1.0, 1.0, m1=1.0, m2=1.0) and hash(arm) == hash(TwoLinkArm(1.0, 1.0, m1=1.0, m2=1.0))


@settings(max_examples=200, deadline=None)
@given(angles, angles, st.sampled_from(["relative", "absolute"]))
def test_within_limits_paths_agree(q1, q2, convention):
    arm = TwoLinkArm(1.0, 1.0, q_min=(-1.0, -2.0), q_max=(1.5, 2.5), limit_convention=convention)
    assert bool(arm.within_limits([q1, q2])) == bool(arm.within_limits(np.array([[q1, q2]]))[0])
    assert bool(TwoLinkArm(1.0, 1.0).within_limits([q1, q2]))
    # a configuration exactly on a limit counts as inside on both paths
    on_limit = [1.5, 2.5 - 1.5] if convention == "absolute" else [1.5, 2.5]
    assert bool(arm.within_limits(on_limit)) and bool(arm.within_limits(np.array([on_limit]))[0])


def test_duck_typed_arm_still_works_on_the_fast_path():
    class Bare:
        l1, l2 = 2.0, 1.0

    np.testing.assert_allclose(kinematics.fk(Bare(), [0.0, math.pi / 2]), [2.0, 1.0], atol=1e-12)
    np.testing.assert_allclose(kinematics.jacobian(Bare(), [0.0, 0.0]), [[0.0, 0.0], [3.0, 1.0]], atol=1e-12)


@given(angles, angles)
@settings(max_examples=50, deadline=None)
def test_fast_path_results_are_fresh_writable_arrays(q1, q2):
    p_tip = ARM.fk([q1, q2])
    assume(np.all(np.isfinite(p_tip)))
    p_tip[0] = 99.0
    assert ARM.fk([q1, q2])[0] != 99.0
    result = ik.newton(ARM, ARM.fk([q1, q2]).tolist())
    result.q[0] = 5.0  # the arrays of a result are its own
    assert ik.newton(ARM, ARM.fk([q1, q2]).tolist()).q[0] != 5.0


@pytest.mark.parametrize("not_an_arm", [None, 3.0, "arm"], ids=repr)
def test_single_input_with_something_that_is_not_an_arm_is_refused_as_in_a_batch(not_an_arm):
    one, batch_of_one = [0.3, 0.4], np.array([[0.3, 0.4]])
    calls = [
        lambda q: kinematics.fk(not_an_arm, q),
        lambda q: kinematics.jacobian(not_an_arm, q),
        lambda p: ik.closed_form(not_an_arm, p),
        lambda p: ik.newton(not_an_arm, p),
        lambda q: dynamics.forward_dynamics(not_an_arm, q, q, q),
        lambda q: dynamics.inverse_dynamics(not_an_arm, q, q, q),
    ]
    for call in calls:
        fast, slow = outcome(lambda: call(one)), outcome(lambda: call(batch_of_one))
        assert fast[0] == slow[0] == "error"
        assert fast[1] == slow[1]
        assert "arm" in fast[1][1]


@pytest.mark.parametrize("tol", [-1e-3, float("nan"), "0.1", None], ids=repr)
def test_within_limits_checks_its_tolerance_on_the_fast_path(tol):
    fast = outcome(lambda: arms.ten.within_limits([0.1, 0.2], tol=tol))
    slow = outcome(lambda: arms.ten.within_limits(np.array([[0.1, 0.2]]), tol=tol))
    assert fast[0] == slow[0] == "error" and fast[1] == slow[1]


@pytest.mark.parametrize("rates", [[1e200, 1e200], [1e155, -1e155], [3e153, 0.0]], ids=repr)
def test_overflowing_single_state_is_refused_as_in_a_batch(rates):
    """Finite inputs whose dynamics overflow float64: the same OverflowError (or the same finite answer)."""
    for call in (
        lambda q, qd: dynamics.forward_dynamics(ARM, q, qd, np.zeros_like(q)),
        lambda q, qd: dynamics.inverse_dynamics(ARM, q, qd, np.zeros_like(q)),
    ):
        fast = outcome(lambda: call([0.3, 0.4], rates))
        slow = outcome(lambda: call(np.array([[0.3, 0.4]]), np.array([rates]))[0])
        assert fast[0] == slow[0]
        if fast[0] == "error":  # the messages differ only in the index of the overflowing entry
            assert fast[1][0] is slow[1][0] is OverflowError
        else:
            assert_same_outcome(fast, slow)
