"""Newton's method on the forward-kinematics equations, vectorised over targets."""

import numpy as np

from .._validate import as_count, as_finite_scalar, broadcast_start
from ..conventions import wrap_angle
from ..kinematics import fk, jacobian
from .result import assemble_result
from .targets import check_reachable

__all__ = ["newton", "distance_outside_reach"]


def distance_outside_reach(arm, p):
    """How far each target lies outside the reach annulus (0 inside), metres.

    This is the smallest residual any configuration can achieve.
    """
    r_min, r_max = arm.reach
    distance = np.hypot(p[..., 0], p[..., 1])
    return np.maximum(0.0, np.maximum(distance - r_max, r_min - distance))


def newton(arm, p, q0=(0.5, 1.0), tol=1e-12, max_iter=100):
    """Solve ``fk(q) = p`` by Newton's method with step control and angle wrapping.

    Each iteration takes the damped Newton (Levenberg-Marquardt) step
    ``dq = -(J^T J + lam I)^(-1) J^T (fk(q) - p)`` and keeps it only if it
    lowers the residual; ``lam`` shrinks after a good step (tending to the
    full Newton step ``-J^(-1) r``, which converges quadratically) and grows
    after a bad one (tending to a short gradient step).  Angles are wrapped to
    ``[-pi, pi)`` after each step.  Plain full Newton steps from a cold start
    overshoot or stall near singular configurations; this control makes the
    iteration converge from almost every start, not from all: a stretched
    or folded start whose arm points along the target (``q0 = (0, 0)`` for
    ``p = (3, 0)`` on the 2 m arm) has a zero gradient, and the iteration
    stops there with ``success`` false.  Joint limits are not applied: read
    the result's ``within_limits``.

    Parameters
    ----------
    arm : TwoLinkArm
    p : array_like, shape (..., 2)
        Target tip positions in metres.
    q0 : array_like, shape (2,) or (..., 2)
        Starting joint angles in radians (broadcast against the targets).
    tol : float
        Success when ``|fk(q) - p| <= tol * (l1 + l2)`` (plus the distance
        outside the reach for targets on a boundary within round-off).
    max_iter : int
        Iteration cap per target.

    Returns
    -------
    IKResult
        ``method="newton"``; the branch found depends on ``q0``.

    Raises
    ------
    twolink.UnreachableError
        For targets outside the reach (message gives distance and reach).
    ValueError
        For NaN/inf targets or starts, or a non-positive ``tol``/``max_iter``.

    Examples
    --------
    >>> from twolink import arms, ik
    >>> result = ik.newton(arms.ten, [[10.0, 10.0], [-5.0, 12.0]], q0=[0.5, 1.0])
    >>> result.success
    array([ True,  True])
    >>> bool(np.all(result.residual < 1e-10))
    True
    """
    p = check_reachable(arm, p)
    tol = as_finite_scalar(tol, "tol", minimum=0.0, strictly=True)
    max_iter = as_count(max_iter, "max_iter", minimum=1)
    p_flat = p.reshape(-1, 2)
    q = wrap_angle(broadcast_start(q0, p.shape, "q0")).reshape(-1, 2).copy()

    scale = arm.l1 + arm.l2
    threshold = tol * scale + distance_outside_reach(arm, p_flat)
    residual_vec = fk(arm, q) - p_flat
    error = np.hypot(residual_vec[:, 0], residual_vec[:, 1])
    damping = np.full(len(q), 1e-3 * scale**2)
    iterations = np.zeros(len(q), dtype=int)
    identity = np.eye(2)
    active = np.flatnonzero(error > threshold)
    for _ in range(max_iter):
        if active.size == 0:
            break
        J = jacobian(arm, q[active])
        JT = np.swapaxes(J, -1, -2)
        normal = JT @ J + damping[active, None, None] * identity
        gradient = (JT @ residual_vec[active, :, None])[..., 0]
        step = np.linalg.solve(normal, -gradient[..., None])[..., 0]
        q_trial = wrap_angle(q[active] + step)
        residual_trial = fk(arm, q_trial) - p_flat[active]
        error_trial = np.hypot(residual_trial[:, 0], residual_trial[:, 1])
        better = error_trial < error[active]
        accepted = active[better]
        q[accepted] = q_trial[better]
        residual_vec[accepted] = residual_trial[better]
        error[accepted] = error_trial[better]
        damping[accepted] *= 0.2
        damping[active[~better]] *= 10.0
        iterations[active] += 1
        still = (error[active] > threshold[active]) & (damping[active] < 1e12 * scale**2)
        active = active[still]

    return assemble_result(
        arm, p, q, iterations, threshold, "newton",
        solved_message=f"converged for all {len(q)} targets (max {iterations.max(initial=0)} iterations)",
        failure_detail=lambda index, residual: (
            f"did not converge: residual {residual:.3g} m after {iterations[index]} iterations"
        ),
    )
