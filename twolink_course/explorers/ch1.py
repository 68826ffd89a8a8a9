"""Chapter 1's explorer and figure: the arm at joint angles given in degrees, and its two angle conventions.

:class:`ArmAngles` draws an arm, its reach and a title once and moves the arm
for joint angles given in degrees (the sliders' unit); :func:`draw_angle_conventions`
draws one pose of an arm with the arcs of ``q1``, the relative ``q2`` (DH) and the
absolute ``q2_abs = q1 + q2``.  The chapter builds its explorer from
:class:`ArmAngles` in a few lines; how it keeps up with the hand (the figure
drawn once, a move that changes one line and one title) lives here.

Examples
--------
>>> from twolink import arms
>>> view = ArmAngles(arms.osake, "the OSAKE arm")
>>> view.update(q1=30, q2=45)
>>> view.ax.get_title()
'q1 = 30°, q2 = 45°'
>>> print(view.describe(q1=30, q2=45))
The OSAKE arm at q = (30°, 45°): tip at x = 0.1164 m, y = 0.1611 m, z = 0.0650 m; link 2 at 75° from the x-axis.
"""

from __future__ import annotations

import numpy as np
from matplotlib.axes import Axes
from matplotlib.patches import Arc
from numpy.typing import ArrayLike

from twolink import TwoLinkArm, to_absolute

from .. import alttext, explorer, figure_style, plot

__all__ = ["ArmAngles", "draw_angle_conventions"]


class ArmAngles:
    """An arm on square axes sized to its reach, moved to joint angles in degrees.

    Parameters
    ----------
    arm : TwoLinkArm
    name : str
        What the sentence under the figure calls the arm ("the OSAKE arm").

    Attributes
    ----------
    figure : matplotlib.figure.Figure
        The explorer's figure (:func:`twolink_course.explorer.explorer_figure`).
    ax : matplotlib.axes.Axes
    arm_line : matplotlib.lines.Line2D
        The arm, moved by :meth:`update`.
    """

    def __init__(self, arm: TwoLinkArm, name: str) -> None:
        self.arm, self.name = arm, name
        self.figure, self.ax = explorer.explorer_figure(4.0, 4.0)
        plot.setup_axes(arm, ax=self.ax)
        plot.draw_reach(arm, ax=self.ax)
        self.arm_line = plot.draw_arm(arm, [0.0, 0.0], ax=self.ax)

    def update(self, q1: float, q2: float) -> None:
        """Move the arm to ``(q1, q2)`` in degrees, converted to radians first."""
        plot.move_arm(self.arm_line, self.arm, np.radians([q1, q2]))
        self.ax.set_title(f"q1 = {q1:g}°, q2 = {q2:g}°")

    def describe(self, q1: float, q2: float) -> str:
        """The sentence under the figure: the tip and link 2's direction at ``(q1, q2)`` degrees."""
        q = np.radians([q1, q2])
        x, y = self.arm.fk(q)
        link2_deg = np.degrees(to_absolute(q)[1])
        return (
            f"{self.name[0].upper()}{self.name[1:]} at q = ({q1:g}°, {q2:g}°): "
            f"tip at x = {x:.4f} m, y = {y:.4f} m, z = {self.arm.d:.4f} m; "
            f"link 2 at {link2_deg:.0f}° from the x-axis."
        )


def draw_angle_conventions(arm: TwoLinkArm, q: ArrayLike, *, ax: Axes) -> list[Arc]:
    """Draw the arm at ``q`` (radians) with the arcs of ``q1``, ``q2`` (relative) and ``q2_abs``.

    Dotted guides show what each angle is measured from: the x-axis at the
    base, link 1 carried on past the elbow, and the horizontal at the elbow.
    Each arc has its own colour and line style (``figure_style.SERIES``) and a
    legend entry; the figure's text alternative gives the three angles.

    Returns
    -------
    list of matplotlib.patches.Arc
        The arcs of ``q1``, ``q2`` and ``q2_abs``.

    Examples
    --------
    >>> import matplotlib.pyplot as plt
    >>> from twolink import arms
    >>> _, ax = plt.subplots()
    >>> arcs = draw_angle_conventions(arms.two_metre, np.radians([35.0, 70.0]), ax=ax)
    >>> [round(arc.theta2 - arc.theta1) for arc in arcs]
    [35, 70, 105]
    >>> plt.close(ax.figure)
    """
    q = np.asarray(q, dtype=float)
    q_abs = to_absolute(q)
    plot.draw_arm(arm, q, ax=ax)
    base, elbow, _ = arm.joint_positions(q)
    along_link_1 = (elbow - base) / np.linalg.norm(elbow - base)
    reach = arm.reach[1]
    guides = [
        ax.plot(*np.transpose([start, end]), color=figure_style.GREY, linestyle=":")[0]
        for start, end in (
            (base, base + [0.75 * reach, 0.0]),
            (elbow, elbow + [0.55 * reach, 0.0]),
            (elbow, elbow + 0.3 * reach * along_link_1),
        )
    ]
    arcs_drawn = [
        (base, 0.30, 0.0, q[0], "q1"),
        (elbow, 0.22, q[0], q_abs[1], "q2 (relative, DH)"),
        (elbow, 0.38, 0.0, q_abs[1], "q2_abs = q1 + q2"),
    ]
    arcs = [
        Arc(
            centre,
            2 * share * reach,
            2 * share * reach,
            theta1=np.degrees(min(start, stop)),  # counter-clockwise, the short way
            theta2=np.degrees(max(start, stop)),
            color=series.color,
            linestyle=series.linestyle,
            linewidth=2,
            label=label,
        )
        for (centre, share, start, stop, label), series in zip(
            arcs_drawn, figure_style.SERIES
        )
    ]
    for arc in arcs:
        ax.add_patch(arc)
    q1, q2, q2_abs = (f"{np.degrees(value):.0f}°" for value in (*q, q_abs[1]))
    alttext.record(
        arcs[0],
        f"Arcs mark q1 = {q1} at the base, from the x-axis to link 1; q2 = {q2} at "
        f"the elbow, from link 1 carried on to link 2; and q2_abs = {q2_abs} at the "
        "elbow, from the horizontal to link 2",
        parts=[*arcs[1:], *guides],
    )
    return arcs
