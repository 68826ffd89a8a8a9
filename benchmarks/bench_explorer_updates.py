"""The kernel's share of an explorer's move: one slider step, timed with no browser.

``benchmarks/bench_widgets.py`` measures what a student sees (key press to a
changed picture in JupyterLab); this one isolates the part the chapter's code
and :mod:`twolink_course.explorer` control.  Each chapter runs in a kernel (nbclient),
its explorers' canvases behave as with a browser attached (no PNG copy kept for
a page that is not there), then every control of every explorer (a slider's or a range's low end one
step, a choice's first two options) goes there and back ``--moves`` times through :meth:`twolink_course.explorer.Explorer.set`.

Prints per slider the median and worst time of one move [ms], the moves that
redrew the whole figure (slow: limits, labels or ticks changed) and the
artists redrawn on each quick move.  With the browser's ~25 ms of messages,
decoding and painting on these 2-core machines, a median under ~20 ms here
keeps the 50 ms of ``bench_widgets.py``.

Run with ``.venv/bin/python benchmarks/bench_explorer_updates.py`` (``--chapters 05 06``
for some, ``--quick``: chapter 1, two moves).
"""

from __future__ import annotations

import argparse
import json
import platform
import sys
from pathlib import Path

import nbformat
from nbclient import NotebookClient

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT), str(ROOT / "tools")]

import course_map  # noqa: E402

from twolink_course.display import markdown_table  # noqa: E402

# Runs in the chapter's kernel after its last cell; prints one JSON line.
MEASURE = """
import gc as _gc, json as _json, time as _time
from twolink_course.explorer import Explorer as _Explorer
_rows, _profiles = [], []
for _index, _explorer in enumerate(o for o in _gc.get_objects() if isinstance(o, _Explorer)):
    for _name, _control in _explorer.controls.items():
        _start = _control.value
        if hasattr(_control, "options"):  # a choice: its first two options
            _other = _control.options[1] if _start == _control.options[0] else _control.options[0]
        elif isinstance(_start, tuple):  # a range: its low end, as bench_widgets moves it
            _low = _start[0] + _control.step
            _other = (_low if _low <= _start[1] else _start[0] - _control.step, _start[1])
        else:
            _other = _start + _control.step if _start + _control.step <= _control.max else _start - _control.step
        _times, _full = [], _explorer.full_redraws
        for _value in [_other, _start] * MOVES:
            _t0 = _time.perf_counter()
            _explorer.set(**{_name: _value})
            _times.append((_time.perf_counter() - _t0) * 1000)
        if PROFILE:
            import cProfile as _cProfile, io as _io, pstats as _pstats
            _profile = _cProfile.Profile()
            _profile.enable()
            for _value in [_other, _start] * MOVES:
                _explorer.set(**{_name: _value})
            _profile.disable()
            _text = _io.StringIO()
            _pstats.Stats(_profile, stream=_text).sort_stats("cumulative").print_stats(30)
            _profiles.append(f"{_explorer._update.__name__}, {_name}:\\n{_text.getvalue()}")
        _rows.append([_index, _explorer._update.__name__, _name, _times,
                      _explorer.full_redraws - _full, len(_explorer._animated)])
print(_json.dumps([_rows, _profiles]))
"""


def measure(path: Path, moves: int, profile: bool = False) -> tuple[list, list]:
    notebook = nbformat.read(path, as_version=4)
    client = NotebookClient(
        notebook,
        timeout=600,
        kernel_name="python3",
        resources={"metadata": {"path": str(path.parent)}},
    )
    probe = nbformat.v4.new_code_cell(
        MEASURE.replace("MOVES", str(moves)).replace("PROFILE", str(profile))
    )
    notebook.cells.append(probe)
    client.execute()
    outputs = "".join(
        o.get("text", "") for o in probe.outputs if o.get("output_type") == "stream"
    )
    return json.loads(outputs)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--chapters", nargs="*", help="chapter numbers, e.g. 03 05")
    parser.add_argument(
        "--moves", type=int, default=10, help="there-and-back moves per slider"
    )
    parser.add_argument("--quick", action="store_true", help="chapter 1, two moves")
    parser.add_argument(
        "--profile",
        action="store_true",
        help="also print cProfile's top 30 per control",
    )
    args = parser.parse_args(argv)
    paths = course_map.chapters(ROOT / "notebooks")
    if args.quick:
        paths, args.moves = paths[:1], 2
    elif args.chapters:
        paths = [p for p in paths if p.name[:2] in args.chapters]
    rows, profiles = [], []
    for path in paths:
        measured, profiled = measure(path, args.moves, args.profile)
        profiles += [f"## {path.stem}: {text}" for text in profiled]
        for index, update, name, times, full, animated in measured:
            ordered = sorted(times)
            rows.append(
                [
                    path.stem,
                    f"{index}: {update}",
                    name,
                    f"{ordered[len(ordered) // 2]:.1f}",
                    f"{ordered[-1]:.1f}",
                    f"{full} of {len(times)}",
                    str(animated),
                ]
            )
    print(
        f"# Explorers: one move in the kernel, no browser ({platform.machine()}, "
        f"CPython {platform.python_version()})\n"
    )
    print(
        markdown_table(
            [
                "chapter",
                "explorer",
                "control",
                "median [ms]",
                "worst [ms]",
                "full redraws",
                "artists redrawn",
            ],
            rows,
        )
    )
    for text in profiles:
        print("\n" + text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
