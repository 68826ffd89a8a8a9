"""Shared hypothesis strategies and settings for the twolink tests."""

import dataclasses
import fcntl
import json
import os
import pathlib
import shutil
import sys
import time

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


@pytest.fixture(scope="module")
def mujoco_log_in_tmp(tmp_path_factory):
    """A module's tests run in a folder of their own: MuJoCo appends its warnings (a
    massless link's singular inertia, ...) to MUJOCO_LOG.TXT in the working folder,
    which must stay out of the checkout."""
    with pytest.MonkeyPatch.context() as patch:
        patch.chdir(tmp_path_factory.mktemp("mujoco-log"))
        yield


# --- the order the files start in, so that both xdist workers stay busy to the end

#: The slowest files, with their rough cost in seconds of one core (the sums of
#: ``pytest --durations=0``; only the order matters).  pyproject.toml hands whole
#: files to the workers (``--dist loadfile``) in collection order
#: (``--no-loadscope-reorder``); these files are collected first, slowest first,
#: so no long file starts last and leaves the other core idle.  Files not named
#: here follow in their usual order.
SLOW_FILES_SECONDS = {
    "tests/browser/test_static_site.py": 81,
    "tests/browser/test_student_edition.py": 28,
    "tests/library/test_workspace.py": 24,
    "tests/infrastructure/test_grade_attacks.py": 15,
    "tests/infrastructure/test_grade.py": 15,
    "tests/library/test_trajectory.py": 11,
    "tests/library/test_public_api.py": 10,
    "tests/library/test_dynamics.py": 10,
    "tests/infrastructure/test_nbgrader.py": 9,
    "tests/infrastructure/test_grade_run.py": 9,
    "tests/browser/test_chapters_in_jupyterlab.py": 9,
    "tests/library/test_velocity.py": 6,
    "tests/course/test_exercises.py": 6,
    "tests/library/test_ik.py": 5,
    "tests/course/test_exercises_rerun.py": 5,
    "tests/library/test_kinematics.py": 5,
    # each chapter, executed by nbval: started before the many small files, which then
    # end the run on both workers together
    "notebooks/06_spring_impedance_control.ipynb": 10,
    "notebooks/07_workspace_trajectories.ipynb": 10,
    "notebooks/05_lagrangian_dynamics.ipynb": 9,
    "notebooks/03_jacobian_velocity.ipynb": 8,
    "notebooks/04_statics_wall.ipynb": 7,
    "notebooks/02_inverse_kinematics.ipynb": 6,
    "notebooks/01_dh_forward_kinematics.ipynb": 5,
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


# --- built once per test run, shared by the xdist workers


def built_once(tmp_path_factory, name, build, budget_seconds=900):
    """The folder ``build(folder)`` filled, built by the first worker that asks, once per run.

    The other workers wait for it (a file lock in the run's temporary folder, above
    each worker's own, as pytest-xdist's documentation shows) and then share it:
    what is in it is read-only for them.  A build that fails leaves nothing, so the
    next worker that asks tries again.  A wait longer than ``budget_seconds`` fails.
    """
    base = tmp_path_factory.getbasetemp()
    if os.environ.get("PYTEST_XDIST_WORKER"):
        base = base.parent  # the run's folder, which holds each worker's
    done = base / name
    deadline = time.monotonic() + budget_seconds
    with open(base / f"{name}.lock", "w") as lock:
        while True:
            try:
                fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
                break
            except BlockingIOError:
                if time.monotonic() > deadline:
                    raise TimeoutError(
                        f"{name}: another worker has built it for {budget_seconds} s"
                    ) from None
                time.sleep(0.2)
        try:
            if not done.is_dir():
                partial = base / f"{name}.partial"
                shutil.rmtree(partial, ignore_errors=True)
                partial.mkdir()
                build(partial)
                partial.rename(done)
        finally:
            fcntl.flock(lock, fcntl.LOCK_UN)
    return done


@pytest.fixture(scope="session")
def course_site(tmp_path_factory):
    """A folder with the static site of every chapter (``make site``), built once per run
    and shared by the xdist workers (:func:`built_once`); read-only for its tests."""
    root = pathlib.Path(__file__).resolve().parent.parent
    sys.path.insert(0, str(root / "tools"))
    import editions

    return built_once(
        tmp_path_factory,
        "course-site",
        lambda folder: editions.build_site(root / "notebooks", folder),
        budget_seconds=600,
    )


@pytest.fixture(scope="session")
def student_edition_bundle(tmp_path_factory):
    """``make student``'s files (``editions.build_student_edition``: the notebooks, the
    twolink wheel, constraints.txt, README.md, then the zip), built once per test run.

    Read-only: a test unzips the zip into a folder of its own.
    """
    root = pathlib.Path(__file__).resolve().parent.parent
    sys.path.insert(0, str(root / "tools"))
    import editions

    def build(folder):
        written = editions.build_student_edition(
            root / "notebooks", folder / "build" / "student"
        )
        (folder / "written.json").write_text(
            json.dumps([str(path.relative_to(folder)) for path in written])
        )

    folder = built_once(tmp_path_factory, "student-edition-bundle", build)
    return [folder / name for name in json.loads((folder / "written.json").read_text())]


@pytest.fixture(scope="session")
def edition_wheel(student_edition_bundle):
    """The twolink wheel of the student edition (``editions.build_wheel``), built once per run."""
    (wheel,) = [path for path in student_edition_bundle if path.suffix == ".whl"]
    return wheel


@dataclasses.dataclass(frozen=True)
class Wheelhouse:
    """Wheels pip installs offline: ``pip_environment()`` points pip at ``folder`` alone
    (no index, no configuration file)."""

    folder: pathlib.Path
    names: tuple[str, ...]
    decoys: dict[str, str]

    def pip_environment(self):
        return {
            "PIP_CONFIG_FILE": os.devnull,  # no index or wheels of this machine's pip.conf
            "PIP_NO_INDEX": "1",
            "PIP_FIND_LINKS": str(self.folder),
            "PIP_DISABLE_PIP_VERSION_CHECK": "1",
        }


#: The packages a student's first run must itself install with twolink: the widgets,
#: whose JupyterLab extensions pip writes into the environment (why the page needs a
#: reload), and ipympl, the explorers' figures (its extension too).
WIDGETS = ("ipywidgets", "jupyterlab_widgets", "widgetsnbextension", "ipympl")
#: Offered beside the installed (pinned) version of each: a higher one, which pip
#: takes unless the edition's constraints.txt keeps it to the pin.
DECOYED = ("ipympl",)


@pytest.fixture(scope="session")
def widget_wheels(tmp_path_factory):
    """Wheels of this environment's widget packages (``WIDGETS``) and a newer decoy of
    each of ``DECOYED``, for the student edition's install cell to install offline."""
    import importlib.metadata

    from packaging.version import Version

    sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
    import _venvs

    decoys = {name: importlib.metadata.version(name) + ".post999" for name in DECOYED}
    for name, decoy in decoys.items():
        assert Version(decoy) > Version(importlib.metadata.version(name)), decoy
    folder = built_once(
        tmp_path_factory,
        "widget-wheels",
        lambda folder: _venvs.wheelhouse(folder, WIDGETS, decoys),
    )
    return Wheelhouse(folder, WIDGETS, decoys)


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
