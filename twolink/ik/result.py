"""The result object shared by every inverse-kinematics solver.

A solver hands :func:`assemble_result` what it found (the joint angles) and
how to judge it (the targets, a residual threshold, words for the message);
the :class:`IKResult` computes ``residual``, ``success``, ``within_limits``,
``iterations`` and ``message`` from those on first access, by forward
kinematics, and keeps them.  Building one costs a few hundred nanoseconds, so
one call of :func:`twolink.ik.closed_form` on one target stays cheap; the
checks are paid for only when read.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, NamedTuple, NoReturn

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._validate import as_pairs
from ..kinematics import fk

if TYPE_CHECKING:
    from ..arm import TwoLinkArm

__all__ = ["IKResult", "FailureDetail", "Judging", "assemble_result", "result_judged_by"]

#: ``failure_detail(flat_index, residual)``: a phrase on why the answer at
#: ``flat_index`` (of the flattened answers) failed, given its residual (m).
FailureDetail = Callable[[int, float], str]


class Judging(NamedTuple):
    """How a solver's answers are judged and described (everything of a result but the arm, targets and ``q``).

    A solver that answers many calls the same way (the closed form) keeps
    one per arm and branch, so building its result costs no more than a few
    attribute stores.
    """

    #: One count for all answers, or one per answer (flat or in the answers' shape).
    iterations: ArrayLike
    #: Success where the residual is at most this, metres: one value, or one per answer.
    threshold: ArrayLike
    #: Which solver produced the result.
    method: str
    #: The message when every answer succeeds.
    solved_message: str
    #: Describes the first failed answer for the message (None: its residual only).
    failure_detail: FailureDetail | None = None


# the lazily computed fields, in this order: success, iterations, residual, within_limits, message
_Fields = tuple[NDArray[np.bool_], NDArray[np.int_], NDArray[np.float64], NDArray[np.bool_], str]


class IKResult:
    """What an IK solver found, and whether to trust it.

    Modelled on the Robotics Toolbox's ``IKSolution``: always check
    ``success`` before using ``q``.  For a batch of targets every field has the
    batch's leading shape; for ``ik.closed_form(..., elbow="both")`` every
    field has a further leading axis of 2 (the down branch first).

    The solvers build it; ``residual``, ``success``, ``within_limits``,
    ``iterations`` and ``message`` are computed from the arm, the targets and
    ``q`` when first read (then kept), so a result whose ``q`` alone is used
    costs no forward kinematics.  The result is immutable (its fields are
    read-only properties, and it takes no new attributes); ``q`` is the
    result's own array: change a copy of it, not it, or the fields read
    afterwards describe the changed angles.

    Attributes
    ----------
    q : numpy.ndarray, shape (..., 2)
        Joint angles in radians (the best found, even when ``success`` is false).
    success : numpy.ndarray of bool, shape (...)
        True where the residual is within the solver's threshold.
    iterations : numpy.ndarray of int, shape (...)
        Iterations (or function evaluations, or grid points) spent per target;
        0 for the closed form.
    residual : numpy.ndarray, shape (...)
        ``|fk(q) - p|`` in metres, always recomputed from ``q`` by forward
        kinematics, never taken from the solver's own bookkeeping.
    method : str
        Which solver produced this result.
    message : str
        A sentence on the outcome: why it failed, where.
    within_limits : numpy.ndarray of bool, shape (...)
        Whether each ``q`` respects the arm's joint limits (all true for an
        arm without limits; ``arm.within_limits(q)``).
        :func:`twolink.ik.newton`, the unconstrained :func:`twolink.ik.minimize`
        and :func:`twolink.ik.closed_form` on a named branch ignore the
        limits: check this field.
    all_success : bool
        True when every target in the batch was solved.

    Parameters
    ----------
    arm : TwoLinkArm
    p : array_like, shape (..., 2)
        The targets, metres.
    q : array_like, shape (..., 2) or (k, ..., 2)
        The answers: one per target, or ``k`` per target stacked on a
        leading axis (the two branches of the closed form).
    iterations : int or array_like of int
        One count for all answers, or one per answer (any shape with one
        entry per answer, e.g. flat).
    threshold : float or array_like
        Success where the residual is at most this, metres: one value, or
        one per answer (flat or in the answers' shape).
    method : str
    solved_message : str
        The message when every answer succeeds.
    failure_detail : callable, optional
        ``failure_detail(flat_index, residual)`` describes the first failure
        for the message.

    Examples
    --------
    >>> from twolink import arms, ik
    >>> result = ik.newton(arms.ten, [10.0, 10.0], q0=[0.5, 1.0])
    >>> bool(result.success), result.method
    (True, 'newton')
    >>> bool(result.residual < 1e-9)
    True
    >>> result.q = [0.0, 0.0]
    Traceback (most recent call last):
    ...
    AttributeError: property 'q' of 'IKResult' object has no setter

    Built by hand (the fields come from forward kinematics):

    >>> made = ik.IKResult(arms.ten, [20.0, 0.0], [0.0, 0.0], iterations=0, threshold=1e-9,
    ...                    method="by hand", solved_message="the arm stretched along x")
    >>> made
    IKResult(method='by hand', q=array([0., 0.]), success=True, residual=0, within_limits=True, iterations=0,
             message='the arm stretched along x')
    >>> ik.closed_form(arms.ten, [[12.0, 4.0], [10.0, 10.0]], elbow="both")
    IKResult(method='closed-form', q of shape (2, 2, 2), success 4 of 4, max residual 1.78e-15, within_limits 2 of 4,
             max iterations 0, message='solved 2 targets in closed form (both branches); 2 of 4 answers violate the joint limits (see within_limits)')
    """

    # _inputs: (arm, p, q, judging), set when built (a tuple: the cheapest to make and free);
    # _fields: the computed fields, set on first read
    __slots__ = ("_inputs", "_fields")

    _inputs: tuple[Any, Any, NDArray[np.float64], Judging]
    _fields: _Fields

    def __init__(
        self,
        arm: TwoLinkArm,
        p: ArrayLike,
        q: ArrayLike,
        *,
        iterations: ArrayLike,
        threshold: ArrayLike,
        method: str,
        solved_message: str,
        failure_detail: FailureDetail | None = None,
    ) -> None:
        p = np.array(as_pairs(p, "target p"))  # a copy: the caller's array may change
        q = np.array(as_pairs(q, "q"))
        if q.shape[q.ndim - p.ndim :] != p.shape:
            raise ValueError(f"q of shape {q.shape} does not hold one answer per target p of shape {p.shape}")
        self._inputs = (arm, p, q, Judging(iterations, threshold, str(method), str(solved_message), failure_detail))

    # ------------------------------------------------------------------ fields
    @property
    def q(self) -> NDArray[np.float64]:
        """Joint angles in radians, shape ``(..., 2)``."""
        return self._inputs[2]

    @property
    def method(self) -> str:
        """Which solver produced this result."""
        return self._inputs[3].method

    @property
    def success(self) -> NDArray[np.bool_]:
        """True where the recomputed residual is within the solver's threshold."""
        return self._evaluated()[0]

    @property
    def iterations(self) -> NDArray[np.int_]:
        """Iterations (function evaluations, grid points) spent per target."""
        return self._evaluated()[1]

    @property
    def residual(self) -> NDArray[np.float64]:
        """``|fk(q) - p|`` in metres, recomputed from ``q`` by forward kinematics."""
        return self._evaluated()[2]

    @property
    def within_limits(self) -> NDArray[np.bool_]:
        """Whether each ``q`` respects the arm's joint limits."""
        return self._evaluated()[3]

    @property
    def message(self) -> str:
        """A sentence on the outcome: why it failed, where."""
        return self._evaluated()[4]

    @property
    def all_success(self) -> bool:
        """True when every target in the batch was solved."""
        return bool(np.all(self._evaluated()[0]))

    def _evaluated(self) -> _Fields:
        try:
            return self._fields
        except AttributeError:  # the first read
            arm, p, q, judging = self._inputs
            fields = _one_answer_fields(arm, p, q, judging) if q.shape == (2,) else _fields(arm, p, q, judging)
            self._fields = fields
            return fields

    # ------------------------------------------------------------------ not an array, repr, pickling
    def __array__(self, *args: object, **kwargs: object) -> NoReturn:
        raise TypeError(
            "an IKResult is not an array of joint angles: use its .q (and check .success), "
            f"e.g. ik.closed_form(arm, p).q; this result came from {self.method!r}"
        )

    def __reduce__(self) -> tuple[Callable[..., IKResult], tuple[Any, ...]]:
        # the inputs hold the solver's message callback (often a closure): keep the computed fields instead
        return (_restored, (self.q, self.method, self._evaluated()))

    def __repr__(self) -> str:
        success, iterations, residual, within, message = self._evaluated()
        if success.ndim == 0:  # one answer: its values
            with np.printoptions(precision=6):
                return (
                    f"IKResult(method={self.method!r}, q={self.q!r}, success={bool(success)}, "
                    f"residual={float(residual):.3g}, within_limits={bool(within)}, iterations={int(iterations)},\n"
                    f"         message={message!r})"
                )
        count = success.size  # a batch: shapes and a summary
        largest = f"{residual.max():.3g}" if count else "-"
        return (
            f"IKResult(method={self.method!r}, q of shape {self.q.shape}, success {int(np.count_nonzero(success))} "
            f"of {count}, max residual {largest}, within_limits {int(np.count_nonzero(within))} of {count}, "
            f"max iterations {int(iterations.max(initial=0))},\n         message={message!r})"
        )


def _flat(values: ArrayLike, size: int, name: str, kind: type) -> NDArray[Any]:
    """``values`` (one, or one per answer in any shape) as a flat array of ``size`` entries."""
    array: NDArray[Any] = np.asarray(values, dtype=kind)
    if array.ndim == 0:
        return np.full(size, array)
    if array.size != size:
        raise ValueError(f"{name} must be one value or one per answer ({size}); got shape {array.shape}")
    return array.reshape(size)


def _fields(arm: TwoLinkArm, p: Any, q: NDArray[np.float64], judging: Judging) -> _Fields:
    """success, iterations, residual, within_limits and message of answers ``q`` to targets ``p``."""
    iterations, threshold, _, solved_message, failure_detail = judging
    shape = q.shape[:-1]
    q_flat = q.reshape(-1, 2)
    tips = fk(arm, q_flat)
    tips -= np.broadcast_to(p, q.shape).reshape(-1, 2)
    residual = np.hypot(tips[:, 0], tips[:, 1])
    success = residual <= _flat(threshold, residual.size, "threshold", float)
    within = np.asarray(arm.within_limits(q_flat), dtype=bool).reshape(-1)
    failures = int(np.count_nonzero(~success))
    if failures:
        first = int(np.flatnonzero(~success)[0])
        what = "targets" if q.ndim == np.ndim(p) else "answers"
        detail = (
            failure_detail(first, float(residual[first]))
            if failure_detail is not None
            else f"residual {residual[first]:.3g} m"
        )
        message = f"failed for {failures} of {success.size} {what} (first: flat index {first}, {detail})"
    else:
        message = solved_message
    if arm.has_limits and not np.all(within):
        outside = int(np.count_nonzero(~within))
        message += f"; {outside} of {within.size} answers violate the joint limits (see within_limits)"
    return (
        success.reshape(shape),
        _flat(iterations, residual.size, "iterations", int).reshape(shape),
        residual.reshape(shape),
        within.reshape(shape),
        message,
    )


def _one_answer_fields(arm: TwoLinkArm, p: Any, q: NDArray[np.float64], judging: Judging) -> _Fields:
    """:func:`_fields` for one answer ``q`` of shape ``(2,)``, on floats: the same values, types and message.

    The residual takes the expressions of :func:`twolink.kinematics.fk` in
    the same order (the tests hold the two to 1e-12).
    """
    iterations, threshold, _, solved_message, failure_detail = judging
    q1, q2 = q.tolist()
    x, y = p if type(p) is tuple else p.tolist()
    l1, l2 = arm.l1, arm.l2
    q12 = q1 + q2
    residual = math.hypot(l1 * math.cos(q1) + l2 * math.cos(q12) - x, l1 * math.sin(q1) + l2 * math.sin(q12) - y)
    # one threshold (or one of one)
    success = residual <= (threshold if type(threshold) is float else float(np.asarray(threshold).reshape(())))
    if success:
        message = solved_message
    else:
        detail = failure_detail(0, residual) if failure_detail is not None else f"residual {residual:.3g} m"
        message = f"failed for 1 of 1 targets (first: flat index 0, {detail})"
    within = bool(arm.within_limits((q1, q2))) if arm.has_limits else True
    if not within:
        message += "; 1 of 1 answers violate the joint limits (see within_limits)"
    return (
        np.array(success),
        np.array(iterations) if type(iterations) is int else np.asarray(iterations, dtype=int).reshape(()),
        np.array(residual),
        np.array(within),
        message,
    )


def _restored(q: NDArray[np.float64], method: str, fields: _Fields) -> IKResult:
    result = _new(IKResult)
    result._inputs = (None, None, q, Judging(0, 0.0, method, fields[4]))  # the fields are known: no arm, no p
    result._fields = fields
    return result


_new = object.__new__


def result_judged_by(arm: TwoLinkArm, p: Any, q: NDArray[np.float64], judging: Judging) -> IKResult:
    """An :class:`IKResult`, built without checks or copies: what every solver returns.

    Every solver ends here, so success is always judged the same way: the FK
    distance from ``fk(q)`` to the target (computed on first access), never
    the solver's own claim.

    Parameters
    ----------
    arm : TwoLinkArm
    p : numpy.ndarray, shape (..., 2), or a pair of floats
        The targets, owned by the result from now on (a copy, or a tuple):
        the solver must not hand over an array its caller can change.
    q : numpy.ndarray, shape (..., 2) or (k, ..., 2)
        The answers, in the result's shape (owned by the result).
    judging : Judging
        How the answers are judged and described.
    """
    result = _new(IKResult)
    result._inputs = (arm, p, q, judging)
    return result


def assemble_result(
    arm: TwoLinkArm,
    p: Any,
    q: NDArray[np.float64],
    iterations: ArrayLike,
    threshold: ArrayLike,
    method: str,
    solved_message: str,
    failure_detail: FailureDetail | None = None,
) -> IKResult:
    """:func:`result_judged_by` with the :class:`Judging` given field by field.

    Parameters
    ----------
    arm : TwoLinkArm
    p : numpy.ndarray, shape (..., 2), or a pair of floats
        The targets, owned by the result (see :func:`result_judged_by`).
    q : numpy.ndarray, shape (..., 2) or (k, ..., 2)
        The answers, in the result's shape.
    iterations : int or numpy.ndarray of int
        One count, or one per answer (flat or in the answers' shape).
    threshold : float or numpy.ndarray
        Success where the residual is at most this (metres): one value, or
        one per answer (flat or in the answers' shape).
    method : str
    solved_message : str
        The message when every answer succeeds.
    failure_detail : callable, optional
        ``failure_detail(flat_index, residual)`` describes the first failed
        answer for the message.
    """
    result = _new(IKResult)
    result._inputs = (arm, p, q, Judging(iterations, threshold, method, solved_message, failure_detail))
    return result
