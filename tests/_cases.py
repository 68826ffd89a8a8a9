"""Test inputs shared by several test files (``conftest.py`` holds the arm and state strategies).

- ``BAD_NUMBERS``: what a number argument must refuse (shared validation, arm parameters).
- ``BAD_PAIRS``: what a one-pair argument (a target, a configuration) must refuse.
- ``stable_id``: a parametrize id that is the same in every process (xdist needs that).
- ``limited_arms``: arms with random joint limits in either convention.
"""

import threading

import numpy as np
from hypothesis import strategies as st

from conftest import angles, lengths
from twolink import TwoLinkArm

BAD_NUMBERS = [
    None,
    "12",
    "abc",
    True,
    False,
    1 + 2j,
    np.complex128(1.0),
    object(),
    [1.0],
    {"x": 1},
]

BAD_PAIRS = [
    [float("nan"), 1.0],
    [0.0, float("inf")],
    ["a", 1.0],
    [None, 1.0],
    [1 + 2j, 0.0],
    [1.0, 2.0, 3.0],
    [],
    [True, False],
    [10**400, 0.0],
    np.array([np.nan, 1.0]),
]


def stable_id(value):
    """A test id that is the same in every process (no memory addresses)."""
    return "object" if type(value) is object else repr(value)


@st.composite
def limited_arms(draw):
    """Arms with random joint limits in either convention (each range 0.05 rad .. 2 pi wide)."""
    l1 = draw(lengths)
    l2 = draw(st.floats(min_value=max(0.05, l1 / 20), max_value=min(20.0, l1 * 20)))
    low = np.array([draw(angles), draw(angles)])
    width = np.array(
        [draw(st.floats(0.05, 2 * np.pi)), draw(st.floats(0.05, 2 * np.pi))]
    )
    return TwoLinkArm(
        l1,
        l2,
        q_min=tuple(low),
        q_max=tuple(low + width),
        limit_convention=draw(st.sampled_from(["relative", "absolute"])),
    )


def in_fresh_thread(function, *args):
    """``function(*args)`` in a thread of its own, with no event loop running.

    Some tests run in a worker where an earlier test left an event loop marked
    as running (Playwright's sync API does): ``asyncio.run`` would refuse, and
    code that looks for a running loop would find one that never runs.
    """
    result, error = [], []

    def target():
        try:
            result.append(function(*args))
        except BaseException as exc:  # re-raised in the caller's thread
            error.append(exc)

    thread = threading.Thread(target=target)
    thread.start()
    thread.join(timeout=60)
    if thread.is_alive():
        raise TimeoutError(f"{function.__name__} did not return within 60 s")
    if error:
        raise error[0]
    return result[0]
