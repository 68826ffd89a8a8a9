"""Shared hypothesis strategies and settings for the twolink tests."""

import os
import pathlib
import sys

import matplotlib
import numpy as np
import pytest
from hypothesis import HealthCheck, settings
from hypothesis import strategies as st

matplotlib.use("Agg")

settings.register_profile(
    "course",
    max_examples=200,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow],
    derandomize=bool(os.environ.get("CI")),
)
settings.load_profile("course")

lengths = st.floats(
    min_value=0.05, max_value=20.0, allow_nan=False, allow_infinity=False
)
angles = st.floats(
    min_value=-np.pi, max_value=np.pi, allow_nan=False, allow_infinity=False
)
unit = st.floats(min_value=0.0, max_value=1.0, allow_nan=False, allow_infinity=False)


@st.composite
def arms(draw, ratio_max=20.0):
    """Arms with link lengths 0.05..20 m and a length ratio of at most ``ratio_max``."""
    from twolink import TwoLinkArm

    l1 = draw(lengths)
    l2 = draw(
        st.floats(
            min_value=max(0.05, l1 / ratio_max), max_value=min(20.0, l1 * ratio_max)
        )
    )
    m1 = draw(st.floats(min_value=0.0, max_value=10.0))
    m2 = draw(st.floats(min_value=0.0, max_value=10.0))
    return TwoLinkArm(l1=l1, l2=l2, m1=m1, m2=m2)


@st.composite
def configurations(draw):
    return np.array([draw(angles), draw(angles)])


# --- dynamics
rates = st.floats(
    min_value=-10.0, max_value=10.0, allow_nan=False, allow_infinity=False
)


@st.composite
def dynamic_arms(draw):
    """Arms with mass (0.1..10 kg per link, so M is invertible), lengths 0.05..20 m (ratio <= 20),
    gravity -20..20 m/s^2, and half the time inertias that are not the uniform-rod value."""
    from twolink import TwoLinkArm

    l1 = draw(lengths)
    l2 = draw(st.floats(min_value=max(0.05, l1 / 20.0), max_value=min(20.0, l1 * 20.0)))
    m1 = draw(st.floats(min_value=0.1, max_value=10.0))
    m2 = draw(st.floats(min_value=0.1, max_value=10.0))
    g = draw(st.floats(min_value=-20.0, max_value=20.0, allow_subnormal=False))
    inertias = {}
    if draw(st.booleans()):
        inertias = {
            "I1": m1 * l1**2 * draw(st.floats(min_value=0.01, max_value=0.5)),
            "I2": m2 * l2**2 * draw(st.floats(min_value=0.01, max_value=0.5)),
        }
    return TwoLinkArm(l1=l1, l2=l2, m1=m1, m2=m2, g=g, **inertias)


# --- checks against MuJoCo (tests/library/test_export.py, tests/test_mujoco_engine.py)


def acceleration_scale(arm, q, qd, tau):
    """The size of the accelerations each term alone would give (rad/s^2): what 1e-9 is relative to.

    Several terms can cancel exactly in twolink's closed form (e.g. the Coriolis
    term at q2 = 0) while MuJoCo's recursive algorithm leaves round-off there.
    """
    q, qd, tau = (np.asarray(v, dtype=float) for v in (q, qd, tau))
    from_torque = arm.forward_dynamics(q, np.zeros(2), tau) - arm.forward_dynamics(
        q, np.zeros(2), np.zeros(2)
    )
    parts = [
        arm.forward_dynamics(q, qd, tau),
        from_torque,
        arm.forward_dynamics(q, qd, np.zeros(2)),
        qd * qd,
    ]
    return max(float(np.max(np.abs(part))) for part in parts)


# --- the order the files start in, so that both xdist workers stay busy to the end

#: The slowest files, with their rough cost in seconds of one core (the sums of
#: ``pytest --durations=0``; only the order matters).  pyproject.toml hands whole
#: files to the workers (``--dist loadfile``) in collection order
#: (``--no-loadscope-reorder``); these files are collected first, slowest first,
#: so no long file starts last and leaves the other core idle.  Files not named
#: here follow in their usual order.
SLOW_FILES_SECONDS = {
    "tests/browser/test_chapters_in_jupyterlab.py": 60,
    "tests/infrastructure/test_student_edition.py": 110,
    "tests/browser/test_static_site.py": 120,
    "tests/infrastructure/test_pytest_anywhere.py": 70,
    "tests/infrastructure/test_grade_attacks.py": 150,
    "tests/infrastructure/test_nbgrader.py": 50,
    "tests/infrastructure/test_grade.py": 45,
    "tests/library/test_import.py": 38,
    "tests/notebooks/test_figures.py": 34,
    "tests/infrastructure/test_install_cell.py": 25,
    "tests/course/test_exercises.py": 25,
    "tests/infrastructure/test_benchmarks_run.py": 21,
    "tests/library/test_trajectory.py": 18,
    "tests/infrastructure/test_portable.py": 18,
}


def pytest_collection_modifyitems(config, items):
    """Collect the slowest files first (a stable sort: each file's tests keep their order)."""
    items.sort(key=lambda item: -SLOW_FILES_SECONDS.get(item.nodeid.split("::")[0], 0))


# --- the student edition, built once per worker


@pytest.fixture(scope="session")
def student_edition(tmp_path_factory):
    """A folder with the student edition of every chapter (``make student``), built once.

    Read-only for the tests that share it: a test that changes a notebook works on a copy.
    """
    root = pathlib.Path(__file__).resolve().parent.parent
    sys.path.insert(0, str(root / "tools"))
    import editions

    out = tmp_path_factory.mktemp("student-edition")
    editions.build_student(root / "notebooks", out)
    return out


# --- the static site, built once per run


#: How long a worker waits for another worker's build of the site, seconds.
SITE_BUILD_BUDGET = 600


@pytest.fixture(scope="session")
def course_site(tmp_path_factory):
    """A folder with the static site of every chapter (``make site``), built once per run.

    The xdist workers share one build (a file lock in the run's temporary
    folder, as pytest-xdist's documentation shows); read-only for its tests.
    """
    import fcntl
    import time

    root = pathlib.Path(__file__).resolve().parent.parent
    sys.path.insert(0, str(root / "tools"))
    import editions

    shared = tmp_path_factory.getbasetemp()
    if os.environ.get("PYTEST_XDIST_WORKER"):
        shared = shared.parent  # the run's folder, above the workers' own
    site, built = shared / "course-site", shared / "course-site.built"
    with open(shared / "course-site.lock", "w") as lock:
        deadline = time.monotonic() + SITE_BUILD_BUDGET
        while True:
            try:
                fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
                break
            except BlockingIOError:
                if time.monotonic() > deadline:
                    raise TimeoutError(
                        f"another worker built the site for {SITE_BUILD_BUDGET} s"
                    ) from None
                time.sleep(0.2)
        try:
            if not built.exists():
                editions.build_site(root / "notebooks", site)
                built.touch()
        finally:
            fcntl.flock(lock, fcntl.LOCK_UN)
    return site


# --- the environment nbval's kernels inherit


@pytest.fixture(autouse=True)
def matplotlib_backend_left_as_found():
    """A test must not set MPLBACKEND for the worker: the notebook kernels nbval starts later in the same
    worker would inherit it and store no figures (strict nbval then fails far from the cause)."""
    before = os.environ.get("MPLBACKEND")
    yield
    assert os.environ.get("MPLBACKEND") == before, (
        "this test changed MPLBACKEND in os.environ; use matplotlib.use()"
    )
