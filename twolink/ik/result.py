"""The result every inverse-kinematics solver returns, and the one function that builds it.

A solver hands :func:`assemble_result` what it found (the joint angles) and
how to judge it (the targets, a residual threshold, words for the message);
:func:`assemble_result` judges the answers by forward kinematics there and
then, and returns an :class:`IKResult` holding the outcome: a frozen
dataclass of plain values, nothing computed later.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, NoReturn

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._values import Value
from ..kinematics import LARGE_ANGLE, fk, reduced_pair, tip_from_trig

if TYPE_CHECKING:
    from ..arm import TwoLinkArm

__all__ = ["IKResult"]

#: ``failure_detail(flat_index, residual)``: a phrase on why the answer at
#: ``flat_index`` (of the flattened answers) failed, given its residual (m).
FailureDetail = Callable[[int, float], str]

_cos, _sin, _hypot, _empty = math.cos, math.sin, math.hypot, np.empty
_LARGE = LARGE_ANGLE


@dataclass(frozen=True, eq=False, repr=False, init=False)
class IKResult(Value):
    """What an IK solver found, and whether to trust it.

    Modelled on the Robotics Toolbox's ``IKSolution``: always check
    ``success`` before using ``q``.  A frozen dataclass of plain values: the
    solvers build it with :func:`assemble_result`, which judges the answers
    by forward kinematics when the result is built.

    For one target (``q`` of shape ``(2,)``) the fields are Python numbers:
    ``success`` and ``within_limits`` are ``bool``, ``residual`` a
    ``float``, ``iterations`` an ``int``.  For a batch of targets they are
    numpy arrays with the batch's leading shape; for
    ``ik.closed_form(..., elbow="both")`` every field has a further leading
    axis of 2 (the down branch first), so one target solved on both branches
    is a batch of two answers.

    Two results with the same fields are equal (``==``, arrays compared by
    their values), and a result pickles (to another process, for a
    parameter sweep).  ``q`` is the result's own array: change a copy of
    it, not it (the other fields describe the angles the solver returned).
    So a result has no hash (its arrays could change under it, and making
    them read-only would cost a one-target call a tenth of its time):
    ``hash(result)`` raises a ``TypeError`` that says so.

    Attributes
    ----------
    q : numpy.ndarray, shape (..., 2)
        Joint angles in radians (the best found, even when ``success`` is false).
    success : bool, or numpy.ndarray of bool, shape (...)
        True where the residual is within the solver's threshold.
    residual : float, or numpy.ndarray of float, shape (...)
        ``|fk(q) - p|`` in metres, always recomputed from ``q`` by forward
        kinematics, never taken from the solver's own bookkeeping (a batch
        of the closed form takes ``cos q2`` and ``sin q2`` from the unit
        vector its ``q2`` is the ``atan2`` of, which they equal to round-off).
    within_limits : bool, or numpy.ndarray of bool, shape (...)
        Whether each ``q`` respects the arm's joint limits (true for an
        arm without limits; ``arm.within_limits(q)``).
        :func:`twolink.ik.newton`, the unconstrained :func:`twolink.ik.minimize`
        and :func:`twolink.ik.closed_form` on a named branch ignore the
        limits: check this field.
    iterations : int, or numpy.ndarray of int, shape (...)
        Iterations (or function evaluations, or grid points) spent per target;
        0 for the closed form.
    method : str
        Which solver produced this result.
    message : str
        A sentence on the outcome: why it failed, where.

    Examples
    --------
    >>> from twolink import arms, ik
    >>> result = ik.newton(arms.ten, [10.0, 10.0], q0=[0.5, 1.0])
    >>> result.success, result.method, result.residual < 1e-9
    (True, 'newton', True)
    >>> result.q = [0.0, 0.0]
    Traceback (most recent call last):
    ...
    dataclasses.FrozenInstanceError: cannot assign to field 'q'

    Built by a solver (here by hand) with :func:`assemble_result`, which
    computes the fields by forward kinematics:

    >>> from twolink.ik.result import assemble_result
    >>> assemble_result(arms.ten, [20.0, 0.0], np.array([0.0, 0.0]), iterations=0, threshold=1e-9,
    ...                 method="by hand", solved_message="the arm stretched along x")
    IKResult(method='by hand', q=array([0., 0.]), success=True, residual=0, within_limits=True, iterations=0,
             message='the arm stretched along x')
    >>> ik.closed_form(arms.ten, [[12.0, 4.0], [10.0, 10.0]], elbow="both")
    IKResult(method='closed-form', q of shape (2, 2, 2), success 4 of 4, max residual 1.78e-15, within_limits 2 of 4,
             max iterations 0, message='solved 2 targets in closed form (both branches); 2 of 4 answers violate the joint limits (see within_limits)')
    """

    q: NDArray[np.float64]
    success: bool | NDArray[np.bool_]
    residual: float | NDArray[np.float64]
    within_limits: bool | NDArray[np.bool_]
    iterations: int | NDArray[np.int_]
    method: str
    message: str

    def __init__(
        self,
        q: NDArray[np.float64],
        success: bool | NDArray[np.bool_],
        residual: float | NDArray[np.float64],
        within_limits: bool | NDArray[np.bool_],
        iterations: int | NDArray[np.int_],
        method: str,
        message: str,
    ) -> None:
        # The __init__ dataclass would write: the same fields, stored straight into the instance's
        # dictionary rather than through one object.__setattr__ call each (a frozen dataclass's way,
        # which costs as much as the closed form itself).
        fields = self.__dict__
        fields["q"] = q
        fields["success"] = success
        fields["residual"] = residual
        fields["within_limits"] = within_limits
        fields["iterations"] = iterations
        fields["method"] = method
        fields["message"] = message

    @property
    def all_success(self) -> bool:
        """True when every target in the batch was solved."""
        return bool(np.all(self.success))

    def __array__(self, *args: object, **kwargs: object) -> NoReturn:
        raise TypeError(
            "an IKResult is not an array of joint angles: use its .q (and check .success), "
            f"e.g. ik.closed_form(arm, p).q; this result came from {self.method!r}"
        )

    _freezes_arrays = False

    def __hash__(self) -> int:
        raise TypeError(
            "an IKResult has no hash: its arrays (q, ...) can be changed in place; "
            "hash what you need from it, e.g. tuple(result.q)"
        )

    def __repr__(self) -> str:
        if self.q.shape == (2,):  # one answer: its values
            with np.printoptions(precision=6):
                return (
                    f"IKResult(method={self.method!r}, q={self.q!r}, success={self.success}, "
                    f"residual={self.residual:.3g}, within_limits={self.within_limits}, iterations={self.iterations},\n"
                    f"         message={self.message!r})"
                )
        success, residual, within = (
            np.asarray(self.success),
            np.asarray(self.residual),
            np.asarray(self.within_limits),
        )
        count = success.size  # a batch: shapes and a summary
        largest = f"{residual.max():.3g}" if count else "-"
        return (
            f"IKResult(method={self.method!r}, q of shape {self.q.shape}, success {int(np.count_nonzero(success))} "
            f"of {count}, max residual {largest}, within_limits {int(np.count_nonzero(within))} of {count}, "
            f"max iterations {int(np.max(self.iterations, initial=0))},\n         message={self.message!r})"
        )


def _flat(values: ArrayLike, size: int, name: str, kind: type) -> NDArray[Any]:
    """``values`` (one, or one per answer in any shape) as a flat array of ``size`` entries."""
    array: NDArray[Any] = np.asarray(values, dtype=kind)
    if array.ndim == 0:
        return np.full(size, array)
    if array.size != size:
        raise ValueError(
            f"{name} must be one value or one per answer ({size}); got shape {array.shape}"
        )
    return array.reshape(size)


def _one(value: ArrayLike, name: str, kind: type) -> Any:
    """``value`` (one number, or an array holding one) as a Python ``kind``."""
    if type(value) is kind:
        return value
    array = np.asarray(value)
    if array.size != 1:
        raise ValueError(
            f"{name} must be one value or one per answer (1); got shape {array.shape}"
        )
    return kind(array.reshape(()))


def _failure_message(
    failures: int, count: int, what: str, first: int, detail: str
) -> str:
    return (
        f"failed for {failures} of {count} {what} (first: flat index {first}, {detail})"
    )


def _limits_note(outside: int, count: int) -> str:
    return (
        f"; {outside} of {count} answers violate the joint limits (see within_limits)"
    )


def one_answer_result(
    arm: TwoLinkArm,
    x: float,
    y: float,
    q1: float,
    q2: float,
    iterations: int,
    threshold: float,
    method: str,
    solved_message: str,
    failure_detail: FailureDetail | None = None,
) -> IKResult:
    """:func:`assemble_result` for one target ``(x, y)`` and one answer ``(q1, q2)``, all floats.

    What a solver that worked on floats calls: the fields are computed on
    floats (the residual with :func:`twolink.kinematics.tip_from_trig`), with
    the values and the message a batch of one would get.
    """
    if (
        -_LARGE <= q1 <= _LARGE and -_LARGE <= q2 <= _LARGE
    ):  # the usual answer: as it is
        q1_reduced, q2_reduced = q1, q2
    else:
        q1_reduced, q2_reduced = reduced_pair(q1, q2)
    q12 = q1_reduced + q2_reduced
    tip_x, tip_y = tip_from_trig(
        arm.l1, arm.l2, _cos(q1_reduced), _sin(q1_reduced), _cos(q12), _sin(q12)
    )
    residual = _hypot(tip_x - x, tip_y - y)
    success = residual <= threshold
    if success:
        message = solved_message
    else:
        detail = (
            failure_detail(0, residual)
            if failure_detail is not None
            else f"residual {residual:.3g} m"
        )
        message = _failure_message(1, 1, "targets", 0, detail)
    within = True if arm.q_min is None else arm.within_limits((q1, q2))
    if not within:
        message += _limits_note(1, 1)
    q = _empty(2)  # then two item assignments: faster than np.array of a tuple
    q[0] = q1
    q[1] = q2
    return IKResult(q, success, residual, within, iterations, method, message)


def assemble_result(
    arm: TwoLinkArm,
    p: Any,
    q: NDArray[np.float64],
    iterations: ArrayLike,
    threshold: ArrayLike,
    method: str,
    solved_message: str,
    failure_detail: FailureDetail | None = None,
    residual: NDArray[np.float64] | None = None,
) -> IKResult:
    """The :class:`IKResult` of answers ``q`` to targets ``p``, judged by forward kinematics now.

    Every solver ends here (or in :func:`one_answer_result`), so success is
    always judged the same way: the distance from ``fk(q)`` to the target,
    never the solver's own claim.

    Parameters
    ----------
    arm : TwoLinkArm
    p : numpy.ndarray, shape (..., 2), or a pair of floats
        The targets (checked by the solver).
    q : numpy.ndarray, shape (..., 2) or (k, ..., 2)
        The answers, in the result's shape (owned by the result from now
        on): one per target, or ``k`` per target stacked on a leading axis
        (the two branches of the closed form).
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
        answer for the message (None: its residual only).
    residual : numpy.ndarray, optional
        ``|fk(q) - p|`` of the answers (one per answer, flat or in their
        shape), when the solver computed it by forward kinematics with
        them (the closed form does, block by block); else computed here.

    Raises
    ------
    ValueError
        When ``q`` does not hold one answer per target, or ``iterations`` or
        ``threshold`` not one value or one per answer.

    Examples
    --------
    >>> from twolink import arms
    >>> result = assemble_result(arms.ten, np.array([[20.0, 0.0]]), np.array([[0.0, 0.1]]), [3], 1e-9,
    ...                          "by hand", "done", lambda index, residual: "a guess")
    >>> result.success, result.iterations, result.message
    (array([False]), array([3]), 'failed for 1 of 1 targets (first: flat index 0, a guess)')
    """
    target_shape = np.shape(p)
    if q.shape[q.ndim - len(target_shape) :] != target_shape or q.shape[-1:] != (2,):
        raise ValueError(
            f"q of shape {q.shape} does not hold one answer per target p of shape {target_shape}"
        )
    if q.shape == (2,):
        x, y = p if type(p) is tuple else np.asarray(p, dtype=float).tolist()
        q1, q2 = q.tolist()
        return one_answer_result(
            arm,
            x,
            y,
            q1,
            q2,
            _one(iterations, "iterations", int),
            _one(threshold, "threshold", float),
            method,
            solved_message,
            failure_detail,
        )
    shape = q.shape[:-1]
    q_flat = q.reshape(-1, 2)
    if residual is None:
        tips = fk(arm, q_flat)
        tips -= np.broadcast_to(p, q.shape).reshape(-1, 2)
        residual = np.hypot(tips[:, 0], tips[:, 1])
    else:
        residual = _flat(residual, q_flat.shape[0], "residual", float)
    success = residual <= _flat(threshold, residual.size, "threshold", float)
    within = np.asarray(arm.within_limits(q_flat), dtype=bool).reshape(-1)
    failures = int(np.count_nonzero(~success))
    if failures:
        first = int(np.flatnonzero(~success)[0])
        what = "targets" if q.ndim == len(target_shape) else "answers"
        detail = (
            failure_detail(first, float(residual[first]))
            if failure_detail is not None
            else f"residual {residual[first]:.3g} m"
        )
        message = _failure_message(failures, success.size, what, first, detail)
    else:
        message = solved_message
    if arm.has_limits and not np.all(within):
        message += _limits_note(int(np.count_nonzero(~within)), within.size)
    return IKResult(
        q,
        success.reshape(shape),
        residual.reshape(shape),
        within.reshape(shape),
        _flat(iterations, residual.size, "iterations", int).reshape(shape),
        method,
        message,
    )
