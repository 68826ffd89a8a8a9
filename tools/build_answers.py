"""Encode the readable exercise references of ``answers/`` into ``twolink_course/exercises/store/``.

The self-checks of the installed package compare a learner's answers with
the values in the store (encoded, so that no module reads as a list of
answers); the references themselves stay readable in the repository's
``answers/`` folder, for teachers and the grader.  One file per chapter:
``answers/ch4.py`` -> ``twolink_course/exercises/store/ch4.txt``: its
``exercises()``, each function part with the calls its ``FORBIDDEN`` lists;
no hidden case, hidden input or reference on hidden inputs (``HIDDEN``,
``RERUN``) is stored: those stay with the grader.

Usage::

    python tools/build_answers.py              # rewrite every chapter's store file
    python tools/build_answers.py --chapter 4  # rewrite chapter 4's only
    python tools/build_answers.py --check      # exit 1 if a store file differs from answers/

``--check`` compares decoded data with numbers equal to 1e-12 relative, so a
store built on another CPU (whose last bits of a computed reference may
differ) still counts as current.
"""

from __future__ import annotations

import argparse
import pathlib
import sys
import textwrap
from collections.abc import Sequence
from typing import Any

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

import answers  # noqa: E402
from twolink_course.exercises import stored  # noqa: E402

STORE = ROOT / "twolink_course" / "exercises" / "store"


def store_file(chapter: str) -> pathlib.Path:
    """The store file of an answers module (``"ch4"`` -> ``.../store/ch4.txt``)."""
    return STORE / f"{chapter}.txt"


def store_text(chapter: str) -> str:
    """The text of a chapter's store file for the current ``answers/``."""
    encoded = stored.encode(answers.chapter_exercises(chapter))
    return "\n".join(textwrap.wrap(encoded, 76)) + "\n"


#: How closely a store file must hold what ``answers/`` computes, relative to each
#: quantity's scale (its largest magnitude).  Far above another machine's round-off (an
#: integrator's 1e-11, the split of a double pole's eigenvalues: 1e-8 on this one), far
#: below any change of an answer, a mistake or a tolerance.
STORE_RTOL = 1e-6


def _numbers(value: Any) -> list[float] | None:
    """The numbers of a number or of a (nested) list of numbers, else None."""
    if isinstance(value, bool):
        return None
    if isinstance(value, (int, float)):
        return [float(value)]
    if isinstance(value, list):
        found: list[float] = []
        for item in value:
            numbers = _numbers(item)
            if numbers is None:
                return None
            found += numbers
        return found
    return None


def _skeleton(value: Any) -> Any:
    """A quantity's nesting and types, its numbers left out."""
    if isinstance(value, list):
        return [_skeleton(item) for item in value]
    return type(value).__name__


def same(a: Any, b: Any) -> bool:
    """Equal data; a quantity (a number, or a nested list of numbers) within
    ``STORE_RTOL`` of its scale, the largest magnitude in either."""
    numbers_a, numbers_b = _numbers(a), _numbers(b)
    if numbers_a is not None and numbers_b is not None:
        if _skeleton(a) != _skeleton(b):
            return False
        scale = max(map(abs, numbers_a + numbers_b), default=0.0)
        return all(
            abs(x - y) <= STORE_RTOL * scale for x, y in zip(numbers_a, numbers_b)
        )
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(same(a[k], b[k]) for k in a)
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(same(x, y) for x, y in zip(a, b))
    if isinstance(a, bool) or isinstance(b, bool):
        return a is b
    return bool(a == b)


def stale() -> list[str]:
    """The store files that differ from what ``answers/`` computes now (or are missing or extra)."""
    wrong = []
    for chapter in answers.chapter_names():
        path = store_file(chapter)
        fresh = stored.decode(store_text(chapter).replace("\n", ""))
        on_disk = (
            stored.decode(path.read_text(encoding="ascii").replace("\n", ""))
            if path.exists()
            else None
        )
        if on_disk is None or not same(on_disk, fresh):
            wrong.append(path.name)
    extra = {path.stem for path in STORE.glob("*.txt")} - set(answers.chapter_names())
    return wrong + sorted(f"{name}.txt (no answers/{name}.py)" for name in extra)


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--check", action="store_true", help="exit 1 if the store is out of date"
    )
    parser.add_argument(
        "--chapter", type=int, help="rewrite only this chapter's store file"
    )
    args = parser.parse_args(argv)
    if args.check:
        wrong = stale()
        if wrong:
            print(f"out of date: {', '.join(wrong)}: run python tools/build_answers.py")
            return 1
        print("twolink_course/exercises/store/ is up to date")
        return 0
    chapters = [f"ch{args.chapter}"] if args.chapter else answers.chapter_names()
    STORE.mkdir(exist_ok=True)
    for chapter in chapters:
        store_file(chapter).write_text(store_text(chapter), encoding="ascii")
        print(f"wrote {store_file(chapter).relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
