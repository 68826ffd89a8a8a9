"""Labelled diagrams of the 2R arm: its DH frames, and the free bodies of its links.

:func:`draw_dh_frames` draws the arm with the frames the Denavit-Hartenberg
convention attaches to it (chapter 1): frame 0 at the base, frame 1 at the
elbow with ``x_1`` along link 1, frame 2 at the tip with ``x_2`` along link 2,
every ``z_i`` out of the page; the link lengths ``a_1``, ``a_2`` along the
``x`` axes and the joint angles ``theta_1``, ``theta_2`` as arcs.

:func:`draw_free_bodies` cuts the arm at its joints and draws each link with
every force and torque that acts on it while the tip pushes with
``force_by_tip`` (chapter 4's free-body equations, weight neglected).

Both follow :mod:`twolink_course.plot`'s conventions (``ax`` keyword-only, ``None``
for the current axes; colours from :mod:`twolink_course.figure_style`) and record
one sentence per diagram, built from the data drawn, for the figure's text
alternative (:func:`twolink_course.alttext.describe`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.artist import Artist
from matplotlib.axes import Axes
from matplotlib.patches import Circle, FancyArrowPatch
from matplotlib.path import Path
from matplotlib.text import Text
from numpy.typing import ArrayLike, NDArray

from twolink._validate import InputTypeError, as_configuration, require_arm

from . import figure_style
from .alttext import angles_text, plain_number, point_text, quantity_text, record
from .plot import axes_or_current, draw_arm, draw_force, draw_torque

if TYPE_CHECKING:
    from twolink.arm import TwoLinkArm

__all__ = ["draw_dh_frames", "draw_free_bodies"]

#: The colour of frame axes and labels (black: the frames are the diagram's subject).
FRAME_COLOR = figure_style.BLACK
#: The colour of the joint-angle arcs.
ANGLE_COLOR = figure_style.VERMILLION


def _label(ax: Axes, point: ArrayLike, text: str, color: str) -> Text:
    """A label centred on ``point``."""
    x, y = (float(v) for v in np.asarray(point, dtype=float))
    return ax.text(x, y, text, ha="center", va="center", color=color)


def _direction(angle: float) -> NDArray[np.float64]:
    return np.array([np.cos(angle), np.sin(angle)])


def _arc(
    ax: Axes, centre: NDArray[np.float64], radius: float, start: float, stop: float
) -> FancyArrowPatch:
    """An arc with an arrowhead, from angle ``start`` to ``stop`` (radians) about ``centre``."""
    angles = np.linspace(start, stop, 40)
    arrow = FancyArrowPatch(
        path=Path(
            centre + radius * np.stack([np.cos(angles), np.sin(angles)], axis=-1)
        ),
        arrowstyle="-|>",
        mutation_scale=12,
        color=ANGLE_COLOR,
        linewidth=1.5,
        zorder=4,
    )
    ax.add_patch(arrow)
    return arrow


def _z_axis(ax: Axes, point: NDArray[np.float64], size: float) -> list[Artist]:
    """An axis out of the page: a circle with a dot in it."""
    ring = Circle(
        tuple(point),
        size,
        fill=True,
        facecolor=figure_style.BACKGROUND,
        edgecolor=FRAME_COLOR,
        linewidth=1.2,
        zorder=6,
    )
    dot = Circle(tuple(point), size * 0.3, color=FRAME_COLOR, zorder=7)
    ax.add_patch(ring)
    ax.add_patch(dot)
    return [ring, dot]


def draw_dh_frames(arm: TwoLinkArm, q: ArrayLike, *, ax: Axes | None = None) -> Axes:
    """Draw the arm at ``q`` with its DH frames 0, 1, 2, link lengths and joint angles, labelled.

    Frame ``i`` sits where link ``i`` ends (frame 0 at the base): its ``x_i``
    axis points along link ``i`` (``x_0`` along the base's x-axis), its
    ``z_i`` axis (the axis of joint ``i + 1``) out of the page, drawn as a dot
    in a circle.  ``a_i`` is the distance along ``x_i`` from ``z_(i-1)`` to
    ``z_i`` (the link length); ``theta_i`` turns ``x_(i-1)`` into ``x_i``
    about ``z_(i-1)`` (``theta_1 = q1`` from ``x_0``, ``theta_2 = q2`` from
    the extension of ``x_1``, drawn dashed).

    Parameters
    ----------
    arm : TwoLinkArm
    q : array_like, shape (2,)
        Joint angles ``(theta_1, theta_2)``, radians.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; the current axes (``plt.gca()``) if omitted.  The
        limits are set to show the arm, the frames and their labels.

    Returns
    -------
    matplotlib.axes.Axes

    Examples
    --------
    >>> from twolink import TwoLinkArm
    >>> from twolink_course import alttext
    >>> ax = draw_dh_frames(TwoLinkArm(1.0, 1.0), np.radians([30.0, 45.0]))
    >>> alttext.describe(ax.figure).split(": ")[0]
    'DH frames of the 2R arm. The arm at q = (30°, 45°) in its DH frames'
    >>> [text.get_text() for text in ax.texts][:3]
    ['$x_0$', '$z_0$', '$x_1$']
    >>> plt.close(ax.figure)
    """
    ax = axes_or_current(ax, "draw_dh_frames")
    require_arm(arm)
    q_arm = as_configuration(q)
    theta_1, theta_2 = float(q_arm[0]), float(q_arm[1])
    origins = arm.joint_positions(q_arm)
    x_angles = (0.0, theta_1, theta_1 + theta_2)
    size = 0.3 * min(arm.l1, arm.l2)
    drawn: list[Artist] = []
    label_points = [origins]

    line = draw_arm(arm, q_arm, ax=ax)
    # x_1 carried on past the elbow: theta_2 is measured from it
    extension = origins[1] + 1.2 * size * _direction(theta_1)
    drawn += ax.plot(
        *np.transpose([origins[1], extension]),
        color=FRAME_COLOR,
        linestyle="--",
        linewidth=1.0,
    )
    for i, (origin, angle) in enumerate(zip(origins, x_angles)):
        head = origin + size * _direction(angle)
        arrow = FancyArrowPatch(
            tuple(origin),
            tuple(head),
            arrowstyle="-|>",
            mutation_scale=14,
            color=FRAME_COLOR,
            linewidth=1.5,
            zorder=5,
        )
        ax.add_patch(arrow)
        drawn.append(arrow)
        label_at = origin + 1.25 * size * _direction(angle)
        label_points.append(label_at[None])
        drawn.append(_label(ax, label_at, f"$x_{i}$", FRAME_COLOR))
        drawn += _z_axis(ax, origin, 0.12 * size)
        # z_i's label below-left of its symbol, away from the x arrow
        away = origin + 0.35 * size * _direction(angle + 0.75 * np.pi)
        label_points.append(away[None])
        drawn.append(_label(ax, away, f"$z_{i}$", FRAME_COLOR))
    for i, (start, stop) in enumerate(zip(origins[:-1], origins[1:]), start=1):
        middle, along = (start + stop) / 2, stop - start
        normal = np.array([-along[1], along[0]]) / np.hypot(*along)
        label_at = middle + 0.35 * size * normal
        label_points.append(label_at[None])
        drawn.append(_label(ax, label_at, f"$a_{i}$", figure_style.ARM.color))
    for i, (centre, start, turn) in enumerate(
        ((origins[0], 0.0, theta_1), (origins[1], theta_1, theta_2)), start=1
    ):
        radius = 0.7 * size
        if abs(turn) > 1e-3:
            drawn.append(_arc(ax, centre, radius, start, start + turn))
        middle = start + turn / 2
        label_at = centre + 1.45 * radius * _direction(middle)
        label_points.append(label_at[None])
        drawn.append(_label(ax, label_at, f"$\\theta_{i}$", ANGLE_COLOR))

    points = np.vstack(label_points)
    low, high = points.min(axis=0) - 0.6 * size, points.max(axis=0) + 0.6 * size
    ax.set_xlim(low[0], high[0])
    ax.set_ylim(low[1], high[1])
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title("DH frames of the 2R arm")
    record(
        line,
        f"The arm at q = {angles_text(q_arm)} in its DH frames: frame 0 at the base "
        f"{point_text(origins[0])} with x0 along the x-axis; frame 1 at the elbow "
        f"{point_text(origins[1])} with x1 along link 1, turned by θ1 = "
        f"{_degrees(theta_1)} from x0; frame 2 at the tip {point_text(origins[2])} "
        f"with x2 along link 2, turned by θ2 = {_degrees(theta_2)} from x1 (its "
        f"extension is dashed); z0, z1 and z2 point out of the page; a1 = "
        f"{quantity_text(arm.l1, 'm')} and a2 = {quantity_text(arm.l2, 'm')} are "
        "the link lengths along x1 and x2",
        parts=drawn,
    )
    return ax


def _degrees(angle: float) -> str:
    return f"{plain_number(round(float(np.degrees(angle)), 1), 6)}°"


def _turning(tau: float) -> str:
    return "counter-clockwise" if tau > 0 else "clockwise" if tau < 0 else "zero"


def _force_words(force: NDArray[np.float64]) -> str:
    magnitude = float(np.hypot(*force))
    if magnitude == 0.0:
        return "0 N"
    angle = plain_number(round(float(np.degrees(np.arctan2(force[1], force[0]))), 1), 6)
    return f"{quantity_text(magnitude, 'N')} at {angle}° from the x-axis"


def draw_free_bodies(
    arm: TwoLinkArm,
    q: ArrayLike,
    force_by_tip: ArrayLike,
    *,
    axes: tuple[Axes, Axes] | None = None,
) -> tuple[Axes, Axes]:
    """Draw link 1 and link 2 cut apart at the elbow, each with every force and torque on it.

    The tip pushes with ``force_by_tip`` = ``F`` (on a wall, say), so the
    wall pushes the tip with ``-F``.  Balancing each link (weight neglected):

    * link 2 feels ``-F`` at the tip, ``f_12`` from link 1 at the elbow and
      the torque ``tau_2`` of motor 2; its forces balance when ``f_12 = F``;
    * link 1 feels ``f_01`` from the base, ``-f_12`` from link 2 at the elbow,
      ``tau_1`` of motor 1 and the reaction ``-tau_2`` of motor 2;
      ``f_01 = F``;
    * the moments balance when ``(tau_1, tau_2) = J^T F``
      (:meth:`twolink.TwoLinkArm.joint_torques`).

    Forces are straight arrows from where they act, all drawn to one scale;
    torques are curved arrows (counter-clockwise positive), labelled with
    their values.

    Parameters
    ----------
    arm : TwoLinkArm
    q : array_like, shape (2,)
        Joint angles, radians.
    force_by_tip : array_like, shape (2,)
        The force the tip exerts, newtons.
    axes : (Axes, Axes), optional
        Where to draw link 1 and link 2; a new figure with two panels if omitted.

    Returns
    -------
    (matplotlib.axes.Axes, matplotlib.axes.Axes)
        The panels of link 1 and link 2.

    Examples
    --------
    >>> from twolink import TwoLinkArm
    >>> from twolink_course import alttext
    >>> link_1, link_2 = draw_free_bodies(
    ...     TwoLinkArm(1.0, 1.0), np.radians([30.0, 60.0]), [0.0, -10.0])
    >>> link_2.get_title(), [text.get_text() for text in link_2.texts][:1]
    ('Link 2', ['$-F$ = 10.0 N'])
    >>> print(alttext.describe(link_1.figure).split(". ")[1])
    Link 1 from the base (0.00, 0.00) m to the elbow (0.87, 0.50) m: the base pushes it with f01 = F, 10.0 N at -90° from the x-axis; link 2 pushes it at the elbow with -f12, 10.0 N at 90° from the x-axis; motor 1 turns it with τ1 = 8.66 N m, clockwise, and the reaction of motor 2 with -τ2 = 0.00 N m
    >>> plt.close(link_1.figure)
    """
    require_arm(arm)
    q_arm = as_configuration(q)
    f_by_tip = as_configuration(
        force_by_tip, "force_by_tip", "one force (Fx, Fy)", "newtons"
    )
    if axes is None:
        figure, pair = plt.subplots(1, 2, figsize=(8.0, 4.0), dpi=figure_style.DPI)
        axes = (pair[0], pair[1])
    elif (
        not isinstance(axes, (tuple, list))
        or len(axes) != 2
        or not all(isinstance(ax, Axes) for ax in axes)
    ):
        raise InputTypeError(
            "draw_free_bodies: axes must be a pair of matplotlib Axes (link 1, link 2), "
            f"or None for a new figure; got {axes!r}"
        )
    magnitude = float(np.hypot(*f_by_tip))
    # torques within round-off of zero are zero (drawn and said so)
    zero_tol = 1e-9 * max(1.0, magnitude * (arm.l1 + arm.l2))
    tau_1, tau_2 = (
        float(v) if abs(v) > zero_tol else 0.0
        for v in arm.joint_torques(q_arm, f_by_tip)
    )
    base, elbow, tip = arm.joint_positions(q_arm)
    length = 0.45 * max(arm.l1, arm.l2)
    scale = length / magnitude if magnitude > 0 else 1.0
    radius = 0.18 * min(arm.l1, arm.l2)
    f_12 = f_by_tip  # link 1 on link 2, at the elbow
    f_01 = f_by_tip  # the base on link 1

    panels = (
        (
            axes[0],
            "Link 1",
            (base, elbow),
            [("$f_{01}$", base, f_01), ("$-f_{12}$", elbow, -f_12)],
            [(r"$\tau_1$", base, tau_1), (r"$-\tau_2$", elbow, -tau_2)],
            f"Link 1 from the base {point_text(base)} to the elbow {point_text(elbow)}: "
            f"the base pushes it with f01 = F, {_force_words(f_01)}; link 2 pushes it "
            f"at the elbow with -f12, {_force_words(-f_12)}; motor 1 turns it with "
            f"τ1 = {_torque_words(tau_1)}, and the reaction of motor 2 with "
            f"-τ2 = {_torque_words(-tau_2)}",
        ),
        (
            axes[1],
            "Link 2",
            (elbow, tip),
            [("$-F$", tip, -f_by_tip), ("$f_{12}$", elbow, f_12)],
            [(r"$\tau_2$", elbow, tau_2)],
            f"Link 2 from the elbow {point_text(elbow)} to the tip {point_text(tip)}: "
            f"the wall pushes the tip with -F, {_force_words(-f_by_tip)}; link 1 "
            f"pushes it at the elbow with f12 = F, {_force_words(f_12)}; motor 2 turns "
            f"it with τ2 = {_torque_words(tau_2)}",
        ),
    )
    for ax, title, ends, forces, torques, sentence in panels:
        ax = axes_or_current(ax, "draw_free_bodies")
        drawn: list[Artist] = []
        (link,) = ax.plot(
            *np.transpose(ends),
            color=figure_style.ARM.color,
            linewidth=4.0,
            solid_capstyle="round",
            marker="o",
            markersize=8,
            markerfacecolor=figure_style.BACKGROUND,
        )
        extent = list(ends)
        along_link = _unit(ends[1] - ends[0])
        across = np.array([-along_link[1], along_link[0]])  # the link's left normal
        for number, (name, point, force) in enumerate(forces):
            drawn.append(draw_force(point, force, scale, ax=ax))
            head = point + scale * force
            # beside the arrow's middle, on one side of the link, the sides
            # alternating: two forces on one line (a link pushed along its length)
            # keep their labels apart
            side = 1.0 if number % 2 == 0 else -1.0
            label_at = (point + head) / 2 + side * 0.4 * length * across
            extent += [head, label_at]
            drawn.append(
                _label(
                    ax,
                    label_at,
                    f"{name} = {quantity_text(float(np.hypot(*force)), 'N')}",
                    figure_style.FORCE.color,
                )
            )
        for number, (name, point, tau) in enumerate(torques):
            drawn.append(draw_torque(point, tau, radius, ax=ax, zero_tol=zero_tol))
            # the first torque's label below its joint, the second's above
            label_at = point + np.array([0.0, (-1.9 if number == 0 else 1.9) * radius])
            extent.append(label_at)
            drawn.append(
                _label(
                    ax,
                    label_at,
                    f"{name} = {quantity_text(tau, 'N m')}",
                    figure_style.TORQUE.color,
                )
            )
        box = np.array(extent)
        low, high = box.min(axis=0) - 1.6 * radius, box.max(axis=0) + 1.6 * radius
        ax.set_xlim(low[0], high[0])
        ax.set_ylim(low[1], high[1])
        ax.set_aspect("equal")
        ax.grid(True, alpha=0.3)
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        ax.set_title(title)
        record(link, sentence, parts=drawn)
    return axes[0], axes[1]


def _unit(vector: NDArray[np.float64]) -> NDArray[np.float64]:
    norm = float(np.hypot(*vector))
    return vector / norm if norm > 0 else np.array([0.0, 1.0])


def _torque_words(tau: float) -> str:
    turning = _turning(tau)
    return (
        quantity_text(tau, "N m")
        if turning == "zero"
        else (f"{quantity_text(abs(tau), 'N m')}, {turning}")
    )
