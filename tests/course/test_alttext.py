"""twolink_course.alttext: every drawing function says what it drew, from its data, and a move says it anew."""

import gc
import re
import weakref

import matplotlib.pyplot as plt
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from twolink import TwoLinkArm, arms, statics, velocity
from twolink.errors import InputTypeError
from twolink_course import alttext, figure_style, plot

ARM = arms.two_metre
NUMBER = re.compile(r"-?\d+(?:\.\d+)?")


@pytest.fixture(autouse=True)
def close_figures():
    yield
    plt.close("all")


def _numbers(text):
    return [float(number) for number in NUMBER.findall(text)]


# ------------------------------------------------------------------ each drawing function

SENTENCES = {
    "draw_reach": (
        lambda ax: plot.draw_reach(TwoLinkArm(2.0, 1.5), ax=ax),
        "The reach: an annulus from 0.50 to 3.50 m.",
    ),
    "draw_arm": (
        lambda ax: plot.draw_arm(ARM, np.radians([30.0, 45.0]), ax=ax),
        "The arm at q = (30°, 45°), tip at (2.25, 2.93) m.",
    ),
    "draw_strobe": (
        lambda ax: plot.draw_strobe(
            ARM, np.linspace([0.0, 0.0], [np.pi / 2, 0.0], 9), ax=ax, frames=3
        ),
        "The arm at 3 instants of a motion from q = (0°, 0°) to (90°, 0°), fading in; "
        "the tip's path from (4.00, 0.00) m to (0.00, 4.00) m.",
    ),
    "draw_ellipse": (
        lambda ax: plot.draw_ellipse(
            velocity.Ellipse(np.array([1.0, 2.0]), np.array([2.0, 1.0]), np.eye(2)),
            ax=ax,
            scale=0.5,
        ),
        "An ellipse centred at (1.00, 2.00) m, semi-axes 1.00 and 0.50 m as drawn, "
        "the major one at 0° from the x-axis.",
    ),
    "draw_force": (
        lambda ax: plot.draw_force([1.0, 1.0], [0.0, -100.0], 0.01, ax=ax, at="head"),
        "A force of 100 N pointing at -90° from the x-axis, onto (1.00, 1.00) m.",
    ),
    "draw_torque": (
        lambda ax: plot.draw_torque([0.0, 0.0], -5.0, 0.5, ax=ax),
        "A torque of 5.00 N m, clockwise, about (0.00, 0.00) m.",
    ),
    "draw_wall": (
        lambda ax: plot.draw_wall(statics.Wall([3.0, 0.0], [1.0, 0.0]), 2.0, ax=ax),
        "A wall 3.00 m from the base, its point nearest the base at (3.00, 0.00) m, "
        "drawn 4.00 m long and hatched on its far side.",
    ),
    "plot_time_series": (
        lambda ax: plot.plot_time_series(
            np.linspace(0.0, 5.0, 11),
            np.zeros((11, 3)),
            "energy",
            "J",
            ["T", "V", "E"],
            ax=ax,
        ),
        "Time series of energy [J] over 0-5 s: T, V and E. Legend: T, V, E.",
    ),
    "draw_note": (
        lambda ax: plot.draw_note("w = 0.5 m²\nellipse at 0.4 m per m/s", ax=ax),
        'A note: "w = 0.5 m²; ellipse at 0.4 m per m/s".',
    ),
}


@pytest.mark.parametrize("name", sorted(SENTENCES))
def test_each_drawing_function_records_what_it_drew(name):
    draw, sentence = SENTENCES[name]
    figure, ax = plt.subplots()
    ax.set_axis_off()
    draw(ax)
    assert alttext.describe(figure) == sentence


def test_every_drawing_function_of_plot_is_covered_here():
    drawing = {name for name in plot.__all__ if name.startswith(("draw_", "plot_"))}
    assert drawing == set(SENTENCES)


def test_parts_of_a_drawing_are_not_counted_again():
    """An arm's base marker, a wall's hatch marks, a strobe's poses: said once."""
    figure, ax = plt.subplots()
    plot.draw_arm(ARM, [0.3, 1.0], ax=ax)
    plot.draw_wall(statics.Wall([3.0, 0.0], [1.0, 0.0]), 2.0, ax=ax)
    plot.draw_strobe(ARM, np.zeros((5, 2)), ax=ax)
    assert "It shows" not in alttext.describe(figure)


def test_an_animation_says_its_frames_times_and_path():
    anim = plot.animate_arm(
        ARM, np.linspace([0.0, 0.0], [np.pi / 2, 0.0], 5), np.linspace(0.0, 2.0, 5)
    )
    text = alttext.describe(anim._fig)
    assert text.startswith(
        "An animation of the arm in 5 frames, from q = (0°, 0°) to (90°, 0°), over 0-2 s, "
        "tracing the tip's path from (4.00, 0.00) m to (0.00, 4.00) m."
    )


# ------------------------------------------------------------------ moves keep it true


@settings(max_examples=40, deadline=None)
@given(
    q_start=st.tuples(st.floats(-3.0, 3.0), st.floats(-3.0, 3.0)),
    q_end=st.tuples(st.floats(-3.0, 3.0), st.floats(-3.0, 3.0)),
)
def test_a_moved_arm_says_what_a_fresh_one_says(q_start, q_end):
    figure = Figure()
    ax = figure.subplots()
    line = plot.draw_arm(ARM, q_start, ax=ax, label="elbow down")
    plot.move_arm(line, ARM, q_end)
    fresh = Figure().subplots()
    plot.draw_arm(ARM, q_end, ax=fresh, label="elbow down")
    assert alttext.recorded(line) == alttext.describe(fresh.figure).split(" Axes:")[0]


@settings(max_examples=40, deadline=None)
@given(q=st.tuples(st.floats(-3.0, 3.0), st.floats(-3.0, 3.0)))
def test_the_arm_sentence_holds_the_angles_and_tip_to_their_rounding(q):
    ax = Figure().subplots()
    line = plot.draw_arm(ARM, q, ax=ax)
    q1_deg, q2_deg, x, y = _numbers(alttext.recorded(line))
    assert np.allclose([q1_deg, q2_deg], np.degrees(q), atol=0.05 + 1e-9)
    assert np.allclose([x, y], ARM.fk(q), atol=0.005 + 1e-9)


def test_move_strobe_and_move_ellipse_say_the_new_data():
    ax = Figure().subplots()
    lines = plot.draw_strobe(ARM, np.zeros((10, 2)), ax=ax, frames=4)
    plot.move_strobe(lines, ARM, np.linspace([0.0, 0.0], [np.pi / 2, 0.0], 10))
    assert "to (90°, 0°)" in alttext.recorded(lines[0])
    assert "to (0.00, 4.00) m" in alttext.recorded(lines[0])
    drawn = plot.draw_ellipse(velocity.velocity_ellipse(ARM, [0.3, 1.2]), ax=ax)
    target = velocity.velocity_ellipse(ARM, [1.0, 0.4])
    plot.move_ellipse(drawn, target)
    fresh = Figure().subplots()
    plot.draw_ellipse(target, ax=fresh)
    assert alttext.recorded(drawn[0]) == alttext.recorded(fresh.patches[0])


def test_a_clipped_ellipse_says_so():
    ax = Figure().subplots()
    fill, _ = plot.draw_ellipse(
        velocity.Ellipse(np.zeros(2), np.array([np.inf, 1.0]), np.eye(2)),
        ax=ax,
        clip=2.0,
    )
    assert "semi-axes 2.00 (clipped) and 1.00 m" in alttext.recorded(fill)


# ------------------------------------------------------------------ any figure


def test_a_plain_matplotlib_figure_gets_a_useful_fallback():
    figure, axes = plt.subplots(1, 2)
    figure.suptitle("Two views")
    axes[0].plot([0.0, 1.0], [0.0, 1.0], label="reference")
    axes[0].plot([0.0, 1.0], [1.0, 0.0])
    axes[0].plot([0.5], [0.5], "kx")
    axes[0].set_xlabel("t [s]")
    axes[0].set_ylabel("q [rad]")
    axes[0].set_title("Joint 1")
    axes[0].legend()
    axes[1].imshow(np.zeros((3, 3)))
    axes[1].set_yscale("symlog")
    text = alttext.describe(figure)
    assert text.startswith(
        "Two views. Panel 1 of 2: Joint 1. It shows the point (0.5, 0.5)"
    )
    assert "the line reference and one line more" in text
    assert "Axes: t [s] from -0.05 to 1.05, q [rad] from -0.05 to 1.05." in text
    assert "Legend: reference." in text
    assert "Panel 2 of 2: It shows one image." in text and "(symlog scale)" in text


def test_sentences_go_with_their_artists():
    """The record keeps no artist alive: a deleted artist's sentence is gone."""
    line = Line2D([0.0], [0.0])
    alttext.record(line, "A point")
    assert alttext.recorded(line) == "A point."
    alive = weakref.ref(line)
    del line
    gc.collect()
    assert alive() is None
    assert all(key() is not None for key in alttext._SENTENCES.keyrefs())


def test_nothing_is_set_on_the_artist():
    line = Line2D([0.0], [0.0])
    before = set(vars(line))
    alttext.record(line, "A point")
    assert set(vars(line)) == before


def test_bad_input_is_refused_with_what_is_allowed():
    with pytest.raises(InputTypeError, match="artist must be a matplotlib Artist"):
        alttext.record("line", "A line")
    with pytest.raises(InputTypeError, match="sentence must be a non-empty string"):
        alttext.record(Line2D([0], [0]), "  ")
    with pytest.raises(InputTypeError, match="figure must be a matplotlib Figure"):
        alttext.describe(plt.gca())


@settings(max_examples=60)
@given(value=st.floats(-1e6, 1e6), noise=st.floats(-1e-12, 1e-12))
def test_numbers_are_rounded_far_above_round_off(value, noise):
    """A change at round-off level changes the text only at a rounding tie."""
    shown, nudged = (
        alttext.point_text([value, 0.0]),
        alttext.point_text([value * (1 + noise), 0.0]),
    )
    tie = abs(abs(value * 100) % 1 - 0.5) < 1e-6
    assert shown == nudged or tie
    assert "-0.00" not in alttext.point_text([-1e-17, 1e-17])


def test_the_style_and_the_sentences_meet_in_the_legend():
    figure, ax = plt.subplots()
    plot.draw_arm(ARM, [0.3, 1.0], ax=ax, label="elbow down")
    plot.draw_arm(ARM, [1.3, -1.0], ax=ax, label="elbow up", role=figure_style.ELBOW_UP)
    ax.legend()
    text = alttext.describe(figure)
    assert "The arm (elbow down) at" in text and "The arm (elbow up) at" in text
    assert text.endswith("Legend: elbow down, elbow up.")


def test_a_colour_bar_is_its_panels_colour_scale_and_log_limits_keep_their_digits():
    from matplotlib.colors import LogNorm
    from matplotlib.figure import Figure

    figure = Figure()
    left, right = figure.subplots(1, 2)
    image = left.imshow(np.logspace(-2.0, 1.5, 100).reshape(10, 10), norm=LogNorm())
    figure.colorbar(image, ax=left, label="tip error [m]")
    right.semilogy([0.0, 1.0], [0.012, 35.0])
    text = alttext.describe(figure)
    assert "Panel 3" not in text and text.count("Panel ") == 2
    first_panel = text.split("Panel 2 of 2")[0]
    assert "Colour scale: tip error [m] from 0.01 to 31.6 (log scale)." in first_panel
    assert (
        "vertical axis from 0.00805 to 52.2 (log scale)" in text
    )  # not "from 0 to 52"


def test_an_arm_labelled_with_its_angles_is_not_told_them_twice():
    from twolink import arms
    from twolink_course import plot

    ax = plot.setup_axes(arms.ten)
    q = np.radians([120.7, 51.3])
    plot.draw_arm(arms.ten, q, ax=ax, label="down: (120.7°, 51.3°)")
    plot.draw_arm(arms.ten, q, ax=ax, label="down")
    text = alttext.describe(ax.figure)
    assert "The arm (down: (120.7°, 51.3°)), tip at (-15.01, 9.99) m" in text
    assert "The arm (down) at q = (120.7°, 51.3°), tip at (-15.01, 9.99) m" in text
    plt.close(ax.figure)


def test_an_arm_label_with_other_numbers_keeps_the_angles():
    from twolink import arms
    from twolink_course import plot

    ax = plot.setup_axes(arms.ten)
    plot.draw_arm(
        arms.ten, np.radians([0.0, 90.0]), ax=ax, label="q2 = 90°: 1/σ2 = 0.81"
    )
    assert "at q = (0°, 90°)" in alttext.describe(
        ax.figure
    )  # "0" is not a number of the label
    plt.close(ax.figure)


def test_legend_entries_with_commas_are_told_apart_by_semicolons():
    figure = Figure()
    ax = figure.subplots()
    ax.plot([0, 1], [0, 1], label="q1, linear law")
    ax.plot([0, 1], [1, 0], label="q2")
    ax.legend()
    assert "Legend: q1, linear law; q2." in alttext.describe(figure)
