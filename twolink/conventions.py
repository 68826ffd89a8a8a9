"""Angle conventions: relative (DH) joint angles and absolute link angles.

The package works in the DH / relative convention: ``q2`` is link 2 measured
from link 1.  One source measures both links from the x-axis (``q2_abs = q1 +
q2``), as for a belt or parallel drive with motor 2 on the ground.
"""

import numpy as np

from ._validate import as_pairs, real_array

__all__ = ["to_absolute", "to_relative", "wrap_angle"]


def to_absolute(q):
    """Relative joint angles ``(q1, q2)`` to absolute link angles ``(q1, q1 + q2)``.

    Parameters
    ----------
    q : array_like, shape (..., 2)
        Relative (DH) joint angles in radians.

    Returns
    -------
    numpy.ndarray, shape (..., 2)
        Angles of link 1 and link 2 from the x-axis, in radians (not wrapped).

    Examples
    --------
    >>> to_absolute([np.pi / 4, np.pi / 2]) / np.pi
    array([0.25, 0.75])
    """
    q = as_pairs(q, "q")
    q_abs = q.copy()
    q_abs[..., 1] += q[..., 0]
    return q_abs


def to_relative(q_abs):
    """Absolute link angles ``(q1, q2_abs)`` to relative joint angles ``(q1, q2_abs - q1)``.

    Parameters
    ----------
    q_abs : array_like, shape (..., 2)
        Angles of link 1 and link 2 from the x-axis, in radians.

    Returns
    -------
    numpy.ndarray, shape (..., 2)
        Relative (DH) joint angles in radians (not wrapped).

    Examples
    --------
    >>> to_relative([np.pi / 4, 3 * np.pi / 4]) / np.pi
    array([0.25, 0.5 ])
    """
    q_abs = as_pairs(q_abs, "q_abs")
    q = q_abs.copy()
    q[..., 1] -= q_abs[..., 0]
    return q


def wrap_angle(angle):
    """Wrap angles to the interval ``[-pi, pi)``.

    Examples
    --------
    >>> float(wrap_angle(3 * np.pi / 2) / np.pi)
    -0.5
    """
    angle = real_array(angle, "angle (rad)")
    if not np.all(np.isfinite(angle)):
        raise ValueError("angle must be finite (radians); NaN or infinity has no wrapped value")
    return (angle + np.pi) % (2.0 * np.pi) - np.pi
