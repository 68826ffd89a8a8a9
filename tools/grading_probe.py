"""What the grader runs in a submission's kernel after each check cell: the answers, taken out as data.

The grader (``tools/grade.py``) inserts a cell after each restored check
cell; the cell executes this file's source in a namespace of its own with
``REQUEST`` set (the exercise, its answers' names, and for a function part
the calls to make).  :func:`report` publishes one display output of MIME
type :data:`MIME`: each answer encoded as plain data (numbers, a bool, a
text, "unsolved", or the name of a type it cannot read), each function
part's return values on the grader's calls, and the :func:`fingerprints`
of what a submission could replace to judge itself (the self-check, the
judging and store modules, the serializer).  The verdicts are computed by
the grader, outside the kernel, from this data alone; a fingerprint that
differs from the grader's own, or a probe cell that publishes nothing, is
reported as tampering.

Only the standard library and numpy are used (plus ``twolink.TwoLinkArm``
to build the arms of a function's calls), each imported afresh in
:func:`report`.

>>> encode(1.5), encode([1, 2]), encode(True), encode(...)
({'numbers': 1.5}, {'numbers': [1.0, 2.0]}, {'bool': True}, {'unsolved': True})
>>> encode(object())
{'unreadable': 'object'}
"""

from __future__ import annotations

from typing import Any

#: The MIME type of the probe's output.
MIME = "application/vnd.twolink.probe+json"
#: Texts and messages longer than this are cut (a flood cannot pass through the probe).
MAX_TEXT = 2_000
#: Answers with more numbers than this are not read.
MAX_NUMBERS = 100_000

#: What a submission could replace to pass without solving: ``module: attributes``.
WATCHED = {
    "twolink_course.selfcheck": ("check", "_hint", "parse_line"),
    "twolink_course.exercises": ("get", "is_unsolved"),
    "twolink_course.exercises.judging": (
        "judge",
        "judge_function",
        "read_answer",
        "_matches",
    ),
    "twolink_course.exercises.stored": ("specification", "decode", "exercise_numbers"),
    "json": ("dumps", "loads"),
    "IPython.display": ("display", "publish_display_data"),
}
#: Builtins the probe itself relies on.
WATCHED_BUILTINS = ("print", "exec", "compile", "isinstance", "__import__", "getattr")


def _code_digest(code: Any, hasher: Any) -> None:
    hasher.update(code.co_code)
    hasher.update(repr((code.co_names, code.co_varnames, code.co_freevars)).encode())
    for constant in code.co_consts:
        if hasattr(constant, "co_code"):
            _code_digest(constant, hasher)
        else:
            hasher.update(repr(constant).encode())


def fingerprint(value: Any) -> str:
    """A digest of what ``value`` is: its code (for a Python function), else its type and name."""
    import hashlib

    hasher = hashlib.sha256()
    function = getattr(value, "__wrapped__", value)  # functools.cache and the like
    code = getattr(function, "__code__", None)
    hasher.update(repr(type(value)).encode())
    hasher.update(repr(getattr(function, "__qualname__", None)).encode())
    hasher.update(repr(getattr(function, "__module__", None)).encode())
    if code is not None:
        _code_digest(code, hasher)
    return hasher.hexdigest()[:16]


def fingerprints(user_namespace: dict[str, Any]) -> dict[str, str]:
    """The fingerprints of everything :data:`WATCHED`, of the builtins used, and of the name ``selfcheck``."""
    import builtins
    import sys

    found: dict[str, str] = {}
    for module_name, attributes in WATCHED.items():
        module = sys.modules.get(module_name)
        found[module_name] = repr(getattr(module, "__file__", None))
        for attribute in attributes:
            found[f"{module_name}.{attribute}"] = fingerprint(
                getattr(module, attribute, None)
            )
    for name in WATCHED_BUILTINS:
        value = getattr(builtins, name, None)
        found[f"builtins.{name}"] = fingerprint(value) + (
            "" if getattr(value, "__self__", None) is builtins else " (replaced)"
        )
    module = sys.modules.get("twolink_course.selfcheck")
    found["the notebook's selfcheck"] = (
        "the module"
        if module is not None and user_namespace.get("selfcheck", module) is module
        else "something else"
    )
    return found


def encode(value: Any) -> dict[str, Any]:
    """An answer as plain data: numbers (nested lists), a bool, a text, unsolved, or unreadable."""
    import numpy as np

    if value is ... or value is None:
        return {"unsolved": True}
    if isinstance(value, (bool, np.bool_)):
        return {"bool": bool(value)}
    if isinstance(value, str):
        return {"text": value[:MAX_TEXT]}
    if callable(value) and not hasattr(value, "__array__"):
        return {"unreadable": "function"}
    try:
        if hasattr(value, "evalf"):  # sympy numbers and matrices
            value = value.evalf()
            if hasattr(value, "tolist"):
                value = value.tolist()
            else:
                value = float(value) if value.is_real else complex(value)
        array = np.asarray(value)
        if array.size > MAX_NUMBERS:
            return {"unreadable": f"array of {array.size} numbers"}
        if np.iscomplexobj(array):
            return {
                "complex": [np.real(array).tolist(), np.imag(array).tolist()],
            }
        numbers = array.astype(float)
    except (TypeError, ValueError, OverflowError):
        return {"unreadable": type(value).__name__[:100]}
    return {"numbers": numbers.tolist()}


def _arguments(arguments: dict[str, Any]) -> dict[str, Any]:
    import numpy as np

    from twolink import TwoLinkArm

    made: dict[str, Any] = {}
    for name, value in arguments.items():
        if isinstance(value, dict) and set(value) == {"arm"}:
            made[name] = TwoLinkArm(**value["arm"])
        elif isinstance(value, list):
            made[name] = np.array(value, dtype=float)
        else:
            made[name] = value
    return made


def _calls(function: Any, calls: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """``function`` called on each of ``calls`` (arguments by name): each return value encoded, or what it raised."""
    if not callable(function):
        return [encode(function)]
    results = []
    for arguments in calls:
        try:
            results.append(encode(function(**_arguments(arguments))))
        except Exception as error:  # the student's function may raise anything
            results.append(
                {"raised": type(error).__name__[:100], "message": str(error)[:MAX_TEXT]}
            )
    return results


def report(request: dict[str, Any], user_namespace: dict[str, Any]) -> None:
    """Publish the answers of ``request["exercise"]`` (one display output of type :data:`MIME`)."""
    from IPython.display import publish_display_data

    answers: dict[str, Any] = {}
    for name in request["names"]:
        if name not in user_namespace:
            answers[name] = {"missing": True}
        elif name in request["calls"]:
            answers[name] = {
                "calls": _calls(user_namespace[name], request["calls"][name])
            }
        else:
            answers[name] = encode(user_namespace[name])
    publish_display_data(
        {
            MIME: {
                "exercise": request["exercise"],
                "answers": answers,
                "fingerprints": fingerprints(user_namespace),
            }
        }
    )
