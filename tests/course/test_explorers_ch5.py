"""Chapter 5's explorer (twolink_course.explorers.ch5): the quick run against the exact one.

The explorer simulates each move with ``simulate_quick`` (LSODA at 1e-6); these
tests hold it to the exact run (DOP853 at 1e-10) across the sliders' ranges, so
that the chapter can say the two are less than a pixel apart.
"""

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402

from twolink import arms  # noqa: E402
from twolink_course.explorers import ch5  # noqa: E402

#: (q1 [deg], q2 [deg], m1 [kg], m2 [kg]): the explorer's start, both ends of m2/m1,
#: three other starts.
RELEASES = [
    (45, 0, 1.0, 1.0),
    (45, 0, 0.1, 5.0),
    (45, 0, 5.0, 0.1),
    (180, 90, 0.1, 5.0),
    (-120, 150, 2.5, 0.5),
    (10, -60, 3.0, 3.0),
]


@pytest.fixture(scope="module")
def view():
    return ch5.Release(arms.two_metre)


@pytest.mark.parametrize("release", RELEASES)
def test_the_quick_run_stays_within_a_millimetre_of_the_exact_one(view, release):
    fast, exact = view.run(*release), view.run(*release, exact=True)
    seconds = view.strobe_end + 1  # the strobe's first second
    assert np.max(exact.tracking_error(fast.p_tip)[:seconds]) < 1e-3
    (t_fast, v_fast), (t_exact, v_exact) = fast.energy(), exact.energy()
    gap = np.max(np.abs([t_fast - t_exact, v_fast - v_exact])) / t_exact.max()
    assert gap < 1e-3
    assert fast.energy_drift() < ch5.FAST_DRIFT_BOUND
    assert exact.energy_drift() < 1e-8
    assert fast.nfev <= 2000


@pytest.mark.parametrize("release", RELEASES)
def test_the_scaled_energies_fit_the_fixed_axis(view, release):
    kinetic, potential = view.run(*release).energy()
    scaled = np.array([kinetic, potential]) / view.energy_scale(*release[2:])
    assert (
        scaled.min() > -1 - 1e-6 and scaled.max() < 2 + 1e-6
    )  # V >= -V_up, T <= 2 V_up
    low, high = view.ax_energy.get_ylim()
    assert low < -1 and high > 2


def test_the_motion_depends_on_the_masses_only_through_their_ratio(view):
    single, doubled = view.run(45, 0, 1.0, 1.0), view.run(45, 0, 2.0, 2.0)
    assert np.allclose(doubled.q, single.q, atol=1e-6)


def test_the_button_shows_the_exact_run_until_the_next_move(view):
    view.update(q1=60, q2=30, m1=1.0, m2=2.0)
    assert view.ax_energy.get_title().startswith("fast run")
    view.show_exact(q1=60, q2=30, m1=1.0, m2=2.0)
    assert view.ax_energy.get_title().startswith("exact run: E drift below 1e-8")
    sentence = view.describe(q1=60, q2=30, m1=1.0, m2=2.0)
    assert sentence.startswith("Exact run (DOP853") and "goes back" in sentence
    view.update(q1=60, q2=30, m1=1.0, m2=2.0)
    assert view.describe(q1=60, q2=30, m1=1.0, m2=2.0).startswith("The 2 m arm")


def test_a_release_in_balance_has_no_kinetic_energy(view):
    view.update(q1=-90, q2=0, m1=1.0, m2=1.0)
    assert "released in balance" in view.describe(q1=-90, q2=0, m1=1.0, m2=1.0)
