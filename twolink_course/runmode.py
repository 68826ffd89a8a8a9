"""The grading switch: heavy displays that no answer depends on are skipped while grading.

A chapter run by the grader (``make grade``) only has to compute the answers
its self-checks read; rendering videos, building interactive figures and
timing solvers is most of a chapter's run time, and nothing a check reads
depends on it.  The environment variable ``TWOLINK_GRADING`` switches that
work off for the kernel it is set for:

- ``TWOLINK_GRADING=1``: grading.  The package's heavy display functions take
  a light path;
- unset, ``""`` or ``"0"``: normal (what a learner, ``make test`` and
  ``make notebooks`` run); nothing changes;
- any other value is refused, by the first function that reads it, with an
  error naming the variable and the values it takes (a typo must not grade
  with the switch silently off, or teach with it silently on).

It is read at each call, not at import, so a kernel, a test or a script can
set it at any time.  With the switch on:

- :func:`twolink_course.plot.animation_html` renders no frame and encodes no video:
  it closes the animation's figure and returns a short note
  (:func:`skipped_note`), for every animation function of
  :mod:`twolink_course.plot`;
- :func:`twolink_course.explorer.explorer_figure` makes a plain (Agg) figure, not
  an ipympl widget, and an :class:`twolink_course.explorer.Explorer` on it runs its
  ``update`` and ``describe`` as usual (``description``, ``values``,
  ``set``, ``redraw``, ``updates`` and the controls behave the same) but
  draws nothing, stores no picture and displays as its description;
- figures shown in a notebook (``plt.show()``, or a figure as a cell's
  value) are not rendered to PNG: :func:`twolink_course.inline.png_output` gives no
  picture, so the figure is neither drawn nor encoded;
- :func:`twolink_course.timing.median_time` (and so
  :func:`twolink_course.timing.compare_ik_methods`) times one call, once, instead
  of calibrated batches: timings are printed, never checked.

Everything else runs as usual: solvers, simulations, symbolic algebra, the
figures' artists and the animations' frames as data.  A self-check prints
the same lines either way (``tests/course/test_runmode.py`` runs chapters both ways
and compares them).

Examples
--------
>>> import os
>>> saved = os.environ.pop(VARIABLE, None)
>>> grading()
False
>>> os.environ[VARIABLE] = "1"
>>> grading()
True
>>> skipped_note("animation")
'animation skipped while grading (TWOLINK_GRADING=1)'
>>> os.environ[VARIABLE] = "yes"
>>> grading()
Traceback (most recent call last):
...
ValueError: TWOLINK_GRADING must be "1" (grading: heavy displays skipped) or "0", empty or unset (normal); got 'yes'
>>> _ = os.environ.pop(VARIABLE) if saved is None else os.environ.update({VARIABLE: saved})
"""

from __future__ import annotations

import os

from twolink.errors import InputTypeError

__all__ = ["VARIABLE", "grading", "skipped_note"]

#: The environment variable that switches grading on ("1") or off ("0", "" or unset).
VARIABLE = "TWOLINK_GRADING"

#: Longest part of a refused value quoted in the error message.
_QUOTED_CHARS = 40


def grading() -> bool:
    """Whether the package runs for the grader (``TWOLINK_GRADING=1``), read now.

    Returns
    -------
    bool
        True for ``"1"``; False for ``"0"``, ``""`` or the variable unset.

    Raises
    ------
    ValueError
        For any other value, naming the variable and the values it takes.

    Examples
    --------
    >>> import os
    >>> saved = os.environ.get(VARIABLE)
    >>> os.environ[VARIABLE] = "0"
    >>> grading()
    False
    >>> _ = os.environ.pop(VARIABLE) if saved is None else os.environ.update({VARIABLE: saved})
    """
    value = os.environ.get(VARIABLE, "")
    if value == "1":
        return True
    if value in ("", "0"):
        return False
    shown = value if len(value) <= _QUOTED_CHARS else value[:_QUOTED_CHARS] + "..."
    raise ValueError(
        f'{VARIABLE} must be "1" (grading: heavy displays skipped) or "0", empty or '
        f"unset (normal); got {shown!r}"
    )


def skipped_note(what: str) -> str:
    """The words that stand in for ``what`` (a video, a picture) skipped while grading.

    Examples
    --------
    >>> skipped_note("interactive figure")
    'interactive figure skipped while grading (TWOLINK_GRADING=1)'
    """
    if not isinstance(what, str) or not what.strip():
        raise InputTypeError(
            f"what must be a non-empty str naming what was skipped; got {what!r}"
        )
    return f"{what} skipped while grading ({VARIABLE}=1)"
