"""Small text helpers for notebooks: tables and sentences built from numbers.

Prose that quotes a number is produced by a code cell, so the number is
computed, never typed.
"""

__all__ = ["markdown_table"]


def markdown_table(headers, rows, formats=None):
    """A Markdown table as a string.

    Parameters
    ----------
    headers : sequence of str
    rows : iterable of sequences
        One sequence of cell values per row.
    formats : sequence of str, optional
        A format spec per column (``".3f"``, ``".2e"``, ``""``).

    Examples
    --------
    >>> print(markdown_table(["x", "y"], [[1.0, 2.5]], [".1f", ".2f"]))
    | x | y |
    |---|---|
    | 1.0 | 2.50 |
    """
    formats = formats or [""] * len(headers)
    if len(formats) != len(headers):
        raise ValueError(f"formats has {len(formats)} entries for {len(headers)} columns")
    lines = ["| " + " | ".join(headers) + " |", "|" + "---|" * len(headers)]
    for row in rows:
        if len(row) != len(headers):
            raise ValueError(f"row {row!r} has {len(row)} cells for {len(headers)} columns")
        lines.append("| " + " | ".join(format(value, spec) for value, spec in zip(row, formats)) + " |")
    return "\n".join(lines)
