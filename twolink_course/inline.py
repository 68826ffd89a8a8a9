"""Figures in notebook outputs: a sharp PNG, shown at its size, with its text alternative.

IPython turns a figure into a notebook output through the display formatter
registered for :class:`matplotlib.figure.Figure`.  :func:`install` registers
:func:`png_output`: IPython's own "retina" rendering (``retina_figure``, what
``matplotlib_inline.backend_inline.set_matplotlib_formats("retina")``
selects: the PNG at twice the figure's dpi, and ``width`` and ``height``
metadata of half its pixels, so it is shown at its intended size and sharp
on a high-resolution screen), plus ``alt``: the figure's text alternative,
:func:`twolink_course.alttext.describe`.  The output then reads

.. code-block:: json

    {"output_type": "display_data",
     "data": {"image/png": "...", "text/plain": "<Figure size 384x384 with 1 Axes>"},
     "metadata": {"image/png": {"width": 369, "height": 361, "alt": "The arm at ..."}}}

nbconvert's templates read ``width`` and ``height`` there, and the course's
site template (``tools/site_template/course/index.html.j2``) reads ``alt``
into the ``<img>``.

A figure laid out by constrained layout (the course style's default) is
printed at its own size (``bbox_inches=None``): it already fits its canvas,
and the inline backend's cropping pass (``bbox_inches="tight"``, a second
draw) would find nothing to crop.  Every other print option is the inline
backend's (``InlineBackend.print_figure_kwargs``).

Examples
--------
>>> from matplotlib.figure import Figure
>>> figure = Figure(figsize=(2.0, 1.0), dpi=96)
>>> ax = figure.subplots()
>>> _ = ax.set_title("Nothing yet")
>>> png, metadata = png_output(figure)
>>> metadata["alt"]
'Nothing yet. Axes: horizontal axis from 0 to 1, vertical axis from 0 to 1.'
>>> sorted(metadata)
['alt', 'height', 'width']
"""

from __future__ import annotations

from typing import Any

import matplotlib
from matplotlib.figure import Figure
from matplotlib.layout_engine import ConstrainedLayoutEngine

from twolink._optional import require
from twolink._validate import InputTypeError

from .alttext import describe
from .runmode import grading

__all__ = ["png_output", "install", "INLINE_BACKENDS", "PIXEL_SCALE"]

#: Stored pixels per displayed pixel (a "retina" PNG, as IPython's ``retina_figure``).
PIXEL_SCALE = 2

#: The names under which matplotlib knows the notebook's inline backend.
INLINE_BACKENDS = ("inline", "module://matplotlib_inline.backend_inline")


def _print_figure_kwargs(figure: Figure) -> dict[str, Any]:
    """The inline backend's ``print_figure_kwargs`` for ``figure``.

    The backend crops every figure to what it drew (``bbox_inches="tight"``,
    which draws the figure twice); a figure laid out by constrained layout
    (the course style's default) already fits its canvas and is drawn once,
    at its own size.
    """
    config = require("matplotlib_inline.config", "twolink_course.inline.png_output")
    kwargs = dict(config.InlineBackend.instance().print_figure_kwargs)
    if isinstance(figure.get_layout_engine(), ConstrainedLayoutEngine):
        kwargs["bbox_inches"] = None
    return kwargs


def png_output(figure: Figure) -> tuple[str, dict[str, Any]] | None:
    """The figure as a notebook output: base64 PNG at twice the pixels, and its metadata.

    Returns
    -------
    (str, dict) or None
        The base64 text of the PNG and ``{"width", "height", "alt"}`` (width
        and height in displayed pixels, half the PNG's); None for a figure
        with nothing drawn (as IPython's formatters do: no empty picture),
        and None while grading (``TWOLINK_GRADING=1``,
        :mod:`twolink_course.runmode`): the figure is then neither drawn nor
        encoded, and the notebook shows only its text form.
    """
    if not isinstance(figure, Figure):
        raise InputTypeError(f"figure must be a matplotlib Figure; got {figure!r}")
    if grading():  # no answer depends on a picture: not drawn, not encoded
        return None
    # as IPython's formatters: no picture of an empty figure
    if not figure.axes and not figure.lines:
        return None
    kwargs = _print_figure_kwargs(figure)
    pylabtools = require("IPython.core.pylabtools", "twolink_course.inline.png_output")
    output = pylabtools.retina_figure(figure, base64=True, **kwargs)
    if output is None:
        return None
    encoded, size = output
    return encoded, {**size, "alt": describe(figure)}


def install() -> bool:
    """Make IPython show figures with :func:`png_output` (idempotent); False outside IPython.

    What it changes, and only that: the ``image/png`` display formatter of
    the running IPython shell for :class:`matplotlib.figure.Figure`, and no
    other format for figures (as ``set_matplotlib_formats("retina")``
    would).  When pyplot's backend is the inline one and has not been loaded
    yet, it is loaded first (``matplotlib_inline`` sets up its own formats
    when loaded, which would replace this formatter if it came later).
    """
    ipython = require("IPython", "twolink_course.inline.install")
    shell = ipython.get_ipython()
    if shell is None:
        return False
    # the backend as configured, without resolving an "auto" backend
    backend = matplotlib.get_backend(auto_select=False)
    if isinstance(backend, str) and backend.lower() in INLINE_BACKENDS:
        require("matplotlib_inline.backend_inline", "twolink_course.inline.install")
    formatters = shell.display_formatter.formatters
    for mime, formatter in formatters.items():
        if mime != "image/png":
            formatter.pop(Figure, None)
    formatters["image/png"].for_type(Figure, png_output)
    return True
