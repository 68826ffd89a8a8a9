"""The course's figure style: colour-blind-safe roles, legible text, sharp pictures.

One look for every figure of the course, set once.  A chapter's first code
cell calls :func:`use`; :mod:`twolink_course.plot` and :mod:`twolink_course.explorer` draw
with the roles below whether or not it was called.

- **Colours**: the Okabe-Ito palette (Okabe & Ito, *Color Universal Design*,
  2002; Wong, *Nature Methods* 8, 441, 2011), as named constants.  Only five
  of them carry meaning, :data:`MEANING_COLOURS` (blue, vermillion, sky blue,
  black and grey): the largest set of the palette whose every pair stays at
  least :data:`MIN_DISTANCE` apart in CAM02-UCS for normal vision and for
  simulated deuteranopia, protanopia and tritanopia
  (``tests/course/test_figure_style.py`` checks it).
- **Roles**: each thing a figure shows (the arm, a target, the reach, a
  force, the elbow-up branch, ...) is a :class:`Role` with a colour, a line
  style and a marker, and no two roles share all three of line style and
  marker, so no meaning rests on hue alone.
- **Text** at least :data:`MIN_FONT_PT` points at display size: figures are
  made at :data:`DPI` = 96 pixels per inch, the CSS inch, so a matplotlib
  point is a CSS point on the page.
- **Sharp**: in a notebook, :func:`use` installs :mod:`twolink_course.inline`'s
  figure formatter: a PNG of twice the pixels (IPython's "retina" format,
  the one ``matplotlib_inline``'s ``set_matplotlib_formats("retina")``
  selects), shown at its intended size through its ``width`` and ``height``
  metadata, with the figure's text alternative as ``alt``.

Examples
--------
>>> ARM.color, ARM.linestyle, ARM.marker
('#0072B2', '-', 'o')
>>> ELBOW_UP.color == VERMILLION and ELBOW_UP.linestyle == "--"
True
>>> RC["figure.dpi"], RC["xtick.labelsize"] >= MIN_FONT_PT
(96, True)
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Any

import matplotlib
from cycler import Cycler, cycler
from matplotlib.markers import MarkerStyle

from . import inline

__all__ = [
    "BLACK",
    "ORANGE",
    "SKY_BLUE",
    "BLUISH_GREEN",
    "YELLOW",
    "BLUE",
    "VERMILLION",
    "REDDISH_PURPLE",
    "GREY",
    "BACKGROUND",
    "OKABE_ITO",
    "MEANING_COLOURS",
    "MIN_DISTANCE",
    "Role",
    "ARM",
    "ELBOW_DOWN",
    "ELBOW_UP",
    "BASE",
    "TARGET",
    "PATH",
    "REACH",
    "FORCE",
    "TORQUE",
    "ELLIPSE",
    "WALL",
    "ROLES",
    "SERIES",
    "DPI",
    "PIXEL_SCALE",
    "MIN_FONT_PT",
    "FONT_PT",
    "SMALL_FONT_PT",
    "RC",
    "prop_cycle",
    "use",
    "context",
]

# --- the Okabe-Ito palette (its eight colours, by their published names)
BLACK = "#000000"
ORANGE = "#E69F00"
SKY_BLUE = "#56B4E9"
BLUISH_GREEN = "#009E73"
YELLOW = "#F0E442"
BLUE = "#0072B2"
VERMILLION = "#D55E00"
REDDISH_PURPLE = "#CC79A7"
#: A neutral grey for context (the reach's outline, notes' frames); not an Okabe-Ito hue.
GREY = "#7F7F7F"
#: The figures' background (and the face of the arm's joints).
BACKGROUND = "#FFFFFF"

#: The palette in its published order.
OKABE_ITO = (
    BLACK,
    ORANGE,
    SKY_BLUE,
    BLUISH_GREEN,
    YELLOW,
    BLUE,
    VERMILLION,
    REDDISH_PURPLE,
)

#: The colours that carry meaning in the course's figures.  Orange, bluish
#: green, reddish purple and yellow are left out: each comes closer than
#: MIN_DISTANCE to one of these for some simulated colour-vision deficiency
#: (orange-vermillion and bluish green-grey under deuteranopia, reddish
#: purple-blue under protanopia, bluish green-blue under tritanopia), and
#: yellow on white is too faint for a line.
MEANING_COLOURS = (BLUE, VERMILLION, SKY_BLUE, BLACK, GREY)

#: Smallest CAM02-UCS colour difference (Delta E') allowed between two colours
#: that carry meaning, for normal vision and under simulated deuteranopia,
#: protanopia and tritanopia (Machado, Oliveira & Fernandes 2009 at severity
#: 100): the minimum perceptual distance of Petroff, "Accessible Color
#: Sequences for Data Visualization" (arXiv:2107.02270), whose color-set
#: generator uses 20 with the same simulation.
MIN_DISTANCE = 20.0


@dataclass(frozen=True)
class Role:
    """What a thing in a figure looks like: colour, line style and marker.

    Attributes
    ----------
    name : str
        What it is, in words (``"arm"``, ``"target"``).
    color : str
        One of :data:`MEANING_COLOURS`.
    linestyle : str
        A matplotlib line style (``"-"``, ``"--"``, ``":"``; ``"none"`` for a
        marker alone).
    marker : str
        A matplotlib marker (``"o"``, ``"X"``), an arrow style for arrows
        (``"-|>"``, ``"->"``), ``"///"`` for a hatched edge, ``""`` for none.
    """

    name: str
    color: str
    linestyle: str
    marker: str

    def line(self) -> dict[str, Any]:
        """The role as keyword arguments of :meth:`matplotlib.axes.Axes.plot`.

        Examples
        --------
        >>> TARGET.line()
        {'color': '#000000', 'linestyle': 'none', 'marker': 'X'}
        >>> PATH.line()
        {'color': '#000000', 'linestyle': ':'}
        """
        options: dict[str, Any] = {"color": self.color, "linestyle": self.linestyle}
        if self.marker and self.marker in MarkerStyle.markers:  # not an arrow or hatch
            options["marker"] = self.marker
        return options


ARM = Role("arm", BLUE, "-", "o")
#: The elbow-down branch looks like any arm; the elbow-up branch differs in all three.
ELBOW_DOWN = ARM
ELBOW_UP = Role("elbow-up branch", VERMILLION, "--", "D")
BASE = Role("base", BLACK, "none", "s")
TARGET = Role("target", BLACK, "none", "X")
PATH = Role("tip's path", BLACK, ":", "")
REACH = Role("reach boundary", GREY, "--", "")
FORCE = Role("force", VERMILLION, "-", "-|>")
TORQUE = Role("torque", BLACK, "-", "->")
ELLIPSE = Role("ellipse", SKY_BLUE, "-", "")
WALL = Role("wall", BLACK, "-", "///")

#: Every role, by name (ELBOW_DOWN is ARM: one look, listed once).
ROLES = {
    role.name: role
    for role in (ARM, ELBOW_UP, BASE, TARGET, PATH, REACH, FORCE, TORQUE, ELLIPSE, WALL)
}

#: Lines told apart by order (the columns of a time series, plain ``ax.plot``
#: calls): colour and line style both change from one to the next.  A fifth
#: line repeats the first: label lines directly beyond four.
SERIES = (
    Role("series 1", BLUE, "-", ""),
    Role("series 2", VERMILLION, "--", ""),
    Role("series 3", BLACK, "-.", ""),
    Role("series 4", GREY, ":", ""),
)

#: Pixels per inch of a figure at its intended size: the CSS inch, so that a
#: matplotlib point is a CSS point on the page.
DPI = 96
#: Stored pixels per displayed pixel (a "retina" PNG): :data:`twolink_course.inline.PIXEL_SCALE`.
PIXEL_SCALE = inline.PIXEL_SCALE
#: Smallest text, in points at display size.
MIN_FONT_PT = 9.0
#: Body text (axis labels, titles are one point larger).
FONT_PT = 10.0
#: Tick labels, legends, notes on figures.
SMALL_FONT_PT = 9.0


def prop_cycle() -> Cycler[str, str]:
    """The colour and line-style cycle of :data:`SERIES`, for ``axes.prop_cycle``.

    Examples
    --------
    >>> [entry["linestyle"] for entry in prop_cycle()]
    ['-', '--', '-.', ':']
    """
    return cycler(
        color=[role.color for role in SERIES],
        linestyle=[role.linestyle for role in SERIES],
    )


#: The rcParams :func:`use` sets (and only these).
RC: dict[str, Any] = {
    "figure.dpi": DPI,
    "savefig.dpi": "figure",
    "figure.facecolor": BACKGROUND,
    "axes.facecolor": BACKGROUND,
    "font.size": FONT_PT,
    "axes.labelsize": FONT_PT,
    "axes.titlesize": FONT_PT + 1,
    "figure.titlesize": FONT_PT + 1,
    "xtick.labelsize": SMALL_FONT_PT,
    "ytick.labelsize": SMALL_FONT_PT,
    "legend.fontsize": SMALL_FONT_PT,
    "legend.title_fontsize": SMALL_FONT_PT,
    "axes.prop_cycle": prop_cycle(),
    "lines.linewidth": 1.8,
    "grid.alpha": 0.3,
    "image.cmap": "cividis",
    # every figure fits its canvas (labels, titles and legends inside), laid out
    # at each draw; the inline output then needs no second, cropping draw
    "figure.constrained_layout.use": True,
}


def use() -> bool:
    """Apply the course style; call it once, in a chapter's first code cell.

    Sets the matplotlib ``rcParams`` listed in :data:`RC` (figure resolution
    96 dpi, font sizes, the :data:`SERIES` colour and line-style cycle, a
    colour-blind-safe colour map, constrained layout), and, when running in IPython, installs
    :func:`twolink_course.inline.install`'s figure formatter (a PNG at twice the
    pixels, shown at its intended size, with its text alternative).  Nothing
    else changes.  Calling it again changes nothing more.

    Returns
    -------
    bool
        Whether the notebook formatter was installed (False outside IPython).

    Examples
    --------
    >>> with context():
    ...     installed = use()
    ...     matplotlib.rcParams["figure.dpi"], installed
    (96.0, False)
    """
    matplotlib.rcParams.update(RC)
    return inline.install()


@contextmanager
def context() -> Iterator[None]:
    """The style's rcParams inside a ``with`` block only (a script, a test).

    Examples
    --------
    >>> with context():
    ...     matplotlib.rcParams["legend.fontsize"]
    9.0
    """
    with matplotlib.rc_context(RC):
        yield
