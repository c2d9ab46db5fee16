"""Test a study's clip size: HD for new studies, as they were for old ones (issue 52).

At 640 × 480 a fist letter's hand was about 21 × 32 px in a sentence clip and A, E, M,
N, S, T could not be told apart; a new study films at 1280 × 720 unless it says
otherwise. A study made before the setting, or imported from a definition without it,
keeps the engine's 640 × 480, so its clips (and their content hashes) stay as they were.
"""

import pytest
from django.core.exceptions import ValidationError

from studyplatform.actions import do_import_study
from studyplatform.lib.exchange import export_study
from studyplatform.lib.stimuli import clip_spec
from studyplatform.models import Condition, Item, Study
from studyplatform.models.studies import CLIP_SIZE, LEGACY_CLIP_SIZE

pytestmark = pytest.mark.django_db


@pytest.fixture
def fresh(alice):
    study = Study.objects.create(owner=alice, slug="fresh", title="Fresh")
    Condition.objects.create(study=study, key="plain", label="Plain", parameters={})
    Item.objects.create(study=study, key="ab", text="AB", position=1)
    return study


def _size(study, condition_key="plain") -> tuple[int, int]:
    spec = clip_spec(study.conditions.get(key=condition_key), study.items.get())
    return spec.width, spec.height


def test_a_new_study_films_in_hd(fresh):
    assert (fresh.clip_width, fresh.clip_height) == CLIP_SIZE == (1280, 720)
    assert _size(fresh) == (1280, 720)


def test_a_study_sets_its_size_and_a_condition_its_own(fresh):
    Study.objects.filter(pk=fresh.pk).update(clip_width=960, clip_height=540)
    fresh.refresh_from_db()
    assert _size(fresh) == (960, 540)
    Condition.objects.create(
        study=fresh, key="small", label="Small", parameters={"width": 480, "height": 360}
    )
    assert _size(fresh, "small") == (480, 360)


def test_an_odd_size_is_refused_by_name(fresh):
    fresh.clip_width = 1281
    with pytest.raises(ValidationError) as refused:
        fresh.full_clean()
    assert "even numbers of pixels" in str(refused.value.message_dict["clip_width"])


def test_the_size_travels_with_a_study_and_an_old_definition_keeps_its_own(fresh, alice, spine):
    data = export_study(fresh)
    assert (data["study"]["clip_width"], data["study"]["clip_height"]) == (1280, 720)
    copy = do_import_study(data, owner=alice, slug="fresh-copy").study
    assert (copy.clip_width, copy.clip_height) == (1280, 720)
    old = export_study(fresh)
    del old["study"]["clip_width"], old["study"]["clip_height"]
    legacy = do_import_study(old, owner=alice, slug="fresh-old").study
    assert (legacy.clip_width, legacy.clip_height) == LEGACY_CLIP_SIZE
    # The demo studies film at a new study's size (issue 52: HD for the demo too).
    assert (spine.clip_width, spine.clip_height) == CLIP_SIZE
