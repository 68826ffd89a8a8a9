"""``import twolink`` is light: no scipy, sympy, matplotlib, control or mujoco until a function needs it.

Each module imports scipy inside the function that calls it.  These tests run
fresh Python processes (this process has long since imported everything):
one checks what ``import twolink`` and each submodule load, the others check
that every function that imports scipy late still works after the light
import.  How long the import takes is measured by
``benchmarks/bench_import.py``, not here.
"""

import json
import os
import pathlib
import pkgutil
import subprocess
import sys
import textwrap

import pytest

import twolink

ROOT = pathlib.Path(__file__).resolve().parents[2]
HEAVY = ("scipy", "sympy", "matplotlib", "control", "mujoco")
# The modules that exist to use a heavy library, and the one they load: chapters import them by name.
HEAVY_BY_DESIGN = {
    "twolink_course.plot": "matplotlib",
    "twolink_course.diagrams": "matplotlib",
    "twolink_course.explorer": "matplotlib",
    "twolink_course.figure_style": "matplotlib",
    "twolink_course.alttext": "matplotlib",
    "twolink_course.inline": "matplotlib",
    "twolink_course.video": "matplotlib",
    "twolink.symbolic": "sympy",
}


def run_fresh(code: str) -> str:
    """Run ``code`` in a fresh interpreter and return what it printed (the test fails on any error)."""
    env = dict(
        os.environ,
        PYTHONPATH=os.pathsep.join(
            filter(None, [str(ROOT), os.environ.get("PYTHONPATH")])
        ),
    )
    env.setdefault("MPLBACKEND", "Agg")
    done = subprocess.run(
        [sys.executable, "-c", textwrap.dedent(code)],
        capture_output=True,
        text=True,
        timeout=120,
        cwd=ROOT,
        env=env,
    )
    assert done.returncode == 0, done.stderr[-3000:]
    return done.stdout


def heavy_modules_after(statement: str) -> list[str]:
    """The heavy libraries in ``sys.modules`` of a fresh process after ``statement``."""
    printed = run_fresh(f"""
        import json, sys
        {statement}
        print(json.dumps(sorted({{name.split(".")[0] for name in sys.modules}} & set({HEAVY!r}))))
    """)
    return json.loads(printed.splitlines()[-1])


def test_import_twolink_loads_no_heavy_library():
    assert heavy_modules_after("import twolink") == []


def test_every_public_name_is_there_after_the_light_import():
    printed = run_fresh("""
        import json, sys
        import twolink
        missing = [name for name in twolink.__all__ if not hasattr(twolink, name)]
        print(json.dumps([missing, "scipy" in sys.modules]))
    """)
    missing, scipy_loaded = json.loads(printed.splitlines()[-1])
    assert missing == [], (
        f"names in twolink.__all__ missing after import twolink: {missing}"
    )
    assert not scipy_loaded, "looking up the public names loaded scipy"


SUBMODULES = sorted(
    module.name
    for module in pkgutil.walk_packages(twolink.__path__, "twolink.")
    if not any(
        module.name == heavy or module.name.startswith(heavy + ".")
        for heavy in HEAVY_BY_DESIGN
    )
)


@pytest.mark.parametrize("module", SUBMODULES)
def test_each_submodule_imports_without_a_heavy_library(module):
    assert heavy_modules_after(f"import {module}") == []


@pytest.mark.parametrize("module, library", sorted(HEAVY_BY_DESIGN.items()))
def test_the_modules_built_on_a_heavy_library_load_only_theirs(module, library):
    assert heavy_modules_after(f"import {module}") == [library]


# One call per function that imports scipy late, each with a check that can fail; every snippet starts
# from the light import, so the function must load what it needs itself.
LATE_SCIPY_CALLS = {
    "ik.minimize (scipy.optimize)": """
        result = twolink.ik.minimize(arms.ten, [10.0, 10.0], q0=[0.4, 1.0])
        assert result.success and np.allclose(arms.ten.fk(result.q), [10.0, 10.0], atol=1e-9), result
        constrained = twolink.ik.minimize(arms.ten, [10.0, 10.0], constrained=True)
        assert np.allclose(arms.ten.fk(constrained.q), [10.0, 10.0], atol=1e-9), constrained
    """,
    "simulate (scipy.integrate)": """
        arm = arms.two_metre
        q0 = [np.pi / 4, 0.3]
        held = twolink.simulate(arm, q0, [0.0, 0.0], 1.0, torque=lambda t, q, qd: arm.gravity(q))
        assert np.allclose(held.q[-1], q0, atol=1e-6), held.q[-1]
        falling = twolink.simulate(arm, q0, [0.0, 0.0], 0.5)
        assert falling.q[-1][0] < q0[0] - 0.1, falling.q[-1]
    """,
    "trajectory.resolved_rate_trajectory (scipy.integrate)": """
        line = twolink.trajectory.LinePath([-3.5, 1.0], [-1.0, 3.5], duration=5.0)
        motion = twolink.trajectory.resolved_rate_trajectory(arms.two_metre, line, n=50)
        assert np.allclose(arms.two_metre.fk(motion.q[-1]), [-1.0, 3.5], atol=1e-6), motion.q[-1]
    """,
    "controllers.JointReference.from_samples (scipy.interpolate)": """
        t = np.linspace(0.0, 2.0, 9)
        q = np.column_stack([np.sin(t), t ** 2])
        reference = twolink.JointReference.from_samples(t, q)
        for time, sample in zip(t, q):
            assert np.allclose(reference(time)[0], sample, atol=1e-12), (time, reference(time)[0], sample)
    """,
    "workspace.largest_inscribed_circle (scipy.optimize)": """
        centre, radius = twolink.workspace.largest_inscribed_circle(arms.ten)
        assert abs(radius - (10 - 5 * np.sqrt(2))) < 1e-6, radius
    """,
    "linearization.critical_damping and equilibrium (scipy.linalg, scipy.optimize)": """
        arm = twolink.TwoLinkArm(l1=1.0, l2=1.0, m1=0.0, m2=1.0, g=0.0)
        q = [0.0, np.pi / 2]
        matrix = twolink.linearization.critical_damping(arm, q, 100.0, kind="matrix")
        scalar = twolink.linearization.critical_damping(arm, q, 100.0)
        assert np.allclose(matrix, matrix.T) and np.linalg.eigvalsh(matrix)[-1] <= scalar + 1e-9, (matrix, scalar)
        spring = twolink.CartesianSpring(arms.two_metre, 600.0, [3.0, 1.0])
        q_rest = twolink.ik.closed_form(arms.two_metre, [3.0, 1.0]).q
        q_sag = twolink.linearization.equilibrium(arms.two_metre, spring, q_rest)
        assert np.allclose(arms.two_metre.fk(q_sag), [3.0, 1.0], atol=0.05), q_sag
    """,
    "sources.mae6245.numerical_ik (scipy.optimize)": """
        from twolink_course.sources import mae6245
        run = mae6245.numerical_ik(acos="matlab")
        assert run.success and abs(run.q[0] - np.pi / 4) < 1e-4, run
    """,
}


@pytest.mark.parametrize("call", sorted(LATE_SCIPY_CALLS))
def test_a_function_that_needs_scipy_works_after_the_light_import(call):
    printed = run_fresh(
        "import sys\nimport numpy as np\nimport twolink\nfrom twolink import arms\n"
        "assert 'scipy' not in sys.modules\n"
        + textwrap.dedent(LATE_SCIPY_CALLS[call])
        + "print('scipy' in sys.modules)\n"
    )
    assert printed.strip() == "True", (
        "the call did not need scipy: it no longer tests a late import"
    )
