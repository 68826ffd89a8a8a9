"""The sympy DH transform: symbols, numbers and names in; never a string evaluated as code."""

import builtins

import numpy as np
import pytest
import sympy as sp

from twolink import symbolic
from twolink.errors import InputTypeError
from twolink.symbolic import christoffel_coriolis, dh_matrix, time_derivative


def test_a_zero_dimensional_array_is_a_number():
    assert dh_matrix(np.array(0.5), 0, 1, 0) == dh_matrix(0.5, 0, 1, 0)


def test_an_identifier_becomes_a_plain_symbol():
    q, a = sp.symbols("q a")
    assert dh_matrix("q", 0, "a", 0) == dh_matrix(q, 0, a, 0)


def test_a_string_of_code_is_refused_and_never_run():
    code = "__import__('builtins').setattr(__import__('builtins'), 'twolink_code_ran', 1) or 0"
    with pytest.raises(
        InputTypeError,
        match=r"theta must be a sympy expression, a real number or a symbol name .*never evaluated",
    ):
        dh_matrix(code, 0, 1, 0)
    assert not hasattr(builtins, "twolink_code_ran")


@pytest.mark.parametrize(
    "bad", [True, None, 1 + 2j, [1.0, 2.0], np.array([0.5]), "q 1", sp.true]
)
def test_other_values_are_refused_naming_the_parameter(bad):
    with pytest.raises(
        InputTypeError,
        match=r"^alpha must be a sympy expression, a real number or a symbol name",
    ):
        dh_matrix(0.0, 0, 1, bad)


@pytest.mark.parametrize("bad", [float("nan"), float("inf")])
def test_nan_and_infinity_are_refused(bad):
    with pytest.raises(ValueError, match=r"^d must be finite; got "):
        dh_matrix(0.0, bad, 1, 0)


def test_planar_fk_hands_out_fresh_matrices_from_one_simplification():
    A1, _, T_02, p_tip = symbolic.planar_fk()
    A1[0, 0] = 0
    T_02[0, 3] = 0
    again = symbolic.planar_fk()
    assert again[0][0, 0] == sp.cos(symbolic.planar_symbols()["q1"])
    assert again[2][:2, 3] == again[3]
    assert again[3][0] != 0 and again[3] == p_tip


@pytest.mark.parametrize("junk", ["False", 1, None, [True]])
def test_planar_fk_takes_only_a_bool_offset_flag(junk):
    with pytest.raises(InputTypeError, match="with_offset must be True or False"):
        symbolic.planar_fk(with_offset=junk)


def test_the_symbol_lists_may_be_sympy_vectors_as_chapter_5_writes_them():
    """Coordinates, rates and accelerations as ``sp.Matrix`` columns, as the chapter builds them."""
    q1, q2, u1, u2, a1, a2 = sp.symbols("q1 q2 u1 u2 a1 a2")
    q, qd, qdd = sp.Matrix([q1, q2]), sp.Matrix([u1, u2]), sp.Matrix([a1, a2])
    assert sp.simplify(time_derivative(q1 * u2, q, qd, qdd) - (u1 * u2 + q1 * a2)) == 0
    M = sp.Matrix([[2 + sp.cos(q2), 0], [0, 1]])
    assert christoffel_coriolis(M, q, qd) == christoffel_coriolis(M, [q1, q2], [u1, u2])
    with pytest.raises(
        InputTypeError, match="coordinates must be a list, tuple or sympy vector"
    ):
        time_derivative(q1, "q1", [u1], [a1])
