"""Throwaway virtual environments for the packaging tests, built in seconds.

A new venv sees only the distributions we choose from the project's own
environment: their top-level files are symlinked into one folder that a
``.pth`` file puts on the new venv's ``sys.path``.  Nothing is downloaded, and
pip sees those distributions as installed (so ``pip install`` of twolink
checks its dependencies against them).

What pip must really install into a venv (a package whose files outside
``site-packages`` matter, such as a JupyterLab extension) comes from a wheelhouse:
:func:`wheelhouse` packs installed distributions back into wheels, offline, and
can add a *decoy*, the same distribution under a higher version, so that a test
sees pip keep to a constraint rather than take the newest.
"""

import base64
import hashlib
import importlib.metadata
import json
import os
import pathlib
import re
import subprocess
import sys
import sysconfig
import venv
import zipfile


def _key(name):
    return re.sub(r"[-_.]+", "-", name).lower()


def closure(names):
    """The installed distributions ``names`` need, with their dependencies.

    A requirement that names extras (``jsonschema[format-nongpl]``) brings the
    dependencies of those extras too, as pip installs them; the extras of
    ``names`` themselves are left out.
    """
    from packaging.requirements import Requirement

    seen, done, todo = {}, set(), [(name, "") for name in names]
    while todo:
        name, extra = todo.pop()
        if (_key(name), extra) in done:
            continue
        done.add((_key(name), extra))
        if _key(name) not in seen:
            seen[_key(name)] = importlib.metadata.distribution(name)
        dist = seen[_key(name)]
        for text in dist.requires or []:
            requirement = Requirement(text)
            if requirement.marker is None or requirement.marker.evaluate(
                {"extra": extra}
            ):
                todo.append((requirement.name, ""))
                todo += [(requirement.name, wanted) for wanted in requirement.extras]
    return list(seen.values())


def requirements(name, extra=None):
    """Names of the distributions the installed ``name`` requires, with those of its ``extra``."""
    from packaging.requirements import Requirement

    names = []
    for text in importlib.metadata.requires(name) or []:
        requirement = Requirement(text)
        if requirement.marker is None or requirement.marker.evaluate(
            {"extra": extra or ""}
        ):
            names.append(requirement.name)
    return names


def installed_except(excluded):
    """Names of every distribution installed here except ``excluded``."""
    excluded = {_key(name) for name in excluded}
    names = {dist.metadata["Name"] for dist in importlib.metadata.distributions()}
    return sorted((name for name in names if _key(name) not in excluded), key=_key)


def link_distributions(target, names, with_dependencies=True, without=()):
    """Symlink the top-level files of ``names`` (and what they need, except ``without``) into ``target``."""
    target = pathlib.Path(target)
    target.mkdir(parents=True, exist_ok=True)
    dists = (
        closure(names)
        if with_dependencies
        else [importlib.metadata.distribution(name) for name in names]
    )
    left_out = {_key(name) for name in without}
    dists = [dist for dist in dists if _key(dist.metadata["Name"]) not in left_out]
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


def bare_venv(root, distributions, with_dependencies=True, without=()):
    """A venv at ``root / 'venv'`` that sees only ``distributions`` (and their dependencies,
    except the distributions named in ``without``, which it lacks).

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
    shared = link_distributions(
        root / "shared-site", distributions, with_dependencies, without
    )
    (pathlib.Path(site) / "twolink_test_shared.pth").write_text(f"{shared}\n")
    return python


def kernel_spec(kernels, name, python, display_name):
    """Write a kernel spec ``kernels/name/kernel.json`` whose kernel is ``python``'s ipykernel.

    A ``KernelSpecManager(kernel_dirs=[str(kernels)])`` then starts it as ``name``: a
    kernel of a throwaway venv, not of the project's environment.
    """
    folder = pathlib.Path(kernels) / name
    folder.mkdir(parents=True)
    argv = [str(python), "-m", "ipykernel_launcher", "-f", "{connection_file}"]
    spec = {"argv": argv, "display_name": display_name, "language": "python"}
    (folder / "kernel.json").write_text(json.dumps(spec), encoding="utf-8")


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


# --- wheels of installed distributions, for pip to install offline


def _record_hash(data):
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=")
    return "sha256=" + digest.decode()


#: Files of a .dist-info folder that belong to the installation, not to the wheel.
_INSTALL_ONLY = {"RECORD", "INSTALLER", "REQUESTED", "direct_url.json"}


def repack(name, out_dir, version=None):
    """A wheel of the installed pure-Python distribution ``name``, written to ``out_dir``.

    Its files are the ones its RECORD lists: those in ``site-packages`` at the
    wheel's root, those elsewhere in the environment (a JupyterLab extension in
    ``share/jupyter``) as the wheel's data, so pip puts them back in the
    environment it installs into; console scripts are left to pip, which
    writes them from ``entry_points.txt``.  ``version`` (a higher one: a decoy)
    replaces the installed version in the file name and the metadata.
    Returns the wheel's path.
    """
    dist = importlib.metadata.distribution(name)
    if "Root-Is-Purelib: true" not in (dist.read_text("WHEEL") or ""):
        raise ValueError(f"{name} is not a pure-Python distribution")
    project = re.sub(r"[-_.]+", "_", dist.metadata["Name"])
    old_info = f"{project}-{dist.version}.dist-info"
    version = version or dist.version
    info, data = f"{project}-{version}.dist-info", f"{project}-{version}.data/data"
    site = pathlib.Path(sysconfig.get_path("purelib"))
    prefix = pathlib.Path(sysconfig.get_path("data"))
    scripts = pathlib.Path(sysconfig.get_path("scripts"))
    wheel = pathlib.Path(out_dir) / f"{project}-{version}-py3-none-any.whl"
    wheel.parent.mkdir(parents=True, exist_ok=True)
    record = []
    with zipfile.ZipFile(wheel, "w", zipfile.ZIP_DEFLATED, compresslevel=1) as archive:
        for entry in dist.files or []:
            path = pathlib.Path(os.path.normpath(dist.locate_file(entry)))
            if "__pycache__" in path.parts or not path.is_file():
                continue
            if path.is_relative_to(site):
                inside = path.relative_to(site).as_posix()
                top, _, rest = inside.partition("/")
                if top.endswith(".dist-info"):
                    if rest in _INSTALL_ONLY:
                        continue
                    inside = f"{info}/{rest}"
            elif path.is_relative_to(scripts):
                continue
            elif path.is_relative_to(prefix):
                inside = f"{data}/{path.relative_to(prefix).as_posix()}"
            else:
                continue
            content = path.read_bytes()
            if inside == f"{info}/METADATA":
                content = re.sub(
                    rb"^Version: .*$",
                    f"Version: {version}".encode(),
                    content,
                    count=1,
                    flags=re.M,
                )
            archive.writestr(inside, content)
            record.append(f"{inside},{_record_hash(content)},{len(content)}")
        if not any(line.startswith(f"{info}/METADATA,") for line in record):
            raise ValueError(f"{name}: no {old_info}/METADATA among its files")
        record.append(f"{info}/RECORD,,")
        archive.writestr(f"{info}/RECORD", "\n".join(record) + "\n")
    return wheel


def wheelhouse(out_dir, names, decoys=None):
    """A folder of wheels of the installed distributions ``names`` (:func:`repack`),
    with a decoy at the version given for each name in ``decoys``; pip installs from it
    offline (``PIP_NO_INDEX=1``, ``PIP_FIND_LINKS=out_dir``)."""
    out_dir = pathlib.Path(out_dir)
    for name in names:
        repack(name, out_dir)
    for name, version in (decoys or {}).items():
        repack(name, out_dir, version)
    return out_dir
