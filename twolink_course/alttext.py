"""Text alternatives of figures, built from the data drawn.

A reader who cannot see a figure gets its text alternative instead: the
``alt`` of its image in JupyterLab and on the static site, the sentence under
an explorer.  Each drawing function of :mod:`twolink_course.plot` records, for what
it drew, a sentence made from the data it drew (:func:`record`): "The arm at
q = (30°, 45°), tip at (2.25, 2.93) m."  A ``move_*`` function records the
new sentence with the new data, so the sentence stays true.
:func:`describe` composes a figure's text alternative from those sentences
and from what any figure has (titles, axis labels with their ranges, legend
entries, texts), so a figure drawn with plain matplotlib calls still gets a
useful one.

The sentences are kept in a :class:`weakref.WeakKeyDictionary` keyed by the
artist (nothing is set on matplotlib's objects; an artist's sentence goes
with it).  Numbers are rounded far above round-off (positions to the
centimetre, angles to 0.1°, other quantities to three significant digits),
so a stored text alternative reads the same on every machine.

Examples
--------
>>> from matplotlib.figure import Figure
>>> figure = Figure()
>>> ax = figure.subplots()
>>> (line,) = ax.plot([0.0, 1.0], [0.0, 2.0], label="tip")
>>> _ = record(line, "The tip moves from (0, 0) to (1, 2) m")
>>> ax.set_xlabel("x [m]"), ax.set_ylabel("y [m]"), ax.set_title("A move")
(Text(0.5, 0, 'x [m]'), Text(0, 0.5, 'y [m]'), Text(0.5, 1.0, 'A move'))
>>> describe(figure)
'A move. The tip moves from (0, 0) to (1, 2) m. Axes: x [m] from -0.05 to 1.05, y [m] from -0.1 to 2.1.'
"""

from __future__ import annotations

import math
import weakref
from collections.abc import Iterable, Sequence
from typing import Any

import numpy as np
from matplotlib.artist import Artist
from matplotlib.axes import Axes
from matplotlib.axis import Axis
from matplotlib.collections import Collection
from matplotlib.figure import Figure, SubFigure
from matplotlib.image import AxesImage
from matplotlib.legend import Legend
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from matplotlib.spines import Spine
from matplotlib.text import Text
from numpy.typing import ArrayLike

from twolink._validate import InputTypeError, as_configuration

from .display import rounded, significant

__all__ = [
    "record",
    "recorded",
    "describe",
    "angles_text",
    "point_text",
    "plain_number",
    "quantity_text",
    "listed",
]

#: Artist -> its sentence; "" for an artist described with another one (the
#: base marker of an arm, the hatch marks of a wall).
_SENTENCES: weakref.WeakKeyDictionary[Artist, str] = weakref.WeakKeyDictionary()


def _as_sentence(text: str) -> str:
    text = " ".join(text.split())
    return text if text.endswith((".", "!", "?")) else text + "."


def record(artist: Artist, sentence: str, *, parts: Iterable[Artist] = ()) -> Artist:
    """Record what ``artist`` shows, in words; ``parts`` are drawn with it and said by it.

    Recording again replaces the sentence (what a ``move_*`` function does).

    Parameters
    ----------
    artist : matplotlib.artist.Artist
        The artist that carries the sentence (a line, a patch, a text).
    sentence : str
        What it shows, from the data drawn; a full stop is added if missing.
    parts : iterable of Artist
        Other artists of the same drawing (markers, hatch marks): the
        sentence covers them, so :func:`describe` does not count them again.

    Returns
    -------
    matplotlib.artist.Artist
        ``artist``.

    Examples
    --------
    >>> from matplotlib.lines import Line2D
    >>> line = record(Line2D([0, 1], [0, 1]), "A diagonal")
    >>> recorded(line)
    'A diagonal.'
    """
    if not isinstance(artist, Artist):
        raise InputTypeError(
            f"artist must be a matplotlib Artist (a line, a patch, a text); got {artist!r}"
        )
    if not isinstance(sentence, str) or not sentence.strip():
        raise InputTypeError(
            f"sentence must be a non-empty string saying what the artist shows; got {sentence!r}"
        )
    _SENTENCES[artist] = _as_sentence(sentence)
    for part in parts:
        if part is not artist and isinstance(part, Artist):
            _SENTENCES[part] = ""
    return artist


def recorded(artist: Artist) -> str | None:
    """The sentence recorded for ``artist`` ("" when another artist's sentence covers it), or None.

    Examples
    --------
    >>> from matplotlib.lines import Line2D
    >>> recorded(Line2D([0], [0])) is None
    True
    """
    return _SENTENCES.get(artist)


# --- numbers as the sentences show them


def plain_number(value: float, digits: int = 3) -> str:
    """``value`` to ``digits`` significant digits, without trailing zeros or ``-0``.

    Examples
    --------
    >>> plain_number(1.1000000000000001), plain_number(1234.0), plain_number(2.5e-5)
    ('1.1', '1230', '2.5e-05')
    >>> plain_number(-0.0), plain_number(5.0)
    ('0', '5')
    """
    value = float(f"{float(value):.{digits}g}") + 0.0
    return f"{value:g}"


def _limit_texts(low: float, high: float) -> tuple[str, str]:
    """An axis range to three significant digits of its span (``-4.6``, ``4.6``)."""
    span = abs(high - low)
    decimals = max(0, 2 - math.floor(math.log10(span))) if span > 0 else 2

    def text(value: float) -> str:
        shown = f"{round(value, decimals) + 0.0:.{decimals}f}"
        return shown.rstrip("0").rstrip(".") if "." in shown else shown

    return text(low), text(high)


def angles_text(q: ArrayLike) -> str:
    """Joint angles given in radians, in degrees to 0.1°: ``"(30°, 45°)"``.

    Examples
    --------
    >>> angles_text(np.radians([30.0, 45.0]))
    '(30°, 45°)'
    >>> angles_text([1.0, -1e-12])
    '(57.3°, 0°)'
    """
    values = as_configuration(q)
    return (
        "("
        + ", ".join(
            f"{plain_number(round(float(v), 1), 6)}°" for v in np.degrees(values)
        )
        + ")"
    )


def point_text(p: ArrayLike, unit: str = "m") -> str:
    """A point to the centimetre: ``"(2.25, 2.93) m"``.

    Examples
    --------
    >>> point_text([2.2501, -1e-16])
    '(2.25, 0.00) m'
    """
    return rounded(as_configuration(p, "p", "one (x, y) point", "metres"), 2, unit)


def quantity_text(value: float, unit: str) -> str:
    """A quantity to three significant digits: ``"100 N"``, ``"5.00 N m"``.

    Examples
    --------
    >>> quantity_text(5.0, "N m")
    '5.00 N m'
    """
    return significant(float(value), 3, unit)


def listed(items: Sequence[str]) -> str:
    """``"a"``, ``"a and b"``, ``"a, b and c"``.

    Examples
    --------
    >>> listed(["T", "V", "E"])
    'T, V and E'
    """
    items = list(items)
    if len(items) <= 1:
        return "".join(items)
    return ", ".join(items[:-1]) + " and " + items[-1]


# --- composing a figure's text alternative


def _count(number: int, one: str, many: str) -> str:
    return f"{'one' if number == 1 else number} {one if number == 1 else many}"


def _axis_text(ax: Axes, which: str) -> str:
    axis_label = (ax.get_xlabel() if which == "x" else ax.get_ylabel()).strip()
    name = axis_label or ("horizontal axis" if which == "x" else "vertical axis")
    low, high = ax.get_xlim() if which == "x" else ax.get_ylim()
    scale = ax.get_xscale() if which == "x" else ax.get_yscale()
    if scale == "log":  # limits apart by decades: each to its own significant digits
        first, last = plain_number(low), plain_number(high)
    else:
        first, last = _limit_texts(low, high)
    return f"{name} from {first} to {last}" + (
        "" if scale == "linear" else f" ({scale} scale)"
    )


def _colorbar_of(ax: Axes) -> Any:
    """The colour bar drawn in ``ax`` (matplotlib's Colorbar sets it, outside its stubs), or None."""
    return getattr(ax, "_colorbar", None)


def _scaled_axes(ax: Axes) -> Any:
    """The axes whose colours the colour bar in ``ax`` explains (None for a mappable of no axes)."""
    return getattr(_colorbar_of(ax).mappable, "axes", None)


def _colour_scale(ax: Axes) -> str:
    """The sentence of a colour bar's axes: its label, range and scale."""
    colorbar = _colorbar_of(ax)
    which = "y" if colorbar.orientation == "vertical" else "x"
    text = _axis_text(ax, which)
    if not (ax.get_ylabel() if which == "y" else ax.get_xlabel()).strip():
        text = text.replace(
            "vertical axis" if which == "y" else "horizontal axis", "values", 1
        )
    return _as_sentence("Colour scale: " + text)


def _marker_points(line: Line2D) -> list[str]:
    """Each point of a marker-only line, ``"(2.5, 1.5)"`` (with its label when it has one)."""
    label = str(line.get_label())
    named = f" ({label})" if label and not label.startswith("_") else ""
    return [
        f"({plain_number(x)}, {plain_number(y)}){named}"
        for x, y in np.asarray(line.get_xydata(), dtype=float)
        if np.isfinite(x) and np.isfinite(y)
    ]


def _unrecorded(ax: Axes, children: Iterable[Artist]) -> str:
    """What plain matplotlib calls drew on ``ax`` and nothing recorded: named lines, counts, texts."""
    named: list[str] = []
    points: list[str] = []
    lines = shapes = images = groups = 0
    texts: list[str] = []
    for child in children:
        if isinstance(child, Line2D):
            label = str(child.get_label())
            if (
                child.get_linestyle() in ("None", "none", "", " ")
                and child.get_marker()
            ):
                points.extend(_marker_points(child))
            elif label and not label.startswith("_"):
                named.append(label)
            else:
                lines += 1
        elif isinstance(child, Text):
            if child.get_text().strip():
                texts.append('"' + " ".join(child.get_text().split()) + '"')
        elif isinstance(child, AxesImage):
            images += 1
        elif isinstance(child, Collection):
            groups += 1
        elif isinstance(child, Patch):
            shapes += 1
    found = []
    if points:
        found.append(
            ("the point " if len(points) == 1 else "the points ") + listed(points)
            if len(points) <= 3
            else f"{len(points)} points"
        )
    if named:
        found.append(("the line " if len(named) == 1 else "the lines ") + listed(named))
    if lines:
        found.append(_count(lines, "line", "lines") + (" more" if named else ""))
    if groups:
        found.append(
            _count(groups, "group of points or areas", "groups of points or areas")
        )
    if shapes:
        found.append(_count(shapes, "shape", "shapes"))
    if images:
        found.append(_count(images, "image", "images"))
    if texts:
        found.append(("the text " if len(texts) == 1 else "the texts ") + listed(texts))
    return _as_sentence("It shows " + listed(found)) if found else ""


def _entries(entries: list[str]) -> str:
    """Legend entries in a sentence: by commas, or by semicolons when an entry holds a comma."""
    return ("; " if any("," in entry for entry in entries) else ", ").join(entries)


def _axes_description(ax: Axes) -> str:
    sentences = []
    title = " ".join(
        part
        for part in (ax.get_title("left"), ax.get_title(), ax.get_title("right"))
        if part.strip()
    )
    if title:
        sentences.append(_as_sentence(title))
    skip = {
        ax.patch,
        ax.title,
        getattr(ax, "_left_title", None),
        getattr(ax, "_right_title", None),
    }
    plain: list[Artist] = []
    for child in ax.get_children():
        if (
            child in skip
            or isinstance(child, (Axis, Spine, Legend))
            or not child.get_visible()
        ):
            continue
        said = _SENTENCES.get(child)
        if said is None:
            plain.append(child)
        elif said:
            sentences.append(said)
    other = _unrecorded(ax, plain)
    if other:
        sentences.append(other)
    if ax.axison:
        sentences.append(
            _as_sentence(f"Axes: {_axis_text(ax, 'x')}, {_axis_text(ax, 'y')}")
        )
    legend = ax.get_legend()
    if legend is not None and legend.get_visible():
        entries = [text.get_text() for text in legend.get_texts() if text.get_text()]
        if entries:
            sentences.append(_as_sentence("Legend: " + _entries(entries)))
    return " ".join(sentences)


def describe(figure: Figure | SubFigure) -> str:
    """A figure's text alternative: what its drawing functions recorded, then what any figure has.

    Per axes (``Panel 2 of 3: ...`` when there are several): its title, the
    recorded sentences in drawing order, what plain matplotlib calls drew
    (named lines, counts of other lines and shapes, texts), the axis labels
    with their ranges, and the legend's entries.  The figure's own title
    (``suptitle``) and legends come first and last.

    Parameters
    ----------
    figure : matplotlib.figure.Figure or SubFigure

    Returns
    -------
    str

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> figure = Figure()
    >>> axes = figure.subplots(1, 2)
    >>> _ = axes[0].plot([0, 1], [1, 0], label="speed")
    >>> _ = axes[0].legend()
    >>> _ = axes[1].text(0.5, 0.5, "no data")
    >>> print(describe(figure))
    Panel 1 of 2: It shows the line speed. Axes: horizontal axis from -0.05 to 1.05, vertical axis from -0.05 to 1.05. Legend: speed. Panel 2 of 2: It shows the text "no data". Axes: horizontal axis from 0 to 1, vertical axis from 0 to 1.
    >>> describe(Figure())
    'An empty figure.'
    """
    if not isinstance(figure, (Figure, SubFigure)):
        raise InputTypeError(
            f"figure must be a matplotlib Figure (or SubFigure); got {figure!r} ({type(figure).__name__})"
        )
    parts = []
    suptitle = figure.get_suptitle().strip()
    if suptitle:
        parts.append(_as_sentence(suptitle))
    visible = [ax for ax in figure.axes if ax.get_visible()]
    # a colour bar is told as its panel's colour scale, not as a panel of its own
    scales = [ax for ax in visible if _colorbar_of(ax) is not None]
    axes = [ax for ax in visible if ax not in scales]
    for number, ax in enumerate(axes, start=1):
        text = _axes_description(ax)
        for scale_ax in scales:
            if _scaled_axes(scale_ax) is ax:
                text += " " + _colour_scale(scale_ax)
        if len(axes) > 1:
            text = f"Panel {number} of {len(axes)}: {text}"
        parts.append(text)
    for scale_ax in scales:  # a colour bar of no panel (a ScalarMappable alone)
        if _scaled_axes(scale_ax) not in axes:
            parts.append(_colour_scale(scale_ax))
    for legend in figure.legends:
        entries = [text.get_text() for text in legend.get_texts() if text.get_text()]
        if entries:
            parts.append(_as_sentence("Legend: " + _entries(entries)))
    return " ".join(part for part in parts if part) or "An empty figure."
