"""Joint references: ``q_ref(t)`` with its rate and acceleration, for controllers to follow.

A :class:`JointReference` is data about time, not a control law: trajectories
(:mod:`twolink.trajectory`) produce one and controllers
(:mod:`twolink.controllers`) follow one, so it lives below both.

Examples
--------
>>> import numpy as np
>>> hold = JointReference.constant([0.5, 1.0])
>>> [value.tolist() for value in hold(2.0)]
[[0.5, 1.0], [0.0, 0.0], [0.0, 0.0]]
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._validate import as_configuration, as_pairs, real_array

#: A function of time giving a pair (radians, rad/s or rad/s^2).
TimeFunction = Callable[[float], ArrayLike]

__all__ = ["JointReference", "TimeFunction"]


def _pair_function(function: object, name: str) -> TimeFunction:
    if not callable(function):
        raise ValueError(
            f"{name} must be a callable of time t -> array of shape (2,); got {function!r}"
        )
    return function


@dataclass(frozen=True, eq=False)
class JointReference:
    """A joint-space reference ``q_ref(t)`` with its rate and acceleration.

    Build one from three callables of time (each ``t -> array (2,)``), from
    a constant configuration (:meth:`constant`) or from samples
    (:meth:`from_samples`, a cubic spline).  Calling it gives
    ``(q_ref, qd_ref, qdd_ref)`` at a time.

    Parameters
    ----------
    position, velocity, acceleration : callable
        ``t -> array (2,)``: radians, rad/s and rad/s^2.

    Examples
    --------
    >>> wave = JointReference(lambda t: np.array([np.sin(t), 0.0]),
    ...                       lambda t: np.array([np.cos(t), 0.0]),
    ...                       lambda t: np.array([-np.sin(t), 0.0]))
    >>> [value.round(6) for value in wave(0.0)]
    [array([0., 0.]), array([1., 0.]), array([-0., 0.])]
    """

    position: TimeFunction
    velocity: TimeFunction
    acceleration: TimeFunction

    def __post_init__(self) -> None:
        for name in ("position", "velocity", "acceleration"):
            _pair_function(getattr(self, name), name)

    def __call__(
        self, t: float
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        """``(q_ref, qd_ref, qdd_ref)`` at time ``t``, each an array of shape (2,).

        Raises
        ------
        ValueError
            When one of the three functions does not return two numbers.
        """
        return (
            _reference_pair(self.position(t), "position", "rad", t),
            _reference_pair(self.velocity(t), "velocity", "rad/s", t),
            _reference_pair(self.acceleration(t), "acceleration", "rad/s^2", t),
        )

    @classmethod
    def constant(cls, q_ref: ArrayLike) -> JointReference:
        """Hold ``q_ref`` (radians, shape (2,)) for ever: zero rate and acceleration.

        Examples
        --------
        >>> JointReference.constant([0.5, 1.0])(3.0)[0]
        array([0.5, 1. ])
        """
        held = as_configuration(q_ref, "q_ref").copy()
        held.setflags(write=False)
        zeros = np.zeros(2)
        zeros.setflags(write=False)
        return cls(lambda t: held, lambda t: zeros, lambda t: zeros)

    @classmethod
    def from_samples(
        cls, t: ArrayLike, q: ArrayLike, qd: ArrayLike | None = None
    ) -> JointReference:
        """A cubic-spline reference through samples ``q`` at times ``t``.

        The spline has continuous rate and acceleration (what a controller
        with an ODE solver needs).  With ``qd`` given, its end rates are
        clamped to ``qd[0]`` and ``qd[-1]``; otherwise "not-a-knot" ends.
        Outside ``[t[0], t[-1]]`` the reference holds its end positions with
        zero rate and acceleration.

        Parameters
        ----------
        t : array_like, shape (n,)
            Strictly increasing times, seconds (n >= 2; n >= 4 without ``qd``).
        q : array_like, shape (n, 2)
            Joint angles, radians (continuous: no 2 pi jumps).
        qd : array_like, shape (n, 2), optional
            Joint rates, rad/s (only the first and last rows are used).

        Examples
        --------
        >>> t = np.linspace(0.0, 1.0, 11)
        >>> q = np.column_stack([t**2, -t])
        >>> reference = JointReference.from_samples(t, q)
        >>> [value.round(9) + 0.0 for value in reference(0.5)]
        [array([ 0.25, -0.5 ]), array([ 1., -1.]), array([2., 0.])]
        >>> reference(2.0)[0], reference(2.0)[1]
        (array([ 1., -1.]), array([0., 0.]))
        """
        times = real_array(t, "t (s)")
        if (
            times.ndim != 1
            or len(times) < 2
            or not np.all(np.isfinite(times))
            or not np.all(np.diff(times) > 0)
        ):
            raise ValueError(
                "t must be a 1-D array of at least 2 finite, strictly increasing times (s)"
            )
        samples = as_pairs(q, "q samples")
        if samples.shape != (len(times), 2):
            raise ValueError(
                f"q must have shape ({len(times)}, 2), one configuration per time; got {samples.shape}"
            )
        # here, not at the top: import twolink stays light
        from scipy.interpolate import CubicSpline

        if qd is None:
            if len(times) < 4:
                raise ValueError(
                    "a not-a-knot spline needs at least 4 samples; give more, or the end rates qd"
                )
            spline = CubicSpline(times, samples, axis=0)
        else:
            rates = as_pairs(qd, "qd samples")
            if rates.shape != samples.shape:
                raise ValueError(
                    f"qd must have the shape of q, {samples.shape}; got {rates.shape}"
                )
            spline = CubicSpline(
                times, samples, axis=0, bc_type=((1, rates[0]), (1, rates[-1]))
            )
        rate, acceleration = spline.derivative(1), spline.derivative(2)
        start, end = float(times[0]), float(times[-1])
        q_start, q_end = samples[0].copy(), samples[-1].copy()

        def position(time: float) -> NDArray[np.float64]:
            if time <= start:
                return q_start
            if time >= end:
                return q_end
            return spline(time)

        def inside(derivative: Any) -> TimeFunction:
            def evaluate(time: float) -> NDArray[np.float64]:
                return derivative(time) if start < time < end else np.zeros(2)

            return evaluate

        return cls(position, inside(rate), inside(acceleration))


def _reference_pair(
    value: object, name: str, unit: str, t: float
) -> NDArray[np.float64]:
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        array = np.empty(0)
    if array.shape != (2,):
        raise ValueError(
            f"the reference's {name}(t) must return two numbers ({unit}), shape (2,); got {value!r} at t = {t}"
        )
    return array
