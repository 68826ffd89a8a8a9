"""Chapter 7's workspace figures and limits explorer (twolink_course.explorers.ch7)."""

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from twolink import arms, ik, workspace  # noqa: E402
from twolink_course.explorers import ch7  # noqa: E402

START = ((0, 90), (-90, 90), "relative")  # arms.ten's limits


@pytest.fixture(scope="module")
def view():
    return ch7.LimitsExplorer(arms.ten)


@pytest.mark.parametrize("limits", [START, ((35, 145), (35, 145), "absolute")])
def test_the_samples_shortcut_is_the_packages_test_of_the_configurations(view, limits):
    # a sampled configuration is within the limits when its own branch at its tip is
    arm = view.limited(*limits)
    inside = ik.limits.move_into_limits(arm, view.sample_q)[1]
    assert np.array_equal(view.samples_within(arm, "auto"), inside)


@pytest.mark.parametrize("limits", [START, ((35, 145), (35, 145), "absolute")])
@pytest.mark.parametrize("elbow", ["auto", "down", "up"])
def test_the_grid_table_agrees_with_is_reachable(view, limits, elbow):
    arm = view.limited(*limits)
    points = view.grid_points[::97]  # a spread of the grid
    table = workspace.BranchTable(arm, points).reachable(arm, elbow=elbow)
    assert np.array_equal(table, workspace.is_reachable(arm, points, elbow=elbow))


def test_the_start_state_is_arms_ten_with_its_largest_circle(view):
    view.update(*START, "either")
    sentence = view.describe(*START, "either")
    assert "5 boundary arcs" in sentence and "about 20%" in sentence
    exact = workspace.largest_inscribed_circle(arms.ten, starts=3)[1]
    assert (
        view.shown["radius"] <= exact + 1e-9
    )  # a circle that fits, at most the largest
    assert exact - view.shown["radius"] < 2 * view.tolerance
    assert "r ≈ 2.93 m" in sentence


def test_the_button_draws_the_optimisers_circle_until_the_next_move(view):
    view.update(*START, "down")
    view.show_exact()
    centre, radius = view.shown["exact"]
    assert np.allclose(view.circle.center, centre) and view.circle.radius == radius
    assert "the optimiser" in view.describe(*START, "down")
    view.update(*START, "down")
    assert "grid search finds" in view.describe(*START, "down")


def test_limits_of_one_configuration_leave_no_area(view):
    view.update((0, 0), (0, 0), "relative", "either")
    sentence = view.describe((0, 0), (0, 0), "relative", "either")
    assert "about 0% of the disc" in sentence and view.shown["radius"] < view.tolerance


def test_draw_workspace_draws_every_layer_and_describes_them():
    fig, ax = plt.subplots()
    lost = ch7.draw_workspace(arms.two_metre_limited, ax, samples=300)
    assert 0.85 < lost < 0.99  # the limited 2 m arm keeps about 8% of its reach
    legend = ch7.workspace_legend(fig, ax, loc="outside lower center")
    labels = [text.get_text() for text in legend.get_texts()]
    assert "boundary" in labels and "in reach, not within the limits" in labels
    plt.close(fig)
