"""Course-only dependencies, imported when a function needs them.

``pip install twolink`` brings only numpy, scipy, sympy and matplotlib.  The
course adds python-control, imageio-ffmpeg, ipywidgets, mujoco and JupyterLab
(``pip install "twolink[course]"``).  A function that needs one of those
imports it through :func:`require`, so that a user without it gets an
``ImportError`` that names the function and the command to run, instead of a
bare ``ModuleNotFoundError``.
"""

from __future__ import annotations

import importlib
from types import ModuleType
from typing import Protocol

__all__ = ["COURSE_INSTALL", "require", "html", "HTMLDisplay"]

#: The command that installs every course-only dependency.
COURSE_INSTALL = 'pip install "twolink[course]"'

#: Import name -> distribution name, for the error message.
_DISTRIBUTIONS = {
    "control": "control",
    "imageio_ffmpeg": "imageio-ffmpeg",
    "ipywidgets": "ipywidgets",
    "ipympl": "ipympl",
    "IPython": "ipython",
    "mujoco": "mujoco",
}


def require(module: str, function: str) -> ModuleType:
    """Import ``module`` for ``function``, or explain how to install it.

    Parameters
    ----------
    module : str
        The import name, e.g. ``"control"``.
    function : str
        The qualified name of the function that needs it, for the message.

    Returns
    -------
    module
        The imported module.

    Raises
    ------
    ImportError
        Naming ``function``, the missing distribution and ``pip install
        "twolink[course]"``.

    Examples
    --------
    >>> require("math", "twolink.example").sqrt(4.0)
    2.0
    >>> require("no_such_module_xyz", "twolink.example")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ImportError: twolink.example needs no_such_module_xyz, which is not installed: pip install "twolink[course]" ...
    """
    try:
        return importlib.import_module(module)
    except ImportError as error:
        top = module.partition(".")[0]
        distribution = _DISTRIBUTIONS.get(top, top)
        raise ImportError(
            f"{function} needs {distribution}, which is not installed: {COURSE_INSTALL} "
            f"installs it with the other course-only dependencies",
            name=module,
        ) from error


class HTMLDisplay(Protocol):
    """What Jupyter displays as HTML: an object with ``_repr_html_()`` (``IPython.display.HTML``, ...)."""

    def _repr_html_(self) -> str:
        """The HTML text Jupyter shows."""
        ...


class _HTML:
    """A minimal stand-in for ``IPython.display.HTML`` when IPython is absent."""

    def __init__(self, data: str) -> None:
        self.data = data

    def _repr_html_(self) -> str:
        return self.data

    def __repr__(self) -> str:
        return f"<HTML: {len(self.data)} characters>"


def html(text: str) -> HTMLDisplay:
    """``IPython.display.HTML(text)``, or an object with the same ``_repr_html_`` without IPython.

    Examples
    --------
    >>> html("<b>x</b>")._repr_html_()
    '<b>x</b>'
    """
    try:
        from IPython.display import HTML
    except ImportError:
        return _HTML(text)
    return HTML(text)
