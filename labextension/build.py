"""Build the prebuilt JupyterLab extension twolink-figure-alt (needs Node.js and npm).

    .venv/bin/python labextension/build.py

1. ``npm ci``: the exact packages of package-lock.json into labextension/node_modules;
2. ``tsc``: src/*.ts to lib/*.js (index: the image renderer, the mime
   extension; a11y: the plugin naming slider handles and making scrolling
   outputs focusable);
3. ``jupyter-builder build`` (what ``jupyter labextension build`` runs since
   JupyterLab 4.6) against the core package.json of the JupyterLab installed
   in this Python, so the shared packages (@jupyterlab/rendermime ...) are
   taken from that JupyterLab, never bundled;
4. records in the built package.json the SHA-256 of the sources (src/*.ts) and the
   JupyterLab version it was built against (tests/infrastructure/test_labextension.py
   compares both: a stale bundle fails the tests), and writes install.json
   (``jupyter labextension list`` then names the Python package that
   installed it).

The output, twolink_figure_alt/labextension/ (package.json and static/), is
committed: users and CI install it without Node.js (pyproject.toml's
data-files put it in {sys.prefix}/share/jupyter/labextensions/).
"""

from __future__ import annotations

import hashlib
import json
import pathlib
import shutil
import subprocess
import sys
import sysconfig

HERE = pathlib.Path(__file__).resolve().parent
SOURCES = HERE / "src"
OUTPUT = HERE / "twolink_figure_alt" / "labextension"
INSTALL_JSON = {
    "packageManager": "python",
    "packageName": "twolink",
    "uninstallInstructions": "Use your Python package manager (pip, conda, etc.) to uninstall the package twolink",
}


def source_sha256() -> str:
    """The hash recorded in the built package.json (tests/infrastructure/test_labextension.py recomputes it).

    Over every src/*.ts in name order, each as its name, NUL, its bytes, NUL.
    """
    digest = hashlib.sha256()
    for path in sorted(SOURCES.glob("*.ts")):
        digest.update(path.name.encode() + b"\0" + path.read_bytes() + b"\0")
    return digest.hexdigest()


def core_package_file() -> tuple[pathlib.Path, str]:
    """The installed JupyterLab's core package.json (its shared package versions) and its version."""
    import jupyterlab

    return pathlib.Path(
        jupyterlab.__file__
    ).parent / "staging" / "package.json", jupyterlab.__version__


def run(*command: str | pathlib.Path) -> None:
    print("+", " ".join(map(str, command)), flush=True)
    subprocess.run([str(part) for part in command], cwd=HERE, check=True)


def main() -> None:
    npm = shutil.which("npm")
    if npm is None:
        sys.exit("build.py needs Node.js and npm (e.g. apt-get install nodejs npm)")
    core, lab_version = core_package_file()
    run(npm, "ci", "--no-audit", "--no-fund")
    run(HERE / "node_modules" / ".bin" / "tsc", "-p", HERE)
    builder = pathlib.Path(sysconfig.get_path("scripts")) / "jupyter-builder"
    run(builder, "build", "--core-package-file", core, HERE)

    built = OUTPUT / "package.json"
    data = json.loads(built.read_text(encoding="utf-8"))
    data["twolink"] = {"source_sha256": source_sha256(), "jupyterlab": lab_version}
    built.write_text(json.dumps(data, indent=2) + "\n", encoding="utf-8")
    (OUTPUT / "install.json").write_text(
        json.dumps(INSTALL_JSON, indent=2) + "\n", encoding="utf-8"
    )
    print(f"built {OUTPUT.relative_to(HERE.parent)} against JupyterLab {lab_version}")


if __name__ == "__main__":
    main()
