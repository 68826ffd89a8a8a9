"""DH transforms and forward kinematics of the planar 2R arm, in sympy.

sympy has no type information: its names (``sp.Symbol``, ``sp.Matrix``,
``sp.Expr``) are ``Any`` to a type checker, and the annotations here say
what is meant.
"""

from __future__ import annotations

import functools
import math

import numpy as np
import sympy as sp

from .._validate import is_real_number
from ..errors import InputTypeError

__all__ = ["planar_symbols", "dh_matrix", "planar_fk"]


def planar_symbols() -> dict[str, sp.Symbol]:
    """The symbols the course uses: joint angles ``q1, q2`` and lengths ``l1, l2``, plus ``d``.

    Lengths are positive and angles real, so sympy can simplify.

    Returns
    -------
    dict
        ``{"q1", "q2", "l1", "l2", "d"}`` mapped to sympy symbols.

    Examples
    --------
    >>> sorted(planar_symbols())
    ['d', 'l1', 'l2', 'q1', 'q2']
    """
    q1, q2 = sp.symbols("q1 q2", real=True)
    l1, l2 = sp.symbols("l1 l2", positive=True)
    d = sp.Symbol("d", real=True)
    return {"q1": q1, "q2": q2, "l1": l1, "l2": l2, "d": d}


def dh_matrix(
    theta: sp.Expr | float,
    d: sp.Expr | float,
    a: sp.Expr | float,
    alpha: sp.Expr | float,
) -> sp.Matrix:
    """The DH transform ``Rot_z(theta) Trans_z(d) Trans_x(a) Rot_x(alpha)`` as a sympy matrix.

    Parameters
    ----------
    theta, d, a, alpha : sympy expression, number or symbol name
        The DH row: joint angle (rad), offset along z, length along x, twist
        about x (rad).  A real number (Python, numpy, or a 0-d numpy
        array) is taken as it is; a string that is a Python identifier
        (``"q1"``) becomes the plain symbol of that name (it is never
        evaluated as code).  Booleans, complex numbers, NaN, infinity and
        other strings are refused.

    Returns
    -------
    sympy.Matrix, shape (4, 4)

    Examples
    --------
    >>> q, a = sp.symbols("q a")
    >>> dh_matrix(q, 0, a, 0)
    Matrix([
    [cos(q), -sin(q), 0, a*cos(q)],
    [sin(q),  cos(q), 0, a*sin(q)],
    [     0,       0, 1,        0],
    [     0,       0, 0,        1]])
    >>> dh_matrix("q", 0, np.array(2.0), 0)[0, 3]
    2.0*cos(q)
    >>> dh_matrix("__import__('os')", 0, 1, 0)
    Traceback (most recent call last):
    ...
    twolink.errors.InputTypeError: theta must be a sympy expression, a real number or a symbol name (a Python identifier such as 'q1'); got the string "__import__('os')", which is not a name (it is never evaluated)
    """
    theta, d, a, alpha = (
        _dh_entry(value, name)
        for value, name in ((theta, "theta"), (d, "d"), (a, "a"), (alpha, "alpha"))
    )
    return sp.Matrix(
        [
            [
                sp.cos(theta),
                -sp.sin(theta) * sp.cos(alpha),
                sp.sin(theta) * sp.sin(alpha),
                a * sp.cos(theta),
            ],
            [
                sp.sin(theta),
                sp.cos(theta) * sp.cos(alpha),
                -sp.cos(theta) * sp.sin(alpha),
                a * sp.sin(theta),
            ],
            [0, sp.sin(alpha), sp.cos(alpha), d],
            [0, 0, 0, 1],
        ]
    )


_ALLOWED = "a sympy expression, a real number or a symbol name (a Python identifier such as 'q1')"


def _dh_entry(value: object, name: str) -> sp.Expr:
    """One DH parameter as a sympy expression: an expression, a real number, or a symbol name; never code."""
    if isinstance(value, np.ndarray) and value.ndim == 0:
        value = value.item()
    if isinstance(value, sp.Expr):
        return value
    if isinstance(value, str):
        if not value.isidentifier():
            raise InputTypeError(
                f"{name} must be {_ALLOWED}; got the string {value!r}, which is not a name (it is never evaluated)"
            )
        return sp.Symbol(value)
    if is_real_number(value):
        if not math.isfinite(value):  # type: ignore[arg-type]
            raise ValueError(f"{name} must be finite; got {value}")
        return sp.sympify(value, strict=True)
    raise InputTypeError(
        f"{name} must be {_ALLOWED}; got {value!r} ({type(value).__name__})"
    )


def planar_fk(
    with_offset: bool = False,
) -> tuple[sp.Matrix, sp.Matrix, sp.Matrix, sp.Matrix]:
    """``(A1, A2, T_02, p_tip)`` of the planar arm, with ``T_02 = A1 A2`` simplified.

    Parameters
    ----------
    with_offset : bool
        Include the base offset ``d`` in the first DH row (the OSAKE arm).

    Returns
    -------
    tuple
        ``A1``, ``A2``, ``T_02`` (4x4 sympy matrices) and the tip position
        ``p_tip = T_02[:2, 3]`` (2x1), in terms of :func:`planar_symbols`.

    Examples
    --------
    >>> A1, A2, T_02, p_tip = planar_fk()
    >>> p_tip
    Matrix([
    [l1*cos(q1) + l2*cos(q1 + q2)],
    [l1*sin(q1) + l2*sin(q1 + q2)]])
    """
    if not isinstance(with_offset, (bool, np.bool_)):
        raise InputTypeError(
            f"with_offset must be True or False; got {with_offset!r} "
            f"({type(with_offset).__name__})"
        )
    A1, A2, T_02 = (sp.Matrix(m) for m in _simplified_fk(bool(with_offset)))
    return A1, A2, T_02, T_02[:2, 3]


@functools.cache
def _simplified_fk(with_offset: bool) -> tuple[sp.ImmutableMatrix, ...]:
    """``A1, A2, T_02`` once per process: simplifying the product is the slow part.

    Kept immutable; :func:`planar_fk` hands out fresh mutable copies.
    """
    symbols = planar_symbols()
    d = symbols["d"] if with_offset else 0
    A1 = dh_matrix(symbols["q1"], d, symbols["l1"], 0)
    A2 = dh_matrix(symbols["q2"], 0, symbols["l2"], 0)
    return tuple(sp.ImmutableMatrix(m) for m in (A1, A2, sp.simplify(A1 * A2)))
