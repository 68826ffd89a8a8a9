"""What the grader runs in a submission's kernel after each check cell: the answers, taken out as data.

The grader (``tools/grade.py``) inserts a cell after each restored check
cell; the cell executes this file's source (and that of
``twolink_course/exercises/forbidden.py``, from the grader's own copy) in a
namespace of its own and calls :func:`report` with a request: the exercise,
its answers' names, for a function part the calls to make (the visible ones,
then hidden ones drawn from a seed the kernel never holds) and the package's
callables it forbids, and for a value exercise graded on hidden inputs the
answer cell's source and the draws of inputs to run it on.  :func:`report`
publishes display outputs of MIME type :data:`MIME`:

- first the answers as the notebook computed them (each encoded as plain
  data: numbers, a bool, a text, "unsolved", or the name of a type it cannot
  read), each function part's return values on the grader's calls (with its
  parameters' names, and the first forbidden call it made), and the
  :func:`fingerprints` of what a submission could replace to fool the probe;
- then, for each draw of hidden inputs, the answers the answer cell computes
  from them (run in a copy of the notebook's namespace, the draw's inputs
  bound, the answers' old values removed).

The verdicts are computed by the grader, outside the kernel, from this data
alone.  Only the standard library and numpy are used (plus ``twolink``'s
``TwoLinkArm`` to build the arms of calls and draws), each imported in the
function that needs it.

>>> encode(1.5), encode([1, 2]), encode(True), encode(...)
({'numbers': 1.5}, {'numbers': [1.0, 2.0]}, {'bool': True}, {'unsolved': True})
>>> encode(float("nan")), encode(object())
({'numbers': 'nan'}, {'unreadable': 'object'})
"""

from __future__ import annotations

from typing import Any

#: The MIME type of the probe's outputs.
MIME = "application/vnd.twolink.probe+json"
#: Texts and messages longer than this are cut (a flood cannot pass through the probe).
MAX_TEXT = 2_000
#: Answers with more numbers than this are not read.
MAX_NUMBERS = 100_000

#: What a submission could replace to change what the probe sees or sends: ``module: attributes``.
WATCHED = {
    "twolink_course.selfcheck": ("check", "_hint", "parse_line"),
    "twolink_course.exercises": ("get", "is_unsolved"),
    "twolink_course.exercises.judging": (
        "judge",
        "judge_function",
        "read_answer",
        "agrees",
        "_matches",
    ),
    "twolink_course.exercises.stored": ("specification", "decode", "exercise_numbers"),
    "json": ("dumps", "loads"),
    "IPython.display": ("display", "publish_display_data"),
    "sys": ("setprofile", "getprofile"),
    "threading": ("setprofile", "getprofile"),
    "contextlib": ("redirect_stdout", "redirect_stderr"),
    "jupyter_client.session": ("Session",),
}
#: Builtins the probe itself relies on.
WATCHED_BUILTINS = (
    "print",
    "exec",
    "compile",
    "isinstance",
    "__import__",
    "getattr",
    "callable",
    "dict",
    "type",
)
#: Methods of the running kernel's objects that carry the probe's outputs: ``(path, attribute)``.
WATCHED_KERNEL = (
    ("kernel.session", "send"),
    ("kernel.session", "pack"),
    ("kernel.session", "serialize"),
    ("display_pub", "publish"),
)
#: Where the packages a notebook may legitimately register kernel event callbacks from.
TRUSTED_CALLBACKS = (
    "IPython",
    "ipykernel",
    "matplotlib",
    "matplotlib_inline",
    "ipympl",
    "ipywidgets",
)


def _code_digest(code: Any, hasher: Any) -> None:
    hasher.update(code.co_code)
    hasher.update(repr((code.co_names, code.co_varnames, code.co_freevars)).encode())
    for constant in code.co_consts:
        if hasattr(constant, "co_code"):
            _code_digest(constant, hasher)
        else:
            hasher.update(repr(constant).encode())


def fingerprint(value: Any) -> str:
    """A digest of what ``value`` is: its type, name and code.

    A Python function's own code, never that of what it says it wraps (a
    replacement made with ``functools.wraps`` carries the original as
    ``__wrapped__``, and is told apart); a bound method's function's code;
    for a class, its methods' code; only a C-level wrapper without code of
    its own (``functools.cache``) is known by what it wraps.
    """
    import hashlib

    hasher = hashlib.sha256()
    hasher.update(repr(type(value)).encode())
    hasher.update(repr(getattr(value, "__qualname__", None)).encode())
    hasher.update(repr(getattr(value, "__module__", None)).encode())
    code = getattr(value, "__code__", None)
    if code is None:
        code = getattr(getattr(value, "__func__", None), "__code__", None)
    if code is None and type(value).__module__ == "functools":
        code = getattr(getattr(value, "__wrapped__", None), "__code__", None)
    if code is not None:
        _code_digest(code, hasher)
    elif isinstance(value, type):
        for name in sorted(vars(value)):
            method = getattr(vars(value)[name], "__code__", None)
            if method is not None:
                hasher.update(name.encode())
                _code_digest(method, hasher)
    return hasher.hexdigest()[:16]


def fingerprints(shell: Any = None) -> dict[str, str]:
    """The fingerprints of everything :data:`WATCHED`, the builtins used, the kernel's
    message path, the notebook's name ``selfcheck`` and its kernel event callbacks."""
    import builtins
    import importlib
    import sys

    found: dict[str, str] = {}
    for module_name, attributes in WATCHED.items():
        try:
            module = importlib.import_module(module_name)
        except Exception:  # absent here: the genuine kernel lacks it too
            module = None
        found[module_name] = repr(getattr(module, "__file__", None))
        for attribute in attributes:
            found[f"{module_name}.{attribute}"] = fingerprint(
                getattr(module, attribute, None)
            )
    for name in WATCHED_BUILTINS:
        value = getattr(builtins, name, None)
        found[f"builtins.{name}"] = fingerprint(value) + (
            ""
            if getattr(value, "__self__", None) is builtins or isinstance(value, type)
            else " (replaced)"
        )
    if shell is not None:
        for path, attribute in WATCHED_KERNEL:
            owner = shell
            for part in path.split("."):
                owner = getattr(owner, part, None)
            found[f"kernel {path}.{attribute}"] = fingerprint(
                getattr(owner, attribute, None)
            )
        callbacks = []
        for event, registered in sorted(getattr(shell.events, "callbacks", {}).items()):
            for callback in registered:
                module = str(getattr(callback, "__module__", None) or "")
                if module.split(".")[0] not in TRUSTED_CALLBACKS:
                    callbacks.append(
                        f"{event}: {getattr(callback, '__qualname__', type(callback).__name__)}"
                    )
        found["kernel event callbacks of the notebook's own"] = repr(callbacks)
        module = sys.modules.get("twolink_course.selfcheck")
        name = shell.user_ns.get("selfcheck", module)
        found["the notebook's selfcheck"] = (
            "the module" if module is not None and name is module else "something else"
        )
    return found


def _numbers(array: Any) -> Any:
    """Nested lists of floats, a non-finite number written as ``"nan"``, ``"inf"`` or ``"-inf"``."""
    import math

    def plain(value: Any) -> Any:
        if isinstance(value, list):
            return [plain(item) for item in value]
        return value if math.isfinite(value) else repr(float(value))

    return plain(array.astype(float).tolist())


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
            return {"complex": [_numbers(np.real(array)), _numbers(np.imag(array))]}
        numbers = _numbers(array.astype(float))
    except (TypeError, ValueError, OverflowError):
        return {"unreadable": type(value).__name__[:100]}
    return {"numbers": numbers}


def decode_input(data: Any) -> Any:
    """One input of a draw, as :func:`grade_plan.encode_input` wrote it: an arm, an array, a number..."""
    import numpy as np

    kind, value = next(iter(data.items()))
    if kind == "arm":
        from twolink import TwoLinkArm

        fields = {name: decode_input(item) for name, item in value.items()}
        return TwoLinkArm(**fields)
    if kind == "array":
        return np.array(value["values"], dtype=value["dtype"])
    if kind == "tuple":
        return tuple(decode_input(item) for item in value)
    if kind == "list":
        return [decode_input(item) for item in value]
    if kind == "dict":
        return {key: decode_input(item) for key, item in value}
    return value  # "float", "int", "str", "bool", "none"


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


def _parameters(function: Any) -> list[list[Any]] | None:
    """The function's parameters as ``[name, kind, has a default]``, or None (no signature)."""
    import inspect

    try:
        signature = inspect.signature(function)
    except (TypeError, ValueError):
        return None
    return [
        [p.name, p.kind.name, p.default is not inspect.Parameter.empty]
        for p in signature.parameters.values()
    ]


def _calls(
    function: Any, calls: list[dict[str, Any]], forbidden: list[str], unavailable: Any
) -> dict[str, Any]:
    """``function`` called on each of ``calls`` (arguments by name), the ``forbidden`` callables
    unavailable: each return value encoded or what it raised, its parameters, the first forbidden call."""
    if not callable(function):
        return {"calls": [encode(function)]}
    results = []
    called: list[str] = []
    for arguments in calls:
        made = _arguments(arguments)
        with unavailable(forbidden) as now:
            try:
                result: Any = function(**made)
            except Exception as error:  # the student's function may raise anything
                result = {
                    "raised": type(error).__name__[:100],
                    "message": str(error)[:MAX_TEXT],
                }
        called += now
        results.append(
            result
            if isinstance(result, dict) and "raised" in result
            else encode(result)
        )
        if called:
            break
    return {
        "calls": results,
        "parameters": _parameters(function),
        "forbidden": called[0] if called else None,
    }


def _rerun(
    shell: Any, number: str, rerun: dict[str, Any], names: list[str], publish: Any
) -> None:
    """Run the answer cell on each draw of hidden inputs, in a copy of the namespace; publish each draw's answers."""
    import contextlib
    import io

    code = compile(
        shell.transform_cell(rerun["source"]),
        f"<exercise {number}, other inputs>",
        "exec",
    )
    for index, draw in enumerate(rerun["draws"]):
        namespace = dict(shell.user_ns)
        for name in names:
            namespace.pop(name, None)
        namespace.update({name: decode_input(data) for name, data in draw.items()})
        sink = io.StringIO()
        found: dict[str, Any] = {"exercise": number, "draw": index}
        try:
            with contextlib.redirect_stdout(sink), contextlib.redirect_stderr(sink):
                exec(code, namespace)
        except Exception as error:  # the student's code may raise anything
            found["raised"] = type(error).__name__[:100]
        found["answers"] = {
            name: encode(namespace[name]) if name in namespace else {"missing": True}
            for name in names
        }
        publish({MIME: found})


def report(request: dict[str, Any], unavailable: Any) -> None:
    """Publish the answers of ``request["exercise"]``, then those on each hidden draw (outputs of type :data:`MIME`).

    ``unavailable``: :func:`twolink_course.exercises.forbidden.unavailable`, from the grader's copy.
    """
    from IPython import get_ipython
    from IPython.display import publish_display_data

    shell = get_ipython()
    user_namespace = shell.user_ns
    answers: dict[str, Any] = {}
    for name in request["names"]:
        if name not in user_namespace:
            answers[name] = {"missing": True}
        elif name in request["calls"]:
            answers[name] = _calls(
                user_namespace[name],
                request["calls"][name],
                request["forbidden"].get(name, []),
                unavailable,
            )
        else:
            answers[name] = encode(user_namespace[name])
    publish_display_data(
        {
            MIME: {
                "exercise": request["exercise"],
                "answers": answers,
                "fingerprints": fingerprints(shell),
            }
        }
    )
    rerun = request.get("rerun")
    if rerun:
        values = [name for name in request["names"] if name not in request["calls"]]
        _rerun(shell, request["exercise"], rerun, values, publish_display_data)
