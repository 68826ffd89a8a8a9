"""Preset arms from the course's source exercises.

The presets are frozen :class:`~twolink.TwoLinkArm` instances: use
:func:`dataclasses.replace` to make a variant, never mutate them.

``two_metre``
    l1 = l2 = 2 m, no joint limits (the wall, spring and line-tracking exercises).
``two_metre_limited``
    The same arm with both absolute link angles limited to [35, 145] deg:
    example limits of the course's choosing, suggested by the angle range of
    one source's workspace plot (``range(35, 145)`` deg, a plot range; that
    project states no joint limits).
``ten``
    a1 = a2 = 10 (units as in the source; read as metres here) with
    q1 in [0, 90] deg and q2 in [-90, 90] deg (the IK and circle exercises).
``osake``
    The "OSAKE" desk arm: L1 = 10 cm, L2 = 11.5 cm, base offset d = 6.5 cm.

Examples
--------
>>> from twolink import arms
>>> arms.osake.l1, arms.osake.l2, arms.osake.d
(0.1, 0.115, 0.065)
>>> np.degrees(arms.ten.q_max).round(6)
array([90., 90.])
"""

import numpy as np

from .arm import TwoLinkArm

__all__ = ["two_metre", "two_metre_limited", "ten", "osake"]

two_metre = TwoLinkArm(l1=2.0, l2=2.0)

two_metre_limited = TwoLinkArm(
    l1=2.0,
    l2=2.0,
    q_min=(np.radians(35.0), np.radians(35.0)),
    q_max=(np.radians(145.0), np.radians(145.0)),
    limit_convention="absolute",
)

ten = TwoLinkArm(
    l1=10.0,
    l2=10.0,
    q_min=(0.0, np.radians(-90.0)),
    q_max=(np.radians(90.0), np.radians(90.0)),
)

osake = TwoLinkArm(l1=0.10, l2=0.115, d=0.065)
