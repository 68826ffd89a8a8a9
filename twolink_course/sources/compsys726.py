"""COMPSYS726, reproduced: the velocity table along the line y = 50.

The coursework derived the planar arm's DH table, ``A1``, ``A2``,
``T = A1 A2`` and its Jacobian (all correct), and the joint rates for a tip
moving only vertically (``xdot = 0``) or only horizontally (``ydot = 0``),
also correct:

- vertical: ``q2dot = (-a1 s1 - a2 s12) / (a1 a2 s2) * ydot``
  (:func:`q2_rate_vertical`);
- horizontal: ``q1dot = a2 c12 / (a1 a2 s2) * xdot`` (:func:`q1_rate_horizontal`).

Then it tabulated joint angles and a joint rate for the tip on the line
``y = 50`` at ``x = 10, 20, ..., 100`` (bare numbers; the arm is not stated).
The arm ``a1 = 100``, ``a2 = 50`` reproduces both printed angle columns to their
printed rounding (:data:`PRINTED_ANGLES_DEG`: whole degrees, e.g. 49, 172 at
``x = 10``), except the last q1, where the method gives -3.38 deg and the
printed value is -3.3: truncated, not rounded, as the worked row's
"theta1 = 49.09" is (the method gives 49.0965; :func:`truncated`).  Its text
calls theta "the angle between the plane and the Link", an absolute angle,
beside a relative DH table.
The rate column is reproduced from the **printed**, rounded angles:
:func:`rate_as_printed` of :data:`PRINTED_ANGLES_DEG` gives 0.6132 at ``x = 10``
(:data:`PRINTED_RATE_FIRST_ROW`) and is within 0.16 % of every printed row.  At
the unrounded angles of the same IK it would be up to 1.24 % off the printed
column (0.6066 at ``x = 10``): the source computed its rates from its rounded
table.
The table has three faults, reproduced here:

1. :func:`ik_as_written`: ``q2 = acosd(...)`` (degrees, right), then
   ``sin(q2)``, ``cos(q2)`` of that degree value (radians expected) in
   ``q1 = atand(y/x)`` minus the elbow term in ``sin(q2)``, ``cos(q2)``
   (reproduced as ``atand(a2 sin q2 / (a1 + a2 cos q2))``): the q1 column is
   wrong.  (``atand(y/x)`` does no harm on this line, where ``x > 0``.)
2. and 3. :func:`rate_as_printed`: the rate column is the **vertical**
   formula, where horizontal motion was asked, evaluated at the printed
   (wrong, rounded) angles and multiplied by -10 (a velocity the text never
   states).

Each fact rests on an item of the course's source record,
``notebooks/source_record.ipynb`` (anchors ``#h2-1`` ... ``#h2-5``).
Lengths are the source's bare numbers; angles in the source's functions are
in degrees, as the source printed them.  Nothing here is for new code: use
:func:`twolink.ik.closed_form` and :meth:`twolink.TwoLinkArm.joint_rates`.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from twolink._validate import as_finite_scalar

__all__ = [
    "A1",
    "A2",
    "Y_LINE",
    "X_LINE",
    "RATE_FACTOR",
    "PRINTED_ANGLES_DEG",
    "PRINTED_RATE_FIRST_ROW",
    "WORKED_ROW_PRINTED_DEG",
    "truncated",
    "ik_as_written",
    "q2_rate_vertical",
    "q1_rate_horizontal",
    "rate_as_printed",
]

A1 = 100.0
"""Link 1 of the arm that reproduces the table (bare units)."""
A2 = 50.0
"""Link 2 of the arm that reproduces the table (bare units)."""
Y_LINE = 50.0
"""The table's line, ``y = 50``."""
X_LINE = np.arange(10.0, 101.0, 10.0)
"""The table's points, ``x = 10, 20, ..., 100``."""
RATE_FACTOR = -10.0
"""The factor the printed rate column carries (a tip velocity the text never states)."""
PRINTED_ANGLES_DEG = np.array(
    [
        [49.0, 172.0],
        [61.0, 164.0],
        [86.0, 156.0],
        [28.0, 147.0],
        [38.0, 139.0],
        [70.0, 130.0],
        [13.0, 121.0],
        [62.0, 111.0],
        [21.0, 101.0],
        [-3.3, 90.0],
    ]
)
"""The source's printed angle table ``(q1, q2)`` in degrees, one row per ``x`` of :data:`X_LINE`, shape (10, 2).

Derived, not transcribed: the reproduction :func:`ik_as_written` at
:data:`X_LINE` rounded as the source printed it, to whole degrees, except the
last row's q1, printed -3.3 (the reproduction gives -3.38, which rounds to
-3.4 and truncates to -3.3, :func:`truncated`).  The source's first and last rows, (49, 172) and (-3.3, 90), are of
this form.  :func:`rate_as_printed` of this table reproduces the printed rate
column to within 0.16 % in every row (0.6132 at ``x = 10``).
"""
PRINTED_RATE_FIRST_ROW = 0.6132
"""The printed rate at ``x = 10``: :func:`rate_as_printed` of the printed angles (49, 172), to 4 decimals."""
WORKED_ROW_PRINTED_DEG = (49.09, 171.89)
"""The worked row's printed "theta1 = 49.09" and "theta2 = 171.89 ~ 172", degrees (``x = 10``)."""


def truncated(values: ArrayLike, decimals: int) -> NDArray[np.float64]:
    """``values`` cut to ``decimals`` decimals, towards zero: how the source's -3.3 and 49.09 come about.

    The reproduction gives -3.3793 deg for the last q1 and 49.0965 deg for the
    worked row's theta1; rounded they print -3.4 and 49.10, truncated -3.3 and
    49.09, as printed (``source_record.ipynb#h2-5``).

    Parameters
    ----------
    values : array_like
        Finite numbers.
    decimals : int
        Decimals kept (>= 0).

    Returns
    -------
    numpy.ndarray

    Examples
    --------
    >>> q1_last, q1_first = ik_as_written(100.0)[0], ik_as_written(10.0)[0]
    >>> float(truncated(q1_last, 1)), float(truncated(q1_first, 2))
    (-3.3, 49.09)
    >>> round(float(q1_last), 1), round(float(q1_first), 2)
    (-3.4, 49.1)
    """
    if isinstance(decimals, bool) or not isinstance(decimals, int) or decimals < 0:
        raise ValueError(f"decimals must be a whole number >= 0; got {decimals!r}")
    scale = 10.0**decimals
    return np.trunc(_array(values, "values") * scale) / scale


def _array(values: ArrayLike, name: str) -> NDArray[np.float64]:
    array = np.asarray(values, dtype=float)
    if not np.isfinite(array).all():
        raise ValueError(f"{name} must be finite numbers; got {values!r}")
    return array


def _lengths(a1: float, a2: float) -> tuple[float, float]:
    return (
        as_finite_scalar(a1, "a1", minimum=0.0, strictly=True),
        as_finite_scalar(a2, "a2", minimum=0.0, strictly=True),
    )


def ik_as_written(
    x: ArrayLike, y: ArrayLike = Y_LINE, a1: float = A1, a2: float = A2
) -> NDArray[np.float64]:
    """Joint angles ``(q1, q2)`` in degrees, as the source's IK function computed them.

    ``q2 = acosd((x^2 + y^2 - a1^2 - a2^2) / (2 a1 a2))`` is right (degrees,
    elbow with ``q2 > 0``).  Then ``q1 = atand(y/x)`` minus the elbow term in
    ``sin(q2)``, ``cos(q2)`` (reproduced as ``atand(a2 sin(q2) / (a1 + a2 cos(q2)))``),
    with ``sin``/``cos`` applied to the degree value of ``q2``, as if it were
    radians: that makes ``q1`` wrong.  ``atand(y/x)`` would also be wrong for
    ``x < 0`` (it cannot tell ``(x, y)`` from ``(-x, -y)``), but every point of
    the table has ``x > 0``.

    Parameters
    ----------
    x, y : array_like
        Target tip position (bare units), broadcast together; ``x != 0``.
    a1, a2 : float
        Link lengths (> 0).

    Returns
    -------
    numpy.ndarray, shape (..., 2)
        ``(q1, q2)`` in degrees.

    Raises
    ------
    ValueError
        If a target is out of reach (the source's ``acosd`` would return a
        complex number there) or ``x == 0`` (``y/x`` is undefined).

    Examples
    --------
    >>> ik_as_written(10.0).round(2)      # printed: 49, 172; right: (70.74, 171.89)
    array([ 49.1 , 171.89])
    >>> ik_as_written(100.0).round(3)     # printed -3.3, 90 (-3.379 rounds to -3.4); right: (0, 90)
    array([-3.379, 90.   ])
    """
    x, y = np.broadcast_arrays(_array(x, "x"), _array(y, "y"))
    a1, a2 = _lengths(a1, a2)
    if np.any(x == 0.0):
        raise ValueError("x must be nonzero: the source's atand(y/x) divides by x")
    cos_q2 = (x**2 + y**2 - a1**2 - a2**2) / (2.0 * a1 * a2)
    if np.any(np.abs(cos_q2) > 1.0):
        raise ValueError(
            f"target out of reach of the a1 = {a1:g}, a2 = {a2:g} arm: "
            f"(x^2 + y^2 - a1^2 - a2^2) / (2 a1 a2) = {cos_q2[np.abs(cos_q2) > 1.0].ravel()[0]:.4g} "
            "is outside [-1, 1]"
        )
    q2_deg = np.degrees(np.arccos(cos_q2))  # acosd: right
    q1_deg = np.degrees(
        np.arctan(y / x)
    ) - np.degrees(  # atand(y/x), and sin/cos of degrees: wrong
        np.arctan(a2 * np.sin(q2_deg) / (a1 + a2 * np.cos(q2_deg)))
    )
    return np.stack([q1_deg, q2_deg], axis=-1)


def q2_rate_vertical(
    q1: ArrayLike, q2: ArrayLike, y_rate: ArrayLike, a1: float = A1, a2: float = A2
) -> NDArray[np.float64]:
    """``q2dot = (-a1 s1 - a2 s12) / (a1 a2 s2) * ydot`` for a tip moving only vertically (the source's, right).

    Parameters
    ----------
    q1, q2 : array_like
        Joint angles, radians.
    y_rate : float or array_like
        Vertical tip velocity (length units per s).
    a1, a2 : float
        Link lengths (> 0).

    Returns
    -------
    numpy.ndarray
        ``q2dot`` in rad/s, the broadcast shape of the inputs.

    Examples
    --------
    >>> round(float(q2_rate_vertical(0.0, np.pi / 2, 1.0, a1=1.0, a2=1.0)), 12)
    -1.0
    """
    q1, q2, y_rate = _array(q1, "q1"), _array(q2, "q2"), _array(y_rate, "y_rate")
    a1, a2 = _lengths(a1, a2)
    return (-a1 * np.sin(q1) - a2 * np.sin(q1 + q2)) / (a1 * a2 * np.sin(q2)) * y_rate


def q1_rate_horizontal(
    q1: ArrayLike, q2: ArrayLike, x_rate: ArrayLike, a1: float = A1, a2: float = A2
) -> NDArray[np.float64]:
    """``q1dot = a2 c12 / (a1 a2 s2) * xdot`` for a tip moving only horizontally (the source's, right).

    Parameters
    ----------
    q1, q2 : array_like
        Joint angles, radians.
    x_rate : float or array_like
        Horizontal tip velocity (length units per s).
    a1, a2 : float
        Link lengths (> 0).

    Returns
    -------
    numpy.ndarray
        ``q1dot`` in rad/s, the broadcast shape of the inputs.

    Examples
    --------
    >>> round(float(q1_rate_horizontal(0.0, np.pi / 2, 1.0, a1=1.0, a2=1.0)), 12)
    0.0
    """
    q1, q2, x_rate = _array(q1, "q1"), _array(q2, "q2"), _array(x_rate, "x_rate")
    a1, a2 = _lengths(a1, a2)
    return a2 * np.cos(q1 + q2) / (a1 * a2 * np.sin(q2)) * x_rate


def rate_as_printed(
    q_deg: ArrayLike, a1: float = A1, a2: float = A2
) -> NDArray[np.float64]:
    """The source's rate column: -10 times the vertical formula at the printed angles.

    The table was to give the joint rates for horizontal motion; its printed
    column equals ``RATE_FACTOR * (-a1 s1 - a2 s12) / (a1 a2 s2)``, the
    vertical-motion ``q2dot`` per unit ``ydot``, evaluated at the table's
    printed angles: the (wrong) angles of :func:`ik_as_written`, rounded as
    printed (:data:`PRINTED_ANGLES_DEG`), converted to radians.  That gives
    the printed column to within 0.16 % in every row (0.6132 at ``x = 10``).
    At the unrounded angles the column would be up to 1.24 % off the printed
    one (0.6066 at ``x = 10``): the source computed its rates from its
    rounded table.

    Parameters
    ----------
    q_deg : array_like, shape (..., 2)
        The table's angles ``(q1, q2)``, degrees.
    a1, a2 : float
        Link lengths (> 0).

    Returns
    -------
    numpy.ndarray, shape (...)
        The column as the source computed it (rad/s per the unstated
        velocity); at the printed angles, the printed column to within 0.16 %.

    Examples
    --------
    At the printed angles (the source record finds these within 0.16 % of the
    printed column, 0.6132 at ``x = 10`` as printed):

    >>> rate_as_printed(PRINTED_ANGLES_DEG).round(4)
    array([0.6132, 0.3781, 0.2734, 0.1884, 0.1957, 0.2007, 0.1364, 0.2022,
           0.1594, 0.0883])

    At the unrounded angles (up to 1.24 % off the printed column; 0.6066 at
    ``x = 10``):

    >>> rate_as_printed(ik_as_written(X_LINE)).round(4)
    array([0.6066, 0.3734, 0.2697, 0.1881, 0.1954, 0.2007, 0.1358, 0.2022,
           0.1596, 0.088 ])
    """
    q = np.radians(_array(q_deg, "q_deg"))
    if q.shape[-1:] != (2,):
        raise ValueError(f"q_deg must have shape (..., 2); got shape {q.shape}")
    return q2_rate_vertical(q[..., 0], q[..., 1], RATE_FACTOR, a1, a2)
