"""Two-way within-subject (repeated-measures) ANOVA: both factors and their interaction,
each with Mauchly's test and the Greenhouse–Geisser and Huynh–Feldt corrections."""

import dataclasses

import numpy as np
import pandas as pd
from statsmodels.stats.anova import AnovaRM

from analysis.anova import (
    contrast_sphericity,
    corrected_pvalue,
    huynh_feldt,
    orthonormal_contrasts,
)
from analysis.results import Result, few_named, format_p, proportion_text, sphericity_text


@dataclasses.dataclass(frozen=True)
class FactorialEffect(Result):
    """One effect (a factor, or the interaction ``A:B``) of a two-way within-subject
    ANOVA; sphericity is tested only for effects of 2 or more df (else NaN, ε = 1)."""

    effect: str
    statistic: float
    df_num: float
    df_den: float
    pvalue: float
    eta_p2: float
    epsilon_gg: float
    pvalue_gg: float
    epsilon_hf: float
    pvalue_hf: float
    mauchly_w: float
    mauchly_pvalue: float
    nobs: int
    notes: tuple[str, ...] = ()

    def apa(self) -> str:
        text = (
            f"{self.effect}: F({self.df_num:g}, {self.df_den:g}) = {self.statistic:.2f}, "
            f"{format_p(self.pvalue)}, η²p = {proportion_text(self.eta_p2)}"
        )
        return text + sphericity_text(self)


def factorial_rm_anova(
    frame: pd.DataFrame, value: str, subject: str, factors: tuple[str, str]
) -> tuple[FactorialEffect, ...]:
    """Test both *factors* of a long table (one *value* per subject and cell; several are
    averaged) and their interaction, as R's ``aov(y ~ A * B + Error(subject / (A * B)))``.

    The F tests are statsmodels' ``AnovaRM``. Each effect's sphericity is that of its
    orthonormal contrasts — Kronecker products of one factor's contrasts with the other's
    normalised mean (Maxwell & Delaney 2004, ch. 12), as R's ``anova.mlm`` takes them
    with ``idata`` — for Mauchly's test, ε and the corrected p-values. Subjects without a
    value in every cell are left out and named in each effect's notes.
    """
    first, second = factors
    cells = frame.pivot_table(index=subject, columns=[first, second], values=value)
    levels = [sorted(frame[f].astype(str).unique()) for f in factors]
    cells.columns = pd.MultiIndex.from_tuples([(str(a), str(b)) for a, b in cells.columns])
    cells = cells.reindex(columns=pd.MultiIndex.from_product(levels))
    missing = cells.index[cells.isna().any(axis=1)]
    notes: tuple[str, ...] = ()
    if len(missing):
        notes = (
            f"{len(missing)} subject(s) without a value in every cell left out "
            f"({few_named(missing)}).",
        )
    cells = cells.dropna()
    long = cells.stack([0, 1], future_stack=True).rename("value").reset_index()
    long.columns = ["subject", first, second, "value"]
    table = AnovaRM(long, "value", "subject", within=[first, second]).fit().anova_table
    a, b = (len(level) for level in levels)
    contrast = {
        first: np.kron(orthonormal_contrasts(a), np.full((1, b), 1 / np.sqrt(b))),
        second: np.kron(np.full((1, a), 1 / np.sqrt(a)), orthonormal_contrasts(b)),
        f"{first}:{second}": np.kron(orthonormal_contrasts(a), orthonormal_contrasts(b)),
    }
    values, n = cells.to_numpy(float), len(cells)
    effects = []
    for name, matrix in contrast.items():
        row = table.loc[name]
        f_value, df_num, df_den = (float(row[c]) for c in ("F Value", "Num DF", "Den DF"))
        w, w_p, epsilon = contrast_sphericity(values @ matrix.T, len(matrix) + 1)
        epsilon_hf = huynh_feldt(epsilon, n, len(matrix) + 1)
        effects.append(
            FactorialEffect(
                effect=name,
                statistic=f_value,
                df_num=df_num,
                df_den=df_den,
                pvalue=float(row["Pr > F"]),
                eta_p2=f_value * df_num / (f_value * df_num + df_den),
                epsilon_gg=epsilon,
                pvalue_gg=corrected_pvalue(f_value, df_num, df_den, epsilon),
                epsilon_hf=epsilon_hf,
                pvalue_hf=corrected_pvalue(f_value, df_num, df_den, epsilon_hf),
                mauchly_w=w,
                mauchly_pvalue=w_p,
                nobs=n,
                notes=notes,
            )
        )
    return tuple(effects)
