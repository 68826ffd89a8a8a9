"""``first_valid``: a hidden draw by rejection, within a budget of tries.

The chapters' ``Rerun.hidden`` functions draw inputs at random and keep the
first draw valid for the exercise (a reachable circle, a boundary inside the
stated bracket...); this bounds the tries, so a draw that can never be valid
fails with a message instead of looping.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

__all__ = ["first_valid"]


def first_valid(
    draw: Callable[[np.random.Generator], dict[str, object] | None],
    rng: np.random.Generator,
    *,
    what: str,
    tries: int = 200,
) -> dict[str, object]:
    """The first of ``draw(rng)``'s results that is not ``None``, within ``tries`` draws.

    Parameters
    ----------
    draw : callable
        ``draw(rng)``: one draw of an exercise's inputs, or ``None`` when the
        draw is not valid for the exercise.
    rng : numpy.random.Generator
        Where the draws come from.
    what : str
        What is drawn, for the error message (``"exercise 7.2's hidden inputs"``).
    tries : int
        How many draws before giving up; at least 1.

    Raises
    ------
    RuntimeError
        No valid draw within ``tries``: the exercise's ranges leave too few
        valid draws (widen them or raise ``tries``).

    Examples
    --------
    >>> rng = np.random.default_rng(0)
    >>> inputs = first_valid(
    ...     lambda rng: (lambda x: {"x": x} if x > 0.5 else None)(rng.uniform()),
    ...     rng, what="a number above 0.5")
    >>> inputs["x"] > 0.5
    True
    >>> first_valid(lambda rng: None, rng, what="nothing", tries=3)
    Traceback (most recent call last):
    ...
    RuntimeError: no valid draw of nothing in 3 tries: widen the ranges drawn from or raise tries
    """
    if not isinstance(tries, int) or tries < 1:
        raise ValueError(f"tries must be a whole number of at least 1; got {tries!r}")
    for _ in range(tries):
        inputs = draw(rng)
        if inputs is not None:
            return inputs
    raise RuntimeError(
        f"no valid draw of {what} in {tries} tries: "
        "widen the ranges drawn from or raise tries"
    )
