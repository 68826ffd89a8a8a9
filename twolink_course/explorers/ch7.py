"""Chapter 7's workspace figures and its explorer of joint limits.

:func:`draw_workspace` draws what the chapter shows of a workspace, layer by
layer: sampled configurations within the limits by elbow branch, every
candidate arc thin and dashed, the boundary arcs thick, the singular circles
grey and dotted, and, shaded grey, what lies within the links' reach but not
within the limits.  :class:`LimitsExplorer` draws the same layers for the
10 + 10 m arm once, with the largest circle that fits, and moves them to any
limits (either convention) and elbow choice.

How the explorer keeps up with the hand: what does not depend on the limits
is computed once, when it is made: random configurations over all joint
angles (a move shows those within the limits) and a
:class:`twolink.workspace.BranchTable` of the shading grid and one of the
samples' tips (both IK branches at every point, solved once).  A move only
compares those angles with the new limits (the rule of
:func:`twolink.ik.solutions_within_limits`).  The boundary arcs are exact
(:func:`twolink.workspace.boundary_arcs`) after every move; the largest circle
is a grid search (:func:`twolink.workspace.largest_circle_on_grid`), always a
circle that fits but possibly a little short of the largest, marked with
"≈"; the button :attr:`LimitsExplorer.exact_button` runs the optimiser,
:func:`twolink.workspace.largest_inscribed_circle`, instead.
``tests/course/test_explorers_ch7.py`` checks the shortcuts against the package.

Examples
--------
>>> from twolink import arms
>>> import matplotlib.pyplot as plt
>>> fig, ax = plt.subplots()
>>> round(draw_workspace(arms.ten, ax, samples=200), 2)  # the reach's share out of reach
0.8
>>> plt.close(fig)
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np
from matplotlib.axes import Axes
from matplotlib.colors import to_rgba
from matplotlib.figure import Figure
from matplotlib.legend import Legend
from matplotlib.lines import Line2D
from matplotlib.patches import Circle, Patch
from matplotlib.spines import Spine
from matplotlib.text import Text
from numpy.typing import NDArray

from twolink import TwoLinkArm, workspace
from twolink._optional import require
from twolink.arcs import Arc

from .. import alttext, explorer, figure_style, plot
from ..display import rounded

__all__ = [
    "SAMPLE_STYLE",
    "LOST",
    "SINGULAR",
    "LARGEST",
    "draw_circle",
    "draw_workspace",
    "workspace_legend",
    "LimitsExplorer",
]

#: How each layer of a workspace figure looks.
SAMPLE_STYLE: dict[str, Any] = {
    "linestyle": "none",
    "markersize": 2.0,
    "markeredgewidth": 0,
    "alpha": 0.5,
}
LOST: dict[str, Any] = {
    "color": figure_style.GREY,
    "alpha": 0.3,
}  # in reach, not within limits
SINGULAR: dict[str, Any] = {
    "color": figure_style.GREY,
    "linestyle": ":",
    "linewidth": 1.5,
}
LARGEST: dict[str, Any] = {
    "color": figure_style.SKY_BLUE,
    "linewidth": 2.5,
    "zorder": 3,
}


def draw_circle(ax: Axes, centre: Any, radius: float, **style: Any) -> Circle:
    """An outline circle on ``ax`` (a singular circle, a circle to trace); returns the patch."""
    circle = Circle(centre, radius, fill=False, **style)
    ax.add_patch(circle)
    return circle


def _shade_unreachable(
    arm: TwoLinkArm, ax: Axes, elbow: str, resolution: int = 260
) -> float:
    """Grey where a point is in the reach annulus but not reachable within the limits."""
    extent = arm.reach[1] * 1.1
    axis = np.linspace(-extent, extent, resolution)
    grid = np.stack(np.meshgrid(axis, axis), axis=-1)
    radius = np.hypot(grid[..., 0], grid[..., 1])
    in_reach = (radius <= arm.reach[1]) & (radius >= arm.reach[0])
    lost = in_reach & ~workspace.is_reachable(arm, grid, elbow=elbow)
    shading = ax.contourf(
        axis,
        axis,
        lost.astype(float),
        levels=[0.5, 1.5],
        colors=[LOST["color"]],
        alpha=LOST["alpha"],
    )
    lost_fraction = float(lost.mean() / max(in_reach.mean(), 1e-12))
    alttext.record(
        shading,
        f"Shaded: the {100 * lost_fraction:.0f}% of the links' reach that the limits "
        "leave out of reach (grid estimate)",
    )
    return lost_fraction


def _draw_samples(arm: TwoLinkArm, ax: Axes, elbow: str, samples: int) -> None:
    """Sampled configurations within the limits, by branch: elbow down dots, elbow up diamonds."""
    p_samples, q_samples = workspace.sample_reachable(arm, samples, seed=1)
    down = np.sin(q_samples[:, 1]) >= 0
    keep = workspace.is_reachable(arm, p_samples, elbow=elbow)
    dots = []
    for branch, role, label in (
        (down, figure_style.ELBOW_DOWN, "elbow down"),
        (~down, figure_style.ELBOW_UP, "elbow up"),
    ):
        dots += ax.plot(
            *p_samples[keep & branch].T,
            color=role.color,
            marker=role.marker,
            **SAMPLE_STYLE,
            label=label,
        )
    alttext.record(
        dots[0],
        f"The tips of {samples} configurations sampled within the limits, marked by "
        "elbow branch (down, up)",
        parts=dots,
    )


def _draw_arcs(arm: TwoLinkArm, ax: Axes, elbow: str) -> None:
    """Every candidate arc thin and dashed, then the boundary arcs thick, each kind labelled once."""
    kinds = (
        (workspace.candidate_arcs(arm), "--", 1.0, "limit and singular arcs"),
        (workspace.boundary_arcs(arm, elbow=elbow), "-", 2.0, "boundary"),
    )
    for arcs, style, width, label in kinds:
        lines = [
            ax.plot(
                *arc.points(120).T,
                color=figure_style.BLACK,
                linestyle=style,
                linewidth=width,
                label=label if index == 0 else None,
            )[0]
            for index, arc in enumerate(arcs)
        ]
        if label == "boundary":
            said = [
                f"{arc.label} (r = {alttext.quantity_text(arc.radius, 'm')})"
                for arc in arcs
            ]
            sentence = f"The boundary, {len(arcs)} arcs: {alttext.listed(said)}"
        else:
            sentence = (
                f"The {len(arcs)} limit and singular arcs that could bound it, dashed"
            )
        alttext.record(lines[0], sentence, parts=lines)


def _draw_singular_circles(arm: TwoLinkArm, ax: Axes) -> None:
    """The stretched and folded circles, grey dotted (a grey dot if their radius is 0)."""
    drawn: list[Any] = []
    for index, radius in enumerate(arm.reach):
        if radius > 0:
            label = "singular circles" if index == 1 else None
            drawn.append(draw_circle(ax, (0, 0), radius, **SINGULAR, label=label))
        else:
            drawn += ax.plot([0], [0], "o", color=SINGULAR["color"], markersize=4)
    radii = [
        f"r = {alttext.quantity_text(radius, 'm')}"
        if radius > 0
        else "the base (r = 0)"
        for radius in arm.reach
    ]
    alttext.record(
        drawn[-1],
        f"The singular circles, arm stretched or folded: {alttext.listed(radii[::-1])}",
        parts=drawn,
    )


def draw_workspace(
    arm: TwoLinkArm,
    ax: Axes,
    elbow: str = "auto",
    samples: int = 1200,
    title: str | None = None,
) -> float:
    """Draw ``arm``'s workspace on ``ax``; return the share of the reach annulus it leaves out.

    Layers: the lost area shaded grey, sampled configurations by branch, the
    candidate arcs (thin, dashed), the boundary arcs for ``elbow`` (thick) and
    the singular circles (grey, dotted); each records its text alternative.
    """
    plot.setup_axes(arm, ax=ax, title=title)
    lost_fraction = _shade_unreachable(arm, ax, elbow)
    _draw_samples(arm, ax, elbow, samples)
    _draw_arcs(arm, ax, elbow)
    _draw_singular_circles(arm, ax)
    return lost_fraction


def workspace_legend(fig: Figure, ax: Axes, **where: Any) -> Legend:
    """One legend for ``ax``'s layers and the shaded area, outside the axes (``loc=``, ``ncols=``)."""
    handles = ax.get_legend_handles_labels()[0]
    handles.append(Patch(**LOST, label="in reach, not within the limits"))
    legend = fig.legend(handles=handles, **where)
    for handle, shown in zip(handles, legend.legend_handles):
        if str(handle.get_label()).startswith("elbow") and isinstance(shown, Line2D):
            shown.set_markersize(6)  # the tiny samples: larger here
    return legend


def _arc_polyline(arcs: list[Arc]) -> tuple[Any, Any]:
    """The arcs as one line, NaN between them: one artist for any number of arcs."""
    if not arcs:
        return [], []
    points = np.vstack([np.vstack([arc.points(120), [np.nan, np.nan]]) for arc in arcs])
    return points[:, 0], points[:, 1]


class LimitsExplorer:
    """The limits explorer's figure: the 10 + 10 m arm's workspace for any limits.

    Parameters
    ----------
    arm : TwoLinkArm
        The links (its limits are replaced by the controls').
    grid : int
        Points per side of the shading grid.
    samples : int
        Configurations drawn over all joint angles, once.
    stride, tolerance : int, float
        The circle search starts from every ``stride``-th grid point and stops
        when its grid is finer than ``tolerance`` metres.

    Attributes
    ----------
    figure : matplotlib.figure.Figure
    exact_button : ipywidgets.Button
        Runs the optimiser for the current limits (wire it with :meth:`connect`).
    shown : dict
        What the figure shows: the arm with its limits, the branch, the number
        of boundary arcs, the circle's radius and the reachable share.
    """

    def __init__(
        self,
        arm: TwoLinkArm,
        grid: int = 200,
        samples: int = 5600,
        stride: int = 5,
        tolerance: float = 0.005,
    ) -> None:
        self.arm, self.stride, self.tolerance = arm, stride, tolerance
        extent = arm.reach[1]  # the grid covers the reach disc, edge to edge
        axis = np.linspace(-extent, extent, grid)
        self.grid_size, self.grid_spacing = grid, float(axis[1] - axis[0])
        self.grid_points = np.stack(np.meshgrid(axis, axis), axis=-1).reshape(-1, 2)
        self.grid_in_reach = np.hypot(*self.grid_points.T) <= extent
        on_search = np.zeros((grid, grid), dtype=bool)
        on_search[::stride, ::stride] = True  # the search's start points
        self.on_search = on_search.ravel()
        # uniform over all (q1, q2), so over all link angles (q1, q1 + q2) too
        self.sample_q = np.random.default_rng(1).uniform(
            -np.pi, np.pi, size=(samples, 2)
        )
        self.sample_tips = arm.fk(self.sample_q)
        self.sample_down = np.sin(self.sample_q[:, 1]) >= 0  # elbow-down configurations
        # both IK branches at every grid point and sample tip, once: the limits change,
        # the links do not
        self.grid_table = workspace.BranchTable(arm, self.grid_points)
        self.sample_tip_table = workspace.BranchTable(arm, self.sample_tips)
        self.figure, self.ax = explorer.explorer_figure(4.0, 4.0)
        ax = self.ax
        # per grid point: clear, or the lost area's grey (LOST, 30%: the grid shows through)
        self.colours = np.round(
            255 * np.array([(0, 0, 0, 0), to_rgba(LOST["color"], LOST["alpha"])])
        ).astype(np.uint8)
        self.lost_image = ax.imshow(
            self.colours[np.zeros((grid, grid), dtype=int)],
            extent=(-extent, extent) * 2,
            origin="lower",
            interpolation="nearest",
            zorder=0.6,  # over the ticks and grid (0.5), under everything else
        )
        plot.setup_axes(
            arm, ax=ax, title=f"{arm.l1:g} + {arm.l2:g} m arm within the limits set"
        )
        for child in ax.get_children():
            if isinstance(
                child, (Spine, Text)
            ):  # the frame and the titles: under the image
                child.set_zorder(0.55)
        self.samples_down, self.samples_up = (
            ax.plot([], [], color=role.color, marker=role.marker, **SAMPLE_STYLE)[0]
            for role in (figure_style.ELBOW_DOWN, figure_style.ELBOW_UP)
        )
        self.candidate_line = ax.plot(
            [], [], color=figure_style.BLACK, linestyle="--", linewidth=1.0
        )[0]
        self.boundary_line = ax.plot([], [], color=figure_style.BLACK, linewidth=2.0)[0]
        draw_circle(ax, (0, 0), extent, **SINGULAR)
        ax.plot(
            [0], [0], "o", color=SINGULAR["color"], markersize=4
        )  # the folded arm: r = 0
        self.circle = draw_circle(ax, (0, 0), 1.0, **LARGEST)
        self.shown: dict[str, Any] = {}
        widgets = require("ipywidgets", "twolink_course.explorers.ch7.LimitsExplorer")
        self.exact_button = widgets.Button(
            description="exact largest circle", layout=widgets.Layout(width="14em")
        )

    def limited(
        self, q1: tuple[float, float], q2: tuple[float, float], limits: str
    ) -> TwoLinkArm:
        """The arm with limits given in degrees, each range as ``(low, high)``."""
        return replace(
            self.arm,
            q_min=tuple(np.radians([q1[0], q2[0]])),
            q_max=tuple(np.radians([q1[1], q2[1]])),
            limit_convention=limits,
        )

    def samples_within(self, arm: TwoLinkArm, branch: str) -> NDArray[np.bool_]:
        """The sampled configurations within the limits (their own branch at their tip),
        whose tips count for ``branch``."""
        valid = self.sample_tip_table.within_limits(arm)  # (n, 2): elbow down, up
        shown = np.where(self.sample_down, valid[:, 0], valid[:, 1])
        if branch != "auto":  # the tip reached within the limits on that branch
            shown &= valid[:, {"down": 0, "up": 1}[branch]]
        return shown

    def update(
        self, q1: tuple[float, float], q2: tuple[float, float], limits: str, elbow: str
    ) -> None:
        """Move every layer to the workspace for these limits (degrees) and elbow choice."""
        arm = self.limited(q1, q2, limits)
        branch = "auto" if elbow == "either" else elbow
        reachable = self.grid_table.reachable(arm, elbow=branch)
        lost = (self.grid_in_reach & ~reachable).reshape(self.grid_size, -1)
        self.lost_image.set_data(self.colours.take(lost.view(np.uint8), axis=0))
        within = self.samples_within(arm, branch)
        self.samples_down.set_data(*self.sample_tips[within & self.sample_down].T)
        self.samples_up.set_data(*self.sample_tips[within & ~self.sample_down].T)
        self.candidate_line.set_data(*_arc_polyline(workspace.candidate_arcs(arm)))
        arcs = workspace.boundary_arcs(arm, elbow=branch)
        self.boundary_line.set_data(*_arc_polyline(arcs))
        candidates = self.grid_points[reachable & self.on_search]
        if len(candidates) == 0:  # a sliver of a workspace between the search points
            candidates = self.grid_points[reachable]
        centre, radius = workspace.largest_circle_on_grid(
            arcs, candidates, self.stride * self.grid_spacing, self.tolerance
        )
        self.circle.set_visible(centre is not None)
        if centre is not None:
            self.circle.set_center((float(centre[0]), float(centre[1])))
            self.circle.set_radius(radius)
        self.shown = {
            "arm": arm,
            "branch": branch,
            "arcs": len(arcs),
            "radius": radius,
            "exact": None,
            "kept": np.count_nonzero(reachable) / np.count_nonzero(self.grid_in_reach),
        }

    def _heading(self, elbow: str) -> str:
        arm = self.shown["arm"]
        return (
            f"The workspace of the {arm.l1:g} + {arm.l2:g} m arm with "
            f"{workspace.describe_limits(arm)}, elbow {elbow}: "
        )

    def show_exact(self) -> None:
        """The optimiser's largest circle for the limits shown, until the next move."""
        try:
            centre, radius = workspace.largest_inscribed_circle(
                self.shown["arm"], starts=3, elbow=self.shown["branch"]
            )
        except ValueError:  # no area reachable: the sentence says so already
            return
        self.circle.set_center((float(centre[0]), float(centre[1])))
        self.circle.set_radius(radius)
        self.circle.set_visible(True)
        self.shown["exact"] = (centre, radius)

    def describe(self, q1: Any, q2: Any, limits: str, elbow: str) -> str:
        """The sentence under the figure."""
        text = self._heading(elbow)
        if self.shown["exact"] is not None:
            centre, radius = self.shown["exact"]
            found = (
                "the optimiser (workspace.largest_inscribed_circle, 3 starts) finds the "
                f"largest circle r = {rounded(radius, 3, 'm')}, centred at "
                f"({centre[0]:.2f}, {centre[1]:.2f}) m"
            )
            if self.shown["radius"] is None:
                return text + found + "; the grid search finds none."
            return (
                text
                + found
                + (
                    f", drawn in place of the grid search's circle (r ≈ "
                    f"{rounded(self.shown['radius'], 2, 'm')})."
                )
            )
        if self.shown["radius"] is None:
            return text + "no area is reachable, so no circle fits."
        return text + (
            f"{self.shown['arcs']} boundary arcs, about "
            f"{rounded(100 * self.shown['kept'], 0)}% of the disc the links sweep is "
            "reachable, and the largest circle the grid search finds has r ≈ "
            f"{rounded(self.shown['radius'], 2, 'm')}."
        )

    def connect(self, view: explorer.Explorer) -> None:
        """Wire :attr:`exact_button` to ``view``: the optimiser's circle, then its redraw."""

        def exact_circle(button: Any) -> None:
            self.show_exact()
            view.redraw(self.describe(**view.values))

        self.exact_button.on_click(exact_circle)
