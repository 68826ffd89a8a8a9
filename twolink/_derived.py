"""Constants derived from an arm's parameters, computed once per arm.

This module is the one place that reads and writes a :class:`twolink.TwoLinkArm`'s
cache.  An arm is frozen, so what follows from its parameters (the inertia
constants of the dynamics, the closed form's reach terms) never changes:
:func:`derived` computes each on first use and keeps it on the arm, in a dict
that ``TwoLinkArm.__post_init__`` creates with :func:`attach_cache`.  The dict
is not a dataclass field: equality, hashing and ``repr`` ignore it.  An object
that is not a ``TwoLinkArm`` (any object with the arm's attributes) has no
cache, and its constants are computed at each call.

Examples
--------
>>> from twolink import TwoLinkArm
>>> arm = TwoLinkArm(l1=2.0, l2=1.0)
>>> calls = []
>>> def reach_of(arm):
...     calls.append(arm)
...     return arm.l1 + arm.l2
>>> derived(arm, "example", reach_of), derived(arm, "example", reach_of), len(calls)
(3.0, 3.0, 1)
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, TypeVar

__all__ = ["attach_cache", "derived", "has_cache"]

#: The attribute holding the cache: a dict from a key (the module's name for
#: what it computed, e.g. ``"dynamics"``) to the value.
CACHE_ATTRIBUTE = "_derived"

_Value = TypeVar("_Value")


def attach_cache(arm: object) -> None:
    """Give ``arm`` (a frozen ``TwoLinkArm`` being built) an empty cache."""
    object.__setattr__(arm, CACHE_ATTRIBUTE, {})


def has_cache(arm: object) -> bool:
    """Whether ``arm`` carries a cache, i.e. was built as a ``TwoLinkArm``."""
    return getattr(arm, CACHE_ATTRIBUTE, None) is not None


def derived(arm: Any, key: str, compute: Callable[[Any], _Value]) -> _Value:
    """``compute(arm)``, computed once per ``TwoLinkArm`` and kept under ``key``.

    Parameters
    ----------
    arm : TwoLinkArm or an object with its attributes
        Without a cache (not a ``TwoLinkArm``) the value is computed each time.
    key : str
        The name of what ``compute`` returns; one key, one computation.
    compute : callable
        ``arm -> value``; it raises for an object that is not an arm.
    """
    try:
        return arm._derived[key]  # the usual case, kept cheap: one call per formula use
    except (AttributeError, KeyError):
        pass
    cache = getattr(arm, CACHE_ATTRIBUTE, None)
    if cache is None:
        return compute(arm)
    value = cache[key] = compute(arm)
    return value
