"""Golden tests of the pairwise analysis against published tables (tests/analysis/published.py)."""

import pytest

from analysis.pairwise import analyze_pairwise
from analysis.results import round_half_up
from analysis.tidy import check_responses
from tests.analysis.published import TABLE_3, TABLE_5_2, table_3_rows, table_5_2_rows


@pytest.fixture(scope="module")
def fingerspelling():
    return analyze_pairwise(check_responses(table_5_2_rows()))


def test_table_5_2_pair_counts_and_percentages(fingerspelling):
    # Seed 000 Table 5.2, opposite orders tallied together.
    assert [(p.a, p.b, p.a_wins, p.b_wins) for p in fingerspelling.pairs] == [
        (a, b, wins_a, wins_b) for (a, b), (wins_a, wins_b) in TABLE_5_2.items()
    ]
    percentages = [round_half_up(100 * p.statistic) for p in fingerspelling.pairs]
    assert percentages == [31.25, 32.50, 30.00, 58.75, 46.25, 40.00]


def test_table_5_2_shares_and_win_rates(fingerspelling):
    # Seed 000 §5.4: shares 15.63/28.96/24.79/30.63 %, win rates 31.25/57.92/49.58/61.25 %.
    rates = {c.condition: c for c in fingerspelling.conditions}
    assert [
        round_half_up(100 * rates[c].share) for c in ("Constant", "Mocap", "Normalized", "Variable")
    ] == [
        15.63,
        28.96,
        24.79,
        30.63,
    ]
    assert [
        round_half_up(100 * rates[c].win_rate)
        for c in ("Constant", "Mocap", "Normalized", "Variable")
    ] == [
        31.25,
        57.92,
        49.58,
        61.25,
    ]
    assert all(rates[c].shown == 240 for c in rates)
    assert sum(rates[c].chosen for c in rates) == 480


def test_table_3_one_sided_p_values():
    # Seed 003 Table 3; spec 07: one-sided exact tests in the direction of the majority.
    result = analyze_pairwise(check_responses(table_3_rows()))
    by_item = {p.item: p for p in result.items}
    assert [round_half_up(by_item[s].pvalue_one_sided_majority, 4) for s in TABLE_3] == [
        0.5841,
        0.0022,
        0.0262,
        0.0004,
        0.2617,
    ]
    assert [(by_item[s].a_wins, by_item[s].b_wins) for s in TABLE_3] == list(TABLE_3.values())
    assert by_item["S1"].majority is None and by_item["S4"].majority == "spine"


def test_two_sided_is_twice_one_sided_for_a_fair_coin():
    result = analyze_pairwise(check_responses(table_3_rows()))
    s4 = next(p for p in result.items if p.item == "S4")
    assert s4.pvalue == pytest.approx(2 * s4.pvalue_one_sided_majority)


def test_holm_adjusted_p_values_are_not_smaller(fingerspelling):
    assert all(p.pvalue_adjusted >= p.pvalue for p in fingerspelling.pairs)


def test_items_tally_each_word_once_per_pair(fingerspelling):
    assert len(fingerspelling.items) == 8 * 6
    assert {p.a_wins + p.b_wins for p in fingerspelling.items} == {10}


def test_repeated_measures_tests_run_on_participant_rates(fingerspelling):
    anova = fingerspelling.rm_anova
    assert anova.nobs == 10 and anova.df_num == 3 and anova.df_den == 27
    assert 0 <= anova.eta_p2 <= 1 and 1 / 3 <= anova.epsilon_gg <= 1
    assert anova.apa().startswith("F(3, 27) = ")
    assert len(fingerspelling.posthoc) == 6
    assert all(t.pvalue_adjusted >= t.pvalue for t in fingerspelling.posthoc)
    assert fingerspelling.friedman.df == 3


def test_bradley_terry_orders_conditions_like_the_win_rates(fingerspelling):
    strengths = {s.condition: s.log_worth for s in fingerspelling.bradley_terry.strengths}
    assert strengths["Constant"] == 0
    assert strengths["Variable"] > strengths["Mocap"] > strengths["Normalized"] > 0


def test_position_bias_is_counted(fingerspelling):
    bias = fingerspelling.position_bias
    assert bias.clip1 + bias.clip2 == 480 and 0 < bias.pvalue <= 1


def test_ties_are_excluded_or_split():
    frame = table_3_rows()
    frame.loc[frame.index[:4], "chosen"] = "none"  # four S1 judgements become ties
    excluded = analyze_pairwise(check_responses(frame))
    split = analyze_pairwise(check_responses(frame), tie_handling="split")
    s1_ex = next(p for p in excluded.items if p.item == "S1")
    s1_split = next(p for p in split.items if p.item == "S1")
    assert s1_ex.ties == 4 and s1_ex.nobs == 18
    assert s1_split.nobs == 22
    assert excluded.ties == 4


def test_comparative_scale_answers_count_as_choices():
    frame = table_3_rows()
    frame["kind"] = "comparative"
    # 1–2 favour clip 1, 3 is "no difference", 4–5 favour clip 2.
    frame["rating"] = [
        1 if c == a else 5 for c, a in zip(frame["chosen"], frame["condition_a"], strict=True)
    ]
    frame.loc[0, "rating"] = 3
    result = analyze_pairwise(check_responses(frame.astype(str)))
    assert result.ties == 1
    assert sum(p.a_wins + p.b_wins for p in result.items) == 22 * 5 - 1


def test_practice_and_attention_check_rows_are_left_out():
    frame = table_3_rows()
    frame.loc[0, "flags"] = "practice"
    frame.loc[1, "flags"] = "attention_check"
    result = analyze_pairwise(check_responses(frame))
    assert result.judgements == 22 * 5 - 2
