"""Exceptions raised by twolink.

Both are subclasses of :class:`ValueError`, so code that already catches
``ValueError`` for bad input keeps working.
"""

__all__ = ["UnreachableError", "SingularityError"]


class UnreachableError(ValueError):
    """A target lies outside what the arm can reach.

    The message names the offending target, its distance from the base and
    the reach interval ``[r_min, r_max]`` of the arm.
    """


class SingularityError(ValueError):
    """A configuration is too close to a kinematic singularity for the request.

    The message names the configuration and how far it is from the singularity.
    """
