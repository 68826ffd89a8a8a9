"""Angle conventions: relative (DH) joint angles and absolute link angles.

The package works in the DH / relative convention: ``q2`` is link 2 measured
from link 1.  One source measures both links from the x-axis (``q2_abs = q1 +
q2``), as for a belt or parallel drive with motor 2 on the ground.

It also holds the package's one vocabulary for the elbow branch,
:data:`ELBOW_WORDS`, which every ``elbow`` parameter (in ``ik``,
``trajectory``, ``workspace``) reads through :func:`check_elbow`.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._validate import as_pairs, real_array

__all__ = ["to_absolute", "to_relative", "wrap_angle", "ELBOW_WORDS"]

#: The words of every ``elbow`` parameter, with one meaning everywhere:
#:
#: - ``"down"``: the branch with ``q2 >= 0`` (the elbow below the line from the
#:   base to the tip when the tip is to the right of the base);
#: - ``"up"``: the branch with ``q2 <= 0``;
#: - ``"both"``: both branches, stacked on a new first axis, ``"down"`` first;
#: - ``"auto"``: the function chooses a branch (each says how: within the joint
#:   limits, continuous along a path, or either branch for a reachability test).
#:
#: A function that cannot give one of them a meaning refuses it with a
#: ``ValueError`` that says why and which words it accepts.
ELBOW_WORDS: tuple[str, ...] = ("down", "up", "both", "auto")


def check_elbow(
    elbow: object, accepted: tuple[str, ...] = ELBOW_WORDS, why: str = ""
) -> str:
    """Return ``elbow`` when it is one of ``accepted`` (a subset of :data:`ELBOW_WORDS`).

    Parameters
    ----------
    elbow : object
        The caller's ``elbow`` argument.
    accepted : tuple of str
        The words this function gives a meaning to.
    why : str, optional
        Why a word of :data:`ELBOW_WORDS` outside ``accepted`` has no meaning
        here; added to the error.

    Returns
    -------
    str
        ``elbow`` itself.

    Raises
    ------
    ValueError
        Naming the accepted words (and ``why``, for a known but refused word).

    Examples
    --------
    >>> check_elbow("up")
    'up'
    >>> check_elbow("both", ("down", "up", "auto"), why="a path follows one branch")
    Traceback (most recent call last):
    ...
    ValueError: elbow must be one of ('down', 'up', 'auto') here; got 'both' (a path follows one branch)
    >>> check_elbow("elbow-up")
    Traceback (most recent call last):
    ...
    ValueError: elbow must be one of ('down', 'up', 'both', 'auto'); got 'elbow-up'
    """
    if isinstance(elbow, str) and elbow in accepted:
        return elbow
    if isinstance(elbow, str) and elbow in ELBOW_WORDS:
        reason = f" ({why})" if why else ""
        raise ValueError(f"elbow must be one of {accepted} here; got {elbow!r}{reason}")
    raise ValueError(f"elbow must be one of {accepted}; got {elbow!r}")


def to_absolute(q: ArrayLike) -> NDArray[np.float64]:
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
    q_rel = as_pairs(q, "q")
    q_abs = q_rel.copy()
    q_abs[..., 1] += q_rel[..., 0]
    return q_abs


def to_relative(q_abs: ArrayLike) -> NDArray[np.float64]:
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
    absolute = as_pairs(q_abs, "q_abs")
    q = absolute.copy()
    q[..., 1] -= absolute[..., 0]
    return q


#: Angles up to this size (4 turns) are wrapped by the remainder after dividing by the float
#: ``2 pi``, within 1e-15 rad of the exact reduction; larger ones by ``atan2(sin, cos)``, whose
#: ``sin`` and ``cos`` reduce the angle exactly (the remainder would be off by up to
#: ``4e-17 |angle|``: 4 rad at 1e17 rad).
_REMAINDER_WRAP = 8.0 * np.pi


def wrap_angle(angle: ArrayLike) -> NDArray[np.float64] | np.float64:
    """Wrap angles to the interval ``[-pi, pi)``, reducing large ones exactly.

    The wrapped angle has the same cosine and sine as the angle, to
    round-off, however large the angle: beyond a few turns it is
    ``atan2(sin a, cos a)``, whose ``sin`` and ``cos`` reduce ``a``
    exactly (the remainder after dividing by the float ``2 pi`` drifts by
    ``4e-17`` of the angle, 4 rad at 1e17 rad).

    Parameters
    ----------
    angle : array_like
        Angles in radians, any shape; finite.

    Returns
    -------
    numpy.ndarray or numpy.float64
        The wrapped angles, same shape as ``angle`` (a numpy float for a
        number).

    Examples
    --------
    >>> float(wrap_angle(3 * np.pi / 2) / np.pi)
    -0.5
    >>> float(wrap_angle(np.nextafter(-np.pi, -4.0)))  # not pi: the interval is half open
    -3.141592653589793
    >>> bool(abs(np.cos(wrap_angle(1e17)) - np.cos(1e17)) < 1e-15)
    True
    """
    angles = real_array(angle, "angle (rad)")
    if not np.all(np.isfinite(angles)):
        raise ValueError(
            "angle must be finite (radians); NaN or infinity has no wrapped value"
        )
    large = np.abs(angles) > _REMAINDER_WRAP
    if np.any(
        large
    ):  # reduced exactly first, then wrapped as any angle (so wrapping twice changes nothing)
        angles = np.where(large, np.arctan2(np.sin(angles), np.cos(angles)), angles)
    wrapped = (angles + np.pi) % (2.0 * np.pi) - np.pi
    # just below -pi the remainder of a tiny negative number rounds up to a whole turn
    return wrapped - 2.0 * np.pi * (wrapped >= np.pi)
