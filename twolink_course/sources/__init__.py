"""What the course's sources computed, reproduced: their methods, with their mistakes.

The course grew from four pieces of university coursework on the 2R arm.
Each module here reproduces one of them, method by method, so that a chapter
(and a test) can show the source's printed number coming out of the source's
own formula before the course corrects it.  Nothing here is meant for use in
new code: the rest of :mod:`twolink` holds the correct versions.

What each piece of coursework asked, computed, printed and got wrong is the
course's source record, ``notebooks/source_record.ipynb`` (a page of the
static site too): one anchor per fact, named after its item (``#h1-4``,
``#h3-2``, ...), which the modules' docstrings and the chapters' casebooks
link; ``tests/notebooks/test_source_record.py`` computes every number it gives with
these modules.

- :mod:`twolink_course.sources.mae6245`: MAE 6245 (inverse kinematics three
  ways, a1 = a2 = 10).
- :mod:`twolink_course.sources.compsys726`: COMPSYS726 (DH, Jacobian, the
  velocity table along y = 50).
- :mod:`twolink_course.sources.osake`: the OSAKE mini-project (L1 = 10 cm,
  L2 = 11.5 cm, base offset 6.5 cm).
- :mod:`twolink_course.sources.me639`: the ME 639 2R mini-project (l1 = l2 = 2 m, absolute
  angles, motor 2 on the ground).

Import the modules explicitly (``from twolink_course.sources import mae6245``).
"""
