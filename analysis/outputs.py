"""Write a Report to disk: results.json, tables (CSV, LaTeX, Markdown), figures, HTML."""

import json
import re
from pathlib import Path

import pandas as pd

from analysis import figures
from analysis.report import Report, results_json
from analysis.results import format_p

# Table columns named for a reader, each read from a rendered result's own field (a dotted
# path for a nested result); results.json keeps the results' vocabulary.
PAIR_COLUMNS = {
    "a": "a",
    "b": "b",
    "a_wins": "a_wins",
    "b_wins": "b_wins",
    "ties": "ties",
    "n": "nobs",
    "pct_a": "statistic",
    "p_two_sided": "pvalue",
    "p_one_sided_majority": "pvalue_one_sided_majority",
    "majority": "majority",
    "p_adjusted": "pvalue_adjusted",
}
CONDITION_COLUMNS = {
    "condition": "condition",
    "shown": "shown",
    "chosen": "chosen",
    "win_rate": "win_rate",
    "share": "share",
    "mean_participant_rate": "mean_participant_rate",
    "sem": "sem",
    "n_participants": "nobs",
}
POSTHOC_COLUMNS = {
    "a": "a",
    "b": "b",
    "t": "statistic",
    "df": "df",
    "p": "pvalue",
    "p_adjusted": "pvalue_adjusted",
    "dz": "dz",
    "dz_ci": "dz_ci",
    "mean_difference": "mean_difference",
    "ci": "ci",
    "apa": "apa",
}
WILCOXON_COLUMNS = {
    "a": "a",
    "b": "b",
    "V": "statistic",
    "p": "pvalue",
    "p_adjusted": "pvalue_adjusted",
    "method": "method",
    "rank_biserial": "rank_biserial",
    "n": "nobs",
    "apa": "apa",
}
PAIRED_COLUMNS = {
    "a": "a",
    "b": "b",
    "n": "nobs",
    "mean_difference": "ttest.mean_difference",
    "ci": "ttest.ci",
    "t": "ttest.statistic",
    "df": "ttest.df",
    "t_p": "ttest.pvalue",
    "t_p_adjusted": "ttest.pvalue_adjusted",
    "dz": "ttest.dz",
    "dz_ci": "ttest.dz_ci",
    "wilcoxon_V": "wilcoxon.statistic",
    "wilcoxon_p": "wilcoxon.pvalue",
    "wilcoxon_method": "wilcoxon.method",
    "wilcoxon_p_adjusted": "wilcoxon.pvalue_adjusted",
    "rank_biserial": "wilcoxon.rank_biserial",
    "apa": "apa",
}
COMPARATIVE_COLUMNS = {
    "a": "a",
    "b": "b",
    "mean_preference_a": "mean_preference",
    "ci": "ci",
    "V": "statistic",
    "p": "pvalue",
    "p_adjusted": "pvalue_adjusted",
    "method": "method",
    "rank_biserial": "rank_biserial",
    "participants": "nobs",
    "judgements": "judgements",
    "apa": "apa",
}


# The HTML report's column headings for a reader; a column not named here shows its name
# with spaces (the CSV, LaTeX and Markdown tables keep the column names).
HEADINGS = {
    "a_wins": "a chosen",
    "b_wins": "b chosen",
    "pct_a": "% a",
    "p_two_sided": "p (two-sided)",
    "p_one_sided_majority": "p (one-sided, majority)",
    "p_adjusted": "p adjusted",
    "win_rate": "win rate",
    "mean_participant_rate": "mean win rate (participants)",
    "sem": "SEM",
    "sd": "SD",
    "q1": "Q1",
    "q3": "Q3",
    "n_participants": "participants",
    "ci_low": "95 % CI low",
    "ci_high": "95 % CI high",
    "dz": "d_z",
    "dz_ci_low": "d_z 95 % CI low",
    "dz_ci_high": "d_z 95 % CI high",
    "rank_biserial": "rank-biserial r",
    "pct_ge3": "% rating ≥ 3",
    "pct_ge4": "% rating ≥ 4",
    "t_p": "t-test p",
    "t_p_adjusted": "t-test p adjusted",
    "wilcoxon_V": "Wilcoxon V",
    "wilcoxon_p": "Wilcoxon p",
    "wilcoxon_method": "Wilcoxon method",
    "wilcoxon_p_adjusted": "Wilcoxon p adjusted",
    "mean_preference_a": "mean preference for a",
    "mean_accuracy": "mean accuracy",
}


def heading(column: str) -> str:
    """Return the HTML report's heading of a table column."""
    return HEADINGS.get(column, column.replace("_", " "))


def _field(row: dict, path: str):
    for name in path.split("."):
        row = row[name]
    return row


def _table(rows: list[dict], columns: dict[str, str], first: tuple[str, ...] = ()) -> pd.DataFrame:
    """Return rendered results as a table with *columns* (a ``ci`` pair becomes
    ``ci_low`` and ``ci_high``), after the fields named in *first*."""
    table = []
    for row in rows:
        cells = {name: row[name] for name in first}
        for column, path in columns.items():
            value = _field(row, path)
            if column.endswith("ci"):
                cells[f"{column}_low"], cells[f"{column}_high"] = value
            else:
                cells[column] = value
        table.append(cells)
    return pd.DataFrame(table)


def _split_ci(rows: list[dict]) -> pd.DataFrame:
    """Return *rows* as a table whose ``ci`` pair becomes ``ci_low`` and ``ci_high``."""
    return _table(rows, {key: key for key in rows[0]})


def _summaries(rows: list[dict]) -> pd.DataFrame:
    """Return per-condition summaries across items, participants named as such."""
    return _split_ci(rows).rename(columns={"n": "answers", "nobs": "participants"})


def _pairs(rows: list[dict]) -> pd.DataFrame:
    """Return binomial tests of pairs, a's share of the decisive judgements in per cent."""
    table = _table(rows, PAIR_COLUMNS, ("item",) if rows and rows[0]["item"] is not None else ())
    return table.assign(pct_a=100 * table["pct_a"].astype(float))


def tables(report: Report, data: dict | None = None) -> dict[str, pd.DataFrame]:
    """Return the report's tables as data frames, by file name stem.

    *data* is the report's :func:`results_json` when the caller already has it.
    """
    data = results_json(report) if data is None else data
    found: dict[str, pd.DataFrame] = {}
    pairwise = data["pairwise"]
    if pairwise:
        found["pairs"] = _pairs(pairwise["pairs"])
        found["items"] = _pairs(pairwise["items"])
        found["conditions"] = _table(pairwise["conditions"], CONDITION_COLUMNS)
        if pairwise["posthoc"]:
            found["posthoc"] = _table(pairwise["posthoc"], POSTHOC_COLUMNS)
        if pairwise["wilcoxon"]:
            found["wilcoxon"] = _table(pairwise["wilcoxon"], WILCOXON_COLUMNS)
    lists = (
        ("ratings", pd.DataFrame),
        ("rating_conditions", _summaries),
        ("rating_comparisons", lambda rows: _table(rows, PAIRED_COLUMNS, ("item", "question"))),
        ("rating_condition_comparisons", lambda rows: _table(rows, PAIRED_COLUMNS, ("measure",))),
        ("intelligibility", pd.DataFrame),
        ("intelligibility_conditions", _summaries),
        ("intelligibility_comparisons", lambda rows: _table(rows, PAIRED_COLUMNS, ("measure",))),
    )
    for name, build in lists:
        if data.get(name):
            found[name] = build(data[name])
    if data.get("comparative"):
        found["comparative"] = _table(data["comparative"], COMPARATIVE_COLUMNS)
    found.update(mixed_tables(data.get("mixed_models")))
    if data.get("quality"):
        found["quality"] = pd.DataFrame(data["quality"])
    excluded = data["exclusions"].get("excluded_participants") or {}
    if excluded:
        found["excluded"] = pd.DataFrame(
            [{"participant": who, "reasons": "; ".join(why)} for who, why in excluded.items()]
        )
    return {name: _numbers(frame) for name, frame in found.items()}


def _numbers(frame: pd.DataFrame) -> pd.DataFrame:
    """Return *frame* with its number columns typed as numbers: a statistic that was not
    computed (None in results.json) is missing, printed "–", never "None"."""
    typed = {}
    for column in frame.columns:
        values = frame[column].dropna()
        if frame[column].dtype == object and all(
            isinstance(v, int | float) and not isinstance(v, bool) for v in values
        ):
            typed[column] = pd.to_numeric(frame[column], errors="coerce").astype(float)
    return frame.assign(**typed) if typed else frame


def _mixed_models(mixed: dict | None) -> list[dict]:
    if not mixed:
        return []
    return ([mixed["pairwise"]] if mixed["pairwise"] else []) + mixed["ordinal"] + mixed["linear"]


def _test_cells(c: dict) -> dict:
    """Return a coefficient's or contrast's SE, test (z, or t with its df), p (and a
    contrast's corrected p) and CI."""
    adjusted = {"p_adjusted": c["pvalue_adjusted"]} if "pvalue_adjusted" in c else {}
    return {
        "se": c["se"],
        "test": "z" if c.get("df") is None else "t",
        "statistic": c["statistic"],
        "df": c.get("df"),
        "p": c["pvalue"],
        **adjusted,
        "ci_low": c["ci"][0],
        "ci_high": c["ci"][1],
    }


def _sd_cells(component: str, column: str, sd: float, levels, ci) -> dict:
    """Return one random-effect SD's row cells, with its profile CI where there is one."""
    low, high = ci or (None, None)
    return {
        "component": component,
        "column": column,
        "sd": sd,
        "levels": levels,
        "ci_low": low,
        "ci_high": high,
    }


def mixed_tables(mixed: dict | None) -> dict[str, pd.DataFrame]:
    """Return the mixed models' effects, random effects and contrasts as three tables."""
    effects, random, contrasts = [], [], []
    for model in _mixed_models(mixed):
        key = {
            "model": model["model"],
            "question": model.get("question", ""),
            "singular": bool(model.get("singular")),
        }
        rows = ([model["position"]] if model.get("position") else []) + model["effects"]
        rows += model.get("thresholds", [])
        for c in rows:
            effects.append(
                {
                    **key,
                    "effect": c["name"],
                    "estimate": c["estimate"],
                    **_test_cells(c),
                }
            )
        for r in model["random"]:
            random.append(
                {
                    **key,
                    **_sd_cells(
                        r["name"], r.get("column", "(Intercept)"), r["sd"], r["levels"], r.get("ci")
                    ),
                }
            )
        if model.get("residual_sd") is not None:
            random.append(
                {
                    **key,
                    **_sd_cells(
                        "residual", "", model["residual_sd"], None, model.get("residual_sd_ci")
                    ),
                }
            )
        for c in model["contrasts"]:
            contrasts.append(
                {
                    **key,
                    "a": c["a"],
                    "b": c["b"],
                    "difference": c["estimate"],
                    **_test_cells(c),
                }
            )
    found = {}
    for name, rows in (
        ("mixed_effects", effects),
        ("mixed_random", random),
        ("mixed_contrasts", contrasts),
    ):
        if rows:
            found[name] = pd.DataFrame(rows)
    return found


def _latex(frame: pd.DataFrame, name: str) -> str:
    """Return a booktabs table (pandas writes \\toprule, \\midrule and \\bottomrule)."""
    # An APA sentence is set as a paragraph column, so the table keeps to the page.
    column_format = "".join(
        "p{6cm}" if c == "apa" else "r" if pd.api.types.is_numeric_dtype(frame[c]) else "l"
        for c in frame.columns
    )
    latex = frame.to_latex(
        index=False,
        column_format=column_format,
        float_format=lambda value: f"{value:.4g}",
        na_rep="--",
        caption=name.replace("_", " ").capitalize(),
        label=f"tab:{name}",
        escape=True,
    )
    return latex.strip() + "\n"


# Characters that change what a Markdown table cell shows (CommonMark §2.4: any ASCII
# punctuation may be backslash-escaped): a researcher's label such as "A | B" or
# "<img onerror=…>" must stay text, not split a column, link or become HTML. Parentheses,
# "#" and "+" mean nothing inside a cell without "[" before them or a line start.
MARKDOWN_SPECIAL = re.compile(r"([\\`*_\[\]<>|~])")


def markdown_text(value):
    """Return *value* as Markdown shows it literally (text escaped, one line); other
    values as they are."""
    if not isinstance(value, str):
        return value
    return MARKDOWN_SPECIAL.sub(r"\\\1", " ".join(value.splitlines()))


def write_report(
    report: Report, frame: pd.DataFrame, out_dir: str | Path, *, draw_figures: bool = True
) -> list[str]:
    """Write every output of *report* into *out_dir*; return the file names written.

    *frame* is the table after exclusions, for the figures that show raw ratings.
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    written = []
    data = results_json(report)
    (out / "results.json").write_text(json.dumps(data, indent=2, ensure_ascii=False) + "\n")
    written.append("results.json")
    table_files = {}
    for name, table in tables(report, data).items():
        table.to_csv(out / f"{name}.csv", index=False)
        (out / f"{name}.tex").write_text(_latex(table, name))
        # tabulate writes its missing value for None only, never for NaN.
        cells = table.astype(object).where(table.notna(), None).map(markdown_text)
        markdown = cells.to_markdown(index=False, floatfmt=".4g", missingval="–")
        (out / f"{name}.md").write_text(markdown + "\n")
        table_files[name] = table
        written += [f"{name}.csv", f"{name}.tex", f"{name}.md"]
    figure_files = []
    if draw_figures:
        figure_files += figures.all_figures(report, frame, out)
        written += figure_files
    (out / "report.html").write_text(render_html(report, data, table_files, figure_files))
    written.append("report.html")
    return written


def _number(value: float | None, digits: int = 3) -> str:
    """Format a number for the report: "–" for none, and never "-0.00"."""
    if value is None:
        return "–"
    text = f"{value:.{digits}f}"
    return text.lstrip("-") if float(text) == 0 else text


def render_html(report: Report, data: dict, table_files: dict, figure_files: list[str]) -> str:
    """Render the one-page HTML report from the results (nothing is recomputed here)."""
    from jinja2 import Environment, PackageLoader, select_autoescape

    environment = Environment(
        loader=PackageLoader("analysis", "templates"),
        autoescape=select_autoescape(["html", "html.j2"]),
    )
    environment.filters["p"] = format_p
    environment.filters["pct"] = lambda value: "–" if value is None else f"{100 * value:.2f} %"
    environment.filters["num"] = _number
    template = environment.get_template("report.html.j2")
    return template.render(
        report=report,
        data=data,
        # APA sentences are listed under their table, not squeezed into a column.
        tables={
            name: frame.drop(columns=["apa"], errors="ignore")
            .rename(columns=heading)
            .to_html(index=False, border=0, float_format=lambda v: f"{v:.4g}", na_rep="–")
            for name, frame in table_files.items()
        },
        figures=[name for name in figure_files if name.endswith(".png")],
    )
