"""The signed content a study shows: its items."""

from django.db import models
from django.utils.translation import gettext_lazy as _

from studyplatform.models.studies import Study, check_unlocked, position_field
from studyplatform.rules import check_item


class Item(models.Model):
    """The signed content shown in every condition: a word, a sentence or a sign pair."""

    class Kind(models.TextChoices):
        WORD = "word", _("Fingerspelled word")
        SENTENCE = "sentence", _("Sentence")
        SIGN_PAIR = "sign_pair", _("Sign pair (transition)")

    study = models.ForeignKey(
        Study, verbose_name=_("study"), on_delete=models.CASCADE, related_name="items"
    )
    key = models.SlugField(
        _("key"), max_length=60, help_text=_("Name used in exported data, e.g. 'GUITAR' or 'S3'.")
    )
    kind = models.CharField(_("kind"), max_length=10, choices=Kind.choices, default=Kind.WORD)
    text = models.TextField(
        _("text"), help_text=_("The word, or the sentence as a gloss sequence.")
    )
    target_text = models.TextField(
        _("target text"),
        blank=True,
        help_text=_("What intelligibility answers are scored against; empty means the text."),
    )
    is_practice = models.BooleanField(
        _("is practice"), default=False, help_text=_("Used only for practice trials.")
    )
    parameters = models.JSONField(
        _("parameters"),
        default=dict,
        blank=True,
        help_text=(
            _(
                'Item-specific settings, e.g. {"seed": 7}; a condition\'s settings override '
                "them. Checked against the technique registry on save."
            )
        ),
    )
    position = position_field()

    class Meta:
        verbose_name = _("item")
        verbose_name_plural = _("items")
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
