"""Chapter 6's explorer: impedance control brings the arm back to its rest point.

:class:`ImpedanceRelease` draws, once, a strobe of the first half second after
a release at rest and the tip's distance from the rest point over 1.5 s, as a
fraction of the distance it started from (the *offset*), and moves them to
the stiffness ``k``, the damping ``d`` and the start point set by the
controls.  The sentence under the figure gives the smallest damping ratio at
the rest point, ``zeta = d / (2 sqrt(k lambda_max))`` with ``lambda_max`` the
heavy eigenvalue of the tip mass (chapter 6, section 5), and where the tip is
at the end.

How it keeps up with the hand: gravity compensation cancels the weight
exactly, so each move integrates the arm lying flat under the spring and the
damper alone, ``tau = J^T (k (x0 - x) - d J qd)``, written out with floats
(:func:`impedance_law`, the torques of
:class:`twolink.controllers.Impedance` without ``g(q)``), with
:func:`twolink.simulation.simulate_quick` (scipy's compiled ``odeint``) at a
looser tolerance and with a budget of evaluations.  A stiff spring with little
damping swings too fast for that budget: the figure then says so, and the
button :attr:`ImpedanceRelease.exact_button` simulates the current values with
:func:`twolink.simulate` and :class:`twolink.controllers.Impedance` at a tight
tolerance.  ``tests/course/test_explorers_ch6.py`` holds the live run to the exact one.
The distance axis holds every release: the spring's energy never exceeds what
it held at the release (the damper only takes energy out), so the curve stays
below 1.

Examples
--------
>>> from twolink import arms
>>> view = ImpedanceRelease(arms.two_metre, [3.0, 1.0])
>>> view.update(k=600.0, d=58.0, x_start=3.0, y_start=2.0)
>>> print(view.describe(k=600.0, d=58.0, x_start=3.0, y_start=2.0))
Released at rest from (3.0, 2.0) m, 1.00 m from the rest point (3, 1), with k = 600 N/m
and d = 58 N s/m: the smallest damping ratio at the rest point is 1.01; after 1.5 s the
live run's tip is below 0.01 m from the rest point.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from twolink import (
    SimulationError,
    TwoLinkArm,
    UnreachableError,
    controllers,
    ik,
    linearization,
    simulate,
)
from twolink._optional import require
from twolink.simulation import simulate_quick

from .. import explorer, figure_style, plot
from ..display import below, rounded, significant

__all__ = [
    "ImpedanceRelease",
    "impedance_law",
    "LIVE",
    "EXACT_IMPEDANCE",
    "LIVE_EVALUATIONS",
]

#: The live run's tolerances (simulate_quick's LSODA) and its budget of evaluations.
LIVE: dict[str, float] = {"rtol": 1e-3, "atol": 1e-4}
LIVE_EVALUATIONS = 400
#: The exact run's tolerances (simulate, DOP853's default method RK45 replaced by the chapter's).
EXACT_IMPEDANCE: dict[str, float] = {"rtol": 1e-8, "atol": 1e-8}

TorqueLaw = Callable[[float, NDArray[np.float64], NDArray[np.float64]], list[float]]


def impedance_law(
    arm: TwoLinkArm, rest_point: ArrayLike, k: float, d: float
) -> TorqueLaw:
    """``tau = J^T (k (x0 - x) - d J qd)`` in floats: impedance control without ``g(q)``.

    The torques of :class:`twolink.controllers.Impedance` with scalar gains,
    minus its gravity compensation, computed with ``math`` on two floats (a
    fraction of the array version's time per call, which a live run makes
    hundreds of times).

    >>> from twolink import arms, controllers
    >>> law = impedance_law(arms.two_metre, [3.0, 1.0], 600.0, 58.0)
    >>> q, qd = np.array([0.1, 1.2]), np.array([0.3, -0.4])
    >>> full = controllers.Impedance(arms.two_metre, 600.0, 58.0, [3.0, 1.0])
    >>> np.allclose(law(0.0, q, qd), full(0.0, q, qd) - arms.two_metre.gravity(q))
    True
    """
    l1, l2 = arm.l1, arm.l2
    x_rest, y_rest = (float(value) for value in np.asarray(rest_point, dtype=float))

    def torque(
        t: float, q: NDArray[np.float64], qd: NDArray[np.float64]
    ) -> list[float]:
        (q1, q2), (qd1, qd2) = q.tolist(), qd.tolist()
        c1, s1 = math.cos(q1), math.sin(q1)
        c12, s12 = math.cos(q1 + q2), math.sin(q1 + q2)
        x, y = l1 * c1 + l2 * c12, l1 * s1 + l2 * s12
        # J = [[-y, -l2 s12], [x, l2 c12]]; F = k (x0 - x) - d J qd
        force_x = k * (x_rest - x) + d * (y * qd1 + l2 * s12 * qd2)
        force_y = k * (y_rest - y) - d * (x * qd1 + l2 * c12 * qd2)
        return [x * force_y - y * force_x, l2 * (c12 * force_y - s12 * force_x)]

    return torque


class ImpedanceRelease:
    """The impedance explorer's figure: a strobe of the release and the tip's distance from rest.

    Parameters
    ----------
    arm : TwoLinkArm
        The (vertical) arm; its weight is compensated.
    rest_point : array_like, shape (2,)
        The spring's rest point ``x0``, metres, reached on the elbow-down branch.

    Attributes
    ----------
    figure : matplotlib.figure.Figure
    exact_button : ipywidgets.Button
        Simulates the current values exactly (wire it with :meth:`connect`).
    shown : dict
        What the figure shows now: ``state`` (``"live"``, ``"exact"``, ``"fast"``,
        ``"unreachable"`` or ``"at rest"``) and the run's numbers.
    """

    def __init__(self, arm: TwoLinkArm, rest_point: ArrayLike) -> None:
        self.arm = arm
        self.flat = dataclasses.replace(arm, g=0.0)  # gravity compensated: the flat arm
        self.rest = np.asarray(rest_point, dtype=float)
        self.q_rest = ik.closed_form(arm, self.rest, elbow="down").q
        self.t_live = np.linspace(0.0, 1.5, 76)  # s, every 0.02 s
        self.t_exact = np.linspace(0.0, 1.5, 301)  # s, every 0.005 s
        self.strobe_times = np.linspace(0.0, 0.5, 6)  # s, the poses the strobe shows
        self.heavy_mass = float(
            np.linalg.eigvalsh(linearization.tip_mass(arm, self.q_rest))[-1]
        )
        self.figure, (self.ax_arm, self.ax_distance) = explorer.explorer_figure(
            7.2, 2.9, ncols=2, gridspec_kw={"width_ratios": [1.0, 1.4]}
        )
        self.titles = {
            "live": f"first {self.strobe_times[-1]:.1f} s after the release",
            "exact": f"exact run, first {self.strobe_times[-1]:.1f} s",
            "fast": "fast swings: press 'exact run'",
            "unreachable": "start out of reach",
            "at rest": "released at the rest point",
        }
        plot.setup_axes(arm, ax=self.ax_arm, title=self.titles["live"])
        self.ax_arm.plot(
            *self.rest, **figure_style.TARGET.line(), markersize=10, label="rest point"
        )
        self.strobe = plot.draw_strobe(
            arm,
            [self.q_rest] * len(self.strobe_times),
            ax=self.ax_arm,
            frames=len(self.strobe_times),
        )
        (self.distance_line,) = plot.plot_time_series(
            self.t_live,
            np.zeros_like(self.t_live),
            "|x - x0| / offset",
            "-",
            ["simulated"],
            ax=self.ax_distance,
        )
        self.ax_distance.set(xlim=(0.0, self.t_live[-1]), ylim=(0.0, 1.1))
        self.ax_distance.axhline(
            1.0, color=figure_style.GREY, linestyle=":", linewidth=0.8
        )
        self.ax_distance.get_legend().remove()
        self.ax_distance.set_title("the tip's distance from x0")
        # the moving artists over everything else in their axes: a move redraws them alone
        for artist in [*self.strobe, self.distance_line]:
            artist.set_zorder(4)
        self.shown: dict[str, Any] = {}
        self._exact_runs: dict[tuple[float, ...], NDArray[np.float64]] = {}
        widgets = require("ipywidgets", "twolink_course.explorers.ch6.ImpedanceRelease")
        self.exact_button = widgets.Button(
            description="exact run",
            tooltip=f"simulate the current values at tolerance {significant(EXACT_IMPEDANCE['rtol'], 1)}",
        )

    def smallest_damping_ratio(self, k: float, d: float) -> float:
        """``d / (2 sqrt(k lambda_max))``: the heavy direction's damping ratio at the rest point."""
        return d / (2.0 * math.sqrt(k * self.heavy_mass))

    def live_run(
        self, k: float, d: float, q_start: NDArray[np.float64]
    ) -> NDArray[np.float64] | None:
        """The joint angles at :attr:`t_live` on the flat arm; ``None`` past the budget."""
        law = impedance_law(self.arm, self.rest, k, d)
        try:
            run = simulate_quick(
                self.flat,
                q_start,
                np.zeros(2),
                self.t_live,
                law,
                max_evaluations=LIVE_EVALUATIONS,
                rtol=LIVE["rtol"],
                atol=LIVE["atol"],
            )
        except (
            SimulationError
        ):  # out of budget: fast swings (passive: it cannot blow up)
            return None
        return run.q

    def exact_run(
        self, k: float, d: float, q_start: NDArray[np.float64]
    ) -> NDArray[np.float64]:
        """The joint angles at :attr:`t_exact`: ``simulate`` with ``controllers.Impedance``, tight."""
        controller = controllers.Impedance(self.arm, k, d, self.rest)
        run = simulate(
            self.arm,
            q_start,
            np.zeros(2),
            self.t_exact[-1],
            torque=controller,
            t_eval=self.t_exact,
            rtol=EXACT_IMPEDANCE["rtol"],
            atol=EXACT_IMPEDANCE["atol"],
        )
        return run.q

    def _release(
        self, k: float, d: float, x_start: float, y_start: float
    ) -> dict[str, Any]:
        try:
            q_start = ik.closed_form(self.arm, [x_start, y_start]).q
        except UnreachableError:
            return {"state": "unreachable"}
        offset = float(np.hypot(x_start - self.rest[0], y_start - self.rest[1]))
        if offset < 1e-9:
            return {
                "state": "at rest",
                "q": np.array([q_start] * len(self.t_live)),
                "t": self.t_live,
            }
        shown: dict[str, Any] = {
            "offset": offset,
            "zeta": self.smallest_damping_ratio(k, d),
        }
        q_exact = self._exact_runs.get((k, d, x_start, y_start))
        if q_exact is not None:
            return {**shown, "state": "exact", "t": self.t_exact, "q": q_exact}
        q_live = self.live_run(k, d, q_start)
        if q_live is None:
            return {**shown, "state": "fast", "q_start": q_start}
        return {**shown, "state": "live", "t": self.t_live, "q": q_live}

    def _draw(self) -> None:
        shown = self.shown
        if self.ax_arm.get_title() != self.titles[shown["state"]]:  # else not redrawn
            self.ax_arm.set_title(self.titles[shown["state"]])
        q = shown.get("q")
        if q is not None:
            last = int(np.abs(shown["t"] - self.strobe_times[-1]).argmin())
            plot.move_strobe(self.strobe, self.arm, q[: last + 1])
        for artist in self.strobe:
            artist.set_visible(q is not None)
        moving = q is not None and "offset" in shown
        self.distance_line.set_visible(moving)
        if q is not None and moving:
            distance = np.linalg.norm(self.arm.fk(q) - self.rest, axis=-1)
            shown["distance"] = distance
            self.distance_line.set_data(shown["t"], distance / shown["offset"])

    def update(self, k: float, d: float, x_start: float, y_start: float) -> None:
        """Simulate the release (live, or the exact run the button made) and move the figure."""
        self.shown = self._release(k, d, x_start, y_start)
        self._draw()

    def show_exact(self, k: float, d: float, x_start: float, y_start: float) -> None:
        """The button: simulate these values exactly and draw that run until the next move."""
        try:
            q_start = ik.closed_form(self.arm, [x_start, y_start]).q
        except UnreachableError:
            return
        self._exact_runs[(k, d, x_start, y_start)] = self.exact_run(k, d, q_start)
        self.update(k, d, x_start, y_start)

    def describe(self, k: float, d: float, x_start: float, y_start: float) -> str:
        """The sentence under the figure."""
        shown = self.shown
        where = f"Released at rest from ({x_start:.1f}, {y_start:.1f}) m"
        if shown.get("state") == "unreachable":
            low, high = self.arm.reach
            return f"{where}: out of reach (the arm reaches {low:.0f} to {high:.0f} m from the shoulder)."
        if shown.get("state") == "at rest":
            return f"{where}, the rest point itself: the spring pulls nowhere and the arm stays."
        rest = f"({self.rest[0]:g}, {self.rest[1]:g})"
        text = (
            f"{where}, {rounded(shown['offset'], 2)} m from the rest point {rest}, with k = "
            f"{k:.0f} N/m and d = {d:.0f} N s/m: the smallest damping ratio at the rest "
            f"point is {rounded(shown['zeta'], 2)}"
        )
        if shown["state"] == "fast":
            return (
                text
                + "; the live run needs too many steps (fast swings): press 'exact run'."
            )
        distance = shown["distance"][-1]
        end = (
            below(distance, 0.01, "m") if distance < 0.01 else rounded(distance, 2, "m")
        )
        text += f"; after {self.t_live[-1]:.1f} s the {shown['state']} run's tip is {end} from the rest point."
        if shown["state"] == "exact":
            text += " The next move of a slider goes back to the live run."
        return text

    def connect(self, view: explorer.Explorer) -> None:
        """Wire :attr:`exact_button` to ``view``: the exact run of its values, then its redraw."""

        def run_exactly(button: Any) -> None:
            button.disabled = True
            self.show_exact(**view.values)
            button.disabled = False
            view.redraw(self.describe(**view.values))

        self.exact_button.on_click(run_exactly)
