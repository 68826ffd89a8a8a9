"""Small text helpers for notebooks: tables, angles and refusals as sentences built from numbers.

Prose that quotes a number is produced by a code cell, so the number is
computed, never typed.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._validate import InputTypeError, as_configuration, as_count
from .errors import SingularityError, UnreachableError

__all__ = ["markdown_table", "angles_deg", "print_error", "CaughtError"]


def markdown_table(headers: Sequence[str], rows: Iterable[Sequence[Any]], formats: Sequence[str] | None = None) -> str:
    """A Markdown table as a string.

    Parameters
    ----------
    headers : sequence of str
    rows : iterable of sequences
        One sequence of cell values per row.
    formats : sequence of str, optional
        A format spec per column (``".3f"``, ``".2e"``, ``""``).

    Examples
    --------
    >>> print(markdown_table(["x", "y"], [[1.0, 2.5]], [".1f", ".2f"]))
    | x | y |
    |---|---|
    | 1.0 | 2.50 |
    """
    formats = formats or [""] * len(headers)
    if len(formats) != len(headers):
        raise ValueError(f"formats has {len(formats)} entries for {len(headers)} columns")
    lines = ["| " + " | ".join(headers) + " |", "|" + "---|" * len(headers)]
    for row in rows:
        if len(row) != len(headers):
            raise ValueError(f"row {row!r} has {len(row)} cells for {len(headers)} columns")
        lines.append("| " + " | ".join(format(value, spec) for value, spec in zip(row, formats)) + " |")
    return "\n".join(lines)


def angles_deg(q: ArrayLike, digits: int = 1) -> str:
    """One configuration in degrees for a legend, a title or a table: ``"(30.0°, 45.0°)"``.

    Parameters
    ----------
    q : array_like, shape (2,)
        Joint angles in radians.
    digits : int
        Decimals shown (>= 0).  A value that rounds to zero prints as ``0``,
        never ``-0``.

    Returns
    -------
    str

    Examples
    --------
    >>> angles_deg(np.radians([30.0, 45.0]))
    '(30.0°, 45.0°)'
    >>> angles_deg([np.pi / 4, -1e-9], digits=0)
    '(45°, 0°)'
    """
    values: NDArray[np.float64] = as_configuration(q)
    decimals = as_count(digits, "digits (decimals shown)", minimum=0)
    q1_deg, q2_deg = (round(float(value), decimals) + 0.0 for value in np.degrees(values))
    return f"({q1_deg:.{decimals}f}°, {q2_deg:.{decimals}f}°)"


@dataclass
class CaughtError:
    """What :func:`print_error` caught: the error, or ``None`` when the block ran through."""

    error: Exception | None = None


@contextmanager
def print_error(
    prefix: str = "", errors: tuple[type[Exception], ...] = (UnreachableError, SingularityError)
) -> Iterator[CaughtError]:
    """Run a block; if it raises one of ``errors``, print ``"{prefix}{Name}: {message}"`` instead of a traceback.

    For notebooks that show how the package refuses a request (a target out
    of reach, a singular configuration): the reader sees the error's
    message, the notebook goes on.  Any other error propagates as usual.

    Parameters
    ----------
    prefix : str
        Printed before the error's name (``"twolink: "``, ``"q = (40°, 0°): "``).
    errors : tuple of exception classes
        What to catch; by default the package's refusals,
        :class:`twolink.UnreachableError` and :class:`twolink.SingularityError`
        (``(ValueError,)`` also catches bad input, which they subclass).

    Yields
    ------
    CaughtError
        Its ``error`` is the caught error after the block, ``None`` if
        nothing was raised (nothing is printed then).

    Examples
    --------
    >>> from twolink import arms, ik
    >>> with print_error("twolink: ") as caught:  # doctest: +ELLIPSIS
    ...     ik.closed_form(arms.two_metre, [5.0, 0.0])
    twolink: UnreachableError: target (5, 0) ...
    >>> type(caught.error).__name__
    'UnreachableError'
    >>> with print_error() as caught:
    ...     q = ik.closed_form(arms.two_metre, [3.0, 1.0]).q
    >>> caught.error is None
    True
    """
    if not isinstance(prefix, str):
        raise InputTypeError(f"prefix must be a string; got {prefix!r} ({type(prefix).__name__})")
    if not (
        isinstance(errors, tuple)
        and errors
        and all(isinstance(kind, type) and issubclass(kind, Exception) for kind in errors)
    ):
        raise InputTypeError(f"errors must be a non-empty tuple of exception classes; got {errors!r}")
    caught = CaughtError()
    try:
        yield caught
    except errors as error:
        caught.error = error
        print(f"{prefix}{type(error).__name__}: {error}")
