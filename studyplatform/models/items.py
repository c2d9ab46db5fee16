"""The signed content a study shows: its items."""

from django.db import models

from studyplatform.models.studies import Study, check_unlocked, position_field
from studyplatform.rules import check_item


class Item(models.Model):
    """The signed content shown in every condition: a word, a sentence or a sign pair."""

    class Kind(models.TextChoices):
        WORD = "word", "Fingerspelled word"
        SENTENCE = "sentence", "Sentence"
        SIGN_PAIR = "sign_pair", "Sign pair (transition)"

    study = models.ForeignKey(Study, on_delete=models.CASCADE, related_name="items")
    key = models.SlugField(
        max_length=60, help_text="Name used in exported data, e.g. 'GUITAR' or 'S3'."
    )
    kind = models.CharField(max_length=10, choices=Kind.choices, default=Kind.WORD)
    text = models.TextField(help_text="The word, or the sentence as a gloss sequence.")
    target_text = models.TextField(
        blank=True,
        help_text="What intelligibility answers are scored against; empty means the text.",
    )
    is_practice = models.BooleanField(default=False, help_text="Used only for practice trials.")
    parameters = models.JSONField(
        default=dict,
        blank=True,
        help_text=(
            'Item-specific settings, e.g. {"seed": 7}; a condition\'s settings override '
            "them. Checked against the technique registry on save."
        ),
    )
    position = position_field()

    class Meta:
        ordering = ["study", "position", "pk"]
        constraints = [
            models.UniqueConstraint(fields=["study", "key"], name="item_key_unique_in_study")
        ]

    def __str__(self) -> str:
        return self.key

    def clean(self) -> None:
        check_unlocked(self.study if self.study_id else None)
        check_item(self)

    @property
    def scoring_target(self) -> str:
        """Return the text intelligibility answers are scored against."""
        return self.target_text or self.text
