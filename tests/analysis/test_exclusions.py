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


def test_participants_are_listed_by_id_with_every_reason(table):
    _kept, report = apply_exclusions(table)
    assert report.excluded_participants == {
        "P01": ["pilot"],
        "P02": ["attention_failed"],
        "P03": ["incomplete"],
    }


def _behaviour(frame):
    """P04 answered one page before its clips ended; P05's pages took 0.8 s each."""
    frame = frame.copy()
    frame["answered_before_end"] = "0"
    frame["time_on_page_ms"] = "6000"
    first_p04 = frame.index[frame["participant"] == "P04"][0]
    frame.loc[first_p04, "answered_before_end"] = "1"
    frame.loc[frame["participant"] == "P05", "time_on_page_ms"] = "800"
    return check_responses(frame)


def test_the_speeder_rule_excludes_who_answered_before_the_clips_ended():
    table = _behaviour(table_3_rows())
    rules = ExclusionRules(answered_before_end=True)
    kept, report = apply_exclusions(table, rules)
    assert "P04" not in set(kept["participant"]) and report.participants_included == 21
    assert report.excluded_participants == {"P04": ["answered before the clips ended"]}
    assert apply_exclusions(table)[1].participants_included == 22  # off by default


def test_the_median_page_time_rule_takes_one_time_per_page():
    table = _behaviour(table_3_rows())
    _kept, report = apply_exclusions(table, ExclusionRules(min_median_page_s=2))
    assert report.excluded_participants == {"P05": ["median time on a page under 2 s"]}
    _kept, report = apply_exclusions(table, ExclusionRules(min_median_page_s=0.5))
    assert report.excluded_participants == {}


def test_a_behaviour_rule_without_its_column_names_the_column():
    table = check_responses(table_3_rows())
    with pytest.raises(TidyFormatError, match="needs the column 'answered_before_end'"):
        apply_exclusions(table, ExclusionRules(answered_before_end=True))
    with pytest.raises(TidyFormatError, match="needs the column 'time_on_page_ms'"):
        apply_exclusions(table, ExclusionRules(min_median_page_s=1))
