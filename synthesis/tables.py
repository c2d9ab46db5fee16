"""Write result tables as CSV and LaTeX: the engine's evaluation commands' outputs.

Every evaluation command (hands, timing, transitions) writes its figures beside the
published ones, with what each was computed on, through these two functions.
"""

import csv
from pathlib import Path


def write_csv(path: Path, rows: list[dict], columns: list[str] | None = None) -> Path:
    """Write *rows* to *path* as CSV (columns: the first row's keys by default)."""
    with Path(path).open("w", newline="", encoding="utf-8") as handle:
        writer = csv.DictWriter(handle, fieldnames=columns or list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    return Path(path)


def _latex_cell(value) -> str:
    if value is None or (isinstance(value, float) and value != value):
        return "--"
    if isinstance(value, float):
        return f"{value:.2f}"
    text = str(value).replace("\\", "/")
    for char in "&%$#_{}":
        text = text.replace(char, "\\" + char)
    return text.replace("<", "$<$").replace(">", "$>$")


def write_latex(path: Path, rows: list[dict], columns: dict[str, str], caption: str) -> Path:
    """Write *rows* to *path* as a LaTeX table: *columns* maps row keys to headings; a
    missing figure prints as ``--``."""
    headings = " & ".join(_latex_cell(heading) for heading in columns.values())
    lines = [
        "\\begin{table}",
        "\\centering",
        f"\\caption{{{_latex_cell(caption)}}}",
        "\\begin{tabular}{" + "l" * len(columns) + "}",
        "\\hline",
        f"{headings} \\\\",
        "\\hline",
        *(" & ".join(_latex_cell(row.get(key)) for key in columns) + " \\\\" for row in rows),
        "\\hline",
        "\\end{tabular}",
        "\\end{table}",
        "",
    ]
    Path(path).write_text("\n".join(lines), "utf-8")
    return Path(path)
