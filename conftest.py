"""Make pytest work the same from any folder of the repository.

pyproject.toml's options name the nbval sanitize file relative to the
repository root (``tests/nbval_sanitize.cfg``); pytest would read that path
relative to the current folder, so ``cd notebooks && pytest --nbval
01_dh_forward_kinematics.ipynb`` would not find it.  A relative path that does
not exist from the current folder is taken from the root instead.
"""

import pathlib


def pytest_configure(config):
    sanitize = getattr(config.option, "nbval_sanitize_with", None)
    if (
        sanitize
        and not pathlib.Path(sanitize).is_absolute()
        and not pathlib.Path(sanitize).exists()
    ):
        from_root = pathlib.Path(config.rootpath) / sanitize
        if from_root.exists():
            config.option.nbval_sanitize_with = str(from_root)
