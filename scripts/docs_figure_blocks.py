"""The figure blocks of docs/*.md, each written from the documented commands' output.

Used by scripts/docs_figures.py (which says how the blocks are marked and checked); the
commands run once each in scripts/docs_figure_runs.py.
"""

import re

from docs_figure_runs import (
    LETTERS,
    curve_rows,
    leave_one_out_rows,
    reconstruction,
    reduction,
    rows,
    six_marker_rows,
    table_3_1,
    transitions,
)


def _table(header: list[str], body: list[list[str]]) -> str:
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    return "\n".join(lines + ["| " + " | ".join(row) + " |" for row in body])


def _block(text: str) -> str:
    return f"\n{text}\n"


def transitions_table() -> str:
    own = rows(f"{transitions('transition')}/table.csv")
    pair = rows(f"{transitions('sign-pair')}/table.csv")
    body = [
        [
            a["model"],
            f"{float(a['mean_rmse_deg']):.2f}",
            a["best_in"],
            f"{float(b['mean_rmse_deg']):.2f}",
            b["best_in"],
            f"{float(a['published_rmse_deg']):.2f}",
            a["published_best_in"],
        ]
        for a, b in zip(own, pair, strict=True)
    ]
    header = [
        "model",
        "mean RMSE (°), own transition left out",
        "best in",
        "mean RMSE (°), sign pair left out",
        "best in",
        "seed 001 (°)",
        "seed 001 best in",
    ]
    intro = (
        "On the default simulated database (4 signers × 6 sentences, 3 of them shared; "
        f"{own[0]['transitions']} arm transitions; seed 0):"
    )
    return _block(f"{intro}\n\n{_table(header, body)}")


def _weightings(holdout: str) -> dict[str, dict[str, float]]:
    found = rows(f"{transitions(holdout)}/weightings.csv")
    return {
        r["weighting"]: {k: float(v) for k, v in r.items() if k.endswith(("_deg", "_share"))}
        for r in found
    }


def transitions_shares() -> str:
    own, pair = _weightings("transition")["raw"], _weightings("sign-pair")["raw"]
    return (
        f"{100 * own['same_signer_share']:.0f} % of fits come from the query's own signer "
        f"(seed 001: 63.6 %) and {100 * own['same_transition_share']:.0f} % are the same "
        f"transition by another signer (12.5 %); with the sign pair left out, "
        f"{100 * pair['same_signer_share']:.0f} % and, by construction, "
        f"{100 * pair['same_transition_share']:.0f} %"
    )


def transitions_winner() -> str:
    means = {
        r["model"]: float(r["mean_rmse_deg"])
        for r in rows(f"{transitions('transition')}/table.csv")
    }
    best = min(means, key=means.get)
    data_driven = "data-driven" in best
    return (
        f"The {'data-driven' if data_driven else 'baseline'} models win here ({best}, "
        f"{means[best]:.2f}°){' and lost in the seed' if data_driven else ', as in the seed'}"
    )


def transitions_searches() -> str:
    w = _weightings("transition")
    raw, z, pca = (w[k]["hermite_rmse_deg"] for k in ("raw", "zscore", "pca"))
    figures = f"(Hermite {raw:.2f}° against {z:.2f}° and {pca:.2f}°)"
    if raw < min(z, pca):
        return (
            f"the seed's raw distance beat z-scoring and PCA here {figures}, against "
            "§5.2.4's expectation: the k = 0 band they down-weight carries the signs' "
            "postures, which is what decides a transition's shape in these data."
        )
    return f"z-scoring or PCA beat the seed's raw distance here {figures}, as §5.2.4 expected."


def transitions_search_signers() -> str:
    w = _weightings("transition")
    return ", ".join(
        f"{name} {100 * w[key]['same_signer_share']:.0f} %"
        for key, name in (("raw", "raw"), ("zscore", "z-scored"), ("pca", "PCA"))
    )


def _dofs(which: str) -> list[str]:
    return [r["dofs"] for r in reduction(which)]


def hands_reduce_engine() -> str:
    a, b, c, d = _dofs("engine")
    error = float(reduction("engine")[3]["mean_error_deg"])
    return (
        f"{a} free DOFs after range < 1°, {b} after adding rmsd < 0.3, {c} after range < 5°, "
        f"{d} after range < 5° + rmsd < 0.5 (mean reconstruction error {error:.1f}°)"
    )


def hands_reduce_human() -> str:
    steps = reduction("human")
    kept, last = int(steps[2]["dofs"]), steps[3]
    rebuilt = kept - int(last["dofs"])
    return (
        f"range < 5° + rmsd < 0.5 leaves {last['dofs']} free DOFs ({rebuilt} rebuilt, mean "
        f"error {float(last['mean_error_deg']):.2f}°)"
    )


def reduction_table() -> str:
    names = ["range < 1°", "range < 1° + rmsd < 0.3", "range < 5°", "range < 5° + rmsd < 0.5"]
    engine, human = reduction("engine"), reduction("human")
    body = [
        [name, e["published_dofs_of_50"], e["dofs"], h["dofs"]]
        for name, e, h in zip(names, engine, human, strict=True)
    ]
    header = [
        "step",
        "seed 002 (two hands, 50 curves)",
        f"engine's ELEPHANT ({engine[0]['of']})",
        f"human letters A–Z ({human[0]['of']})",
    ]
    return _block(_table(header, body))


def _cm(method: str, markers: int, variance: float = 1.0, digits: int = 2) -> str:
    return f"{float(reconstruction(method, variance)[markers]['error_cm']):.{digits}f}"


def hands_lwr_variance() -> str:
    three = [_cm("lwr", 3, v, 3) for v in (1.0, 0.999, 0.99)]
    six = [_cm("lwr", 6, v, 3) for v in (1.0, 0.999, 0.99)]
    return (
        f"HEAVEN from 3 markers: {three[0]} cm with every component, {three[1]} cm with "
        f"those that hold 99.9 % of the variance, "
        f"{three[2]} cm with those that hold 99 %; from 6 markers {six[0]}, {six[1]} and "
        f"{six[2]} cm"
    )


def hands_heaven() -> str:
    return (
        f"LWR {_cm('lwr', 3)} cm from 3 markers, {_cm('lwr', 6)} cm from 6; nearest pose "
        f"{_cm('nearest', 3)} cm and {_cm('nearest', 6)} cm"
    )


def hands_pose_database() -> str:
    database = reconstruction("lwr")[3]["database"]
    poses = int(re.search(r"(\d+) poses", database).group(1))
    return f"{poses:,}"


def _grid(configuration: str, input_starts: str) -> dict[tuple[int, int], dict[str, str]]:
    return {
        (int(r["poses"]), int(r["markers"])): r
        for r in table_3_1()
        if r["configuration"].startswith(configuration) and r["input"].startswith(input_starts)
    }


GRIDS = {
    "engine": ("engine", ""),
    "gestures": ("seed 000", "simulated gestures"),
    "letters": ("seed 000", "human letters"),
}


def table_3_1_grid(which: str) -> str:
    grid = _grid(*GRIDS[which])
    sizes, counts = sorted({p for p, _ in grid}), sorted({m for _, m in grid})
    body = [
        [str(p)]
        + [
            f"{float(grid[p, m]['error_cm']):.2f} "
            + (
                f"(seed {grid[p, m]['published_cm']})"
                if p == sizes[0] and m == counts[0]
                else f"({grid[p, m]['published_cm']})"
            )
            for m in counts
        ]
        for p in sizes
    ]
    return _block(_table(["p \\ m", *map(str, counts)], body))


def _markers(names: str) -> str:
    """Return a marker set (``thumb_tip pinky_pip``) in the docs' words: thumb tip and
    little PIP."""
    joints = {"mcp": "MCP", "pip": "PIP", "ip": "IP", "tip": "tip"}
    words = [
        f"{'little' if d == 'pinky' else d} {joints[j]}"
        for d, j in (n.split("_") for n in names.split())
    ]
    return ", ".join(words[:-1]) + f" and {words[-1]}" if len(words) > 1 else words[0]


def table_3_1_sets() -> str:
    grid = _grid(*GRIDS["gestures"])
    sets = [_markers(grid[1000, m]["set"]) for m in (2, 4, 6)]
    return f"{sets[0]} (m = 2); {sets[1]} (m = 4); {sets[2]} (m = 6)"


def table_3_1_ratio() -> str:
    grid = _grid(*GRIDS["engine"])
    ratios = [float(r["error_cm"]) / float(r["published_cm"]) for r in grid.values()]
    return f"{100 * min(ratios):.0f} % to {100 * max(ratios):.0f} %"


def exhaustive_m3() -> str:
    sets = {(r["markers"], r["method"][:3]): r for r in rows("table-3-1-ours/marker-sets.csv")}
    alg1, pca = sets["3", "exh"], sets["3", "PCA"]
    return (
        f"{_markers(alg1['set'])} at {float(alg1['error_cm']):.2f} cm against "
        f"{_markers(pca['set'])} at {float(pca['error_cm']):.2f} cm"
    )


def reproducing_table_3_1() -> str:
    published = _grid(*GRIDS["engine"])
    body = [
        ["seed 000 (Vicon gestures)"] + [published[1000, m]["published_cm"] for m in (2, 4, 6, 13)]
    ]
    for label, which in (
        ("engine configuration", "engine"),
        ("paper configuration, simulated gestures", "gestures"),
        ("paper configuration, human letters", "letters"),
    ):
        grid = _grid(*GRIDS[which])
        body.append([label] + [f"{float(grid[1000, m]['error_cm']):.2f}" for m in (2, 4, 6, 13)])
    return _block(_table(["p = 1000", "m = 2", "4", "6", "13"], body))


def leave_one_out() -> str:
    found = {r["measure"]: float(r["ours"]) for r in leave_one_out_rows()}
    return (
        f"{found['hold accuracy (leave-one-out, %)']:.2f} % and "
        f"{found['hold mean error (ms)']:.2f} ms"
    )


def letter_distances() -> str:
    import itertools

    from synthesis.timing import letter_distance

    found = {}
    for metric in ("rmsd", "gplvm"):
        pairs = {
            (a, b): letter_distance(a, b, metric) for a, b in itertools.combinations(LETTERS, 2)
        }
        found[metric] = (max(pairs, key=pairs.get), max(pairs.values()), pairs["E", "Z"])
    (_, top, ez), ((g1, g2), g_top, g_ez) = found["rmsd"], found["gplvm"]
    return (
        f"the joint RMSD runs from 0 to {top:.2f} rad with E–Z at {ez:.2f} (seed 000: 0 to "
        f"1.10, E–Z 0.51: {100 * ez / top:.0f} % of the range against the seed's 46 %); "
        f"the GPLVM puts {g1} and {g2} farthest apart and E–Z at {g_ez / g_top:.2f} of the "
        "largest distance"
    )


def spine_table() -> str:
    from spine_formulas import bend_and_twist

    from synthesis.signing.stories import SPINE_STORY

    body = []
    for number, text in enumerate(SPINE_STORY, start=1):
        seed = bend_and_twist(text, "seed")
        comfort = bend_and_twist(text, "comfort")
        twist = [f"{t.min():.1f} to {t.max():.1f}".replace("-", "−") for t in (seed[2], comfort[2])]
        body.append([f"S{number}", f"{seed[1].mean():.1f}", f"{comfort[1].mean():.1f}", *twist])
    header = [
        "sentence",
        "mean bend, seed (°)",
        "mean bend, comfort (°)",
        "twist, seed (°)",
        "twist, comfort (°)",
    ]
    return _block(_table(header, body))


def six_markers() -> str:
    body = [
        [r["method"], _markers(r["set"]), r["marker_error_cm"], r["angle_error_deg"]]
        for r in six_marker_rows()
    ]
    return _block(_table(["six markers", "set", "marker error (cm)", "angle error (°)"], body))


def _signed(value: float) -> str:
    return f"{value:+.1f}".replace("-", "−")


def constant_errors() -> str:
    found = {r["measure"]: float(r["ours"]) for r in leave_one_out_rows()}
    mean = found["Constant model: hold mean error (ms)"]
    signed = found["Constant model: mean recorded − predicted hold (ms)"]
    return (
        f"{mean:.1f} ms per hold and {_signed(signed)} ms recorded − predicted (seed 000 "
        "§4.3, on 304 recorded holds: 170.9 ms and −167.7 ms)"
    )


def learning_curves() -> str:
    body = [
        [
            r["curve"],
            r["label"],
            f"{float(r['accuracy_pct']):.2f}",
            r["published_accuracy_pct"] and f"{float(r['published_accuracy_pct']):.2f}",
            f"{float(r['mean_error_ms']):.2f}",
        ]
        for r in curve_rows()
        if r["published_accuracy_pct"] or r["curve"] == "training size"
    ]
    header = ["figure", "step", "accuracy (%)", "seed 000 (%)", "mean error (ms)"]
    return _block(_table(header, body))
