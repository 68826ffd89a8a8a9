"""Chapter 5's explorer: the arm released at rest, its first second and its energies.

:class:`Release` draws, once, a strobe of the start of a free motion and the
energies ``T``, ``V`` and ``E = T + V`` of the whole run, and moves them to
the release set by the controls (start angles in degrees, link masses in kg).

How it keeps up with the hand: each move simulates with
:func:`twolink.simulation.simulate_quick` (scipy's compiled ``odeint``, LSODA,
on the right-hand side :func:`twolink.simulate` uses) at a looser tolerance
than the chapter's exact runs; ``tests/course/test_explorers_ch5.py`` checks it
against the exact run (DOP853 at ``1e-10``) across the sliders' ranges.  The
button :attr:`Release.exact_button` runs the exact simulation for the current
release and shows it until the next move.  The energies are drawn in units of
``V_up``, the potential energy of the arm held straight up (``V = 0`` at
shoulder height), so one fixed axis holds every release: ``V`` and ``E`` lie
in ``[-V_up, V_up]`` and ``T = E - V`` is at most ``2 V_up``.

Examples
--------
>>> from twolink import arms
>>> view = Release(arms.two_metre)
>>> view.update(q1=45, q2=0, m1=1.0, m2=1.0)
>>> view.describe(q1=45, q2=0, m1=1.0, m2=1.0).split(". ")[0]
'The 2 m arm released at rest from q = (45°, 0°) with m1 = 1.0 kg and m2 = 1.0 kg'
"""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np

from twolink import TwoLinkArm, simulate
from twolink._optional import require
from twolink.simulation import SimulationResult, simulate_quick

from .. import explorer, plot
from ..display import below, rounded, significant

__all__ = ["Release", "EXACT_RELEASE", "FAST", "FAST_DRIFT_BOUND"]

#: The chapter's exact run: DOP853 at tight tolerances (energy drift below 1e-8).
EXACT_RELEASE: dict[str, Any] = {"method": "DOP853", "rtol": 1e-10, "atol": 1e-10}
#: The explorer's quick run: simulate_quick's tolerances, and the drift it stays under.
FAST: dict[str, float] = {"rtol": 1e-6, "atol": 1e-6}
FAST_DRIFT_BOUND = 1e-3


class Release:
    """The release explorer's figure: a strobe of the first second and the energies of 5 s.

    Parameters
    ----------
    arm : TwoLinkArm
        The arm whose masses the controls replace.
    duration : float
        Seconds simulated, s.
    samples : int
        Samples of the run (the strobe draws the first second of them).

    Attributes
    ----------
    figure : matplotlib.figure.Figure
    exact_button : ipywidgets.Button
        Runs the exact simulation of the current release (wire it with :meth:`connect`).
    shown : SimulationResult or None
        The run on the figure.
    """

    def __init__(
        self, arm: TwoLinkArm, duration: float = 5.0, samples: int = 251
    ) -> None:
        self.arm = arm
        self.t = np.linspace(0.0, duration, samples)
        self.strobe_end = int(np.searchsorted(self.t, 1.0))  # the first second
        self.figure, (ax_arm, self.ax_energy) = explorer.explorer_figure(
            6.6, 3.0, ncols=2
        )
        seconds = self.t[self.strobe_end]
        plot.setup_axes(arm, ax=ax_arm, title=f"the first {seconds:.1f} s")
        self.strobe = plot.draw_strobe(
            arm, np.zeros((self.strobe_end + 1, 2)), ax=ax_arm, frames=6
        )
        self.energy_lines = plot.plot_time_series(
            self.t,
            np.zeros((samples, 3)),
            "energy / V_up",
            "-",
            ["T", "V", "E = T + V"],
            ax=self.ax_energy,
        )
        # fixed limits in units of V_up (a move never redraws the axes): V and E within
        # +-1, T up to 2, the legend above 2, where no curve goes
        self.ax_energy.set_ylim(-1.2, 2.9)
        self.ax_energy.set_title("fast run")
        legend = self.ax_energy.legend(loc="upper center", ncols=3)
        # titles, legend and frames lie where no line goes, under the moving lines: a
        # move does not redraw them
        for panel in (ax_arm, self.ax_energy):
            for still in [panel.title, *panel.spines.values()]:
                still.set_zorder(1)
        legend.set_zorder(1)
        self.shown: SimulationResult | None = None
        self._exact = False
        widgets = require("ipywidgets", "twolink_course.explorers.ch5.Release")
        self.exact_button = widgets.Button(
            description=f"exact run ({EXACT_RELEASE['method']}, {significant(EXACT_RELEASE['rtol'], 1)})",
            tooltip="simulate the current release with the chapter's tolerances",
            layout=widgets.Layout(width="16em"),
        )

    def arm_with(self, m1: float, m2: float) -> TwoLinkArm:
        """The arm with these link masses, kg."""
        return dataclasses.replace(self.arm, m1=m1, m2=m2)

    def energy_scale(self, m1: float, m2: float) -> float:
        """``V_up`` (J): the potential energy of the arm held straight up."""
        arm = self.arm_with(m1, m2)
        return float(arm.energy(np.radians([90.0, 0.0]), np.zeros(2))[1])

    def run(
        self, q1: float, q2: float, m1: float, m2: float, exact: bool = False
    ) -> SimulationResult:
        """The release at rest from ``(q1, q2)`` degrees: the quick run, or the exact one."""
        arm, q0 = self.arm_with(m1, m2), np.radians([q1, q2])
        if exact:
            return simulate(
                arm, q0, np.zeros(2), self.t[-1], t_eval=self.t, **EXACT_RELEASE
            )
        return simulate_quick(
            arm, q0, np.zeros(2), self.t, rtol=FAST["rtol"], atol=FAST["atol"]
        )

    def _draw(self, motion: SimulationResult) -> None:
        plot.move_strobe(self.strobe, self.arm, motion.q[: self.strobe_end + 1])
        kinetic, potential = motion.energy()
        scale = self.energy_scale(motion.arm.m1, motion.arm.m2)
        for line, energy in zip(
            self.energy_lines, (kinetic, potential, kinetic + potential)
        ):
            line.set_ydata(energy / scale)
        self.shown = motion

    def update(self, q1: float, q2: float, m1: float, m2: float) -> None:
        """Simulate the release quickly and move the strobe and the energies to it."""
        motion = self.run(q1, q2, m1, m2)
        self._draw(motion)
        self._exact = False
        drift = _drift_text(motion.energy_drift(), FAST_DRIFT_BOUND)
        self.ax_energy.title.set_text(f"fast run: E drift {drift}")

    def show_exact(self, q1: float, q2: float, m1: float, m2: float) -> None:
        """Simulate the release exactly (the button) and draw that run instead."""
        motion = self.run(q1, q2, m1, m2, exact=True)
        self._draw(motion)
        self._exact = True
        drift = _drift_text(motion.energy_drift(), 1e-8)
        self.ax_energy.title.set_text(f"exact run: E drift {drift}")

    def describe(self, q1: float, q2: float, m1: float, m2: float) -> str:
        """The sentence under the figure, for the run it shows."""
        motion = self.shown if self.shown is not None else self.run(q1, q2, m1, m2)
        kinetic, _ = motion.energy()
        scale = self.energy_scale(m1, m2)
        bound = 1e-8 if self._exact else FAST_DRIFT_BOUND
        if kinetic.max() < 1e-9 * scale:  # released in balance (straight up or down)
            energies = "T stays at 0 J: released in balance, the arm stays where it is."
        else:
            energies = (
                f"T peaks at {rounded(kinetic.max(), 1, 'J')}; E = T + V should stay "
                f"constant, and its drift is {_drift_text(motion.energy_drift(), bound)} "
                "of that peak."
            )
        name = f"{self.arm.l1:g} m" if self.arm.l1 == self.arm.l2 else "two-link"
        opening = (
            f"Exact run ({EXACT_RELEASE['method']} at rtol = atol = "
            f"{significant(EXACT_RELEASE['rtol'], 1)}) of the {name}"
            if self._exact
            else f"The {name}"
        )
        text = (
            f"{opening} arm released at rest from q = ({q1:g}°, {q2:g}°) with m1 = "
            f"{m1:.1f} kg and m2 = {m2:.1f} kg. Left, its first "
            f"{self.t[self.strobe_end]:.1f} s: the tip moves from "
            f"{rounded(motion.p_tip[0], 2, 'm')} to "
            f"{rounded(motion.p_tip[self.strobe_end], 2, 'm')}. Right, its energies over "
            f"{self.t[-1]:.0f} s in units of V_up = {rounded(scale, 1, 'J')} (the arm "
            "held straight up). " + energies
        )
        if self._exact:
            text += " The next move of a slider goes back to the fast run."
        return text

    def connect(self, view: explorer.Explorer) -> None:
        """Wire :attr:`exact_button` to ``view``: the exact run of its values, then its redraw."""

        def run_exactly(button: Any) -> None:
            self.show_exact(**view.values)
            view.redraw(self.describe(**view.values))

        self.exact_button.on_click(run_exactly)


def _drift_text(drift: float, bound: float) -> str:
    """An energy drift as the bound it stays under, or its value when it does not."""
    return below(drift, bound) if drift < bound else significant(drift, 1)
