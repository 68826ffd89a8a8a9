"""tools/portable.py: the emulated numeric environments really take effect, and strict nbval under them tells a match from a mismatch."""

import functools
import json
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools"))
import portable  # noqa: E402

VARIANTS = {variant.name: variant for variant in portable.VARIANTS}


@functools.cache
def as_installed():
    """What this machine runs as installed: probed once, when a test first asks (not at collection)."""
    return portable.probe(VARIANTS["as-installed"])


def test_there_are_at_least_three_variants_and_the_first_is_as_installed():
    assert len(portable.VARIANTS) >= 3
    assert portable.VARIANTS[0].env == {}
    assert len({variant.name for variant in portable.VARIANTS}) == len(
        portable.VARIANTS
    )


@pytest.mark.parametrize(
    "variant", portable.VARIANTS[1:], ids=lambda variant: variant.name
)
def test_each_variant_changes_what_numpy_or_openblas_run(variant):
    native = set(as_installed()["simd"])
    lacking = [group for group in variant.requires if group not in native]
    if lacking:
        pytest.skip(f"this CPU lacks {lacking}, which {variant.name} needs")
    seen = portable.probe(variant)
    disabled = variant.env.get("NPY_DISABLE_CPU_FEATURES", "").split()
    assert not set(disabled) & set(seen["simd"]), (
        f"numpy still runs {set(disabled) & set(seen['simd'])}"
    )
    if "OPENBLAS_CORETYPE" in variant.env:
        assert seen["blas_core"] is not None, "OpenBLAS's kernel could not be read back"
        assert seen["blas_core"].lower() == variant.env["OPENBLAS_CORETYPE"].lower()
    if "OPENBLAS_NUM_THREADS" in variant.env:
        assert seen["blas_threads"] == int(variant.env["OPENBLAS_NUM_THREADS"])


def test_variant_env_drops_inherited_emulation_and_mplbackend(monkeypatch):
    monkeypatch.setenv("OPENBLAS_CORETYPE", "Nehalem")
    monkeypatch.setenv("MPLBACKEND", "Agg")
    env = portable.variant_env(VARIANTS["as-installed"])
    assert "OPENBLAS_CORETYPE" not in env and "MPLBACKEND" not in env


def _notebook(path, stored_text):
    cell = {
        "cell_type": "code",
        "execution_count": 1,
        "id": "c1",
        "metadata": {},
        "outputs": [{"name": "stdout", "output_type": "stream", "text": [stored_text]}],
        "source": ["print(round(0.1 + 0.2, 6))"],
    }
    content = {
        "cells": [cell],
        "metadata": {
            "kernelspec": {
                "display_name": "Python 3",
                "language": "python",
                "name": "python3",
            }
        },
        "nbformat": 4,
        "nbformat_minor": 5,
    }
    path.write_text(json.dumps(content), encoding="utf-8")
    return str(path)


@pytest.mark.infrastructure
def test_a_matching_notebook_passes_and_a_mismatching_one_fails(tmp_path, capsys):
    """One strict nbval run of both notebooks: the one storing 0.3 passes, the one storing 0.30000000000000004 fails.

    The failure shown compares the mismatching notebook's stored output with the
    fresh one, so the test that passed is the matching notebook's.  A variant
    whose run passes is a ``pass`` row: ``test_a_kernel_that_did_not_start_is_run_again_once``.
    """
    good = _notebook(tmp_path / "good.ipynb", "0.3\n")
    bad = _notebook(tmp_path / "bad.ipynb", "0.30000000000000004\n")
    assert (
        portable.main([good, bad, "--variant", "as-installed", "--workers", "0"]) == 1
    )
    said = capsys.readouterr()
    assert "| as-installed | FAIL (exit 1) | 1 failed, 1 passed" in said.out
    assert "'0.30000000000000004\\n' == '0.3\\n'" in said.err, said.err[-3000:]


def test_an_unknown_notebook_is_refused_by_name(tmp_path, capsys):
    with pytest.raises(SystemExit):
        portable.main([str(tmp_path / "missing.ipynb")])
    assert "no such notebook" in capsys.readouterr().err


def _scripted_runs(monkeypatch, outcomes):
    """Replace run_nbval by a script of (exit code, output) pairs; return the list of calls made.

    The probe answers as it did for this machine (a real probe per variant:
    ``test_each_variant_changes_what_numpy_or_openblas_run``).
    """
    calls = []
    seen = as_installed()
    monkeypatch.setattr(portable, "probe", lambda variant: seen)

    def fake_run_nbval(variant, notebooks, workers):
        code, output = outcomes[len(calls)]
        calls.append(variant.name)
        return code, "1 passed" if code == 0 else "1 failed", 0.0, output

    monkeypatch.setattr(portable, "run_nbval", fake_run_nbval)
    return calls


def test_a_kernel_that_did_not_start_is_run_again_once(monkeypatch, tmp_path, capsys):
    good = _notebook(tmp_path / "good.ipynb", "0.3\n")
    calls = _scripted_runs(
        monkeypatch, [(1, "ERROR nbval:kernel.py:59 Failure starting kernel"), (0, "")]
    )
    assert portable.main([good, "--variant", "as-installed"]) == 0
    assert calls == ["as-installed", "as-installed"]
    said = capsys.readouterr().out
    assert "a kernel failed to start (not a mismatch of outputs)" in said
    assert "| as-installed | pass | 1 passed |" in said


def test_a_mismatch_is_never_run_again(monkeypatch, tmp_path):
    good = _notebook(tmp_path / "good.ipynb", "0.3\n")
    calls = _scripted_runs(
        monkeypatch, [(1, "assert reference_output == test_output failed"), (0, "")]
    )
    assert portable.main([good, "--variant", "as-installed"]) == 1
    assert calls == ["as-installed"]


def test_except_runs_every_variant_but_those_named(monkeypatch, tmp_path, capsys):
    """What .ci/run does after make test: every variant but as-installed, in their order."""
    good = _notebook(tmp_path / "good.ipynb", "0.3\n")
    others = [name for name in VARIANTS if name != "as-installed"]
    monkeypatch.setattr(
        portable,
        "VARIANTS",
        tuple(
            portable.Variant(v.name, v.why, v.env) for v in VARIANTS.values()
        ),  # no CPU requirement: every variant runs here
    )
    calls = _scripted_runs(monkeypatch, [(0, "")] * len(others))
    assert portable.main([good, "--except", "as-installed"]) == 0
    assert calls == others
    with pytest.raises(SystemExit):
        portable.main([good, "--variant", "sse-1-thread", "--except", "sse-1-thread"])
    assert "leave no variant to run" in capsys.readouterr().err


def test_ci_leaves_out_the_variant_make_test_ran():
    ci_run = (Path(__file__).resolve().parents[2] / ".ci" / "run").read_text(
        encoding="utf-8"
    )
    assert "make portable EXCEPT=as-installed" in ci_run
    makefile = (Path(__file__).resolve().parents[2] / "Makefile").read_text(
        encoding="utf-8"
    )
    assert "$(addprefix --except ,$(EXCEPT))" in makefile
