"""The prebuilt JupyterLab extension twolink-figure-alt (labextension/): built from
its source, shipped by the wheel and installed in this venv.

It sets a figure's ``<img alt>`` from the output metadata in JupyterLab (the
mime extension, labextension/src/index.ts), and (the plugin,
labextension/src/a11y.ts) names ipywidgets' slider handles by their widget's
description and makes outputs that scroll focusable; the browser tests that
it does are tests/browser/test_chapters_in_jupyterlab.py -k "alt or slider".
Its build output is committed, so a change of the source without a rebuild
(``.venv/bin/python labextension/build.py``, needs Node.js) must fail here.
"""

import glob
import hashlib
import json
import pathlib
import re
import subprocess
import sys
import tomllib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
SOURCE_DIR = ROOT / "labextension"
BUILT = SOURCE_DIR / "twolink_figure_alt" / "labextension"
NAME = "twolink-figure-alt"
REBUILD = "rebuild it: .venv/bin/python labextension/build.py"


def read_json(path):
    return json.loads(path.read_text(encoding="utf-8"))


def built_scripts():
    return {
        path.name: path.read_text(encoding="utf-8")
        for path in BUILT.glob("static/*.js")
    }


def sources_sha256():
    """labextension/build.py's hash: every src/*.ts in name order, as name, NUL, bytes, NUL."""
    digest = hashlib.sha256()
    for path in sorted((SOURCE_DIR / "src").glob("*.ts")):
        digest.update(path.name.encode() + b"\0" + path.read_bytes() + b"\0")
    return digest.hexdigest()


def test_the_built_bundle_is_the_build_of_the_source():
    source, built = (
        read_json(SOURCE_DIR / "package.json"),
        read_json(BUILT / "package.json"),
    )
    assert built["name"] == source["name"] == NAME
    assert built["version"] == source["version"], REBUILD
    assert {path.name for path in (SOURCE_DIR / "src").glob("*.ts")} == {
        "index.ts",
        "a11y.ts",
    }
    assert built["twolink"]["source_sha256"] == sources_sha256(), (
        f"labextension/src/ changed: {REBUILD}"
    )
    for key in ("description", "dependencies", "jupyterlab"):
        expected = source[key]
        if key == "jupyterlab":
            expected = {**expected, "_build": built[key]["_build"]}
        assert built[key] == expected, f"package.json's {key} changed: {REBUILD}"
    # JupyterLab loads the entry point named here and asks it for the mime
    # extension (src/index.ts) and the plugin (src/a11y.ts).
    build = built["jupyterlab"]["_build"]
    assert (BUILT / build["load"]).is_file()
    assert build["mimeExtension"] == "./mimeExtension"
    assert build["extension"] == "./extension"


def test_the_built_code_reads_alt_from_the_metadata_of_the_image_types():
    # Minified: only what survives minification (property names, strings) is checked.
    scripts = "\n".join(built_scripts().values())
    assert re.search(r"extends \w+\.RenderedImage\b", scripts), (
        "subclasses JupyterLab's RenderedImage"
    )
    assert ".metadata[this.mimeType]" in scripts and re.search(r"\.alt\s*=", scripts)
    for mime_type in ("image/png", "image/jpeg", "image/gif"):
        assert f'"{mime_type}"' in scripts
    # @jupyterlab/rendermime is JupyterLab's own (a shared singleton), never bundled.
    assert "renderImage" not in scripts and "lodash" not in scripts


def test_the_built_code_names_slider_handles_and_makes_scrolling_outputs_focusable():
    scripts = "\n".join(built_scripts().values())
    assert '"twolink-figure-alt:a11y"' in scripts and "autoStart:!0" in scripts
    # the handles of ipywidgets' sliders, labelled by the widget's description
    for fragment in (
        "new MutationObserver",
        '".widget-slider"',
        "noUi-handle[role=",
        '"widget-label"',
        '"aria-labelledby"',
    ):
        assert fragment in scripts, fragment
    # outputs that overflow, measured after layout, get a tab stop
    for fragment in ("new ResizeObserver", '".jp-OutputArea-output"', ".tabIndex=0"):
        assert fragment in scripts, fragment
    # nothing of JupyterLab's or Lumino's bundled (the plugin imports types only)
    assert "CommandRegistry" not in scripts and "PromiseDelegate" not in scripts


def test_built_against_the_installed_jupyterlab():
    jupyterlab = pytest.importorskip("jupyterlab")
    built = read_json(BUILT / "package.json")["twolink"]["jupyterlab"]
    assert built == jupyterlab.__version__, (
        f"built against JupyterLab {built}, {jupyterlab.__version__} is installed: {REBUILD}"
    )


def test_the_wheel_installs_every_built_file_where_jupyterlab_looks():
    """pyproject's data-files globs cover the whole bundle (a wheel without static/ would load nothing)."""
    pyproject = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    data_files = pyproject["tool"]["setuptools"]["data-files"]
    target = f"share/jupyter/labextensions/{NAME}"
    installed = {
        f"{folder}/{pathlib.Path(path).name}"
        for folder, patterns in data_files.items()
        for pattern in patterns
        for path in glob.glob(pattern, root_dir=ROOT)
    }
    expected = {
        f"{target}/{path.relative_to(BUILT).as_posix()}"
        for path in BUILT.rglob("*")
        if path.is_file()
    }
    assert installed == expected


def test_jupyterlab_in_this_venv_lists_it_enabled():
    pytest.importorskip("jupyterlab")
    result = subprocess.run(
        [sys.executable, "-m", "jupyter", "labextension", "list"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    listing = re.sub(r"\x1b\[[0-9;]*m", "", result.stdout + result.stderr)
    version = read_json(SOURCE_DIR / "package.json")["version"]
    assert re.search(rf"^\s*{NAME} v{re.escape(version)} enabled OK", listing, re.M), (
        f"JupyterLab does not list {NAME} as enabled (run `make install`):\n{listing}"
    )
