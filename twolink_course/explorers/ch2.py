"""Chapter 2's explorer and figures: both IK branches for a target, and the tip-error map of a grid search.

:class:`TargetBranches` draws an arm's reach, both closed-form branches (elbow
down solid, elbow up dashed, dotted when a branch leaves the joint limits), the
target and a note for a target out of reach, once, and moves them for a target
``(x, y)``; :func:`draw_branches` draws both branches of a few targets, side by
side; :func:`draw_tip_error_map` draws the tip error over a joint grid, with the
closed-form branches and a grid search's answer on it.  The chapter builds each
in a few lines; how they keep up with the hand (artists drawn once and moved,
the legend under the axes, below what moves) lives here.

Examples
--------
>>> from twolink import arms
>>> view = TargetBranches(arms.ten)
>>> view.update(x=5.0, y=15.0)
>>> print(view.describe(x=5.0, y=15.0))
Target (5, 15) m, 15.81 m from the base, inside the reach 0-20 m: elbow down at q = (33.8°, 75.5°), within limits; elbow up at q = (109.3°, -75.5°), outside limits.
>>> view.update(x=18.0, y=12.0)
>>> view.ax.get_title()
'(18, 12) m is out of reach'
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from matplotlib import patheffects
from matplotlib.axes import Axes
from matplotlib.colors import LogNorm
from matplotlib.lines import Line2D
from numpy.typing import ArrayLike, NDArray

from twolink import TwoLinkArm, UnreachableError, ik

from .. import alttext, explorer, figure_style, plot
from ..display import angles_deg, rounded

__all__ = ["BRANCH_ROLES", "TargetBranches", "draw_branches", "draw_tip_error_map"]

#: How the two branches look: elbow down (q2 >= 0) solid, elbow up (q2 <= 0) dashed.
BRANCH_ROLES = (figure_style.ARM, figure_style.ELBOW_UP)
BRANCH_NAMES = ("down", "up")


def _limits_text(arm: TwoLinkArm, q: NDArray[np.float64]) -> str:
    return "within limits" if arm.within_limits(q) else "outside limits"


class TargetBranches:
    """Both closed-form branches of an arm for a target ``(x, y)``, moved as the target moves.

    Parameters
    ----------
    arm : TwoLinkArm
        An arm with joint limits (``within_limits``), such as ``twolink.arms.ten``.

    Attributes
    ----------
    figure : matplotlib.figure.Figure
        The explorer's figure (:func:`twolink_course.explorer.explorer_figure`).
    ax : matplotlib.axes.Axes
    branch_lines : list of matplotlib.lines.Line2D
        The elbow-down and elbow-up arms.
    """

    def __init__(self, arm: TwoLinkArm) -> None:
        self.arm = arm
        self.figure, self.ax = explorer.explorer_figure(4.0, 4.6)
        plot.setup_axes(arm, ax=self.ax)
        plot.draw_reach(arm, ax=self.ax)
        self.branch_lines = [
            plot.draw_arm(arm, [0.0, 0.0], ax=self.ax, role=role, label=label)
            for role, label in zip(
                BRANCH_ROLES, ("elbow down (q2 ≥ 0)", "elbow up (q2 ≤ 0)")
            )
        ]
        (self.target_mark,) = self.ax.plot(
            [], [], **figure_style.TARGET.line(), markersize=10, label="target"
        )
        outside_limits = Line2D(
            [], [], color=figure_style.GREY, linewidth=2, linestyle=":"
        )
        outside_limits.set_label("dotted: outside limits")
        # under the axes, below the moving artists: a move never redraws the legend
        self.ax.legend(
            handles=[*self.branch_lines, self.target_mark, outside_limits],
            loc="upper center",
            bbox_to_anchor=(0.5, -0.13),
            ncols=2,
        ).set_zorder(1.5)
        # the note for a target out of reach, in the corner away from it (no arm there)
        self.notes = {
            corner: plot.draw_note("", ax=self.ax, corner=corner)
            for corner in ("lower left", "upper right")
        }

    def solve(
        self, x: float, y: float
    ) -> tuple[NDArray[np.float64] | None, UnreachableError | None]:
        """Both branches ``[down, up]`` for the target and no error, or no branches and the error."""
        try:
            return ik.closed_form(self.arm, [x, y], elbow="both").q, None
        except UnreachableError as error:
            return None, error

    def update(self, x: float, y: float) -> None:
        """Move the target to ``(x, y)`` m and the arms to its branches (or say why there are none)."""
        self.target_mark.set_data([x], [y])
        q_both, error = self.solve(x, y)
        corner = "upper right" if x + y < 0 else "lower left"
        for line in self.branch_lines:
            line.set_visible(q_both is not None)
        for name, note in self.notes.items():
            note.set_visible(error is not None and name == corner)
        if q_both is None:
            self.ax.set_title(f"({x:g}, {y:g}) m is out of reach")
            self.notes[corner].set_text(
                f"no solution: {rounded(np.hypot(x, y), 2, 'm')} from the base,\n"
                f"beyond the reach of {self.arm.reach[1]:g} m"
            )
            return
        self.ax.set_title(f"target ({x:g}, {y:g}) m")
        for line, role, q in zip(self.branch_lines, BRANCH_ROLES, q_both):
            plot.move_arm(line, self.arm, q)
            line.set_linestyle(role.linestyle if self.arm.within_limits(q) else ":")

    def describe(self, x: float, y: float) -> str:
        """The sentence under the figure: both branches' angles and limits, or why there are none."""
        q_both, error = self.solve(x, y)
        if q_both is None:
            return f"No solution: {error}."
        down, up = (f"{angles_deg(q)}, {_limits_text(self.arm, q)}" for q in q_both)
        r_min, r_max = self.arm.reach
        return (
            f"Target ({x:g}, {y:g}) m, {rounded(np.hypot(x, y), 2, 'm')} from the base, "
            f"inside the reach {r_min:g}-{r_max:g} m: elbow down at q = {down}; "
            f"elbow up at q = {up}."
        )


def draw_branches(
    arm: TwoLinkArm,
    targets: Sequence[ArrayLike],
    titles: Sequence[str],
    axes: Sequence[Axes],
) -> list[NDArray[np.float64]]:
    """Draw both closed-form branches of each target on its own axes; return each target's ``[down, up]``.

    Each axes shows the reach, the two arms (labelled with their angles, the
    legend under the axes) and the target.

    Examples
    --------
    >>> import matplotlib.pyplot as plt
    >>> from twolink import arms
    >>> fig, axes = plt.subplots(1, 2)
    >>> q = draw_branches(arms.ten, [(15, 10), (-15, 10)], ["right", "left"], axes)
    >>> np.degrees(q[0][:, 1]).round(3)
    array([ 51.318, -51.318])
    >>> plt.close(fig)
    """
    found = []
    for ax, p_target, title in zip(axes, targets, titles, strict=True):
        q_both = ik.closed_form(arm, p_target, elbow="both").q
        plot.setup_axes(arm, ax=ax, title=title)
        plot.draw_reach(arm, ax=ax)
        for q, role, name in zip(q_both, BRANCH_ROLES, BRANCH_NAMES):
            plot.draw_arm(arm, q, ax=ax, role=role, label=f"{name}: {angles_deg(q)}")
        x, y = np.asarray(p_target, dtype=float)
        (mark,) = ax.plot([x], [y], **figure_style.TARGET.line(), markersize=10)
        mark.set_label("target")
        alttext.record(mark, f"The target at {alttext.point_text(p_target)}")
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.18))
        found.append(q_both)
    return found


def draw_tip_error_map(
    arm: TwoLinkArm,
    p_target: ArrayLike,
    q_grid_answer: ArrayLike,
    grid_step: float,
    *,
    ax: Axes,
    unit: str = "m",
) -> NDArray[np.float64]:
    """The tip error over the arm's joint ranges, as colour on a log scale, for one target.

    Drawn on a grid of 181 by 361 points over the arm's joint limits (finer
    than the search's ``grid_step``), with white contours at 0.5, 1 and 2
    (``unit``, the arm's length unit), both closed-form branches (filled markers) and the
    grid search's answer ``q_grid_answer`` (a cross with a light edge); the
    legend goes under the figure.  Returns the map's values, shape (181, 361).

    Examples
    --------
    >>> import matplotlib.pyplot as plt
    >>> from twolink import arms
    >>> fig, ax = plt.subplots()
    >>> errors = draw_tip_error_map(arms.ten, [15.0, 10.0], np.radians([8.0, 51.0]), np.radians(1.0), ax=ax)
    >>> errors.shape, bool(errors.min() < 0.05)
    ((181, 361), True)
    >>> plt.close(fig)
    """
    if arm.q_min is None or arm.q_max is None:
        raise ValueError(
            "arm must have joint limits (q_min, q_max): the map covers them"
        )
    (q1_low, q2_low), (q1_high, q2_high) = arm.q_min, arm.q_max
    q1_axis = np.linspace(q1_low, q1_high, 181)
    q2_axis = np.linspace(q2_low, q2_high, 361)
    q_grid = np.stack(np.meshgrid(q1_axis, q2_axis, indexing="ij"), axis=-1)
    errors = np.hypot(*np.moveaxis(arm.fk(q_grid) - np.asarray(p_target), -1, 0))
    q1_deg, q2_deg = np.degrees(q1_axis), np.degrees(q2_axis)
    norm = LogNorm(vmin=1e-2, vmax=30.0)
    image = ax.pcolormesh(q1_deg, q2_deg, errors.T, norm=norm, shading="nearest")
    alttext.record(
        image,
        f"The tip error for the target {alttext.point_text(p_target)} over q1 from "
        f"{q1_deg[0]:g}° to {q1_deg[-1]:g}° and q2 from {q2_deg[0]:g}° to "
        f"{q2_deg[-1]:g}°, in colour: two basins of small error, one around each "
        "closed-form branch",
    )
    scale = ax.figure.colorbar(image, ax=ax, label=f"tip error [{unit}]")
    assert scale.solids is not None  # drawn by colorbar
    alttext.record(
        scale.solids,
        f"The colour scale: tip error on a log scale from {norm.vmin:g} {unit} (dark "
        f"blue) to {norm.vmax:g} {unit} (yellow)",
        parts=[scale.dividers],
    )
    levels = [0.5, 1.0, 2.0]
    contours = ax.contour(
        q1_deg,
        q2_deg,
        errors.T,
        levels=levels,
        colors=figure_style.BACKGROUND,
        linewidths=0.7,
    )
    listed = alttext.listed([f"{level:g}" for level in levels])
    alttext.record(contours, f"White contours of the tip error at {listed} {unit}")
    for q, role, name in zip(
        ik.closed_form(arm, p_target, elbow="both").q, BRANCH_ROLES, BRANCH_NAMES
    ):
        ax.plot(
            *np.degrees(q),
            linestyle="none",
            marker=role.marker,
            color=role.color,
            markeredgecolor=figure_style.BACKGROUND,
            markersize=11,
            label=f"closed form, {name}",
        )
    ax.plot(
        *np.degrees(np.asarray(q_grid_answer, dtype=float)),
        linestyle="none",
        marker="+",
        color=figure_style.BLACK,
        markersize=9,
        markeredgewidth=1.5,
        path_effects=[
            patheffects.withStroke(linewidth=3, foreground=figure_style.BACKGROUND)
        ],
        label=f"brute force, {np.degrees(grid_step):g}° grid",
    )
    ax.set_xlabel("q1 [deg]")
    ax.set_ylabel("q2 [deg]")
    ax.figure.legend(loc="outside lower center", ncols=2)
    return errors
