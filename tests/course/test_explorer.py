"""twolink_course.explorer: controls labelled with units on round grids, a figure drawn
once and moved in place, and what an explorer stores for static pages."""

import asyncio
import base64

import matplotlib
import matplotlib.pyplot as plt
import numpy as np
import pytest
from _cases import in_fresh_thread

from twolink import arms
from twolink.errors import InputTypeError
from twolink_course import explorer, figure_style, plot

ARM = arms.two_metre


def _arm_explorer(**kwargs):
    figure, ax = explorer.explorer_figure(3.0, 3.0)
    plot.setup_axes(ARM, ax=ax)
    line = plot.draw_arm(ARM, [0.0, 0.0], ax=ax)
    calls = []

    def update(q1, q2):
        calls.append((q1, q2))
        plot.move_arm(line, ARM, np.radians([q1, q2]))

    def describe(q1, q2):
        x, y = ARM.fk(np.radians([q1, q2]))
        return f"The arm at q = ({q1}°, {q2}°), tip at ({x:.2f}, {y:.2f}) m."

    controls = {
        "q1": explorer.slider("q1", "deg", 30, -180, 180, 5),
        "q2": explorer.slider("q2", "deg", 45, -180, 180, 5),
    }
    view = explorer.Explorer(figure, update, controls, describe=describe, **kwargs)
    return view, line, calls


def test_the_figure_is_drawn_once_and_moved_in_place():
    view, line, calls = _arm_explorer()
    artists_before = list(view.figure.axes[0].get_children())
    view.set(q1=90, q2=0)
    view.controls["q2"].value = 90
    assert calls == [(30, 45), (90, 0), (90, 90)]
    assert view.updates == 3
    assert list(view.figure.axes[0].get_children()) == artists_before
    np.testing.assert_allclose(line.get_xydata()[-1], [-2.0, 2.0], atol=1e-12)
    assert view.description == "The arm at q = (90°, 90°), tip at (-2.00, 2.00) m."


def test_a_change_to_the_same_value_does_not_update():
    view, _, calls = _arm_explorer()
    view.set(q1=30)
    assert calls == [(30, 45)]


def test_the_explorers_figure_stays_out_of_pyplot_and_keeps_its_backend():
    backend = matplotlib.get_backend()
    before = plt.get_fignums()
    view, _, _ = _arm_explorer()
    assert plt.get_fignums() == before
    assert matplotlib.get_backend() == backend
    from ipympl.backend_nbagg import Canvas

    assert isinstance(view.figure.canvas, Canvas)
    canvas = view.figure.canvas
    assert not (canvas.toolbar_visible or canvas.header_visible or canvas.resizable)


def test_display_stores_widgets_a_png_of_the_first_state_and_its_description():
    view, _, _ = _arm_explorer()
    data, metadata = view._repr_mimebundle_()
    assert "application/vnd.jupyter.widget-view+json" in data
    png = base64.b64decode(data["image/png"])
    assert png.startswith(b"\x89PNG") and png == view.png(figure_style.PIXEL_SCALE)
    assert data["text/plain"] == view.description
    assert metadata["image/png"]["alt"] == view.description
    assert metadata["image/png"]["width"] == 288  # 3 in at 96 dpi
    # stored at twice the pixels, shown at the intended size
    assert int.from_bytes(png[16:20], "big") == 2 * 288


def test_without_describe_the_stored_picture_is_described_by_its_drawing():
    figure, ax = explorer.explorer_figure(3.0, 3.0)
    plot.setup_axes(ARM, ax=ax)
    line = plot.draw_arm(ARM, [0.0, 0.0], ax=ax)
    view = explorer.Explorer(
        figure,
        lambda q1: plot.move_arm(line, ARM, np.radians([q1, 0.0])),
        {"q1": explorer.slider("q1", "deg", 90, -180, 180, 1)},
    )
    _, metadata = view._repr_mimebundle_()
    assert metadata["image/png"]["alt"].startswith(
        "An interactive figure with q1 [deg]. The arm at q = (90°, 0°), tip at (0.00, 4.00) m."
    )


def test_the_layout_holds_controls_extra_canvas_and_description():
    import ipywidgets as widgets

    button = widgets.Button(description="exact run")
    view, _, _ = _arm_explorer(extra=[button])
    children = view.widget.children
    assert children[:2] == tuple(view.controls.values())
    assert children[2] is button and children[3] is view.figure.canvas
    assert view.description in children[4].value


def test_set_refuses_unknown_controls():
    view, _, _ = _arm_explorer()
    with pytest.raises(
        ValueError, match=r"no control named \['q3'\]; the controls are"
    ):
        view.set(q3=1)


@pytest.mark.parametrize(
    ("figure", "update", "controls", "message"),
    [
        (
            "not a figure",
            lambda: None,
            {"a": None},
            "figure must be a matplotlib Figure",
        ),
        (None, 3, {}, "update and describe must be callables"),
        (None, lambda: None, {}, "controls must be a non-empty mapping"),
        (None, lambda: None, {"not an id": None}, "must be named by an identifier"),
    ],
)
def test_explorer_refuses_what_it_cannot_use(figure, update, controls, message):
    if figure is None:
        figure, _ = explorer.explorer_figure(2.0, 2.0)
    if controls and "a" not in controls:
        controls = {"not an id": explorer.slider("x", "m", 0, 0, 1, 1)}
    with pytest.raises(InputTypeError, match=message):
        explorer.Explorer(figure, update, controls)


def test_an_inline_figure_is_refused_with_the_way_to_make_one():
    figure = plt.figure()
    with pytest.raises(InputTypeError, match="explorer_figure"):
        explorer.Explorer(
            figure, lambda: None, {"x": explorer.slider("x", "m", 0, 0, 1, 1)}
        )
    plt.close(figure)


def test_slider_labels_steps_and_readouts():
    angle = explorer.slider("q1", "deg", 30, -180, 180, 5)
    assert (angle.description, angle.min, angle.max, angle.step) == (
        "q1 [deg]",
        -180,
        180,
        5,
    )
    stiffness = explorer.slider("stiffness k", "N/m", 600.0, 50.0, 3000.0, 50.0)
    assert stiffness.readout_format == ".0f"
    position = explorer.slider("position", "", 0.25, 0.0, 1.0, 0.005)
    assert position.description == "position" and position.readout_format == ".3f"
    assert not explorer.slider(
        "m1", "kg", 1.0, 0.1, 5.0, 0.1, continuous=False
    ).continuous_update


def test_the_track_grows_with_the_number_of_steps_within_limits():
    def track(slider):
        return int(slider.layout.width.split("+ ")[1].rstrip("px)")) - 90

    few = explorer.slider("a", "m", 0, 0, 10, 1)
    many = explorer.slider("b", "m", 0, 0, 250, 1)
    most = explorer.slider("c", "m", 0, 0, 2000, 1)
    assert track(few) == explorer.TRACK_MIN_PX
    assert track(many) == 250 * explorer.PIXELS_PER_STEP
    assert track(most) == explorer.TRACK_MAX_PX


@pytest.mark.parametrize(
    ("arguments", "message"),
    [
        (
            ("x", "m", 0.25, 0.0, 1.0, 0.1),
            r"start value 0.25 is not on the grid 0 \+ k 0.1",
        ),
        (("x", "m", 2.0, 0.0, 1.0, 0.5), "not on the grid 0 \\+ k 0.5 within 0..1"),
        (("x", "m", 0.0, 0.0, 1.0, 0.3), "not a whole number of steps of 0.3"),
        (("x", "m", 0.0, 1.0, 1.0, 0.1), "minimum must be below the maximum"),
        (("x", "m", 0.0, 0.0, 1.0, 0.0), "step of x \\[m\\]"),
        (("x", "m", 0.0, 0.0, 1.0, 1e-4), "more than MAX_STEPS"),
        (("x", "m", float("nan"), 0.0, 1.0, 0.1), "value of x \\[m\\]"),
    ],
)
def test_slider_refuses_grids_that_do_not_land_on_round_values(arguments, message):
    with pytest.raises(ValueError, match=message):
        explorer.slider(*arguments)


@pytest.mark.parametrize("label", ["", "   ", None, 3])
def test_a_control_needs_a_label_in_words(label):
    with pytest.raises(InputTypeError, match="label in words"):
        explorer.slider(label, "m", 0, 0, 1, 1)


def test_range_slider_and_choice():
    limits = explorer.range_slider("q1 limits", "deg", (0, 90), -180, 180, 5)
    assert (limits.description, limits.value) == ("q1 limits [deg]", (0, 90))
    with pytest.raises(ValueError, match="must be ordered"):
        explorer.range_slider("q1 limits", "deg", (90, 0), -180, 180, 5)
    with pytest.raises(InputTypeError, match="takes ints"):
        explorer.range_slider("q1 limits", "deg", (0.5, 90), -180, 180, 5)
    elbow = explorer.choice("elbow", ["down", "up"], "up")
    assert (elbow.description, elbow.value) == ("elbow", "up")
    with pytest.raises(ValueError, match=r"must be one of \['down', 'up'\]"):
        explorer.choice("elbow", ["down", "up"], "left")
    with pytest.raises(InputTypeError, match="options must be words"):
        explorer.choice("elbow", [1, 2], 1)


def test_explorer_figure_sizes_and_columns():
    figure, axes = explorer.explorer_figure(8.0, 3.0, ncols=2)
    assert len(axes) == 2 and tuple(figure.get_size_inches()) == (8.0, 3.0)
    with pytest.raises(ValueError, match="ncols must be a positive int"):
        explorer.explorer_figure(3.0, 3.0, ncols=0)
    with pytest.raises(ValueError, match="width"):
        explorer.explorer_figure(-1.0, 3.0)


def test_move_arm_refuses_what_draw_arm_did_not_return():
    with pytest.raises(InputTypeError, match="Line2D draw_arm returned"):
        plot.move_arm("line", ARM, [0.0, 0.0])


def test_set_with_several_values_updates_once():
    view, _, calls = _arm_explorer()
    view.set(q1=90, q2=0)
    assert calls == [(30, 45), (90, 0)]


def test_the_site_template_gives_a_described_png_its_alternative_text(tmp_path):
    import nbformat
    from nbconvert import HTMLExporter

    view, _, _ = _arm_explorer()
    data, metadata = view._repr_mimebundle_()
    data.pop("application/vnd.jupyter.widget-view+json")  # stored without widget state
    notebook = nbformat.v4.new_notebook()
    cell = nbformat.v4.new_code_cell("view")
    cell.outputs = [
        nbformat.v4.new_output("display_data", data=data, metadata=metadata)
    ]
    notebook.cells = [cell]
    root = __import__("pathlib").Path(__file__).resolve().parents[2]
    exporter = HTMLExporter(
        extra_template_basedirs=[str(root / "tools" / "site_template")],
        template_name="course",
    )
    page, _ = exporter.from_notebook_node(notebook)
    assert f'alt="{view.description}"' in page


NOTEBOOKS = sorted(
    (__import__("pathlib").Path(__file__).resolve().parents[2] / "notebooks").glob(
        "*.ipynb"
    )
)


def _globals_read_by_functions(table):
    """Global names read inside the functions (at any depth) of a symbol table."""
    names = set()
    for child in table.get_children():
        if child.get_type() == "function":
            names |= {
                symbol.get_name()
                for symbol in child.get_symbols()
                if symbol.is_global() and symbol.is_referenced()
            }
        names |= _globals_read_by_functions(child)
    return names


def _function_reads(table):
    """Top-level functions of a cell -> the global names each reads (at any depth)."""
    return {
        child.get_name(): {
            symbol.get_name()
            for symbol in child.get_symbols()
            if symbol.is_global() and symbol.is_referenced()
        }
        | _globals_read_by_functions(child)
        for child in table.get_children()
        if child.get_type() == "function"
    }


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[path.name for path in NOTEBOOKS])
def test_no_later_cell_rebinds_a_name_an_explorer_moves(path):
    """An explorer's update runs long after its cell, when every cell has run: a
    global it reads (``ax``, ``line``) that a later cell rebinds would make the
    sliders move another figure.  The names read by the functions of the
    explorer's cell count, and so do those read by the functions of earlier
    cells that they call (at any depth).  Build explorers inside a function, or
    give what they draw names of their own."""
    import symtable

    import nbformat
    from IPython.core.inputtransformer2 import TransformerManager

    to_python = TransformerManager().transform_cell
    cells = [
        to_python(cell.source)
        for cell in nbformat.read(path, as_version=4).cells
        if cell.cell_type == "code"
    ]
    tables = [symtable.symtable(source, "cell", "exec") for source in cells]
    problems = []
    for index, source in enumerate(cells):
        if "explorer.Explorer(" not in source:
            continue
        defined = {}  # function name -> names it reads, the latest definition first
        for earlier in tables[:index]:
            defined.update(_function_reads(earlier))
        read = _globals_read_by_functions(tables[index])
        pending = list(read)
        while pending:
            name = pending.pop()
            for more in defined.pop(name, set()) - read:
                read.add(more)
                pending.append(more)
        for later_index in range(index + 1, len(cells)):
            rebound = {
                symbol.get_name()
                for symbol in tables[later_index].get_symbols()
                if symbol.is_assigned() or symbol.is_imported()
            }
            for name in sorted(read & rebound):
                problems.append(
                    f"code cell {index} builds an explorer whose functions read {name!r} "
                    f"(directly or through a function they call), which code cell "
                    f"{later_index} rebinds"
                )
    assert problems == []


def test_redraw_shows_a_change_made_outside_the_update_and_its_description():
    view, line, _ = _arm_explorer()
    view.figure.canvas.draw()  # as the browser's first request
    line.set_data([0.0, -1.0], [0.0, -1.0])  # what a button would do
    view.redraw("A button moved the arm to (-1, -1) m.")
    assert view.description == "A button moved the arm to (-1, -1) m."
    assert view.description in view.widget.children[-1].value
    pixels = np.asarray(view.figure.canvas.buffer_rgba())
    fresh = np.asarray(_png_pixels(view.png()))
    assert pixels.shape == fresh.shape and np.array_equal(
        pixels[..., :3], fresh[..., :3]
    )


def _png_pixels(png):
    import io

    from PIL import Image

    return Image.open(io.BytesIO(png)).convert("RGBA")


def test_blitted_moves_show_the_same_pixels_as_a_full_draw():
    view, _, _ = _arm_explorer()
    canvas = view.figure.canvas
    canvas.draw()
    for q1 in (40, 55, 70):  # the first move redraws, the next ones blit
        view.set(q1=q1)
    assert view._background is not None
    blitted = np.asarray(canvas.buffer_rgba()).copy()
    fresh = np.asarray(_png_pixels(view.png()))
    assert np.array_equal(blitted[..., :3], fresh[..., :3])


def test_the_rebinding_check_follows_functions_defined_in_earlier_cells(tmp_path):
    import nbformat

    notebook = nbformat.v4.new_notebook()
    notebook.cells = [
        nbformat.v4.new_code_cell("figure, ax = explorer.explorer_figure(3.0, 3.0)"),
        nbformat.v4.new_code_cell("def move(q1):\n    ax.set_title(str(q1))"),
        nbformat.v4.new_code_cell(
            "def update(q1):\n    move(q1)\n\n"
            "view = explorer.Explorer(figure, update, {})"
        ),
        nbformat.v4.new_code_cell("fig, ax = plt.subplots()"),
    ]
    path = tmp_path / "chapter.ipynb"
    nbformat.write(notebook, path)
    with pytest.raises(AssertionError, match="read 'ax' .*which code cell 3 rebinds"):
        test_no_later_cell_rebinds_a_name_an_explorer_moves(path)


def test_a_move_redraws_neither_the_axes_nor_the_figure_a_new_limit_does():
    view, _, _ = _arm_explorer()
    ax = view.figure.axes[0]
    assert ax.get_axisbelow() is True  # ticks and grid under the moving artists
    view.figure.canvas.draw()
    view.set(q1=40)  # the first move after a draw by someone else redraws
    full = view.full_redraws
    for q1 in (50, 60, 70):
        view.set(q1=q1)
    assert view.full_redraws == full
    assert not any(isinstance(a, (matplotlib.axis.Axis,)) for a in view._animated)
    ax.set_xlim(-5.0, 5.0)
    view.set(q1=80)
    assert view.full_redraws == full + 1


def test_while_the_hand_moves_the_sentence_waits_and_only_the_last_is_sent():
    in_fresh_thread(_drag_then_stop)


def _drag_then_stop():
    view, _, _ = _arm_explorer()
    text = view.widget.children[-1]
    assert "(30°, 45°)" in text.value  # the first sentence at once
    sent = []
    text.observe(lambda change: sent.append(change.new), names="value")

    async def drag():
        for q1 in (40, 50, 60):
            view.set(q1=q1)
            assert f"({q1}°, 45°)" in view.description  # known at once
            await asyncio.sleep(explorer.DESCRIPTION_DELAY / 10)
        assert sent == []  # the page is not asked to lay out a sentence per move
        await asyncio.sleep(explorer.DESCRIPTION_DELAY * 2)

    asyncio.run(drag())
    assert len(sent) == 1 and "(60°, 45°)" in sent[0]
    view.set(q1=70)  # no event loop (a script): at once
    assert "(70°, 45°)" in text.value
    view.redraw("A button's sentence.")  # a button: at once
    assert "A button&#x27;s sentence." in text.value


def test_an_empty_title_does_not_make_every_move_redraw_the_legend():
    figure, ax = explorer.explorer_figure(3.0, 3.0)
    plot.setup_axes(ARM, ax=ax)
    # the arm drawn above everything, so a move redraws the arm alone
    line = plot.draw_arm(ARM, [0.0, 0.0], ax=ax, label="arm")
    line.set_zorder(10)
    legend = ax.legend(loc="lower left")

    def update(q1):
        plot.move_arm(line, ARM, np.radians([q1, 0.0]))

    view = explorer.Explorer(
        figure, update, {"q1": explorer.slider("q1", "deg", 30, 0, 90, 5)}
    )
    figure.canvas.draw()
    for q1 in (35, 40, 45):
        view.set(q1=q1)
    assert ax.get_title() == ""
    assert ax.title not in view._animated and legend not in view._animated
    assert view._animated == [line]
    ax.set_title("now with a title")  # a real change is still seen
    view.set(q1=50)
    assert ax.title in view._animated


def test_the_canvas_is_ipympls_own_and_keeps_no_data_url_of_its_own():
    import ipympl.backend_nbagg as backend

    view, _, _ = _arm_explorer()
    canvas = view.figure.canvas
    assert type(canvas) is backend.Canvas
    view.set(q1=40)
    # ipympl's copy (base64 without the "data:" prefix) would make the page draw a broken image
    assert canvas._data_url is None and canvas.syncing_data_url is False


def test_a_draw_the_page_asks_for_waits_until_a_move_in_another_thread_is_done():
    import threading

    view, _, _ = _arm_explorer()
    canvas = view.figure.canvas
    drawn = threading.Event()

    def page_asks_for_a_picture():
        canvas.draw()  # what ipympl's handle_draw calls, on a subshell's thread
        drawn.set()

    with view._lock:  # a move in progress on the main thread
        other = threading.Thread(target=page_asks_for_a_picture)
        other.start()
        assert not drawn.wait(0.3), "the page's draw ran in the middle of a move"
    assert drawn.wait(10.0)
    other.join()


@pytest.mark.parametrize("width, height", [(6.6, 3.0), (7.2, 2.9), (4.0, 4.6)])
def test_an_explorer_figure_has_whole_pixels(width, height):
    figure, _ = explorer.explorer_figure(width, height)
    pixels = figure.bbox.size
    assert np.allclose(pixels, np.round(pixels), atol=1e-9), pixels
    assert np.allclose(pixels, np.array([width, height]) * figure.dpi, atol=0.5)


def test_while_grading_an_explorer_updates_and_describes_but_draws_nothing(
    monkeypatch,
):
    import ipywidgets as widgets

    taught, taught_line, taught_calls = _arm_explorer()
    monkeypatch.setenv("TWOLINK_GRADING", "1")
    graded, graded_line, graded_calls = _arm_explorer()
    assert taught.drawn and not graded.drawn
    assert not isinstance(graded.figure.canvas, widgets.DOMWidget)  # no ipympl canvas
    draws = []
    graded.figure.canvas.mpl_connect("draw_event", draws.append)
    for view in (taught, graded):
        view.set(q1=90, q2=0)
        view.controls["q2"].value = 90
        view.redraw()
    # the same updates, descriptions and artists as the drawn explorer
    assert graded_calls == taught_calls == [(30, 45), (90, 0), (90, 90)]
    assert graded.updates == taught.updates == 3
    assert graded.values == taught.values
    assert graded.description == taught.description
    # the sentence under the figure is written at once, or DESCRIPTION_DELAY after a
    # move when an event loop runs in this thread (one left by an earlier test):
    # written at once here, so the check does not depend on the tests before it
    graded.redraw(graded.description)
    assert graded.description in graded.widget.children[-1].value
    np.testing.assert_array_equal(graded_line.get_xydata(), taught_line.get_xydata())
    assert draws == [] and graded.full_redraws == 0 < taught.full_redraws
    # shown as its description and a note: no widget view, no picture
    data, metadata = graded._repr_mimebundle_()
    assert set(data) == {"text/plain", "text/html"} and metadata == {}
    assert data["text/plain"] == (
        f"{graded.description}\n"
        "(interactive figure skipped while grading (TWOLINK_GRADING=1))"
    )
    assert graded.figure.canvas not in graded.widget.children
    # a picture asked for explicitly is still drawn
    assert graded.png().startswith(b"\x89PNG")


def test_while_grading_an_explorer_still_refuses_what_it_cannot_use(monkeypatch):
    monkeypatch.setenv("TWOLINK_GRADING", "1")
    figure, _ = explorer.explorer_figure(3.0, 3.0)
    with pytest.raises(InputTypeError, match="controls must be a non-empty mapping"):
        explorer.Explorer(figure, lambda: None, {})
    with pytest.raises(InputTypeError, match="figure must be a matplotlib Figure"):
        explorer.Explorer(
            None, lambda q1: None, {"q1": explorer.slider("q1", "deg", 0, 0, 9, 1)}
        )
    monkeypatch.setenv("TWOLINK_GRADING", "yes")
    with pytest.raises(ValueError, match="TWOLINK_GRADING must be"):
        explorer.explorer_figure(3.0, 3.0)
