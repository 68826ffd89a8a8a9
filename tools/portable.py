"""Strict nbval of the chapters under several numeric environments emulated on one machine.

A stored output must read the same on every CPU, BLAS kernel and operating
system.  Round-off differs between them: numpy picks SIMD loops by the CPU
(SSE, AVX2, AVX-512), OpenBLAS picks kernels by the CPU and splits work over
threads.  One x86-64 machine can emulate the others, because numpy reads
``NPY_DISABLE_CPU_FEATURES`` (names of the SIMD groups not to use; names the
CPU lacks are ignored) and OpenBLAS reads ``OPENBLAS_CORETYPE`` (the kernel
family) and ``OPENBLAS_NUM_THREADS``.  This script runs the notebooks under
strict nbval once per variant, prints what each variant really ran with
(numpy's enabled SIMD groups, OpenBLAS's kernel and threads, read back from
the libraries) and a table of results, and exits non-zero if any variant
fails.

Usage::

    python tools/portable.py                       # every variant: every chapter and the package's doctests
    python tools/portable.py notebooks/02_inverse_kinematics.ipynb
    python tools/portable.py --variant sse-1-thread notebooks/04_statics_wall.ipynb
    python tools/portable.py --except as-installed  # after make test, which ran that one
    python tools/portable.py --list                 # the variants and their settings
"""

from __future__ import annotations

import argparse
import json
import os
import re
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent

# numpy's x86 SIMD groups above the x86-64-v2 baseline (numpy.show_config() lists the ones found).
AVX512_GROUPS = "X86_V4 AVX512_ICL AVX512_SPR"
AVX2_AND_UP_GROUPS = "X86_V3 " + AVX512_GROUPS


@dataclass(frozen=True)
class Variant:
    """One numeric environment: the environment variables that emulate it, and why it is here."""

    name: str
    why: str
    env: dict[str, str] = field(default_factory=dict)
    # numpy CPU-feature groups this CPU must have for the emulation to run (a
    # forced OpenBLAS kernel the CPU cannot execute stops with SIGILL).
    requires: tuple[str, ...] = ()


VARIANTS = (
    Variant(
        "as-installed",
        "numpy and OpenBLAS pick the best paths for this CPU (what `make test` runs)",
    ),
    Variant(
        "avx2-haswell",
        "an AVX2 machine without AVX-512 (most laptops and CI runners)",
        {"NPY_DISABLE_CPU_FEATURES": AVX512_GROUPS, "OPENBLAS_CORETYPE": "Haswell"},
        ("X86_V3",),
    ),
    Variant(
        "v2-sandybridge",
        "numpy limited to the x86-64-v2 baseline (no AVX2/FMA, no AVX-512) with OpenBLAS's older AVX kernels",
        {
            "NPY_DISABLE_CPU_FEATURES": AVX2_AND_UP_GROUPS,
            "OPENBLAS_CORETYPE": "Sandybridge",
        },
        ("X86_V3",),
    ),
    Variant(
        "sse-1-thread",
        "OpenBLAS's SSE kernels on one thread (another summation order), numpy as installed",
        {
            "OPENBLAS_CORETYPE": "Nehalem",
            "OPENBLAS_NUM_THREADS": "1",
            "OMP_NUM_THREADS": "1",
        },
        ("X86_V2",),
    ),
)

# Printed by a child Python under each variant: what the libraries really use.
PROBE = r"""
import ctypes, glob, json, os
import numpy
from numpy._core._multiarray_umath import __cpu_features__ as features
groups = [name for name in ("X86_V2", "X86_V3", "X86_V4", "AVX512_ICL", "AVX512_SPR", "ASIMD", "SVE") if features.get(name)]
core = threads = None
for lib in glob.glob(os.path.join(os.path.dirname(numpy.__file__), os.pardir, "numpy.libs", "*openblas*")):
    blas = ctypes.CDLL(lib)
    for suffix in ("64_", ""):
        name = getattr(blas, "scipy_openblas_get_corename" + suffix, None)
        count = getattr(blas, "scipy_openblas_get_num_threads" + suffix, None)
        if name is not None and count is not None:
            name.restype = ctypes.c_char_p
            core, threads = name().decode(), count()
            break
print(json.dumps({"simd": groups, "blas_core": core, "blas_threads": threads}))
"""


def variant_env(variant: Variant) -> dict[str, str]:
    """The process environment for a variant: ours minus any inherited emulation, plus the variant's."""
    env = {
        key: value for key, value in os.environ.items() if key not in _EMULATION_KEYS
    }
    env.pop("MPLBACKEND", None)  # kernels must store their figures (inline backend)
    env.update(variant.env)
    return env


_EMULATION_KEYS = {
    "NPY_DISABLE_CPU_FEATURES",
    "NPY_ENABLE_CPU_FEATURES",
    "OPENBLAS_CORETYPE",
    "OPENBLAS_NUM_THREADS",
    "OMP_NUM_THREADS",
}


def probe(variant: Variant) -> dict[str, Any]:
    """numpy's enabled SIMD groups and OpenBLAS's kernel and threads under a variant (read from the libraries)."""
    result = subprocess.run(
        [sys.executable, "-c", PROBE],
        env=variant_env(variant),
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
    if result.returncode != 0:
        raise RuntimeError(
            f"variant {variant.name}: the probe failed:\n{result.stderr.strip()}"
        )
    return json.loads(result.stdout.strip().splitlines()[-1])


KERNEL_START_FAILED = "Failure starting kernel"


def run_nbval(
    variant: Variant, notebooks: list[str], workers: str
) -> tuple[int, str, float, str]:
    """Strict nbval (the options in pyproject.toml) of ``notebooks`` under a variant: exit code, summary, seconds, output."""
    start = time.monotonic()
    # The options of pyproject.toml (strict nbval, the sanitize file), wherever the notebooks are.
    command = [
        sys.executable,
        "-m",
        "pytest",
        "-c",
        str(ROOT / "pyproject.toml"),
        "--rootdir",
        str(ROOT),
        *notebooks,
        "-q",
        "-n",
        workers,
        # stored outputs only: the chapter checks (figures, exercises) ran in make test
        "-p",
        "no:chapter_checks",
    ]
    result = subprocess.run(
        command,
        cwd=ROOT,
        env=variant_env(variant),
        capture_output=True,
        text=True,
        timeout=1800,
        check=False,
    )
    seconds = time.monotonic() - start
    lines = [line for line in result.stdout.splitlines() if line.strip()]
    summary = next(
        (
            line
            for line in reversed(lines)
            if re.search(r"\b(passed|failed|error|no tests ran)\b", line)
        ),
        "",
    )
    if result.returncode != 0:
        failed = [line for line in lines if line.startswith(("FAILED", "ERROR"))]
        print("\n".join(failed) or result.stdout[-4000:], file=sys.stderr)
    return (
        result.returncode,
        re.sub(r"\x1b\[[0-9;]*m", "", summary).strip("= "),
        seconds,
        result.stdout + result.stderr,
    )


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument(
        "notebooks",
        nargs="*",
        help="notebooks to check (default: every chapter in notebooks/ and the doctests of twolink/)",
    )
    parser.add_argument(
        "--variant",
        action="append",
        choices=[v.name for v in VARIANTS],
        help="run only these (repeatable)",
    )
    parser.add_argument(
        "--except",
        dest="excepted",
        action="append",
        choices=[v.name for v in VARIANTS],
        help="run every variant but these (repeatable)",
    )
    parser.add_argument(
        "--workers", default="2", help="pytest-xdist workers (default 2)"
    )
    parser.add_argument(
        "--list", action="store_true", help="print the variants and exit"
    )
    args = parser.parse_args(argv)

    chosen = [
        v
        for v in VARIANTS
        if (not args.variant or v.name in args.variant)
        and v.name not in (args.excepted or ())
    ]
    if not chosen:
        parser.error("--variant and --except leave no variant to run")
    if args.list:
        for variant in chosen:
            settings = (
                " ".join(f'{key}="{value}"' for key, value in variant.env.items())
                or "(no variables)"
            )
            print(f"{variant.name}: {variant.why}\n    {settings}")
        return 0
    # By default every chapter, and the docstrings' examples (stored outputs too, run as doctests).
    notebooks = args.notebooks or [
        *sorted(
            str(path.relative_to(ROOT)) for path in (ROOT / "notebooks").glob("*.ipynb")
        ),
        "twolink",
        "twolink_course",
    ]
    notebooks = [
        str(Path(name).resolve()) if Path(name).is_file() else name
        for name in notebooks
    ]
    missing = [name for name in notebooks if not (ROOT / name).exists()]
    if missing:
        parser.error(f"no such notebook: {', '.join(missing)}")

    native = set(probe(VARIANTS[0])["simd"])
    rows = []
    for variant in chosen:
        lacking = [group for group in variant.requires if group not in native]
        if lacking:
            print(
                f"[{variant.name}] skipped: this CPU lacks {', '.join(lacking)}, which the emulation needs",
                flush=True,
            )
            rows.append(
                (variant.name, "skipped", f"this CPU lacks {', '.join(lacking)}", 0.0)
            )
            continue
        seen = probe(variant)
        above = [group for group in seen["simd"] if group != "X86_V2"]
        print(
            f"[{variant.name}] {variant.why}; numpy SIMD above the x86-64-v2 baseline: {', '.join(above) or 'none'}; "
            f"OpenBLAS kernel {seen['blas_core']}, {seen['blas_threads']} thread(s)",
            flush=True,
        )
        code, summary, seconds, output = run_nbval(variant, notebooks, args.workers)
        if code != 0 and KERNEL_START_FAILED in output:
            # Not a number that differs: a kernel that did not start (jupyter_client picks free TCP
            # ports by probing, and two kernels started at once on a loaded machine can collide).
            print(
                f"[{variant.name}] a kernel failed to start (not a mismatch of outputs); running this variant again",
                flush=True,
            )
            code, summary, seconds, output = run_nbval(variant, notebooks, args.workers)
        # pytest's exit 5 (nothing collected) is a failure too.
        rows.append(
            (
                variant.name,
                "pass" if code == 0 else f"FAIL (exit {code})",
                summary,
                seconds,
            )
        )
        print(
            f"[{variant.name}] {rows[-1][1]}: {summary} ({seconds:.0f} s)", flush=True
        )

    print("\n| variant | result | strict nbval | seconds |\n|---|---|---|---|")
    for name, verdict, summary, seconds in rows:
        print(f"| {name} | {verdict} | {summary} | {seconds:.0f} |")
    return 0 if all(verdict in ("pass", "skipped") for _, verdict, _, _ in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
