"""twolink.dh: DH matrices and frames agree with the elementary transforms and with kinematics."""

import numpy as np
import pytest
from _cases import stable_id
from hypothesis import given
from hypothesis import strategies as st

from conftest import arms as arm_strategy
from conftest import configurations
from twolink import (
    TwoLinkArm,
    arms,
    dh,
    kinematics,
)


@given(arm=arm_strategy(), q=configurations())
def test_dh_product_equals_closed_form_fk(arm, q):
    T_01, T_02 = arm.transforms(q)
    assert np.allclose(T_02[:2, 3], arm.fk(q), atol=1e-12 * (arm.l1 + arm.l2))
    assert np.allclose(T_01[:2, 3], arm.joint_positions(q)[1], atol=1e-12 * arm.l1)
    # rotation part is a planar rotation by q1 + q2
    angle = q[0] + q[1]
    assert np.allclose(
        T_02[:2, :2], [[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]]
    )
    assert np.allclose(T_02[3], [0, 0, 0, 1])


def test_base_offset_goes_into_z_only():
    q = np.radians([30.0, 60.0])
    T_01, T_02 = arms.osake.transforms(q)
    assert T_02[2, 3] == pytest.approx(0.065)
    assert T_01[2, 3] == pytest.approx(0.065)
    assert np.allclose(T_02[:2, 3], arms.osake.fk(q))


@given(arm=arm_strategy(), q=configurations())
def test_geometric_jacobian_rows(arm, q):
    J6 = arm.geometric_jacobian(q)
    assert J6.shape == (6, 2)
    assert np.allclose(J6[:2], arm.jacobian(q), atol=1e-12 * (arm.l1 + arm.l2))
    assert np.allclose(J6[2:5], 0.0, atol=1e-12 * (arm.l1 + arm.l2))
    assert np.allclose(J6[5], [1.0, 1.0])


def test_dh_table_rows():
    rows = arms.osake.dh_table()
    assert [row.joint for row in rows] == ["q1", "q2"]
    assert (rows[0].d, rows[0].a, rows[0].alpha) == (0.065, 0.10, 0.0)
    assert (rows[1].d, rows[1].a, rows[1].alpha) == (0.0, 0.115, 0.0)


@pytest.mark.parametrize(
    "bad", [None, "0.3", [0.3, 1j], True, np.inf, [np.nan]], ids=stable_id
)
def test_dh_matrix_refuses_non_angles(bad):
    with pytest.raises(ValueError, match="must be"):
        dh.dh_matrix(bad, 0.0, 1.0, 0.0)


def elementary_dh(theta, d, a, alpha):
    """``Rot_z(theta) Trans_z(d) Trans_x(a) Rot_x(alpha)``, multiplied out by numpy."""
    c, s = np.cos(theta), np.sin(theta)
    rot_z = np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])
    trans_z = np.eye(4)
    trans_z[2, 3] = d
    trans_x = np.eye(4)
    trans_x[0, 3] = a
    ca, sa = np.cos(alpha), np.sin(alpha)
    rot_x = np.array([[1, 0, 0, 0], [0, ca, -sa, 0], [0, sa, ca, 0], [0, 0, 0, 1]])
    return rot_z @ trans_z @ trans_x @ rot_x


finite = st.floats(-10.0, 10.0)


@given(theta=finite, d=finite, a=finite, alpha=finite)
def test_dh_matrix_is_the_product_of_its_four_elementary_transforms(theta, d, a, alpha):
    A = dh.dh_matrix(theta, d, a, alpha)
    assert A.shape == (4, 4)
    assert np.allclose(A, elementary_dh(theta, d, a, alpha), atol=1e-12)


@given(theta=finite, alpha=finite)
def test_dh_matrix_rotation_part_is_a_rotation(theta, alpha):
    rotation = dh.dh_matrix(theta, 0.3, 1.2, alpha)[:3, :3]
    assert np.allclose(rotation @ rotation.T, np.eye(3), atol=1e-12)
    assert np.linalg.det(rotation) == pytest.approx(1.0, abs=1e-12)


def test_dh_matrix_is_vectorised_over_theta():
    thetas = np.array([[0.0, 0.5], [1.0, -2.0], [3.0, 0.1]])
    batch = dh.dh_matrix(thetas, 0.1, 2.0, 0.4)
    assert batch.shape == (3, 2, 4, 4)
    for index in np.ndindex(thetas.shape):
        assert np.array_equal(batch[index], dh.dh_matrix(thetas[index], 0.1, 2.0, 0.4))


@pytest.mark.parametrize("name", ["d", "a", "alpha"])
def test_dh_matrix_refuses_a_parameter_that_is_not_finite_naming_it(name):
    values = {"d": 0.0, "a": 1.0, "alpha": 0.0, name: np.inf}
    with pytest.raises(ValueError, match=rf"^{name} "):
        dh.dh_matrix(0.3, **values)


@given(arm=arm_strategy(), q=configurations())
def test_the_dh_frames_put_the_elbow_and_tip_where_kinematics_does(arm, q):
    T_01, T_02 = dh.transforms(arm, q)
    points = kinematics.joint_positions(arm, q)
    scale = 1e-12 * (arm.l1 + arm.l2)
    assert np.allclose(T_01[:2, 3], points[1], atol=scale)
    assert np.allclose(T_02[:2, 3], kinematics.fk(arm, q), atol=scale)
    assert np.array_equal(T_01, dh.dh_matrix(q[0], arm.d, arm.l1, 0.0))


def test_transforms_and_geometric_jacobian_take_batches():
    q = np.array([[0.1, 0.2], [1.0, -1.5], [2.5, 3.0], [-0.4, 0.0]])
    T_01, T_02 = dh.transforms(arms.two_metre, q)
    assert T_01.shape == T_02.shape == (4, 4, 4)
    assert np.allclose(T_02[:, :2, 3], kinematics.fk(arms.two_metre, q))
    J6 = dh.geometric_jacobian(arms.two_metre, q)
    assert J6.shape == (4, 6, 2)
    assert np.allclose(J6[:, :2], kinematics.jacobian(arms.two_metre, q))


def test_dh_table_rows_are_named_tuples_of_the_arm():
    arm = TwoLinkArm(1.5, 0.5, d=0.2)
    first, second = dh.dh_table(arm)
    assert first == dh.DHRow("q1", 0.0, 0.2, 1.5, 0.0)
    assert second._asdict() == {
        "joint": "q2",
        "theta_offset": 0.0,
        "d": 0.0,
        "a": 0.5,
        "alpha": 0.0,
    }
