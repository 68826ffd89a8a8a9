"""Forward kinematics, DH transforms, Jacobians, statics and conventions."""

import functools

import numpy as np
import pytest
from _cases import BAD_PAIRS
from hypothesis import given, settings
from hypothesis import strategies as st

from conftest import arms as arm_strategy
from conftest import configurations
from twolink import (
    TwoLinkArm,
    UnreachableError,
    arms,
    kinematics,
)
from twolink._validate import as_pairs, pair_floats


@given(arm=arm_strategy(), q=configurations())
def test_fk_matches_the_textbook_formula(arm, q):
    q1, q2 = q
    expected = [
        arm.l1 * np.cos(q1) + arm.l2 * np.cos(q1 + q2),
        arm.l1 * np.sin(q1) + arm.l2 * np.sin(q1 + q2),
    ]
    assert np.allclose(arm.fk(q), expected, atol=1e-12 * (arm.l1 + arm.l2))


@given(arm=arm_strategy(), q=configurations())
def test_jacobian_matches_central_finite_differences(arm, q):
    h = 1e-6
    J_fd = np.empty((2, 2))
    for joint in range(2):
        dq = np.zeros(2)
        dq[joint] = h
        J_fd[:, joint] = (arm.fk(q + dq) - arm.fk(q - dq)) / (2 * h)
    assert np.allclose(arm.jacobian(q), J_fd, atol=1e-8 * (arm.l1 + arm.l2))


@given(arm=arm_strategy(), q=configurations())
def test_jacobian_determinant_is_l1_l2_sin_q2(arm, q):
    assert np.linalg.det(arm.jacobian(q)) == pytest.approx(
        arm.l1 * arm.l2 * np.sin(q[1]), abs=1e-9 * (arm.l1 + arm.l2) ** 2
    )


def test_vectorised_shapes_agree_with_single_calls():
    rng = np.random.default_rng(1)
    q = rng.uniform(-np.pi, np.pi, (3, 4, 2))
    arm = arms.osake
    assert arm.fk(q).shape == (3, 4, 2)
    assert arm.jacobian(q).shape == (3, 4, 2, 2)
    assert arm.joint_positions(q).shape == (3, 4, 3, 2)
    assert arm.geometric_jacobian(q).shape == (3, 4, 6, 2)
    assert arm.transforms(q)[1].shape == (3, 4, 4, 4)
    assert np.allclose(arm.fk(q)[2, 1], arm.fk(q[2, 1]))
    assert np.allclose(arm.jacobian(q)[0, 3], arm.jacobian(q[0, 3]))
    assert np.allclose(arm.joint_positions(q)[..., 2, :], arm.fk(q))


@given(
    arm=arm_strategy(), q=configurations(), qd=configurations(), force=configurations()
)
def test_joint_torques_power_balance(arm, q, qd, force):
    """Virtual work: tau . qd equals F . v for the tip velocity v = J qd."""
    tau = arm.joint_torques(q, force)
    v_tip = arm.jacobian(q) @ qd
    assert tau @ qd == pytest.approx(force @ v_tip, abs=1e-9 * (arm.l1 + arm.l2) * 10)


@pytest.mark.parametrize(
    "bad", [[1.0, 2.0, 3.0], [[1.0], [2.0]], 1.0, [np.nan, 0.0], [0.0, np.inf], "ab"]
)
def test_bad_configurations_raise(bad):
    arm = TwoLinkArm(1.0, 1.0)
    for method in (
        arm.fk,
        arm.jacobian,
        arm.joint_positions,
        arm.transforms,
        arm.geometric_jacobian,
    ):
        with pytest.raises(ValueError, match="q must"):
            method(bad)


def test_bad_force_raises():
    with pytest.raises(ValueError, match="force_by_tip must be finite"):
        arms.two_metre.joint_torques([0.0, 1.0], [np.nan, 1.0])


# ----------------------------------------------------------------- J^T F and the derivatives of J
@functools.cache
def symbolic_jacobian_derivative():
    """dJ/dq from sympy (planar_fk's tip differentiated twice), as a function of (q1, q2, l1, l2);
    derived when a test first asks, not when each worker imports this file."""
    import sympy as sp

    from twolink.symbolic import planar_fk, planar_symbols

    s = planar_symbols()
    q = [s["q1"], s["q2"]]
    J = planar_fk()[3].jacobian(q)
    dJ = [
        [[sp.diff(J[i, j], q[k]) for k in range(2)] for j in range(2)] for i in range(2)
    ]
    return sp.lambdify((s["q1"], s["q2"], s["l1"], s["l2"]), dJ, "numpy")


@given(arm=arm_strategy(), q=configurations())
def test_jacobian_derivative_is_sympys_derivative_of_the_jacobian(arm, q):
    expected = np.array(
        symbolic_jacobian_derivative()(q[0], q[1], arm.l1, arm.l2), dtype=float
    )
    assert np.allclose(
        kinematics.jacobian_derivative(arm, q),
        expected,
        rtol=0.0,
        atol=1e-12 * (arm.l1 + arm.l2),
    )


@given(arm=arm_strategy(), q=configurations())
def test_jacobian_derivative_matches_finite_differences_of_the_jacobian(arm, q):
    step = 1e-6
    columns = [
        (arm.jacobian(q + step * e) - arm.jacobian(q - step * e)) / (2 * step)
        for e in np.eye(2)
    ]
    by_differences = np.stack(
        columns, axis=-1
    )  # index k (the joint differentiated by) last
    dJ = kinematics.jacobian_derivative(arm, q)
    assert np.allclose(dJ, by_differences, rtol=0.0, atol=1e-8 * (arm.l1 + arm.l2))
    assert np.array_equal(dJ, np.swapaxes(dJ, -1, -2))  # d^2 p / dq_j dq_k is symmetric


@given(arm=arm_strategy(), q=configurations(), qd=configurations())
def test_jacobian_rate_is_the_derivative_along_the_motion(arm, q, qd):
    Jdot = kinematics.jacobian_rate(arm, q, qd)
    expected = np.einsum(
        "ijk,k->ij",
        np.array(
            symbolic_jacobian_derivative()(q[0], q[1], arm.l1, arm.l2), dtype=float
        ),
        qd,
    )
    scale = (arm.l1 + arm.l2) * (1 + np.abs(qd).sum())
    assert np.allclose(Jdot, expected, rtol=0.0, atol=1e-12 * scale)
    step = 1e-6
    by_differences = (arm.jacobian(q + step * qd) - arm.jacobian(q - step * qd)) / (
        2 * step
    )
    assert np.allclose(Jdot, by_differences, rtol=0.0, atol=1e-7 * scale)


def test_derivatives_of_the_jacobian_are_vectorised():
    q = np.random.default_rng(2).uniform(-np.pi, np.pi, (3, 4, 2))
    qd = np.random.default_rng(3).uniform(-2.0, 2.0, (4, 2))
    arm = arms.osake
    dJ = kinematics.jacobian_derivative(arm, q)
    Jdot = kinematics.jacobian_rate(arm, q, qd)
    assert dJ.shape == (3, 4, 2, 2, 2) and Jdot.shape == (3, 4, 2, 2)
    for index in np.ndindex(3, 4):
        assert np.array_equal(dJ[index], kinematics.jacobian_derivative(arm, q[index]))
        assert np.allclose(
            Jdot[index],
            kinematics.jacobian_rate(arm, q[index], qd[index[1]]),
            rtol=0.0,
            atol=1e-15,
        )
    with pytest.raises(
        ValueError,
        match=r"q of shape \(3, 4, 2\) and qd of shape \(3, 2\) do not broadcast",
    ):
        kinematics.jacobian_rate(arm, q, qd[:3])


@given(arm=arm_strategy(), q=configurations(), force=configurations())
def test_joint_torques_one_input_path_equals_the_vectorised_path_and_J_transpose_F(
    arm, q, force
):
    one = kinematics.joint_torques(arm, q, force)
    batch = kinematics.joint_torques(arm, q[None], force[None])[0]
    scale = (arm.l1 + arm.l2) * (1 + np.abs(force).sum())
    assert np.allclose(one, batch, rtol=0.0, atol=1e-12 * scale)
    assert np.allclose(one, arm.jacobian(q).T @ force, rtol=0.0, atol=1e-12 * scale)
    assert np.allclose(
        kinematics.joint_torques(arm, q, -force), -one, rtol=0.0, atol=1e-12 * scale
    )


def test_pushing_down_on_a_table_takes_clockwise_torques():
    """Sign check by hand: the arm stretched along x pushes down on a table (force_by_tip = (0, -10) N):
    the motors press it down, clockwise (negative torques), and the table pushes the tip up with 10 N."""
    tau = kinematics.joint_torques(arms.two_metre, [0.0, 0.0], [0.0, -10.0])
    assert np.allclose(tau, [-40.0, -20.0])


# ----------------------------------------------------------------- one configuration on floats, a batch on arrays
# fk, the Jacobian and J^T F evaluate one formula each (tip_from_trig, jacobian_from_trig, torques_from_jacobian):
# with math for a pair of floats, with numpy for a batch.  The two evaluations agree to round-off, and a
# single input the float path does not read is refused exactly as the vectorised checks refuse it.
ONE_ARM = TwoLinkArm(1.0, 0.7, m1=2.0, m2=1.2)
wide_angles = st.floats(-4.0, 4.0, allow_nan=False)
short_lengths = st.floats(0.05, 5.0, allow_nan=False)


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


def refused_in_a_batch_of_one(function, bad, name):
    """``function`` on ``bad`` read by the vectorised checks, as a batch of one."""
    return lambda: function(as_pairs(bad, name)[None, :])[0]


@pytest.mark.parametrize("bad", BAD_PAIRS, ids=repr)
def test_single_bad_configuration_is_refused_as_the_vectorised_path_refuses_it(bad):
    for function in (ONE_ARM.fk, ONE_ARM.jacobian):
        assert_same_outcome(
            outcome(lambda: function(bad)),
            outcome(refused_in_a_batch_of_one(function, bad, "q")),
        )


@settings(max_examples=200, deadline=None)
@given(short_lengths, short_lengths, wide_angles, wide_angles, wide_angles, wide_angles)
def test_fk_jacobian_and_joint_torques_paths_agree(l1, l2, q1, q2, fx, fy):
    arm = TwoLinkArm(l1, l2)
    for q in ([q1, q2], (q1, q2), np.array([q1, q2])):
        np.testing.assert_allclose(
            arm.fk(q), arm.fk(np.array([[q1, q2]]))[0], rtol=0, atol=1e-12
        )
        np.testing.assert_allclose(
            arm.jacobian(q), arm.jacobian(np.array([[q1, q2]]))[0], rtol=0, atol=1e-12
        )
        one = arm.joint_torques(q, [fx, fy])
        np.testing.assert_allclose(
            one,
            arm.joint_torques(np.array([[q1, q2]]), [fx, fy])[0],
            rtol=0,
            atol=1e-12,
        )
    assert arm.fk([q1, q2]).shape == (2,) and arm.jacobian([q1, q2]).shape == (2, 2)
    # the batch path, block by block, gives row for row what one call gives
    q_many = np.array([[q1, q2], [q2, q1]] * 5000)  # more than one block
    np.testing.assert_allclose(arm.fk(q_many)[-1], arm.fk([q2, q1]), rtol=0, atol=1e-12)
    np.testing.assert_allclose(
        arm.jacobian(q_many)[-2], arm.jacobian([q1, q2]), rtol=0, atol=1e-12
    )


def test_the_formulas_read_as_the_textbook():
    c1, s1, c12, s12 = np.cos(0.3), np.sin(0.3), np.cos(1.0), np.sin(1.0)
    assert kinematics.tip_from_trig(2.0, 1.0, c1, s1, c12, s12) == (
        2 * c1 + c12,
        2 * s1 + s12,
    )
    assert kinematics.jacobian_from_trig(2.0, 1.0, c1, s1, c12, s12) == (
        -2 * s1 - s12,
        -s12,
        2 * c1 + c12,
        c12,
    )
    assert kinematics.torques_from_jacobian(1.0, 2.0, 3.0, 4.0, 10.0, 100.0) == (
        310.0,
        420.0,
    )


def test_duck_typed_arm_still_works_on_the_float_path():
    class Bare:
        l1, l2 = 2.0, 1.0

    np.testing.assert_allclose(
        kinematics.fk(Bare(), [0.0, np.pi / 2]), [2.0, 1.0], atol=1e-12
    )
    np.testing.assert_allclose(
        kinematics.jacobian(Bare(), [0.0, 0.0]), [[0.0, 0.0], [3.0, 1.0]], atol=1e-12
    )


@given(wide_angles, wide_angles)
@settings(max_examples=50, deadline=None)
def test_float_path_results_are_fresh_writable_arrays(q1, q2):
    p_tip = ONE_ARM.fk([q1, q2])
    p_tip[0] = 99.0
    assert ONE_ARM.fk([q1, q2])[0] != 99.0
    J = ONE_ARM.jacobian([q1, q2])
    J[0, 0] = 99.0
    assert ONE_ARM.jacobian([q1, q2])[0, 0] != 99.0


@pytest.mark.parametrize("not_an_arm", [None, 3.0, "arm"], ids=repr)
def test_single_configuration_with_something_that_is_not_an_arm_is_refused_as_in_a_batch(
    not_an_arm,
):
    for call in (
        lambda q: kinematics.fk(not_an_arm, q),
        lambda q: kinematics.jacobian(not_an_arm, q),
    ):
        fast, slow = (
            outcome(lambda: call([0.3, 0.4])),
            outcome(lambda: call(np.array([[0.3, 0.4]]))),
        )
        assert fast[0] == slow[0] == "error"
        assert fast[1] == slow[1]
        assert "arm" in fast[1][1]


# ----------------------------------------------------------------- large angles, reduced exactly
#: Any finite angle, up to the largest float.
any_angles = st.floats(-1.7e308, 1.7e308, allow_nan=False, allow_infinity=False)

KINEMATICS_CALLS = {
    "fk": lambda q: ONE_ARM.fk(q),
    "jacobian": lambda q: ONE_ARM.jacobian(q),
    "joint_positions": lambda q: ONE_ARM.joint_positions(q),
    "joint_torques": lambda q: ONE_ARM.joint_torques(q, [1.0, 0.5]),
    "jacobian_derivative": lambda q: kinematics.jacobian_derivative(ONE_ARM, q),
    "jacobian_rate": lambda q: kinematics.jacobian_rate(ONE_ARM, q, [0.3, -0.2]),
}


def exactly_reduced(angle):
    """``angle`` in (-pi, pi] with the same sine and cosine: libm's sin and cos reduce exactly."""
    return float(np.arctan2(np.sin(angle), np.cos(angle)))


@settings(max_examples=60)
@given(q1=any_angles, q2=any_angles, batch=st.booleans())
@pytest.mark.parametrize("name", sorted(KINEMATICS_CALLS))
def test_large_angles_are_reduced_exactly_never_rounded_in_a_sum(name, q1, q2, batch):
    """fk(1e17, 0.5) put link 2 at 1e17 rad: the sum rounded the 0.5 away (and 1e308 + 1e308 overflowed)."""
    call = KINEMATICS_CALLS[name]
    q = [q1, q2]
    reduced = [exactly_reduced(q1), exactly_reduced(q2)]
    got = call([q, q])[1] if batch else call(q)
    assert np.allclose(got, call(reduced), rtol=0.0, atol=1e-14)


def test_a_sub_revolution_part_of_link_2_is_kept_beside_a_large_q1():
    q1 = 1e17
    reduced = exactly_reduced(q1)
    assert not np.allclose(ONE_ARM.fk([q1, 0.5]), ONE_ARM.fk([q1, 0.0]))
    assert np.allclose(ONE_ARM.fk([q1, 0.5]), ONE_ARM.fk([reduced, 0.5]), atol=1e-15)


# ----------------------------------------------------------------- the reach message
@pytest.mark.parametrize("outside", [1 + 2e-10, 1 + 1e-9, 1 + 1e-7])
def test_unreachable_just_outside_the_reach_does_not_print_as_the_reach(outside):
    """6 digits printed "4 m from the base; reaches [0, 4] m": now the digits and the overshoot show."""
    arm = TwoLinkArm(2.0, 2.0)
    with pytest.raises(UnreachableError) as raised:
        kinematics.require_within_reach(arm, [4.0 * outside, 0.0])
    message = str(raised.value)
    distance = message.split(" is ")[1].split(" m from the base")[0]
    assert float(distance) > 4.0 and distance != "4"
    assert (
        "beyond the outer reach circle" in message and "round-off tolerance" in message
    )
    assert message.endswith("this arm reaches distances in [0, 4] m (l1=2, l2=2)")


def test_unreachable_inside_the_hole_just_short_of_the_reach_says_so():
    with pytest.raises(
        UnreachableError,
        match=r"is 0\.99999999\d* m from the base, [0-9.e-]+ m inside the inner",
    ):
        kinematics.require_within_reach(TwoLinkArm(2.0, 1.0), [1.0 - 3e-9, 0.0])
    with pytest.raises(
        UnreachableError, match=r"is 5 m from the base; this arm reaches"
    ):
        kinematics.require_within_reach(TwoLinkArm(2.0, 2.0), [3.0, 4.0])


def test_a_shape_mismatch_of_joint_torques_names_the_arguments_and_their_shapes():
    with pytest.raises(
        ValueError,
        match=r"q of shape \(3, 2\) and force_by_tip of shape \(4, 2\) do not broadcast",
    ):
        arms.two_metre.joint_torques(np.zeros((3, 2)), np.zeros((4, 2)))
