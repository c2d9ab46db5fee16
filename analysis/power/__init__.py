"""Power planning by simulating the planned design under the analysis model (issue 21)."""

from analysis.power.closed_form import binomial_n, binomial_power, paired_t_n, paired_t_power
from analysis.power.design import (
    PlannedDesign,
    Trial,
    design_from_responses,
    parse_design,
    read_design,
)
from analysis.power.results import PowerCurve, PowerPoint
from analysis.power.simulation import TESTS, Effects, effects_from_pilot, power_curve, simulate

__all__ = [
    "TESTS",
    "Effects",
    "PlannedDesign",
    "PowerCurve",
    "PowerPoint",
    "Trial",
    "binomial_n",
    "binomial_power",
    "design_from_responses",
    "effects_from_pilot",
    "paired_t_n",
    "paired_t_power",
    "parse_design",
    "power_curve",
    "read_design",
    "simulate",
]
