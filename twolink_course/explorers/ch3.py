"""Chapter 3's explorer and figures: the velocity ellipse, rates along a line, and two resolved-rate motions.

:class:`VelocityEllipse` draws an arm, its reach and its velocity ellipse
(around the tip, at a stated scale) once and moves them for joint angles in
degrees.  :func:`draw_line_rates` plots joint rates along a line with a
table's rows on it; :func:`draw_velocity_ellipses` draws an arm's ellipse at
a few poses; :func:`draw_manipulability_map` maps the manipulability over the
workspace; :func:`draw_circle_velocities` draws a tip's velocity arrows round
its circle; :func:`draw_rates_and_tracking`, :func:`draw_motion_strobes` and
:func:`animate_motions` draw what two resolved-rate motions of the same line
(the exact inverse and damped least squares) do: their joint rates and their
distance from the line, a strobe of each, and both arms moving together.  The
chapter computes the motions and builds each figure in one call; the drawing
(colours and line styles per motion and joint, text alternatives from the
data) lives here.

Examples
--------
>>> from twolink import arms
>>> view = VelocityEllipse(arms.osake, scale=0.4)
>>> view.update(q1=30, q2=60)
>>> print(view.describe(q1=30, q2=60))
The OSAKE arm at q = (30°, 60°) and its velocity ellipse (the tip velocities for |q̇| ≤ 1 rad/s, drawn around the tip at 0.4 m per m/s). Its semi-axes are σ1 = 0.214 and σ2 = 0.047 m/s per rad/s, the long one at -20° from the x-axis; the manipulability is w = 99.6 cm².
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
from matplotlib.axes import Axes
from matplotlib.lines import Line2D
from matplotlib.patches import Circle
from numpy.typing import ArrayLike

from twolink import TwoLinkArm, ik, velocity
from twolink.trajectory import JointTrajectory

from .. import alttext, explorer, figure_style, plot
from ..display import rounded

__all__ = [
    "VelocityEllipse",
    "draw_line_rates",
    "draw_velocity_ellipses",
    "draw_manipulability_map",
    "draw_circle_velocities",
    "draw_rates_and_tracking",
    "draw_motion_strobes",
    "animate_motions",
]


class VelocityEllipse:
    """An arm and its velocity ellipse, moved to joint angles given in degrees.

    Parameters
    ----------
    arm : TwoLinkArm
    scale : float
        Metres of figure per m/s of tip velocity (stated under the axes).
    name : str
        What the sentence under the figure calls the arm.

    Attributes
    ----------
    figure : matplotlib.figure.Figure
        The explorer's figure (:func:`twolink_course.explorer.explorer_figure`).
    ax : matplotlib.axes.Axes
    ellipse, arm_line :
        What :meth:`update` moves.
    """

    def __init__(
        self, arm: TwoLinkArm, scale: float, name: str = "the OSAKE arm"
    ) -> None:
        self.arm, self.scale, self.name = arm, scale, name
        self.figure, self.ax = explorer.explorer_figure(4.0, 4.0)
        plot.setup_axes(arm, ax=self.ax)
        plot.draw_reach(arm, ax=self.ax)
        self.ellipse = plot.draw_ellipse(
            velocity.velocity_ellipse(arm, [0.0, np.pi / 2]), ax=self.ax, scale=scale
        )
        self.arm_line = plot.draw_arm(arm, [0.0, 0.0], ax=self.ax, linewidth=3.0)
        # the scale under the axes: a note inside them would hide the arm or the ellipse
        self.ax.set_xlabel(f"x [m]; ellipse drawn at {scale} m per m/s")

    def update(self, q1: float, q2: float) -> None:
        """Move the arm and its ellipse to ``(q1, q2)`` in degrees; the title gives w and the semi-axes."""
        q = np.radians([q1, q2])
        ellipse = velocity.velocity_ellipse(self.arm, q)
        plot.move_ellipse(self.ellipse, ellipse, scale=self.scale)
        plot.move_arm(self.arm_line, self.arm, q)
        sigma_1, sigma_2 = ellipse.semi_axes
        w_cm2 = 1e4 * float(self.arm.manipulability(q))
        self.ax.set_title(
            f"q1 = {q1:g}°, q2 = {q2:g}°: w = {w_cm2:.1f} cm²,\n"
            f"σ1 = {sigma_1:.3f}, σ2 = {sigma_2:.3f} m/s per rad/s"
        )

    def describe(self, q1: float, q2: float) -> str:
        """The sentence under the figure: the ellipse's semi-axes, its direction and w, or the singular pose."""
        q = np.radians([q1, q2])
        ellipse = velocity.velocity_ellipse(self.arm, q)
        sigma_1, sigma_2 = ellipse.semi_axes
        long_axis_deg = (
            90 - (90 - round(float(np.degrees(ellipse.angle)))) % 180
        )  # -90 is 90
        sentence = (
            f"{self.name[0].upper()}{self.name[1:]} at q = ({q1:g}°, {q2:g}°) and its "
            "velocity ellipse (the tip velocities for |q̇| ≤ 1 rad/s, drawn around the "
            f"tip at {self.scale} m per m/s). "
        )
        if q2 % 180 == 0:  # exactly stretched or folded
            shape = "stretched" if q2 == 0 else "folded"
            return sentence + (
                f"The arm is {shape}, a singular pose: the ellipse is a segment "
                f"{rounded(2 * sigma_1, 3, 'm/s')} long at {long_axis_deg}° from the "
                "x-axis, and the manipulability w is 0."
            )
        w_cm2 = 1e4 * float(self.arm.manipulability(q))
        return sentence + (
            f"Its semi-axes are σ1 = {rounded(sigma_1, 3)} and σ2 = {rounded(sigma_2, 3)} "
            f"m/s per rad/s, the long one at {long_axis_deg}° from the x-axis; the "
            f"manipulability is w = {rounded(w_cm2, 1, 'cm²')}."
        )


def draw_line_rates(
    x_fine: ArrayLike,
    rates_fine: ArrayLike,
    x_table: ArrayLike,
    rates_table: ArrayLike,
    x_edge: float,
    *,
    ax: Axes,
) -> None:
    """Joint rates (deg/s, one column per joint) along a line: a curve, the table's rows as markers, the edge.

    The joints differ in colour and line style, the table's rows in marker
    shape too; a dashed vertical line marks ``x_edge``, where the arm is
    stretched.  The text alternative gives each curve's first and last rate.
    """
    x_fine, rates_fine = np.asarray(x_fine), np.asarray(rates_fine)
    for joint, (series, marker) in enumerate(zip(figure_style.SERIES, ("o", "s"))):
        name, rates = f"q̇{joint + 1}", rates_fine[:, joint]
        (line,) = ax.plot(x_fine, rates, **series.line(), label=name)
        start, end = (alttext.quantity_text(rates[i], "°/s") for i in (0, -1))
        alttext.record(
            line,
            f"{name} from {start} at x = {x_fine[0]:.1f} m to {end} at x = "
            f"{x_fine[-1]:.3f} m",
        )
        (marks,) = ax.plot(
            x_table,
            np.asarray(rates_table)[:, joint],
            marker,
            color=series.color,
            label=f"{name}, table",
        )
        rows = len(np.asarray(x_table))
        alttext.record(marks, f"{name} at the table's {rows} rows, on its line")
    edge = ax.axvline(x_edge, **figure_style.REACH.line(), linewidth=1)
    text = ax.text(
        x_edge - 0.02,
        0.3,
        "arm stretched\n(q2 = 0)",
        ha="right",
        transform=ax.get_xaxis_transform(),
    )
    alttext.record(
        edge,
        f"The workspace's edge at x = {x_edge:.3f} m, where the arm is stretched (q2 = 0)",
        parts=[text],
    )
    ax.set_ylabel("joint rate [deg/s]")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="lower left")


def draw_velocity_ellipses(
    arm: TwoLinkArm, poses_deg: dict[str, ArrayLike], scale: float, axes: Sequence[Axes]
) -> None:
    """The arm and its velocity ellipse at each pose (degrees), one axes each, titled with w."""
    for ax, (title, q_deg) in zip(axes, poses_deg.items(), strict=True):
        q = np.radians(np.asarray(q_deg, dtype=float))
        w = float(arm.manipulability(q))
        plot.setup_axes(arm, ax=ax, margin=0.1, title=f"{title},\nw = {w:.4f} m²")
        plot.draw_reach(arm, ax=ax)
        plot.draw_ellipse(velocity.velocity_ellipse(arm, q), ax=ax, scale=scale)
        plot.draw_arm(arm, q, ax=ax, linewidth=3.0)


def draw_manipulability_map(arm: TwoLinkArm, *, ax: Axes, points: int = 201) -> float:
    """Manipulability ``w`` (cm²) over the workspace in filled contours, with its best circle dotted.

    Returns the largest ``w`` on the grid, m².
    """
    extent = arm.reach[1] * 1.05
    x_grid, y_grid = np.meshgrid(*[np.linspace(-extent, extent, points)] * 2)
    r_grid = np.hypot(x_grid, y_grid)
    inside = (r_grid >= arm.reach[0]) & (r_grid <= arm.reach[1])
    w_grid = np.full(x_grid.shape, np.nan)  # NaN: outside the workspace, not drawn
    targets = np.stack([x_grid, y_grid], axis=-1)[inside]
    w_grid[inside] = arm.manipulability(ik.closed_form(arm, targets).q)
    w_map = ax.contourf(x_grid, y_grid, w_grid * 1e4, levels=12)  # the style's cividis
    bar = ax.figure.colorbar(w_map, ax=ax, label="w [cm²]")
    largest = float(np.nanmax(w_grid))
    alttext.record(
        w_map,
        "The manipulability w over the workspace in filled contours, from 0 on the "
        f"reach circles to {1e4 * largest:.0f} cm² on the circle of largest w",
    )
    levels = np.asarray(w_map.levels)
    low, high = (alttext.plain_number(float(level)) for level in levels[[0, -1]])
    alttext.record(
        bar.ax.collections[0],
        f"The colour scale of w, from {low} to {high} cm² in {len(levels) - 1} bands",
        parts=bar.ax.collections,
    )
    plot.draw_reach(arm, ax=ax)
    r_best = float(np.hypot(arm.l1, arm.l2))
    circle = ax.add_patch(
        Circle(
            (0, 0),
            r_best,
            fill=False,
            color=figure_style.BLACK,
            linestyle=":",
            linewidth=1.5,
        )
    )
    alttext.record(
        circle,
        f"A dotted circle of radius {rounded(1e3 * r_best, 1, 'mm')}, where q2 = ±90°",
    )
    ax.set(aspect="equal", xlabel="x [m]", ylabel="y [m]")
    return largest


def draw_circle_velocities(
    arm: TwoLinkArm, q: ArrayLike, qd: ArrayLike, scale: float, *, ax: Axes
) -> None:
    """The tip's circle (``q`` with joint 1 turning at the rates ``qd``), one arm pose and the velocity arrows.

    ``scale`` is in metres of figure per m/s; the arrows are tangent to the
    circle, and the text alternative says which way they turn.
    """
    q, qd = np.asarray(q, dtype=float), np.asarray(qd, dtype=float)
    p, v = arm.fk(q), arm.tip_velocity(q, qd)
    radius = float(np.linalg.norm(p[0]))
    plot.draw_reach(arm, ax=ax)
    circle = ax.add_patch(
        Circle((0, 0), radius, fill=False, **figure_style.PATH.line(), linewidth=1.2)
    )
    alttext.record(circle, f"The tip's circle, radius {rounded(1e3 * radius, 2, 'mm')}")
    plot.draw_arm(arm, q[1], ax=ax, linewidth=3.0)
    arrows = ax.quiver(
        p[:, 0],
        p[:, 1],
        v[:, 0],
        v[:, 1],
        angles="xy",
        scale_units="xy",
        scale=1 / scale,
        color=figure_style.VERMILLION,
        width=0.008,
    )
    cross = p[0, 0] * v[0, 1] - p[0, 1] * v[0, 0]  # z of p x v: > 0 counter-clockwise
    turning = "counter-clockwise" if cross > 0 else "clockwise"
    alttext.record(
        arrows,
        f"{len(p)} arrows of the tip velocity round the circle, tangent to it, "
        f"{turning}, all of the same length",
    )


def _motions(
    motions: Sequence[JointTrajectory], names: Sequence[str]
) -> list[tuple[JointTrajectory, str, figure_style.Role]]:
    if len(motions) != len(names) or len(motions) > len(figure_style.SERIES):
        raise ValueError(
            f"give one name per motion, at most {len(figure_style.SERIES)}; got "
            f"{len(motions)} motions and {len(names)} names"
        )
    return list(zip(motions, names, figure_style.SERIES))


def draw_rates_and_tracking(
    motions: Sequence[JointTrajectory],
    names: Sequence[str],
    axes: tuple[Axes, Axes],
) -> None:
    """Joint rates (left) and distance from the line point (right) of each motion, against time.

    Each motion has a colour of its own (``figure_style.SERIES``); on the
    left, joint 1 is drawn in the motion's line style and joint 2 in a
    dotted or dash-dotted one.  The text alternative gives each line's
    largest magnitude.
    """
    ax_rates, ax_error = axes
    for (motion, name, look), q2_style in zip(_motions(motions, names), (":", "-.")):
        for joint, style in enumerate((look.linestyle, q2_style)):
            _series(
                ax_rates,
                motion.t,
                motion.qd[:, joint],
                "joint rate",
                "rad/s",
                f"q̇{joint + 1}, {name}",
                look,
                style,
                1,
            )
        _series(
            ax_error,
            motion.t,
            1e3 * motion.tracking_error(),
            "distance from the line point",
            "mm",
            name,
            look,
            look.linestyle,
            0,
        )
    # where no line runs: right of the spike, left of the peak
    ax_rates.legend(loc="lower right")
    ax_error.legend(loc="upper left")


def _series(
    ax: Axes,
    t: Any,
    values: Any,
    quantity: str,
    unit: str,
    label: str,
    look: figure_style.Role,
    linestyle: str,
    decimals: int,
) -> None:
    (line,) = plot.plot_time_series(
        t,
        values,
        quantity,
        unit,
        [label],
        ax=ax,
        colors=[look.color],
        linestyle=linestyle,
    )
    largest = rounded(np.abs(values).max(), decimals, unit)
    alttext.record(line, f"{quantity}, {label}: largest magnitude {largest}")


def _reference_line(ax: Axes, start: ArrayLike, goal: ArrayLike) -> Line2D:
    """The line the tip should follow, wide and light under everything."""
    (line,) = ax.plot(
        *np.stack([start, goal]).T,
        color=figure_style.GREY,
        alpha=0.4,
        linewidth=6.0,
        solid_capstyle="butt",
        zorder=1,
        label="reference line",
    )
    alttext.record(
        line,
        f"The reference line from {alttext.point_text(start)} to "
        f"{alttext.point_text(goal)}, wide and light",
    )
    return line


def draw_motion_strobes(
    arm: TwoLinkArm,
    motions: Sequence[JointTrajectory],
    titles: Sequence[str],
    line: tuple[ArrayLike, ArrayLike],
    axes: Sequence[Axes],
    poses: int = 9,
    extent: float | None = None,
) -> None:
    """A strobe of each motion on its own axes: equally spaced poses fading in, over the reference line.

    Poses in the elbow-down branch (``sin q2 > 0``) are drawn solid, those
    in the elbow-up branch dashed with diamond joints; each axes shows the
    tip's path too, and ``x`` and ``y`` from ``-extent`` to ``extent`` metres
    when given.  The legend (of the last axes) goes under the figure.
    """
    for ax, motion, title in zip(axes, motions, titles, strict=True):
        samples = np.linspace(0, len(motion.t) - 1, poses).round().astype(int)
        plot.setup_axes(arm, ax=ax, margin=0.05, title=title)
        _reference_line(ax, *line)
        elbow_down = np.sin(motion.q[samples, 1]) > 0
        drawn = []
        for role, shown, name in (
            (figure_style.ELBOW_DOWN, elbow_down, "elbow down (sin q2 > 0)"),
            (figure_style.ELBOW_UP, ~elbow_down, "elbow up (sin q2 < 0)"),
        ):
            if shown.any():
                q_shown = motion.q[samples[shown]]
                strobe = plot.draw_strobe(
                    arm, q_shown, ax=ax, frames=len(q_shown), path=False, role=role
                )
                strobe[-1].set_label(name)  # the most opaque pose of the branch
                said = alttext.recorded(strobe[0]) or ""
                alttext.record(
                    strobe[0], said.replace("The arm", f"The arm, {name},", 1)
                )
                drawn += strobe
        for rank, pose in enumerate(drawn):  # fading in over the whole motion
            pose.set_alpha(0.25 + 0.75 * rank / max(len(drawn) - 1, 1))
        (path,) = ax.plot(
            *motion.p_tip.T, **figure_style.PATH.line(), label="tip's path"
        )
        alttext.record(
            path,
            f"The tip's path from {alttext.point_text(motion.p_tip[0])} to "
            f"{alttext.point_text(motion.p_tip[-1])}",
        )
        if extent is not None:
            ax.set(xlim=(-extent, extent), ylim=(-extent, extent))
    axes[-1].figure.legend(
        *axes[-1].get_legend_handles_labels(), loc="outside lower center", ncols=2
    )


def animate_motions(
    arm: TwoLinkArm,
    solid: JointTrajectory,
    dashed: JointTrajectory,
    line: tuple[ArrayLike, ArrayLike],
    title: str,
    every: int = 10,
    extent: float | None = None,
) -> Any:
    """Both motions in one animation: ``solid`` as the arm, ``dashed`` as a dashed arm tracing its tip.

    Every ``every``-th sample is a frame, on axes from ``-extent`` to
    ``extent`` metres when given; returns what
    :func:`twolink_course.plot.animation_html` shows.
    """
    frames = slice(None, None, every)
    q_solid, q_dashed = solid.q[frames], dashed.q[frames]
    ax = plot.setup_axes(arm, size=(4.5, 4.5))
    _reference_line(ax, *line)
    dashed_arm = plot.draw_arm(
        arm, q_dashed[0], ax=ax, role=figure_style.ELBOW_UP, linewidth=3.0
    )
    (trace,) = ax.plot(
        [], [], color=figure_style.ELBOW_UP.color, linestyle="--", linewidth=1.2
    )
    tips = arm.fk(q_dashed)
    alttext.record(
        dashed_arm,
        f"The dashed arm in the same frames, from q = {alttext.angles_text(q_dashed[0])} "
        f"to {alttext.angles_text(q_dashed[-1])}, tracing its tip's path to "
        f"{alttext.point_text(tips[-1])}",
        parts=[trace],
    )

    def move_dashed(frame: int) -> list[Any]:
        points = arm.joint_positions(q_dashed[frame])
        dashed_arm.set_data(points[:, 0], points[:, 1])
        trace.set_data(tips[: frame + 1, 0], tips[: frame + 1, 1])
        return [dashed_arm, trace]

    animation = plot.animate_arm(
        arm, q_solid, t=solid.t[frames], ax=ax, extra=move_dashed, title=title
    )
    if extent is not None:
        ax.set(xlim=(-extent, extent), ylim=(-extent, extent))
    return plot.animation_html(animation)
