"""Frozen value objects that behave like values: equality, hashing and pickling with array fields (private).

The package's results and models are frozen dataclasses, many holding numpy
arrays.  A dataclass's own ``==`` compares the fields as a tuple, which for
arrays raises numpy's "truth value of an array is ambiguous", and its hash
fails on them ("unhashable type").  :class:`Value`, their base, gives them:

- ``==`` field by field, arrays by shape and values (NaN equal to NaN,
  ``-0.0`` to ``0.0``), nested tuples, lists and dicts likewise;
- a hash from the same values, so that equal objects hash alike;
- arrays that cannot change: :func:`freeze` stores each array field
  read-only (a copy, unless the array is already read-only and owns its
  data), so that an object's hash and equality never change under it, and
  unpickling (or copying) freezes them again.

A dataclass opts in by deriving from :class:`Value` with ``eq=False`` (so
that ``dataclass`` keeps these methods) and calling :func:`freeze` when it
is built.

Examples
--------
>>> from dataclasses import dataclass
>>> @dataclass(frozen=True, eq=False)
... class Sample(Value):
...     t: np.ndarray
...     def __post_init__(self):
...         freeze(self)
>>> a, b = Sample(np.array([0.0, np.nan])), Sample(np.array([-0.0, np.nan]))
>>> a == b, hash(a) == hash(b), a.t.flags.writeable
(True, True, False)
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np

__all__ = ["Value", "freeze", "same", "value_key"]


def _frozen(array: np.ndarray, owned: bool) -> np.ndarray:
    """``array`` read-only: itself when it already is and owns its data (or is ``owned``), else a read-only copy."""
    if array.base is None and (owned or not array.flags.writeable):
        array.setflags(write=False)
        return array
    copy = np.array(array)
    copy.setflags(write=False)
    return copy


def _frozen_value(value: Any, owned: bool) -> Any:
    if type(value) is np.ndarray:
        return _frozen(value, owned)
    if (
        type(value) is list
    ):  # lists of arrays (event times): a tuple, which cannot change either
        return tuple(_frozen_value(item, owned) for item in value)
    if type(value) is tuple and any(type(item) is np.ndarray for item in value):
        return tuple(_frozen_value(item, owned) for item in value)
    return value


def freeze(value_object: Any, owned: bool = False) -> None:
    """Store every array field of the dataclass ``value_object`` read-only (lists of them as tuples).

    An array that is read-only and owns its data is kept; others are
    copied, unless ``owned`` says that nothing else holds them (unpickled
    arrays), which are then made read-only in place.
    """
    fields = value_object.__dict__
    for field in dataclasses.fields(value_object):
        value = fields.get(field.name)
        frozen = _frozen_value(value, owned)
        if frozen is not value:
            fields[field.name] = frozen


def same(first: Any, second: Any) -> bool:
    """Whether two field values are equal: arrays by shape and values (NaN equal to NaN), containers item by item.

    Examples
    --------
    >>> same(np.array([1.0, np.nan]), np.array([1.0, np.nan])), same((1, [2.0]), (1, [2.0])), same(np.zeros(2), np.zeros(3))
    (True, True, False)
    """
    if first is second:
        return True
    if isinstance(first, np.ndarray) or isinstance(second, np.ndarray):
        if not (isinstance(first, np.ndarray) and isinstance(second, np.ndarray)):
            return False
        if first.shape != second.shape:
            return False
        try:
            return bool(np.array_equal(first, second, equal_nan=True))
        except TypeError:  # not numbers: NaN has no meaning
            return bool(np.array_equal(first, second))
    if isinstance(first, (tuple, list)) and isinstance(second, (tuple, list)):
        return (
            type(first) is type(second)
            and len(first) == len(second)
            and all(same(a, b) for a, b in zip(first, second))
        )
    if isinstance(first, dict) and isinstance(second, dict):
        return first.keys() == second.keys() and all(
            same(first[key], second[key]) for key in first
        )
    if isinstance(first, float) and isinstance(second, float):
        return first == second or (math.isnan(first) and math.isnan(second))
    equal = first == second
    if isinstance(equal, np.ndarray):
        return bool(equal.all())
    return bool(equal)


def value_key(value: Any) -> Any:
    """A hashable stand-in for a field value, equal for values that :func:`same` calls equal.

    Examples
    --------
    >>> value_key(np.array([0.0, -0.0])) == value_key(np.array([-0.0, 0.0]))
    True
    """
    if isinstance(value, np.ndarray):
        if value.dtype.kind in "biuf":
            numbers = value.astype(float) + 0.0  # -0.0 and 0.0 alike
            numbers[np.isnan(numbers)] = np.nan  # one NaN
            return ("array", value.shape, numbers.tobytes())
        return ("array", value.shape, tuple(value_key(item) for item in value.flat))
    if isinstance(value, (tuple, list)):
        return (type(value).__name__, tuple(value_key(item) for item in value))
    if isinstance(value, dict):
        return (
            "dict",
            tuple(sorted((repr(k), value_key(v)) for k, v in value.items())),
        )
    if isinstance(value, float):
        return "nan" if math.isnan(value) else value + 0.0
    return value


class Value:
    """Base of the package's frozen dataclasses: equality and hashing field by field, arrays by value."""

    __slots__ = ()

    def __eq__(self, other: object) -> bool:
        if other.__class__ is not self.__class__:
            return NotImplemented
        return all(
            same(getattr(self, field.name), getattr(other, field.name))
            for field in dataclasses.fields(self)  # type: ignore[arg-type]
            if field.compare
        )

    def __hash__(self) -> int:
        return hash(
            (
                type(self).__qualname__,
                *(
                    value_key(getattr(self, field.name))
                    for field in dataclasses.fields(self)  # type: ignore[arg-type]
                    if field.compare
                ),
            )
        )

    #: Whether the class keeps its arrays read-only (:func:`freeze`); a class that does not
    #: (:class:`twolink.ik.IKResult`) defines a ``__hash__`` that refuses, saying why.
    _freezes_arrays = True

    def __setstate__(self, state: dict[str, Any]) -> None:
        """Unpickling (and :func:`copy.copy`): the fields back, arrays read-only again."""
        self.__dict__.update(state)
        if self._freezes_arrays:
            freeze(self, owned=True)
