"""twolink_course: what shows, checks and grades a chapter of the twolink course.

The arm and its mechanics are the library, :mod:`twolink`; this package stands
beside it and imports it, never the reverse.  It holds what a chapter needs
to be read, played with and graded:

- drawing: :mod:`~twolink_course.figure_style` (the course's figure style and
  colour roles), :mod:`~twolink_course.plot` (the arm, its paths, ellipses,
  forces and animations), :mod:`~twolink_course.diagrams` (DH frames and
  free bodies), :mod:`~twolink_course.video` (the blitting video writer);
- reading: :mod:`~twolink_course.alttext` (every figure's text alternative),
  :mod:`~twolink_course.inline` (figures as notebook outputs with it),
  :mod:`~twolink_course.display` (numbers, tables and bounds as sentences);
- playing: :mod:`~twolink_course.explorer` (sliders that move a figure drawn once),
  :mod:`~twolink_course.timing` (timing tables of the IK solvers);
- checking and grading: :mod:`~twolink_course.exercises` (each part's
  specification and its judge), :mod:`~twolink_course.selfcheck` (the check
  cells), :mod:`~twolink_course.runmode` (the grading switch);
- the coursework the course grew from, reproduced:
  :mod:`~twolink_course.sources`.

It needs the course's dependencies (``pip install "twolink[course]"``:
matplotlib, ipywidgets, ipympl, JupyterLab, ...); ``pip install twolink``
alone gives the library.  Import the modules by name
(``from twolink_course import plot, explorer``): ``import twolink_course``
loads none of them.
"""

import importlib.util

# The kit's modules draw with matplotlib: without the course's dependencies, say what to install.
if importlib.util.find_spec("matplotlib") is None:
    raise ImportError(
        "twolink_course (the course kit) needs the course's dependencies, which are not "
        'installed: pip install "twolink[course]" installs them (pip install twolink '
        "alone gives the library, twolink)",
        name="matplotlib",
    )

__all__: list[str] = []
