"""Magnitudes: parameters outside the representable range are refused; overflowing results are reported (class 9)."""

import warnings

import numpy as np
import pytest

from twolink import TwoLinkArm, arms, ik
from twolink.arm import LENGTH_RANGE


@pytest.mark.parametrize(
    "kwargs, name",
    [
        ({"l1": 1e155, "l2": 1.0}, "l1"),
        ({"l1": 1.0, "l2": 1e-160}, "l2"),
        ({"l1": 1.0, "l2": 1.0, "m1": 1e300}, "m1"),
        ({"l1": 1.0, "l2": 1.0, "m2": 1e200}, "m2"),
        ({"l1": 1.0, "l2": 1.0, "I1": 1e200}, "I1"),
        ({"l1": 1.0, "l2": 1.0, "g": 1e300}, "g"),
    ],
)
def test_parameters_outside_the_representable_range_are_refused_naming_the_range(
    kwargs, name
):
    with pytest.raises(
        ValueError, match=rf"{name} .* is outside the representable range"
    ):
        TwoLinkArm(**kwargs)


@pytest.mark.parametrize("length", [LENGTH_RANGE[0], 1e-30, 1.0, 1e30, LENGTH_RANGE[1]])
def test_arms_at_the_ends_of_the_range_are_exact(length):
    arm = TwoLinkArm(
        length, length, m1=2.0, m2=3.0, g=0.0
    )  # with gravity, tiny arms are all weight (qdd lost to m g l)
    q = np.array([0.4, 1.1])
    qdd_wanted = np.array([0.8, -1.3])
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no overflow or underflow warnings either
        p = arm.fk(q)
        assert np.allclose(ik.closed_form(arm, p).q, q, rtol=1e-12)
        tau = arm.inverse_dynamics(q, [0.3, -0.2], qdd_wanted)
        qdd = arm.forward_dynamics(q, [0.3, -0.2], tau)
    assert np.all(np.isfinite(tau))
    assert np.allclose(qdd, qdd_wanted, rtol=1e-9, atol=1e-9)


def test_overflowing_joint_rates_are_reported_not_returned_as_inf():
    with pytest.raises(
        OverflowError, match=r"joint rates qd \(rad/s\) overflow float64"
    ):
        arms.two_metre.joint_rates([0.3, 1e-5], [0.0, 1e305])
    with pytest.raises(OverflowError, match="joint rates"):
        arms.two_metre.joint_rates_dls([0.3, 1e-5], [0.0, 1e305], 1e-300)
    with pytest.raises(OverflowError, match="tip velocities"):
        arms.two_metre.tip_velocity([0.3, 1.0], [1e308, 1e308])


def test_overflowing_dynamics_are_reported():
    arm = TwoLinkArm(1.0, 1.0)
    with pytest.raises(OverflowError, match="joint accelerations"):
        arm.forward_dynamics([0.3, 0.4], [1e160, 0.0], [0.0, 0.0])
    with pytest.raises(OverflowError, match="joint accelerations"):
        arm.forward_dynamics(np.array([[0.3, 0.4]]), [1e160, 0.0], [0.0, 0.0])
    with pytest.raises(OverflowError, match="joint torques"):
        arm.inverse_dynamics([0.3, 0.4], [0.0, 0.0], [1e308, 1e308])
