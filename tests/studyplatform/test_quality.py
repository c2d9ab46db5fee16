"""Test deriving per-trial quality from media events: visits, plays, ends, errors."""

import pytest

from studyplatform.lib.quality import device_of, page_orders, participant_quality, quality_cells
from studyplatform.models import MediaEvent, Participant, Trial


def event(pk, kind, at, trial=1, clip=None, **detail):
    return MediaEvent(
        pk=pk, kind=kind, client_time_ms=at, trial_id=trial, clip_position=clip, detail=detail
    )


def test_visits_plays_ends_errors_and_viewport():
    events = [
        event(1, "page_shown", 1_000, width=390, height=844),
        event(2, "play", 1_500, clip=1),
        event(3, "ended", 3_500, clip=1),
        event(4, "play", 4_000, clip=1),
        event(5, "ended", 6_000, clip=1),
        event(6, "error", 6_500, clip=2),
        event(7, "page_shown", 8_000, trial=2),  # the next page: trial 1 lasted 7 s
        event(8, "page_hidden", 9_000, trial=2),
        event(9, "page_shown", 20_000, trial=1),  # back to trial 1 for 2 s
        event(10, "page_shown", 22_000, trial=2),
        event(11, "play", 22_500, trial=2, clip=2),
    ]
    quality = participant_quality(reversed(events))  # any order
    first, second = quality[1], quality[2]
    assert first.on_page_ms == 7_000 + 2_000 and first.first_shown_ms == 1_000
    assert first.plays == {1: 2, 2: 0} and first.first_ended_ms == {1: 3_500}
    assert first.errors == 1 and first.viewport == "390x844"
    # Hidden after 1 s; the last visit lasts until its last event.
    assert second.on_page_ms == 1_000 + 500 and second.plays == {1: 0, 2: 1}


@pytest.mark.django_db
def test_cells_of_an_answer_given_before_the_second_clip_ended(fingerspelling):
    trial = Trial.objects.get(study=fingerspelling, key="cmp-01")
    participant = Participant(
        study=fingerspelling,
        user_agent="Mozilla/5.0 (iPhone) Mobile",
        schedule=[{"trial": "practice-1"}, {"trial": "cmp-01"}],
    )
    quality = participant_quality(
        [
            event(1, "page_shown", 1_000, trial=trial.pk, width=800, height=600),
            event(2, "play", 1_100, trial=trial.pk, clip=1),
            event(3, "ended", 3_000, trial=trial.pk, clip=1),
            event(4, "play", 3_100, trial=trial.pk, clip=2),
            event(5, "ended", 5_000, trial=trial.pk, clip=2),
        ]
    )[trial.pk]
    orders = page_orders(participant)
    early = quality_cells(participant, trial, quality, rt_ms=3_500, answered_at=None, orders=orders)
    assert early["answered_before_end"] == "1" and early["page_order"] == "2"
    assert (early["clip1_plays"], early["clip2_ended"], early["replays"]) == ("1", "1", "0")
    assert early["device"] == "phone" and early["viewport"] == "800x600"
    assert (
        quality_cells(participant, trial, quality, 4_500, None, orders)["answered_before_end"]
        == "0"
    )
    nothing = quality_cells(participant, trial, None, 4_500, None, orders)
    assert nothing["clip1_plays"] == "" and nothing["page_order"] == "2"


@pytest.mark.parametrize(
    ("agent", "device"),
    [
        ("Mozilla/5.0 (X11; Linux x86_64) Chrome/131.0", "desktop"),
        ("Mozilla/5.0 (Linux; Android 14; Pixel 8) Chrome/131.0 Mobile Safari/537.36", "phone"),
        ("Mozilla/5.0 (Linux; Android 13; SM-X700) Chrome/131.0 Safari/537.36", "tablet"),
        ("Mozilla/5.0 (iPad; CPU OS 17_0 like Mac OS X)", "tablet"),
        ("", ""),
    ],
)
def test_device_from_the_user_agent(agent, device):
    assert device_of(agent) == device


@pytest.mark.django_db
def test_a_page_shown_again_counts_from_the_showing_the_answer_was_given_in(fingerspelling):
    """Issue 35: shown, reloaded 5 s later, both clips played to the end, answered."""
    trial = Trial.objects.get(study=fingerspelling, key="cmp-01")
    participant = Participant(study=fingerspelling, schedule=[{"trial": "cmp-01"}])
    shown_twice = [
        event(1, "page_shown", 1_000, trial=trial.pk),
        event(2, "page_hidden", 6_000, trial=trial.pk),  # the reload
        event(3, "page_shown", 6_100, trial=trial.pk),
        event(4, "ended", 9_000, trial=trial.pk, clip=1),
        event(5, "ended", 12_000, trial=trial.pk, clip=2),
    ]
    quality = participant_quality(shown_twice)[trial.pk]
    orders = page_orders(participant)
    # Answered at 13,000 ms: 6,900 ms after the second showing.
    after = quality_cells(participant, trial, quality, 6_900, None, orders, client_ms=13_000)
    assert after["answered_before_end"] == "0"
    # Without the browser's time, the showing the response time fits in is used.
    assert (
        quality_cells(participant, trial, quality, 6_900, None, orders)["answered_before_end"]
        == "0"
    )
    # An answer before clip 2 ended is still early, either way.
    early = quality_cells(participant, trial, quality, 4_900, None, orders, client_ms=11_000)
    assert early["answered_before_end"] == "1"
    assert (
        quality_cells(participant, trial, quality, 4_900, None, orders)["answered_before_end"]
        == "1"
    )


@pytest.mark.django_db
def test_a_clip_that_ended_in_an_earlier_showing_counts(fingerspelling):
    """Both clips watched, then Back to the page and the answer changed without replaying."""
    trial = Trial.objects.get(study=fingerspelling, key="cmp-01")
    participant = Participant(study=fingerspelling, schedule=[{"trial": "cmp-01"}])
    quality = participant_quality(
        [
            event(1, "page_shown", 1_000, trial=trial.pk),
            event(2, "ended", 3_000, trial=trial.pk, clip=1),
            event(3, "ended", 5_000, trial=trial.pk, clip=2),
            event(4, "page_shown", 6_000, trial=99),
            event(5, "page_shown", 8_000, trial=trial.pk),
        ]
    )[trial.pk]
    cells = quality_cells(participant, trial, quality, 500, None, page_orders(participant), 8_500)
    assert cells["answered_before_end"] == "0"
