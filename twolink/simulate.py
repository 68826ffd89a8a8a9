"""Simulating the arm: integrate ``M qdd + C qd + g = tau`` with scipy's ``solve_ivp``.

The right-hand side comes from :func:`twolink.dynamics.state_derivative`;
the inputs are checked once, at the entry of :func:`simulate`.  A torque
callable ``(t, q, qd) -> tau`` drives the arm (a controller plugs in here);
without one the arm moves freely under gravity.
"""

from dataclasses import dataclass
from types import MappingProxyType

import numpy as np
from scipy.integrate import solve_ivp

from . import dynamics
from ._validate import as_finite_scalar, as_pairs

__all__ = ["simulate", "SimulationResult", "SimulationError"]

#: Solver settings used unless the caller passes others: an 8th-order
#: Runge-Kutta method at tolerances tight enough that the energy of free
#: motion drifts by less than 1e-8 of its scale over 10 s (read-only).
DEFAULT_SOLVER_OPTIONS = MappingProxyType({"method": "DOP853", "rtol": 1e-10, "atol": 1e-10})


class SimulationError(RuntimeError):
    """The ODE solver failed before reaching the end time (its message says why)."""


def _frozen(array):
    array = np.array(array, dtype=float)
    array.setflags(write=False)
    return array


@dataclass(frozen=True)
class SimulationResult:
    """A simulated motion of the arm (read-only arrays).

    Attributes
    ----------
    arm : TwoLinkArm
        The arm that was simulated.
    t : numpy.ndarray, shape (n,)
        Times in seconds.
    q, qd : numpy.ndarray, shape (n, 2)
        Joint angles (rad) and rates (rad/s) at those times.
    tau : numpy.ndarray, shape (n, 2)
        Motor torques (N m) at those times (zeros for free motion).
    status : int
        ``solve_ivp``'s status: 0 reached ``t_end``, 1 stopped by a terminal
        event (failures raise :class:`SimulationError` instead).
    message : str
        ``solve_ivp``'s message.
    nfev : int
        Number of right-hand-side evaluations.
    t_events, y_events : list or None
        Event times and states when ``events`` were passed to the solver.
    """

    arm: object
    t: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    tau: np.ndarray
    status: int
    message: str
    nfev: int
    t_events: object = None
    y_events: object = None

    def energy(self):
        """Kinetic and potential energy ``(T, V)`` along the motion, each shape ``(n,)``, joules."""
        return dynamics.energy(self.arm, self.q, self.qd)

    def energy_drift(self):
        """Relative drift of the total energy: ``max |E(t) - E(0)| / max T``.

        Divided by the largest kinetic energy of the motion, the energy that
        changes form (the total itself depends on where ``V = 0`` is put).
        For free motion the exact value is 0, so this measures the solver's
        error; with torques or events it is no conservation check.

        Returns
        -------
        float
            0.0 for a motion that never moves and never changes energy.

        Examples
        --------
        >>> from twolink import arms
        >>> result = simulate(arms.two_metre, [np.pi / 4, 0.0], [0.0, 0.0], 2.0)
        >>> result.energy_drift() < 1e-9
        True
        """
        kinetic, potential = self.energy()
        total = kinetic + potential
        change = float(np.max(np.abs(total - total[0])))
        scale = float(np.max(kinetic))
        if scale == 0.0:
            return 0.0 if change == 0.0 else float("inf")
        return change / scale

    def frames(self, max_frames=50):
        """Indices of at most ``max_frames`` samples, evenly spread, first and last included.

        Examples
        --------
        >>> from twolink import arms
        >>> result = simulate(arms.two_metre, [0.0, 0.0], [0.0, 0.0], 1.0, t_eval=np.linspace(0, 1, 101))
        >>> result.frames(5)
        array([  0,  25,  50,  75, 100])
        """
        if int(max_frames) < 2:
            raise ValueError(f"max_frames must be >= 2; got {max_frames}")
        count = min(int(max_frames), len(self.t))
        return np.unique(np.linspace(0, len(self.t) - 1, count).round().astype(int))


def simulate(arm, q0, qd0, t_end, torque=None, t_eval=None, **solver_options):
    """Integrate the arm's motion from ``(q0, qd0)`` at ``t = 0`` to ``t_end``.

    Solves ``M(q) qdd + C(q, qd) qd + g(q) = tau`` with
    :func:`scipy.integrate.solve_ivp` on the state ``(q1, q2, qd1, qd2)``.

    Parameters
    ----------
    arm : TwoLinkArm
        Its mass matrix must be invertible (links with mass).
    q0, qd0 : array_like, shape (2,)
        Initial joint angles (rad) and rates (rad/s).
    t_end : float
        End time in seconds (> 0).
    torque : callable, optional
        ``torque(t, q, qd) -> tau``, two motor torques in N m (``q`` and
        ``qd`` are arrays of shape ``(2,)``).  It must be a function of its
        arguments only: it is also called again at the output times to
        report ``tau``.  ``None`` (default) is free motion.
    t_eval : array_like, optional
        Times at which to report the motion (within ``[0, t_end]``,
        increasing); by default the solver's own steps.
    **solver_options
        Passed to ``solve_ivp`` (``method``, ``rtol``, ``atol``,
        ``max_step``, ``events``, ...).  Defaults: ``method="DOP853"``,
        ``rtol=atol=1e-10``.

    Returns
    -------
    SimulationResult

    Raises
    ------
    ValueError
        For a start of the wrong shape or not finite, a non-positive
        ``t_end``, a ``torque`` that is not callable or does not return two
        finite numbers, or an arm with a singular mass matrix.
    SimulationError
        When the solver fails (for example the step size becomes too small);
        no partial result is returned.

    Examples
    --------
    Held at rest by torques equal to gravity, the arm stays put:

    >>> from twolink import arms
    >>> arm = arms.two_metre
    >>> q0 = [np.pi / 4, 0.0]
    >>> held = simulate(arm, q0, [0.0, 0.0], 2.0, torque=lambda t, q, qd: arm.gravity(q))
    >>> bool(np.allclose(held.q, q0, atol=1e-9)), held.status
    (True, 0)
    >>> simulate(arm, q0, [0.0, 0.0], -1.0)
    Traceback (most recent call last):
    ...
    ValueError: t_end (s) must be > 0.0; got -1.0
    """
    q0 = as_pairs(q0, "q0")
    qd0 = as_pairs(qd0, "qd0")
    if q0.shape != (2,) or qd0.shape != (2,):
        raise ValueError(f"q0 and qd0 must be one state each, shape (2,); got {q0.shape} and {qd0.shape}")
    t_end = as_finite_scalar(t_end, "t_end (s)", minimum=0.0, strictly=True)
    right_hand_side = dynamics.state_derivative(arm, torque)
    options = dict(DEFAULT_SOLVER_OPTIONS)
    options.update(solver_options)
    if t_eval is not None:
        t_eval = np.asarray(t_eval, dtype=float)
    solution = solve_ivp(right_hand_side, (0.0, t_end), np.concatenate([q0, qd0]), t_eval=t_eval, **options)
    if solution.status < 0 or not np.all(np.isfinite(solution.y)):
        reached = solution.t[-1] if solution.t.size else 0.0
        raise SimulationError(
            f"the integration failed at t = {reached:.6g} s of {t_end:.6g} s: {solution.message} "
            "(try a smaller max_step, looser tolerances or another method)"
        )
    q = solution.y[:2].T
    qd = solution.y[2:].T
    if torque is None:
        tau = np.zeros_like(q)
    else:
        tau = np.array(
            [dynamics._torque_floats(torque(t, q_t.copy(), qd_t.copy()), t) for t, q_t, qd_t in zip(solution.t, q, qd)]
        ).reshape(q.shape)
    return SimulationResult(
        arm=arm,
        t=_frozen(solution.t),
        q=_frozen(q),
        qd=_frozen(qd),
        tau=_frozen(tau),
        status=int(solution.status),
        message=str(solution.message),
        nfev=int(solution.nfev),
        t_events=solution.t_events,
        y_events=solution.y_events,
    )
