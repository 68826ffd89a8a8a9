"""The package's one integration: scipy's ``solve_ivp`` within a budget, its options checked (private).

:func:`twolink.simulate` and :func:`twolink.trajectory.resolved_rate_trajectory`
both integrate with :func:`integrate`, and :func:`twolink.simulation.simulate_quick`
spends the same budget (:class:`twolink.budgets.EvaluationBudget`) through
:func:`budgeted`:

- the solver's options are checked against what the method accepts
  (:func:`solver_options`: a misspelt name is refused with the names it
  could have meant, never passed through to be ignored), and a ``max_step``
  or ``first_step`` that could never reach the end within the budget is
  refused before anything runs;
- every evaluation of the right-hand side, and every event function, spends
  the budget; when it is spent :class:`BudgetSpent` stops the solver and the
  caller's error says where, what ran out and what to change;
- the solver failing (its own status) or its arithmetic breaking down is a
  :class:`twolink.SimulationError` naming the time, the last state and the
  solver's words.

The integration runs with the method it is given: nothing here switches
method.

Examples
--------
>>> from twolink.budgets import EvaluationBudget
>>> decay = lambda t, y: [-y[0]]
>>> solution = integrate(decay, 1.0, [1.0], t_eval=[1.0], options={"method": "RK45", "rtol": 1e-9, "atol": 1e-12},
...                      budget=EvaluationBudget(1000, 10.0), what="the decay", state_text=str,
...                      advice=lambda stop: "")
>>> round(float(solution.y[0, -1]), 9), round(float(np.exp(-1.0)), 9)
(0.367879441, 0.367879441)
>>> solver_options({"method": "RK45", "rtoll": 1e-6}, 1.0, 100)
Traceback (most recent call last):
...
ValueError: 'rtoll' is not an option of solve_ivp's method 'RK45' (did you mean 'rtol'?); it takes: method, rtol, atol, max_step, first_step, events
"""

from __future__ import annotations

import difflib
import math
from collections import deque
from collections.abc import Callable, Mapping, Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from ._validate import InputTypeError, as_finite_scalar, real_array
from .budgets import EvaluationBudget
from .errors import SimulationError

__all__ = [
    "METHODS",
    "EXPLICIT_METHODS",
    "BudgetSpent",
    "solver_options",
    "budgeted",
    "spent_error",
    "integrate",
]

#: The methods of :func:`scipy.integrate.solve_ivp`, by name.
METHODS = ("RK45", "RK23", "DOP853", "Radau", "BDF", "LSODA")

#: The explicit Runge-Kutta methods among them (a stiff loop needs one of the others).
EXPLICIT_METHODS = ("RK23", "RK45", "DOP853")

#: Options every method takes (``t_eval`` is an argument of its own).
_COMMON_OPTIONS = ("method", "rtol", "atol", "max_step", "first_step", "events")

#: Options only some methods take (as :func:`scipy.integrate.solve_ivp` documents them).
_METHOD_OPTIONS = {
    "Radau": ("jac", "jac_sparsity"),
    "BDF": ("jac", "jac_sparsity"),
    "LSODA": ("jac", "lband", "uband", "min_step"),
}

#: Fewest right-hand-side evaluations one step of a method costs (the explicit methods'
#: stages; an implicit step costs at least one): how a ``max_step`` is weighed against a budget.
EVALUATIONS_PER_STEP = {"RK23": 3, "RK45": 6, "DOP853": 12}

#: States of the latest evaluations a :class:`BudgetSpent` carries (two steps of DOP853).
RECENT_EVALUATIONS = 24


class _Raised(Exception):
    """Carries an error of the right-hand side through the solver, so that it reaches the caller unchanged."""

    def __init__(self, error: Exception) -> None:
        super().__init__(error)
        self.error = error


class BudgetSpent(Exception):
    """The budget ran out at time ``t`` in ``state``; ``which`` names it (never reaches users).

    ``recent`` holds the states of the evaluations just before, newest last
    (at most :data:`RECENT_EVALUATIONS`): where the motion was as the budget
    ran out, for the advice (a contact that is stiff only while the tip is in
    the wall may be out of it at the very last evaluation).
    """

    def __init__(
        self,
        t: float,
        state: ArrayLike,
        which: str,
        recent: Sequence[ArrayLike] = (),
    ) -> None:
        super().__init__(which)
        self.t, self.state, self.which = float(t), np.array(state, dtype=float), which
        self.recent = [np.array(past, dtype=float) for past in recent]


def _options_of(method: str) -> tuple[str, ...]:
    return _COMMON_OPTIONS + _METHOD_OPTIONS.get(method, ())


def _positive_time(value: object, name: str, t_end: float) -> float:
    step = as_finite_scalar(value, f"{name} (s)", minimum=0.0, strictly=True)
    if step > t_end:
        raise ValueError(
            f"{name} (s) must be at most the time to integrate, {t_end:.6g} s; got {step:.6g}"
        )
    return step


def solver_options(
    options: Mapping[str, Any], t_end: float, max_evaluations: int
) -> dict[str, Any]:
    """``options`` for ``solve_ivp``, each name one its method takes and each value checked.

    Parameters
    ----------
    options : mapping
        ``method`` (one of :data:`METHODS`) and the method's options.
    t_end : float
        The time to integrate (s): ``first_step`` and ``max_step`` may not exceed it.
    max_evaluations : int
        The budget: a ``max_step`` that needs more steps than this is refused
        at once (the integration could only run out of budget).

    Raises
    ------
    ValueError
        Naming the option, what was given and what is allowed (for a name
        the method does not take: the names it takes, and the close ones).
    twolink.errors.InputTypeError
        For a value of the wrong type (a tolerance given as a string, ...).

    Examples
    --------
    >>> solver_options({"method": "DOP853", "max_step": 1e-300}, 1.0, 10**6)
    Traceback (most recent call last):
    ...
    ValueError: max_step = 1e-300 s would take at least 1e+300 steps of 12 evaluations to reach t_end = 1 s, more than max_evaluations = 1000000: give max_step >= 1.2e-05 s, or raise max_evaluations
    """
    method = options.get("method", "RK45")
    if not (isinstance(method, str) and method in METHODS):
        raise ValueError(f"method must be one of {METHODS}; got {method!r}")
    allowed = _options_of(method)
    checked: dict[str, Any] = {"method": method}
    for name, value in options.items():
        if name not in allowed:
            close = difflib.get_close_matches(
                name,
                sorted({*allowed, *(o for v in _METHOD_OPTIONS.values() for o in v)}),
                n=1,
            )
            hint = f" (did you mean {close[0]!r}?)" if close else ""
            raise ValueError(
                f"{name!r} is not an option of solve_ivp's method {method!r}{hint}; "
                f"it takes: {', '.join(allowed)}"
            )
        if name in ("rtol", "atol"):
            tolerance = real_array(value, name, "positive numbers")
            if tolerance.ndim > 1 or not np.all(
                np.isfinite(tolerance) & (tolerance > 0.0)
            ):
                raise ValueError(
                    f"{name} must be a positive finite number (or one per state variable); got {value!r}"
                )
            value = float(tolerance) if tolerance.ndim == 0 else tolerance
        elif name == "first_step":
            value = _positive_time(value, name, t_end)
        elif name == "min_step" or (
            name == "max_step"
            and not (isinstance(value, (float, np.floating)) and value == math.inf)
        ):  # max_step may be infinite (scipy's default)
            value = _positive_time(value, name, t_end)
        checked[name] = value
    max_step = checked.get("max_step", math.inf)
    steps = t_end / max_step
    per_step = EVALUATIONS_PER_STEP.get(method, 1)
    if steps * per_step > max_evaluations:
        raise ValueError(
            f"max_step = {max_step:.6g} s would take at least {steps:.3g} steps of {per_step} evaluation"
            f"{'s' if per_step != 1 else ''} to reach t_end = {t_end:.6g} s, more than max_evaluations = "
            f"{max_evaluations}: give max_step >= {t_end * per_step / max_evaluations:.2g} s, or raise "
            "max_evaluations"
        )
    return checked


def budgeted(
    function: Callable[[float, Any], Any], budget: EvaluationBudget
) -> Callable[[float, Any], Any]:
    """``function(t, state)`` that first spends one evaluation of ``budget``, raising :class:`BudgetSpent` when it is spent.

    The :class:`BudgetSpent` carries the states of the latest evaluations too,
    kept as the solver passed them, uncopied (a copy would cost as much as a
    tenth of the cheapest right-hand side): a solver that reuses its array
    (odeint, LSODA, BDF) leaves its latest state in several of them.
    """
    recent: deque[Any] = deque(maxlen=RECENT_EVALUATIONS)

    def spending(t: float, state: Any) -> Any:
        spent = budget.spend()
        if spent is not None:
            raise BudgetSpent(t, state, spent, recent)
        recent.append(state)
        return function(t, state)

    return spending


def _timed_events(
    events: Callable[..., Any] | Sequence[Callable[..., Any]], budget: EvaluationBudget
) -> Callable[..., Any] | list[Callable[..., Any]]:
    """``events`` (one callable or a list) wrapped so that each call, between the solver's steps, checks the wall clock."""

    def timed(event: object) -> Callable[..., Any]:
        if not callable(event):
            raise InputTypeError(
                f"events must be callables event(t, y) (or a list of them); got {event!r}"
            )

        def checked(t: float, state: Any) -> Any:
            if budget.out_of_time():
                raise BudgetSpent(t, state, "max_wall_time")
            return event(t, state)

        # solve_ivp reads these two attributes of an event function (not in its type)
        setattr(checked, "terminal", getattr(event, "terminal", False))  # noqa: B010
        setattr(checked, "direction", getattr(event, "direction", 0.0))  # noqa: B010
        return checked

    if callable(events):
        return timed(events)
    if not isinstance(events, (list, tuple)):
        raise InputTypeError(
            f"events must be callables event(t, y) (or a list of them); got {events!r}"
        )
    return [timed(event) for event in events]


def spent_error(
    what: str,
    method: str,
    budget: EvaluationBudget,
    stop: BudgetSpent,
    t_end: float,
    state_text: Callable[[Any], str],
    advice: Callable[[BudgetSpent], str],
) -> SimulationError:
    """The error of a spent budget: what ran out, where, with which method, in which state, and what to change."""
    return SimulationError(
        f"{what} used up its budget of {budget.describe(stop.which)} at t = {stop.t:.6g} s of "
        f"{t_end:.6g} s with method {method!r} (state {state_text(stop.state)}); {advice(stop)}"
    )


def integrate(
    right_hand_side: Callable[[float, Any], Any],
    t_end: float,
    start: ArrayLike,
    *,
    t_eval: ArrayLike | None,
    options: Mapping[str, Any],
    budget: EvaluationBudget,
    what: str,
    state_text: Callable[[Any], str],
    advice: Callable[[BudgetSpent], str],
) -> Any:
    """Integrate ``dy/dt = right_hand_side(t, y)`` from ``y(0) = start`` to ``t_end`` with ``solve_ivp``.

    Parameters
    ----------
    right_hand_side : callable
        ``f(t, y)``; its own errors reach the caller unchanged.
    t_end : float
        The end time (s), checked by the caller.
    start : array_like
        The state at ``t = 0``.
    t_eval : array_like or None
        Output times (checked by the caller), or the solver's own steps.
    options : mapping
        The solver's options, checked by :func:`solver_options`.
    budget : EvaluationBudget
        Spent by every evaluation of ``right_hand_side`` and read by every event.
    what : str
        What integrates, for the messages (``"the integration"``, ``"resolved rate"``).
    state_text : callable
        A state in words, for the messages.
    advice : callable
        What to change when the budget is spent (given the :class:`BudgetSpent`).

    Returns
    -------
    scipy.integrate's OdeResult
        Its ``status`` is 0 (the end reached) or 1 (a terminal event).

    Raises
    ------
    twolink.SimulationError
        When the budget is spent, the solver fails or its arithmetic breaks
        down: the message names the time reached, the state there and what
        to change.
    """
    # here, not at the top: import twolink stays light
    from scipy.integrate import solve_ivp

    arguments = dict(options)
    if arguments.get("events") is not None:
        arguments["events"] = _timed_events(arguments["events"], budget)
    last: list[Any] = [0.0, start]

    def evaluate(t: float, state: Any) -> Any:
        last[0], last[1] = t, state
        try:
            return right_hand_side(t, state)
        except Exception as error:  # noqa: BLE001 - re-raised unchanged below
            raise _Raised(error) from None

    try:
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            solution = solve_ivp(
                budgeted(evaluate, budget),
                (0.0, t_end),
                start,
                t_eval=t_eval,
                **arguments,
            )
    except BudgetSpent as stop:
        raise spent_error(
            what, arguments["method"], budget, stop, t_end, state_text, advice
        ) from None
    except _Raised as raised:
        raise raised.error from None
    except (ValueError, ArithmeticError, np.linalg.LinAlgError) as exc:
        if budget.evaluations == 0:  # scipy refused the options or the start: bad input
            raise
        # the solver's own arithmetic broke down (overflowing rates or Jacobian): a blow-up, not bad input
        raise SimulationError(
            f"{what} broke down at t = {last[0]:.6g} s after {budget.evaluations} evaluations "
            f"({type(exc).__name__}: {exc}), last state {state_text(np.asarray(last[1], dtype=float))}: "
            "the rates overflow; check the gains and the torques"
        ) from exc
    if solution.status < 0 or not np.all(np.isfinite(solution.y)):
        reached = max(float(solution.t[-1]) if solution.t.size else 0.0, last[0])
        raise SimulationError(
            f"{what} failed at t = {reached:.6g} s of {t_end:.6g} s with method "
            f"{arguments['method']!r}: {solution.message} (last state "
            f"{state_text(np.asarray(last[1], dtype=float))}; try a smaller max_step, looser tolerances "
            "or another method)"
        )
    return solution
