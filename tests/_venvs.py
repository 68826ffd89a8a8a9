"""Throwaway virtual environments for the packaging tests, built in seconds.

A new venv sees only the distributions we choose from the project's own
environment: their top-level files are symlinked into one folder that a
``.pth`` file puts on the new venv's ``sys.path``.  Nothing is downloaded, and
pip sees those distributions as installed (so ``pip install`` of twolink
checks its dependencies against them).
"""

import importlib.metadata
import pathlib
import re
import subprocess
import sys
import venv


def _key(name):
    return re.sub(r"[-_.]+", "-", name).lower()


def closure(names):
    """The installed distributions ``names`` need, with their dependencies (extras left out)."""
    from packaging.requirements import Requirement

    seen, todo = {}, list(names)
    while todo:
        name = todo.pop()
        if _key(name) in seen:
            continue
        dist = importlib.metadata.distribution(name)
        seen[_key(name)] = dist
        for text in dist.requires or []:
            requirement = Requirement(text)
            if requirement.marker is None or requirement.marker.evaluate({"extra": ""}):
                todo.append(requirement.name)
    return list(seen.values())


def installed_except(excluded):
    """Names of every distribution installed here except ``excluded``."""
    excluded = {_key(name) for name in excluded}
    names = {dist.metadata["Name"] for dist in importlib.metadata.distributions()}
    return sorted((name for name in names if _key(name) not in excluded), key=_key)


def link_distributions(target, names, with_dependencies=True):
    """Symlink the top-level files of ``names`` (and what they need) into ``target``."""
    target = pathlib.Path(target)
    target.mkdir(parents=True, exist_ok=True)
    dists = (
        closure(names)
        if with_dependencies
        else [importlib.metadata.distribution(name) for name in names]
    )
    for dist in dists:
        top_levels = {
            pathlib.PurePath(str(entry)).parts[0] for entry in dist.files or []
        }
        for top in top_levels:
            if top in ("..", "__pycache__") or top.endswith(".pth"):
                continue
            source = pathlib.Path(dist.locate_file(top))
            link = target / top
            if source.exists() and not link.exists():
                link.symlink_to(source)
    return target


def bare_venv(root, distributions, with_dependencies=True):
    """A venv at ``root / 'venv'`` that sees only ``distributions`` (and their dependencies).

    Returns the path of its python.
    """
    root = pathlib.Path(root)
    env_dir = root / "venv"
    venv.EnvBuilder(with_pip=False, symlinks=True).create(env_dir)
    python = env_dir / "bin" / "python"
    site = subprocess.run(
        [
            str(python),
            "-c",
            "import sysconfig; print(sysconfig.get_paths()['purelib'])",
        ],
        capture_output=True,
        text=True,
        check=True,
    ).stdout.strip()
    shared = link_distributions(root / "shared-site", distributions, with_dependencies)
    (pathlib.Path(site) / "twolink_test_shared.pth").write_text(f"{shared}\n")
    return python


def pip(python, *args, **kwargs):
    """Run the project's pip against another interpreter (``pip --python``)."""
    return subprocess.run(
        [
            sys.executable,
            "-m",
            "pip",
            "--python",
            str(python),
            "--disable-pip-version-check",
            *args,
        ],
        capture_output=True,
        text=True,
        **kwargs,
    )
