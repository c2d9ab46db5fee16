"""Record participants' answers and what they did with the media."""

from django.db import models
from django.utils.translation import gettext
from django.utils.translation import gettext_lazy as _

from studyplatform.files.storage import private_storage
from studyplatform.models.design import Question, Trial
from studyplatform.models.participants import Participant
from studyplatform.models.stimuli import Stimulus
from studyplatform.questions import NO_DIFFERENCE


class Response(models.Model):
    """A participant's answer to one question of one trial; at most one exists per key."""

    NO_DIFFERENCE = NO_DIFFERENCE

    participant = models.ForeignKey(
        Participant,
        verbose_name=_("participant"),
        on_delete=models.CASCADE,
        related_name="responses",
    )
    trial = models.ForeignKey(
        Trial, verbose_name=_("trial"), on_delete=models.RESTRICT, related_name="responses"
    )
    question = models.ForeignKey(
        Question, verbose_name=_("question"), on_delete=models.RESTRICT, related_name="responses"
    )
    chosen = models.CharField(
        _("chosen"),
        max_length=40,
        blank=True,
        help_text=_("Pairwise: the chosen condition's key, or 'none'."),
    )
    chosen_position = models.PositiveSmallIntegerField(
        _("chosen position"),
        null=True,
        blank=True,
        help_text=_("Pairwise: 1 or 2 for Clip 1 or Clip 2, empty for 'none'."),
    )
    rating = models.SmallIntegerField(
        _("rating"),
        null=True,
        blank=True,
        help_text=_("The chosen option's value (Likert, comparative, choice)."),
    )
    number = models.FloatField(_("number"), null=True, blank=True)
    text = models.TextField(_("text"), blank=True)
    video = models.FileField(
        _("video"),
        upload_to="answers/",
        storage=private_storage,
        blank=True,
        help_text=_("A signed answer (private: only the study's researchers can open it)."),
    )
    video_sha256 = models.CharField(
        _("signed answer's SHA-256"),
        max_length=64,
        blank=True,
        help_text=_("Of the signed answer's file, as checked on upload; names it in exports."),
    )
    score = models.FloatField(
        _("score"),
        null=True,
        blank=True,
        help_text=_("Intelligibility: word-level accuracy in [0, 1]."),
    )
    rt_ms = models.PositiveIntegerField(
        _("response time (ms)"), null=True, blank=True, help_text=_("From page shown to answer.")
    )
    answered_client_ms = models.BigIntegerField(
        _("answered at (browser clock, ms)"),
        null=True,
        blank=True,
        help_text=_(
            "When the answer was given on the participant's browser clock, the clock "
            "of the media events (ms since 1970); the quality columns compare the two."
        ),
    )
    revision = models.PositiveIntegerField(
        _("revision"), default=1, help_text=_("How many times the participant gave this answer.")
    )
    answered_at = models.DateTimeField(_("answered at"), auto_now_add=True)
    updated_at = models.DateTimeField(_("updated at"), auto_now=True)

    class Meta:
        verbose_name = _("response")
        verbose_name_plural = _("responses")
        ordering = ["participant", "trial", "question"]
        constraints = [
            models.UniqueConstraint(
                fields=["participant", "trial", "question"], name="one_response_per_question"
            )
        ]

    def __str__(self) -> str:
        return gettext("%(trial)s/%(question)s by participant %(number)s") % {
            "trial": self.trial.key,
            "question": self.question.key,
            "number": self.participant_id,
        }


class MediaEvent(models.Model):
    """One thing that happened to a clip or page: play, pause, seek, end, error, shown."""

    class Kind(models.TextChoices):
        PAGE_SHOWN = "page_shown", _("Page shown")
        PAGE_HIDDEN = "page_hidden", _("Page hidden")
        PLAY = "play", _("Play")
        PAUSE = "pause", _("Pause")
        SEEK = "seek", _("Seek")
        ENDED = "ended", _("Ended")
        ERROR = "error", _("Playback error")

    participant = models.ForeignKey(
        Participant,
        verbose_name=_("participant"),
        on_delete=models.CASCADE,
        related_name="media_events",
    )
    trial = models.ForeignKey(
        Trial,
        verbose_name=_("trial"),
        on_delete=models.RESTRICT,
        null=True,
        blank=True,
        related_name="media_events",
    )
    stimulus = models.ForeignKey(
        Stimulus,
        verbose_name=_("stimulus"),
        on_delete=models.SET_NULL,
        null=True,
        blank=True,
        related_name="media_events",
    )
    clip_position = models.PositiveSmallIntegerField(
        _("clip position"), null=True, blank=True, help_text=_("1 or 2: which clip on the page.")
    )
    kind = models.CharField(_("kind"), max_length=20, choices=Kind.choices)
    media_time_s = models.FloatField(
        _("media time s"),
        null=True,
        blank=True,
        help_text=_("Playback position when it happened (s)."),
    )
    client_time_ms = models.BigIntegerField(
        _("client time ms"),
        null=True,
        blank=True,
        help_text=_("Browser clock when it happened (ms since the epoch)."),
    )
    detail = models.JSONField(_("detail"), default=dict, blank=True)
    created_at = models.DateTimeField(_("created at"), auto_now_add=True)

    class Meta:
        verbose_name = _("media event")
        verbose_name_plural = _("media events")
        ordering = ["participant", "client_time_ms", "pk"]
        indexes = [models.Index(fields=["participant", "trial"])]

    def __str__(self) -> str:
        return gettext("%(kind)s by participant %(number)s") % {
            "kind": self.kind,
            "number": self.participant_id,
        }
