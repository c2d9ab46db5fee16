"""Write a Report to disk: results.json, tables (CSV, LaTeX, Markdown), figures, HTML."""

import json
from pathlib import Path

import pandas as pd

from analysis import figures
from analysis.report import Report, results_json
from analysis.results import format_p


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
            found["posthoc"] = pd.DataFrame(pairwise["posthoc"]).drop(columns=["ci", "apa"])
    if data["ratings"]:
        found["ratings"] = pd.DataFrame(data["ratings"])
    if data["rating_comparisons"]:
        found["rating_comparisons"] = pd.DataFrame(data["rating_comparisons"])
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
                }
                for c in data["comparative"]
            ]
        )
    if data["intelligibility"]:
        found["intelligibility"] = pd.DataFrame(data["intelligibility"])
    found.update(mixed_tables(data.get("mixed_models")))
    if data.get("quality"):
        found["quality"] = pd.DataFrame(data["quality"])
    excluded = data["exclusions"].get("excluded_participants") or {}
    if excluded:
        found["excluded"] = pd.DataFrame(
            [{"participant": who, "reasons": "; ".join(why)} for who, why in excluded.items()]
        )
    return found


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
    latex = frame.to_latex(
        index=False,
        float_format=lambda value: f"{value:.4g}",
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
        (out / f"{name}.md").write_text(table.to_markdown(index=False, floatfmt=".4g") + "\n")
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
        tables={
            name: frame.to_html(
                index=False, border=0, float_format=lambda v: f"{v:.4g}", na_rep="–"
            )
            for name, frame in table_files.items()
        },
        figures=[name for name in figure_files if name.endswith(".png")],
    )
