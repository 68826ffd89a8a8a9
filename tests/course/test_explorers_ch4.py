"""Chapter 4's explorer (twolink_course.explorers.ch4): the wall push, drawn once and moved."""

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402
from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from twolink import TwoLinkArm, Wall, arms, velocity, wall_contact  # noqa: E402
from twolink_course.explorers import ch4  # noqa: E402

WALL_A, WALL_B = (4.0, 0.0), (0.0, 4.0)


@pytest.fixture(scope="module")
def view():
    arm = arms.two_metre
    contacts = wall_contact(arm, Wall.through(WALL_A, WALL_B), 500.0)
    return ch4.WallPushView(arm, WALL_A, WALL_B, contacts)


def test_the_start_is_the_step_nearest_the_elbow_down_contact(view):
    start = view.start_position(0.005)
    contact = view.contacts.p_contact[view.contacts.branch("down")]
    exact = np.linalg.norm(contact - WALL_A) / np.linalg.norm(
        np.subtract(WALL_B, WALL_A)
    )
    assert abs(start - exact) <= 0.0025 and round(start / 0.005, 9).is_integer()


@settings(max_examples=40, deadline=None)
@given(
    position=st.floats(0.0, 1.0),
    force=st.floats(0.0, 1000.0),
    elbow=st.sampled_from(["down", "up"]),
)
def test_a_move_puts_the_tip_on_the_wall_and_the_torques_are_J_transpose_F(
    view, position, force, elbow
):
    view.update(position=position, force=force, elbow=elbow)
    q, tau, off_normal = view.state(position, force, elbow)
    tip = view.arm_line.get_xydata()[-1]
    assert np.allclose(tip, view.arm.fk(q), atol=1e-9)
    assert abs(view.wall.signed_distance(tip)) < 1e-9
    expected = view.arm.joint_torques(q, force * view.wall.into_wall())
    assert np.allclose(tau, expected, atol=1e-5)
    assert -180.0 <= off_normal < 180.0
    assert f"{tau[0]:+.1f} N m" in view.ax.get_title()
    # the ellipse stays inside the axes: at most ELLIPSE_CLIP from the tip, as the note says
    outline = view.ellipse[-1].get_xydata()
    assert np.all(np.linalg.norm(outline - tip, axis=1) <= ch4.ELLIPSE_CLIP + 1e-9)
    low, high = ch4.LIMITS
    assert np.all((outline > low) & (outline < high))


def test_at_a_contact_link_2_is_on_the_normal_and_tau2_vanishes(view):
    q, tau, off_normal = view.state(view.start_position(1e-9), 500.0, "down")
    assert abs(off_normal) < 1e-6 and abs(tau[1]) < 1e-3


def test_the_description_says_the_ellipse_is_unbounded_at_full_stretch(view):
    sentence = view.describe(position=0.0, force=500.0, elbow="down")
    assert "unbounded along the stretched arm" in sentence
    assert "(4.00, 0.00) m" in sentence
    near = view.describe(position=0.5, force=500.0, elbow="up")
    q, _, _ = view.state(0.5, 500.0, "up")
    longest = velocity.force_ellipse(view.arm, q).semi_axes[0]
    assert f"semi-axes {longest:.2g} N" in near


def test_an_arm_of_unequal_links_is_named_by_both():
    arm = TwoLinkArm(2.5, 1.5)
    contacts = wall_contact(arm, Wall.through(WALL_A, WALL_B), 100.0)
    view = ch4.WallPushView(arm, WALL_A, WALL_B, contacts)
    assert view.describe(0.5, 100.0, "down").startswith("The 1.5 m + 2.5 m arm")
