"""Statistics and reports on a tidy table of responses (pandas/statsmodels).

Never imports Django or any other SignStudy package; runs on a CSV from the command line
(``python -m analysis report responses.csv --out DIR``) as well as inside the platform.
"""

from analysis.anova import rm_anova, sphericity
from analysis.bradley_terry import bradley_terry
from analysis.comparative import compare_preferences, preferences
from analysis.exclusions import ExclusionRules, apply_exclusions
from analysis.factorial import FactorialEffect, factorial_rm_anova
from analysis.intelligibility import score_intelligibility, word_accuracy, words
from analysis.outputs import write_report
from analysis.pairwise import analyze_pairwise, binomial_pair, judgements
from analysis.ratings import compare_ratings, summarize_ratings
from analysis.report import Report, ReportOptions, build_report, results_json
from analysis.results import format_p, round_half_up
from analysis.tidy import REQUIRED_COLUMNS, TidyFormatError, check_responses, read_responses
from analysis.wide import WideMapping, parse_mapping, read_mapping, wide_to_tidy
from analysis.within import adjust, friedman, paired_ttests, wilcoxon_tests

__all__ = [
    "REQUIRED_COLUMNS",
    "ExclusionRules",
    "FactorialEffect",
    "Report",
    "ReportOptions",
    "TidyFormatError",
    "WideMapping",
    "adjust",
    "analyze_pairwise",
    "apply_exclusions",
    "binomial_pair",
    "bradley_terry",
    "build_report",
    "check_responses",
    "compare_preferences",
    "compare_ratings",
    "factorial_rm_anova",
    "format_p",
    "friedman",
    "judgements",
    "paired_ttests",
    "parse_mapping",
    "preferences",
    "read_mapping",
    "read_responses",
    "results_json",
    "rm_anova",
    "round_half_up",
    "score_intelligibility",
    "sphericity",
    "summarize_ratings",
    "wide_to_tidy",
    "wilcoxon_tests",
    "word_accuracy",
    "words",
    "write_report",
]
