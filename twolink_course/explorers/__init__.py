"""The chapters' explorers: each figure drawn once and moved to the controls' values.

One module per chapter (``ch4``, ...).  A chapter builds its explorer in a few
lines that say what is drawn against what: it makes the figure object of its
chapter's module and wires that object's ``update`` and ``describe`` to the
sliders with :class:`twolink_course.explorer.Explorer`.  How the figure keeps up
with the hand (artists drawn once and moved, heavy work done once, a quicker
solver checked against the exact one) lives here, with the tests that check it
(``tests/course/test_explorers_chN.py``).
"""
