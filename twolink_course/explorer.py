"""Explorers: sliders that move a figure drawn once, at the speed of the hand.

An explorer is a figure whose artists are made once, the controls (sliders,
choices) that change it, and an ``update(**values)`` function that moves those
artists (``set_data``, ``set_text``, ...) for new values.  The figure lives in
an ipympl canvas (Matplotlib's interactive Jupyter backend), which sends the
browser only the pixels that changed, so a move costs the update and one
render, not a new figure and a new PNG.

- :func:`explorer_figure` makes the figure, on an ipympl canvas;
- :func:`slider`, :func:`range_slider` and :func:`choice` make controls
  labelled in words with units, with steps that land on round values and a
  track wide enough for their number of steps;
- :class:`Explorer` wires them: it calls ``update`` once, then on every
  change, and shows a sentence describing what the figure shows (the text
  alternative) under the figure.

While a slider is dragged the browser's widget manager sends the kernel only
the latest value once the previous one is handled, and the canvas renders
when the browser asks for a frame, so the latest value wins and nothing is
still drawing after the hand stops, as long as ``update`` is quick: keep heavy
work (samples, meshes, reference curves) out of it, computed once beforehand.
The sentence under the figure is sent once the hand has stopped for
``DESCRIPTION_DELAY`` seconds (``Explorer.description`` is always current).

Displayed in a notebook an explorer stores, besides the live widgets, a PNG of
its first state and its description, which static renderers (nbconvert,
GitHub) show instead of the widgets.

While grading (``TWOLINK_GRADING=1``, :mod:`twolink_course.runmode`) nothing is drawn:
:func:`explorer_figure` makes a plain figure (no ipympl canvas, no widget), and
an :class:`Explorer` runs ``update`` and ``describe`` as always (its
``description``, ``values``, ``set``, ``refresh``, ``redraw``, ``updates`` and
controls behave the same) but renders no picture, and displays as its
description with a note that the interactive figure was skipped.

Examples
--------
>>> import numpy as np
>>> from twolink import arms
>>> from twolink_course import explorer, plot
>>> arm = arms.two_metre
>>> figure, ax = explorer_figure(4.0, 4.0)
>>> _ = plot.setup_axes(arm, ax=ax)
>>> line = plot.draw_arm(arm, [0.0, 0.0], ax=ax)
>>> def update(q1, q2):
...     plot.move_arm(line, arm, np.radians([q1, q2]))
>>> def describe(q1, q2):
...     x, y = arm.fk(np.radians([q1, q2]))
...     return f"The arm at q = ({q1:g}°, {q2:g}°), tip at ({x:.2f}, {y:.2f}) m."
>>> view = Explorer(
...     figure,
...     update,
...     {"q1": slider("q1", "deg", 30, -180, 180, 1), "q2": slider("q2", "deg", 45, -180, 180, 1)},
...     describe=describe,
... )
>>> view.description
'The arm at q = (30°, 45°), tip at (2.25, 2.93) m.'
>>> view.set(q2=0)
>>> view.description
'The arm at q = (30°, 0°), tip at (3.46, 2.00) m.'
>>> np.round(line.get_xydata()[-1], 2)
array([3.46, 2.  ])
"""

from __future__ import annotations

import asyncio
import base64
import html
import io
import itertools
import math
import sys
import threading
import warnings
import weakref
from collections.abc import Callable, Mapping, Sequence
from decimal import Decimal
from typing import Any

import matplotlib
from matplotlib.artist import Artist
from matplotlib.axis import Axis
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.spines import Spine

from twolink._optional import require
from twolink._validate import InputTypeError, as_finite_scalar

from . import figure_style
from .alttext import describe as describe_figure
from .alttext import listed
from .runmode import grading, skipped_note

__all__ = ["Explorer", "explorer_figure", "slider", "range_slider", "choice"]

#: Pixels of slider track per step, at least: finer and a key press or a
#: drag of one pixel would skip values.
PIXELS_PER_STEP = 2
#: Track width limits, pixels: wide enough to aim, narrow enough for a laptop.
TRACK_MIN_PX, TRACK_MAX_PX = 280, 640
#: Width of every control's label, so that the tracks line up.
LABEL_WIDTH = "9em"
#: Width of each button of a choice.
CHOICE_BUTTON_WIDTH = "6em"
#: The CSS class of an explorer's box in the page.
CSS_CLASS = "twolink-explorer"
#: Seconds the sentence under the figure waits for the hand to stop (a drag
#: sends only the picture; the page then lays out the new sentence once).
DESCRIPTION_DELAY = 0.15
#: Most steps on one slider (a finer slider cannot be aimed at one value).
MAX_STEPS = 2000

_figure_numbers = itertools.count(1)


def _ipympl_backend() -> Any:
    """ipympl's backend module, leaving pyplot's backend as it was.

    ``import ipympl`` switches pyplot to itself when matplotlib is loaded; the
    notebook's other figures must stay on their own backend (inline), so the
    backend in use before is put back.
    """
    if "ipympl.backend_nbagg" in sys.modules:
        return sys.modules["ipympl.backend_nbagg"]
    # the backend as configured, or matplotlib's "auto" sentinel (not resolved:
    # resolving it would choose and load a backend)
    saved = dict.__getitem__(matplotlib.rcParams, "backend")
    module = require("ipympl.backend_nbagg", "twolink_course.explorer")
    if dict.__getitem__(matplotlib.rcParams, "backend") != saved:
        if "matplotlib.pyplot" in sys.modules:  # (saved may be "auto": a sentinel)
            sys.modules["matplotlib.pyplot"].switch_backend(saved)
        else:
            dict.__setitem__(matplotlib.rcParams, "backend", saved)
    return module


#: Each explorer figure's lock: one thread at a time moves or draws it.
_draw_locks: weakref.WeakKeyDictionary[Figure, threading.RLock] = (
    weakref.WeakKeyDictionary()
)


def _draw_lock(figure: Figure) -> threading.RLock:
    """The lock held while ``figure`` is changed or drawn.

    ipykernel 7 runs the messages of JupyterLab's widgets on a subshell, a
    thread of its own, beside the kernel's main thread: the page's request
    for a picture (ipympl's ``draw``) and a slider's new value can then draw
    the same canvas at the same time, and the picture sent is a mix of both
    (often the axes alone: chapter 5's blank explorer after Run All).
    """
    return _draw_locks.setdefault(figure, threading.RLock())


def _whole_pixels(width: float, height: float, dpi: float) -> tuple[float, float]:
    """``width`` x ``height`` inches rounded to whole pixels at ``dpi``.

    The page draws the picture into a canvas of whole pixels; a figure of
    6.6 inches at 96 dpi is 633.6 pixels, which the kernel and the page
    would round differently.  Made at whole pixels, both agree.

    >>> _whole_pixels(6.6, 3.0, 96.0)
    (6.604166666666667, 3.0)
    """
    return (
        max(1, round(width * dpi)) / dpi,
        max(1, round(height * dpi)) / dpi,
    )


def _widgets() -> Any:
    return require("ipywidgets", "twolink_course.explorer")


def explorer_figure(
    width: float,
    height: float,
    *,
    ncols: int = 1,
    dpi: float = figure_style.DPI,
    **subplot_kw: Any,
) -> tuple[Figure, Any]:
    """A figure of ``width`` x ``height`` inches on an ipympl canvas, and its axes.

    The figure is not registered with pyplot, so the notebook's other figures
    keep their backend (inline) and this one is shown only inside its
    :class:`Explorer`.  The canvas has no toolbar, header or footer and does
    not resize.  The figure and its axes are made with the course style
    (:func:`twolink_course.figure_style.context`: font sizes, the colour and line-style
    cycle), whether or not :func:`twolink_course.figure_style.use` was called.

    While grading (:func:`twolink_course.runmode.grading`) the figure is on a plain
    Agg canvas instead: no widget, no ipympl, nothing sent to a browser.

    Parameters
    ----------
    width, height : float
        Size in inches (at ``dpi`` pixels per inch).
    ncols : int
        Number of axes side by side (``axes`` is then an array of them).
    dpi : float
        Pixels per inch of the figure at its intended size (``figure_style.DPI``,
        the CSS inch; ipympl doubles the pixels on a high-resolution screen
        by itself).
    **subplot_kw
        Passed to :meth:`matplotlib.figure.Figure.subplots` (e.g. ``gridspec_kw``).

    Returns
    -------
    (matplotlib.figure.Figure, axes)
    """
    width = as_finite_scalar(width, "width (inches)", minimum=0.0, strictly=True)
    height = as_finite_scalar(height, "height (inches)", minimum=0.0, strictly=True)
    if type(ncols) is not int or ncols < 1:
        raise ValueError(f"ncols must be a positive int; got {ncols!r}")
    backend = None if grading() else _ipympl_backend()
    with figure_style.context():
        figure = Figure(figsize=_whole_pixels(width, height, dpi), dpi=dpi)
        # no layout engine: laid out once (Explorer), so a move never shifts the axes
        figure.set_layout_engine("none")
        axes = figure.subplots(1, ncols, **subplot_kw)
    if backend is None:
        FigureCanvasAgg(figure)  # drawn only if asked (Explorer.png)
        return figure, axes
    with warnings.catch_warnings():
        # ipympl 0.10's toolbar passes traitlets an argument it deprecates
        warnings.filterwarnings(
            "ignore", "Passing unrecognized arguments", DeprecationWarning
        )
        canvas = backend.Canvas(figure)
        backend.FigureManager(canvas, next(_figure_numbers))
    # ipympl keeps a copy of every picture it sends, as a data URL, until the
    # page's canvas says it is ready; its copy lacks the URL's "data:" prefix, so
    # a page that builds the canvas from it loads a broken image (the console's
    # "drawImage ... 'broken' state").  The first picture reaches the page as the
    # pictures after it do, and static renderers get the Explorer's own PNG.
    canvas.syncing_data_url = False
    lock = _draw_lock(figure)
    draw = canvas.draw

    def draw_alone() -> None:  # every draw ipympl asks for, one at a time
        with lock:
            draw()

    canvas.draw = draw_alone
    canvas.header_visible = False
    canvas.footer_visible = False
    canvas.toolbar_visible = False
    canvas.resizable = False
    canvas.capture_scroll = False
    return figure, axes


def _decimals(step: float) -> int:
    exponent = Decimal(repr(step)).normalize().as_tuple().exponent
    return max(0, -int(exponent)) if isinstance(exponent, int) else 0


def _on_grid(value: float, minimum: float, step: float) -> bool:
    steps = (value - minimum) / step
    return abs(steps - round(steps)) <= 1e-9 * max(1.0, abs(steps))


def _grid(
    label: str, unit: str, minimum: float, maximum: float, step: float
) -> tuple[float, float, float, int]:
    name = f"{label} [{unit}]" if unit else label
    minimum = as_finite_scalar(minimum, f"the minimum of {name}")
    maximum = as_finite_scalar(maximum, f"the maximum of {name}")
    step = as_finite_scalar(step, f"the step of {name}", minimum=0.0, strictly=True)
    if not minimum < maximum:
        raise ValueError(
            f"{name}: the minimum must be below the maximum; got {minimum:g} and {maximum:g}"
        )
    if not _on_grid(maximum, minimum, step):
        raise ValueError(
            f"{name}: the range {minimum:g}..{maximum:g} is not a whole number of steps of {step:g}"
        )
    steps = round((maximum - minimum) / step)
    if steps > MAX_STEPS:
        raise ValueError(
            f"{name}: {steps} steps of {step:g} is more than MAX_STEPS = {MAX_STEPS}; use a larger step"
        )
    return minimum, maximum, step, steps


def _layout(steps: int) -> Any:
    track = min(max(TRACK_MIN_PX, PIXELS_PER_STEP * steps), TRACK_MAX_PX)
    return _widgets().Layout(width=f"calc({LABEL_WIDTH} + {track + 90}px)")


def _label(label: str, unit: str) -> str:
    if not isinstance(label, str) or not label.strip():
        raise InputTypeError(f"a control needs a label in words; got {label!r}")
    if not isinstance(unit, str):
        raise InputTypeError(f"unit must be a string ('' for none); got {unit!r}")
    return f"{label} [{unit}]" if unit else label


def slider(
    label: str,
    unit: str,
    value: float,
    minimum: float,
    maximum: float,
    step: float,
    *,
    continuous: bool = True,
) -> Any:
    """A slider labelled ``"label [unit]"`` whose steps land on round values.

    An ``IntSlider`` when value, ends and step are all ints, else a
    ``FloatSlider`` whose readout shows as many decimals as the step has.

    Parameters
    ----------
    label : str
        What the slider sets, in words or a symbol (``"q1"``, ``"stiffness k"``).
    unit : str
        Its unit (``"deg"``, ``"N/m"``; ``""`` for a pure number).
    value, minimum, maximum, step : float
        The start value and the grid; ``value`` and ``maximum`` must lie on the
        grid ``minimum + k step``.
    continuous : bool
        Send values while dragging (the default); ``False`` only on release.

    Examples
    --------
    >>> angle = slider("q1", "deg", 30, -180, 180, 5)
    >>> angle.description, angle.value, type(angle).__name__
    ('q1 [deg]', 30, 'IntSlider')
    >>> slider("stiffness k", "N/m", 600.0, 50.0, 3000.0, 50.0).readout_format
    '.0f'
    >>> slider("x", "m", 0.25, 0.0, 1.0, 0.1)
    Traceback (most recent call last):
    ...
    ValueError: x [m]: the start value 0.25 is not on the grid 0 + k 0.1
    """
    widgets = _widgets()
    description = _label(label, unit)
    low, high, size, steps = _grid(label, unit, minimum, maximum, step)
    start = as_finite_scalar(value, f"the value of {description}")
    if not (low <= start <= high and _on_grid(start, low, size)):
        raise ValueError(
            f"{description}: the start value {start:g} is not on the grid {low:g} + k {size:g}"
            + ("" if low <= start <= high else f" within {low:g}..{high:g}")
        )
    common = dict(
        description=description,
        continuous_update=bool(continuous),
        style={"description_width": LABEL_WIDTH},
        layout=_layout(steps),
    )
    if all(type(number) is int for number in (value, minimum, maximum, step)):
        return widgets.IntSlider(
            value=value, min=minimum, max=maximum, step=step, **common
        )
    return widgets.FloatSlider(
        value=start,
        min=low,
        max=high,
        step=size,
        readout_format=f".{_decimals(size)}f",
        **common,
    )


def range_slider(
    label: str,
    unit: str,
    value: tuple[int, int],
    minimum: int,
    maximum: int,
    step: int,
    *,
    continuous: bool = True,
) -> Any:
    """An integer range slider (two handles) labelled ``"label [unit]"``.

    Examples
    --------
    >>> limits = range_slider("q1 limits", "deg", (0, 90), -180, 180, 5)
    >>> limits.description, limits.value
    ('q1 limits [deg]', (0, 90))
    """
    widgets = _widgets()
    description = _label(label, unit)
    if not all(type(number) is int for number in (minimum, maximum, step, *value)):
        raise InputTypeError(f"{description}: a range slider takes ints")
    low, high, size, steps = _grid(label, unit, minimum, maximum, step)
    first, last = value
    if not (
        low <= first <= last <= high
        and _on_grid(first, low, size)
        and _on_grid(last, low, size)
    ):
        raise ValueError(
            f"{description}: the start range {value} must be ordered, within "
            f"{minimum}..{maximum} and on its grid of {step}"
        )
    return widgets.IntRangeSlider(
        value=(first, last),
        min=minimum,
        max=maximum,
        step=step,
        description=description,
        continuous_update=bool(continuous),
        style={"description_width": LABEL_WIDTH},
        layout=_layout(steps),
    )


def choice(label: str, options: Sequence[str], value: str) -> Any:
    """Buttons for one of a few ``options`` (words), labelled ``label``.

    Examples
    --------
    >>> elbow = choice("elbow", ["down", "up"], "down")
    >>> elbow.description, elbow.value, elbow.options
    ('elbow', 'down', ('down', 'up'))
    """
    widgets = _widgets()
    description = _label(label, "")
    names = list(options)
    if not names or not all(isinstance(name, str) for name in names):
        raise InputTypeError(f"{description}: options must be words; got {options!r}")
    if value not in names:
        raise ValueError(f"{description}: value must be one of {names}; got {value!r}")
    # laid out as the sliders are (ipywidgets' inline row: the label right-aligned
    # in its column, the buttons beside it); ToggleButtons alone is a block, whose
    # label stood above the buttons, outside the column the sliders' labels share
    toggle = widgets.ToggleButtons(
        options=names,
        value=value,
        description=description,
        style={"description_width": LABEL_WIDTH, "button_width": CHOICE_BUTTON_WIDTH},
    )
    toggle.add_class("widget-inline-hbox")
    return toggle


class Explorer:
    """A figure drawn once and the controls that move it.

    Parameters
    ----------
    figure : matplotlib.figure.Figure
        From :func:`explorer_figure`, with its artists already drawn.
    update : callable
        ``update(**values)``: moves the artists for the controls' values (keys
        are the names of ``controls``).  Called once here, then on every change.
    controls : mapping of str to widget
        Name -> a control with a ``value`` (see :func:`slider`, :func:`choice`).
    describe : callable, optional
        ``describe(**values) -> str``: what the figure shows, in words (the
        text alternative, shown under the figure and stored for static pages).
        Without it, the stored picture's text alternative is
        :func:`twolink_course.alttext.describe` of the figure (what the drawing
        functions recorded, kept true by the ``move_*`` functions).
    extra : sequence of widgets, optional
        Further widgets placed after the controls (a button, a note).

    Attributes
    ----------
    widget : ipywidgets.VBox
        Controls, canvas and description, displayed by ``display(explorer)``
        (no canvas while grading).
    updates : int
        How many times ``update`` has run.
    full_redraws : int
        How many of those redrew the whole figure (the first, and any that
        changed axis limits, labels or ticks): a slow move.  Every other
        update draws only the artists it changed, and those above them.
    drawn : bool
        Whether the explorer draws its figure: False while grading
        (:func:`twolink_course.runmode.grading` when it was made), when ``update``
        and ``describe`` still run but nothing is rendered (``full_redraws``
        stays 0) and it displays as its description.
    """

    def __init__(
        self,
        figure: Figure,
        update: Callable[..., object],
        controls: Mapping[str, Any],
        *,
        describe: Callable[..., str] | None = None,
        extra: Sequence[Any] = (),
    ) -> None:
        widgets = _widgets()
        self.drawn = not grading()
        if not isinstance(figure, Figure) or (
            self.drawn and not isinstance(figure.canvas, widgets.DOMWidget)
        ):
            raise InputTypeError(
                "figure must be a matplotlib Figure from twolink_course.explorer.explorer_figure "
                f"(on an ipympl canvas); got {figure!r}"
            )
        if not callable(update) or (describe is not None and not callable(describe)):
            raise InputTypeError("update and describe must be callables of the values")
        if not isinstance(controls, Mapping) or not controls:
            raise InputTypeError(
                "controls must be a non-empty mapping of names to widgets"
            )
        for name, control in controls.items():
            if not (isinstance(name, str) and name.isidentifier()) or not hasattr(
                control, "value"
            ):
                raise InputTypeError(
                    f"control {name!r} must be named by an identifier and have a value; got {control!r}"
                )
        self.figure = figure
        self._lock = _draw_lock(figure)
        self.controls = dict(controls)
        self._update = update
        self._describe = describe
        self.description = ""
        self._text = widgets.HTML(layout=widgets.Layout(max_width="640px"))
        self.updates = 0
        self.full_redraws = 0
        self._holding = False
        self._background: Any = None
        self._saving = False
        self._limits: list[tuple[float, ...]] = []
        self._animated: list[Artist] = []
        self._pending_text: asyncio.TimerHandle | None = None
        for ax in figure.axes:
            # ticks, tick labels and grid under every artist: a move, which
            # redraws what lies above the artists it changes, never redraws them
            ax.set_axisbelow(True)
        figure.canvas.mpl_connect("draw_event", self._on_draw)
        values = self.values
        update(**values)
        self.updates += 1
        if not self.drawn:  # grading: no layout, no picture, no canvas in the page
            if describe is not None:
                self.description = str(describe(**values))
                self._show_description(wait=False)
            for control in self.controls.values():
                control.observe(self._changed, names="value")
            self.widget = widgets.VBox([*self.controls.values(), *extra, self._text])
            self.widget.add_class(CSS_CLASS)
            return
        figure.tight_layout()  # once, for the first state: labels inside the canvas
        self._show_changes()  # the one full draw of the first state
        if describe is not None:
            self.description = str(describe(**values))
            self._show_description(wait=False)  # the first sentence, at once
        for control in self.controls.values():
            control.observe(self._changed, names="value")
        self.widget = widgets.VBox(
            [*self.controls.values(), *extra, figure.canvas, self._text]
        )
        self.widget.add_class(CSS_CLASS)  # how a page (and the browser tests) finds it

    @property
    def values(self) -> dict[str, Any]:
        """The controls' current values, by name."""
        return {name: control.value for name, control in self.controls.items()}

    def set(self, **values: Any) -> None:
        """Set controls by name, then update the figure once (if a value changed)."""
        unknown = sorted(set(values) - set(self.controls))
        if unknown:
            raise ValueError(
                f"no control named {unknown}; the controls are {sorted(self.controls)}"
            )
        with self._lock:
            before = self.values
            self._holding = True
            try:
                for name, value in values.items():
                    self.controls[name].value = value
            finally:
                self._holding = False
            if self.values != before:
                self.refresh()

    def refresh(self) -> None:
        """Move the artists for the current values and show them.

        What the update changed is found by matplotlib's ``stale`` flags: when
        only artists inside the axes moved (lines, texts, patches), they are
        drawn over the saved background and only they are sent (blitting);
        anything else (limits, a new axes, the first draw) redraws the figure.
        """
        with self._lock:  # a page's request for a picture waits for the move
            values = self.values
            self._update(**values)
            self.updates += 1
            self._show_changes()  # the picture first: it is what the hand waits for
            if self._describe is not None:
                self.description = str(self._describe(**values))
                self._show_description(wait=True)

    def redraw(self, description: str | None = None) -> None:
        """Show artists changed outside the update (by a button's exact run, say).

        ``description``, when given, replaces the sentence under the figure (it
        then describes what the button drew, until the next change of a control).
        """
        if description is not None:
            self.description = str(description)
            self._show_description(wait=False)
        with self._lock:
            self._show_changes()

    def _show_description(self, *, wait: bool) -> None:
        """Put ``description`` under the figure: at once, or once the hand has
        stopped for ``DESCRIPTION_DELAY`` (when the kernel runs an event loop)."""
        if self._pending_text is not None:
            self._pending_text.cancel()
            self._pending_text = None
        text = f"<p>{html.escape(self.description)}</p>"
        try:
            loop = asyncio.get_running_loop() if wait else None
        except RuntimeError:  # no loop (a script, a test): now
            loop = None
        if loop is None:
            self._text.value = text
        else:
            self._pending_text = loop.call_later(
                DESCRIPTION_DELAY, setattr, self._text, "value", text
            )

    def _moved_artists(self) -> list[Artist] | None:
        """The axes' children the update changed, or None when the figure must be redrawn."""
        if self._background is None or self._limits != self._axes_limits():
            return None
        moved: list[Artist] = []
        for ax in self.figure.axes:
            if not ax.stale:
                continue
            for child in ax.get_children():
                if child.stale:
                    if isinstance(child, (Axis, Spine)) or child is ax.patch:
                        return None
                    moved.append(child)
        if self.figure.stale and not moved:
            return None  # a change outside the axes
        return moved

    def _axes_limits(self) -> list[tuple[float, ...]]:
        return [(*ax.get_xlim(), *ax.get_ylim()) for ax in self.figure.axes]

    def _show_changes(self) -> None:
        if not self.drawn:
            return
        canvas: Any = self.figure.canvas
        moved = self._moved_artists()
        if moved is None or any(artist not in self._animated for artist in moved):
            self._animate(moved or [])
            self._background = None
            self.full_redraws += 1
            canvas.draw()  # a full draw now; _on_draw saves the new background
            return
        canvas.restore_region(self._background)
        self._draw_animated()
        for artist in moved:
            artist.stale = False
        self.figure.stale = False
        canvas.blit(self.figure.bbox)

    def _on_draw(self, event: Any) -> None:
        """After a full draw: save the background, then draw the moving artists on it."""
        canvas: Any = self.figure.canvas
        if (
            self._saving
            or getattr(event, "renderer", None) is not canvas.get_renderer()
        ):
            return  # a savefig or a layout pass, not the canvas's own picture
        self._background = canvas.copy_from_bbox(self.figure.bbox)
        self._limits = self._axes_limits()
        self._draw_animated()
        # The picture is now current. An artist still marked stale drew nothing
        # (an empty title, a hidden note, which return before clearing the
        # flag): left marked, every move would count it as moved and redraw it
        # and everything above it (legends, notes).
        for ax in self.figure.axes:
            for child in ax.get_children():
                child.stale = False

    def _animate(self, moved: list[Artist]) -> None:
        """Mark ``moved`` and every artist its axes draws after them as animated.

        A moving artist is drawn over the background; an artist that a full
        draw would put on top of it (a higher ``zorder``, or the same and added
        later: a base marker, a note) must then be drawn again over it too.
        """
        for ax in self.figure.axes:
            order = self._drawing_order(ax)
            starts = [order.index(artist) for artist in moved if artist in order]
            for artist in order[min(starts) :] if starts else ():
                if artist not in self._animated:
                    artist.set_animated(True)
                    self._animated.append(artist)
        for artist in moved:  # outside any axes' children: on the figure
            if artist not in self._animated:
                artist.set_animated(True)
                self._animated.append(artist)

    @staticmethod
    def _drawing_order(ax: Any) -> list[Artist]:
        """The axes' children in the order ``Axes.draw`` draws them (by zorder, stable)."""
        children = [child for child in ax.get_children() if child is not ax.patch]
        return sorted(children, key=lambda child: child.get_zorder())

    def _draw_animated(self) -> None:
        """Draw the animated artists still in the figure, in drawing order."""
        self._animated = [a for a in self._animated if a.figure is self.figure]
        rank = {}
        for ax_index, ax in enumerate(self.figure.axes):
            for position, artist in enumerate(self._drawing_order(ax)):
                rank[id(artist)] = (ax_index, position)
        for artist in sorted(
            self._animated, key=lambda a: rank.get(id(a), (len(rank), 0))
        ):
            self.figure.draw_artist(artist)

    def _changed(self, change: Any) -> None:
        if not self._holding:
            self.refresh()

    def png(self, scale: float = 1.0) -> bytes:
        """The figure as it stands, moving artists included, as PNG bytes.

        ``scale`` multiplies the pixels (``figure_style.PIXEL_SCALE`` for the stored
        picture, shown at its intended size on a high-resolution screen).
        """
        scale = as_finite_scalar(scale, "scale", minimum=0.0, strictly=True)
        buffer = io.BytesIO()
        with self._lock:
            return self._png(buffer, scale)

    def _png(self, buffer: io.BytesIO, scale: float) -> bytes:
        self._saving = True
        for artist in self._animated:
            artist.set_animated(False)
        try:
            self.figure.savefig(buffer, format="png", dpi=self.figure.dpi * scale)
        finally:
            for artist in self._animated:
                artist.set_animated(True)
            self._saving = False
        return buffer.getvalue()

    def _repr_mimebundle_(self, **kwargs: Any) -> tuple[dict[str, Any], dict[str, Any]]:
        text = self.description or (
            "An interactive figure with "
            + listed(
                [
                    getattr(control, "description", name) or name
                    for name, control in self.controls.items()
                ]
            )
            + ". "
            + describe_figure(self.figure)
        )
        if not self.drawn:  # grading: the words only, no widget and no picture
            note = skipped_note("interactive figure")
            return {
                "text/plain": f"{text}\n({note})",
                "text/html": f"<p>{html.escape(text)}</p>\n"
                f"<p><em>{html.escape(note)}</em></p>",
            }, {}
        data = self.widget._repr_mimebundle_(**kwargs)
        data = dict(data[0] if isinstance(data, tuple) else data)
        data["image/png"] = base64.b64encode(self.png(figure_style.PIXEL_SCALE)).decode(
            "ascii"
        )
        data["text/plain"] = text
        width, height = self.figure.get_size_inches() * self.figure.dpi
        metadata = {
            "image/png": {
                "width": int(math.ceil(width)),
                "height": int(math.ceil(height)),
                "alt": text,
            }
        }
        return data, metadata
