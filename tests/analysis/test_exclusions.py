"""Test that exclusion rules drop whole participants and report why."""

import pytest

from analysis import ExclusionRules, TidyFormatError, apply_exclusions, check_responses
from tests.analysis.published import table_3_rows


@pytest.fixture
def table():
    frame = table_3_rows()
    frame["fluency"] = frame["participant"].map(lambda p: "native" if p < "P05" else "studied")
    frame.loc[frame["participant"] == "P01", "flags"] = "pilot"
    first_p02 = frame.index[frame["participant"] == "P02"][0]
    frame.loc[first_p02, "flags"] = "attention_failed"
    frame.loc[frame["participant"] == "P03", "flags"] = "incomplete"
    return check_responses(frame)


def test_default_rules_drop_pilot_failed_and_incomplete(table):
    kept, report = apply_exclusions(table)
    assert set(kept["participant"]) == set(table["participant"]) - {"P01", "P02", "P03"}
    assert report.excluded_by_reason == {"pilot": 1, "attention_failed": 1, "incomplete": 1}
    assert (report.participants_total, report.participants_included) == (22, 19)


def test_rules_can_keep_them(table):
    _kept, report = apply_exclusions(
        table, ExclusionRules(pilot=False, failed_attention=False, incomplete=False)
    )
    assert report.participants_included == 22 and report.excluded_by_reason == {}


def test_demographic_filter(table):
    kept, report = apply_exclusions(
        table,
        ExclusionRules(
            pilot=False, failed_attention=False, incomplete=False, keep_only={"fluency": ["native"]}
        ),
    )
    assert set(kept["participant"]) == {"P01", "P02", "P03", "P04"}
    assert report.excluded_by_reason == {"fluency not in native": 18}


def test_filter_on_a_missing_column_is_named(table):
    with pytest.raises(TidyFormatError, match="Cannot filter on 'hearing'"):
        apply_exclusions(table, ExclusionRules(keep_only={"hearing": ["deaf"]}))
