"""twolink_course.figure_style: colours that stay apart for colour-blind readers, shapes that tell roles
apart without colour, legible text, and a use() that sets only what it says.

The colour-vision test: every pair of colours that carries meaning (the style's,
and those each drawing function of twolink_course.plot draws together) is simulated
for deuteranopia, protanopia and tritanopia (Machado, Oliveira & Fernandes
2009 at severity 100, as colorspacious implements it) and must stay at least
``figure_style.MIN_DISTANCE`` (20) apart in CAM02-UCS (Delta E'), the minimum
perceptual distance of Petroff, "Accessible Color Sequences for Data
Visualization" (arXiv:2107.02270), for normal vision too.
"""

import itertools

import matplotlib
import matplotlib.pyplot as plt
import numpy as np
import pytest
from colorspacious import cspace_convert, deltaE
from matplotlib.colors import to_hex, to_rgb
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from twolink import arms, simulate, statics, velocity
from twolink_course import figure_style, plot

VISIONS = ("normal", "deuteranomaly", "protanomaly", "tritanomaly")
ARM = arms.two_metre


@pytest.fixture(autouse=True)
def close_figures():
    yield
    plt.close("all")


def seen(colour, vision):
    """The sRGB colour (0..1) as a reader with ``vision`` sees it (severity 100: the full deficiency)."""
    rgb = np.array(to_rgb(colour))
    if vision == "normal":
        return rgb
    simulated = cspace_convert(
        rgb, {"name": "sRGB1+CVD", "cvd_type": vision, "severity": 100}, "sRGB1"
    )
    return np.clip(simulated, 0.0, 1.0)


def distance(first, second, vision):
    """CAM02-UCS colour difference (Delta E') of two colours as ``vision`` sees them."""
    return float(deltaE(seen(first, vision), seen(second, vision), input_space="sRGB1"))


def closest_pair(colours, vision):
    return min(
        (distance(a, b, vision), a, b) for a, b in itertools.combinations(colours, 2)
    )


# ------------------------------------------------------------------ the measure can fail


def test_the_simulation_confuses_what_deuteranopes_confuse():
    """The measure is sensitive: Okabe-Ito's orange and vermillion, apart for normal
    vision, come closer than the threshold under deuteranopia; red and green collapse."""
    orange, vermillion = figure_style.ORANGE, figure_style.VERMILLION
    assert distance(orange, vermillion, "normal") >= figure_style.MIN_DISTANCE
    assert distance(orange, vermillion, "deuteranomaly") < figure_style.MIN_DISTANCE
    assert distance("#d62728", "#2ca02c", "deuteranomaly") < 10.0  # tab:red, tab:green
    assert distance("#000000", "#000000", "tritanomaly") == pytest.approx(0.0)


# ------------------------------------------------------------------ the style's colours


@pytest.mark.parametrize("vision", VISIONS)
def test_every_pair_of_meaning_colours_stays_apart(vision):
    smallest, first, second = closest_pair(figure_style.MEANING_COLOURS, vision)
    assert smallest >= figure_style.MIN_DISTANCE, (vision, first, second, smallest)


def test_every_role_and_series_uses_a_meaning_colour():
    roles = [*figure_style.ROLES.values(), *figure_style.SERIES]
    assert {role.color for role in roles} <= set(figure_style.MEANING_COLOURS)
    assert set(figure_style.MEANING_COLOURS) <= set(figure_style.OKABE_ITO) | {
        figure_style.GREY
    }


def test_roles_differ_in_line_style_or_marker_not_in_colour_alone():
    for roles in (list(figure_style.ROLES.values()), list(figure_style.SERIES)):
        for first, second in itertools.combinations(roles, 2):
            assert (first.linestyle, first.marker) != (
                second.linestyle,
                second.marker,
            ), (first.name, second.name)


def test_the_elbow_branches_differ_in_colour_line_style_and_marker():
    down, up = figure_style.ELBOW_DOWN, figure_style.ELBOW_UP
    assert down is figure_style.ARM
    assert down.color != up.color
    assert down.linestyle != up.linestyle and down.marker != up.marker


def test_the_prop_cycle_is_the_series():
    cycle = list(figure_style.prop_cycle())
    assert [(entry["color"], entry["linestyle"]) for entry in cycle] == [
        (role.color, role.linestyle) for role in figure_style.SERIES
    ]
    assert figure_style.RC["axes.prop_cycle"] == figure_style.prop_cycle()


# ------------------------------------------------------------------ what twolink_course.plot draws


def _meaning_colours_drawn(figure):
    """The colours of lines, line markers and patch outlines (not fills of the background)."""
    colours = set()
    background = figure_style.BACKGROUND.lower()
    for ax in figure.axes:
        for artist in ax.get_children():
            if not artist.get_visible():
                continue
            if isinstance(artist, Line2D):
                found = [artist.get_color(), artist.get_markeredgecolor()]
            elif isinstance(artist, Patch) and artist is not ax.patch:
                found = [artist.get_edgecolor()]
                if artist.get_fill():
                    found.append(artist.get_facecolor())
            else:
                continue
            for colour in found:
                if matplotlib.colors.to_rgba(colour)[3] == 0:
                    continue
                hex_colour = to_hex(colour, keep_alpha=False).lower()
                if hex_colour != background:
                    colours.add(hex_colour)
    return colours


def _draw_everything(ax):
    plot.draw_reach(ARM, ax=ax)
    plot.draw_arm(ARM, [0.3, 1.0], ax=ax)
    plot.draw_arm(ARM, [1.0, -1.0], ax=ax, role=figure_style.ELBOW_UP)
    plot.draw_strobe(ARM, np.linspace([0.0, 0.3], [1.0, 1.5], 12), ax=ax, frames=4)
    plot.draw_ellipse(velocity.velocity_ellipse(ARM, [0.3, 1.0]), ax=ax, scale=0.5)
    plot.draw_force([1.0, 1.0], [100.0, 0.0], 0.01, ax=ax)
    plot.draw_torque([0.0, 0.0], 5.0, 0.5, ax=ax)
    plot.draw_wall(statics.Wall.through([4.0, 0.0], [0.0, 4.0]), 3.0, ax=ax)
    ax.plot([2.0], [1.0], **figure_style.TARGET.line())


FIGURES = {
    "draw_arm": lambda ax: plot.draw_arm(ARM, [0.3, 1.0], ax=ax),
    "draw_strobe": lambda ax: plot.draw_strobe(
        ARM, np.linspace([0.0, 0.3], [1.0, 1.5], 12), ax=ax
    ),
    "animate_arm": lambda ax: plot.animate_arm(
        ARM, np.linspace([0.0, 0.3], [1.0, 1.5], 5), ax=ax
    ),
    "animate_simulation": lambda ax: plot.animate_simulation(
        simulate(ARM, [0.3, 0.0], [0.0, 0.0], 0.5, t_eval=np.linspace(0.0, 0.5, 11)),
        max_frames=5,
        ax=ax,
    ),
    "plot_time_series": lambda ax: plot.plot_time_series(
        np.linspace(0.0, 1.0, 5),
        np.ones((5, 4)) * [1.0, 2.0, 3.0, 4.0],
        "energy",
        "J",
        ["T", "V", "E", "W"],
        ax=ax,
    ),
    "every drawing together": _draw_everything,
}


@pytest.mark.parametrize("name", sorted(FIGURES))
def test_each_plot_function_draws_meaning_colours_that_stay_apart(name):
    figure, ax = plt.subplots()
    FIGURES[name](ax)
    drawn = _meaning_colours_drawn(figure)
    allowed = {colour.lower() for colour in figure_style.MEANING_COLOURS}
    assert drawn and drawn <= allowed, sorted(drawn - allowed)
    if len(drawn) > 1:
        for vision in VISIONS:
            smallest, first, second = closest_pair(sorted(drawn), vision)
            assert smallest >= figure_style.MIN_DISTANCE, (
                name,
                vision,
                first,
                second,
            )


def test_plot_time_series_columns_differ_in_line_style_as_well_as_colour():
    _, ax = plt.subplots()
    lines = plot.plot_time_series(
        np.linspace(0.0, 1.0, 5), np.zeros((5, 4)), "angle", "rad", ax=ax
    )
    assert len({line.get_linestyle() for line in lines}) == 4
    assert len({line.get_color() for line in lines}) == 4


def test_draw_arm_branches_differ_without_colour():
    _, ax = plt.subplots()
    down = plot.draw_arm(ARM, [0.3, 1.0], ax=ax)
    up = plot.draw_arm(ARM, [1.3, -1.0], ax=ax, role=figure_style.ELBOW_UP)
    assert down.get_linestyle() != up.get_linestyle()
    assert down.get_marker() != up.get_marker()


# ------------------------------------------------------------------ text and resolution


def test_text_is_at_least_the_minimum_size_at_display_size():
    """A point at ``figure_style.DPI`` is a CSS point: size x dpi / 96 is the size the reader sees."""
    with figure_style.context():
        figure, axes = plt.subplots(1, 2, figsize=(8.0, 4.0))
        plot.setup_axes(ARM, ax=axes[0], title="Reach")
        _draw_everything(axes[0])
        plot.draw_note("ellipse drawn at 0.5 m per m/s", ax=axes[0])
        plot.plot_time_series(
            np.linspace(0.0, 1.0, 5),
            np.zeros((5, 2)),
            "q",
            "rad",
            ["q1", "q2"],
            ax=axes[1],
        )
        figure.canvas.draw()
        texts = [
            text
            for text in figure.findobj(matplotlib.text.Text)
            if text.get_visible() and text.get_text()
        ]
    assert len(texts) > 10
    sizes = {text.get_fontsize() * figure.dpi / 96.0 for text in texts}
    assert min(sizes) >= figure_style.MIN_FONT_PT, sorted(sizes)


def test_setup_axes_makes_figures_at_the_css_inch():
    ax = plot.setup_axes(ARM)
    assert ax.figure.dpi == figure_style.DPI == 96


# ------------------------------------------------------------------ use() and context()


def test_use_sets_exactly_the_listed_rcparams_and_is_idempotent():
    with matplotlib.rc_context():
        before = dict(matplotlib.rcParams)
        assert figure_style.use() is False  # no IPython shell here
        after_once = dict(matplotlib.rcParams)
        figure_style.use()
        assert dict(matplotlib.rcParams) == after_once
        changed = {key for key in before if before[key] != after_once[key]}
        assert changed <= set(figure_style.RC)
        for key, value in figure_style.RC.items():
            assert matplotlib.rcParams[key] == matplotlib.rcParams.validate[key](value)
    assert dict(matplotlib.rcParams) == before


def test_context_applies_the_style_only_inside():
    outside = matplotlib.rcParams["figure.dpi"]
    with figure_style.context():
        assert matplotlib.rcParams["figure.dpi"] == figure_style.DPI
    assert matplotlib.rcParams["figure.dpi"] == outside


def test_role_line_gives_plot_options_and_leaves_arrow_styles_out():
    assert figure_style.ARM.line() == {
        "color": figure_style.BLUE,
        "linestyle": "-",
        "marker": "o",
    }
    assert "marker" not in figure_style.FORCE.line()
    _, ax = plt.subplots()
    (line,) = ax.plot([0.0], [1.0], **figure_style.TARGET.line())
    assert line.get_marker() == "X" and line.get_linestyle() == "None"
