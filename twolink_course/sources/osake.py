"""The OSAKE mini-project, reproduced: a desk arm's DH transform, Jacobian and C++ programs.

The mini-project studied a small desk arm, "OSAKE": link lengths
``L1 = 10 cm``, ``L2 = 11.5 cm`` and its plane of motion ``d = 6.5 cm`` above
the base frame.  Its final ``H_0^2`` and 6x2 geometric Jacobian, at the top
of its work, were right; the step-by-step derivation below them was not, and
its two C++ programs have mistakes of their own.  Each function here
reproduces one of those steps or programs as the source did it, so that
chapter 1 and chapter 3 of the course (and the tests) can show the source's
result coming out of the source's method before correcting it.  Each fact
rests on an item of the course's source record,
``notebooks/source_record.ipynb`` (anchors ``#h3-1`` ... ``#h3-5``):

- :func:`h02_as_expanded`: the hand-expanded ``H_0^2`` (``cos q1 cos q2`` and
  ``sin q1 cos q2`` where ``cos(q1+q2)`` and ``sin(q1+q2)`` belong, ``l1`` and
  ``l2`` swapped in the position column; ``source_record.ipynb#h3-1``);
- :func:`jacobian_as_printed`: the 6x2 Jacobian the derivation prints under
  its recipe, read as products (the only reading that gives its numbers):
  its two position columns are ``(l1 + l2 c2)(-s1, c1)`` and
  ``l2 s2 (-s1, c1)``, parallel at every pose, so the printed matrix is
  singular everywhere; at ``q = (30, 45)`` deg it gives
  ``[[-9.07, -4.07], [15.70, 7.04]]`` cm, where the right block is
  ``[[-16.11, -11.11], [11.64, 2.98]]`` (``source_record.ipynb#h3-2``);
- :func:`d02_tip_as_written`: the vector ``d_0^2`` written under the expanded
  ``H_0^2``, a third tip, (12.04, 12.73) cm at ``q = (30, 45)`` deg
  (``source_record.ipynb#h3-5``);
- :func:`cpp_fk_tip`: the C++ forward-kinematics program (link lengths read
  into ``int``, so 11.5 becomes 11, a 5 mm error; no z-offset in ``H01``, so
  the 6.5 cm height is dropped; a triple-loop matrix product, which is right;
  ``source_record.ipynb#h3-3``);
- :func:`velocity_program_speed`: the C++ velocity program (angles meant in
  degrees passed to ``cos``/``sin``, 3 deg/s used as 3 rad/s, the linear angle
  functions differentiated by a forward difference, the tip's linear speed
  called its "end-tip angular velocity"; ``source_record.ipynb#h3-4``).  The
  source shows no output of it: run as written, at its ``t = 2`` s, it gives
  10.8975 cm/s (reproduced, never printed), where the right tip speed is
  0.9757 cm/s.

Lengths are in the source's unit, centimetres (as it typed them); angles are
plain numbers handed to ``cos``/``sin``, i.e. radians, unless a docstring
says the source meant degrees.  Nothing here is for new code: the correct
versions are :meth:`twolink.TwoLinkArm.transforms`,
:meth:`twolink.TwoLinkArm.geometric_jacobian` and
:meth:`twolink.TwoLinkArm.tip_velocity`.
"""

from __future__ import annotations

import re
from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from twolink._validate import as_configuration, as_finite_scalar, as_pairs

__all__ = [
    "L1_CM",
    "L2_CM",
    "D_CM",
    "h02_as_expanded",
    "jacobian_as_printed",
    "d02_tip_as_written",
    "cpp_read_int",
    "matmul_triple_loop",
    "cpp_fk_tip",
    "velocity_program_speed",
]

L1_CM = 10.0
"""Link 1 of the OSAKE arm, cm."""
L2_CM = 11.5
"""Link 2 of the OSAKE arm, cm."""
D_CM = 6.5
"""Height of the arm's plane above the base frame (first DH row's ``d``), cm."""


def _lengths(l1: float, l2: float) -> tuple[float, float]:
    return (
        as_finite_scalar(l1, "l1 (cm)", minimum=0.0, strictly=True),
        as_finite_scalar(l2, "l2 (cm)", minimum=0.0, strictly=True),
    )


def h02_as_expanded(
    q: ArrayLike, l1: float = L1_CM, l2: float = L2_CM, d: float = D_CM
) -> NDArray[np.float64]:
    """The source's hand-expanded ``H_0^2``, with both of its mistakes.

    Where ``cos(q1 + q2)`` belongs the expansion has ``cos q1 cos q2``, where
    ``sin(q1 + q2)`` belongs it has ``sin q1 cos q2`` (the ``sin q1 sin q2`` and
    ``cos q1 sin q2`` terms of the angle-sum formulas are lost), and the
    position column has ``l1`` and ``l2`` swapped:
    ``x = l2 cos q1 + l1 cos q1 cos q2``, ``y = l2 sin q1 + l1 sin q1 cos q2``.
    Its upper-left block has determinant ``cos^2 q2``, so it is a rotation
    only at ``q2 = 0`` or ``pi``; the tip is right only at ``q2 = 0``.

    Parameters
    ----------
    q : array_like, shape (..., 2)
        Joint angles ``(q1, q2)``, radians.
    l1, l2 : float
        Link lengths (> 0), cm.
    d : float
        Height of the arm's plane, cm.

    Returns
    -------
    numpy.ndarray, shape (..., 4, 4)

    Examples
    --------
    >>> H = h02_as_expanded(np.radians([30.0, 45.0]))
    >>> H[:2, 3].round(3)                 # the right tip is (11.637, 16.108) cm
    array([16.083,  9.286])
    >>> round(float(np.linalg.det(H[:2, :2])), 3)   # cos^2 45 deg, not 1
    0.5
    >>> np.allclose(h02_as_expanded([0.7, 0.0])[:2, 3], (L1_CM + L2_CM) * np.array([np.cos(0.7), np.sin(0.7)]))
    True
    """
    q = as_pairs(q, "q (rad)")
    l1, l2 = _lengths(l1, l2)
    d = as_finite_scalar(d, "d (cm)")
    c1, s1, c2 = np.cos(q[..., 0]), np.sin(q[..., 0]), np.cos(q[..., 1])
    H = np.zeros(q.shape[:-1] + (4, 4))
    H[..., 0, 0], H[..., 0, 1] = c1 * c2, -s1 * c2
    H[..., 1, 0], H[..., 1, 1] = s1 * c2, c1 * c2
    H[..., 2, 2] = H[..., 3, 3] = 1.0
    H[..., 0, 3] = l2 * c1 + l1 * c1 * c2
    H[..., 1, 3] = l2 * s1 + l1 * s1 * c2
    H[..., 2, 3] = d
    return H


def jacobian_as_printed(
    q: ArrayLike, l1: float = L1_CM, l2: float = L2_CM
) -> NDArray[np.float64]:
    """The 6x2 Jacobian the source's derivation printed, read as products: singular everywhere.

    The derivation writes its recipe with ``(d_2^0 - d_1^0)`` in both columns,
    then states that ``d_1^0`` is the zero matrix (although it had written
    ``d_1^0 = (l1 c1, l1 s1, d)``, the elbow, just above) and that ``R_0^0`` is
    the 4x4 identity (``R_0^0`` is 3x3).  The matrix printed under it follows
    neither reading of that recipe: column 1 does contain the ``l1`` terms
    (the lever from the base, as ``z_0 x (o_2 - o_0)`` needs) and column 2
    does not, but both columns carry the product error of the source's
    expanded ``H_0^2`` (:func:`h02_as_expanded`): products of single-angle
    terms where ``sin(q1 + q2)`` and ``cos(q1 + q2)`` belong.  Read as
    products, the only reading that gives its numbers at ``q = (30, 45)`` deg
    (``source_record.ipynb#h3-2``), the printed position block is::

        column 1 = (-l2 s1 c2 - l1 s1,  l2 c1 c2 + l1 c1) = (l1 + l2 c2) (-s1, c1)
        column 2 = (        -l2 s1 s2,          l2 c1 s2) =      l2 s2  (-s1, c1)

    Both columns are multiples of ``(-s1, c1)``: they are **parallel** at
    every pose (not equal: their lengths differ), so the printed block has
    determinant 0 for every ``q``.  At ``q2 = 45`` deg, where ``cos q2 = sin
    q2``, the numbers hide it; at ``q = (30, 60)`` deg the printed determinant
    is 0 while the right one, ``l1 l2 sin q2``, is 99.6 cm^2.

    Rows: the ``v_x`` and ``v_y`` rows are the printed matrix as read above;
    the ``v_z`` row (0) and the ``omega`` rows (``(0, 0, 1)`` for both
    joints), which it prints as the right Jacobian has them, complete the
    6x2 shape of :meth:`twolink.TwoLinkArm.geometric_jacobian`.

    Parameters
    ----------
    q : array_like, shape (..., 2)
        Joint angles ``(q1, q2)``, radians.
    l1, l2 : float
        Link lengths (> 0), cm.

    Returns
    -------
    numpy.ndarray, shape (..., 6, 2)
        Rows ``v_x, v_y, v_z`` (cm per rad) and ``omega_x, omega_y, omega_z``
        (1 per rad), one column per joint.

    Examples
    --------
    The printed matrix at ``q = (30, 45)`` deg, cm per rad, to two decimals
    (the right block is ``[[-16.11, -11.11], [11.64, 2.98]]``):

    >>> from twolink_course.display import rounded
    >>> J = jacobian_as_printed(np.radians([30.0, 45.0]))
    >>> rounded(J[0], 2), rounded(J[1], 2)          # v_x row, v_y row
    ('(-9.07, -4.07)', '(15.70, 7.04)')
    >>> J[2:, 0], J.shape
    (array([0., 0., 0., 1.]), (6, 2))

    Singular at every pose: at ``(30, 60)`` deg too, where the right block's
    determinant is ``l1 l2 sin 60 deg``:

    >>> J_60 = jacobian_as_printed(np.radians([30.0, 60.0]))[:2]
    >>> bool(abs(np.linalg.det(J_60)) < 1e-12), round(L1_CM * L2_CM * float(np.sin(np.radians(60.0))), 1)
    (True, 99.6)
    """
    q = as_pairs(q, "q (rad)")
    l1, l2 = _lengths(l1, l2)
    c1, s1 = np.cos(q[..., 0]), np.sin(q[..., 0])
    c2, s2 = np.cos(q[..., 1]), np.sin(q[..., 1])
    J = np.zeros(q.shape[:-1] + (6, 2))
    # l2 (-s12, c12) with single-angle products in their place, plus, in
    # column 1, the l1 lever from the base
    J[..., 0, 0] = -l2 * s1 * c2 - l1 * s1
    J[..., 1, 0] = l2 * c1 * c2 + l1 * c1
    J[..., 0, 1] = -l2 * s1 * s2
    J[..., 1, 1] = l2 * c1 * s2
    J[..., 5, :] = 1.0
    return J


def d02_tip_as_written(
    q: ArrayLike, l1: float = L1_CM, l2: float = L2_CM
) -> NDArray[np.float64]:
    """The tip ``(x, y)`` in cm that the vector ``d_0^2`` under the source's expanded ``H_0^2`` gives.

    That vector has ``l1`` and ``l2``, and sine and cosine, swapped
    (``source_record.ipynb#h3-5``): its x entry is
    ``l2 cos q1 sin q2 + l1 sin q1``, reproduced here with the y entry
    ``l2 sin q1 sin q2 + l1 cos q1`` (the same swaps; at ``q2 = 45`` deg,
    where ``sin q2 = cos q2``, the record's numbers cannot tell ``sin q2``
    from ``cos q2`` there).  It is a third tip, different from both the
    expanded ``H_0^2``'s (:func:`h02_as_expanded`) and the right one; the
    source never evaluates it.

    Parameters
    ----------
    q : array_like, shape (..., 2)
        Joint angles ``(q1, q2)``, radians.
    l1, l2 : float
        Link lengths (> 0), cm.

    Returns
    -------
    numpy.ndarray, shape (..., 2)

    Examples
    --------
    >>> d02_tip_as_written(np.radians([30.0, 45.0])).round(2)   # the right tip: (11.64, 16.11)
    array([12.04, 12.73])
    """
    q = as_pairs(q, "q (rad)")
    l1, l2 = _lengths(l1, l2)
    c1, s1, s2 = np.cos(q[..., 0]), np.sin(q[..., 0]), np.sin(q[..., 1])
    return np.stack([l2 * c1 * s2 + l1 * s1, l2 * s1 * s2 + l1 * c1], axis=-1)


def cpp_read_int(typed: str) -> int:
    """What C++'s ``std::cin >> n`` stores in an ``int n`` when the user types ``typed``.

    The stream reads the leading integer and stops at the first character
    that cannot belong to it: ``"11.5"`` gives 11 (the ``".5"`` stays in the
    stream).

    Parameters
    ----------
    typed : str
        What the user typed, e.g. ``"11.5"``.

    Returns
    -------
    int
        The integer ``cin`` stores.

    Raises
    ------
    ValueError
        If ``typed`` does not start with an integer (``cin`` would fail).

    Examples
    --------
    >>> cpp_read_int("11.5"), cpp_read_int("10"), cpp_read_int(" -3.9")
    (11, 10, -3)
    >>> cpp_read_int("abc")
    Traceback (most recent call last):
    ...
    ValueError: typed must start with an integer for `cin >> int`; got 'abc'
    """
    match = re.match(r"\s*([+-]?\d+)", str(typed))
    if match is None:
        raise ValueError(
            f"typed must start with an integer for `cin >> int`; got {typed!r}"
        )
    return int(match.group(1))


def matmul_triple_loop(
    left: Sequence[Sequence[float]], right: Sequence[Sequence[float]]
) -> list[list[float]]:
    """The matrix product ``(AB)_ij = sum_k A_ik B_kj`` by three nested loops, as the C++ program did.

    Correct (it is the definition) and slow; kept to compare with ``@``.

    Parameters
    ----------
    left, right : sequence of sequences of float
        The matrices as rows (nested lists, as in the C++ program); ``left``
        has as many columns as ``right`` has rows.

    Returns
    -------
    list of list of float
        The product, as rows.

    Examples
    --------
    >>> matmul_triple_loop([[1.0, 2.0], [3.0, 4.0]], [[0.0, 1.0], [1.0, 0.0]])
    [[2.0, 1.0], [4.0, 3.0]]
    """
    n_rows, n_inner, n_cols = len(left), len(right), len(right[0])
    if any(len(row) != n_inner for row in left):
        raise ValueError(
            f"left must have {n_inner} columns (the rows of right); got rows of lengths "
            f"{[len(row) for row in left]}"
        )
    product = [[0.0] * n_cols for _ in range(n_rows)]
    for i in range(n_rows):
        for j in range(n_cols):
            for k in range(n_inner):
                product[i][j] += left[i][k] * right[k][j]
    return product


def _dh_planar(theta: float, d: float, a: float) -> list[list[float]]:
    c, s = np.cos(theta), np.sin(theta)
    return [
        [c, -s, 0.0, a * c],
        [s, c, 0.0, a * s],
        [0.0, 0.0, 1.0, d],
        [0.0, 0.0, 0.0, 1.0],
    ]


def cpp_fk_tip(
    q: ArrayLike,
    l1_typed: str = "10",
    l2_typed: str = "11.5",
    d: float = D_CM,
    *,
    int_lengths: bool = True,
    drop_offset: bool = True,
) -> NDArray[np.float64]:
    """The tip ``(x, y, z)`` in cm as the source's C++ forward-kinematics program computed it.

    The program read the link lengths into ``int`` variables (so ``11.5``
    became 11, :func:`cpp_read_int`), built ``H01`` with a z-offset of 0 (the
    6.5 cm height ``d`` dropped) and multiplied ``H01 H12`` with triple loops
    (:func:`matmul_triple_loop`, which is right).  The two switches turn each
    mistake off, so that each one's share of the error can be measured.

    Parameters
    ----------
    q : array_like, shape (2,)
        Joint angles, radians (this reproduction passes them on as given).
    l1_typed, l2_typed : str
        The link lengths as the user typed them, cm.
    d : float
        The arm's real height, cm (used only with ``drop_offset=False``).
    int_lengths : bool
        Read the lengths into ``int`` as the source did (``False``: as doubles).
    drop_offset : bool
        Put 0 in ``H01``'s z-offset as the source did (``False``: ``d``).

    Returns
    -------
    numpy.ndarray, shape (3,)

    Examples
    --------
    >>> cpp_fk_tip(np.radians([30.0, 45.0])).round(4)      # the right tip: (11.6367, 16.1081, 6.5)
    array([11.5073, 15.6252,  0.    ])
    >>> cpp_fk_tip(np.radians([30.0, 45.0]), int_lengths=False, drop_offset=False).round(4)
    array([11.6367, 16.1081,  6.5   ])
    """
    q = as_configuration(q, "q")
    if int_lengths:
        l1, l2 = float(cpp_read_int(l1_typed)), float(cpp_read_int(l2_typed))
    else:
        l1, l2 = float(l1_typed), float(l2_typed)
    l1, l2 = _lengths(l1, l2)
    height = 0.0 if drop_offset else as_finite_scalar(d, "d (cm)")
    H01 = _dh_planar(q[0], height, l1)
    H12 = _dh_planar(q[1], 0.0, l2)
    H02 = matmul_triple_loop(H01, H12)
    return np.array([H02[0][3], H02[1][3], H02[2][3]])


def velocity_program_speed(
    t: float = 2.0, l1: float = L1_CM, l2: float = L2_CM, step: float = 1e-6
) -> float:
    """The number the source's C++ velocity program gives when run: its "end-tip angular velocity".

    The program states all its details (``source_record.ipynb#h3-4``), and
    this function follows them: ``double l1 = 10.0; double l2 = 11.5;`` (cm),
    the angle functions ``theta1 = 3 t`` and ``theta2 = 60``, both meant in
    degrees, evaluated at ``t = 2`` s and passed to ``cos``/``sin``, which take
    radians.  It differentiates the two angle functions numerically by a
    **forward** difference with ``delta_t = 1e-6`` s; for these linear
    functions that only returns their slopes ``(3, 0)`` (to round-off), which
    it uses as joint rates in rad/s, although 3 was meant as 3 deg/s.  From
    those angles and rates it forms the tip velocity ``(vx, vy)`` (this
    reproduction does so with the planar Jacobian, ``J(theta) theta_dot``) and
    computes ``sqrt(vx^2 + vy^2)``, the tip's **linear** speed in cm/s, under
    the name "end-tip angular velocity".  The source shows no output of this
    program: run as written it gives 10.8975 (reproduced here; never call it
    a printed value).  (Its comment "relation for theta2" stands above
    theta1's function, and it computes the tip position ``px``, ``py`` and
    never uses it; neither changes the number.)

    The number is ``3 |p(60 rad)|``, 3 rad/s times the tip's distance from the
    base at ``q2 = 60`` rad (3.63 cm); it does not depend on ``t``: the arm turns
    rigidly about the base.  The right tip speed at ``t = 2`` s, with
    ``q = (6, 60)`` deg and ``q_dot = (3, 0)`` deg/s, is 0.9757 cm/s
    (:meth:`twolink.TwoLinkArm.tip_velocity` of :data:`twolink.arms.osake`);
    the right angular velocity of the arm is ``3 deg/s = 0.05236 rad/s``.

    Parameters
    ----------
    t : float
        Time, s (the program's ``t = 2``).
    l1, l2 : float
        Link lengths (> 0), cm (the program's 10.0 and 11.5).
    step : float
        Forward-difference step (> 0), s (the program's ``delta_t = 1e-6``).

    Returns
    -------
    float
        The number the program computes, cm/s (a linear speed; the source
        called it an angular velocity).

    Examples
    --------
    >>> round(velocity_program_speed(), 4)          # the program's t = 2, delta_t = 1e-6
    10.8975
    >>> from twolink import arms
    >>> q, q_dot = np.radians([3.0 * 2.0, 60.0]), np.radians([3.0, 0.0])   # t = 2 s, in radians
    >>> round(100 * float(np.linalg.norm(arms.osake.tip_velocity(q, q_dot))), 4)   # the right tip speed, cm/s
    0.9757
    """
    t = as_finite_scalar(t, "t (s)")
    step = as_finite_scalar(step, "step (s)", minimum=0.0, strictly=True)
    l1, l2 = _lengths(l1, l2)

    def angles(
        time: float,
    ) -> NDArray[np.float64]:  # the numbers the program fed to cos/sin ("degrees")
        return np.array([3.0 * time, 60.0])

    theta = angles(t)
    theta_dot = (
        angles(t + step) - angles(t)
    ) / step  # forward difference: the slope (3, 0), to round-off
    q12 = theta[0] + theta[1]
    J = np.array(
        [
            [-l1 * np.sin(theta[0]) - l2 * np.sin(q12), -l2 * np.sin(q12)],
            [l1 * np.cos(theta[0]) + l2 * np.cos(q12), l2 * np.cos(q12)],
        ]
    )
    vx, vy = J @ theta_dot
    return float(np.sqrt(vx**2 + vy**2))
