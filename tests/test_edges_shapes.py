"""Shape mismatches name the arguments and their shapes (issue 11, class 10)."""

import numpy as np
import pytest

from twolink import arms, contact, controllers, statics

ARM = arms.two_metre
A3, A4 = np.zeros((3, 2)), np.zeros((4, 2))


@pytest.mark.parametrize(
    "call, fragment",
    [
        (
            lambda: ARM.coriolis(A3, A4),
            r"q of shape \(3, 2\) and qd of shape \(4, 2\) do not broadcast",
        ),
        (
            lambda: ARM.energy(A3, A4),
            r"q of shape \(3, 2\) and qd of shape \(4, 2\) do not broadcast",
        ),
        (
            lambda: ARM.joint_torques(A3, A4),
            r"q of shape \(3, 2\) and force_by_tip of shape \(4, 2\) do not broadcast",
        ),
        (
            lambda: ARM.inverse_dynamics(A3, A3, A3, A4),
            r"qdd of shape \(3, 2\) and force_by_tip of shape \(4, 2\)",
        ),
        (
            lambda: ARM.inverse_dynamics(A3, A4, A3),
            r"q of shape \(3, 2\), qd of shape \(4, 2\) and qdd of shape",
        ),
        (
            lambda: ARM.forward_dynamics(A3, A3, A3, A4),
            r"tau of shape \(3, 2\) and force_by_tip of shape \(4, 2\)",
        ),
        (
            lambda: controllers.Impedance(ARM, 600.0, 50.0, [3.0, 1.0]).force_on_tip(
                A3, A4
            ),
            r"q of shape \(3, 2\) and qd of shape \(4, 2\) do not broadcast",
        ),
        (
            lambda: contact.TipForce(ARM, None, [1.0, 0.0])(0.0, A3, A3),
            r"q must be one configuration of shape \(2,\) \(radians\); got shape \(3, 2\)",
        ),
        (
            lambda: contact.TipForce(ARM, None, lambda t, p, v: [1.0, 2.0, 3.0])(
                0.0, [0.1, 0.2], [0.0, 0.0]
            ),
            r"force_on_tip\(t, p_tip, v_tip\) must have shape \(\.\.\., 2\)",
        ),
        (
            lambda: contact.TipForce(ARM, None, lambda t, p, v: np.zeros((2, 2)))(
                0.0, [0.1, 0.2], [0.0, 0.0]
            ),
            r"force_on_tip\(t, p_tip, v_tip\) must return shape \(2,\)",
        ),
        (
            lambda: contact.TipForce(
                ARM, lambda t, q, qd: np.zeros((3, 2)), [1.0, 0.0]
            )(0.0, [0.1, 0.2], [0.0, 0.0]),
            r"controller\(t, q, qd\) must return shape \(2,\)",
        ),
    ],
)
def test_shape_mismatches_name_the_arguments_and_their_shapes(call, fragment):
    with pytest.raises(ValueError, match=fragment):
        call()


def test_a_spring_wall_in_tip_force_still_works():
    wall = contact.SpringWall(
        statics.Wall.through([4.0, 0.0], [0.0, 4.0]), stiffness=1e5
    )
    pushed = contact.TipForce(ARM, None, wall)
    assert pushed(0.0, np.array([0.0, 0.0]), np.zeros(2)).shape == (2,)
