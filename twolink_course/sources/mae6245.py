"""MAE 6245, reproduced: inverse kinematics three ways on a1 = a2 = 10.

The assignment asks for the IK of the planar 2R arm with a1 = a2 = 10 (no
units): (a) a closed form and a MATLAB function, (b) "one of the numerical
techniques shown in class (root finding or optimization)", (c) a brute-force
function over q1 in [0, 90] deg, q2 in [-90, 90] deg, and ``tic``/``toc``
timings on a circle of 10 to 20 targets, "(preferably equi-distant)": a
preference, not a requirement (``notebooks/source_record.ipynb#h1-5``,
``#h1-4``).  Its worked solution chose MATLAB's ``fminunc`` for (b).  It
contains the closed form and the ``fminunc`` objective for the target
(10 sqrt 2, 10 sqrt 2), an ``fmincon`` feasibility formulation, a
forward-kinematics check, a workspace scatter on a 0.1 rad grid (its part (c))
and the circle's points.  It has no brute-force IK function, no measured
times and no arm drawn on the circle: for the timing it says only that the
time "would typically be" closed form, numerical, brute force "in increasing
order".  This module reruns what the solution did, step by step, so that
chapters 2 and 7 (and the tests) show its printed numbers coming out of its
own formulas; each fact rests on an item of the course's source record,
``notebooks/source_record.ipynb`` (anchors ``#h1-1`` ... ``#h1-9``):

- :func:`x_equation_roots`: its closed form, the ``a cos t + b sin t = c``
  solution applied to the x-equation alone; printed "theta1 = +-0.7854,
  theta2 = 0", of which the minus root is spurious (``#h1-1``).
- :func:`closed_form_cosine`: the cosine its closed-form script computes at its
  own target, 1.0000000000000002 in IEEE doubles (``#h1-7``): ``acos`` of it is
  complex in MATLAB, whose ``atan2`` takes real arguments only.  Not run in
  MATLAB here: the course asks what the script does there, it does not say.
- :func:`numerical_ik`: its ``fminunc`` run on the absolute y-residual with
  q1 + q2 from ``acos`` of the x-equation, translated with MATLAB's ``acos``
  (complex outside [-1, 1]) or with numpy's (``nan`` there); printed
  0.7854, 0 (``#h1-2``).
- :func:`fk_check`: its forward-kinematics check, typed with theta1 = 0.7845
  (a digit swap of 0.7854); printed x = 14.1548, y = 14.1294 (``#h1-3``).
  Its part (e) draws the arm at :data:`PART_E_ANGLES`, the same swap a
  second time (``#h1-9``).
- :func:`circle_angles`: its circle points, ``phi = 0:0.5:2*pi``: 13 points,
  the last gap shorter than the others (``#h1-4``).
- :func:`workspace_grid`: its part (c) workspace scatter's grid,
  ``0:0.1:pi/2`` and ``-pi/2:0.1:pi/2``, whose last samples, 1.5 and
  1.529 rad, stop short of pi/2 (``#h1-8``).

The correct methods live in :mod:`twolink.ik`; nothing here is meant for new
code.  Angles in radians, lengths in the assignment's units (read as metres).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "A1",
    "A2",
    "TARGET",
    "Q1_START",
    "FK_CHECK_THETA1",
    "CIRCLE_CENTRE",
    "CIRCLE_RADIUS",
    "CIRCLE_STEP",
    "WORKSPACE_STEP",
    "PART_E_ANGLES",
    "TASK_CIRCLE_POINTS",
    "TASK_RANGES_DEG",
    "colon",
    "x_equation_roots",
    "closed_form_cosine",
    "y_residual",
    "NumericalRun",
    "numerical_ik",
    "fk_check",
    "circle_angles",
    "workspace_grid",
]

#: The assignment's link lengths (no units; the course reads them as metres).
A1 = 10.0
A2 = 10.0
#: The IK target its solution solved, at full stretch: (10 sqrt 2, 10 sqrt 2).
TARGET = (10.0 * np.sqrt(2.0), 10.0 * np.sqrt(2.0))
#: Where its solution's ``fminunc`` run started, rad.
Q1_START = 0.4
#: The theta1 its solution's FK check was typed with: 0.7845, a digit swap of 0.7854
#: (its caption says 0.7854).
FK_CHECK_THETA1 = 0.7845
#: The angles its part (e) draws the arm at, (0.7845, -0.7845) rad: the digit swap again.
PART_E_ANGLES = (0.7845, -0.7845)
#: Its solution's circle of targets: centre, radius and the step of ``phi = 0:0.5:2*pi`` (rad).
CIRCLE_CENTRE = (12.5, 12.5)
CIRCLE_RADIUS = 2.0
CIRCLE_STEP = 0.5
#: How many points the task asks for on the circle: 10 to 20, "(preferably equi-distant)".
TASK_CIRCLE_POINTS = (10, 20)
#: The joint ranges the task sets for the brute-force function, degrees: q1, q2.
TASK_RANGES_DEG = ((0.0, 90.0), (-90.0, 90.0))
#: The step of its part (c) workspace grid, ``0:0.1:pi/2`` and ``-pi/2:0.1:pi/2`` (rad).
WORKSPACE_STEP = 0.1

_ACOS: dict[str, Callable[[Any], Any]] = {"matlab": np.emath.arccos, "numpy": np.arccos}


def _check_acos(acos: str) -> Callable[[Any], Any]:
    if acos not in _ACOS:
        raise ValueError(f"acos must be one of {sorted(_ACOS)}; got {acos!r}")
    return _ACOS[acos]


def x_equation_roots(
    p: ArrayLike, theta2: float, a1: float = A1, a2: float = A2
) -> NDArray[np.float64]:
    """Both roots of the solution's closed form: the x-equation solved for theta1.

    With theta2 known, ``x = (a1 + a2 cos theta2) cos theta1 - a2 sin theta2 sin theta1``
    has the form ``a cos t + b sin t = c`` (``a = a1 + a2 c2``, ``b = -a2 s2``,
    ``c = x``), solved as
    ``theta1 = atan2(b, a) +- atan2(sqrt(a^2 + b^2 - x^2), x)``.  Both roots
    satisfy the x-equation; the y-equation was never imposed, so one of them is
    in general spurious: with theta2 fixed the tip's distance from the base is
    fixed, and the spurious root puts the tip at the mirror point (x, -y).

    Parameters
    ----------
    p : pair of float
        The target (x, y); only x enters.
    theta2 : float
        The elbow angle, radians (its solution printed theta2 = 0 for its target).
    a1, a2 : float
        Link lengths.

    Returns
    -------
    numpy.ndarray, shape (2,)
        theta1 with the plus sign, theta1 with the minus sign, radians.

    Examples
    --------
    The solution's printed "theta1 = +-0.7854" for its target:

    >>> roots = x_equation_roots(TARGET, theta2=0.0)
    >>> roots.round(4)
    array([ 0.7854, -0.7854])

    Only the plus root puts the tip on the target; the minus root lands at (x, -y):

    >>> [fk_check(theta1, 0.0).round(2).tolist() for theta1 in roots]
    [[14.14, 14.14], [14.14, -14.14]]
    """
    x = float(np.asarray(p, dtype=float)[0])
    a = a1 + a2 * np.cos(theta2)
    b = -a2 * np.sin(theta2)
    discriminant = a**2 + b**2 - x**2
    if discriminant < 0:
        raise ValueError(
            f"no real root: x = {x:g} exceeds sqrt(a^2 + b^2) = {np.hypot(a, b):g} for theta2 = {theta2:g}"
        )
    direction = np.arctan2(b, a)
    half_angle = np.arctan2(np.sqrt(discriminant), x)
    return np.array([direction + half_angle, direction - half_angle])


def closed_form_cosine(p: ArrayLike = TARGET, a1: float = A1, a2: float = A2) -> float:
    """``(x^2 + y^2 - a1^2 - a2^2) / (2 a1 a2)`` as its closed-form script computes it, in IEEE doubles.

    At its own target, (10 sqrt 2, 10 sqrt 2), the arm is stretched and the
    exact value is 1; in doubles ``x^2`` is 200.00000000000003 and the cosine
    1.0000000000000002, just above 1 (the same arithmetic in MATLAB).  MATLAB's
    ``acos`` is complex there (about 2.1e-8 i, :func:`numpy.emath.arccos`)
    and its ``atan2`` takes real arguments only, so the script as written
    would stop with an error at that target, while the solution shows
    "theta1 = +-0.7854, theta2 = 0" (``source_record.ipynb#h1-7``).  Not run
    in MATLAB here: a question to ask, not a claim about what MATLAB did.

    Parameters
    ----------
    p : pair of float
        The target (x, y).
    a1, a2 : float
        Link lengths.

    Returns
    -------
    float

    Examples
    --------
    >>> x = float(TARGET[0])
    >>> repr(x * x), repr(closed_form_cosine())
    ('200.00000000000003', '1.0000000000000002')
    >>> round(abs(complex(np.emath.arccos(closed_form_cosine())).imag), 9)
    2.1e-08
    """
    x, y = (float(value) for value in np.asarray(p, dtype=float))
    return (x * x + y * y - a1 * a1 - a2 * a2) / (2.0 * a1 * a2)


def y_residual(
    q1: ArrayLike,
    p: ArrayLike = TARGET,
    acos: str = "matlab",
    a1: float = A1,
    a2: float = A2,
) -> NDArray[np.float64] | np.float64:
    """The solution's objective: ``abs(a1 sin q1 + a2 sin(acos((x - a1 cos q1)/a2)) - y)``.

    q1 + q2 is taken from ``acos`` of the x-equation and put into the
    y-equation; the absolute value (not a square) of what is left is the
    objective it minimised over q1 alone.

    Parameters
    ----------
    q1 : float or array_like
        Link 1 angle, radians.
    p : pair of float
        The target (x, y).
    acos : {"matlab", "numpy"}
        "matlab": ``acos`` of a number outside [-1, 1] is complex (MATLAB's
        ``acos``, here :func:`numpy.emath.arccos`), and the residual is the
        modulus of a complex number.  "numpy": :func:`numpy.arccos`, ``nan``
        there (its RuntimeWarning silenced, as in a script nobody watches).
    a1, a2 : float
        Link lengths.

    Returns
    -------
    numpy.float64 or numpy.ndarray
        The objective, >= 0 (``nan`` for "numpy" outside the domain), a
        numpy float for a number ``q1``, else an array of its shape.

    Examples
    --------
    At q1 = 1.41 the argument of ``acos`` is 1.25: MATLAB's ``acos`` still gives a
    number, numpy's gives ``nan``.

    >>> round(float(y_residual(1.41, acos="matlab")), 2), float(y_residual(1.41, acos="numpy"))
    (8.69, nan)
    >>> float(y_residual(np.pi / 4)) < 1e-12
    True
    """
    arccos = _check_acos(acos)
    x, y = np.asarray(p, dtype=float)
    angle = np.asarray(q1, dtype=float)
    with np.errstate(invalid="ignore"):
        residual = (
            a1 * np.sin(angle) + a2 * np.sin(arccos((x - a1 * np.cos(angle)) / a2)) - y
        )
    return np.abs(residual)


@dataclass(frozen=True)
class NumericalRun:
    """One run of the solution's numerical IK (see :func:`numerical_ik`).

    Attributes
    ----------
    q : numpy.ndarray, shape (2,)
        (q1, q2) in radians: q1 where the optimiser stopped, q2 the real part of
        ``acos((x - a1 cos q1)/a2) - q1`` (``nan`` with numpy's ``acos`` outside
        its domain).
    q2_imag : float
        The imaginary part of that q2 (MATLAB's ``acos`` outside [-1, 1]); 0 for a
        real answer.
    success : bool
        scipy's verdict.
    message : str
        scipy's message.
    iterations : int
        Quasi-Newton iterations (scipy's ``nit``).
    evaluations : int
        Objective evaluations.
    q1_trials, objective_trials : numpy.ndarray
        Every q1 the optimiser asked about, and the objective it got back.
    """

    q: NDArray[np.float64]
    q2_imag: float
    success: bool
    message: str
    iterations: int
    evaluations: int
    q1_trials: NDArray[np.float64]
    objective_trials: NDArray[np.float64]


def numerical_ik(
    p: ArrayLike = TARGET,
    q1_start: float = Q1_START,
    acos: str = "matlab",
    a1: float = A1,
    a2: float = A2,
) -> NumericalRun:
    """The solution's numerical IK, translated: minimise :func:`y_residual` over q1, then q2.

    MATLAB's ``fminunc`` (a quasi-Newton method) becomes scipy's BFGS from the
    same start; then ``q2 = acos((x - a1 cos q1)/a2) - q1``.

    Parameters
    ----------
    p : pair of float
        The target (x, y).
    q1_start : float
        Start of the minimisation, radians (the solution's 0.4).
    acos : {"matlab", "numpy"}
        Which ``acos`` the translation uses (see :func:`y_residual`).
    a1, a2 : float
        Link lengths.

    Returns
    -------
    NumericalRun

    Examples
    --------
    With MATLAB's ``acos`` the method reaches the solution's printed 0.7854, 0:

    >>> run = numerical_ik(acos="matlab")
    >>> round(float(run.q[0]), 4), bool(abs(run.q[1]) < 1e-6), run.success
    (0.7854, True, True)

    The same code with numpy's ``arccos``: the first trial step leaves the domain,
    the objective returns nan without an error, and the run ends far away:

    >>> run = numerical_ik(acos="numpy")
    >>> run.success, bool(np.isnan(run.q[1])), bool(abs(run.q[0]) > 2 * np.pi)
    (False, True, True)
    """
    arccos = _check_acos(acos)
    x = float(np.asarray(p, dtype=float)[0])
    q1_trials: list[float] = []
    objective_trials: list[float] = []

    def objective(q1_vector: NDArray[np.float64]) -> float:
        value = float(y_residual(q1_vector[0], p, acos, a1, a2))
        q1_trials.append(float(q1_vector[0]))
        objective_trials.append(value)
        return value

    import scipy.optimize  # here, not at the top: import twolink stays light

    outcome = scipy.optimize.minimize(objective, [float(q1_start)], method="BFGS")
    q1 = float(outcome.x[0])
    with np.errstate(invalid="ignore"):
        q12 = complex(arccos((x - a1 * np.cos(q1)) / a2))
    return NumericalRun(
        q=np.array([q1, q12.real - q1]),
        q2_imag=float(q12.imag),
        success=bool(outcome.success),
        message=str(outcome.message),
        iterations=int(outcome.nit),
        evaluations=int(outcome.nfev),
        q1_trials=np.array(q1_trials),
        objective_trials=np.array(objective_trials),
    )


def fk_check(
    theta1: float = FK_CHECK_THETA1, theta2: float = 0.0, a1: float = A1, a2: float = A2
) -> NDArray[np.float64]:
    """The solution's FK check: ``x = a1 cos t1 + a2 cos(t1 + t2)``, ``y`` likewise.

    It was typed with theta1 = 0.7845 instead of the 0.7854 its IK had printed.

    Parameters
    ----------
    theta1, theta2 : float
        Joint angles, radians (relative, DH).
    a1, a2 : float
        Link lengths.

    Returns
    -------
    numpy.ndarray, shape (2,)
        The tip (x, y).

    Examples
    --------
    The printed "x = 14.1548, y = 14.1294":

    >>> fk_check().round(4)
    array([14.1548, 14.1294])
    """
    return np.array(
        [
            a1 * np.cos(theta1) + a2 * np.cos(theta1 + theta2),
            a1 * np.sin(theta1) + a2 * np.sin(theta1 + theta2),
        ]
    )


def colon(start: float, step: float, stop: float) -> NDArray[np.float64]:
    """MATLAB's colon operator ``start:step:stop``: ``start + k step`` up to ``stop``, never beyond.

    Parameters
    ----------
    start, stop : float
        The first value and the bound the last one does not pass.
    step : float
        Increment (> 0).

    Returns
    -------
    numpy.ndarray

    Examples
    --------
    >>> colon(0.0, 0.5, 2.0)
    array([0. , 0.5, 1. , 1.5, 2. ])
    >>> float(colon(0.0, 0.1, np.pi / 2)[-1])       # short of pi/2
    1.5
    """
    if not step > 0:
        raise ValueError(f"step must be > 0; got {step!r}")
    if not np.isfinite(start) or not np.isfinite(stop) or stop < start:
        raise ValueError(
            f"start and stop must be finite with start <= stop; got {start!r}, {stop!r}"
        )
    count = int(np.floor((stop - start) / step + 1e-10)) + 1
    return start + step * np.arange(count, dtype=np.float64)


def circle_angles(step: float = CIRCLE_STEP) -> NDArray[np.float64]:
    """The solution's circle parameter ``phi = 0:step:2*pi`` (MATLAB's colon operator).

    The colon operator stops at the last multiple of the step not beyond
    2 pi, so with step 0.5 there are 13 angles, 0 to 6, and the gap from the
    last back to the first is 2 pi - 6 = 0.283 rad, not 0.5
    (``source_record.ipynb#h1-4``).

    Parameters
    ----------
    step : float
        Increment, radians (> 0).

    Returns
    -------
    numpy.ndarray
        The angles, radians.

    Examples
    --------
    >>> phi = circle_angles()
    >>> len(phi), float(phi[-1]), round(float(2 * np.pi - phi[-1]), 3)
    (13, 6.0, 0.283)
    """
    if not step > 0:
        raise ValueError(f"step must be > 0 rad; got {step!r}")
    return colon(0.0, step, 2 * np.pi)


def workspace_grid(
    step: float = WORKSPACE_STEP,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The two axes of its part (c) workspace scatter: ``0:step:pi/2`` and ``-pi/2:step:pi/2``.

    The colon operator stops at the last sample not beyond pi/2, so with
    the solution's step 0.1 the axes end at 1.5 and 1.529 rad, short of
    pi/2: the scatter misses the edge of the joint ranges, the
    grid-end mistake (``source_record.ipynb#h1-8``).

    Parameters
    ----------
    step : float
        Increment, radians (> 0).

    Returns
    -------
    (numpy.ndarray, numpy.ndarray)
        The theta1 and theta2 samples, radians.

    Examples
    --------
    >>> theta1, theta2 = workspace_grid()
    >>> round(float(theta1[-1]), 3), round(float(theta2[-1]), 3)
    (1.5, 1.529)
    >>> bool(theta1[-1] < np.pi / 2 and theta2[-1] < np.pi / 2)
    True
    """
    return colon(0.0, step, np.pi / 2), colon(-np.pi / 2, step, np.pi / 2)
