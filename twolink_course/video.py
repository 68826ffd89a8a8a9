"""Animations that remember what moves, and a video writer that redraws only that.

matplotlib's ``Animation.save`` draws the whole figure for every frame of a
video: axes, ticks, tick labels and title included, which is most of the time
a notebook spends on an animation.  :class:`MovingAnimation` records the
artists its frame function returns; :class:`BlittingFFMpegWriter` draws the
rest of the figure once and, for every frame, restores that picture and draws
over it only the artists at or above the lowest layer (zorder) of the moving
ones, in the order a full draw would use.  The frames are the same pixels a
full draw gives (``tests/course/test_video.py`` compares the videos byte for byte),
in a fraction of the time.  Anything the writer cannot prove the same (a
moving artist outside an axes, overlapping axes, a resolution other than the
figure's, other save options) takes matplotlib's full draw.
"""

from __future__ import annotations

import base64
import warnings
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from pathlib import Path
from tempfile import TemporaryDirectory
from typing import Any

import matplotlib
from matplotlib import animation
from matplotlib.artist import Artist
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.colors import to_rgba
from matplotlib.figure import Figure
from matplotlib.layout_engine import PlaceHolderLayoutEngine

__all__ = [
    "MovingAnimation",
    "BlittingFFMpegWriter",
    "html5_video",
    "frames_drawn_once",
]

#: matplotlib's ``Animation.to_html5_video`` tag, filled the same way.
VIDEO_TAG = """<video {size} {options}>
  <source type="video/mp4" src="data:video/mp4;base64,{video}">
  Your browser does not support the video tag.
</video>"""


class MovingAnimation(animation.FuncAnimation):
    """A :class:`matplotlib.animation.FuncAnimation` that keeps the artists each frame moved.

    ``update(frame)`` returns the artists it changed, as for blitting;
    :attr:`moved` holds those of the last frame drawn.

    Examples
    --------
    >>> import matplotlib.pyplot as plt
    >>> fig, ax = plt.subplots(figsize=(4.0, 3.0), dpi=80)
    >>> (line,) = ax.plot([0.0, 1.0], [0.0, 0.0])
    >>> def update(frame):
    ...     line.set_ydata([0.0, frame])
    ...     return [line]
    >>> anim = MovingAnimation(fig, update, frames=3)
    >>> import imageio_ffmpeg
    >>> with matplotlib.rc_context({"animation.ffmpeg_path": imageio_ffmpeg.get_ffmpeg_exe()}):
    ...     tag = html5_video(anim, embed_limit=5.0)
    >>> tag.splitlines()[0], anim.moved == [line]
    ('<video width="320" height="240" controls autoplay loop>', True)
    >>> plt.close(fig)
    """

    def __init__(
        self,
        fig: Figure,
        update: Callable[[Any], Iterable[Artist]],
        frames: Any = None,
        interval: float = 200.0,
    ) -> None:
        self.moved: list[Artist] = []
        #: milliseconds between frames
        self.interval = float(interval)
        #: whether the video loops (FuncAnimation's default)
        self.repeat = True

        def recorded(frame: Any) -> list[Artist]:
            self.moved = list(update(frame))
            return self.moved

        super().__init__(fig, recorded, frames=frames, interval=interval, blit=False)


class BlittingFFMpegWriter(animation.FFMpegWriter):
    """matplotlib's ffmpeg writer, drawing only the moving part of each frame.

    ``moving()`` returns the artists the current frame moved (for a
    :class:`MovingAnimation`, ``lambda: anim.moved``).  The command line,
    the frame size and the bytes sent to ffmpeg are those of
    :class:`matplotlib.animation.FFMpegWriter`; so is every frame the writer
    cannot draw exactly this way.
    """

    def __init__(self, moving: Callable[[], list[Artist]], **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self._moving = moving
        self._front: list[Artist] = []
        self._background: Any = None
        self._views: list[Any] = []
        self._children: list[int] = []

    def grab_frame(self, **savefig_kwargs: Any) -> None:
        figure = self.fig
        canvas = figure.canvas
        moved = self._moving()
        if not (
            self._drawable(figure, moved, savefig_kwargs)
            and isinstance(canvas, FigureCanvasAgg)
        ):
            self._release()
            super().grab_frame(**savefig_kwargs)
            return
        # as FFMpegWriter.grab_frame: the size its setup fixed (kept outside matplotlib's type stubs)
        self.fig.set_size_inches(getattr(self, "_w"), getattr(self, "_h"))  # noqa: B009
        axes_moved = _axes_of(moved)
        if (
            self._background is None
            or not set(moved) <= set(self._front)
            or self._views != _views(axes_moved)
            or self._children != _child_counts(axes_moved)
        ):
            self._draw_background(canvas, moved, axes_moved)
        canvas.restore_region(self._background)
        for artist in self._front:
            figure.draw_artist(artist)
        # the pipe to ffmpeg that FFMpegWriter.setup opened, as its own grab_frame writes to it
        getattr(self, "_proc").stdin.write(canvas.buffer_rgba())  # noqa: B009

    def finish(self) -> None:
        self._release()
        super().finish()

    def _drawable(
        self, figure: Figure, moved: list[Artist], savefig_kwargs: dict[str, Any]
    ) -> bool:
        """Whether the frame can be drawn over a background with the same pixels as a full draw."""
        if not moved or self.dpi != figure.dpi or self.frame_format != "rgba":
            return False
        engine = figure.get_layout_engine()
        if engine is not None and not isinstance(engine, PlaceHolderLayoutEngine):
            return False  # laid out again at every draw: only a full draw is that draw
        if set(savefig_kwargs) - {"facecolor", "transparent"} or savefig_kwargs.get(
            "transparent"
        ):
            return False
        if "facecolor" in savefig_kwargs and to_rgba(
            savefig_kwargs["facecolor"]
        ) != to_rgba(figure.get_facecolor()):
            return False
        axes_moved = _axes_of(moved)
        if any(artist.axes is None for artist in moved):
            return False
        for ax in axes_moved:
            if any(child.get_animated() for child in ax.get_children()):
                return False  # left out of a draw, drawn in a save: the background could not have them
            # another axes over this one would be drawn under its moving artists
            box = ax.get_position()
            for other in figure.axes:
                if other is not ax and other.get_position().overlaps(box):
                    return False
        return True

    def _draw_background(
        self, canvas: FigureCanvasAgg, moved: list[Artist], axes_moved: list[Any]
    ) -> None:
        """Draw the figure without the front artists and keep the picture."""
        self._release()

        lowest = min(artist.get_zorder() for artist in moved)
        front = []
        for ax in axes_moved:
            children = [child for child in ax.get_children() if child is not ax.patch]
            # a full draw draws an axes' children sorted by zorder (a stable sort)
            children.sort(key=lambda child: child.get_zorder())
            # hidden ones too: a moving artist may show itself later (drawing a
            # hidden artist draws nothing)
            front += [child for child in children if child.get_zorder() >= lowest]
        # marked animated, which a figure's draw leaves out, except while it is saved: so the
        # background is drawn as a figure not being saved (hidden artists would not do: a
        # hidden title is moved by the axes' title layout)
        # (the flag behind canvas.is_saving(), outside matplotlib's type stubs)
        saving = getattr(canvas, "_is_saving")  # noqa: B009
        for artist in front:
            artist.set_animated(True)
        setattr(canvas, "_is_saving", False)  # noqa: B010
        try:
            canvas.draw()
        finally:
            setattr(canvas, "_is_saving", saving)  # noqa: B010
            for artist in front:
                artist.set_animated(False)
        self._front = front
        self._background = canvas.copy_from_bbox(self.fig.bbox)
        self._views = _views(axes_moved)
        self._children = _child_counts(axes_moved)

    def _release(self) -> None:
        """Forget the background (the next frame drawn this way draws it again)."""
        self._front = []
        self._background = None


def _axes_of(artists: list[Artist]) -> list[Any]:
    """The axes holding ``artists``, each once, in order."""
    axes: list[Any] = []
    for artist in artists:
        if artist.axes is not None and artist.axes not in axes:
            axes.append(artist.axes)
    return axes


def _views(axes: list[Any]) -> list[Any]:
    return [tuple(ax.viewLim.bounds) for ax in axes]


def _child_counts(axes: list[Any]) -> list[int]:
    return [len(ax.get_children()) for ax in axes]


@contextmanager
def frames_drawn_once(anim: animation.Animation) -> Iterator[None]:
    """While saving ``anim``: no extra draw of the canvas after each frame.

    matplotlib's ``save`` draws each frame twice: once on the canvas after
    the frame's update (``draw_idle``) and again for the writer; only the
    second one is recorded, so the first is skipped.
    """
    # matplotlib keeps the figure in _fig, outside its type stubs
    canvas = getattr(anim, "_fig").canvas  # noqa: B009
    canvas.draw_idle = lambda *args, **kwargs: None
    try:
        yield
    finally:
        del canvas.draw_idle  # the class's method again


def html5_video(anim: MovingAnimation, embed_limit: float) -> str:
    """``anim.to_html5_video(embed_limit)``, the same tag and video, each frame drawn by :class:`BlittingFFMpegWriter`.

    Parameters
    ----------
    anim : MovingAnimation
    embed_limit : float
        Largest video embedded, in MB (base64); a larger one gives
        matplotlib's text ``"Video too large to embed."`` and a warning.
    """
    writer = BlittingFFMpegWriter(
        lambda: anim.moved,
        codec="h264",
        bitrate=matplotlib.rcParams["animation.bitrate"],
        fps=1000.0 / anim.interval,
    )
    with TemporaryDirectory() as folder, frames_drawn_once(anim):
        path = Path(folder, "temp.m4v")
        anim.save(str(path), writer=writer)
        video = base64.encodebytes(path.read_bytes())
    if len(video) >= embed_limit * 1024 * 1024:
        warnings.warn(
            f"the animation's video is {len(video)} bytes, over the embed limit of {embed_limit} MB: "
            "use fewer frames (max_frames) or a smaller figure",
            stacklevel=2,
        )
        return "Video too large to embed."
    options = "controls autoplay" + (" loop" if anim.repeat else "")
    width, height = writer.frame_size
    return VIDEO_TAG.format(
        video=video.decode("ascii"),
        size=f'width="{width}" height="{height}"',
        options=options,
    )
