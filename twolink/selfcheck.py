"""Self-checks for the course's exercises: right or wrong, with a hint.

An exercise cell assigns the learner's answer to a named variable; the next
cell calls :func:`check_close` (or :func:`check_true`) with the value the
package computes.  An answer left as ``...`` (the stub of the student edition)
reports "not solved yet" instead of raising, so a notebook runs top to bottom
with unsolved exercises.
"""

import numpy as np

__all__ = ["check_close", "check_true", "NOT_SOLVED"]

NOT_SOLVED = "not solved yet"


def _unsolved(answer):
    return answer is ... or answer is None


def check_close(label, answer, expected, atol=1e-6, rtol=0.0, hint=""):
    """Print whether ``answer`` matches ``expected`` (same shape, within tolerance).

    Parameters
    ----------
    label : str
        Which exercise, e.g. ``"Exercise 1.1"``.
    answer : array_like or Ellipsis
        The learner's value; ``...`` or ``None`` means not attempted yet.
    expected : array_like
        The reference value.
    atol, rtol : float
        Tolerances as in :func:`numpy.allclose`.
    hint : str
        Shown when the answer is wrong.

    Returns
    -------
    bool
        True when correct.

    Examples
    --------
    >>> check_close("Exercise 0.1", [1.0, 2.0], [1.0, 2.0 + 1e-9])
    Exercise 0.1: correct.
    True
    >>> check_close("Exercise 0.1", ..., [1.0, 2.0])
    Exercise 0.1: not solved yet (replace the ... with your answer).
    False
    >>> check_close("Exercise 0.1", [2.0, 1.0], [1.0, 2.0], hint="order is (x, y)")
    Exercise 0.1: not right yet. Hint: order is (x, y)
    False
    """
    if _unsolved(answer):
        print(f"{label}: {NOT_SOLVED} (replace the ... with your answer).")
        return False
    try:
        answer_array = np.asarray(answer, dtype=float)
    except (TypeError, ValueError):
        print(f"{label}: expected numbers, got {type(answer).__name__}. Hint: {hint}")
        return False
    expected_array = np.asarray(expected, dtype=float)
    if answer_array.shape != expected_array.shape:
        print(f"{label}: expected shape {expected_array.shape}, got {answer_array.shape}. Hint: {hint}")
        return False
    if np.allclose(answer_array, expected_array, atol=atol, rtol=rtol):
        print(f"{label}: correct.")
        return True
    print(f"{label}: not right yet. Hint: {hint}")
    return False


def check_true(label, answer, condition, hint=""):
    """Print whether a learner's answer satisfies ``condition(answer)``.

    Examples
    --------
    >>> check_true("Exercise 0.2", 3, lambda n: n > 2)
    Exercise 0.2: correct.
    True
    """
    if _unsolved(answer):
        print(f"{label}: {NOT_SOLVED} (replace the ... with your answer).")
        return False
    try:
        ok = bool(condition(answer))
    except Exception as exc:  # the learner's value may be of any type
        print(f"{label}: the check could not use your answer ({type(exc).__name__}: {exc}). Hint: {hint}")
        return False
    print(f"{label}: correct." if ok else f"{label}: not right yet. Hint: {hint}")
    return ok
