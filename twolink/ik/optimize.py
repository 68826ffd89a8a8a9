"""Inverse kinematics as an optimisation problem, solved by scipy.

Two formulations from the source coursework (MATLAB ``fminunc`` and
``fmincon``), translated to :func:`scipy.optimize.minimize`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._validate import as_finite_scalar, as_flag, broadcast_start
from ..kinematics import distance_outside_reach, fk, jacobian
from .result import IKResult, assemble_result
from .targets import reachable_targets

if TYPE_CHECKING:
    from ..arm import TwoLinkArm

__all__ = ["minimize"]


def _solve_one(
    arm: TwoLinkArm,
    p_target: NDArray[np.float64],
    q0: NDArray[np.float64],
    constrained: bool,
    bounds: list[tuple[float, float]] | None,
) -> Any:
    import scipy.optimize  # here, not at the top: import twolink stays light

    scale = arm.l1 + arm.l2
    if not constrained:

        def squared_error(q: NDArray[np.float64]) -> tuple[float, NDArray[np.float64]]:
            residual_vec = (fk(arm, q) - p_target) / scale
            return float(0.5 * residual_vec @ residual_vec), jacobian(
                arm, q
            ).T @ residual_vec / scale

        return scipy.optimize.minimize(
            squared_error,
            q0,
            jac=True,
            method="BFGS",
            options={"gtol": 1e-14, "maxiter": 500},
        )

    # fmincon-style feasibility problem: minimise a constant subject to fk(q) = p.
    constraint = {
        "type": "eq",
        "fun": lambda q: (fk(arm, q) - p_target) / scale,
        "jac": lambda q: jacobian(arm, q) / scale,
    }
    return scipy.optimize.minimize(
        lambda q: 0.0,
        q0,
        jac=lambda q: np.zeros(2),
        method="SLSQP",
        constraints=[constraint],
        bounds=bounds,
        options={"ftol": 1e-15, "maxiter": 500},
    )


def minimize(
    arm: TwoLinkArm,
    p: ArrayLike,
    q0: ArrayLike = (0.5, 1.0),
    constrained: bool = False,
    tol: float = 1e-9,
) -> IKResult:
    """Solve IK with :func:`scipy.optimize.minimize`, one target at a time.

    ``constrained=False`` minimises ``|fk(q) - p|^2 / 2`` with BFGS, the
    analogue of MATLAB's unconstrained ``fminunc``.  ``constrained=True``
    poses the ``fmincon`` feasibility problem: minimise a constant subject to
    the equality constraint ``fk(q) - p = 0``, solved with SLSQP; relative
    joint limits of the arm become bounds there.  (Absolute-angle limits are
    not passed as bounds.)  The unconstrained form ignores joint limits; the
    result's ``within_limits`` says whether each answer respects them.
    Like :func:`twolink.ik.newton`, neither form converges from every start
    (a stretched start pointing at the target has a zero gradient).

    Parameters
    ----------
    arm : TwoLinkArm
    p : array_like, shape (..., 2)
        Target tip positions in metres.
    q0 : array_like, shape (2,) or (..., 2)
        Starting joint angles in radians.
    constrained : bool
        Which formulation to use (see above).
    tol : float
        Success when ``|fk(q) - p| <= tol * (l1 + l2)``, checked on the
        recomputed residual whatever scipy reports.

    Returns
    -------
    IKResult
        ``method`` is ``"minimize-bfgs"`` or ``"minimize-slsqp"``;
        ``iterations`` counts scipy's iterations.

    Raises
    ------
    twolink.UnreachableError
        For targets outside the reach.
    ValueError
        For NaN/inf targets or starts, or a non-positive ``tol``.
    twolink.errors.InputTypeError
        For a ``constrained`` that is not ``True`` or ``False`` (a string
        ``"False"`` would be truthy).

    Examples
    --------
    >>> from twolink import arms, ik
    >>> result = ik.minimize(arms.ten, [10.0, 10.0], q0=[0.4, 1.0])
    >>> bool(result.success), bool(result.residual < 1e-8)
    (True, True)
    >>> ik.minimize(arms.ten, [10.0, 10.0], constrained=True).method
    'minimize-slsqp'
    """
    p = reachable_targets(arm, p)
    constrained = as_flag(constrained, "constrained")
    tol = as_finite_scalar(tol, "tol", minimum=0.0, strictly=True)
    q0_flat = broadcast_start(q0, p.shape, "q0").reshape(-1, 2)
    p_flat = p.reshape(-1, 2)
    bounds = None
    if (
        constrained
        and arm.q_min is not None
        and arm.q_max is not None
        and arm.limit_convention == "relative"
    ):
        bounds = list(zip(arm.q_min, arm.q_max))
        q0_flat = np.clip(q0_flat, arm.q_min, arm.q_max)

    q = np.empty_like(p_flat)
    iterations = np.zeros(len(p_flat), dtype=int)
    scipy_messages: list[str] = []
    for index, (p_target, q0_target) in enumerate(zip(p_flat, q0_flat)):
        outcome = _solve_one(arm, p_target, q0_target, constrained, bounds)
        q[index] = outcome.x
        # no iterations when the bounds fix every joint (scipy's result then has no nit)
        iterations[index] = outcome.get("nit", 0)
        scipy_messages.append(outcome.message)

    threshold = tol * (arm.l1 + arm.l2) + distance_outside_reach(arm, p_flat)
    return assemble_result(
        arm,
        p,
        q.reshape(p.shape),
        iterations,
        threshold,
        "minimize-slsqp" if constrained else "minimize-bfgs",
        solved_message=f"solved all {len(q)} targets",
        failure_detail=lambda index, residual: (
            f"residual {residual:.3g} m; scipy said: {scipy_messages[index]}"
        ),
    )
