"""The package's own answer made unavailable while a learner's function is judged.

An exercise that asks for a function the package already has (``tip_position``
is ``arm.fk``) forbids it: its part lists the callables by dotted import path
(``PartSpec.forbidden``), and while :func:`unavailable` is active a call of any
of them, by whatever name it is reached (``arm.fk``, ``kinematics.fk``, an
alias, a copy of the function), raises :class:`ForbiddenCall` and is recorded.
The self-check (:func:`twolink_course.exercises.judging.judge_function`) and the
grader's probe in the learner's kernel (``tools/grading_probe.py``, which runs
this file's source from the grader's own copy) both use it.

The calls are seen by the interpreter's profile hook (:func:`sys.setprofile`,
and :func:`threading.setprofile` for threads started meanwhile): it sees every
Python function that starts, whatever name called it.  Standard library only.

>>> import twolink.kinematics
>>> from twolink import TwoLinkArm
>>> with unavailable(["twolink.kinematics.fk"]) as called:
...     try:
...         TwoLinkArm(1.0, 1.0).fk([0.0, 0.0])
...     except ForbiddenCall as error:
...         print(error)
this exercise asks you to write it yourself: kinematics.fk is the package's answer
>>> called
['twolink.kinematics.fk']
"""

from __future__ import annotations

import contextlib
import importlib
import sys
import threading
from collections.abc import Iterator, Sequence
from typing import Any

__all__ = ["ForbiddenCall", "unavailable", "shown_name", "reason", "resolve"]


class ForbiddenCall(Exception):
    """A call of a callable the exercise asks the learner not to use."""


def shown_name(path: str) -> str:
    """How a learner writes the callable at ``path``: a method on an arm as ``arm.fk``.

    >>> shown_name("twolink.arm.TwoLinkArm.fk"), shown_name("twolink.workspace.is_reachable")
    ('arm.fk', 'workspace.is_reachable')
    """
    parts = path.split(".")
    if len(parts) >= 2 and parts[-2][:1].isupper():  # a method of a class
        owner = parts[-2]
        instance = "arm" if owner.endswith("Arm") else owner[:1].lower() + owner[1:]
        return f"{instance}.{parts[-1]}"
    return ".".join(parts[-2:])


def reason(path: str) -> str:
    """Why a call of ``path`` fails the part, in words.

    >>> reason("twolink.arm.TwoLinkArm.joint_rates")
    "this exercise asks you to write it yourself: arm.joint_rates is the package's answer"
    """
    return (
        f"this exercise asks you to write it yourself: {shown_name(path)} is the "
        "package's answer"
    )


def resolve(path: str) -> Any:
    """The object at dotted import path ``path`` (a module's attribute, a class's method).

    >>> resolve("twolink.kinematics.fk").__name__
    'fk'
    >>> resolve("twolink.no_such_thing")
    Traceback (most recent call last):
    ...
    ValueError: forbidden call 'twolink.no_such_thing': no such callable (give a dotted import path such as 'twolink.kinematics.fk')
    """
    parts = path.split(".")
    for split in range(len(parts) - 1, 0, -1):
        try:
            found: Any = importlib.import_module(".".join(parts[:split]))
        except ImportError:
            continue
        try:
            for name in parts[split:]:
                found = getattr(found, name)
        except AttributeError:
            break
        if callable(found):
            return found
        break
    raise ValueError(
        f"forbidden call {path!r}: no such callable (give a dotted import path such "
        "as 'twolink.kinematics.fk')"
    )


def _code(found: Any) -> Any:
    """The code object that runs when ``found`` is called, or None (a builtin)."""
    for candidate in (found, getattr(found, "__func__", None)):
        code = getattr(candidate, "__code__", None)
        if code is not None:
            return code
    if isinstance(found, type):  # a class: its constructor
        for method in ("__init__", "__new__"):
            code = getattr(getattr(found, method, None), "__code__", None)
            if code is not None:
                return code
    return None


@contextlib.contextmanager
def unavailable(paths: Sequence[str]) -> Iterator[list[str]]:
    """While active, each callable of ``paths`` raises :class:`ForbiddenCall` when called.

    Yields the list of the paths called meanwhile (filled as they are), so a
    caller that catches the error itself is still found out.  The profile
    hooks in place before are put back at the end.
    """
    called: list[str] = []
    if not paths:
        yield called
        return
    by_code: dict[Any, str] = {}
    by_identity: dict[int, str] = {}
    for path in paths:
        found = resolve(path)
        code = _code(found)
        if code is not None:
            by_code[code] = path
        else:
            by_identity[id(found)] = path

    def hook(frame: Any, event: str, argument: Any) -> None:
        if event == "call":
            path = by_code.get(frame.f_code)
        elif event == "c_call":
            path = by_identity.get(id(argument))
        else:
            return
        if path is not None:
            called.append(path)
            raise ForbiddenCall(reason(path))

    before, before_threads = sys.getprofile(), threading.getprofile()
    sys.setprofile(hook)
    threading.setprofile(hook)
    try:
        yield called
    finally:
        sys.setprofile(before)
        threading.setprofile(before_threads)
