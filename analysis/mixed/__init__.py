"""Mixed-effects models with participants and items crossed (issue 21).

- :func:`mixed_bradley_terry`: paired choices, logistic or Davidson ties;
- :func:`ordinal_mixed`: Likert ratings, cumulative-link (proportional odds);
- :func:`linear_mixed`: ratings as numbers (REML, lme4::lmer's criterion);
- :func:`fit_laplace`: the maximum-likelihood engine under the first two.
"""

from analysis.mixed.families import Bernoulli, Binomial, CumulativeLogit, Davidson
from analysis.mixed.laplace import Component, LaplaceFit, MixedProblem, fit_laplace
from analysis.mixed.linear import linear_mixed
from analysis.mixed.ordinal import (
    ordinal_mixed,
    ordinal_problem,
    proportional_odds_test,
    rating_rows,
)
from analysis.mixed.pairwise import mixed_bradley_terry, pairwise_problem, strengths_identifiable
from analysis.mixed.results import (
    Coefficient,
    Contrast,
    CumulativeLinkMixedResult,
    LinearMixedResult,
    MixedBradleyTerryResult,
    MixedModels,
    ProportionalOddsTest,
    VarianceComponent,
)
from analysis.mixed.section import fit_mixed_models

__all__ = [
    "Bernoulli",
    "Binomial",
    "Coefficient",
    "Component",
    "Contrast",
    "CumulativeLinkMixedResult",
    "CumulativeLogit",
    "Davidson",
    "LaplaceFit",
    "LinearMixedResult",
    "MixedBradleyTerryResult",
    "MixedModels",
    "MixedProblem",
    "ProportionalOddsTest",
    "VarianceComponent",
    "fit_laplace",
    "fit_mixed_models",
    "linear_mixed",
    "mixed_bradley_terry",
    "ordinal_mixed",
    "ordinal_problem",
    "pairwise_problem",
    "proportional_odds_test",
    "rating_rows",
    "strengths_identifiable",
]
