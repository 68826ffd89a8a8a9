"""``Rerun``: how a value exercise is graded on inputs the student never saw.

A stand-in until the grading side defines ``answers.Rerun`` (the same three
fields); the chapter modules import it from here, so pointing them at the
grading side's class is a one-line change per module.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

__all__ = ["Rerun"]


@dataclass(frozen=True)
class Rerun:
    """A value exercise's inputs cell, a draw of hidden inputs, and the references for any inputs.

    Attributes
    ----------
    inputs : dict
        Exactly what the exercise's inputs cell (``# Inputs of exercise N.M``) binds.
    hidden : callable
        ``hidden(rng)``: one draw of inputs the student never saw, valid for the
        exercise (reachable targets, non-singular poses, the same kind of arm).
    answers : callable
        ``answers(inputs)``: each part's reference value, by part name, computed
        by the package from those inputs.
    """

    inputs: dict[str, object]
    hidden: Callable[[np.random.Generator], dict[str, object]]
    answers: Callable[[dict[str, object]], dict[str, object]]
