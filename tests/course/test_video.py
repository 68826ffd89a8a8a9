"""twolink_course.video: a video drawn by redrawing only what moves is the video matplotlib draws in full."""

import imageio_ffmpeg
import matplotlib
import matplotlib.pyplot as plt
import numpy as np
import pytest
from matplotlib.patches import Circle

from twolink import arms
from twolink_course import figure_style, plot, video


@pytest.fixture(autouse=True)
def ffmpeg_and_closed_figures():
    # matplotlib's layout, whatever an earlier test left in rcParams (the course
    # style's constrained layout is checked by its own test below)
    with matplotlib.rc_context(
        {
            "animation.ffmpeg_path": imageio_ffmpeg.get_ffmpeg_exe(),
            "figure.constrained_layout.use": False,
            "figure.autolayout": False,
        }
    ):
        yield
    plt.close("all")


def _counting_draws(anim):
    draws = []
    anim._fig.canvas.mpl_connect("draw_event", draws.append)
    return draws


def _both_videos(make):
    """The video of ``make()`` drawn by twolink's writer and by matplotlib's, and the full draws each made."""
    fast = make()
    fast_draws = _counting_draws(fast)
    fast_video = video.html5_video(fast, embed_limit=5.0)
    full = make()
    full_draws = _counting_draws(full)
    full_video = full.to_html5_video(embed_limit=5.0)
    return fast_video, full_video, len(fast_draws), len(full_draws)


def _arm_with_everything():
    """An arm animation with a clock, a patch under the arm, a moving force arrow and a legend over all."""
    arm = arms.two_metre
    q_path = np.linspace([0.0, 0.2], [1.4, 1.9], 8)
    ax = plot.setup_axes(arm, title="everything")
    ax.add_patch(Circle((1.0, 1.0), 0.8, alpha=0.3, label="a disc"))
    arrow = plot.draw_force(arm.fk(q_path[0]), [0.0, -5.0], ax=ax, scale=0.1)
    ax.legend(loc="lower left")

    def push(frame):
        tip = arm.fk(q_path[frame])
        arrow.set_positions(tuple(tip), tuple(tip + [0.0, -0.5 - 0.1 * frame]))
        return [arrow]

    return plot.animate_arm(arm, q_path, t=np.linspace(0.0, 0.7, 8), ax=ax, extra=push)


@pytest.mark.parametrize(
    "make",
    [
        lambda: plot.animate_arm(
            arms.two_metre, np.linspace([0.0, 0.0], [1.5, 1.5], 6)
        ),
        _arm_with_everything,
    ],
    ids=["plain arm", "patch, arrow and legend"],
)
def test_the_video_is_matplotlibs_byte_for_byte_with_one_full_draw(make):
    fast_video, full_video, fast_draws, full_draws = _both_videos(make)
    assert "data:video/mp4;base64," in fast_video
    assert fast_video == full_video
    assert fast_draws == 1 and full_draws >= 6


def test_moving_animation_keeps_what_the_last_frame_moved():
    anim = _arm_with_everything()
    assert anim.moved == []
    video.html5_video(anim, embed_limit=5.0)
    kinds = sorted(type(artist).__name__ for artist in anim.moved)
    assert kinds == ["FancyArrowPatch", "Line2D", "Line2D", "Text"]
    assert anim.interval == 100.0 and anim.repeat


def test_a_view_that_changes_mid_video_redraws_the_background():
    def make():
        anim = plot.animate_arm(arms.two_metre, np.linspace([0.0, 0.0], [1.5, 1.5], 6))
        ax = anim._fig.axes[0]
        update = anim._func

        def zooming(frame):
            ax.set_xlim(-4.5 + 0.3 * frame, 4.5)
            return update(frame)

        anim._func = zooming
        return anim

    fast_video, full_video, fast_draws, _ = _both_videos(make)
    assert fast_video == full_video
    assert fast_draws == 6  # every frame had a new view


def test_overlapping_axes_take_the_full_draw():
    def make():
        anim = plot.animate_arm(arms.two_metre, np.linspace([0.0, 0.0], [1.5, 1.5], 4))
        anim._fig.add_axes((0.6, 0.6, 0.3, 0.3)).plot(
            [0, 1], [1, 0]
        )  # an inset over the arm
        return anim

    fast_video, full_video, fast_draws, _ = _both_videos(make)
    assert fast_video == full_video
    assert fast_draws == 4  # each frame drawn in full


def test_an_artist_outside_the_axes_takes_the_full_draw():
    def make():
        fig = plt.figure(figsize=(3.0, 2.0), dpi=80)
        label = fig.text(0.5, 0.5, "")

        def update(frame):
            label.set_text(f"frame {frame}")
            return [label]

        return video.MovingAnimation(fig, update, frames=3, interval=100.0)

    fast_video, full_video, fast_draws, _ = _both_videos(make)
    assert fast_video == full_video and fast_draws == 3  # each frame drawn in full


def test_a_video_over_the_embed_limit_is_refused_with_advice():
    anim = plot.animate_arm(arms.two_metre, np.linspace([0.0, 0.0], [1.5, 1.5], 4))
    with pytest.warns(UserWarning, match="over the embed limit.*max_frames"):
        assert video.html5_video(anim, embed_limit=1e-6) == "Video too large to embed."


def test_the_figure_is_drawn_in_full_again_after_the_video():
    anim = _arm_with_everything()
    video.html5_video(anim, embed_limit=5.0)
    ax = anim._fig.axes[0]
    assert all(artist.get_visible() for artist in ax.get_children())
    assert not any(artist.get_animated() for artist in ax.get_children())


def test_an_artist_marked_animated_takes_the_full_draw_and_stays_marked():
    def make():
        anim = plot.animate_arm(arms.two_metre, np.linspace([0.0, 0.0], [1.5, 1.5], 3))
        (marked,) = anim._fig.axes[0].plot([-3.0, 3.0], [-1.0, -1.0], animated=True)
        return anim

    fast_video, full_video, fast_draws, _ = _both_videos(make)
    assert fast_video == full_video and fast_draws == 3


def test_an_artist_that_shows_itself_later_needs_no_full_draw_per_frame():
    def make():
        anim = plot.animate_arm(arms.two_metre, np.linspace([0.0, 0.0], [1.5, 1.5], 5))
        ax = anim._fig.axes[0]
        (flag,) = ax.plot([1.0], [1.0], "s", visible=False)
        update = anim._func

        def showing(frame):
            flag.set_visible(frame >= 3)
            return [*update(frame), flag]

        anim._func = showing
        return anim

    fast_video, full_video, fast_draws, _ = _both_videos(make)
    assert fast_video == full_video and fast_draws == 1


def test_under_the_course_style_an_animations_own_figure_is_laid_out_once():
    """Constrained layout lays a figure out again at every draw (not always to the same
    place): an animation's own figure is laid out for its first frame and held, so its
    video is matplotlib's, drawn once."""

    def make():
        with figure_style.context():
            return plot.animate_arm(
                arms.two_metre, np.linspace([0.0, 0.0], [1.5, 1.5], 5), title="held"
            )

    from matplotlib.layout_engine import PlaceHolderLayoutEngine

    anim = make()
    assert isinstance(anim._fig.get_layout_engine(), PlaceHolderLayoutEngine)
    # the same figure's video, by twolink's writer and by matplotlib's
    fast_video, full_video, fast_draws, _ = _both_videos(make)
    assert fast_video == full_video and fast_draws == 1


def test_under_the_course_style_a_callers_figure_is_laid_out_once_when_its_video_is_made():
    """A figure the caller made (and drew more on) keeps its layout engine until
    animation_html takes the finished figure: then it is laid out once and each frame
    redraws only what moves, instead of a layout and a full draw per frame."""
    with figure_style.context():
        fig, ax = plt.subplots(figsize=(3.0, 3.0))
        anim = plot.animate_arm(
            arms.two_metre, np.linspace([0.0, 0.0], [1.5, 1.5], 8), ax=ax, title="mine"
        )
        ax.add_patch(Circle((1.0, 1.0), 0.5, alpha=0.3))  # drawn on after animate_arm
        engine = fig.get_layout_engine()
        assert engine is not None and engine.__class__.__name__ == (
            "ConstrainedLayoutEngine"
        )
        draws = _counting_draws(anim)
        shown = plot.animation_html(anim)
    assert "<video" in shown.data
    assert len(draws) == 1, f"{len(draws)} full draws for 8 frames"
    assert fig.get_layout_engine().__class__.__name__ == "PlaceHolderLayoutEngine"
