"""Chapter 4's explorer: the arm pushing on a wall, its force ellipse and its torques.

:class:`WallPushView` draws the wall, the contacts of :func:`twolink.wall_contact`
(rings), the arm, its force ellipse, the push ``F`` and the two motor torques
once, and moves them for a tip position along the wall, a push and an elbow
branch.  Every move is the closed-form inverse kinematics and ``J^T F``:
nothing is approximated to keep up with the hand.

Examples
--------
>>> import numpy as np
>>> from twolink import Wall, arms, wall_contact
>>> wall = Wall.through([4.0, 0.0], [0.0, 4.0])
>>> view = WallPushView(arms.two_metre, [4.0, 0.0], [0.0, 4.0], wall_contact(arms.two_metre, wall, 500.0))
>>> view.start_position(0.005)
0.18
>>> view.update(position=0.18, force=500.0, elbow="down")
>>> print(view.describe(position=0.18, force=500.0, elbow="down"))
The 2 m arm, elbow down, has its tip at position 0.180 on the wall, (3.28, 0.72) m, and
pushes 500 N into it: τ = (905.1, -5.1) N m; link 2 is 0.3° from the wall's normal (0° at
this elbow's contact, a ring on the wall). Its force ellipse (|τ| ≤ 1 N m) has semi-axes
1.0 N and 0.26 N.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.transforms import Affine2D
from numpy.typing import ArrayLike, NDArray

from twolink import TwoLinkArm, Wall, ik, to_absolute, velocity
from twolink.statics import WallContact

from .. import explorer, figure_style, plot
from ..display import rounded, significant

__all__ = ["WallPushView"]

#: Figure metres per newton of the force ellipse (|tau| <= 1 N m), and its longest drawn semi-axis.
ELLIPSE_SCALE, ELLIPSE_CLIP = 1.0, 1.5
#: Figure metres per newton of the push F.
FORCE_SCALE = 2e-3
#: The axes' limits, metres: the wall segment, every elbow and every ellipse as drawn.
LIMITS = (-2.6, 5.6)
#: Torques below this are drawn as zero (a dotted circle), N m.
ZERO_TORQUE = 1e-9


class WallPushView:
    """The wall explorer's figure: drawn once, moved by :meth:`update`.

    Parameters
    ----------
    arm : TwoLinkArm
    wall_start, wall_end : array_like, shape (2,)
        The wall segment the tip slides along (position 0 and 1), metres.
    contacts : twolink.statics.WallContact
        The contacts where link 2 is perpendicular to the wall, drawn as rings.

    Attributes
    ----------
    figure : matplotlib.figure.Figure
        The explorer's figure (an ipympl canvas, :func:`twolink_course.explorer.explorer_figure`).
    """

    def __init__(
        self,
        arm: TwoLinkArm,
        wall_start: ArrayLike,
        wall_end: ArrayLike,
        contacts: WallContact,
    ) -> None:
        self.arm = arm
        self.wall_start = np.asarray(wall_start, dtype=float)
        self.wall_end = np.asarray(wall_end, dtype=float)
        self.wall: Wall = Wall.through(self.wall_start, self.wall_end)
        self.contacts = contacts
        self.figure, self.ax = explorer.explorer_figure(4.0, 4.0)
        ax = self.ax
        plot.setup_axes(arm, ax=ax)
        ax.set_xlim(*LIMITS)
        ax.set_ylim(*LIMITS)
        half = 0.5 * float(np.linalg.norm(self.wall_end - self.wall_start)) + 1.2
        fixed = [
            *plot.draw_wall(self.wall, ax=ax, half_length=half),
            *ax.plot(
                *contacts.p_contact.T,
                "o",
                color=figure_style.TARGET.color,
                fillstyle="none",
                markersize=11,
            ),
            plot.draw_note(
                f"force ellipse (|τ| ≤ 1 N m):\n1 N drawn as {ELLIPSE_SCALE:g} m, "
                f"at most {ELLIPSE_CLIP:g} m\nF: 100 N drawn as {100 * FORCE_SCALE:g} m",
                ax=ax,
            ),
        ]
        for part in fixed:  # under every moving part: a move does not redraw them
            part.set_zorder(0.9)
        q_start = contacts.q[contacts.branch("down")]
        self.ellipse = plot.draw_ellipse(
            velocity.force_ellipse(arm, q_start),
            ax=ax,
            scale=ELLIPSE_SCALE,
            clip=ELLIPSE_CLIP,
        )
        self.arm_line = plot.draw_arm(arm, q_start, ax=ax)
        tip = arm.fk(q_start)
        self.push = plot.draw_force(
            tip, contacts.force_by_tip, ax=ax, scale=FORCE_SCALE
        )
        self.torque_marks = [
            self._torque_marks(radius=0.55, start=np.pi),
            self._torque_marks(radius=0.45),
        ]

    def _torque_marks(self, radius: float, start: float = 0.0) -> dict[float, Any]:
        """A joint's three marks (counter-clockwise, clockwise, none) about (0, 0)."""
        return {
            sign: plot.draw_torque(
                [0.0, 0.0], sign, ax=self.ax, radius=radius, start=start
            )
            for sign in (1.0, -1.0, 0.0)
        }

    def start_position(self, step: float) -> float:
        """The slider step nearest the elbow-down contact, as a position along the wall.

        >>> from twolink import Wall, arms, wall_contact
        >>> wall = Wall.through([4.0, 0.0], [0.0, 4.0])
        >>> WallPushView(arms.two_metre, [4, 0], [0, 4], wall_contact(arms.two_metre, wall, 1.0)).start_position(0.1)
        0.2
        """
        along = self.wall_end - self.wall_start
        contact = self.contacts.p_contact[self.contacts.branch("down")]
        exact = float((contact - self.wall_start) @ along / (along @ along))
        return round(round(exact / step) * step, 10)

    def state(
        self, position: float, force: float, elbow: str
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], float]:
        """The pose, the torques ``J^T F`` and link 2's angle from the wall's normal (deg)."""
        p_tip = self.wall_start + position * (self.wall_end - self.wall_start)
        q = ik.closed_form(self.arm, p_tip, elbow=elbow).q
        into = self.wall.into_wall()
        tau = self.arm.joint_torques(q, force * into).round(6) + 0.0  # no -0.0
        off = np.degrees(to_absolute(q)[1] - np.arctan2(into[1], into[0]))
        return q, tau, round((off + 180.0) % 360.0 - 180.0, 6) + 0.0

    def update(self, position: float, force: float, elbow: str) -> None:
        """Move the arm, the ellipse, the push and the torque marks; the torques in the title."""
        q, tau, _ = self.state(position, force, elbow)
        base, elbow_point, tip = self.arm.joint_positions(q)
        plot.move_arm(self.arm_line, self.arm, q)
        plot.move_ellipse(
            self.ellipse,
            velocity.force_ellipse(self.arm, q),
            scale=ELLIPSE_SCALE,
            clip=ELLIPSE_CLIP,
        )
        self.push.set_positions(
            tuple(tip), tuple(tip + FORCE_SCALE * force * self.wall.into_wall())
        )
        self.push.set_visible(force > 0)
        for marks, centre, torque in zip(self.torque_marks, (base, elbow_point), tau):
            shown = 0.0 if abs(torque) <= ZERO_TORQUE else float(np.sign(torque))
            for sign, mark in marks.items():
                mark.set_transform(Affine2D().translate(*centre) + self.ax.transData)
                mark.set_visible(sign == shown)
        self.ax.set_title(f"τ1 = {tau[0]:+.1f} N m, τ2 = {tau[1]:+.1f} N m")

    def describe(self, position: float, force: float, elbow: str) -> str:
        """The sentence under the figure: where the tip is, the torques, link 2's angle, the ellipse."""
        q, tau, off_normal = self.state(position, force, elbow)
        longest, shortest = velocity.force_ellipse(self.arm, q).semi_axes
        if np.isfinite(longest):
            ellipse = (
                f"has semi-axes {significant(longest, 2, 'N')} and "
                f"{significant(shortest, 2, 'N')}"
            )
        else:
            ellipse = (
                f"is unbounded along the stretched arm, {significant(shortest, 2, 'N')} "
                "across it"
            )
        lengths = {f"{self.arm.l1:g} m", f"{self.arm.l2:g} m"}
        return (
            f"The {' + '.join(sorted(lengths))} arm, elbow {elbow}, has its tip at position "
            f"{position:.3f} on the wall, {rounded(self.arm.fk(q), 2, 'm')}, and pushes "
            f"{force:g} N into it: τ = {rounded(tau, 1, 'N m')}; link 2 is "
            f"{rounded(off_normal, 1, '°')} from the wall's normal (0° at this elbow's "
            f"contact, a ring on the wall). Its force ellipse (|τ| ≤ 1 N m) {ellipse}."
        )
