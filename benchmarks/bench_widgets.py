"""Explorers at the speed of the hand: key press to a changed picture, in JupyterLab.

For every chapter this opens the notebook in JupyterLab in headless Chromium
(the browser suite's server and browser, ``tools/lab_browser.py``), runs all
cells (timed from the menu click to the kernel going idle), then moves every
slider of every explorer with the arrow keys and measures, in the page, the
time from the key press to the first animation frame whose picture differs:
the pixels of the explorer's canvases (ipympl), or an ``<img>`` source or an
``<svg>`` (older explorers).  A burst of quick presses then measures how long
the picture keeps changing after the last one ("settle").

Prints one row per chapter: the median, 95th percentile and worst latency over
all moves, the settle time and the Run All time, beside the targets on these
2-core machines (median <= 50 ms, 95th percentile <= 100 ms, Run All <= 8 s).

Run with ``make bench-widgets`` or ``.venv/bin/python benchmarks/bench_widgets.py``
(``--quick``: chapter 1 only, two moves per slider; ``--chapters 03 05`` for
some).  The server is the course's (``make lab``: kernel messages without
Nagle's delay, ``tools/lab_server/twolink_nodelay.py``); ``--stock-server``
measures a plain one.  Needs Chromium (``apt-get install -y chromium``).
"""

from __future__ import annotations

import argparse
import math
import platform
import re
import statistics
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tools"))

import course_map  # noqa: E402
import lab_browser  # noqa: E402

from twolink_course.display import markdown_table  # noqa: E402

TARGET_MEDIAN_MS = 50.0
TARGET_P95_MS = 100.0
TARGET_RUN_ALL_S = 8.0
#: An explorer's box: twolink_course.explorer.CSS_CLASS (an ipywidgets `interactive`
#: before it, measured for comparison).
EXPLORER = ".twolink-explorer, .widget-interact"
#: No change within this long counts as a miss (reported, worst = this).
TIMEOUT_MS = 5000.0

# In the page: a signature of what an explorer shows (canvas pixels, image
# sources, svg markup), as a JavaScript function of the element ``box``.
SIGNATURE = """(box => {
    let hash = 0;
    for (const canvas of box.querySelectorAll('canvas')) {
      if (!canvas.width || !canvas.height) continue;
      const data = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height).data;
      for (let i = 0; i < data.length; i += 8) hash = (hash * 31 + data[i]) | 0;
    }
    for (const image of box.querySelectorAll('img'))
      for (let i = 0; i < image.src.length; i += 97) hash = (hash * 31 + image.src.charCodeAt(i)) | 0;
    for (const svg of box.querySelectorAll('svg')) hash = (hash * 31 + svg.outerHTML.length) | 0;
    return hash;
})"""

# A watcher started before a key press: it resolves with the milliseconds from
# the key down to the first frame whose signature differs.
WATCH = """
([box, timeoutMs]) => {
  const signature = () => SIGNATURE(box);
  const before = signature();
  window.__twolinkLatency = new Promise(resolve => {
    let start = null;
    document.addEventListener('keydown', () => { start = performance.now(); }, {capture: true, once: true});
    const tick = () => {
      if (start !== null) {
        if (signature() !== before) { resolve(performance.now() - start); return; }
        if (performance.now() - start > timeoutMs) { resolve(null); return; }
      }
      requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  });
}
""".replace("SIGNATURE", SIGNATURE)

# After a burst: resolve with the time from the last key press to the last
# frame whose picture changed, once it has been still for a second.
SETTLE = """
async ([box]) => {
  const signature = () => SIGNATURE(box);
  const lastKey = window.__twolinkLastKey;
  let last = signature(), changedAt = performance.now();
  return await new Promise(resolve => {
    const tick = () => {
      const now = performance.now(), current = signature();
      if (current !== last) { last = current; changedAt = now; }
      if (now - changedAt > 1000) { resolve(Math.max(0, changedAt - lastKey)); return; }
      requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  });
}
""".replace("SIGNATURE", SIGNATURE)


def open_and_run(page, lab, path: Path) -> float:
    """Open the chapter, run all cells; the Run All time in seconds."""
    page.goto(
        f"{lab['url']}/lab/workspaces/bench-{path.stem}/tree/{path.name}?reset&token={lab['token']}"
    )
    panel = page.locator(".jp-NotebookPanel:not(.lm-mod-hidden)")
    panel.locator(".jp-Cell").first.wait_for(timeout=90_000)
    dialog = page.locator(".jp-Dialog .jp-mod-accept")
    if dialog.count():
        dialog.first.click()
    idle = """() => {
        const bar = document.querySelector('#jp-main-statusbar');
        return bar && /\\|\\s*Idle/.test(bar.innerText);
    }"""
    page.wait_for_function(idle, timeout=90_000)
    start = time.monotonic()
    page.locator(".lm-MenuBar-itemLabel", has_text=re.compile(r"^Run$")).click()
    page.locator(".lm-Menu-itemLabel", has_text=re.compile(r"^Run All Cells$")).click()
    page.wait_for_function(
        """() => {
            const prompts = [...document.querySelectorAll(
                '.jp-NotebookPanel:not(.lm-mod-hidden) .jp-CodeCell .jp-InputPrompt')];
            return prompts.length > 0 && prompts.every(p => /\\[\\d+\\]/.test(p.innerText));
        }""",
        timeout=300_000,
    )
    page.wait_for_function(idle, timeout=300_000)
    return time.monotonic() - start


def move(page, box, handle, key: str) -> float | None:
    """Press ``key`` on a slider handle; milliseconds to a changed picture (None: no change)."""
    box_handle = box.element_handle()
    page.evaluate(WATCH, [box_handle, TIMEOUT_MS])
    handle.press(key)
    return page.evaluate("() => window.__twolinkLatency")


def measure_chapter(page, lab, path: Path, moves: int) -> dict:
    run_all = open_and_run(page, lab, path)
    panel = ".jp-NotebookPanel:not(.lm-mod-hidden)"
    boxes = page.locator(", ".join(f"{panel} {box}" for box in EXPLORER.split(", ")))
    latencies: list[float] = []
    misses = 0
    settles: list[float] = []
    sliders_total = 0
    for index in range(boxes.count()):
        box = boxes.nth(index)
        box.scroll_into_view_if_needed()
        # as a reader's hand reaches the slider after the figure appears: the
        # canvas's first picture (requested by the page when shown) is in
        page.wait_for_timeout(500)
        sliders = box.locator(".widget-slider")
        sliders_total += sliders.count()
        for slider_index in range(sliders.count()):
            handle = sliders.nth(slider_index).locator(".noUi-handle").first
            for step in range(moves):
                # there and back, so a slider at an end still moves
                key = "ArrowRight" if step % 2 == 0 else "ArrowLeft"
                latency = move(page, box, handle, key)
                if latency is None:
                    misses += 1
                    latencies.append(TIMEOUT_MS)
                else:
                    latencies.append(latency)
            # a burst: ten presses 30 ms apart, as a held key or a quick drag
            for press in range(10):
                handle.press("ArrowRight" if press % 2 == 0 else "ArrowLeft")
                page.evaluate("() => { window.__twolinkLastKey = performance.now(); }")
                page.wait_for_timeout(30)
            settles.append(page.evaluate(SETTLE, [box.element_handle()]))
    ordered = sorted(latencies)
    # nearest rank: the smallest value at or above 95 % of the moves
    p95 = ordered[math.ceil(0.95 * len(ordered)) - 1] if ordered else None
    return {
        "chapter": path.stem,
        "explorers": boxes.count(),
        "sliders": sliders_total,
        "moves": len(latencies),
        "misses": misses,
        "median": statistics.median(latencies) if latencies else None,
        "p95": p95,
        "worst": max(latencies) if latencies else None,
        "settle": max(settles) if settles else None,
        "run_all": run_all,
    }


def _ms(value: float | None) -> str:
    return "-" if value is None else f"{value:.0f}"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument(
        "--quick", action="store_true", help="chapter 1, two moves per slider"
    )
    parser.add_argument("--chapters", nargs="*", help="chapter numbers, e.g. 03 05")
    parser.add_argument("--moves", type=int, default=10, help="key presses per slider")
    parser.add_argument(
        "--stock-server",
        action="store_true",
        help="without the course's server extension (Nagle's algorithm left on), for comparison",
    )
    args = parser.parse_args(argv)
    reason = lab_browser.missing()
    if reason:
        print(f"bench_widgets: skipped: {reason}")
        return 0
    notebooks = course_map.chapters(ROOT / "notebooks")
    if args.quick:
        notebooks, args.moves = notebooks[:1], 2
    elif args.chapters:
        notebooks = [path for path in notebooks if path.name[:2] in args.chapters]
    rows = []
    with (
        tempfile.TemporaryDirectory() as home,
        lab_browser.jupyterlab(Path(home), nodelay=not args.stock_server) as lab,
    ):
        with lab_browser.chromium() as browser:
            for path in notebooks:
                context = browser.new_context(viewport={"width": 1400, "height": 1000})
                page = context.new_page()
                try:
                    rows.append(measure_chapter(page, lab, path, args.moves))
                finally:
                    context.close()
                    lab_browser.shut_down_kernels(lab)
    print(
        f"# Explorers: key press to a changed picture, JupyterLab in headless Chromium "
        f"({platform.machine()}, {platform.python_implementation()} {platform.python_version()}"
        f"{'; stock server, Nagle on' if args.stock_server else ''})\n"
    )
    table = []
    for row in rows:
        meets = (
            row["moves"] == 0
            or (row["median"] <= TARGET_MEDIAN_MS and row["p95"] <= TARGET_P95_MS)
        ) and row["run_all"] <= TARGET_RUN_ALL_S
        table.append(
            [
                row["chapter"],
                str(row["explorers"]),
                str(row["sliders"]),
                f"{row['moves']} ({row['misses']} missed)",
                _ms(row["median"]),
                _ms(row["p95"]),
                _ms(row["worst"]),
                _ms(row["settle"]),
                f"{row['run_all']:.1f}",
                "yes" if meets else "NO",
            ]
        )
    print(
        markdown_table(
            [
                "chapter",
                "explorers",
                "sliders",
                "moves",
                "median [ms]",
                "p95 [ms]",
                "worst [ms]",
                "settle after a burst [ms]",
                "Run All [s]",
                "meets",
            ],
            table,
        )
    )
    print(
        f"\nTargets: median <= {TARGET_MEDIAN_MS:.0f} ms and 95th percentile <= "
        f"{TARGET_P95_MS:.0f} ms over all moves; Run All <= {TARGET_RUN_ALL_S:.0f} s."
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
