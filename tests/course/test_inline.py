"""twolink_course.inline: a figure in a notebook output is a PNG of twice the pixels, shown at its
intended size, whose metadata carries its text alternative, and the site renders that as
the image's ``alt``."""

import base64
import io
import json
import os
import pathlib
import re
import subprocess
import sys
import textwrap

import matplotlib.pyplot as plt
import nbformat
import numpy as np
import pytest
from matplotlib.figure import Figure
from matplotlib.layout_engine import ConstrainedLayoutEngine
from nbclient import NotebookClient
from PIL import Image

from twolink import arms
from twolink.errors import InputTypeError
from twolink_course import alttext, figure_style, inline, plot

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(autouse=True)
def close_figures():
    yield
    plt.close("all")


def _pixels(png_base64):
    return Image.open(io.BytesIO(base64.b64decode(png_base64))).size


def _twice(size, metadata):
    """The PNG has twice the displayed pixels (the displayed size is half, rounded down)."""
    width, height = size
    return width // 2 == metadata["width"] and height // 2 == metadata["height"]


def test_png_output_is_twice_the_pixels_with_size_and_alt():
    with figure_style.context():
        ax = plot.setup_axes(arms.two_metre)
        plot.draw_arm(arms.two_metre, [0.5, 0.5], ax=ax)
    png, metadata = inline.png_output(ax.figure)
    assert set(metadata) == {"width", "height", "alt"}
    assert _twice(_pixels(png), metadata)
    assert metadata["width"] > 300  # 4 inches at 96 dpi, cropped to the drawing
    assert metadata["alt"] == alttext.describe(ax.figure)
    assert metadata["alt"].startswith("The arm at q = (28.6°, 28.6°)")


def test_png_output_of_an_empty_figure_is_nothing_and_junk_is_refused():
    assert inline.png_output(Figure()) is None
    with pytest.raises(InputTypeError, match="figure must be a matplotlib Figure"):
        inline.png_output(plt.gca())


def test_install_outside_ipython_changes_nothing():
    assert inline.install() is False


#: What one fresh interpreter says (an InteractiveShell is a process-wide singleton): first the
#: modules importing the package side loaded, then the course style installed in an IPython shell.
FRESH_PROCESS = textwrap.dedent("""
    import json, sys
    import twolink, twolink_course.figure_style, twolink_course.alttext, twolink_course.inline
    print(json.dumps(sorted(m for m in ('IPython', 'matplotlib.pyplot') if m in sys.modules)))
    from IPython.core.interactiveshell import InteractiveShell
    from matplotlib.figure import Figure
    from twolink_course import figure_style
    shell = InteractiveShell.instance()
    shell.display_formatter.formatters["image/svg+xml"].for_type(Figure, lambda f: "<svg/>")
    first, second = figure_style.use(), figure_style.use()
    figure = Figure(figsize=(2.0, 1.0))
    ax = figure.subplots()
    ax.set_xlabel("t [s]")
    data, metadata = shell.display_formatter.format(figure)
    print(json.dumps([first, second, sorted(data), metadata]))
""")


@pytest.fixture(scope="module")
def fresh_process():
    """The two lines ``FRESH_PROCESS`` prints, parsed."""
    env = {key: value for key, value in os.environ.items() if key != "MPLBACKEND"}
    env["MPLBACKEND"] = "Agg"
    done = subprocess.run(
        [sys.executable, "-c", FRESH_PROCESS],
        capture_output=True,
        text=True,
        timeout=120,
        cwd=ROOT,
        env=env,
    )
    assert done.returncode == 0, done.stderr[-3000:]
    return [json.loads(line) for line in done.stdout.splitlines()[-2:]]


def test_install_in_an_ipython_shell_formats_figures_with_alt(fresh_process):
    """In a fresh process (an InteractiveShell is a process-wide singleton)."""
    first, second, mimes, metadata = fresh_process[1]
    assert first is True and second is True
    assert mimes == ["image/png", "text/plain"]  # the svg formatter is gone
    assert metadata["image/png"]["alt"].startswith("Axes: t [s] from 0 to 1")
    assert metadata["image/png"]["width"] > 100


CELLS = [
    "from twolink_course import figure_style\nprint(figure_style.use(), figure_style.use())",
    "import numpy as np\nimport matplotlib.pyplot as plt\nfrom twolink import arms\nfrom twolink_course import plot\n"
    "ax = plot.setup_axes(arms.two_metre, title='The arm')\n"
    "plot.draw_arm(arms.two_metre, np.radians([30.0, 45.0]), ax=ax)\nplt.show()",
    "fig, ax = plt.subplots(figsize=(4.0, 3.0))\n"
    "ax.plot([0.0, 5.0], [1.0, 2.0], label='E')\nax.set_xlabel('t [s]')\n"
    "ax.set_ylabel('energy [J]')\nax.legend()\nplt.show()",
]


@pytest.fixture(scope="module")
def executed(tmp_path_factory):
    """The three cells run in a fresh kernel, as a chapter's would be."""
    notebook = nbformat.v4.new_notebook()
    notebook.cells = [nbformat.v4.new_code_cell(source) for source in CELLS]
    env = {key: value for key, value in os.environ.items() if key != "MPLBACKEND"}
    client = NotebookClient(
        notebook,
        timeout=120,
        kernel_name="python3",
        resources={"metadata": {"path": str(tmp_path_factory.mktemp("nb"))}},
    )
    client.execute(env=env)
    return notebook


def _images(cell):
    return [output for output in cell.outputs if "image/png" in output.get("data", {})]


def test_a_chapter_calls_use_once_and_again_harmlessly(executed):
    assert executed.cells[0].outputs[0]["text"] == "True True\n"


def test_a_drawn_figure_is_stored_sharp_at_its_size_with_its_sentence(executed):
    (output,) = _images(executed.cells[1])
    metadata = output["metadata"]["image/png"]
    assert metadata["alt"] == (
        "The arm. The arm at q = (30°, 45°), tip at (2.25, 2.93) m. "
        "Axes: x [m] from -4.6 to 4.6, y [m] from -4.6 to 4.6."
    )
    assert _twice(_pixels(output["data"]["image/png"]), metadata)


def test_a_plain_matplotlib_figure_gets_the_fallback(executed):
    (output,) = _images(executed.cells[2])
    metadata = output["metadata"]["image/png"]
    assert metadata["alt"] == (
        "It shows the line E. Axes: t [s] from -0.25 to 5.25, "
        "energy [J] from 0.95 to 2.05. Legend: E."
    )
    assert _twice(_pixels(output["data"]["image/png"]), metadata)
    assert 4.0 * figure_style.DPI * 0.8 < metadata["width"] <= 4.0 * figure_style.DPI


def test_the_site_renders_the_stored_alt_as_the_images_alt(executed):
    from nbconvert import HTMLExporter

    exporter = HTMLExporter(
        extra_template_basedirs=[str(ROOT / "tools" / "site_template")],
        template_name="course",
    )
    page, _ = exporter.from_notebook_node(executed)
    for cell in executed.cells[1:]:
        (output,) = _images(cell)
        metadata = output["metadata"]["image/png"]
        assert f'alt="{metadata["alt"]}"' in page
        assert re.search(rf'width="?{metadata["width"]}"?[ />]', page)
    assert "No description has been provided" not in page


def test_the_package_side_imports_no_ipython_and_no_pyplot(fresh_process):
    """Importing twolink and the kit's figure modules, in a fresh process, loads neither."""
    assert fresh_process[0] == []


def test_a_figure_laid_out_by_constrained_layout_is_stored_whole_not_cropped():
    from matplotlib.figure import Figure

    from twolink_course import figure_style

    sizes = {}
    for layout in ("constrained", "none"):
        with figure_style.context():
            figure = Figure(figsize=(3.0, 2.0), layout=layout)
        ax = figure.subplots()
        ax.plot([0.0, 1.0], [0.0, 1.0], label="a line")
        ax.set_xlabel("x [m]")
        ax.legend()
        png, metadata = inline.png_output(figure)
        sizes[layout] = (metadata["width"], metadata["height"])
    # constrained layout fits the canvas: stored as it is, without the crop's extra pass
    assert sizes["constrained"] == (round(3.0 * figure.dpi), round(2.0 * figure.dpi))
    # without a layout engine the backend crops to what was drawn
    assert sizes["none"] != sizes["constrained"]


def test_while_grading_a_figure_is_neither_drawn_nor_encoded(monkeypatch):
    with figure_style.context():
        ax = plot.setup_axes(arms.two_metre)
        plot.draw_arm(arms.two_metre, [0.5, 0.5], ax=ax)
    draws = []
    ax.figure.canvas.mpl_connect("draw_event", draws.append)
    monkeypatch.setenv("TWOLINK_GRADING", "1")
    assert inline.png_output(ax.figure) is None
    assert draws == []
    with pytest.raises(InputTypeError, match="figure must be a matplotlib Figure"):
        inline.png_output(plt.gca())
    monkeypatch.delenv("TWOLINK_GRADING")
    png, _ = inline.png_output(ax.figure)
    assert png and draws  # drawn without the switch


def _rgba(png):
    return np.asarray(Image.open(io.BytesIO(png)).convert("RGBA"))


def _busy_figure(facecolor="white"):
    """A pyplot figure (the inline backend's Agg canvas) with what a chapter's figures hold."""
    with figure_style.context():
        figure, (left, right) = plt.subplots(
            1, 2, figsize=(6.0, 3.0), facecolor=facecolor
        )
    left.plot([0.0, 1.0, 2.0], [0.0, 1.0, 4.0], label="a curve")
    left.set_xlabel("t [s]")
    left.set_ylabel("energy [J]")
    left.legend()
    left.annotate("a note", (1.0, 1.0))
    (moving,) = left.plot([0.5], [2.0], "o")
    moving.set_animated(True)  # drawn when saving, as savefig draws it
    image = right.imshow(np.arange(12.0).reshape(3, 4))
    figure.colorbar(image, ax=right, label="value")
    right.set_yscale("linear")
    figure.suptitle("Two panels")
    return figure


def test_a_constrained_figure_is_ipythons_retina_png_at_its_own_size():
    from IPython.core.pylabtools import retina_figure

    figure = _busy_figure()
    dpi = figure.dpi
    png, metadata = inline.png_output(figure)
    assert figure.dpi == dpi and not figure.canvas.is_saving()
    assert isinstance(figure.get_layout_engine(), ConstrainedLayoutEngine)
    assert (metadata["width"], metadata["height"]) == (
        round(6.0 * dpi),
        round(3.0 * dpi),
    )
    # the same figure made again, printed by IPython uncropped (a figure's second
    # print can differ from its first: constrained layout moves a colorbar's axes again)
    reference, size = retina_figure(_busy_figure(), bbox_inches=None)
    assert size == {"width": metadata["width"], "height": metadata["height"]}
    assert np.array_equal(_rgba(base64.b64decode(png)), _rgba(reference))
    assert _rgba(reference)[..., 3].min() == 255  # opaque, animated artist included


def test_a_transparent_figure_keeps_its_alpha_channel():
    png, _ = inline.png_output(_busy_figure(facecolor="none"))
    assert _rgba(base64.b64decode(png))[..., 3].min() < 255


# matplotlib_inline's observer of the option, which traitlets calls old-style
@pytest.mark.filterwarnings("ignore:InlineBackend._print_figure_kwargs_changed")
def test_changed_print_options_and_other_canvases_go_through_ipython(monkeypatch):
    from matplotlib_inline.config import InlineBackend

    figure = _busy_figure()
    draws = []
    figure.canvas.mpl_connect("draw_event", draws.append)
    monkeypatch.setattr(
        InlineBackend.instance(),
        "print_figure_kwargs",
        {"bbox_inches": "tight", "facecolor": "yellow"},
    )
    png, _ = inline.png_output(figure)
    assert len(draws) == 2  # IPython's print, with the reader's options
    assert tuple(_rgba(base64.b64decode(png))[0, 0]) == (255, 255, 0, 255)
    monkeypatch.undo()
    bare = Figure(figsize=(2.0, 1.0), layout="constrained")  # no Agg canvas of its own
    bare.subplots().plot([0.0, 1.0])
    png, metadata = inline.png_output(bare)
    assert _twice(_pixels(png), metadata)
