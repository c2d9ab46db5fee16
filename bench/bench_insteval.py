"""Time the mixed models on an InstEval subset against R's lme4 and ordinal (issue 56).

lme4's InstEval (lecture ratings 1–5 by students of lecturers at ETH Zürich; GPL-2, shipped
in R's lme4 package and not copied here) restricted to its first 300 students: 8,135
ratings, 300 students crossed with 999 lecturers. Each student is a participant, each
lecturer an item and ``service`` the condition. Targets: the linear mixed model as the
report fits it (REML, Satterthwaite df, profile CIs of the SDs, ML refit and LR test)
under 10 s, the cumulative-link mixed model under 60 s, on two cores. R fits the same
models on the same rows: lmerTest's lmer + anova, ``confint(parm = "theta_", method =
"profile")``, the ML refit with ``anova(m0, m1)``, and ``clmm``. Prints the machine line,
each time beside R's, and the estimates beside R's; asserts nothing. Needs Debian's R
with lme4, lmerTest and ordinal (not project dependencies)::

    apt-get install r-base-core r-cran-lme4 r-cran-lmertest r-cran-ordinal r-cran-jsonlite
    .venv/bin/python bench/bench_insteval.py [--students N]   (0: all 2,972 students)
"""

import argparse
import json
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from analysis import check_responses
from analysis.mixed import linear_mixed, ordinal_mixed
from bench.machine import describe

STUDENTS = 300

R_SCRIPT = """
suppressPackageStartupMessages({library(lme4); library(lmerTest); library(ordinal);
  library(jsonlite)})
args <- commandArgs(trailingOnly = TRUE)
data(InstEval, package = "lme4")
n <- as.integer(args[2])
s <- if (n > 0) droplevels(subset(InstEval, s %in% levels(s)[seq_len(n)])) else InstEval
write.csv(data.frame(s = s$s, d = s$d, service = s$service, y = s$y), args[1],
          row.names = FALSE)
seconds <- function(expr) unname(system.time(expr)["elapsed"])
fit <- seconds({m <- lmerTest::lmer(y ~ service + (1 | s) + (1 | d), data = s); a <- anova(m)})
profile <- seconds(ci <- confint(m, parm = "theta_", method = "profile", oldNames = FALSE))
lr <- seconds({m1 <- update(m, REML = FALSE); m0 <- update(m1, . ~ 1 + (1 | s) + (1 | d));
  test <- anova(m0, m1)})
s$yo <- factor(s$y, ordered = TRUE)
ordinal <- seconds(c1 <- clmm(yo ~ service + (1 | s) + (1 | d), data = s))
st <- VarCorr(c1)
cat(toJSON(list(
  seconds = list(lmer_anova = fit, profile = profile, ml_lr = lr, clmm = ordinal),
  lmm = list(effect = fixef(m)[["service1"]], df = summary(m)$coefficients[2, "df"],
             sd = as.data.frame(VarCorr(m))$sdcor, ci = unname(ci), lr = test$Chisq[2]),
  clmm = list(effect = coef(c1)[["service1"]],
              sd = c(attr(st$s, "stddev")[[1]], attr(st$d, "stddev")[[1]]))),
  auto_unbox = TRUE, digits = NA))
"""


def r_reference(folder: Path, students: int) -> tuple[pd.DataFrame, dict]:
    """Return the subset's rows (exported by R) and R's timings and estimates."""
    if shutil.which("Rscript") is None:
        sys.exit("bench_insteval needs R with lme4, lmerTest and ordinal: see the docstring.")
    rows = folder / "insteval.csv"
    script = folder / "insteval.R"
    script.write_text(R_SCRIPT)
    output = subprocess.run(
        ["Rscript", str(script), str(rows), str(students)],
        check=True,
        capture_output=True,
        text=True,
    ).stdout
    return pd.read_csv(rows), json.loads(output.strip().splitlines()[-1])


def tidy(rows: pd.DataFrame) -> pd.DataFrame:
    """Return the ratings as the tidy table: students as participants, lecturers as items."""
    n = len(rows)
    frame = pd.DataFrame(
        {
            "study": "insteval",
            "block": "b",
            "trial": [f"t{i}" for i in range(n)],
            "participant": "s" + rows["s"].astype(str),
            "item": "d" + rows["d"].astype(str),
            "kind": "rating",
            "condition_a": "service" + rows["service"].astype(str),
            "condition_b": "",
            "chosen": "",
            "question": "y",
            "rating": rows["y"].astype(str),
            "text": "",
            "rt_ms": "",
            "flags": "",
        }
    )
    return check_responses(frame.astype(str))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--students", type=int, default=STUDENTS)
    students = parser.parse_args().students
    print(describe())
    with tempfile.TemporaryDirectory() as folder:
        rows, r = r_reference(Path(folder), students)
    frame = tidy(rows)
    print(
        f"InstEval, first {students or 'all'} students: {len(rows)} ratings, "
        f"{rows['s'].nunique()} students × {rows['d'].nunique()} lecturers"
    )
    seconds = r["seconds"]
    started = time.perf_counter()
    lmm = linear_mixed(frame, "y", ["service0", "service1"])
    lmm_s = time.perf_counter() - started
    r_lmm = seconds["lmer_anova"] + seconds["profile"] + seconds["ml_lr"]
    print(
        f"Linear mixed model, REML + Satterthwaite + profile CIs + ML refit and LR test: "
        f"{lmm_s:.1f} s (target < 10 s); R {r_lmm:.1f} s (lmer + anova "
        f"{seconds['lmer_anova']:.1f}, profile {seconds['profile']:.1f}, "
        f"ML + LR {seconds['ml_lr']:.1f})"
    )
    effect = lmm.effects[0]
    sds = {c.name: (round(c.sd, 5), tuple(round(v, 5) for v in c.ci)) for c in lmm.random}
    print(
        f"  service: {effect.estimate:.6f} (R {r['lmm']['effect']:.6f}), df {effect.df:.2f} "
        f"(R {r['lmm']['df']:.2f}), LR χ² {lmm.likelihood_ratio.statistic:.5f} "
        f"(R {r['lmm']['lr']:.5f})"
    )
    print(
        f"  SDs and profile CIs {sds}; R (lecturer, student, residual) {r['lmm']['sd']}, "
        f"CIs {r['lmm']['ci']}"
    )
    started = time.perf_counter()
    clmm = ordinal_mixed(frame, "y", ["service0", "service1"])
    clmm_s = time.perf_counter() - started
    print(
        f"Cumulative-link mixed model: {clmm_s:.1f} s (target < 60 s); "
        f"R clmm {seconds['clmm']:.1f} s"
    )
    print(
        f"  service: {clmm.effects[0].estimate:.6f} (R {r['clmm']['effect']:.6f}); SDs "
        f"{ {c.name: round(c.sd, 5) for c in clmm.random} } (R student, lecturer "
        f"{[round(v, 5) for v in r['clmm']['sd']]})"
    )


if __name__ == "__main__":
    main()
