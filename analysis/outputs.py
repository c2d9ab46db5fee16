"""Write a Report to disk: results.json, tables (CSV, LaTeX, Markdown), figures, HTML."""

import json
from pathlib import Path

import pandas as pd

from analysis import figures
from analysis.report import Report, results_json
from analysis.results import format_p


def _split_ci(rows: list[dict]) -> pd.DataFrame:
    """Return *rows* as a table whose ``ci`` pair becomes ``ci_low`` and ``ci_high``."""
    split = []
    for row in rows:
        cells = {}
        for key, value in row.items():
            if key == "ci":
                cells["ci_low"], cells["ci_high"] = value
            else:
                cells[key] = value
        split.append(cells)
    return pd.DataFrame(split)


def _summaries(rows: list[dict]) -> pd.DataFrame:
    """Return per-condition summaries across items, participants named as such."""
    return _split_ci(rows).rename(columns={"n": "answers", "nobs": "participants"})


def tables(report: Report, data: dict | None = None) -> dict[str, pd.DataFrame]:
    """Return the report's tables as data frames, by file name stem.

    *data* is the report's :func:`results_json` when the caller already has it.
    """
    data = results_json(report) if data is None else data
    found: dict[str, pd.DataFrame] = {}
    pairwise = data["pairwise"]
    if pairwise:
        found["pairs"] = pd.DataFrame(pairwise["pairs"])
        found["items"] = pd.DataFrame(pairwise["items"])
        found["conditions"] = pd.DataFrame(pairwise["conditions"])
        if pairwise["posthoc"]:
            found["posthoc"] = _split_ci(pairwise["posthoc"])
        if pairwise["wilcoxon"]:
            found["wilcoxon"] = pd.DataFrame(pairwise["wilcoxon"]).rename(
                columns={"statistic": "W", "pvalue": "p", "pvalue_adjusted": "p_adjusted",
                         "nobs": "n"}
            )  # fmt: skip
    lists = (
        ("ratings", pd.DataFrame),
        ("rating_conditions", _summaries),
        ("rating_comparisons", _split_ci),
        ("rating_condition_comparisons", _split_ci),
        ("intelligibility", pd.DataFrame),
        ("intelligibility_conditions", _summaries),
        ("intelligibility_comparisons", _split_ci),
    )
    for name, build in lists:
        if data.get(name):
            found[name] = build(data[name])
    if data.get("comparative"):
        found["comparative"] = pd.DataFrame(
            [
                {
                    "a": c["a"],
                    "b": c["b"],
                    "mean_preference_a": c["mean_preference"],
                    "ci_low": c["ci"][0],
                    "ci_high": c["ci"][1],
                    "W": c["statistic"],
                    "p": c["pvalue"],
                    "p_adjusted": c["pvalue_adjusted"],
                    "rank_biserial": c["rank_biserial"],
                    "participants": c["nobs"],
                    "judgements": c["judgements"],
                    "apa": c["apa"],
                }
                for c in data["comparative"]
            ]
        )
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
    return {"component": component, "column": column, "sd": sd, "levels": levels,
            "ci_low": low, "ci_high": high}  # fmt: skip


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
                {**key, **_sd_cells(r["name"], r.get("column", "(Intercept)"), r["sd"],
                                    r["levels"], r.get("ci"))}
            )  # fmt: skip
        if model.get("residual_sd") is not None:
            random.append(
                {**key, **_sd_cells("residual", "", model["residual_sd"], None,
                                    model.get("residual_sd_ci"))}
            )  # fmt: skip
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
        cells = table.astype(object).where(table.notna(), None)
        markdown = cells.to_markdown(index=False, floatfmt=".4g", missingval="–")
        (out / f"{name}.md").write_text(markdown + "\n")
        table_files[name] = table
        written += [f"{name}.csv", f"{name}.tex", f"{name}.md"]
    figure_files = []
    if draw_figures:
        figure_files += figures.condition_rates_figure(report, out)
        figure_files += figures.pairwise_matrix_figure(report, out)
        figure_files += figures.ratings_figure(report, frame, out)
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
            name: frame.drop(columns=["apa"], errors="ignore").to_html(
                index=False, border=0, float_format=lambda v: f"{v:.4g}", na_rep="–"
            )
            for name, frame in table_files.items()
        },
        figures=[name for name in figure_files if name.endswith(".png")],
    )
