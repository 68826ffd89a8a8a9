"""Drawing the arm with matplotlib: still figures and animations.

Every function draws on an axes you pass (or a new one) and returns what it
made, so notebooks compose figures without global state.
"""

import matplotlib.pyplot as plt
import numpy as np
from matplotlib import animation
from matplotlib.patches import Circle

from ._validate import as_pairs

__all__ = [
    "setup_axes",
    "draw_reach",
    "draw_arm",
    "draw_strobe",
    "animate_arm",
    "animation_html",
    "animate_simulation",
    "draw_ellipse",
    "draw_force",
    "draw_torque",
    "draw_wall",
]

LINK_COLOR = "#1f4e79"
JOINT_COLOR = "#f2a900"
PATH_COLOR = "#c0392b"


def setup_axes(arm, ax=None, margin=0.15, size=(4.0, 4.0), title=None):
    """Square axes sized to the arm's reach, with a light grid.

    Parameters
    ----------
    arm : TwoLinkArm
    ax : matplotlib.axes.Axes, optional
        Axes to set up; a new figure of ``size`` inches is made if omitted.
    margin : float
        Extra room around the reach circle, as a fraction of the reach.
    title : str, optional

    Returns
    -------
    matplotlib.axes.Axes

    Examples
    --------
    >>> from twolink import arms
    >>> ax = setup_axes(arms.two_metre)
    >>> [float(v) for v in ax.get_xlim()]
    [-4.6, 4.6]
    >>> plt.close(ax.figure)
    """
    if ax is None:
        _, ax = plt.subplots(figsize=size, dpi=80)
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


def draw_reach(arm, ax, **style):
    """Draw the reach annulus' two circles (``r_min`` and ``r_max``) on ``ax``."""
    options = {"fill": False, "linestyle": "--", "color": "0.6", "linewidth": 1.0}
    options.update(style)
    circles = []
    for radius in arm.reach:
        if radius > 0:
            circles.append(ax.add_patch(Circle((0.0, 0.0), radius, **options)))
    return circles


def draw_arm(arm, q, ax, color=LINK_COLOR, label=None, alpha=1.0, linewidth=4.0):
    """Draw the arm at one configuration: links, joints and base.

    Parameters
    ----------
    arm : TwoLinkArm
    q : array_like, shape (2,)
        Joint angles in radians.
    ax : matplotlib.axes.Axes
    color, label, alpha, linewidth :
        Line style of the links.

    Returns
    -------
    matplotlib.lines.Line2D
        The line through base, elbow and tip (update it with ``set_data``).

    Examples
    --------
    >>> from twolink import arms
    >>> ax = setup_axes(arms.two_metre)
    >>> line = draw_arm(arms.two_metre, [0.0, np.pi / 2], ax)
    >>> np.round(line.get_xydata(), 12)
    array([[0., 0.],
           [2., 0.],
           [2., 2.]])
    >>> plt.close(ax.figure)
    """
    q = as_pairs(q, "q")
    if q.ndim != 1:
        raise ValueError(f"draw_arm draws one configuration, q of shape (2,); got {q.shape}")
    points = arm.joint_positions(q)
    (line,) = ax.plot(
        points[:, 0],
        points[:, 1],
        "-o",
        color=color,
        linewidth=linewidth,
        markersize=linewidth * 2,
        markerfacecolor=JOINT_COLOR,
        markeredgecolor=color,
        alpha=alpha,
        label=label,
        solid_capstyle="round",
    )
    ax.plot([0.0], [0.0], marker="s", color="k", markersize=8)
    return line


def draw_strobe(arm, q_path, ax, frames=8, color=LINK_COLOR, path=True):
    """A still of a motion: the arm at ``frames`` evenly spaced instants, fading in.

    Use it beside an animation so the motion shows where scripts do not run
    (GitHub, PDF).

    Parameters
    ----------
    arm : TwoLinkArm
    q_path : array_like, shape (n, 2)
        Joint angles along the motion, radians.
    ax : matplotlib.axes.Axes
    frames : int
        How many poses to draw (first and last included).
    path : bool
        Also draw the tip's path.

    Returns
    -------
    list of matplotlib.lines.Line2D
    """
    q_path = as_pairs(q_path, "q_path")
    indices = np.linspace(0, len(q_path) - 1, min(frames, len(q_path))).round().astype(int)
    lines = []
    for rank, index in enumerate(indices):
        alpha = 0.25 + 0.75 * rank / max(1, len(indices) - 1)
        lines.append(draw_arm(arm, q_path[index], ax, color=color, alpha=alpha, linewidth=3.0))
    if path:
        p_path = arm.fk(q_path)
        lines.extend(ax.plot(p_path[:, 0], p_path[:, 1], color=PATH_COLOR, linewidth=1.5))
    return lines


def animate_arm(arm, q_path, t=None, ax=None, path=True, interval=100, title=None, extra=None):
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
        Axes to draw on (set up with :func:`setup_axes` if omitted).
    path : bool
        Trace the tip's path as the arm moves.
    interval : float
        Milliseconds between frames.
    extra : callable, optional
        ``extra(frame_index) -> iterable of artists`` to update more artists
        (force arrows, targets) each frame.

    Returns
    -------
    matplotlib.animation.FuncAnimation
        Show it in a notebook with :func:`animation_html`, after closing its
        figure (``plt.close(anim._fig)`` is done for you there).

    Examples
    --------
    >>> from twolink import arms
    >>> q_path = np.linspace([0.0, 0.0], [np.pi / 2, np.pi / 2], 5)
    >>> anim = animate_arm(arms.two_metre, q_path)
    >>> len(list(anim.new_frame_seq()))
    5
    >>> plt.close(anim._fig)
    """
    q_path = as_pairs(q_path, "q_path")
    if q_path.ndim != 2 or len(q_path) < 1:
        raise ValueError(f"q_path must have shape (n, 2) with n >= 1; got {q_path.shape}")
    ax = setup_axes(arm, ax, title=title)
    p_path = arm.fk(q_path)
    arm_line = draw_arm(arm, q_path[0], ax)
    (tip_trace,) = ax.plot([], [], color=PATH_COLOR, linewidth=1.5)
    clock = ax.text(0.02, 0.95, "", transform=ax.transAxes, fontsize=9)

    def update(frame):
        points = arm.joint_positions(q_path[frame])
        arm_line.set_data(points[:, 0], points[:, 1])
        artists = [arm_line, tip_trace, clock]
        if path:
            tip_trace.set_data(p_path[: frame + 1, 0], p_path[: frame + 1, 1])
        if t is not None:
            clock.set_text(f"t = {t[frame]:.2f} s")
        if extra is not None:
            artists.extend(extra(frame))
        return artists

    return animation.FuncAnimation(ax.figure, update, frames=len(q_path), interval=interval, blit=False)


def animation_html(anim):
    """An H.264 ``<video>`` of the animation for notebooks (small, byte-stable).

    Uses the ffmpeg shipped by the ``imageio-ffmpeg`` package, so no system
    ffmpeg is needed, and closes the animation's figure so no stray still is
    shown.  Without imageio-ffmpeg (``pip install twolink`` alone) it falls
    back to matplotlib's JavaScript player (``to_jshtml``), headed by a note
    saying so and how to get the video.

    Returns
    -------
    IPython.display.HTML
        (or an object with the same ``_repr_html_`` when IPython is absent)
    """
    import matplotlib

    from ._optional import COURSE_INSTALL, html, require

    plt.close(anim._fig)
    try:
        imageio_ffmpeg = require("imageio_ffmpeg", "twolink.plot.animation_html")
        ffmpeg = imageio_ffmpeg.get_ffmpeg_exe()
    except (ImportError, RuntimeError):  # not installed, or its binary is missing
        note = (
            "<p><em>twolink.plot.animation_html: ffmpeg (imageio-ffmpeg) is not installed, so this is "
            f"a JavaScript animation instead of a video; {COURSE_INSTALL} gives the video.</em></p>"
        )
        with matplotlib.rc_context({"animation.embed_limit": 5.0}):  # MB, as for the video
            return html(note + anim.to_jshtml(default_mode="loop"))
    with matplotlib.rc_context({"animation.ffmpeg_path": ffmpeg}):
        return html(anim.to_html5_video(embed_limit=5.0))


def animate_simulation(result, max_frames=50, ax=None, path=True, title=None, speed=1.0):
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
        As for :func:`animate_arm`.
    speed : float
        Playback speed relative to real time (> 0).

    Returns
    -------
    matplotlib.animation.FuncAnimation

    Examples
    --------
    >>> from twolink import arms, simulate
    >>> result = simulate(arms.two_metre, [np.pi / 4, 0.0], [0.0, 0.0], 2.0, t_eval=np.linspace(0.0, 2.0, 201))
    >>> anim = animate_simulation(result, max_frames=21)
    >>> len(list(anim.new_frame_seq())), anim._interval
    (21, 100.0)
    >>> plt.close(anim._fig)
    """
    if not speed > 0:
        raise ValueError(f"speed must be > 0; got {speed}")
    frames = result.frames(max_frames)
    t = result.t[frames]
    interval = 1000.0 * float(t[-1] - t[0]) / max(1, len(frames) - 1) / speed
    return animate_arm(result.arm, result.q[frames], t=t, ax=ax, path=path, interval=interval, title=title)


# --- velocity and statics: ellipses, force arrows, torque arcs, walls
FORCE_COLOR = "#1e8449"
TORQUE_COLOR = "#7d3c98"
ELLIPSE_COLOR = "#2e86c1"


def draw_ellipse(ellipse, ax, scale=1.0, clip=None, color=ELLIPSE_COLOR, alpha=0.25, label=None):
    """Draw one :class:`twolink.velocity.Ellipse` (filled, with its outline) on ``ax``.

    Parameters
    ----------
    ellipse : twolink.velocity.Ellipse
        A single ellipse (``center`` of shape (2,)).
    ax : matplotlib.axes.Axes
    scale : float
        Metres of figure per unit of the ellipse's quantity (e.g. m per m/s).
    clip : float, optional
        Longest semi-axis drawn, in figure metres (needed at singular poses,
        where a force ellipse is unbounded).

    Returns
    -------
    list of matplotlib artists
        The filled polygon and the outline.

    Examples
    --------
    >>> from twolink import arms, velocity
    >>> ax = setup_axes(arms.two_metre)
    >>> artists = draw_ellipse(velocity.velocity_ellipse(arms.two_metre, [0.3, 1.2]), ax, scale=0.5)
    >>> len(artists)
    2
    >>> plt.close(ax.figure)
    """
    if np.ndim(ellipse.center) != 1:
        raise ValueError(f"draw_ellipse draws one ellipse (center of shape (2,)); got {np.shape(ellipse.center)}")
    points = ellipse.points(scale=scale, clip=clip)
    (fill,) = ax.fill(points[:, 0], points[:, 1], color=color, alpha=alpha, label=label)
    (outline,) = ax.plot(points[:, 0], points[:, 1], color=color, linewidth=1.2)
    return [fill, outline]


def draw_force(ax, point, force, scale, at="tail", color=FORCE_COLOR, label=None, width=2.0):
    """Draw a force as a straight arrow of length ``scale * |force|``.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    point : array_like, shape (2,)
        Where the force acts, metres.
    force : array_like, shape (2,)
        The force vector, newtons.
    scale : float
        Metres of figure per newton (> 0).
    at : {"tail", "head"}
        Whether the arrow starts at ``point`` (a push away from it) or ends
        there (a push onto it).

    Returns
    -------
    matplotlib.patches.FancyArrowPatch
        Move it with ``arrow.set_positions(tail, head)``.

    Examples
    --------
    >>> from twolink import arms
    >>> ax = setup_axes(arms.two_metre)
    >>> arrow = draw_force(ax, [1.0, 0.0], [100.0, 0.0], scale=0.01)
    >>> [tuple(float(v) for v in end) for end in arrow._posA_posB]
    [(1.0, 0.0), (2.0, 0.0)]
    >>> plt.close(ax.figure)
    """
    from matplotlib.patches import FancyArrowPatch

    point = as_pairs(point, "point")
    force = as_pairs(force, "force")
    if at not in ("tail", "head"):
        raise ValueError(f"at must be 'tail' or 'head'; got {at!r}")
    if not scale > 0:
        raise ValueError(f"scale must be > 0 (metres of figure per newton); got {scale!r}")
    tail, head = (point, point + scale * force) if at == "tail" else (point - scale * force, point)
    arrow = FancyArrowPatch(
        tuple(tail), tuple(head), arrowstyle="-|>", mutation_scale=14, color=color, linewidth=width, label=label,
        zorder=5,
    )
    ax.add_patch(arrow)
    return arrow


def draw_torque(ax, center, tau, radius, color=TORQUE_COLOR, start=0.0, zero_tol=1e-9):
    """Draw a joint torque as a curved arrow around ``center``.

    Counter-clockwise for ``tau > 0`` (the positive joint direction),
    clockwise for ``tau < 0``; a small dotted circle when ``|tau| <= zero_tol``
    (no torque).  The arrow's size does not scale with ``|tau|``: label it.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    center : array_like, shape (2,)
        The joint, metres.
    tau : float
        Torque, N m.
    radius : float
        Radius of the arc in figure metres.
    start : float
        Angle where the arc starts, radians.

    Returns
    -------
    matplotlib.patches.Patch

    Examples
    --------
    >>> from twolink import arms
    >>> ax = setup_axes(arms.two_metre)
    >>> type(draw_torque(ax, [0.0, 0.0], 5.0, radius=0.5)).__name__
    'FancyArrowPatch'
    >>> type(draw_torque(ax, [0.0, 0.0], 0.0, radius=0.5)).__name__
    'Circle'
    >>> plt.close(ax.figure)
    """
    from matplotlib.patches import FancyArrowPatch
    from matplotlib.path import Path

    center = as_pairs(center, "center")
    if abs(tau) <= zero_tol:
        return ax.add_patch(Circle(tuple(center), radius * 0.5, fill=False, color=color, linewidth=1.5, linestyle=":"))
    sweep = np.sign(tau) * np.radians(270.0)
    angle = start + np.linspace(0.0, sweep, 40)
    vertices = center + radius * np.stack([np.cos(angle), np.sin(angle)], axis=-1)
    arrow = FancyArrowPatch(
        path=Path(vertices), arrowstyle="-|>", mutation_scale=12, color=color, linewidth=1.8, zorder=5
    )
    ax.add_patch(arrow)
    return arrow


def draw_wall(wall, ax, half_length, color="0.25", hatch=0.15):
    """Draw a :class:`twolink.statics.Wall` as a line with hatching on its far side.

    The segment is centred on the point of the wall nearest the base; the
    hatch marks stand on the side away from the base (inside the wall).

    Parameters
    ----------
    wall : twolink.statics.Wall
    ax : matplotlib.axes.Axes
    half_length : float
        Half the drawn length, metres.
    hatch : float
        Length of the hatch marks, metres.

    Returns
    -------
    list of matplotlib.lines.Line2D

    Examples
    --------
    >>> from twolink import arms, statics
    >>> ax = setup_axes(arms.two_metre)
    >>> lines = draw_wall(statics.Wall.through([4.0, 0.0], [0.0, 4.0]), ax, half_length=3.0)
    >>> np.round(lines[0].get_xydata().sum(axis=1), 12)
    array([4., 4.])
    >>> plt.close(ax.figure)
    """
    normal = wall.into_wall()
    along = np.array([-normal[1], normal[0]])
    foot = wall.point - (wall.point @ along) * along  # nearest point to the base
    ends = foot + np.outer([-half_length, half_length], along)
    lines = ax.plot(ends[:, 0], ends[:, 1], color=color, linewidth=2.5)
    for offset in np.arange(-half_length, half_length + 1e-12, max(hatch, half_length / 40)):
        base = foot + offset * along
        tip = base + hatch * (normal + along) / np.sqrt(2.0)
        lines += ax.plot([base[0], tip[0]], [base[1], tip[1]], color=color, linewidth=0.8)
    return lines
