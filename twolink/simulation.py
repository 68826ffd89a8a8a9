"""Simulating the arm: integrate ``M qdd + C qd + g = tau`` with scipy's ``solve_ivp``.

The right-hand side comes from :func:`twolink.dynamics.state_derivative`;
the inputs are checked once, at the entry of :func:`simulate`.
:func:`simulate_quick` integrates the same right-hand side with scipy's
compiled ``odeint`` (LSODA) at looser tolerances, for a picture that must
follow a slider (a millisecond or two for a few seconds of motion).  A torque
callable ``(t, q, qd) -> tau`` drives the arm (a controller plugs in here);
without one the arm moves freely under gravity.

The :class:`SimulationResult` holds the motion and reads it the way a
:class:`twolink.trajectory.JointTrajectory` does: ``p_tip`` and
``tracking_error(path)`` mean the same on both, and ``energy`` /
``energy_drift`` take the potential energy of a spring the controller
simulates (``extra_potential=controller.potential_energy``).
"""

from __future__ import annotations

import math
import time
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from types import MappingProxyType
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import dynamics
from ._integration import (
    EXPLICIT_METHODS,
    BudgetSpent,
    budgeted,
    integrate,
    solver_options,
    spent_error,
)
from ._validate import (
    InputTypeError,
    as_configuration,
    as_count,
    as_finite_scalar,
    as_time_span,
    real_array,
    torque_floats,
)
from ._values import Value, freeze
from .budgets import DEFAULT_MAX_EVALUATIONS, DEFAULT_MAX_WALL_TIME, EvaluationBudget
from .errors import SimulationError
from .kinematics import fk
from .trajectory import path_positions

if TYPE_CHECKING:
    from .arm import TwoLinkArm
    from .trajectory import JointTrajectory, Path

#: A torque law ``tau(t, q, qd)``: time (s), joint angles (rad) and rates (rad/s), each ``(2,)``, to two torques (N m).
TorqueLaw = Callable[[float, NDArray[np.float64], NDArray[np.float64]], ArrayLike]

#: A potential energy ``V(q)`` in joules, vectorised over configurations ``(n, 2)`` -> ``(n,)``.
PotentialEnergy = Callable[[NDArray[np.float64]], ArrayLike]

__all__ = ["simulate", "simulate_quick", "SimulationResult"]

#: Solver settings used unless the caller passes others: an 8th-order
#: Runge-Kutta method at tolerances tight enough that the energy of free
#: motion drifts by less than 1e-8 of its scale over 10 s (read-only).
DEFAULT_SOLVER_OPTIONS = MappingProxyType(
    {"method": "DOP853", "rtol": 1e-10, "atol": 1e-10}
)


#: Right-hand-side evaluations per step of each explicit method, and the
#: length of its stability interval on the negative real axis (h |lambda| <= it).
_EXPLICIT_COST = {"RK23": (3, 2.5), "RK45": (6, 3.3), "DOP853": (12, 6.0)}


#: Tolerances of :func:`simulate_quick` unless the caller passes others: loose enough for
#: about 1e3 evaluations per 5 s of free motion, tight enough for a picture (the tip of
#: the 2 m arm within a millimetre of the exact run over 5 s of a chaotic swing).
QUICK_TOLERANCES = MappingProxyType({"rtol": 1e-6, "atol": 1e-6})

#: Right-hand-side evaluations :func:`simulate_quick` may spend unless told otherwise (5 s
#: of free motion take about 1.1e3 at its default tolerances; 1e5 take about 0.2 s).
QUICK_MAX_EVALUATIONS = 100_000

#: A loop counts as stiff when its fastest rate (1/s) times the time simulated exceeds this:
#: its fastest mode then dies out a thousand times within the run, and an explicit method's
#: steps are set by stability, not by accuracy.
STIFF_SPAN = 1e3

#: Mean seconds per right-hand-side call above which a spent wall-time budget is blamed on a slow
#: torque function (the arm's own dynamics take about 1e-5 s a call; 1e-3 s is a hundred times that).
SLOW_CALL = 1e-3


def _jacobian_eigenvalues(right_hand_side, t, state):
    """Eigenvalues of ``df/dx`` at one state by central differences (8 evaluations), or None."""
    try:
        columns = []
        for index in range(4):
            step = 1e-7 * max(1.0, abs(state[index]))
            offset = np.zeros(4)
            offset[index] = step
            forward = np.asarray(right_hand_side(t, state + offset), dtype=float)
            backward = np.asarray(right_hand_side(t, state - offset), dtype=float)
            columns.append((forward - backward) / (2.0 * step))
        jacobian = np.column_stack(columns)
        if not np.all(np.isfinite(jacobian)):
            return None
        return np.linalg.eigvals(jacobian)
    except (ValueError, ArithmeticError, SimulationError):
        return None


def _stiffness(right_hand_side, t, state):
    """Largest ``|lambda|`` of the linearised loop at a state (1/s), or None if it cannot be estimated."""
    eigenvalues = _jacobian_eigenvalues(right_hand_side, t, state)
    if eigenvalues is None or eigenvalues.size == 0:
        return None
    return float(np.max(np.abs(eigenvalues)))


def _explicit_evaluations(method, rate, duration):
    """About how many evaluations an explicit method needs for stability alone over ``duration``."""
    per_step, interval = _EXPLICIT_COST[method]
    return per_step * rate * duration / interval


def _budget_advice(inner, stop, budget, method, t_end, torque, max_step):
    """What to change when the budget of :func:`simulate` ran out: a slow torque function, ``max_step`` or stiffness.

    A wall time spent at few evaluations blames the torque function; steps no
    longer than ``max_step`` on average blame it; otherwise the stiffness
    of the loop where the budget ran out decides.
    """
    evaluations = budget.evaluations
    per_call = (time.monotonic() - budget.started) / max(evaluations, 1)
    if stop.which == "max_wall_time" and torque is not None and per_call > SLOW_CALL:
        return (
            f"the torque function is the likely cause: the dynamics were evaluated only {evaluations} times, "
            f"{per_call:.3g} s a call (the arm's own part takes about 1e-5 s), so torque(t, q, qd) is slow; "
            "make it faster (no printing, plotting or sleeping in it) or raise max_wall_time"
        )
    explicit = method in EXPLICIT_METHODS
    per_step = _EXPLICIT_COST[method][0] if explicit else 1
    mean_step = stop.t * per_step / max(evaluations, 1)
    if max_step < math.inf and mean_step <= 2.0 * max_step:
        return (
            f"max_step = {max_step:.3g} s limited the steps ({mean_step:.3g} s on average, "
            f"{t_end / max_step:.3g} steps for {t_end:.6g} s): give a larger max_step or raise the budget"
        )
    # the fastest rate where the budget ran out: at its last evaluation and the few before
    # (a tip bouncing on a stiff wall may be off it at the very last one); 0 where none is known
    rates = [_stiffness(inner, stop.t, state) for state in (*stop.recent, stop.state)]
    rate = max((rate for rate in rates if rate is not None), default=0.0)
    stiff = rate * t_end > STIFF_SPAN
    if explicit:
        # and the steps taken were no longer than the explicit method's stability limit allows
        stiff = stiff and mean_step * rate < 3.0 * _EXPLICIT_COST[method][1]
    if stiff:
        advice = (
            f"the closed loop is stiff there (fastest rate {rate:.3g} 1/s, time constant {1.0 / rate:.2g} s, "
            f"against {t_end:.6g} s to simulate)"
        )
        if explicit:
            return (
                advice
                + f": use an implicit method, method='Radau' or method='LSODA', instead of {method!r}"
            )
        return advice + ": loosen rtol/atol or raise the budget"
    if explicit:
        return "try looser tolerances, method='Radau' or method='LSODA' (if the loop is stiff), or a larger budget"
    return (
        f"with the implicit method {method!r}, loosen rtol/atol (the defaults 1e-10 suit smooth motion; "
        "a contact or a switching controller is not smooth), give max_step, or raise the budget"
    )


def _state_text(state):
    """``q = (..) rad, qd = (..) rad/s`` of a state ``(q1, q2, qd1, qd2)``, for a message."""
    return f"q = ({state[0]:.6g}, {state[1]:.6g}) rad, qd = ({state[2]:.6g}, {state[3]:.6g}) rad/s"


def _start_state(q0, qd0):
    """The checked start ``(q1, q2, qd1, qd2)`` of :func:`simulate` and :func:`simulate_quick`."""
    q_start = as_configuration(q0, "q0")
    qd_start = as_configuration(
        qd0, "qd0", what="one pair of joint rates", unit="rad/s"
    )
    return np.concatenate([q_start, qd_start])


def _past_the_start(inner, budget, check_overflow):
    """``inner`` as the right-hand side of a run: past its first evaluation an error is the motion failing.

    At the first evaluation (the start) a ``ValueError`` is bad input (a
    torque function that returns NaN or junk there) and reaches the caller
    as it is.  Later the same error, or an arithmetic one, means the motion
    failed on the way: a :class:`SimulationError` naming the time, the state
    and the cause.  With ``check_overflow``, accelerations that overflow are
    a blow-up too.
    """

    def right_hand_side(t, state):
        try:
            derivative = inner(t, state)
        except (ValueError, ArithmeticError) as exc:
            if budget.evaluations <= 1:
                raise
            raise SimulationError(
                f"the motion failed at t = {t:.6g} s in the state {_state_text(state)}: {exc}"
            ) from None
        if check_overflow and not math.isfinite(derivative[2] + derivative[3]):
            raise SimulationError(
                f"the motion blew up at t = {t:.6g} s: the accelerations overflow "
                f"(qdd = ({derivative[2]:.6g}, {derivative[3]:.6g}) rad/s^2) in the state "
                f"{_state_text(state)}"
            )
        return derivative

    return right_hand_side


def _torques_at(torque, times, q, qd, budget=None):
    """The torques ``torque(t, q, qd)`` at the output times, shape (n, 2) (zeros for free motion).

    With a ``budget``, a slow torque function stops at its wall time.
    """
    if torque is None:
        return np.zeros_like(q)
    torques: list[tuple[float, float]] = []
    # rows of private copies: a torque that writes into its q or qd changes neither the result nor the next call
    for t, q_t, qd_t in zip(times, np.array(q), np.array(qd)):
        if budget is not None and budget.out_of_time():
            raise SimulationError(
                f"the integration reached t = {times[-1]:.6g} s, but recomputing the torques at the {len(times)} "
                f"output times used up the budget of max_wall_time = {budget.max_wall_time:.3g} s after "
                f"{len(torques)} of them: torque(t, q, qd) is slow; make it faster, pass fewer t_eval times "
                "or raise max_wall_time"
            )
        torques.append(torque_floats(torque(t, q_t, qd_t), t))
    return np.array(torques).reshape(q.shape)


def _check_t_eval(t_eval, t_end=None):
    """``t_eval`` as output times: real, 1-D, non-empty, finite, strictly increasing, in ``[0, t_end]``.

    ``t_end=None``: the last time is the end (:func:`simulate_quick`).
    """
    times = real_array(t_eval, "t_eval", "times in seconds (real numbers)")
    if times.ndim != 1 or times.size == 0:
        raise ValueError(
            f"t_eval must be a non-empty 1-D array of times (s); got shape {times.shape}"
        )
    if not np.all(np.isfinite(times)):
        raise ValueError("t_eval must be finite times (s); it holds NaN or infinity")
    if times.size > 1 and not np.all(np.diff(times) > 0.0):
        first = int(np.flatnonzero(~(np.diff(times) > 0.0))[0])
        raise ValueError(
            f"t_eval must be strictly increasing; t_eval[{first + 1}] = {times[first + 1]:.6g} s follows "
            f"t_eval[{first}] = {times[first]:.6g} s"
        )
    if t_end is None:
        t_end = times[-1]
    if times[0] < 0.0 or times[-1] > t_end:
        raise ValueError(
            f"t_eval must lie in [0, t_end] = [0, {t_end:.6g}] s; got [{times[0]:.6g}, {times[-1]:.6g}] s"
        )
    return times


@dataclass(frozen=True, eq=False)
class SimulationResult(Value):
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
        event (failures raise :class:`SimulationError` instead); always 0
        from :func:`simulate_quick`.
    message : str
        ``solve_ivp``'s message, or from :func:`simulate_quick` one that
        names ``odeint`` (LSODA) and its tolerances.
    nfev : int
        Number of right-hand-side evaluations.
    t_events, y_events : list of numpy.ndarray or None
        Event times and states when ``events`` were passed to the solver.
    """

    arm: TwoLinkArm
    t: NDArray[np.float64]
    q: NDArray[np.float64]
    qd: NDArray[np.float64]
    tau: NDArray[np.float64]
    status: int
    message: str
    nfev: int
    t_events: list[NDArray[np.float64]] | None = None
    y_events: list[NDArray[np.float64]] | None = None

    def __post_init__(self) -> None:
        freeze(self)

    @property
    def p_tip(self) -> NDArray[np.float64]:
        """Where the tip is, ``fk(q)``: shape (n, 2), metres (as :attr:`twolink.trajectory.JointTrajectory.p_tip`)."""
        return fk(self.arm, self.q)

    def tracking_error(
        self, path: Path | JointTrajectory | ArrayLike | None = None
    ) -> NDArray[np.float64]:
        """Distance of the tip from where ``path`` wants it, ``|p_tip - p_path|`` per sample: shape (n,), metres.

        The same method as :meth:`twolink.trajectory.JointTrajectory.tracking_error`.

        Parameters
        ----------
        path : LinePath, CirclePath, JointTrajectory or array_like
            What the tip should follow, read at the result's times ``t`` by
            :func:`twolink.trajectory.path_positions`: a path object (its
            position at every time), a trajectory sampled at the same times
            (simulate with ``t_eval=trajectory.t``), points of shape (n, 2),
            or one fixed point (2,).  A simulation has no path of its own,
            so ``None`` is refused.

        Raises
        ------
        ValueError
            For ``path=None`` or a path that does not fit the times (see
            :func:`twolink.trajectory.path_positions`).

        Examples
        --------
        >>> from twolink import arms
        >>> held = simulate(arms.two_metre, [0.0, 0.0], [0.0, 0.0], 1.0, t_eval=[0.0, 1.0],
        ...                 torque=lambda t, q, qd: arms.two_metre.gravity(q))
        >>> held.tracking_error([4.0, 0.0]).round(9) + 0.0       # held stretched out at (4, 0)
        array([0., 0.])
        """
        if path is None:
            raise ValueError(
                "a simulation has no path of its own: pass what the tip should follow (a LinePath or CirclePath, "
                "a JointTrajectory sampled at the same times, or points of shape (n, 2) or (2,) in metres)"
            )
        difference = self.p_tip - path_positions(path, self.t)
        return np.hypot(difference[:, 0], difference[:, 1])

    def energy(
        self, extra_potential: PotentialEnergy | None = None
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Kinetic and potential energy ``(T, V)`` along the motion, each shape ``(n,)``, joules.

        Parameters
        ----------
        extra_potential : callable, optional
            ``V_extra(q)``: potential energy stored outside the arm (a
            spring the controller simulates), joules; called once with all
            the configurations ``q`` of shape (n, 2), it must return shape
            (n,): for example ``CartesianSpring(...).potential_energy``.
            Added to ``V``.

        Returns
        -------
        kinetic, potential : numpy.ndarray, shape (n,)
            ``T = qd^T M qd / 2`` and ``V = V_gravity (+ V_extra)``
            (:func:`twolink.dynamics.energy`).

        Raises
        ------
        ValueError
            If ``extra_potential`` is not callable or does not return ``n``
            finite energies.
        """
        kinetic, potential = dynamics.energy(self.arm, self.q, self.qd)
        if extra_potential is not None:
            potential = potential + self._extra_energy(extra_potential)
        return kinetic, potential

    def _extra_energy(self, extra_potential: PotentialEnergy) -> NDArray[np.float64]:
        if not callable(extra_potential):
            raise InputTypeError(
                f"extra_potential must be None or a callable V(q) -> joules (e.g. a controller's potential_energy); "
                f"got {extra_potential!r}"
            )
        expected = self.q.shape[:-1]
        try:
            values = np.asarray(extra_potential(self.q), dtype=float)
        except (TypeError, ValueError) as exc:
            raise ValueError(
                f"extra_potential(q) must return energies in joules, one per configuration: {exc}"
            ) from exc
        if values.shape != expected:
            raise ValueError(
                f"extra_potential(q) must be vectorised: q of shape {self.q.shape} in, energies of shape "
                f"{expected} (joules) out; got shape {values.shape}"
            )
        if not np.all(np.isfinite(values)):
            first = int(np.flatnonzero(~np.isfinite(values))[0])
            raise ValueError(
                f"extra_potential(q) returned {values[first]} J at t = {self.t[first]:.6g} s (sample {first})"
            )
        return values

    def energy_drift(self, extra_potential: PotentialEnergy | None = None) -> float:
        """Relative drift of the total energy: ``max |E(t) - E(0)| / max T``.

        Divided by the largest kinetic energy of the motion, the energy that
        changes form (the total itself depends on where ``V = 0`` is put).
        For free motion the exact value is 0, so this measures the solver's
        error; likewise under a conservative controller when its potential
        energy is passed as ``extra_potential`` (a spring: ``E = T + V_gravity
        + V_spring``).  With other torques or events it is no conservation check.

        Parameters
        ----------
        extra_potential : callable, optional
            ``V_extra(q)`` in joules, vectorised over ``q`` of shape (n, 2)
            (see :meth:`energy`), e.g. ``spring.potential_energy``.

        Returns
        -------
        float
            0.0 for a motion that never moves and never changes energy.

        Examples
        --------
        >>> from twolink import arms, controllers
        >>> result = simulate(arms.two_metre, [np.pi / 4, 0.0], [0.0, 0.0], 2.0)
        >>> result.energy_drift() < 1e-9
        True
        >>> spring = controllers.CartesianSpring(arms.two_metre, stiffness=600.0, rest_point=[3.0, 1.0])
        >>> bouncing = simulate(arms.two_metre, [0.3, 0.6], [0.0, 0.0], 1.0, torque=spring)
        >>> bouncing.energy_drift(extra_potential=spring.potential_energy) < 1e-8 < bouncing.energy_drift()
        True
        """
        kinetic, potential = self.energy(extra_potential)
        total = kinetic + potential
        change = float(np.max(np.abs(total - total[0])))
        scale = float(np.max(kinetic))
        if scale == 0.0:
            return 0.0 if change == 0.0 else float("inf")
        return change / scale

    def frames(self, max_frames: int = 50) -> NDArray[np.int_]:
        """Indices of at most ``max_frames`` samples, evenly spread, first and last included.

        Examples
        --------
        >>> from twolink import arms
        >>> result = simulate(arms.two_metre, [0.0, 0.0], [0.0, 0.0], 1.0, t_eval=np.linspace(0, 1, 101))
        >>> result.frames(5)
        array([  0,  25,  50,  75, 100])
        """
        count = min(as_count(max_frames, "max_frames", minimum=2), len(self.t))
        return np.unique(np.linspace(0, len(self.t) - 1, count).round().astype(int))


def simulate(
    arm: TwoLinkArm,
    q0: ArrayLike,
    qd0: ArrayLike,
    t_end: float,
    torque: TorqueLaw | None = None,
    t_eval: ArrayLike | None = None,
    max_evaluations: int = DEFAULT_MAX_EVALUATIONS,
    max_wall_time: float = DEFAULT_MAX_WALL_TIME,
    **solver_options_given: Any,
) -> SimulationResult:
    """Integrate the arm's motion from ``(q0, qd0)`` at ``t = 0`` to ``t_end``.

    Solves ``M(q) qdd + C(q, qd) qd + g(q) = tau`` with
    :func:`scipy.integrate.solve_ivp` on the state ``(q1, q2, qd1, qd2)``.

    It integrates with the method it is given (``DOP853`` unless
    ``method=`` says otherwise), and nothing hangs: the integration has a
    budget of right-hand-side evaluations and of wall time.  A stiff closed
    loop (large gains, a hard contact wall) on an explicit method would
    need millions of tiny steps: when the loop is already so stiff at the
    start that the budget could not suffice, the call is refused at once,
    and when the budget runs out on the way, the :class:`SimulationError`
    says where and why (the loop is stiff, with its fastest rate; a slow
    torque function; a ``max_step`` that limits every step) and what to
    change (``method="Radau"`` or ``"LSODA"`` for a stiff loop).

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
        Times at which to report the motion: finite, strictly increasing,
        within ``[0, t_end]``, at least one; by default the solver's own steps.
    max_evaluations : int
        Budget of right-hand-side evaluations (default
        ``DEFAULT_MAX_EVALUATIONS`` = 1e6; 10 s of free motion takes ~7e3).
    max_wall_time : float
        Budget of wall-clock seconds (default ``DEFAULT_MAX_WALL_TIME`` = 30).
    **solver_options_given
        Options of ``solve_ivp``: ``method`` (``"DOP853"``, ``"RK45"``,
        ``"RK23"``, ``"Radau"``, ``"BDF"``, ``"LSODA"``), ``rtol``,
        ``atol``, ``max_step``, ``first_step``, ``events``, and the method's
        own (``jac``, ``jac_sparsity`` for Radau and BDF; ``jac``,
        ``lband``, ``uband``, ``min_step`` for LSODA).  A name the method
        does not take is refused (scipy would ignore it), and so is a
        ``max_step`` too small to reach ``t_end`` within the budget.
        Defaults: ``method="DOP853"``, ``rtol=atol=1e-10``.

    Returns
    -------
    SimulationResult

    See Also
    --------
    simulate_quick : the same motion by scipy's compiled ``odeint`` at looser
        tolerances, 10 to 20 times faster, for a picture that follows a slider.

    Raises
    ------
    ValueError
        For a start of the wrong shape or not finite, a ``t_end`` outside
        ``TIME_RANGE`` = [1e-50, 1e50] s, a bad ``t_eval``, budget or
        solver option, a ``torque`` that is not callable or does not return
        two finite numbers at the start, or an arm with a singular mass
        matrix.
    SimulationError
        When the solver fails (for example the step size becomes too small),
        the motion fails on the way (the state or the accelerations blow up,
        the torque function returns NaN: the message names the time and the
        state), the loop is too stiff at the start for the explicit method
        and the budget, or the budget runs out; no partial result is
        returned.

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
    ValueError: t_end (s) must be in [1e-50, 1e+50]; got -1
    """
    start = _start_state(q0, qd0)
    t_end = as_time_span(t_end, "t_end (s)")
    budget = EvaluationBudget(max_evaluations, max_wall_time)
    inner = dynamics.state_derivative(arm, torque)
    options = solver_options(
        {**DEFAULT_SOLVER_OPTIONS, **solver_options_given},
        t_end,
        budget.max_evaluations,
    )
    method = options["method"]
    if t_eval is not None:
        t_eval = _check_t_eval(t_eval, t_end)
    note = ""
    if method in EXPLICIT_METHODS:
        # an explicit method on a loop already stiff at the start: refused when it could
        # not finish within the budget, noted when it would be slow
        try:
            rate = _stiffness(_out_of_time_checked(inner, budget), 0.0, start)
        except BudgetSpent as stop:
            raise spent_error(
                "the stiffness estimate at the start",
                method,
                budget,
                stop,
                t_end,
                _state_text,
                lambda stop: _budget_advice(
                    inner, stop, budget, method, t_end, torque, math.inf
                ),
            ) from None
        stiff = rate is not None and rate * t_end > STIFF_SPAN
        needed = _explicit_evaluations(method, rate, t_end) if stiff else 0.0
        if needed > budget.max_evaluations:
            raise SimulationError(
                f"the closed loop is stiff at t = 0 in the state {_state_text(start)} (fastest rate "
                f"{rate:.3g} 1/s, time constant {1.0 / rate:.2g} s): the explicit method {method!r} would "
                f"need about {needed:.2g} evaluations for {t_end:.6g} s, more than max_evaluations = "
                f"{budget.max_evaluations}; use an implicit method, method='Radau' or method='LSODA'"
            )
        if needed > budget.max_evaluations / 4:
            note = f" (the loop is stiff: fastest rate {rate:.3g} 1/s at t = 0; method='Radau' would be faster)"
    solution = integrate(
        _past_the_start(inner, budget, check_overflow=True),
        t_end,
        start,
        t_eval=t_eval,
        options=options,
        budget=budget,
        what="the integration",
        state_text=_state_text,
        advice=lambda stop: _budget_advice(
            inner,
            stop,
            budget,
            method,
            t_end,
            torque,
            options.get("max_step", math.inf),
        ),
    )
    q = solution.y[:2].T
    qd = solution.y[2:].T
    tau = _torques_at(torque, solution.t, q, qd, budget)
    return SimulationResult(
        arm=arm,
        t=solution.t,
        q=q,
        qd=qd,
        tau=tau,
        status=int(solution.status),
        message=str(solution.message) + note,
        nfev=int(solution.nfev),
        t_events=solution.t_events,
        y_events=solution.y_events,
    )


def _out_of_time_checked(inner, budget):
    """``inner`` that first checks the wall clock (the stiffness estimate at the start calls it 8 times)."""

    def checked(t, state):
        if budget.out_of_time():
            raise BudgetSpent(t, state, "max_wall_time")
        return inner(t, state)

    return checked


def simulate_quick(
    arm: TwoLinkArm,
    q0: ArrayLike,
    qd0: ArrayLike,
    t_eval: ArrayLike,
    torque: TorqueLaw | None = None,
    *,
    rtol: float = QUICK_TOLERANCES["rtol"],
    atol: float = QUICK_TOLERANCES["atol"],
    max_evaluations: int = QUICK_MAX_EVALUATIONS,
    max_wall_time: float = DEFAULT_MAX_WALL_TIME,
) -> SimulationResult:
    """The motion of :func:`simulate` by scipy's compiled ``odeint``: quick, for a picture.

    Integrates the same equations, ``M(q) qdd + C(q, qd) qd + g(q) = tau``
    on the same right-hand side (:func:`twolink.dynamics.state_derivative`),
    with :func:`scipy.integrate.odeint`: LSODA, compiled Fortran that
    switches between a non-stiff and a stiff method by itself and calls
    Python only for the right-hand side.  The inputs are checked as
    :func:`simulate` checks them, with the same messages.

    Which to use: this one where a simulation must keep up with a hand on a
    slider (5 s of free motion of the 2 m arm take about 1e3 evaluations and
    under 2 ms here, 10 to 20 times less than :func:`simulate`; see
    ``benchmarks/bench_dynamics.py``), and where an error of a millimetre
    is invisible.
    :func:`simulate` stays the exact run: tight tolerances (energy drift
    under 1e-8), events, the solver's own steps and the advice for stiff
    loops; use it for every number you report, and check a
    quick run against it.

    Parameters
    ----------
    arm : TwoLinkArm
        Its mass matrix must be invertible (links with mass).
    q0, qd0 : array_like, shape (2,)
        Joint angles (rad) and rates (rad/s) at ``t = 0``.
    t_eval : array_like, shape (n,)
        The times to report (s), required (``odeint`` reports at given
        times): finite, strictly increasing, from ``t = 0`` on; the motion
        is integrated to the last.  As :func:`simulate`'s ``t_eval`` with
        ``t_end = t_eval[-1]``.
    torque : callable, optional
        ``torque(t, q, qd) -> tau`` in N m, a function of its arguments only
        (as for :func:`simulate`); ``None`` (default) is free motion.
    rtol, atol : float
        ``odeint``'s relative and absolute tolerances (> 0); defaults
        ``QUICK_TOLERANCES``, 1e-6 each: fine for a picture (the energy of
        free motion drifts by 1e-5 to 1e-4 of its scale over 5 s, against
        under 1e-8 in :func:`simulate`), not for a reported number.
    max_evaluations : int
        Budget of right-hand-side evaluations (default
        ``QUICK_MAX_EVALUATIONS`` = 1e5).  A slider's run passes a few
        hundred: a motion that needs more (fast swings, a stiff loop) stops
        with a :class:`SimulationError` instead of keeping the hand waiting.
    max_wall_time : float
        Budget of wall-clock seconds (default ``DEFAULT_MAX_WALL_TIME`` = 30),
        read at every evaluation as :func:`simulate` reads it: a slow torque
        function stops there, named as the cause.

    Returns
    -------
    SimulationResult
        At the times ``t_eval``; ``status`` 0, ``message`` naming ``odeint``
        and its tolerances, ``nfev`` the evaluations spent, no events.

    Raises
    ------
    ValueError
        For a bad start, ``t_eval``, tolerance, budget or ``torque``, or a
        singular mass matrix, with :func:`simulate`'s messages.
    SimulationError
        When the budget runs out (the message names it and says what to
        change), the motion blows up, or ``odeint`` fails.

    Examples
    --------
    A release of the 2 m arm, quick and exact:

    >>> from twolink import arms
    >>> times = np.linspace(0.0, 2.0, 101)
    >>> quick = simulate_quick(arms.two_metre, [np.pi / 4, 0.0], [0.0, 0.0], times)
    >>> exact = simulate(arms.two_metre, [np.pi / 4, 0.0], [0.0, 0.0], 2.0, t_eval=times)
    >>> bool(np.max(exact.tracking_error(quick.p_tip)) < 1e-3), quick.message[:30]
    (True, 'odeint (LSODA) reached t = 2 s')
    >>> simulate_quick(arms.two_metre, [np.pi / 4, 0.0], [0.0, 0.0], times, max_evaluations=50)
    ... # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    twolink.errors.SimulationError: the quick run used up its budget of max_evaluations = 50 evaluations ...
    """
    start = _start_state(q0, qd0)
    times = _check_t_eval(t_eval)
    if times[-1] > 0.0:
        as_time_span(times[-1], "the last time of t_eval (s)")
    tolerances = {
        name: as_finite_scalar(value, name, minimum=0.0, strictly=True)
        for name, value in (("rtol", rtol), ("atol", atol))
    }
    tolerance_text = f"rtol = {tolerances['rtol']:.3g}, atol = {tolerances['atol']:.3g}"
    budget = EvaluationBudget(max_evaluations, max_wall_time)
    inner = dynamics.state_derivative(arm, torque)
    # lean, odeint calls it ~1e3 times a run: a blow-up shows in the next state, which inner checks
    right_hand_side = budgeted(
        _past_the_start(inner, budget, check_overflow=False), budget
    )

    # here, not at the top: import twolink stays light
    from scipy.integrate import ODEintWarning, odeint

    # odeint starts at its first time: t = 0, the start, then the times asked for
    grid = times if times[0] == 0.0 else np.concatenate([[0.0], times])
    report: dict[str, Any] = {"message": "Integration successful.", "tcur": []}
    try:
        if len(grid) == 1:  # only the start: nothing to integrate
            states = start[np.newaxis, :]
        else:
            with warnings.catch_warnings():  # a failure raises below, with its message
                warnings.simplefilter("ignore", ODEintWarning)
                states, report = odeint(
                    right_hand_side,
                    start,
                    grid,
                    tfirst=True,
                    full_output=True,
                    mxstep=budget.max_evaluations,  # per output interval: the budget is what stops it
                    **tolerances,
                )
    except BudgetSpent as stop:
        if stop.which == "max_wall_time":
            advice = _budget_advice(
                inner, stop, budget, "LSODA", times[-1], torque, math.inf
            )
        else:
            advice = (
                f"the motion needs more steps at {tolerance_text} (fast swings or a stiff loop); raise "
                "max_evaluations, loosen rtol/atol, or run it with simulate (the exact run)"
            )
        raise SimulationError(
            f"the quick run used up its budget of {budget.describe(stop.which)} at "
            f"t = {stop.t:.6g} s of {times[-1]:.6g} s (state {_state_text(stop.state)}): {advice}"
        ) from None
    message = str(report["message"])
    if message != "Integration successful." or not np.all(np.isfinite(states)):
        reached = float(np.max(report["tcur"], initial=0.0))
        last = max(int(np.searchsorted(grid, reached, side="right")) - 1, 0)
        raise SimulationError(
            f"the quick run (odeint, LSODA) failed near t = {reached:.6g} s of {times[-1]:.6g} s after "
            f"{budget.evaluations} evaluations ({message}); state at t = {grid[last]:.6g} s: "
            f"{_state_text(states[last])}; the rates or the torques may overflow (check the controller's "
            "gains and the torques it returns), else try looser tolerances, or simulate"
        )
    states = states[len(grid) - len(times) :]
    q, qd = states[:, :2], states[:, 2:]
    return SimulationResult(
        arm=arm,
        t=times,
        q=q,
        qd=qd,
        tau=_torques_at(torque, times, q, qd, budget),
        status=0,
        message=f"odeint (LSODA) reached t = {times[-1]:.6g} s at {tolerance_text}: {message}",
        nfev=budget.evaluations,
    )
