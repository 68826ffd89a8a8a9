"""Drawing the arm with matplotlib: still figures, animations and time plots.

Every drawing function takes the axes as the keyword-only argument ``ax``,
the first after the ``*`` (``draw_arm(arm, q, *, ax=None, ...)``), and returns
what it made, so notebooks compose figures without global state.
``ax=None`` means the current axes, :func:`matplotlib.pyplot.gca`; the
functions that set up axes of their own (:func:`setup_axes`,
:func:`animate_arm`, :func:`animate_simulation`) make a new, square figure
instead.  The ``move_*`` functions move what a drawing function returned
(:func:`move_arm`, :func:`move_strobe`, :func:`move_ellipse`): an explorer
(:mod:`twolink_course.explorer`) draws once and moves its artists on every change.

Colours, line styles and markers come from the roles of
:mod:`twolink_course.figure_style` (the arm, the tip's path, a force, ...), never from
colour names here.  Every drawing function records, for what it drew, a
sentence built from the data drawn (:func:`twolink_course.alttext.record`), and
every ``move_*`` function records the new one, so the figure's text
alternative, :func:`twolink_course.alttext.describe`, stays true.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable, Sequence
from html import escape as html_escape
from typing import TYPE_CHECKING, Any

import matplotlib.pyplot as plt
import numpy as np
from matplotlib import animation
from matplotlib.artist import Artist
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.layout_engine import PlaceHolderLayoutEngine
from matplotlib.lines import Line2D
from matplotlib.patches import Circle, FancyArrowPatch, Polygon
from matplotlib.path import Path
from matplotlib.text import Text
from matplotlib.typing import ColorType
from numpy.typing import ArrayLike, NDArray

from twolink._optional import COURSE_INSTALL, require
from twolink._validate import (
    InputTypeError,
    as_configuration,
    as_finite_scalar,
    as_pairs,
    real_array,
    require_arm,
)
from twolink.velocity import Ellipse

from . import figure_style
from .alttext import (
    angles_text,
    describe,
    listed,
    plain_number,
    point_text,
    quantity_text,
    record,
)
from .display import rounded
from .runmode import grading, skipped_note
from .video import MovingAnimation, frames_drawn_once, html5_video

if TYPE_CHECKING:
    from twolink.arm import TwoLinkArm
    from twolink.simulation import SimulationResult
    from twolink.statics import Wall

__all__ = [
    "setup_axes",
    "draw_reach",
    "draw_arm",
    "move_arm",
    "move_strobe",
    "move_ellipse",
    "draw_strobe",
    "animate_arm",
    "animation_html",
    "animate_simulation",
    "draw_ellipse",
    "draw_force",
    "draw_torque",
    "draw_wall",
    "plot_time_series",
    "draw_note",
]

#: The colours of the roles (:mod:`twolink_course.figure_style`), by the names chapters use.
LINK_COLOR = figure_style.ARM.color
PATH_COLOR = figure_style.PATH.color


def axes_or_current(ax: Axes | None, who: str) -> Axes:
    """``ax``, or the current axes when it is None; anything else is refused naming ``ax``."""
    if ax is None:
        return plt.gca()
    if not isinstance(ax, Axes):
        raise InputTypeError(
            f"{who}: ax must be a matplotlib Axes (or None for the current axes, plt.gca()); "
            f"got {ax!r} ({type(ax).__name__})"
        )
    return ax


def _path(q_path: ArrayLike) -> NDArray[np.float64]:
    """``q_path`` as an array of shape ``(n, 2)`` with ``n >= 1``, or a message naming its shape."""
    q_frames: NDArray[np.float64] = as_pairs(q_path, "q_path")
    if q_frames.ndim != 2 or len(q_frames) < 1:
        raise ValueError(
            f"q_path must have shape (n, 2) with n >= 1 (radians); got shape {q_frames.shape}"
        )
    return q_frames


def _figure_of(ax: Axes) -> Figure:
    """The figure that holds ``ax`` (the top-level one when ``ax`` sits in a subfigure)."""
    figure = ax.figure
    if not isinstance(
        figure, Figure
    ):  # a SubFigure: its own .figure is the top-level one
        figure = figure.figure
    return figure


def setup_axes(
    arm: TwoLinkArm,
    *,
    ax: Axes | None = None,
    margin: float = 0.15,
    size: tuple[float, float] = (4.0, 4.0),
    title: str | None = None,
) -> Axes:
    """Square axes sized to the arm's reach, labelled ``x [m]`` and ``y [m]``, with a light grid.

    Parameters
    ----------
    arm : TwoLinkArm
    ax : matplotlib.axes.Axes, optional
        Axes to set up.  Unlike the drawing functions, ``None`` does not mean
        the current axes: a new figure of ``size`` inches is made.
    margin : float
        Extra room around the reach circle, as a fraction of the reach.
    size : (float, float)
        Width and height of the new figure in inches (only when ``ax`` is None).
    title : str, optional

    Returns
    -------
    matplotlib.axes.Axes

    Examples
    --------
    >>> from twolink import arms
    >>> ax = setup_axes(arms.two_metre)
    >>> [float(v) for v in ax.get_xlim()], ax.get_xlabel()
    ([-4.6, 4.6], 'x [m]')
    >>> plt.close(ax.figure)
    """
    if ax is None:
        _, ax = plt.subplots(figsize=size, dpi=figure_style.DPI)
    else:
        ax = axes_or_current(ax, "setup_axes")
    limit = arm.reach[1] * (1.0 + margin)
    ax.set_xlim(-limit, limit)
    ax.set_ylim(-limit, limit)
    ax.set_aspect("equal")
    ax.grid(True, alpha=0.3)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    if title:
        ax.set_title(title)
    return ax


def draw_reach(
    arm: TwoLinkArm, *, ax: Axes | None = None, **options: Any
) -> list[Circle]:
    """Draw the reach annulus' two circles (``r_min`` and ``r_max``; none of radius 0).

    Parameters
    ----------
    arm : TwoLinkArm
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; the current axes (``plt.gca()``) if omitted.
    **options
        Options of :class:`matplotlib.patches.Circle` (the reach role of
        :mod:`twolink_course.figure_style`, dashed grey outlines, by default).

    Returns
    -------
    list of matplotlib.patches.Circle

    Examples
    --------
    >>> from twolink import TwoLinkArm
    >>> ax = setup_axes(TwoLinkArm(2.0, 1.0))
    >>> [circle.radius for circle in draw_reach(TwoLinkArm(2.0, 1.0), ax=ax)]
    [1.0, 3.0]
    >>> plt.close(ax.figure)
    """
    ax = axes_or_current(ax, "draw_reach")
    circle_options: dict[str, Any] = {
        "fill": False,
        "linestyle": figure_style.REACH.linestyle,
        "color": figure_style.REACH.color,
        "linewidth": 1.2,
    }
    circle_options.update(options)
    circles = []
    for radius in arm.reach:
        if radius > 0:
            circle = Circle((0.0, 0.0), radius, **circle_options)
            ax.add_patch(circle)
            circles.append(circle)
    r_min, r_max = arm.reach
    if r_min > 0:
        sentence = f"The reach: an annulus from {rounded(r_min, 2)} to {rounded(r_max, 2, 'm')}"
    else:
        sentence = f"The reach: a disc of radius {rounded(r_max, 2, 'm')}"
    record(circles[0], sentence, parts=circles)
    return circles


def draw_arm(
    arm: TwoLinkArm,
    q: ArrayLike,
    *,
    ax: Axes | None = None,
    color: ColorType | None = None,
    label: str | None = None,
    alpha: float = 1.0,
    linewidth: float = 4.0,
    role: figure_style.Role = figure_style.ARM,
) -> Line2D:
    """Draw the arm at one configuration: links, joints and base.

    Parameters
    ----------
    arm : TwoLinkArm
    q : array_like, shape (2,)
        Joint angles in radians.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; the current axes (``plt.gca()``) if omitted.
    color, label, alpha, linewidth :
        Style of the links (``color=None``: the role's colour).
    role : twolink_course.figure_style.Role
        Line style, joint marker and colour: ``figure_style.ARM`` (which is
        ``figure_style.ELBOW_DOWN``), or ``figure_style.ELBOW_UP`` for the other branch.

    Returns
    -------
    matplotlib.lines.Line2D
        The line through base, elbow and tip (move it with :func:`move_arm`).

    Examples
    --------
    >>> from twolink import arms
    >>> ax = setup_axes(arms.two_metre)
    >>> line = draw_arm(arms.two_metre, [0.0, np.pi / 2], ax=ax)
    >>> np.round(line.get_xydata(), 12)
    array([[0., 0.],
           [2., 0.],
           [2., 2.]])
    >>> plt.close(ax.figure)
    """
    ax = axes_or_current(ax, "draw_arm")
    q_arm = as_configuration(q)
    line = _draw_links(arm, q_arm, ax, role, color, label, alpha, linewidth)
    base = _draw_base(ax)
    record(line, _arm_sentence(arm, q_arm, label), parts=[base])
    return line


def _draw_links(
    arm: TwoLinkArm,
    q: NDArray[np.float64],
    ax: Axes,
    role: figure_style.Role,
    color: ColorType | None,
    label: str | None,
    alpha: float,
    linewidth: float,
) -> Line2D:
    """The line through base, elbow and tip, joints marked (no base square, nothing recorded)."""
    if not isinstance(role, figure_style.Role):
        raise InputTypeError(
            f"role must be a twolink_course.figure_style.Role (figure_style.ARM, figure_style.ELBOW_UP); got {role!r}"
        )
    color = role.color if color is None else color
    points = arm.joint_positions(q)
    (line,) = ax.plot(
        points[:, 0],
        points[:, 1],
        linestyle=role.linestyle,
        marker=role.marker,
        color=color,
        linewidth=linewidth,
        markersize=linewidth * 2,
        markerfacecolor=figure_style.BACKGROUND,
        markeredgecolor=color,
        markeredgewidth=max(1.0, linewidth / 2),
        alpha=alpha,
        label=label,
        solid_capstyle="round",
    )
    return line


def _draw_base(ax: Axes) -> Line2D:
    """The base marker (nothing recorded)."""
    (base,) = ax.plot([0.0], [0.0], **figure_style.BASE.line(), markersize=8)
    return base


def _arm_sentence(arm: TwoLinkArm, q: NDArray[np.float64], label: str | None) -> str:
    angles = angles_text(q)
    tip = f"tip at {point_text(arm.fk(q))}"
    if not label or label.startswith("_"):
        return f"The arm at q = {angles}, {tip}"
    numbers = angles.strip("()").replace("°", "").split(", ")
    in_label = set(re.findall(r"-?\d+(?:\.\d+)?", label))
    if all(
        number in in_label for number in numbers
    ):  # the label already gives the angles
        return f"The arm ({label}), {tip}"
    return f"The arm ({label}) at q = {angles}, {tip}"


def move_arm(line: Line2D, arm: TwoLinkArm, q: ArrayLike) -> Line2D:
    """Move an arm drawn by :func:`draw_arm` to the configuration ``q`` (radians).

    What an explorer calls on a slider change: the line's data change, nothing
    is drawn anew.

    Examples
    --------
    >>> from twolink import arms
    >>> ax = setup_axes(arms.two_metre)
    >>> line = draw_arm(arms.two_metre, [0.0, 0.0], ax=ax)
    >>> np.round(move_arm(line, arms.two_metre, [np.pi / 2, 0.0]).get_xydata(), 12)
    array([[0., 0.],
           [0., 2.],
           [0., 4.]])
    >>> plt.close(ax.figure)
    """
    if not isinstance(line, Line2D):
        raise InputTypeError(f"line must be the Line2D draw_arm returned; got {line!r}")
    q_arm = as_configuration(q)
    _move_arm_line(line, arm, q_arm)
    record(line, _arm_sentence(arm, q_arm, _label_of(line)))
    return line


def _label_of(artist: Artist) -> str | None:
    """The artist's legend label, or None (matplotlib's ``_child0`` names are not labels)."""
    label = artist.get_label()
    return (
        label
        if isinstance(label, str) and label and not label.startswith("_")
        else None
    )


def _move_arm_line(line: Line2D, arm: TwoLinkArm, q: NDArray[np.float64]) -> None:
    points = arm.joint_positions(q)
    line.set_data(points[:, 0], points[:, 1])


def _strobe_indices(samples: int, frames: int) -> NDArray[np.int_]:
    """The samples a strobe of ``frames`` poses shows: evenly spaced, first and last."""
    return np.linspace(0, samples - 1, min(frames, samples)).round().astype(int)


def draw_strobe(
    arm: TwoLinkArm,
    q_path: ArrayLike,
    *,
    ax: Axes | None = None,
    frames: int = 8,
    color: ColorType | None = None,
    path: bool = True,
    role: figure_style.Role = figure_style.ARM,
) -> list[Line2D]:
    """A still of a motion: the arm at ``frames`` evenly spaced instants, fading in.

    Use it beside an animation so the motion shows where scripts do not run
    (GitHub, PDF).

    Parameters
    ----------
    arm : TwoLinkArm
    q_path : array_like, shape (n, 2)
        Joint angles along the motion, radians.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; the current axes (``plt.gca()``) if omitted.
    frames : int
        How many poses to draw (first and last included).
    color : colour, optional
        The poses' colour (``None``: the role's).
    path : bool
        Also draw the tip's path.
    role : twolink_course.figure_style.Role
        The poses' look (``figure_style.ARM`` or ``figure_style.ELBOW_UP``).

    Returns
    -------
    list of matplotlib.lines.Line2D
        The poses, then the tip's path.

    Examples
    --------
    >>> from twolink import arms
    >>> ax = setup_axes(arms.two_metre)
    >>> len(draw_strobe(arms.two_metre, np.linspace([0.0, 0.0], [1.0, 1.0], 20), ax=ax, frames=5))
    6
    >>> plt.close(ax.figure)
    """
    ax = axes_or_current(ax, "draw_strobe")
    q_samples = _path(q_path)
    indices = _strobe_indices(len(q_samples), frames)
    lines = []
    for rank, index in enumerate(indices):
        alpha = 0.25 + 0.75 * rank / max(1, len(indices) - 1)
        lines.append(
            _draw_links(
                arm, q_samples[index], ax, role, color, None, alpha, linewidth=3.0
            )
        )
    base = _draw_base(ax)  # once, over the poses
    if path:
        p_path = arm.fk(q_samples)
        lines.extend(
            ax.plot(
                p_path[:, 0], p_path[:, 1], **figure_style.PATH.line(), linewidth=1.5
            )
        )
    record(
        lines[0],
        _strobe_sentence(arm, q_samples, len(indices), path),
        parts=[*lines, base],
    )
    return lines


def _strobe_sentence(
    arm: TwoLinkArm, q_samples: NDArray[np.float64], poses: int, path: bool
) -> str:
    shown = "once" if poses == 1 else f"at {poses} instants"
    sentence = (
        f"The arm {shown} of a motion from q = {angles_text(q_samples[0])} "
        f"to {angles_text(q_samples[-1])}, fading in"
    )
    if path:
        p_path = arm.fk(q_samples)
        sentence += (
            f"; the tip's path from {point_text(p_path[0])} to {point_text(p_path[-1])}"
        )
    return sentence


def move_strobe(
    lines: Sequence[Line2D], arm: TwoLinkArm, q_path: ArrayLike, *, path: bool = True
) -> Sequence[Line2D]:
    """Move a strobe drawn by :func:`draw_strobe` to a new motion ``q_path``.

    ``lines`` is what :func:`draw_strobe` returned (the poses, then the tip's
    path when ``path`` was true); the same samples are shown as it would pick.

    Examples
    --------
    >>> from twolink import arms
    >>> ax = setup_axes(arms.two_metre)
    >>> lines = draw_strobe(arms.two_metre, np.zeros((20, 2)), ax=ax, frames=5)
    >>> moved = move_strobe(lines, arms.two_metre, np.linspace([0.0, 0.0], [np.pi / 2, 0.0], 20))
    >>> np.round(moved[-2].get_xydata()[-1], 12)  # the last pose: straight up
    array([0., 4.])
    >>> plt.close(ax.figure)
    """
    q_samples = _path(q_path)
    poses = list(lines[:-1] if path else lines)
    if not poses or not all(isinstance(line, Line2D) for line in lines):
        raise InputTypeError(
            "lines must be the list of Line2D that draw_strobe returned"
        )
    for line, index in zip(poses, _strobe_indices(len(q_samples), len(poses))):
        _move_arm_line(line, arm, q_samples[index])
    if len(q_samples) < len(poses):  # fewer samples than poses: hide the rest
        for line in poses[len(q_samples) :]:
            line.set_visible(False)
    for line in poses[: len(q_samples)]:
        line.set_visible(True)
    if path:
        p_path = arm.fk(q_samples)
        lines[-1].set_data(p_path[:, 0], p_path[:, 1])
    shown = min(len(poses), len(q_samples))
    record(lines[0], _strobe_sentence(arm, q_samples, shown, path))
    return lines


def animate_arm(
    arm: TwoLinkArm,
    q_path: ArrayLike,
    t: ArrayLike | None = None,
    *,
    ax: Axes | None = None,
    path: bool = True,
    interval: float = 100.0,
    title: str | None = None,
    extra: Callable[[int], Iterable[Artist]] | None = None,
) -> MovingAnimation:
    """Animate the arm along a joint-space path, optionally tracing the tip.

    Parameters
    ----------
    arm : TwoLinkArm
    q_path : array_like, shape (n, 2)
        Joint angles per frame, radians.  Keep ``n`` around 50 or fewer for
        notebooks (each frame is a video frame).
    t : array_like, shape (n,), optional
        Times of the frames in seconds, shown in the corner.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on, set up with :func:`setup_axes`; as there, ``None``
        makes a new figure (an animation needs a figure of its own).
    path : bool
        Trace the tip's path as the arm moves.
    interval : float
        Milliseconds between frames.
    title : str, optional
    extra : callable, optional
        ``extra(frame_index) -> iterable of artists`` to update more artists
        (force arrows, targets) each frame.

    Returns
    -------
    twolink_course.video.MovingAnimation
        A :class:`matplotlib.animation.FuncAnimation` that keeps the artists
        each frame moved.  Show it in a notebook with :func:`animation_html`, which closes its
        figure so no stray still is shown.

    Examples
    --------
    >>> from twolink import arms
    >>> q_path = np.linspace([0.0, 0.0], [np.pi / 2, np.pi / 2], 5)
    >>> anim = animate_arm(arms.two_metre, q_path)
    >>> len(list(anim.new_frame_seq()))
    5
    >>> plt.close("all")
    """
    q_frames = _path(q_path)
    times = None
    if t is not None:
        times = real_array(t, "t")
        if times.shape != (len(q_frames),):
            raise ValueError(
                f"t must have shape ({len(q_frames)},), one time per frame of q_path; got {times.shape}"
            )
    own_figure = ax is None
    ax = setup_axes(arm, ax=ax, title=title)
    p_path = arm.fk(q_frames)
    arm_line = _draw_links(arm, q_frames[0], ax, figure_style.ARM, None, None, 1.0, 4.0)
    base = _draw_base(ax)
    (tip_trace,) = ax.plot([], [], **figure_style.PATH.line(), linewidth=1.5)
    clock = ax.text(
        0.02, 0.95, "", transform=ax.transAxes, fontsize=figure_style.SMALL_FONT_PT
    )
    sentence = (
        f"An animation of the arm in {len(q_frames)} frames, from q = "
        f"{angles_text(q_frames[0])} to {angles_text(q_frames[-1])}"
    )
    if times is not None:
        sentence += f", over {plain_number(times[0])}-{plain_number(times[-1])} s"
    if path:
        sentence += (
            f", tracing the tip's path from {point_text(p_path[0])} "
            f"to {point_text(p_path[-1])}"
        )
    record(arm_line, sentence, parts=[base, tip_trace, clock])

    def update(frame: int) -> list[Artist]:
        points = arm.joint_positions(q_frames[frame])
        arm_line.set_data(points[:, 0], points[:, 1])
        artists: list[Artist] = [arm_line, tip_trace, clock]
        if path:
            tip_trace.set_data(p_path[: frame + 1, 0], p_path[: frame + 1, 1])
        if times is not None:
            clock.set_text(f"t = {times[frame]:.2f} s")
        if extra is not None:
            artists.extend(extra(frame))
        return artists

    figure = _figure_of(ax)
    if own_figure:  # nothing else will be drawn on it
        _hold_layout(figure)
    return MovingAnimation(figure, update, frames=len(q_frames), interval=interval)


def _hold_layout(figure: Figure) -> None:
    """Lay ``figure`` out once, now, and keep that layout for every later draw.

    A layout engine (the course style's constrained layout) lays a figure out
    again at every draw, so an animation's video would lay out every frame
    (about half of each frame's time) and could not redraw only what moves;
    held, the frames are drawn over one background (:mod:`twolink_course.video`).
    """
    engine = figure.get_layout_engine()
    if engine is None or isinstance(engine, PlaceHolderLayoutEngine):
        return
    engine.execute(figure)
    figure.set_layout_engine("none")


def animation_html(anim: animation.Animation) -> Any:
    """An H.264 ``<video>`` of the animation for notebooks (small, byte-stable).

    Uses the ffmpeg shipped by the ``imageio-ffmpeg`` package, so no system
    ffmpeg is needed.  The animations of this module draw their axes once and
    only what moves per frame (:mod:`twolink_course.video`; the same video as
    matplotlib's ``to_html5_video``, several times faster).  Closes the animation's figure so no stray still is
    shown.  Without imageio-ffmpeg (``pip install twolink`` alone) it falls
    back to matplotlib's JavaScript player (``to_jshtml``), headed by a note
    saying so and how to get the video.

    The video is labelled with the animation's text alternative
    (:func:`twolink_course.alttext.describe` of its figure) as the ``aria-label`` of
    a ``<div role="figure">`` around it, so the ``<video>`` tag itself stays
    matplotlib's.

    While grading (``TWOLINK_GRADING=1``, :mod:`twolink_course.runmode`) no frame is
    drawn and no video encoded: the figure is closed and a one-line note
    stands in for the video (no answer depends on a video).

    Returns
    -------
    IPython.display.HTML

    Examples
    --------
    >>> import os
    >>> from twolink import arms
    >>> from twolink_course import runmode
    >>> anim = animate_arm(arms.two_metre, np.linspace([0.0, 0.0], [1.0, 1.0], 5))
    >>> saved = os.environ.get(runmode.VARIABLE)
    >>> os.environ[runmode.VARIABLE] = "1"
    >>> animation_html(anim)._repr_html_()
    '<p><em>twolink_course.plot.animation_html: animation skipped while grading (TWOLINK_GRADING=1).</em></p>'
    >>> _ = os.environ.pop(runmode.VARIABLE) if saved is None else os.environ.update({runmode.VARIABLE: saved})
    >>> plt.fignum_exists(anim._fig.number)
    False
    """
    html = require("IPython.display", "twolink_course.plot.animation_html").HTML
    # matplotlib keeps the figure in _fig, outside its type stubs
    figure = getattr(anim, "_fig")  # noqa: B009
    if grading():  # no frame drawn, no video encoded: nothing an answer reads
        plt.close(figure)
        # as a save would mark it: matplotlib warns of an animation deleted unrendered
        setattr(anim, "_draw_was_started", True)  # noqa: B010
        return html(
            "<p><em>twolink_course.plot.animation_html: "
            f"{html_escape(skipped_note('animation'))}.</em></p>"
        )
    label = html_escape(describe(figure), quote=True)
    plt.close(figure)
    try:
        imageio_ffmpeg = require("imageio_ffmpeg", "twolink_course.plot.animation_html")
        ffmpeg = imageio_ffmpeg.get_ffmpeg_exe()
    except (ImportError, RuntimeError):  # not installed, or its binary is missing
        note = (
            "<p><em>twolink_course.plot.animation_html: ffmpeg (imageio-ffmpeg) is not installed, so this is "
            f"a JavaScript animation instead of a video; {COURSE_INSTALL} gives the video.</em></p>"
        )
        with plt.rc_context({"animation.embed_limit": 5.0}):  # MB, as for the video
            return html(note + anim.to_jshtml(default_mode="loop"))
    with plt.rc_context({"animation.ffmpeg_path": ffmpeg}):
        if isinstance(anim, MovingAnimation):  # the axes drawn once, not per frame
            _hold_layout(figure)  # the figure is complete: laid out for the first frame
            video = html5_video(anim, embed_limit=5.0)
        else:
            with frames_drawn_once(anim):
                video = anim.to_html5_video(embed_limit=5.0)
    if video.startswith("<video"):
        # labelled by a wrapper, so the <video> tag stays matplotlib's, byte for byte
        video = f'<div role="figure" aria-label="{label}">\n{video}\n</div>'
    return html(video)


def animate_simulation(
    result: SimulationResult,
    max_frames: int = 50,
    *,
    ax: Axes | None = None,
    path: bool = True,
    title: str | None = None,
    speed: float = 1.0,
) -> MovingAnimation:
    """Animate a :class:`twolink.SimulationResult` at (about) real speed, with a clock.

    Picks at most ``max_frames`` evenly spread samples (first and last
    included) so the video stays small, and plays them at ``speed`` times
    real time.

    Parameters
    ----------
    result : twolink.SimulationResult
        What :func:`twolink.simulate` returned.
    max_frames : int
        Frames in the animation (>= 2; 50 keeps a notebook video ~30 KB).
    ax, path, title :
        As for :func:`animate_arm` (``ax=None`` makes a new figure).
    speed : float
        Playback speed relative to real time (> 0).

    Returns
    -------
    twolink_course.video.MovingAnimation

    Examples
    --------
    >>> from twolink import arms, simulate
    >>> result = simulate(arms.two_metre, [np.pi / 4, 0.0], [0.0, 0.0], 2.0, t_eval=np.linspace(0.0, 2.0, 201))
    >>> anim = animate_simulation(result, max_frames=21)
    >>> len(list(anim.new_frame_seq())), anim._interval
    (21, 100.0)
    >>> plt.close("all")
    """
    speed = as_finite_scalar(speed, "speed", minimum=0.0, strictly=True)
    frames = result.frames(max_frames)
    t = result.t[frames]
    interval = 1000.0 * float(t[-1] - t[0]) / max(1, len(frames) - 1) / speed
    arm = require_arm(result.arm, "result.arm")
    return animate_arm(
        arm, result.q[frames], t=t, ax=ax, path=path, interval=interval, title=title
    )


# --- velocity and statics: ellipses, force arrows, torque arcs, walls
FORCE_COLOR = figure_style.FORCE.color
TORQUE_COLOR = figure_style.TORQUE.color
ELLIPSE_COLOR = figure_style.ELLIPSE.color


def draw_ellipse(
    ellipse: Ellipse,
    *,
    ax: Axes | None = None,
    scale: float = 1.0,
    clip: float | None = None,
    color: ColorType = ELLIPSE_COLOR,
    alpha: float = 0.25,
    label: str | None = None,
) -> list[Polygon | Line2D]:
    """Draw one :class:`twolink.velocity.Ellipse` (filled, with its outline).

    Parameters
    ----------
    ellipse : twolink.velocity.Ellipse
        A single ellipse (``centre`` of shape (2,)).
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; the current axes (``plt.gca()``) if omitted.
    scale : float
        Metres of figure per unit of the ellipse's quantity (e.g. m per m/s).
    clip : float, optional
        Longest semi-axis drawn, in figure metres (needed at singular poses,
        where a force ellipse is unbounded).
    color, alpha, label :
        Style of the filled ellipse (the outline has the same colour).

    Returns
    -------
    list of matplotlib artists
        The filled polygon and the outline.

    Examples
    --------
    >>> from twolink import arms, velocity
    >>> ax = setup_axes(arms.two_metre)
    >>> artists = draw_ellipse(velocity.velocity_ellipse(arms.two_metre, [0.3, 1.2]), ax=ax, scale=0.5)
    >>> [type(artist).__name__ for artist in artists]
    ['Polygon', 'Line2D']
    >>> plt.close(ax.figure)
    """
    ax = axes_or_current(ax, "draw_ellipse")
    if np.ndim(ellipse.centre) != 1:
        raise ValueError(
            f"draw_ellipse draws one ellipse (centre of shape (2,)); got {np.shape(ellipse.centre)}"
        )
    points = ellipse.points(scale=scale, clip=clip)
    (fill,) = ax.fill(points[:, 0], points[:, 1], color=color, alpha=alpha, label=label)
    (outline,) = ax.plot(
        points[:, 0],
        points[:, 1],
        color=color,
        linestyle=figure_style.ELLIPSE.linestyle,
        linewidth=1.5,
    )
    record(fill, _ellipse_sentence(ellipse, scale, clip, label), parts=[outline])
    return [fill, outline]


def _ellipse_sentence(
    ellipse: Ellipse, scale: float, clip: float | None, label: str | None
) -> str:
    """Centre, drawn semi-axes (figure metres) and the major axis' direction."""
    drawn = []
    for semi_axis in np.asarray(ellipse.semi_axes, dtype=float) * scale:
        if clip is not None and not semi_axis <= clip:
            drawn.append(f"{rounded(clip, 2)} (clipped)")
        else:
            drawn.append(rounded(semi_axis, 2))
    name = (
        f"An ellipse ({label})" if label and not label.startswith("_") else "An ellipse"
    )
    angle = plain_number(round(float(np.degrees(ellipse.angle)), 1), 6)
    return (
        f"{name} centred at {point_text(ellipse.centre)}, semi-axes {listed(drawn)} m "
        f"as drawn, the major one at {angle}° from the x-axis"
    )


def move_ellipse(
    artists: Sequence[Artist],
    ellipse: Ellipse,
    *,
    scale: float = 1.0,
    clip: float | None = None,
) -> Sequence[Artist]:
    """Move an ellipse drawn by :func:`draw_ellipse` (its fill and outline) to ``ellipse``.

    Examples
    --------
    >>> from twolink import arms, velocity
    >>> ax = setup_axes(arms.two_metre)
    >>> drawn = draw_ellipse(velocity.velocity_ellipse(arms.two_metre, [0.3, 1.2]), ax=ax)
    >>> ellipse = velocity.velocity_ellipse(arms.two_metre, [0.3, 0.6])
    >>> fill, outline = move_ellipse(drawn, ellipse, scale=0.5)
    >>> bool(np.allclose(outline.get_xydata(), ellipse.points(scale=0.5)))
    True
    >>> plt.close(ax.figure)
    """
    fill, outline = artists if len(artists) == 2 else (None, None)
    if not (isinstance(fill, Polygon) and isinstance(outline, Line2D)):
        raise InputTypeError(
            "artists must be the [fill, outline] that draw_ellipse returned"
        )
    points = ellipse.points(scale=scale, clip=clip)
    fill.set_xy(points)
    outline.set_data(points[:, 0], points[:, 1])
    record(fill, _ellipse_sentence(ellipse, scale, clip, _label_of(fill)))
    return artists


def draw_force(
    point: ArrayLike,
    vector: ArrayLike,
    scale: float,
    *,
    ax: Axes | None = None,
    at: str = "tail",
    color: ColorType = FORCE_COLOR,
    label: str | None = None,
    width: float = 2.0,
) -> FancyArrowPatch:
    """Draw a force as a straight arrow of length ``scale * |vector|``.

    Any force: the one the tip exerts (``force_by_tip``, drawn at the tip)
    or one acting on it (``force_on_tip``); say which in a label or the title.

    Parameters
    ----------
    point : array_like, shape (2,)
        Where the force acts, metres.
    vector : array_like, shape (2,)
        The force, newtons.
    scale : float
        Metres of figure per newton (> 0).
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; the current axes (``plt.gca()``) if omitted.
    at : {"tail", "head"}
        Whether the arrow starts at ``point`` (a push away from it) or ends
        there (a push onto it).
    color, label, width :
        Style of the arrow.

    Returns
    -------
    matplotlib.patches.FancyArrowPatch
        Move it with ``arrow.set_positions(tail, head)``.

    Examples
    --------
    >>> from twolink import arms
    >>> ax = setup_axes(arms.two_metre)
    >>> arrow = draw_force([1.0, 0.0], [100.0, 0.0], scale=0.01, ax=ax)
    >>> [tuple(float(v) for v in end) for end in arrow._posA_posB]
    [(1.0, 0.0), (2.0, 0.0)]
    >>> plt.close(ax.figure)
    """
    ax = axes_or_current(ax, "draw_force")
    p_point: NDArray[np.float64] = as_configuration(
        point, "point", "one (x, y) point", "metres"
    )
    f_vector: NDArray[np.float64] = as_configuration(
        vector, "vector", "one force (Fx, Fy)", "newtons"
    )
    if at not in ("tail", "head"):
        raise ValueError(f"at must be 'tail' or 'head'; got {at!r}")
    scale = as_finite_scalar(
        scale, "scale (metres of figure per newton)", minimum=0.0, strictly=True
    )
    if at == "tail":
        tail, head = p_point, p_point + scale * f_vector
    else:
        tail, head = p_point - scale * f_vector, p_point
    arrow = FancyArrowPatch(
        (float(tail[0]), float(tail[1])),
        (float(head[0]), float(head[1])),
        arrowstyle=figure_style.FORCE.marker,
        mutation_scale=14,
        color=color,
        linestyle=figure_style.FORCE.linestyle,
        linewidth=width,
        label=label,
        zorder=5,
    )
    ax.add_patch(arrow)
    name = f"A force ({label})" if label and not label.startswith("_") else "A force"
    magnitude = float(np.hypot(*f_vector))
    if magnitude == 0.0:
        sentence = f"{name} of 0 N at {point_text(p_point)}"
    else:
        angle = plain_number(
            round(float(np.degrees(np.arctan2(f_vector[1], f_vector[0]))), 1), 6
        )
        where = "from" if at == "tail" else "onto"
        sentence = (
            f"{name} of {quantity_text(magnitude, 'N')} pointing at {angle}° from the "
            f"x-axis, {where} {point_text(p_point)}"
        )
    record(arrow, sentence)
    return arrow


def draw_torque(
    centre: ArrayLike,
    tau: float,
    radius: float,
    *,
    ax: Axes | None = None,
    color: ColorType = TORQUE_COLOR,
    start: float = 0.0,
    zero_tol: float = 1e-9,
) -> FancyArrowPatch | Circle:
    """Draw a joint torque as a curved arrow around ``centre``.

    Counter-clockwise for ``tau > 0`` (the positive joint direction),
    clockwise for ``tau < 0``; a small dotted circle when ``|tau| <= zero_tol``
    (no torque).  The arrow's size does not scale with ``|tau|``: label it.

    Parameters
    ----------
    centre : array_like, shape (2,)
        The joint, metres.
    tau : float
        Torque, N m.
    radius : float
        Radius of the arc in figure metres (> 0).
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; the current axes (``plt.gca()``) if omitted.
    color : colour
    start : float
        Angle where the arc starts, radians.
    zero_tol : float
        Largest ``|tau|`` (N m) drawn as no torque.

    Returns
    -------
    matplotlib.patches.FancyArrowPatch or matplotlib.patches.Circle

    Examples
    --------
    >>> from twolink import arms
    >>> ax = setup_axes(arms.two_metre)
    >>> type(draw_torque([0.0, 0.0], 5.0, radius=0.5, ax=ax)).__name__
    'FancyArrowPatch'
    >>> type(draw_torque([0.0, 0.0], 0.0, radius=0.5, ax=ax)).__name__
    'Circle'
    >>> plt.close(ax.figure)
    """
    ax = axes_or_current(ax, "draw_torque")
    c_point: NDArray[np.float64] = as_configuration(
        centre, "centre", "one (x, y) point", "metres"
    )
    tau = as_finite_scalar(tau, "tau (N m)")
    radius = as_finite_scalar(
        radius, "radius (figure metres)", minimum=0.0, strictly=True
    )
    if abs(tau) <= zero_tol:
        circle = Circle(
            (float(c_point[0]), float(c_point[1])),
            radius * 0.5,
            fill=False,
            color=color,
            linewidth=1.5,
            linestyle=":",
        )
        ax.add_patch(circle)
        record(circle, f"No torque about {point_text(c_point)}")
        return circle
    sweep = np.sign(tau) * np.radians(270.0)
    angle = start + np.linspace(0.0, sweep, 40)
    vertices = c_point + radius * np.stack([np.cos(angle), np.sin(angle)], axis=-1)
    arrow = FancyArrowPatch(
        path=Path(vertices),
        arrowstyle=figure_style.TORQUE.marker,
        mutation_scale=12,
        color=color,
        linestyle=figure_style.TORQUE.linestyle,
        linewidth=1.8,
        zorder=5,
    )
    ax.add_patch(arrow)
    turning = "counter-clockwise" if tau > 0 else "clockwise"
    record(
        arrow,
        f"A torque of {quantity_text(abs(tau), 'N m')}, {turning}, about {point_text(c_point)}",
    )
    return arrow


def draw_wall(
    wall: Wall,
    half_length: float,
    *,
    ax: Axes | None = None,
    color: ColorType = figure_style.WALL.color,
    hatch: float = 0.15,
) -> list[Line2D]:
    """Draw a :class:`twolink.statics.Wall` as a line with hatching on its far side.

    The segment is centred on the point of the wall nearest the base; the
    hatch marks stand on the side away from the base (inside the wall).

    Parameters
    ----------
    wall : twolink.statics.Wall
    half_length : float
        Half the drawn length, metres.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; the current axes (``plt.gca()``) if omitted.
    color : colour
    hatch : float
        Length of the hatch marks, metres.

    Returns
    -------
    list of matplotlib.lines.Line2D
        The wall's line, then the hatch marks.

    Examples
    --------
    >>> from twolink import arms, statics
    >>> ax = setup_axes(arms.two_metre)
    >>> lines = draw_wall(statics.Wall.through([4.0, 0.0], [0.0, 4.0]), half_length=3.0, ax=ax)
    >>> np.round(lines[0].get_xydata().sum(axis=1), 12)
    array([4., 4.])
    >>> plt.close(ax.figure)
    """
    ax = axes_or_current(ax, "draw_wall")
    half_length = as_finite_scalar(
        half_length, "half_length (m)", minimum=0.0, strictly=True
    )
    normal = wall.into_wall()
    along = np.array([-normal[1], normal[0]])
    foot = wall.point - (wall.point @ along) * along  # nearest point to the base
    ends = foot + np.outer([-half_length, half_length], along)
    lines = ax.plot(
        ends[:, 0],
        ends[:, 1],
        color=color,
        linestyle=figure_style.WALL.linestyle,
        linewidth=2.5,
    )
    for offset in np.arange(
        -half_length, half_length + 1e-12, max(hatch, half_length / 40)
    ):
        base = foot + offset * along
        tip = base + hatch * (normal + along) / np.sqrt(2.0)
        lines += ax.plot(
            [base[0], tip[0]], [base[1], tip[1]], color=color, linewidth=0.8
        )
    record(
        lines[0],
        f"A wall {rounded(wall.distance_from_base(), 2, 'm')} from the base, its point "
        f"nearest the base at {point_text(foot)}, drawn {rounded(2 * half_length, 2, 'm')} "
        "long and hatched on its far side",
        parts=lines,
    )
    return lines


# --- quantities against time, notes on figures


def plot_time_series(
    t: ArrayLike,
    values: ArrayLike,
    quantity: str,
    unit: str,
    labels: Sequence[str] | None = None,
    *,
    ax: Axes | None = None,
    fmt: str | None = None,
    colors: Sequence[ColorType] | None = None,
    log: bool = False,
    **line_options: Any,
) -> list[Line2D]:
    """Plot one or more quantities against time: ``t [s]`` across, ``quantity [unit]`` up.

    One line per column of ``values`` (joint 1, joint 2, ...), with a light
    grid and, when ``labels`` are given, a legend.  Call it again on the
    same ``ax`` to add lines (another run, another style): the labels and
    the legend are set anew and the legend lists every labelled line.

    Parameters
    ----------
    t : array_like, shape (n,)
        Times in seconds (finite).
    values : array_like, shape (n,) or (n, k)
        The quantity at each time, one column per line, in ``unit`` (NaN
        leaves a gap).
    quantity : str
        What is plotted, for the axis label (``"joint angle"``).
    unit : str
        Its unit, for the axis label (``"deg"``, ``"N m"``; ``"-"`` for a
        dimensionless ratio).
    labels : sequence of str, optional
        One legend entry per column (``["q1", "q2"]``); no legend if omitted.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; the current axes (``plt.gca()``) if omitted.
    fmt : str, optional
        matplotlib format string of every line (``"--"``, ``"o"``); if
        omitted, column ``k`` takes the line style of ``figure_style.SERIES[k]``.
    colors : sequence of colours, optional
        One colour per column; if omitted, column ``k`` takes the colour of
        ``figure_style.SERIES[k]`` (so joint 1 keeps its colour from run to run,
        and a run drawn with another ``fmt`` differs in line style).
    log : bool
        Logarithmic vertical axis.
    **line_options
        More options of :meth:`matplotlib.axes.Axes.plot` (``linewidth``,
        ``markersize``, ``alpha``).

    Returns
    -------
    list of matplotlib.lines.Line2D
        One per column.

    Examples
    --------
    >>> t = np.linspace(0.0, 1.0, 11)
    >>> fig, ax = plt.subplots()
    >>> lines = plot_time_series(t, np.column_stack([t, t**2]), "joint angle", "rad", ["q1", "q2"], ax=ax)
    >>> len(lines), ax.get_xlabel(), ax.get_ylabel()
    (2, 't [s]', 'joint angle [rad]')
    >>> [text.get_text() for text in ax.get_legend().get_texts()]
    ['q1', 'q2']
    >>> plt.close(fig)
    """
    ax = axes_or_current(ax, "plot_time_series")
    times = real_array(t, "t (s)")
    if times.ndim != 1 or not np.all(np.isfinite(times)):
        raise ValueError(
            f"t must be finite times in seconds of shape (n,); got shape {times.shape}"
        )
    data = real_array(values, "values")
    if data.ndim == 1:
        data = data[:, None]
    if data.ndim != 2 or len(data) != len(times):
        raise ValueError(
            f"values must have shape ({len(times)},) or ({len(times)}, k), one row per time of t; got {np.shape(values)}"
        )
    for name, text in (("quantity", quantity), ("unit", unit)):
        if not isinstance(text, str) or not text.strip():
            raise InputTypeError(
                f"{name} must be a non-empty string (the axis label is 'quantity [unit]'); got {text!r}"
            )
    columns = data.shape[1]
    if labels is not None and (isinstance(labels, str) or len(labels) != columns):
        raise ValueError(
            f"labels must be a sequence of {columns} strings, one per column of values; got {labels!r}"
        )
    if colors is not None and (isinstance(colors, str) or len(colors) != columns):
        raise ValueError(
            f"colors must be a sequence of {columns} colours, one per column of values; got {colors!r}"
        )
    lines = []
    for column in range(columns):
        series = figure_style.SERIES[column % len(figure_style.SERIES)]
        options: dict[str, Any] = {"color": series.color}
        if fmt is None:
            options["linestyle"] = series.linestyle
        options.update(line_options)
        if labels is not None:
            options["label"] = labels[column]
        if colors is not None:
            options["color"] = colors[column]
        arguments = (
            (times, data[:, column]) if fmt is None else (times, data[:, column], fmt)
        )
        lines.extend(ax.plot(*arguments, **options))
    ax.set_xlabel("t [s]")
    ax.set_ylabel(f"{quantity} [{unit}]")
    if log:
        ax.set_yscale("log")
    ax.grid(True, which="both" if log else "major", alpha=0.3)
    if labels is not None:
        ax.legend(fontsize=figure_style.SMALL_FONT_PT)
    shown = (
        listed(list(labels))
        if labels is not None
        else ("one line" if columns == 1 else f"{columns} lines")
    )
    if not lines or not len(times):
        return lines
    record(
        lines[0],
        f"Time series of {quantity} [{unit}] over "
        f"{plain_number(times[0])}-{plain_number(times[-1])} s: {shown}",
        parts=lines,
    )
    return lines


_NOTE_CORNERS = {
    "lower left": (0.03, 0.03, "left", "bottom"),
    "upper left": (0.03, 0.97, "left", "top"),
    "lower right": (0.97, 0.03, "right", "bottom"),
    "upper right": (0.97, 0.97, "right", "top"),
}


def draw_note(
    text: str,
    *,
    ax: Axes | None = None,
    corner: str = "lower left",
    fontsize: float = figure_style.SMALL_FONT_PT,
) -> Text:
    """Write a boxed note in a corner of the axes (values, the drawing scale of ellipses or arrows).

    Parameters
    ----------
    text : str
        The note; ``"\\n"`` breaks lines.
    ax : matplotlib.axes.Axes, optional
        Axes to write on; the current axes (``plt.gca()``) if omitted.
    corner : {"lower left", "upper left", "lower right", "upper right"}
    fontsize : float

    Returns
    -------
    matplotlib.text.Text

    Examples
    --------
    >>> fig, ax = plt.subplots()
    >>> note = draw_note("ellipse drawn at 0.4 m per m/s", ax=ax)
    >>> note.get_text(), note.get_position()
    ('ellipse drawn at 0.4 m per m/s', (0.03, 0.03))
    >>> plt.close(fig)
    """
    ax = axes_or_current(ax, "draw_note")
    if not isinstance(text, str):
        raise InputTypeError(
            f"text must be a string; got {text!r} ({type(text).__name__})"
        )
    if corner not in _NOTE_CORNERS:
        raise ValueError(
            f"corner must be one of {', '.join(map(repr, _NOTE_CORNERS))}; got {corner!r}"
        )
    x, y, horizontal, vertical = _NOTE_CORNERS[corner]
    note = ax.text(
        x,
        y,
        text,
        transform=ax.transAxes,
        fontsize=fontsize,
        ha=horizontal,
        va=vertical,
        bbox={
            "facecolor": figure_style.BACKGROUND,
            "edgecolor": figure_style.GREY,
            "alpha": 0.9,
        },
    )
    said = "; ".join(line.strip() for line in text.splitlines() if line.strip())
    record(note, f'A note: "{said}"' if said else "An empty note")
    return note
