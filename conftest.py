"""Make pytest work the same from any folder of the repository, and mark each test by its folder.

pyproject.toml's options name the nbval sanitize file relative to the
repository root (``tests/nbval_sanitize.cfg``); pytest would read that path
relative to the current folder, so ``cd notebooks && pytest --nbval
01_dh_forward_kinematics.ipynb`` would not find it.  A relative path that does
not exist from the current folder is taken from the root instead.

Every test carries the marker of the folder it lives in (``FOLDER_MARKERS``),
so ``pytest -m library`` or ``-m "not infrastructure"`` select by what a test
proves, and a new test file is marked by being put in its folder: there is no
list of tests to keep.
"""

import importlib.util
import pathlib

import pytest

#: The chapter checks that ride along in nbval's run of each chapter (figures,
#: exercises: tests/notebooks/chapter_checks.py); ``-p no:chapter_checks`` leaves them out.
CHAPTER_CHECKS = (
    pathlib.Path(__file__).parent / "tests" / "notebooks" / "chapter_checks.py"
)

#: The markers of the tests under each folder (relative to the root; the longest
#: matching folder wins).  The doctests of a package count with its folder of tests.
FOLDER_MARKERS = {
    "tests/library": ("library",),
    "twolink": ("library",),
    "tests/course": ("course",),
    "twolink_course": ("course",),
    "tests/notebooks": ("notebooks",),
    "notebooks": ("notebooks",),
    "tests/infrastructure": ("infrastructure",),
    "tools": ("infrastructure",),
    "tests/browser": ("infrastructure", "browser"),
    "tests/repository": ("repository",),
    "tests/benchmarks": ("benchmarks",),
}


def folder_markers(relative_path: str) -> tuple[str, ...]:
    """The markers of a test file at ``relative_path`` (from the root, with ``/``)."""
    for folder in sorted(FOLDER_MARKERS, key=len, reverse=True):
        if relative_path == folder or relative_path.startswith(folder + "/"):
            return FOLDER_MARKERS[folder]
    return ()


def pytest_configure(config):
    sanitize = getattr(config.option, "nbval_sanitize_with", None)
    if (
        sanitize
        and not pathlib.Path(sanitize).is_absolute()
        and not pathlib.Path(sanitize).exists()
    ):
        from_root = pathlib.Path(config.rootpath) / sanitize
        if from_root.exists():
            config.option.nbval_sanitize_with = str(from_root)
    if (
        getattr(config.option, "nbval", False)
        or getattr(config.option, "nbval_lax", False)
    ) and not config.pluginmanager.is_blocked("chapter_checks"):
        if CHAPTER_CHECKS.exists():  # a copy of this file elsewhere has no checks
            spec = importlib.util.spec_from_file_location(
                "chapter_checks", CHAPTER_CHECKS
            )
            module = importlib.util.module_from_spec(spec)
            spec.loader.exec_module(module)
            config.pluginmanager.register(module.ChapterChecks(), "chapter_checks")


@pytest.hookimpl(tryfirst=True)
def pytest_collection_modifyitems(config, items):
    """Each test gets the markers of its folder (first, so other hooks see them)."""
    root = pathlib.Path(config.rootpath)
    for item in items:
        try:
            relative = item.path.relative_to(root).as_posix()
        except ValueError:  # outside the repository: a test's own temporary copy
            continue
        for marker in folder_markers(relative):
            item.add_marker(marker)
