"""The README's Python examples run as written (an example that never runs goes stale)."""

import pathlib
import re

import pytest

README = (pathlib.Path(__file__).resolve().parents[1] / "README.md").read_text(
    encoding="utf-8"
)
EXAMPLES = re.findall(r"```python\n(.*?)```", README, flags=re.S)


def test_the_readme_has_python_examples():
    assert EXAMPLES


@pytest.mark.parametrize("index", range(len(EXAMPLES)))
def test_a_readme_example_runs(index, capsys):
    exec(compile(EXAMPLES[index], f"README.md example {index + 1}", "exec"), {})
    assert capsys.readouterr().out  # each example prints what it shows
