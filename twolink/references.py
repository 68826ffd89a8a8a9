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
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._validate import as_configuration, as_pairs, as_time, real_array
from ._values import Value, freeze

#: A function of time giving a pair (radians, rad/s or rad/s^2).
TimeFunction = Callable[[float], ArrayLike]

__all__ = ["JointReference"]


def _pair_function(function: object, name: str) -> TimeFunction:
    if not callable(function):
        raise ValueError(
            f"{name} must be a callable of time t -> array of shape (2,); got {function!r}"
        )
    return function


@dataclass(frozen=True, eq=False)
class JointReference(Value):
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
        t = as_time(t)
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
        return cls(_Held(held), _Held(np.zeros(2)), _Held(np.zeros(2)))

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
        times, samples = _samples(t, q, "q samples")
        if qd is None:
            if len(times) < 4:
                raise ValueError(
                    "a not-a-knot spline needs at least 4 samples; give more, or the end rates qd"
                )
            rates = None
        else:
            rates = _like(qd, "qd", samples.shape)
        return cls(
            *(
                _Interpolant("cubic spline", times, samples, rates, None, k)
                for k in range(3)
            )
        )

    @classmethod
    def from_derivatives(
        cls, t: ArrayLike, q: ArrayLike, qd: ArrayLike, qdd: ArrayLike
    ) -> JointReference:
        """The piecewise quintic through samples of ``q``, ``qd`` and ``qdd``, matching all three at every sample.

        On each interval the one quintic with the samples' angles, rates and
        accelerations at both ends (scipy's
        :meth:`scipy.interpolate.BPoly.from_derivatives`): continuous rate
        and acceleration, no fit.  Outside ``[t[0], t[-1]]`` it holds the end
        positions at rest.

        Parameters
        ----------
        t : array_like, shape (n,)
            Strictly increasing times, seconds (n >= 2).
        q, qd, qdd : array_like, shape (n, 2)
            Joint angles (rad), rates (rad/s) and accelerations (rad/s^2).

        Examples
        --------
        >>> t = np.array([0.0, 1.0])
        >>> reference = JointReference.from_derivatives(t, [[0.0, 0.0], [1.0, 2.0]], np.zeros((2, 2)), np.zeros((2, 2)))
        >>> [value.round(12) + 0.0 for value in reference(0.5)]
        [array([0.5, 1. ]), array([1.875, 3.75 ]), array([0., 0.])]
        """
        times, samples = _samples(t, q, "q samples")
        rates, accelerations = (
            _like(values, name, samples.shape)
            for values, name in ((qd, "qd"), (qdd, "qdd"))
        )
        return cls(
            *(
                _Interpolant("quintic Hermite", times, samples, rates, accelerations, k)
                for k in range(3)
            )
        )


def _samples(
    t: ArrayLike, q: ArrayLike, name: str
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Checked sample times ``(n,)`` and configurations ``(n, 2)`` of a reference."""
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
    samples = as_pairs(q, name)
    if samples.shape != (len(times), 2):
        raise ValueError(
            f"q must have shape ({len(times)}, 2), one configuration per time; got {samples.shape}"
        )
    return times, samples


def _like(values: ArrayLike, name: str, shape: tuple[int, ...]) -> NDArray[np.float64]:
    """``values`` (samples of a derivative) as pairs of the samples' ``shape``, or an error naming ``name``."""
    pairs = as_pairs(values, f"{name} samples")
    if pairs.shape != shape:
        raise ValueError(f"{name} must have the shape of q, {shape}; got {pairs.shape}")
    return pairs


@dataclass(frozen=True, eq=False)
class _Held(Value):
    """``t -> value`` for every time (a constant reference's functions)."""

    value: NDArray[np.float64]

    def __post_init__(self) -> None:
        freeze(self)

    def __call__(self, t: float) -> NDArray[np.float64]:
        return self.value


@dataclass(frozen=True, eq=False)
class _Interpolant(Value):
    """The ``derivative``-th derivative of a piecewise polynomial through samples (a reference's function).

    ``"cubic spline"`` through ``q`` (end rates clamped to ``qd``'s first and
    last rows when given, else not-a-knot), or ``"quintic Hermite"`` through
    ``q``, ``qd`` and ``qdd``.  Outside ``[t[0], t[-1]]`` the position is
    held at its end and the derivatives are zero (for the spline also at
    ``t[0]`` and ``t[-1]`` themselves).  A value built from its samples:
    equal to another built from the same, and picklable.
    """

    kind: str
    t: NDArray[np.float64]
    q: NDArray[np.float64]
    qd: NDArray[np.float64] | None
    qdd: NDArray[np.float64] | None
    derivative: int
    polynomial: Any = field(default=None, compare=False, repr=False)

    def __post_init__(self) -> None:
        freeze(self)
        # here, not at the top: import twolink stays light
        from scipy.interpolate import BPoly, CubicSpline

        if self.qd is not None and self.qdd is not None:  # the quintic Hermite
            polynomial = BPoly.from_derivatives(
                self.t, np.stack([self.q, self.qd, self.qdd], axis=1)
            )
        elif self.qd is None:
            polynomial = CubicSpline(self.t, self.q, axis=0)
        else:
            polynomial = CubicSpline(
                self.t,
                self.q,
                axis=0,
                bc_type=((1, self.qd[0]), (1, self.qd[-1])),
            )
        if self.derivative:
            polynomial = polynomial.derivative(self.derivative)
        object.__setattr__(self, "polynomial", polynomial)

    def __call__(self, time: float) -> NDArray[np.float64]:
        start, end = self.t[0], self.t[-1]
        if self.derivative == 0:
            if time <= start:
                return self.q[0].copy()
            if time >= end:
                return self.q[-1].copy()
        elif not (
            start <= time <= end
            if self.kind == "quintic Hermite"
            else start < time < end
        ):
            return np.zeros(2)
        return np.asarray(self.polynomial(time), dtype=float)


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
