"""Test the design builder: its action, its admin page, and the identical-clip guard."""

from collections import Counter

import pytest
from django.urls import reverse

from stimuli.plan import Design, DesignSpec
from studyplatform.actions.design import DesignRejected, do_build_design
from studyplatform.actions.stimuli import GenerateOptions, IdenticalClips, do_generate_stimuli
from studyplatform.lib.design import summarize_design
from studyplatform.lib.schedule import build_schedule
from studyplatform.lib.stimuli import identical_clips
from studyplatform.models import (
    Block,
    Condition,
    Item,
    Participant,
    Question,
    Response,
    Study,
    Trial,
)

pytestmark = pytest.mark.django_db
WORDS = ("CAT", "DOG", "BIRD", "FISH")


@pytest.fixture
def fresh(alice):
    """A study as a researcher starts one: two timing conditions, four words, a practice word."""
    study = Study.objects.create(owner=alice, slug="fresh", title="Fresh study")
    Condition.objects.create(
        study=study, key="constant", label="Constant", position=1, parameters={"timing": "constant"}
    )
    Condition.objects.create(
        study=study, key="variable", label="Variable", position=2, parameters={"timing": "variable"}
    )
    for position, word in enumerate(WORDS, 1):
        Item.objects.create(study=study, key=word, text=word, position=position)
    Item.objects.create(study=study, key="EXAMPLE", text="HELLO", is_practice=True, position=9)
    closing = Block.objects.create(study=study, key="closing", kind=Block.Kind.CLOSING, position=1)
    comments = Question.objects.create(
        study=study, key="comments", kind="open", text="Comments?", required=False
    )
    trial = Trial.objects.create(study=study, block=closing, key="closing", kind="open")
    trial.questions.add(comments)
    return study


def spec(design=Design.BALANCED_PAIRS, **extra) -> DesignSpec:
    return DesignSpec(design=design, conditions=("constant", "variable"), items=WORDS, **extra)


def test_building_a_pair_design_creates_blocks_trials_and_a_standard_question(fresh):
    built = do_build_design(fresh, spec(practice_items=("EXAMPLE",), attention_checks=1))
    assert (built.pages, built.practice_pages, built.attention_checks) == (6, 1, 1)
    question = built.question_created
    assert question.kind == "pairwise" and question.allow_no_difference
    blocks = list(fresh.blocks.order_by("position").values_list("key", "kind"))
    assert blocks == [("practice", "practice"), ("trials", "trials"), ("closing", "closing")]
    main = Trial.objects.filter(block__key="trials", is_attention_check=False)
    pairs = Counter((t.condition_a.key, t.condition_b.key) for t in main)
    assert pairs == {("constant", "variable"): 2, ("variable", "constant"): 2}
    check = Trial.objects.get(block__key="trials", is_attention_check=True)
    assert check.condition_a == check.condition_b and check.expected_answer == "none"
    assert all(list(t.questions.all()) == [question] for t in Trial.objects.filter(kind="pairwise"))
    fresh.refresh_from_db()
    assert fresh.design["design"] == "balanced_pairs"
    assert fresh.design["questions"] == [question.key]
    assert len(build_schedule(fresh, seed=1)) == 7  # practice, 4 + 1 trials, closing


def test_building_again_replaces_the_builders_pages_and_keeps_the_others(fresh):
    do_build_design(fresh, spec(practice_items=("EXAMPLE",), attention_checks=1))
    questions = list(fresh.questions.filter(kind="pairwise"))
    fresh.refresh_from_db()
    do_build_design(fresh, spec(Design.ALL_PAIRS), questions)
    assert not fresh.blocks.filter(key="practice").exists()  # no practice chosen this time
    assert Trial.objects.filter(block__key="trials").count() == 8
    assert Trial.objects.filter(key="closing").exists()
    assert fresh.questions.filter(kind="pairwise").count() == 1  # no second standard question


def test_a_rating_design_creates_a_five_point_question_and_an_instructed_check(fresh):
    built = do_build_design(fresh, spec(Design.RATINGS, attention_checks=1))
    question = built.question_created
    assert question.kind == "likert" and question.options.count() == 5
    check = Trial.objects.get(is_attention_check=True)
    assert check.kind == "rating" and check.condition_b is None
    assert check.expected_answer == "5" and "Very natural" in check.text
    assert Trial.objects.filter(kind="rating", is_attention_check=False).count() == 8


def test_the_latin_square_design_rotates_conditions_across_participants(fresh):
    do_build_design(fresh, spec(Design.LATIN_SQUARE))
    fresh.refresh_from_db()
    assert fresh.rotate_conditions
    shown = Counter()
    for enrollment in range(2):
        for entry in build_schedule(fresh, seed=enrollment, enrollment=enrollment):
            if "a" in entry:
                shown[(entry["trial"], entry["a"])] += 1
    assert len(shown) == 8 and set(shown.values()) == {1}
    do_build_design(fresh, spec())
    fresh.refresh_from_db()
    assert not fresh.rotate_conditions


def test_questions_must_suit_the_design(fresh):
    likert = Question.objects.create(study=fresh, key="clarity", kind="likert", text="Clear?")
    with pytest.raises(DesignRejected, match="cannot ask clarity"):
        do_build_design(fresh, spec(), [likert])


def test_an_identical_clip_check_needs_a_no_difference_answer(fresh):
    choice = Question.objects.create(study=fresh, key="better", kind="pairwise", text="Better?")
    with pytest.raises(DesignRejected, match="Cannot see a difference"):
        do_build_design(fresh, spec(attention_checks=1), [choice])
    assert not Trial.objects.filter(block__kind="trials").exists()


def test_only_a_draft_is_built_and_answered_pages_are_never_deleted(fresh):
    do_build_design(fresh, spec())
    participant = Participant.objects.create(study=fresh, is_pilot=True)
    trial = Trial.objects.filter(block__key="trials").first()
    Response.objects.create(
        participant=participant, trial=trial, question=trial.questions.get(), chosen="constant"
    )
    fresh.refresh_from_db()
    with pytest.raises(DesignRejected, match="have answers"):
        do_build_design(fresh, spec(Design.ALL_PAIRS), list(trial.questions.all()))
    assert Trial.objects.filter(block__key="trials").count() == 4
    fresh.status = Study.Status.OPEN
    fresh.save()
    with pytest.raises(DesignRejected, match="design is locked"):
        do_build_design(fresh, spec())


def test_the_summary_counts_pages_pairs_and_estimates_the_duration(fresh):
    do_build_design(fresh, spec(Design.ALL_PAIRS, practice_items=("EXAMPLE",)))
    summary = summarize_design(fresh)
    assert summary.pages == 10  # practice, 8 comparisons, closing
    assert dict(summary.pages_by_block) == {"Practice": 1, "trials": 8, "closing": 1}
    # The Variable condition uses the built-in model, trained on simulated holds (issue 53).
    simulated = "Variable (simulated)"
    assert summary.pair_counts == (("Constant", simulated, 4), (simulated, "Constant", 4))
    assert summary.balanced and summary.clips_known == 0 and summary.clips_total == 18
    # 18 clips of 3 s (none rendered yet), 9 answers of 5 s, one open page's answer.
    assert summary.minutes == pytest.approx((18 * 3 + 10 * 5) / 60)


def test_the_builder_page_builds_from_ticked_boxes(fresh, client, alice):
    client.force_login(alice)
    url = reverse("admin:studyplatform_study_design", args=[fresh.pk])
    page = client.get(url)
    assert page.status_code == 200 and b"Design builder" in page.content
    ids = lambda model, **f: [o.pk for o in model.objects.filter(study=fresh, **f)]  # noqa: E731
    response = client.post(
        url,
        {
            "design": "balanced_pairs",
            "conditions": ids(Condition),
            "items": ids(Item, is_practice=False),
            "practice_items": ids(Item, is_practice=True),
            "attention_checks": "1",
            "randomize_order": "on",
        },
    )
    assert response.status_code == 302
    summary = client.get(url).content.decode()
    assert 'id="summary-pages">7<' in summary and "Balanced" in summary
    assert Trial.objects.filter(block__key="trials").count() == 5


def test_the_builder_page_names_what_is_wrong(fresh, client, alice):
    client.force_login(alice)
    url = reverse("admin:studyplatform_study_design", args=[fresh.pk])
    three = [i.pk for i in Item.objects.filter(study=fresh, is_practice=False)][:3]
    response = client.post(
        url,
        {
            "design": "balanced_pairs",
            "conditions": [c.pk for c in fresh.conditions.all()],
            "items": three,
            "attention_checks": "0",
        },
    )
    assert response.status_code == 200
    assert "even number of items; got 3" in response.content.decode()
    assert not Trial.objects.filter(block__key="trials").exists()


def test_the_builder_page_is_read_only_once_the_study_is_open(fresh, client, alice):
    do_build_design(fresh, spec())
    fresh.status = Study.Status.OPEN
    fresh.save()
    client.force_login(alice)
    url = reverse("admin:studyplatform_study_design", args=[fresh.pk])
    page = client.get(url).content.decode()
    assert 'id="design-locked"' in page and "Build the pages" not in page
    client.post(url, {"design": "all_pairs", "conditions": [], "items": []})
    assert Trial.objects.filter(block__key="trials").count() == 4


def test_another_researchers_builder_is_not_there(fresh, client, bob):
    client.force_login(bob)
    url = reverse("admin:studyplatform_study_design", args=[fresh.pk])
    assert client.get(url).status_code == 404


@pytest.fixture
def same_twice(fresh):
    """The issue's trap: two conditions whose settings change nothing the clip shows."""
    fresh.conditions.update(parameters={})
    do_build_design(fresh, spec())
    return fresh


def test_identical_clips_are_found_warned_about_and_refused_unless_confirmed(
    same_twice, client, alice
):
    identical = identical_clips(same_twice)
    assert sorted(item.key for item, _ in identical) == sorted(WORDS)
    with pytest.raises(IdenticalClips, match="identical clips for CAT"):
        do_generate_stimuli(same_twice, GenerateOptions(enqueue=False))
    client.force_login(alice)
    change = client.get(reverse("admin:studyplatform_study_change", args=[same_twice.pk]))
    assert "Conditions render identical clips" in change.content.decode()
    generate = reverse("admin:studyplatform_study_generate", args=[same_twice.pk])
    refused = client.post(generate)
    assert refused.status_code == 200 and 'name="allow_identical"' in refused.content.decode()
    assert not same_twice.conditions.first().stimuli.exists()
    confirmed = client.post(generate, {"allow_identical": "1"})
    assert confirmed.status_code == 302 and confirmed["Location"].endswith("/stimuli/")


def test_different_settings_are_not_identical(fresh):
    do_build_design(fresh, spec())
    assert identical_clips(fresh) == []
    assert do_generate_stimuli(fresh, GenerateOptions(enqueue=False)).total == 8


def test_a_study_with_identical_clips_is_not_opened_unless_intended(same_twice, client, alice):
    from django.forms.models import model_to_dict

    client.force_login(alice)
    url = reverse("admin:studyplatform_study_change", args=[same_twice.pk])
    form = client.get(url).context["adminform"].form
    data = {k: v for k, v in model_to_dict(same_twice, fields=form.fields).items() if v is not None}
    data.update({"status": "open", **_no_inline_changes()})
    response = client.post(url, data)
    assert response.status_code == 400 and "identical clips intended" in response.content.decode()
    same_twice.refresh_from_db()
    assert same_twice.status == "draft"
    data["allow_identical_clips"] = "on"
    assert client.post(url, data).status_code == 302
    same_twice.refresh_from_db()
    assert same_twice.status == "open"


def _no_inline_changes() -> dict:
    """Return management forms saying the post changes no conditions, items, trials…."""
    prefixes = (
        "conditions",
        "items",
        "questions",
        "blocks",
        "trials",
        "studyplatform-aslvideo-content_type-object_id",
    )
    return {f"{p}-{f}": 0 for p in prefixes for f in ("TOTAL_FORMS", "INITIAL_FORMS")}


def test_a_slider_study_from_builder_to_report(fresh):
    """Issue 57's proof of a scale kind: a slider and a Likert question on the same rating
    pages, built by the builder, answered, exported with their scales, and analysed each
    by its own models (the slider by the linear mixed model only)."""
    from analysis import ReportOptions, build_report, read_responses
    from studyplatform.actions import Answer, do_enroll_participant, do_save_response
    from studyplatform.lib.export import tidy_csv
    from studyplatform.models import AnswerOption

    slider = Question.objects.create(study=fresh, key="natural", kind="slider", text="How natural?")
    for value, label in ((0, "Not at all natural"), (100, "Completely natural")):
        AnswerOption.objects.create(question=slider, value=value, label=label, position=value)
    likert = Question.objects.create(study=fresh, key="clear", kind="likert", text="How clear?")
    for value in range(1, 6):
        AnswerOption.objects.create(question=likert, value=value, position=value)
    do_build_design(fresh, spec(Design.RATINGS, attention_checks=1), [slider])
    check = Trial.objects.get(is_attention_check=True)
    assert check.expected_answer == "100" and "Completely natural" in check.text
    # One page's check expects one answer: with the Likert beside it, no check.
    built = do_build_design(fresh, spec(Design.RATINGS, attention_checks=0), [slider, likert])
    assert built.pages == 8 and not Trial.objects.filter(is_attention_check=True).exists()
    fresh.status = "open"
    fresh.save(update_fields=["status"])
    rng = __import__("numpy").random.default_rng(7)
    for number in range(8):
        participant = do_enroll_participant(fresh, consented=True)
        for trial in fresh.trials.filter(kind="rating").select_related("condition_a"):
            shift = 15 if trial.condition_a.key == "variable" else 0
            natural = int(rng.integers(20, 70)) + shift
            do_save_response(participant, trial, slider, Answer(rating=natural))
            clear = 1 + (number + trial.position + shift // 5) % 5
            do_save_response(participant, trial, likert, Answer(rating=clear))
        Participant.objects.filter(pk=participant.pk).update(finished_at=participant.started_at)
    frame = read_responses(__import__("io").StringIO(tidy_csv(fresh)))
    rated = frame[frame["kind"].eq("rating")]
    assert set(zip(rated["question"], rated["scale"], strict=True)) == {
        ("natural", "continuous"),
        ("clear", "ordinal"),
    }
    assert rated.loc[rated["question"].eq("natural"), "rating"].between(0, 100).all()
    mixed = build_report(frame, ReportOptions()).mixed
    assert [m.question for m in mixed.ordinal] == ["clear"]
    assert [m.question for m in mixed.linear] == ["clear", "natural"]
    assert "continuous scale (a slider)" in mixed.linear[1].notes[0]
    assert "interval numbers" in mixed.linear[0].notes[0]


def test_a_shuffled_attention_check_is_never_the_first_page_of_its_block(fresh):
    """Issue 55, item 7: with shuffling, the attention check could come first, before the
    participant had seen a real page (it then tests the instructions, not attention)."""
    do_build_design(fresh, spec(Design.ALL_PAIRS, attention_checks=1), [])
    checks = set(Trial.objects.filter(is_attention_check=True).values_list("key", flat=True))
    trials = set(Trial.objects.filter(block__key="trials").values_list("key", flat=True))
    firsts = Counter()
    for seed in range(200):
        pages = [e["trial"] for e in build_schedule(fresh, seed=seed) if e["trial"] in trials]
        firsts[pages[0] in checks] += 1
        assert sorted(pages) == sorted(trials)  # every page once, the check among them
    # 1 check among 9 pages would come first about 22 times in 200 shuffles.
    assert firsts[True] == 0 and firsts[False] == 200
