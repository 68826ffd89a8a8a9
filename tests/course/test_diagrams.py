"""The DH-frames diagram and the free-body diagrams: what they draw is the arm's own geometry and a balanced load."""

import re

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from matplotlib.patches import FancyArrowPatch

from twolink import TwoLinkArm
from twolink.errors import InputTypeError
from twolink_course import alttext, diagrams

angles = st.floats(-np.pi, np.pi, allow_nan=False)
lengths = st.floats(0.2, 3.0, allow_nan=False)
forces = st.floats(-500.0, 500.0, allow_nan=False)


@pytest.fixture(autouse=True)
def close_figures():
    yield
    plt.close("all")


def straight_arrows(ax):
    """(tail, head) of every straight arrow on the axes (forces, frame axes)."""
    return [
        tuple(np.array(end, dtype=float) for end in patch._posA_posB)
        for patch in ax.patches
        if isinstance(patch, FancyArrowPatch) and patch._posA_posB is not None
    ]


@settings(max_examples=25, deadline=None)
@given(lengths, lengths, angles, angles)
def test_each_x_axis_starts_at_its_frame_and_points_along_its_link(l1, l2, q1, q2):
    arm = TwoLinkArm(l1, l2)
    ax = diagrams.draw_dh_frames(arm, [q1, q2])
    origins = arm.joint_positions([q1, q2])
    directions = [0.0, q1, q1 + q2]
    arrows = straight_arrows(ax)
    assert len(arrows) == 3
    for (tail, head), origin, angle in zip(arrows, origins, directions):
        assert np.allclose(tail, origin)
        along = (head - tail) / np.linalg.norm(head - tail)
        assert np.allclose(along, [np.cos(angle), np.sin(angle)], atol=1e-9)
    labels = [text.get_text() for text in ax.texts]
    for name in (
        "x_0",
        "x_1",
        "x_2",
        "z_0",
        "z_1",
        "z_2",
        "a_1",
        "a_2",
        "theta_1",
        "theta_2",
    ):
        assert any(name in label for label in labels), f"no label {name}"
    xlim, ylim = ax.get_xlim(), ax.get_ylim()
    for point in origins:
        assert xlim[0] < point[0] < xlim[1] and ylim[0] < point[1] < ylim[1]
    plt.close(ax.figure)


def test_the_dh_diagram_says_where_each_frame_is():
    arm = TwoLinkArm(2.0, 1.5)
    q = np.radians([30.0, -60.0])
    ax = diagrams.draw_dh_frames(arm, q)
    text = alttext.describe(ax.figure)
    assert alttext.point_text(arm.joint_positions(q)[1]) in text
    assert alttext.point_text(arm.fk(q)) in text
    assert "θ1 = 30° from x0" in text and "θ2 = -60° from x1" in text
    assert "a1 = 2.00 m and a2 = 1.50 m" in text


def _torque_values(ax):
    found = {}
    for text in ax.texts:
        match = re.match(r"\$(-?)\\tau_(\d)\$ = (\S+) N m", text.get_text())
        if match:
            found[match.group(1) + match.group(2)] = float(match.group(3))
    return found


def _cross(r, f):
    return r[0] * f[1] - r[1] * f[0]


@settings(max_examples=25, deadline=None)
@given(lengths, lengths, angles, angles, forces, forces)
def test_each_free_body_is_in_balance(l1, l2, q1, q2, fx, fy):
    arm = TwoLinkArm(l1, l2)
    force_by_tip = np.array([fx, fy])
    link_1, link_2 = diagrams.draw_free_bodies(arm, [q1, q2], force_by_tip)
    tau = arm.joint_torques([q1, q2], force_by_tip)
    magnitude = np.hypot(fx, fy)
    for ax, torques in ((link_1, tau[0] - tau[1]), (link_2, tau[1])):
        arrows = straight_arrows(ax)
        assert len(arrows) == 2
        vectors = [head - tail for tail, head in arrows]
        # drawn to one scale: the forces on each link add up to zero
        assert np.allclose(
            vectors[0] + vectors[1], 0.0, atol=1e-9 * max(1.0, magnitude)
        )
        if magnitude > 1e-6:
            scale = np.linalg.norm(vectors[0]) / magnitude
            moment = sum(
                _cross(tail, v / scale) for (tail, _), v in zip(arrows, vectors)
            )
            # the motor torques on the link cancel the forces' moment about the origin
            assert moment + torques == pytest.approx(
                0.0, abs=1e-6 * max(1.0, magnitude)
            )
    labelled = {**_torque_values(link_1), **_torque_values(link_2)}
    assert labelled.keys() == {"1", "-2", "2"}
    for key, value in (("1", tau[0]), ("2", tau[1]), ("-2", -tau[1])):
        assert labelled[key] == pytest.approx(
            value, rel=5e-3, abs=1e-6 * max(1.0, magnitude)
        )
    plt.close(link_1.figure)


def test_the_free_bodies_draw_on_given_axes_and_describe_each_link():
    figure, (left, right) = plt.subplots(1, 2)
    arm = TwoLinkArm(2.0, 2.0)
    returned = diagrams.draw_free_bodies(
        arm, np.radians([20.0, 70.0]), [80.0, 60.0], axes=(left, right)
    )
    assert returned == (left, right)
    text = alttext.describe(figure)
    assert "Link 1 from the base (0.00, 0.00) m" in text
    assert "the wall pushes the tip with -F, 100 N at -143.1° from the x-axis" in text


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: diagrams.draw_dh_frames("arm", [0.0, 0.0]), "TwoLinkArm"),
        (lambda: diagrams.draw_dh_frames(TwoLinkArm(1.0, 1.0), [0.0]), "q"),
        (
            lambda: diagrams.draw_dh_frames(
                TwoLinkArm(1.0, 1.0), [0.0, 0.0], ax="axes"
            ),
            "ax must be",
        ),
        (
            lambda: diagrams.draw_free_bodies(
                TwoLinkArm(1.0, 1.0), [0.0, 0.0], [np.nan, 1.0]
            ),
            "force_by_tip",
        ),
        (
            lambda: diagrams.draw_free_bodies(
                TwoLinkArm(1.0, 1.0), [0.0, 0.0], [1.0, 1.0], axes="ax"
            ),
            "pair",
        ),
    ],
)
def test_bad_input_is_refused_with_a_message_naming_it(call, message):
    with pytest.raises((InputTypeError, ValueError, TypeError), match=message):
        call()
