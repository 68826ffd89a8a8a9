"""twolink_course.plot: every drawing function takes ``ax`` the same way, labels its axes "quantity [unit]", draws what it says."""

import gc
import inspect
import re
import warnings

import matplotlib
import matplotlib.pyplot as plt
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from matplotlib.axes import Axes
from matplotlib.lines import Line2D
from matplotlib.patches import Circle, FancyArrowPatch

from twolink import TwoLinkArm, arms, simulate, statics, velocity
from twolink.errors import InputTypeError
from twolink_course import plot

LABEL_WITH_UNIT = re.compile(
    r"\S.*\[[^\]]+\]"
)  # the rule of tests/notebooks/test_figures.py: "x [m]", "joint rate [rad/s]"

ARM = arms.two_metre
Q_PATH = np.linspace([0.0, 0.3], [1.0, 1.5], 12)
T_PATH = np.linspace(0.0, 1.1, 12)


@pytest.fixture(autouse=True)
def close_figures():
    yield
    plt.close("all")


def _artists(result):
    return list(result) if isinstance(result, list) else [result]


# Every function that draws onto existing axes, called with its other arguments; ``options`` carries ax.
DRAWERS = {
    "draw_reach": lambda **options: plot.draw_reach(ARM, **options),
    "draw_arm": lambda **options: plot.draw_arm(ARM, [0.3, 1.0], **options),
    "draw_strobe": lambda **options: plot.draw_strobe(ARM, Q_PATH, frames=4, **options),
    "draw_ellipse": lambda **options: plot.draw_ellipse(
        velocity.velocity_ellipse(ARM, [0.3, 1.0]), scale=0.5, **options
    ),
    "draw_force": lambda **options: plot.draw_force(
        [1.0, 1.0], [100.0, 0.0], 0.01, **options
    ),
    "draw_torque": lambda **options: plot.draw_torque([0.0, 0.0], 5.0, 0.5, **options),
    "draw_wall": lambda **options: plot.draw_wall(
        statics.Wall.through([4.0, 0.0], [0.0, 4.0]), 3.0, **options
    ),
    "plot_time_series": lambda **options: plot.plot_time_series(
        T_PATH, Q_PATH, "joint angle", "rad", ["q1", "q2"], **options
    ),
    "draw_note": lambda **options: plot.draw_note("1 N drawn as 2 m", **options),
}
# Functions that make axes of their own when ax is None (a new figure).
SETTERS = {
    "setup_axes": lambda **options: plot.setup_axes(ARM, **options),
    "animate_arm": lambda **options: plot.animate_arm(ARM, Q_PATH, T_PATH, **options),
    "animate_simulation": lambda **options: plot.animate_simulation(
        simulate(ARM, [0.3, 0.0], [0.0, 0.0], 0.5, t_eval=np.linspace(0.0, 0.5, 11)),
        max_frames=5,
        **options,
    ),
}
NOT_DRAWING = {"animation_html"}  # shows an animation; takes no axes
# move what a drawing function returned (for explorers); they take its artists, not axes
MOVERS = {"move_arm", "move_strobe", "move_ellipse"}


def _axes_of(name, result):
    if name.startswith("animate"):
        return result._fig.axes[0]
    if name == "setup_axes":
        return result
    return None


def test_every_public_function_is_covered_here():
    assert set(plot.__all__) == set(DRAWERS) | set(SETTERS) | NOT_DRAWING | MOVERS


@pytest.mark.parametrize("name", sorted(set(plot.__all__) - NOT_DRAWING - MOVERS))
def test_ax_is_keyword_only_first_after_the_star_and_defaults_to_none(name):
    parameters = inspect.signature(getattr(plot, name)).parameters.values()
    keyword_only = [
        parameter
        for parameter in parameters
        if parameter.kind is inspect.Parameter.KEYWORD_ONLY
    ]
    assert keyword_only, f"{name} has no keyword-only parameters"
    first = keyword_only[0]
    assert (first.name, first.default, first.annotation) == ("ax", None, "Axes | None")


@pytest.mark.parametrize("name", sorted(plot.__all__))
def test_every_public_function_is_fully_annotated(name):
    signature = inspect.signature(getattr(plot, name))
    missing = [
        p.name
        for p in signature.parameters.values()
        if p.annotation is inspect.Parameter.empty
    ]
    assert not missing and signature.return_annotation is not inspect.Signature.empty, (
        name,
        missing,
    )


@pytest.mark.parametrize("name", sorted(DRAWERS))
def test_draws_on_the_given_axes_and_leaves_the_current_ones_alone(name):
    _, ax_given = plt.subplots()
    _, ax_current = plt.subplots()  # made last: plt.gca() is this one
    assert plt.gca() is ax_current
    artists = _artists(DRAWERS[name](ax=ax_given))
    assert artists and all(artist.axes is ax_given for artist in artists)
    assert not ax_current.lines and not ax_current.patches and not ax_current.texts
    assert plt.gca() is ax_current


@pytest.mark.parametrize("name", sorted(DRAWERS))
def test_draws_on_the_current_axes_when_no_ax_is_given(name):
    _, ax_other = plt.subplots()
    _, ax_current = plt.subplots()
    figures = plt.get_fignums()
    artists = _artists(DRAWERS[name]())
    assert artists and all(artist.axes is ax_current for artist in artists)
    assert not ax_other.lines and not ax_other.patches
    assert plt.get_fignums() == figures  # no new figure


@pytest.mark.parametrize("name", sorted(SETTERS))
def test_setters_use_the_given_axes(name):
    _, ax_given = plt.subplots()
    figures = plt.get_fignums()
    result = SETTERS[name](ax=ax_given)
    assert _axes_of(name, result) is ax_given
    assert plt.get_fignums() == figures


@pytest.mark.parametrize("name", sorted(SETTERS))
def test_setters_make_a_new_square_figure_when_no_ax_is_given(name):
    _, ax_current = plt.subplots()
    figures = set(plt.get_fignums())
    ax = _axes_of(name, SETTERS[name]())
    assert ax is not ax_current and ax.figure.number not in figures
    assert tuple(ax.figure.get_size_inches()) == (4.0, 4.0)
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("x [m]", "y [m]")


@pytest.mark.parametrize("name", sorted(DRAWERS))
def test_refuses_an_ax_that_is_not_axes(name):
    figure, _ = plt.subplots()
    with pytest.raises(InputTypeError, match=r"ax must be a matplotlib Axes \(or None"):
        DRAWERS[name](ax=figure)


@pytest.mark.parametrize(
    "call",
    [
        lambda ax: plot.draw_arm(ARM, [0.3, 1.0], ax),
        lambda ax: plot.draw_reach(ARM, ax),
        lambda ax: plot.draw_force(ax, [1.0, 1.0], [100.0, 0.0], scale=0.01),
        lambda ax: plot.draw_torque(ax, [0.0, 0.0], 5.0, radius=0.5),
        lambda ax: plot.draw_wall(
            statics.Wall.through([4.0, 0.0], [0.0, 4.0]), ax, half_length=3.0
        ),
        lambda ax: plot.draw_ellipse(
            velocity.velocity_ellipse(ARM, [0.3, 1.0]), ax, scale=0.5
        ),
        lambda ax: plot.setup_axes(ARM, ax),
    ],
)
def test_the_old_positional_ax_fails_loudly(call):
    _, ax = plt.subplots()
    with pytest.raises(TypeError):
        call(ax)


@pytest.mark.parametrize("name", sorted(set(SETTERS) | {"plot_time_series"}))
def test_axis_labels_state_quantity_and_unit(name):
    _, ax_given = plt.subplots()
    (SETTERS.get(name) or DRAWERS[name])(ax=ax_given)
    for label in (ax_given.get_xlabel(), ax_given.get_ylabel()):
        assert LABEL_WITH_UNIT.match(label), label


# ------------------------------------------------------------------ what each one draws


def test_setup_axes_fits_the_reach_with_its_margin():
    ax = plot.setup_axes(TwoLinkArm(2.0, 1.0), margin=0.5, title="t")
    assert ax.get_xlim() == pytest.approx(
        (-4.5, 4.5)
    ) and ax.get_ylim() == pytest.approx((-4.5, 4.5))
    assert ax.get_title() == "t"


def test_draw_reach_skips_a_zero_inner_radius():
    assert [circle.radius for circle in plot.draw_reach(TwoLinkArm(1.0, 1.0))] == [2.0]
    assert [
        circle.radius for circle in plot.draw_reach(TwoLinkArm(3.0, 1.0), color="k")
    ] == [2.0, 4.0]


def test_draw_arm_goes_through_base_elbow_and_tip():
    line = plot.draw_arm(ARM, [0.3, 1.0])
    assert np.allclose(line.get_xydata(), ARM.joint_positions([0.3, 1.0]))
    with pytest.raises(
        ValueError, match=r"q must be one configuration of shape \(2,\)"
    ):
        plot.draw_arm(ARM, Q_PATH)


def test_draw_strobe_draws_the_first_and_last_pose_and_the_tip_path():
    lines = plot.draw_strobe(ARM, Q_PATH, frames=3)
    assert len(lines) == 4
    assert np.allclose(lines[0].get_xydata(), ARM.joint_positions(Q_PATH[0]))
    assert np.allclose(lines[2].get_xydata(), ARM.joint_positions(Q_PATH[-1]))
    assert np.allclose(lines[3].get_xydata(), ARM.fk(Q_PATH))
    assert len(plot.draw_strobe(ARM, Q_PATH, frames=3, path=False)) == 3
    with pytest.raises(ValueError, match=r"q_path must have shape \(n, 2\)"):
        plot.draw_strobe(ARM, [0.3, 1.0])


def test_animate_arm_shows_the_time_of_each_frame():
    anim = plot.animate_arm(ARM, Q_PATH, T_PATH)
    anim._func(len(Q_PATH) - 1)
    assert "t = 1.10 s" in [text.get_text() for text in anim._fig.axes[0].texts]
    with pytest.raises(ValueError, match=r"t must have shape \(12,\)"):
        plot.animate_arm(ARM, Q_PATH, T_PATH[:-1])


def test_ellipse_centre_is_the_tip_and_draw_ellipse_draws_one():
    ellipse = velocity.velocity_ellipse(ARM, [0.3, 1.0])
    assert np.allclose(ellipse.centre, ARM.fk([0.3, 1.0]))
    assert not hasattr(ellipse, "center")
    fill, outline = plot.draw_ellipse(ellipse, scale=0.5)
    assert np.allclose(outline.get_xydata(), ellipse.points(scale=0.5))
    assert np.allclose(fill.get_xy(), ellipse.points(scale=0.5))
    batch = velocity.velocity_ellipse(ARM, Q_PATH)
    with pytest.raises(ValueError, match=r"one ellipse \(centre of shape \(2,\)\)"):
        plot.draw_ellipse(batch)


@settings(max_examples=30)
@given(
    point=st.tuples(st.floats(-5, 5), st.floats(-5, 5)),
    force=st.tuples(st.floats(-500, 500), st.floats(-500, 500)),
    scale=st.floats(1e-4, 1e-1),
)
def test_draw_force_arrow_is_scale_times_the_force_at_its_tail_or_head(
    point, force, scale
):
    _, ax = plt.subplots()
    tail, head = plot.draw_force(point, force, scale, ax=ax)._posA_posB
    assert np.allclose(tail, point) and np.allclose(
        np.subtract(head, tail), scale * np.array(force), atol=1e-12
    )
    tail, head = plot.draw_force(point, force, scale, ax=ax, at="head")._posA_posB
    assert np.allclose(head, point) and np.allclose(
        np.subtract(head, tail), scale * np.array(force), atol=1e-12
    )
    plt.close(ax.figure)


def test_draw_force_refuses_bad_input():
    with pytest.raises(ValueError, match="at must be 'tail' or 'head'"):
        plot.draw_force([0.0, 0.0], [1.0, 0.0], 0.1, at="middle")
    with pytest.raises(ValueError, match="scale"):
        plot.draw_force([0.0, 0.0], [1.0, 0.0], 0.0)
    with pytest.raises(
        ValueError,
        match=r"vector must be one force \(Fx, Fy\) of shape \(2,\) \(newtons\)",
    ):
        plot.draw_force([0.0, 0.0], [[1.0, 0.0]], 0.1)


@pytest.mark.parametrize("tau, turning", [(5.0, 1.0), (-5.0, -1.0)])
def test_draw_torque_turns_with_the_sign_of_tau_around_the_centre(tau, turning):
    arrow = plot.draw_torque([1.0, 2.0], tau, 0.5, start=0.3)
    vertices = arrow._path_original.vertices - [
        1.0,
        2.0,
    ]  # the arc given, before the head is added
    assert np.allclose(np.hypot(vertices[:, 0], vertices[:, 1]), 0.5)
    angles = np.unwrap(np.arctan2(vertices[:, 1], vertices[:, 0]))
    assert angles[0] == pytest.approx(0.3)
    assert np.sign(angles[-1] - angles[0]) == turning and abs(
        angles[-1] - angles[0]
    ) == pytest.approx(1.5 * np.pi)


def test_draw_torque_without_torque_is_a_dotted_circle():
    circle = plot.draw_torque([1.0, 2.0], 1e-12, 0.5)
    assert (
        isinstance(circle, Circle)
        and circle.center == (1.0, 2.0)
        and circle.radius == 0.25
    )
    assert isinstance(
        plot.draw_torque([1.0, 2.0], 1e-6, 0.5, zero_tol=1e-9), FancyArrowPatch
    )
    with pytest.raises(ValueError, match="radius"):
        plot.draw_torque([1.0, 2.0], 1.0, -0.5)


def test_draw_wall_hatches_the_side_away_from_the_base():
    wall = statics.Wall.through([4.0, 0.0], [0.0, 4.0])
    line, *hatches = plot.draw_wall(wall, 3.0)
    assert np.allclose(line.get_xydata().sum(axis=1), 4.0)
    assert hatches and all(wall.signed_distance(h.get_xydata()[1]) > 0 for h in hatches)


# ------------------------------------------------------------------ plot_time_series


def test_plot_time_series_one_line_per_column_with_labels_legend_and_grid():
    _, ax = plt.subplots()
    values = np.column_stack([np.sin(T_PATH), np.cos(T_PATH)])
    lines = plot.plot_time_series(
        T_PATH, values, "joint angle", "rad", ["q1", "q2"], ax=ax, colors=["C3", "k"]
    )
    assert [line.get_label() for line in lines] == ["q1", "q2"]
    assert [line.get_color() for line in lines] == ["C3", "k"]
    for column, line in enumerate(lines):
        assert np.array_equal(line.get_xdata(), T_PATH) and np.array_equal(
            line.get_ydata(), values[:, column]
        )
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("t [s]", "joint angle [rad]")
    assert [text.get_text() for text in ax.get_legend().get_texts()] == ["q1", "q2"]
    assert ax.xaxis.get_gridlines()[0].get_visible()


def test_plot_time_series_adds_a_second_run_to_the_same_legend():
    _, ax = plt.subplots()
    plot.plot_time_series(
        T_PATH, Q_PATH, "angle", "rad", ["q1, exact", "q2, exact"], ax=ax
    )
    dashed = plot.plot_time_series(
        T_PATH, 2 * Q_PATH, "angle", "rad", ["q1, DLS", "q2, DLS"], ax=ax, fmt="--"
    )
    assert all(line.get_linestyle() == "--" for line in dashed)
    assert len([text.get_text() for text in ax.get_legend().get_texts()]) == 4


def test_plot_time_series_one_column_no_labels_log_axis_and_line_options():
    _, ax = plt.subplots()
    (line,) = plot.plot_time_series(
        T_PATH, T_PATH + 1.0, "energy drift", "-", ax=ax, log=True, linewidth=0.5
    )
    assert (
        ax.get_legend() is None
        and ax.get_yscale() == "log"
        and line.get_linewidth() == 0.5
    )
    assert ax.get_ylabel() == "energy drift [-]"


@pytest.mark.parametrize(
    "arguments, message",
    [
        (
            (T_PATH, Q_PATH[:-1], "angle", "rad"),
            r"values must have shape \(12,\) or \(12, k\)",
        ),
        (
            (T_PATH, Q_PATH, "angle", "rad", ["q1"]),
            "labels must be a sequence of 2 strings",
        ),
        (
            (T_PATH, Q_PATH, "angle", "rad", "q1"),
            "labels must be a sequence of 2 strings",
        ),
        ((T_PATH, Q_PATH, "", "rad"), r"quantity must be a non-empty string"),
        ((T_PATH, Q_PATH, "angle", None), r"unit must be a non-empty string"),
        (
            (Q_PATH, Q_PATH, "angle", "rad"),
            r"t must be finite times in seconds of shape \(n,\)",
        ),
        (
            (np.where(T_PATH > 0.5, np.inf, T_PATH), Q_PATH, "angle", "rad"),
            r"t must be finite times",
        ),
    ],
)
def test_plot_time_series_refuses_what_it_cannot_label(arguments, message):
    with pytest.raises(ValueError, match=message):
        plot.plot_time_series(*arguments)


def test_plot_time_series_refuses_a_colour_per_line_mismatch():
    with pytest.raises(ValueError, match="colors must be a sequence of 2 colours"):
        plot.plot_time_series(T_PATH, Q_PATH, "angle", "rad", colors=["C0"])


# ------------------------------------------------------------------ draw_note


@pytest.mark.parametrize(
    "corner, position, alignment",
    [
        ("lower left", (0.03, 0.03), ("left", "bottom")),
        ("upper left", (0.03, 0.97), ("left", "top")),
        ("lower right", (0.97, 0.03), ("right", "bottom")),
        ("upper right", (0.97, 0.97), ("right", "top")),
    ],
)
def test_draw_note_sits_in_its_corner_in_axes_coordinates(corner, position, alignment):
    _, ax = plt.subplots()
    ax.set_xlim(-100, 100)
    note = plot.draw_note(
        "w = 0.5 m²\nellipse drawn at 0.4 m per m/s", ax=ax, corner=corner
    )
    assert note.get_position() == position and note.get_transform() == ax.transAxes
    assert (note.get_horizontalalignment(), note.get_verticalalignment()) == alignment
    assert note.get_bbox_patch() is not None and note in ax.texts


def test_draw_note_refuses_unknown_corners_and_non_text():
    with pytest.raises(ValueError, match="corner must be one of 'lower left'"):
        plot.draw_note("x", corner="middle")
    with pytest.raises(InputTypeError, match="text must be a string"):
        plot.draw_note(3.0)


def test_returned_types_are_the_documented_matplotlib_artists():
    assert isinstance(plot.setup_axes(ARM), Axes)
    assert isinstance(plot.draw_arm(ARM, [0.3, 1.0]), Line2D)
    assert all(
        isinstance(line, Line2D)
        for line in plot.draw_wall(statics.Wall([3.0, 0.0], [1.0, 0.0]), 1.0)
    )


@pytest.mark.parametrize("name", sorted(plot.__all__))
def test_parameters_use_the_package_vocabulary(name):
    parameters = inspect.signature(getattr(plot, name)).parameters
    assert not [p for p in parameters if "center" in p or p == "force"], list(
        parameters
    )


def test_move_ellipse_and_move_strobe_follow_draw_ellipse_and_draw_strobe():
    from twolink import velocity

    arm = arms.two_metre
    ax = plot.setup_axes(arm)
    drawn = plot.draw_ellipse(
        velocity.velocity_ellipse(arm, [0.3, 1.2]), ax=ax, scale=0.5
    )
    target = velocity.velocity_ellipse(arm, [1.0, 0.4])
    plot.move_ellipse(drawn, target, scale=0.5)
    fresh = plot.draw_ellipse(target, ax=ax, scale=0.5)
    assert np.allclose(drawn[0].get_xy(), fresh[0].get_xy())
    assert np.allclose(drawn[1].get_xydata(), fresh[1].get_xydata())
    with pytest.raises(InputTypeError, match="fill, outline"):
        plot.move_ellipse([drawn[1]], target)
    path = np.linspace([0.0, 0.0], [1.0, 2.0], 30)
    strobe = plot.draw_strobe(arm, np.zeros((30, 2)), ax=ax, frames=6)
    plot.move_strobe(strobe, arm, path)
    expected = plot.draw_strobe(arm, path, ax=ax, frames=6)
    for moved, drawn_line in zip(strobe, expected):
        assert np.allclose(moved.get_xydata(), drawn_line.get_xydata())
    short = np.zeros((3, 2))
    plot.move_strobe(strobe, arm, short)
    assert [line.get_visible() for line in strobe[:-1]] == [True] * 3 + [False] * 3
    with pytest.raises(InputTypeError, match="draw_strobe returned"):
        plot.move_strobe([], arm, path)
    plt.close(ax.figure)


def test_animation_html_draws_the_axes_once_and_makes_matplotlibs_video():
    # matplotlib's layout, whatever an earlier test left in rcParams
    with matplotlib.rc_context(
        {"figure.constrained_layout.use": False, "figure.autolayout": False}
    ):
        _check_animation_html_against_matplotlib()


def _check_animation_html_against_matplotlib():
    import imageio_ffmpeg
    from matplotlib import animation

    q_path = np.linspace([0.0, 0.0], [np.pi / 2, np.pi / 2], 6)

    def made(plain):
        anim = plot.animate_arm(arms.two_metre, q_path, t=np.linspace(0.0, 1.0, 6))
        if plain:  # the same frames as a FuncAnimation that does not say what moves
            anim = animation.FuncAnimation(
                anim._fig, anim._func, frames=6, interval=100.0
            )
        draws = []
        anim._fig.canvas.mpl_connect("draw_event", lambda event: draws.append(event))
        return anim, draws

    anim, draws = made(plain=False)
    video = plot.animation_html(anim).data
    assert "<video" in video and len(draws) == 1  # the axes once, then only what moves
    plain, plain_draws = made(plain=True)
    assert plot.animation_html(plain).data == video
    assert (
        len(plain_draws) == 6
    )  # each frame once (matplotlib's save alone draws twice)
    assert "draw_idle" not in vars(plain._fig.canvas)  # the canvas's own method again
    reference, reference_draws = made(plain=False)
    with matplotlib.rc_context(
        {"animation.ffmpeg_path": imageio_ffmpeg.get_ffmpeg_exe()}
    ):
        assert reference.to_html5_video(embed_limit=5.0) in video
    assert len(reference_draws) > len(plain_draws)
    plt.close("all")


def test_a_strobe_draws_the_base_once_over_its_poses():
    ax = plot.setup_axes(arms.two_metre)
    lines = plot.draw_strobe(
        arms.two_metre, np.linspace([0.0, 0.0], [1.0, 1.0], 20), ax=ax, frames=5
    )
    bases = [line for line in ax.lines if line.get_marker() == "s"]
    order = list(ax.lines)
    assert len(bases) == 1  # over every pose, under the tip's path as before
    assert all(order.index(pose) < order.index(bases[0]) for pose in lines[:-1])
    assert len(lines) == 6 and bases[0] not in lines
    plt.close(ax.figure)


def test_while_grading_animation_html_draws_no_frame_and_closes_the_figure(
    monkeypatch,
):
    anim = plot.animate_arm(ARM, Q_PATH, t=T_PATH)
    draws = []
    anim._fig.canvas.mpl_connect("draw_event", draws.append)

    def no_video(*args, **kwargs):
        raise AssertionError("a video was encoded while grading")

    monkeypatch.setattr(plot, "html5_video", no_video)
    monkeypatch.setenv("TWOLINK_GRADING", "1")
    gc.collect()  # earlier tests' animations warn when collected: not while recording
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        html = plot.animation_html(anim)._repr_html_()
        del anim
        gc.collect()
    # matplotlib warns of an animation deleted unrendered: not of this one
    assert [str(warning.message) for warning in caught] == []
    assert html == (
        "<p><em>twolink_course.plot.animation_html: animation skipped while grading "
        "(TWOLINK_GRADING=1).</em></p>"
    )
    assert draws == [] and plt.get_fignums() == []
    monkeypatch.setenv("TWOLINK_GRADING", "on")
    with pytest.raises(ValueError, match="TWOLINK_GRADING must be"):
        plot.animation_html(plot.animate_arm(ARM, Q_PATH))
