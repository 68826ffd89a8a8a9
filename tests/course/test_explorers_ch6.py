"""Chapter 6's explorer (twolink_course.explorers.ch6): the live run against the exact one."""

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402
from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from twolink import arms, controllers, ik, linearization  # noqa: E402
from twolink_course.explorers import ch6  # noqa: E402

REST = np.array([3.0, 1.0])
#: (k [N/m], d [N s/m], start [m]): critical at the source's spring, underdamped from
#: afar, stiff from below.
RELEASES = [
    (600.0, 58.0, (3.0, 2.0)),
    (600.0, 20.0, (-1.0, 2.5)),
    (2000.0, 100.0, (0.5, -2.0)),
]


@pytest.fixture(scope="module")
def view():
    return ch6.ImpedanceRelease(arms.two_metre, REST)


@settings(max_examples=30, deadline=None)
@given(
    q=st.lists(st.floats(-3, 3), min_size=2, max_size=2),
    qd=st.lists(st.floats(-3, 3), min_size=2, max_size=2),
    k=st.floats(50, 3000),
    d=st.floats(0, 200),
)
def test_the_float_law_is_impedance_control_without_gravity(q, qd, k, d):
    q, qd = np.array(q), np.array(qd)
    full = controllers.Impedance(arms.two_metre, k, d, REST)(0.0, q, qd)
    expected = full - arms.two_metre.gravity(q)
    law = ch6.impedance_law(arms.two_metre, REST, k, d)(0.0, q, qd)
    assert np.allclose(
        law, expected, rtol=1e-12, atol=1e-9 * (1 + np.abs(expected).max())
    )


@pytest.mark.parametrize("k, d, start", RELEASES)
def test_the_live_run_stays_within_5_mm_of_the_exact_one(view, k, d, start):
    q_start = ik.closed_form(arms.two_metre, start).q
    live, exact = view.live_run(k, d, q_start), view.exact_run(k, d, q_start)
    assert live is not None
    every = (len(view.t_exact) - 1) // (len(view.t_live) - 1)
    assert np.allclose(view.t_exact[::every], view.t_live)
    gap = np.linalg.norm(
        arms.two_metre.fk(live) - arms.two_metre.fk(exact[::every]), axis=-1
    )
    assert gap.max() < 5e-3
    # the damper only takes energy out: the tip never gets further than it started
    offset = np.linalg.norm(np.asarray(start) - REST)
    assert (
        np.linalg.norm(arms.two_metre.fk(exact) - REST, axis=-1).max() <= offset + 1e-9
    )


def test_the_damping_ratio_is_the_heavy_directions(view):
    d_c = linearization.critical_damping(arms.two_metre, view.q_rest, 600.0)
    assert np.isclose(view.smallest_damping_ratio(600.0, d_c), 1.0)


def test_a_stiff_undamped_spring_runs_out_of_the_live_budget_and_the_button_draws_it(
    view,
):
    values = dict(k=3000.0, d=0.0, x_start=-1.0, y_start=2.5)
    view.update(**values)
    assert view.shown["state"] == "fast" and "press 'exact run'" in view.describe(
        **values
    )
    assert not view.distance_line.get_visible()
    view.show_exact(**values)
    assert view.shown["state"] == "exact" and view.distance_line.get_visible()
    assert view.describe(**values).endswith("goes back to the live run.")
    view.update(
        k=3000.0, d=10.0, x_start=-1.0, y_start=2.5
    )  # another value: live again
    assert view.shown["state"] in ("live", "fast")


def test_out_of_reach_and_at_rest_say_so(view):
    view.update(k=600.0, d=58.0, x_start=4.0, y_start=4.0)
    assert "out of reach" in view.describe(k=600.0, d=58.0, x_start=4.0, y_start=4.0)
    view.update(k=600.0, d=58.0, x_start=3.0, y_start=1.0)
    assert "the arm stays" in view.describe(k=600.0, d=58.0, x_start=3.0, y_start=1.0)
