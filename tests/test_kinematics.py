"""Forward kinematics, DH transforms, Jacobians, statics and conventions."""

import numpy as np
import pytest
from conftest import arms as arm_strategy
from conftest import configurations
from hypothesis import given

from twolink import TwoLinkArm, arms, kinematics, to_absolute, to_relative, wrap_angle


@given(arm=arm_strategy(), q=configurations())
def test_fk_matches_the_textbook_formula(arm, q):
    q1, q2 = q
    expected = [
        arm.l1 * np.cos(q1) + arm.l2 * np.cos(q1 + q2),
        arm.l1 * np.sin(q1) + arm.l2 * np.sin(q1 + q2),
    ]
    assert np.allclose(arm.fk(q), expected, atol=1e-12 * (arm.l1 + arm.l2))


@given(arm=arm_strategy(), q=configurations())
def test_dh_product_equals_closed_form_fk(arm, q):
    T_01, T_02 = arm.transforms(q)
    assert np.allclose(T_02[:2, 3], arm.fk(q), atol=1e-12 * (arm.l1 + arm.l2))
    assert np.allclose(T_01[:2, 3], arm.joint_positions(q)[1], atol=1e-12 * arm.l1)
    # rotation part is a planar rotation by q1 + q2
    angle = q[0] + q[1]
    assert np.allclose(T_02[:2, :2], [[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])
    assert np.allclose(T_02[3], [0, 0, 0, 1])


def test_base_offset_goes_into_z_only():
    q = np.radians([30.0, 60.0])
    T_01, T_02 = arms.osake.transforms(q)
    assert T_02[2, 3] == pytest.approx(0.065)
    assert T_01[2, 3] == pytest.approx(0.065)
    assert np.allclose(T_02[:2, 3], arms.osake.fk(q))


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


@given(arm=arm_strategy(), q=configurations())
def test_geometric_jacobian_rows(arm, q):
    J6 = arm.geometric_jacobian(q)
    assert J6.shape == (6, 2)
    assert np.allclose(J6[:2], arm.jacobian(q), atol=1e-12 * (arm.l1 + arm.l2))
    assert np.allclose(J6[2:5], 0.0, atol=1e-12 * (arm.l1 + arm.l2))
    assert np.allclose(J6[5], [1.0, 1.0])


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


@given(arm=arm_strategy(), q=configurations(), qd=configurations(), force=configurations())
def test_joint_torques_power_balance(arm, q, qd, force):
    """Virtual work: tau . qd equals F . v for the tip velocity v = J qd."""
    tau = arm.joint_torques(q, force)
    v_tip = arm.jacobian(q) @ qd
    assert tau @ qd == pytest.approx(force @ v_tip, abs=1e-9 * (arm.l1 + arm.l2) * 10)


@given(q=configurations())
def test_absolute_relative_round_trip(q):
    q_abs = to_absolute(q)
    assert q_abs[1] == pytest.approx(q[0] + q[1])
    assert np.allclose(to_relative(q_abs), q)


@given(q=configurations())
def test_fk_is_the_same_in_both_conventions(q):
    arm = arms.two_metre
    q1, q2_abs = to_absolute(q)
    expected = [2 * np.cos(q1) + 2 * np.cos(q2_abs), 2 * np.sin(q1) + 2 * np.sin(q2_abs)]
    assert np.allclose(arm.fk(q), expected)


def test_wrap_angle_range():
    angles = np.linspace(-20, 20, 1001)
    wrapped = wrap_angle(angles)
    assert np.all(wrapped >= -np.pi) and np.all(wrapped < np.pi)
    assert np.allclose(np.cos(wrapped), np.cos(angles)) and np.allclose(np.sin(wrapped), np.sin(angles))


@pytest.mark.parametrize("bad", [[1.0, 2.0, 3.0], [[1.0], [2.0]], 1.0, [np.nan, 0.0], [0.0, np.inf], "ab"])
def test_bad_configurations_raise(bad):
    arm = TwoLinkArm(1.0, 1.0)
    for method in (arm.fk, arm.jacobian, arm.joint_positions, arm.transforms, arm.geometric_jacobian):
        with pytest.raises(ValueError, match="q must"):
            method(bad)


def test_bad_force_raises():
    with pytest.raises(ValueError, match="force_by_tip must be finite"):
        arms.two_metre.joint_torques([0.0, 1.0], [np.nan, 1.0])


def test_dh_table_rows():
    rows = arms.osake.dh_table()
    assert [row.joint for row in rows] == ["q1", "q2"]
    assert (rows[0].d, rows[0].a, rows[0].alpha) == (0.065, 0.10, 0.0)
    assert (rows[1].d, rows[1].a, rows[1].alpha) == (0.0, 0.115, 0.0)


# ----------------------------------------------------------------- J^T F and the derivatives of J
def _symbolic_jacobian_derivative():
    """dJ/dq from sympy (planar_fk's tip differentiated twice), as a function of (q1, q2, l1, l2)."""
    import sympy as sp

    from twolink.symbolic import planar_fk, planar_symbols

    s = planar_symbols()
    q = [s["q1"], s["q2"]]
    J = planar_fk()[3].jacobian(q)
    dJ = [[[sp.diff(J[i, j], q[k]) for k in range(2)] for j in range(2)] for i in range(2)]
    return sp.lambdify((s["q1"], s["q2"], s["l1"], s["l2"]), dJ, "numpy")


SYMBOLIC_DJ = _symbolic_jacobian_derivative()


@given(arm=arm_strategy(), q=configurations())
def test_jacobian_derivative_is_sympys_derivative_of_the_jacobian(arm, q):
    expected = np.array(SYMBOLIC_DJ(q[0], q[1], arm.l1, arm.l2), dtype=float)
    assert np.allclose(kinematics.jacobian_derivative(arm, q), expected, rtol=0.0, atol=1e-12 * (arm.l1 + arm.l2))


@given(arm=arm_strategy(), q=configurations())
def test_jacobian_derivative_matches_finite_differences_of_the_jacobian(arm, q):
    step = 1e-6
    columns = [(arm.jacobian(q + step * e) - arm.jacobian(q - step * e)) / (2 * step) for e in np.eye(2)]
    by_differences = np.stack(columns, axis=-1)  # index k (the joint differentiated by) last
    dJ = kinematics.jacobian_derivative(arm, q)
    assert np.allclose(dJ, by_differences, rtol=0.0, atol=1e-8 * (arm.l1 + arm.l2))
    assert np.array_equal(dJ, np.swapaxes(dJ, -1, -2))  # d^2 p / dq_j dq_k is symmetric


@given(arm=arm_strategy(), q=configurations(), qd=configurations())
def test_jacobian_rate_is_the_derivative_along_the_motion(arm, q, qd):
    Jdot = kinematics.jacobian_rate(arm, q, qd)
    expected = np.einsum("ijk,k->ij", np.array(SYMBOLIC_DJ(q[0], q[1], arm.l1, arm.l2), dtype=float), qd)
    scale = (arm.l1 + arm.l2) * (1 + np.abs(qd).sum())
    assert np.allclose(Jdot, expected, rtol=0.0, atol=1e-12 * scale)
    step = 1e-6
    by_differences = (arm.jacobian(q + step * qd) - arm.jacobian(q - step * qd)) / (2 * step)
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
        assert np.allclose(Jdot[index], kinematics.jacobian_rate(arm, q[index], qd[index[1]]), rtol=0.0, atol=1e-15)
    with pytest.raises(ValueError, match=r"q of shape \(3, 4, 2\) and qd of shape \(3, 2\) do not broadcast"):
        kinematics.jacobian_rate(arm, q, qd[:3])


@given(arm=arm_strategy(), q=configurations(), force=configurations())
def test_joint_torques_one_input_path_equals_the_vectorised_path_and_J_transpose_F(arm, q, force):
    one = kinematics.joint_torques(arm, q, force)
    batch = kinematics.joint_torques(arm, q[None], force[None])[0]
    scale = (arm.l1 + arm.l2) * (1 + np.abs(force).sum())
    assert np.allclose(one, batch, rtol=0.0, atol=1e-12 * scale)
    assert np.allclose(one, arm.jacobian(q).T @ force, rtol=0.0, atol=1e-12 * scale)
    assert np.allclose(kinematics.joint_torques(arm, q, -force), -one, rtol=0.0, atol=1e-12 * scale)


def test_pushing_down_on_a_table_takes_clockwise_torques():
    """Sign check by hand: the arm stretched along x pushes down on a table (force_by_tip = (0, -10) N):
    the motors press it down, clockwise (negative torques), and the table pushes the tip up with 10 N."""
    tau = kinematics.joint_torques(arms.two_metre, [0.0, 0.0], [0.0, -10.0])
    assert np.allclose(tau, [-40.0, -20.0])
