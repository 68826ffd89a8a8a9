"""twolink.stiffness: joint and tip stiffness are inverse maps, symmetric and positive where they should be."""

import control
import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from conftest import configurations, dynamic_arms
from twolink import SingularityError, TwoLinkArm, arms, stiffness
from twolink.controllers import Impedance, JointPD
from twolink.linearization import (
    linearize,
)


@given(
    dynamic_arms(),
    st.floats(-np.pi, np.pi),
    st.floats(0.2, np.pi - 0.2),
    st.floats(1.0, 1000.0),
    st.floats(-0.9, 0.9),
    st.floats(1.0, 1000.0),
)
def test_joint_and_tip_stiffness_are_inverse_maps(arm, q1, q2, k11, correlation, k22):
    q = np.array([q1, q2])
    K_tip = np.array(
        [
            [k11, correlation * np.sqrt(k11 * k22)],
            [correlation * np.sqrt(k11 * k22), k22],
        ]
    )
    back = stiffness.tip_stiffness(arm, q, stiffness.joint_stiffness(arm, q, K_tip))
    assert np.allclose(back, K_tip, rtol=1e-6, atol=1e-6 * k11)


@pytest.mark.parametrize("q_ref", [[0.4, 1.3], [-1.0, 0.3], [2.0, -2.5]])
def test_tip_stiffness_is_what_python_control_says_a_steady_push_does(q_ref):
    """dcgain of the linearised loop is the compliance: K_tip^-1 for a joint PD, K^-1 for impedance."""
    arm = arms.two_metre
    kp = np.array([[300.0, 20.0], [20.0, 100.0]])
    loop = linearize(arm, JointPD(arm, kp, 30.0, q_ref), q_ref)
    assert np.allclose(
        control.dcgain(loop),
        np.linalg.inv(stiffness.tip_stiffness(arm, q_ref, kp)),
        rtol=1e-9,
    )
    K = np.array([[600.0, 100.0], [100.0, 300.0]])
    impedance = Impedance(arm, K, 40.0, arm.fk(q_ref))
    assert np.allclose(
        control.dcgain(linearize(arm, impedance, q_ref)), np.linalg.inv(K), rtol=1e-9
    )


def test_stiffness_ellipse_and_singular_poses():
    arm = arms.two_metre
    ellipse = stiffness.stiffness_ellipse(
        arm, [0.2, 1.0], [[500.0, 100.0], [100.0, 500.0]]
    )
    assert np.allclose(ellipse.semi_axes, [600.0, 400.0])
    assert np.allclose(np.abs(ellipse.directions[:, 0]), np.sqrt(0.5))
    assert np.allclose(ellipse.centre, arm.fk([0.2, 1.0]))
    with pytest.raises(SingularityError, match="unbounded"):
        stiffness.tip_stiffness(arm, [0.5, 0.0], 100.0)
    with pytest.raises(ValueError, match="one configuration"):
        stiffness.joint_stiffness(arm, [[0.5, 0.0]], 100.0)


# ---------------------------------------------------------------- symmetric, positive (semi-)definite
spd_entries = st.tuples(
    st.floats(1.0, 1000.0), st.floats(-0.9, 0.9), st.floats(1.0, 1000.0)
)


def spd_matrix(k11, correlation, k22):
    off_diagonal = correlation * np.sqrt(k11 * k22)
    return np.array([[k11, off_diagonal], [off_diagonal, k22]])


@given(dynamic_arms(), configurations(), spd_entries)
def test_joint_stiffness_is_symmetric_positive_semi_definite(arm, q, entries):
    K_tip = spd_matrix(*entries)
    K_joint = stiffness.joint_stiffness(arm, q, K_tip)
    J = arm.jacobian(q)
    assert np.array_equal(K_joint, K_joint.T)
    assert np.allclose(
        K_joint, J.T @ K_tip @ J, rtol=1e-12, atol=1e-9 * np.abs(K_joint).max()
    )
    assert np.linalg.eigvalsh(K_joint).min() >= -1e-9 * np.abs(K_joint).max()


@given(
    dynamic_arms(),
    st.floats(-np.pi, np.pi),
    st.floats(0.2, np.pi - 0.2),
    st.sampled_from([1.0, -1.0]),
    spd_entries,
)
def test_tip_stiffness_away_from_singularities_is_symmetric_positive_definite(
    arm, q1, q2, branch, entries
):
    q = np.array([q1, branch * q2])
    K_tip = stiffness.tip_stiffness(arm, q, spd_matrix(*entries))
    assert np.array_equal(K_tip, K_tip.T)
    assert np.linalg.eigvalsh(K_tip).min() > 0.0


def test_a_stretched_arm_meets_no_spring_along_its_null_motion():
    """The module's example: stretched along x, dq = (1, -2) moves the tip by nothing."""
    arm = TwoLinkArm(1.0, 1.0)
    K_joint = stiffness.joint_stiffness(arm, [0.0, 0.0], 100.0)
    assert np.allclose(K_joint @ [1.0, -2.0], 0.0, atol=1e-12)
    assert np.linalg.det(K_joint) == pytest.approx(0.0, abs=1e-9)


@given(
    st.floats(-np.pi, np.pi),
    st.floats(-np.pi, np.pi),
    spd_entries,
)
def test_the_stiffness_ellipse_axes_are_the_eigenpairs_largest_first(q1, q2, entries):
    K_tip = spd_matrix(*entries)
    ellipse = stiffness.stiffness_ellipse(arms.two_metre, [q1, q2], K_tip)
    assert ellipse.semi_axes[0] >= ellipse.semi_axes[1] > 0.0
    assert np.allclose(ellipse.directions.T @ ellipse.directions, np.eye(2))
    for axis in range(2):
        direction = ellipse.directions[:, axis]
        assert np.allclose(K_tip @ direction, ellipse.semi_axes[axis] * direction)


@pytest.mark.parametrize(
    "gain, fragment",
    [
        ([[100.0, 50.0], [0.0, 100.0]], "symmetric"),
        (-5.0, "tip stiffness"),
        ([[100.0, 0.0], [0.0, -1.0]], "tip stiffness"),
        ([1.0, 2.0, 3.0], "tip stiffness"),
        (np.nan, "tip stiffness"),
    ],
    ids=["not symmetric", "negative", "negative eigenvalue", "shape", "nan"],
)
def test_a_tip_stiffness_that_is_no_spring_is_refused(gain, fragment):
    with pytest.raises(ValueError, match=fragment):
        stiffness.joint_stiffness(arms.two_metre, [0.3, 1.0], gain)
