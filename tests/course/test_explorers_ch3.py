"""Chapter 3's explorer and figures (twolink_course.explorers.ch3): the velocity ellipse, rates, two motions."""

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from twolink import TwoLinkArm, arms, ik, trajectory, velocity  # noqa: E402
from twolink_course import alttext  # noqa: E402
from twolink_course.explorers import ch3  # noqa: E402

FIVE_DEGREES = st.integers(-36, 36).map(lambda n: 5 * n)


@pytest.fixture(scope="module")
def view():
    return ch3.VelocityEllipse(arms.osake, scale=0.4)


@settings(max_examples=50, deadline=None)
@given(q1=FIVE_DEGREES, q2=FIVE_DEGREES)
def test_a_move_puts_the_arm_and_its_ellipse_at_the_angles_in_degrees(view, q1, q2):
    view.update(q1=q1, q2=q2)
    q = np.radians([q1, q2])
    assert np.allclose(view.arm_line.get_xydata(), arms.osake.joint_positions(q))
    ellipse = velocity.velocity_ellipse(arms.osake, q)
    sentence = view.describe(q1=q1, q2=q2)
    assert sentence.startswith(f"The OSAKE arm at q = ({q1}°, {q2}°)")
    if q2 % 180 == 0:
        assert "a singular pose" in sentence and "w is 0" in sentence
    else:
        w = 1e4 * float(arms.osake.manipulability(q))
        assert f"w = {w:.1f} cm²" in sentence
        sigma_1, sigma_2 = ellipse.semi_axes
        assert f"σ1 = {sigma_1:.3f}" in view.ax.get_title()
        assert np.isclose(sigma_1 * sigma_2, abs(np.linalg.det(arms.osake.jacobian(q))))


def test_the_scale_is_stated_under_the_axes_and_the_limits_never_move(view):
    assert "0.4 m per m/s" in view.ax.get_xlabel()
    limits = view.ax.get_xlim(), view.ax.get_ylim()
    for q2 in (0, 90, 180):
        view.update(q1=30, q2=q2)
    assert (view.ax.get_xlim(), view.ax.get_ylim()) == limits


def test_the_line_rates_figure_says_what_it_draws():
    fig, ax = plt.subplots()
    try:
        x = np.linspace(0.1, 1.0, 5)
        rates = np.column_stack([x, -x])
        ch3.draw_line_rates(x, rates, x[::2], rates[::2], 1.4, ax=ax)
        said = alttext.describe(fig)
        assert "q̇1 from 0.100°/s at x = 0.1 m to 1.00°/s at x = 1.000 m" in said
        assert "at the table's 3 rows" in said and "x = 1.400 m" in said
        assert ax.get_ylabel() == "joint rate [deg/s]"
    finally:
        plt.close(fig)


def test_the_manipulability_map_peaks_at_l1_l2_on_its_circle():
    fig, ax = plt.subplots()
    try:
        arm = TwoLinkArm(0.3, 0.2)
        largest = ch3.draw_manipulability_map(arm, ax=ax, points=101)
        assert largest <= arm.l1 * arm.l2 and np.isclose(
            largest, arm.l1 * arm.l2, rtol=1e-2
        )
        said = alttext.describe(fig)
        assert "dotted circle of radius 360.6 mm" in said and "w [cm²]" in said
    finally:
        plt.close(fig)


def test_the_circle_arrows_are_tangent_and_say_which_way_they_turn():
    fig, ax = plt.subplots()
    try:
        q = np.column_stack([np.radians(np.arange(0, 360, 60)), np.full(6, 1.0)])
        ch3.draw_circle_velocities(arms.osake, q, [-0.1, 0.0], 4.0, ax=ax)
        (arrows,) = [c for c in ax.collections if hasattr(c, "U")]
        tips, velocities = arrows.get_offsets(), np.column_stack([arrows.U, arrows.V])
        assert np.allclose(np.sum(tips * velocities, axis=1), 0.0, atol=1e-12)
        assert "clockwise" in alttext.describe(
            fig
        ) and "counter-" not in alttext.describe(fig)
    finally:
        plt.close(fig)


@pytest.fixture(scope="module")
def motions():
    arm = arms.two_metre
    q0 = ik.closed_form(arm, [-1.5, 0.05], elbow="down").q
    line = trajectory.LinePath(arm.fk(q0), [1.5, 0.05], 3.0, law="linear")
    return [
        trajectory.resolved_rate_trajectory(arm, line, n=101, q0=q0, damping=damping)
        for damping in (0.0, 0.2)
    ]


def test_the_two_motions_are_drawn_and_described(motions):
    fig, axes = plt.subplots(1, 2)
    try:
        ch3.draw_rates_and_tracking(motions, ["exact", "DLS"], axes)
        said = alttext.describe(fig)
        peak = np.abs(motions[0].qd[:, 0]).max()
        assert f"q̇1, exact: largest magnitude {peak:.1f} rad/s" in said
        assert len(axes[0].get_lines()) == 4 and len(axes[1].get_lines()) == 2
    finally:
        plt.close(fig)
    fig, axes = plt.subplots(1, 2)
    try:
        line = ([-1.5, 0.05], [1.5, 0.05])
        ch3.draw_motion_strobes(
            arms.two_metre, motions, ["a", "b"], line, axes, extent=2.6
        )
        said = alttext.describe(fig)
        assert "elbow up (sin q2 < 0)" in said and "The tip's path" in said
        assert axes[0].get_xlim() == (-2.6, 2.6)
    finally:
        plt.close(fig)


def test_motions_need_a_name_each():
    with pytest.raises(ValueError, match="one name per motion"):
        ch3.draw_rates_and_tracking([], ["a"], (None, None))
