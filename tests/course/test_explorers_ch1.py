"""Chapter 1's explorer and figure (twolink_course.explorers.ch1): the arm moved in degrees, the two angle conventions."""

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from twolink import TwoLinkArm, arms, to_absolute  # noqa: E402
from twolink_course import alttext  # noqa: E402
from twolink_course.explorers import ch1  # noqa: E402

DEGREES = st.integers(-180, 180)


@pytest.fixture(scope="module")
def view():
    return ch1.ArmAngles(arms.osake, "the OSAKE arm")


@settings(max_examples=40, deadline=None)
@given(q1=DEGREES, q2=DEGREES)
def test_a_move_puts_the_arm_at_the_angles_given_in_degrees(view, q1, q2):
    view.update(q1=q1, q2=q2)
    q = np.radians([q1, q2])
    assert np.allclose(view.arm_line.get_xydata(), arms.osake.joint_positions(q))
    assert view.ax.get_title() == f"q1 = {q1}°, q2 = {q2}°"
    sentence = view.describe(q1=q1, q2=q2)
    x, y = arms.osake.fk(q)
    assert sentence.startswith(f"The OSAKE arm at q = ({q1}°, {q2}°)")
    assert f"x = {x:.4f} m, y = {y:.4f} m, z = 0.0650 m" in sentence
    assert f"link 2 at {np.degrees(to_absolute(q)[1]):.0f}°" in sentence


def test_the_axes_hold_every_pose_so_a_move_never_changes_them(view):
    limits = view.ax.get_xlim(), view.ax.get_ylim()
    for q1, q2 in ((0, 0), (180, 0), (-90, 0), (45, 180)):
        view.update(q1=q1, q2=q2)
        points = view.arm_line.get_xydata()
        assert np.all(np.abs(points) <= arms.osake.reach[1] + 1e-12)
    assert (view.ax.get_xlim(), view.ax.get_ylim()) == limits


@given(
    q=st.tuples(st.floats(-1.5, 1.5), st.floats(-1.5, 1.5)).filter(
        lambda q: min(abs(q[0]), abs(q[1]), abs(q[0] + q[1])) > 0.05
    )
)
@settings(max_examples=15, deadline=None)
def test_the_arcs_span_q1_q2_and_their_sum(q):
    _, ax = plt.subplots()
    try:
        arcs = ch1.draw_angle_conventions(TwoLinkArm(2.0, 1.5), np.array(q), ax=ax)
        spans = [np.radians(arc.theta2 - arc.theta1) for arc in arcs]
        assert np.allclose(spans, np.abs([q[0], q[1], q[0] + q[1]]))
        said = alttext.describe(ax.figure)
        assert f"q1 = {np.degrees(q[0]):.0f}°" in said
        assert f"q2_abs = {np.degrees(q[0] + q[1]):.0f}°" in said
    finally:
        plt.close(ax.figure)
