"""Exceptions raised by twolink.

The first two are subclasses of :class:`ValueError`, so code that already
catches ``ValueError`` for bad input keeps working; :class:`SimulationError`
(integrator trouble, not bad input) is a :class:`RuntimeError`.
"""

__all__ = ["UnreachableError", "SingularityError", "SimulationError", "InputTypeError"]


class UnreachableError(ValueError):
    """A target lies outside what the arm can reach.

    The message names the offending target, its distance from the base and
    the reach interval ``[r_min, r_max]`` of the arm.
    """


class SingularityError(ValueError):
    """A configuration is too close to a kinematic singularity for the request.

    The message names the configuration and how far it is from the singularity.
    """


class SimulationError(RuntimeError):
    """The ODE solver failed before reaching the end time (its message says why).

    Raised for a solver failure, a blow-up of the state (NaN, infinity or
    overflowing rates, with the time and the state), and a stiff loop that
    used up its budget of evaluations or wall time (with the method to use).
    """


class InputTypeError(TypeError, ValueError):
    """An argument of the wrong type: a string, ``None``, a boolean, a complex number or an object where numbers belong, or not an arm where an arm belongs.

    A :class:`TypeError`, and also a :class:`ValueError` so that code
    catching ``ValueError`` for bad input keeps working.
    """
