"""Small text helpers for notebooks: tables, angles, numbers and refusals as sentences built from numbers.

Prose that quotes a number is produced by a code cell, so the number is
computed, never typed.  A number a notebook shows must read the same on
every CPU, BLAS kernel and operating system, so:

- a quantity at round-off or solver-tolerance level (an error, a residual,
  a drift) is shown as the bound it stays under, :func:`below` or
  :func:`at_most`, which also checks that the claim holds;
- a quantity that an iterative solver, an integrator or MuJoCo settles to is
  shown to the digits it settles to, far above its noise, :func:`rounded`
  (decimals) or :func:`significant` (significant digits).
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from twolink._validate import (
    InputTypeError,
    as_configuration,
    as_count,
    as_finite_scalar,
    real_array,
)
from twolink.errors import SingularityError, UnreachableError

__all__ = [
    "markdown_table",
    "angles_deg",
    "below",
    "at_most",
    "rounded",
    "significant",
    "BoundError",
    "print_error",
    "CaughtError",
]


class BoundError(ValueError):
    """A quantity is not within the bound a notebook states for it: the sentence would be false."""


def _number_text(value: float) -> str:
    """A bound as text: ``0.5``, ``0.01``, and below 0.01 with a plain exponent (``1e-3``, ``2.5e-5``); ``-0`` -> ``0``.

    One style for every small bound, so that a table's ``below 1e-3`` and
    ``below 1e-8`` read alike.
    """
    value += 0.0
    if value != 0.0 and (abs(value) < 0.01 or abs(value) >= 1e6):
        mantissa, exponent = format(value, ".6e").split("e")
        return f"{mantissa.rstrip('0').rstrip('.')}e{int(exponent)}"
    return _plain_exponent(format(value, "g"))


def _plain_exponent(text: str) -> str:
    """``2.5e+04`` -> ``2.5e4``, ``2.e-05`` -> ``2e-5``."""
    text = text.replace(".e", "e")
    return re.sub(
        r"e([+-])0*(\d)",
        lambda match: "e" + match.group(1).replace("+", "") + match.group(2),
        text,
    )


def _with_unit(text: str, unit: str) -> str:
    """``"3 m"``: a space before a unit, none before the degree sign (``"45°"``)."""
    if not isinstance(unit, str):
        raise InputTypeError(
            f"unit must be a string such as 'm' or '°'; got {unit!r} ({type(unit).__name__})"
        )
    if not unit:
        return text
    return f"{text}{unit}" if unit.startswith("°") else f"{text} {unit}"


def _largest_magnitude(value: ArrayLike, name: str) -> float:
    values = real_array(value, name)
    if values.size == 0:
        raise ValueError(f"{name} is empty: give at least one number to bound")
    if not np.all(np.isfinite(values)):
        raise ValueError(
            f"{name} has a NaN or infinite entry: a bound of it would be meaningless; find where it came from"
        )
    return float(np.max(np.abs(values)))


def below(value: ArrayLike, bound: float, unit: str = "") -> str:
    """A round-off or tolerance-level quantity as the bound it stays under: ``"below 1e-12 m"``.

    Its digits are noise (another CPU or BLAS kernel prints other ones), so
    the text names the bound instead, after checking that the largest
    magnitude in ``value`` is strictly below it.  Choose the bound well above
    the noise (a factor of ten or more), so the check holds on every machine.

    Parameters
    ----------
    value : float or array_like
        The quantity (an error, a residual, a drift); for an array, its
        largest magnitude is checked.
    bound : float
        A positive, finite bound, e.g. ``1e-12`` or a solver's tolerance.
    unit : str
        Appended after a space (``"m"``, ``"rad"``, ``"N"``), the degree sign
        ``"°"`` without one; ``""`` for none.

    Returns
    -------
    str

    Raises
    ------
    BoundError
        If the largest magnitude is not below ``bound``: the sentence would be
        false.  Find why the quantity grew, or state a larger bound.

    Examples
    --------
    >>> below(2.2e-16, 1e-12, "m")
    'below 1e-12 m'
    >>> below([3e-9, -4e-9], 1e-6)
    'below 1e-6'
    >>> below(2e-5, 1e-3, "°")
    'below 1e-3°'
    >>> below(0.02, 1e-3, "m")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    twolink_course.display.BoundError: value's largest magnitude 0.02 is not below the stated bound 1e-3 m; ...
    """
    limit = as_finite_scalar(bound, "bound", minimum=0.0, strictly=True)
    largest = _largest_magnitude(value, "value")
    if not largest < limit:
        raise BoundError(
            f"value's largest magnitude {largest:.3g} is not below the stated bound {_with_unit(_number_text(limit), unit)}; "
            "the sentence would be false: find why the quantity grew, or state a larger bound"
        )
    return "below " + _with_unit(_number_text(limit), unit)


def at_most(value: ArrayLike, bound: float, unit: str = "") -> str:
    """A count or a quantity shown by the bound it does not exceed: ``"at most 8 iterations"``.

    For what varies between machines but has a known ceiling (a solver's
    iteration count, a number of samples near a tie): the text names the
    ceiling after checking that the largest magnitude of ``value`` does not
    exceed it.

    Parameters
    ----------
    value : float or array_like
    bound : float
        A non-negative, finite bound.
    unit : str
        Appended after a space (the degree sign ``"°"`` without one); ``""`` for none.

    Returns
    -------
    str

    Raises
    ------
    BoundError
        If the largest magnitude exceeds ``bound``.

    Examples
    --------
    >>> at_most(5, 8, "iterations")
    'at most 8 iterations'
    >>> at_most([0.5, 1.0], 1.0, "deg")
    'at most 1 deg'
    """
    limit = as_finite_scalar(bound, "bound", minimum=0.0)
    largest = _largest_magnitude(value, "value")
    if largest > limit:
        raise BoundError(
            f"value's largest magnitude {largest:.3g} exceeds the stated bound {_with_unit(_number_text(limit), unit)}; "
            "the sentence would be false: find why the quantity grew, or state a larger bound"
        )
    return "at most " + _with_unit(_number_text(limit), unit)


def _entries_to_show(value: ArrayLike) -> tuple[list[float], bool]:
    """The finite numbers of a scalar or a vector, as floats, and whether it was a scalar."""
    values = real_array(value, "value")
    if values.ndim > 1:
        raise ValueError(
            f"value must be one number or a vector; got an array of shape {values.shape}"
        )
    if not np.all(np.isfinite(values)):
        raise ValueError(
            "value has a NaN or infinite entry: it cannot be shown rounded; find where it came from"
        )
    return [float(entry) for entry in values.reshape(-1)], values.ndim == 0


def _joined(texts: list[str], scalar: bool) -> str:
    return texts[0] if scalar else "(" + ", ".join(texts) + ")"


def rounded(value: ArrayLike, decimals: int, unit: str = "") -> str:
    """A settled quantity to a fixed number of decimals: ``"500.5 N"``, ``"(1.20, 0.35) m"``.

    For what a solver, an integrator or MuJoCo settles to: show the decimals
    it settles to, far above its noise, not the last digit it prints.  A
    value that rounds to zero prints as ``0``, never ``-0``.

    Parameters
    ----------
    value : float or array_like, at most one axis
        One number, or a vector printed as ``(a, b, ...)``.
    decimals : int
        Decimals shown (>= 0).
    unit : str
        Appended after a space (the degree sign ``"°"`` without one); ``""`` for none.

    Returns
    -------
    str

    Examples
    --------
    >>> rounded(500.5405, 1, "N")
    '500.5 N'
    >>> rounded([1.2, -1e-17], 2, "m")
    '(1.20, 0.00) m'
    """
    places = as_count(decimals, "decimals (decimals shown)", minimum=0)
    entries, scalar = _entries_to_show(value)
    return _with_unit(
        _joined(
            [f"{round(entry, places) + 0.0:.{places}f}" for entry in entries], scalar
        ),
        unit,
    )


def significant(value: ArrayLike, digits: int, unit: str = "") -> str:
    """A settled quantity to a number of significant digits: ``"0.0133 m/s"``, ``"2.5e4 N/m"``.

    Like :func:`rounded`, for a quantity well above its noise whose size
    varies (a stiffness, a period, a small but real speed).

    Parameters
    ----------
    value : float or array_like, at most one axis
    digits : int
        Significant digits shown (>= 1).
    unit : str
        Appended after a space (the degree sign ``"°"`` without one); ``""`` for none.

    Returns
    -------
    str

    Examples
    --------
    >>> significant(0.013333333, 3, "m/s")
    '0.0133 m/s'
    >>> significant([25000.0, -0.5], 2)
    '(2.5e4, -0.50)'
    """
    count = as_count(digits, "digits (significant digits shown)", minimum=1)
    entries, scalar = _entries_to_show(value)
    return _with_unit(
        _joined(
            [
                _plain_exponent(format(entry + 0.0, f"#.{count}g")).rstrip(".")
                for entry in entries
            ],
            scalar,
        ),
        unit,
    )


def markdown_table(
    headers: Sequence[str],
    rows: Iterable[Sequence[Any]],
    formats: Sequence[str] | None = None,
) -> str:
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
        raise ValueError(
            f"formats has {len(formats)} entries for {len(headers)} columns"
        )
    lines = ["| " + " | ".join(headers) + " |", "|" + "---|" * len(headers)]
    for row in rows:
        if len(row) != len(headers):
            raise ValueError(
                f"row {row!r} has {len(row)} cells for {len(headers)} columns"
            )
        lines.append(
            "| "
            + " | ".join(format(value, spec) for value, spec in zip(row, formats))
            + " |"
        )
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
    q1_deg, q2_deg = (
        round(float(value), decimals) + 0.0 for value in np.degrees(values)
    )
    return f"({q1_deg:.{decimals}f}°, {q2_deg:.{decimals}f}°)"


@dataclass
class CaughtError:
    """What :func:`print_error` caught: the error, or ``None`` when the block ran through."""

    error: Exception | None = None


@contextmanager
def print_error(
    prefix: str = "",
    errors: tuple[type[Exception], ...] = (UnreachableError, SingularityError),
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
        raise InputTypeError(
            f"prefix must be a string; got {prefix!r} ({type(prefix).__name__})"
        )
    if not (
        isinstance(errors, tuple)
        and errors
        and all(
            isinstance(kind, type) and issubclass(kind, Exception) for kind in errors
        )
    ):
        raise InputTypeError(
            f"errors must be a non-empty tuple of exception classes; got {errors!r}"
        )
    caught = CaughtError()
    try:
        yield caught
    except errors as error:
        caught.error = error
        print(f"{prefix}{type(error).__name__}: {error}")
