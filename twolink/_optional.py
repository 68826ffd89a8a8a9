"""Optional dependencies, imported when a function needs them.

``pip install twolink`` brings only numpy, scipy and sympy.  Two functions
need more: :mod:`twolink.engine` needs MuJoCo (``pip install
"twolink[mujoco]"``) and :func:`twolink.linearize` needs python-control
(``pip install "twolink[control]"``); the course kit, :mod:`twolink_course`,
needs matplotlib, ipywidgets, ipympl and JupyterLab (``pip install
"twolink[course]"``, which includes both).  A function that needs one of those
imports it through :func:`require`, so that a user without it gets an
``ImportError`` that names the function and the command to run, instead of a
bare ``ModuleNotFoundError``.
"""

from __future__ import annotations

import importlib
from types import ModuleType

__all__ = ["COURSE_INSTALL", "require"]

#: The command that installs every optional dependency (the course's, which include the library's).
COURSE_INSTALL = 'pip install "twolink[course]"'

#: Import name -> (distribution name, the extra that brings it), for the error message.
_DISTRIBUTIONS = {
    "control": ("control", "control"),
    "mujoco": ("mujoco", "mujoco"),
    "imageio_ffmpeg": ("imageio-ffmpeg", "course"),
    "ipywidgets": ("ipywidgets", "course"),
    "ipympl": ("ipympl", "course"),
    "IPython": ("ipython", "course"),
    "matplotlib": ("matplotlib", "course"),
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
        Naming ``function``, the missing distribution and the ``pip install``
        command of the extra that brings it.

    Examples
    --------
    >>> require("math", "twolink.example").sqrt(4.0)
    2.0
    >>> require("no_such_module_xyz", "twolink.example")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ImportError: twolink.example needs no_such_module_xyz, which is not installed: pip install "twolink[course]" installs it
    """
    try:
        return importlib.import_module(module)
    except ImportError as error:
        top = module.partition(".")[0]
        distribution, extra = _DISTRIBUTIONS.get(top, (top, "course"))
        raise ImportError(
            f"{function} needs {distribution}, which is not installed: "
            f'pip install "twolink[{extra}]" installs it',
            name=module,
        ) from error
