"""Speed and accuracy of the dynamics (issue: chapter 5, Lagrangian dynamics).

Prints one table: each figure measured on this machine beside its target.

* ``arm.forward_dynamics`` vectorised over 1e5 states: at most 300 ns per state;
* ``arm.forward_dynamics`` one state per call: at most 10 us per call;
* ``twolink.simulate``: 10 s of free motion of the 2 m arm (1 kg rods,
  g = 9.81) from q = (pi/4, 0) at rest, DOP853 at rtol = atol = 1e-10, in
  under 0.15 s with a relative energy drift under 1e-8;
* ``simulate_quick`` (scipy's compiled ``odeint``, rtol = atol = 1e-6) beside
  ``simulate`` for the explorers' 5 s free release from (pi/4, 0) with 251
  samples: at most 3 ms, the tip within 2 mm of the exact run.

Reference rows (no target) time the same work done the plain way:
``numpy.linalg.solve`` on stacked matrices and the sympy-lambdified
equations of :mod:`twolink.symbolic`.  For scale, pinocchio's C++ ``aba``
takes about 1.3 us per call from Python on this kind of machine.

Run with ``make bench`` or ``.venv/bin/python benchmarks/bench_dynamics.py``
(``--quick`` for a smoke run with tiny sizes, used by the test suite: it
checks that the script runs, not the speed).
"""

import argparse
import platform

import numpy as np

from twolink import arms, simulate
from twolink.simulation import simulate_quick
from twolink.symbolic import lambdify_dynamics
from twolink_course.display import markdown_table
from twolink_course.timing import median_time as _median_time


def numpy_solve_forward_dynamics(arm, q, qd, tau):
    """The same accelerations with the matrices stacked and numpy.linalg.solve (reference)."""
    rhs = tau - np.einsum("...ij,...j->...i", arm.coriolis(q, qd), qd) - arm.gravity(q)
    return np.linalg.solve(arm.mass_matrix(q), rhs[..., None])[..., 0]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--quick",
        action="store_true",
        help="tiny sizes: checks the script runs, not the speed",
    )
    quick = parser.parse_args(argv).quick

    def median_time(function, repeat, min_seconds=0.05):
        return _median_time(
            function,
            repeat=1 if quick else repeat,
            min_seconds=1e-9 if quick else min_seconds,
        )

    arm = arms.two_metre
    rng = np.random.default_rng(5)
    count = 200 if quick else 100_000
    q, qd, tau = rng.uniform(-np.pi, np.pi, (3, count, 2))
    rows = []

    seconds = median_time(lambda: arm.forward_dynamics(q, qd, tau), repeat=7)
    rows.append(
        (
            "arm.forward_dynamics, 1e5 states (vectorised)",
            f"{seconds / count * 1e9:.0f} ns/state",
            "<= 300 ns",
            seconds / count <= 300e-9,
        )
    )
    seconds = median_time(
        lambda: numpy_solve_forward_dynamics(arm, q, qd, tau), repeat=7
    )
    rows.append(
        (
            "  reference: M, C, g stacked + numpy.linalg.solve",
            f"{seconds / count * 1e9:.0f} ns/state",
            "(info)",
            True,
        )
    )
    seconds = median_time(lambda: arm.inverse_dynamics(q, qd, tau), repeat=7)
    rows.append(
        (
            "arm.inverse_dynamics, 1e5 states (vectorised)",
            f"{seconds / count * 1e9:.0f} ns/state",
            "(info)",
            True,
        )
    )

    q1, qd1, tau1 = q[0], qd[0], tau[0]
    seconds = median_time(lambda: arm.forward_dynamics(q1, qd1, tau1), repeat=7)
    rows.append(
        (
            "arm.forward_dynamics, one state per call (arrays)",
            f"{seconds * 1e6:.2f} us/call",
            "<= 10 us",
            seconds <= 10e-6,
        )
    )
    q_list, qd_list, tau_list = q1.tolist(), qd1.tolist(), tau1.tolist()
    seconds = median_time(
        lambda: arm.forward_dynamics(q_list, qd_list, tau_list), repeat=7
    )
    rows.append(
        (
            "arm.forward_dynamics, one state per call (lists)",
            f"{seconds * 1e6:.2f} us/call",
            "<= 10 us",
            seconds <= 10e-6,
        )
    )
    seconds = median_time(lambda: arm.inverse_dynamics(q1, qd1, tau1), repeat=7)
    rows.append(
        (
            "arm.inverse_dynamics, one state per call (arrays)",
            f"{seconds * 1e6:.2f} us/call",
            "(info)",
            True,
        )
    )
    numeric = lambdify_dynamics("relative")

    def lambdified_forward():
        rhs = tau1 - numeric.coriolis(arm, q1, qd1) @ qd1 - numeric.gravity(arm, q1)
        return np.linalg.solve(numeric.mass_matrix(arm, q1), rhs)

    assert np.allclose(
        lambdified_forward(),
        arm.forward_dynamics(q1, qd1, tau1),
        rtol=1e-12,
        atol=1e-12,
    )
    seconds = median_time(lambdified_forward, repeat=7)
    rows.append(
        (
            "  reference: sympy-lambdified M, C, g + numpy.linalg.solve",
            f"{seconds * 1e6:.2f} us/call",
            "(info)",
            True,
        )
    )

    start = dict(
        arm=arm,
        q0=[np.pi / 4, 0.0],
        qd0=[0.0, 0.0],
        t_end=0.5 if quick else 10.0,
        method="DOP853",
        rtol=1e-10,
        atol=1e-10,
    )
    result = simulate(**start)
    seconds = median_time(lambda: simulate(**start), repeat=5, min_seconds=0.2)
    rows.append(
        (
            f"simulate {start['t_end']:g} s free motion from (pi/4, 0), DOP853 1e-10 ({result.nfev} RHS calls)",
            f"{seconds:.3f} s",
            "< 0.15 s",
            seconds < 0.15,
        )
    )
    drift = result.energy_drift()
    rows.append(
        (
            f"  relative energy drift max abs(E - E0) / max T over those {start['t_end']:g} s",
            f"{drift:.1e}",
            "< 1e-8",
            drift < 1e-8,
        )
    )

    release = dict(q0=[np.pi / 4, 0.0], qd0=[0.0, 0.0])
    samples = np.linspace(0.0, 0.5 if quick else 5.0, 51 if quick else 251)
    exact = simulate(arm, **release, t_end=samples[-1], t_eval=samples)
    exact_seconds = median_time(
        lambda: simulate(arm, **release, t_end=samples[-1], t_eval=samples), repeat=5
    )
    rows.append(
        (
            f"simulate, the explorers' release: {samples[-1]:g} s free, {len(samples)} samples, "
            f"DOP853 1e-10 ({exact.nfev} RHS calls)",
            f"{exact_seconds * 1e3:.1f} ms",
            "(info)",
            True,
        )
    )
    fast = simulate_quick(arm, **release, t_eval=samples)
    seconds = median_time(
        lambda: simulate_quick(arm, **release, t_eval=samples), repeat=7
    )
    rows.append(
        (
            f"  simulate_quick, the same release, odeint LSODA 1e-6 ({fast.nfev} RHS calls, "
            f"{exact_seconds / seconds:.0f}x faster)",
            f"{seconds * 1e3:.2f} ms",
            "<= 3 ms",
            seconds <= 3e-3,
        )
    )
    gap = float(np.max(exact.tracking_error(fast.p_tip)))
    rows.append(
        (
            "  its tip's largest distance from simulate's",
            f"{gap * 1e3:.2f} mm",
            "< 2 mm",
            gap < 2e-3,
        )
    )

    print(
        f"# twolink dynamics benchmark ({platform.processor() or platform.machine()}, numpy {np.__version__})\n"
    )
    print(
        markdown_table(
            ["quantity", "measured", "target", "meets target"],
            [(a, b, c, "yes" if ok else "NO") for a, b, c, ok in rows],
        )
    )
    return quick or all(ok for *_, ok in rows)


if __name__ == "__main__":
    raise SystemExit(0 if main() else 1)
