"""Record participants' answers and what they did with the media."""

from django.db import models

from studyplatform.files.storage import private_storage
from studyplatform.models.design import Question, Trial
from studyplatform.models.participants import Participant
from studyplatform.models.stimuli import Stimulus
from studyplatform.questions import NO_DIFFERENCE


class Response(models.Model):
    """A participant's answer to one question of one trial; at most one exists per key."""

    NO_DIFFERENCE = NO_DIFFERENCE

    participant = models.ForeignKey(Participant, on_delete=models.CASCADE, related_name="responses")
    trial = models.ForeignKey(Trial, on_delete=models.RESTRICT, related_name="responses")
    question = models.ForeignKey(Question, on_delete=models.RESTRICT, related_name="responses")
    chosen = models.CharField(
        max_length=40, blank=True, help_text="Pairwise: the chosen condition's key, or 'none'."
    )
    chosen_position = models.PositiveSmallIntegerField(
        null=True, blank=True, help_text="Pairwise: 1 or 2 for Clip 1 or Clip 2, empty for 'none'."
    )
    rating = models.SmallIntegerField(
        null=True, blank=True, help_text="The chosen option's value (Likert, comparative, choice)."
    )
    number = models.FloatField(null=True, blank=True)
    text = models.TextField(blank=True)
    video = models.FileField(
        upload_to="answers/",
        storage=private_storage,
        blank=True,
        help_text="A signed answer (private: only the study's researchers can open it).",
    )
    video_sha256 = models.CharField(
        "signed answer's SHA-256",
        max_length=64,
        blank=True,
        help_text="Of the signed answer's file, as checked on upload; names it in exports.",
    )
    score = models.FloatField(
        null=True, blank=True, help_text="Intelligibility: word-level accuracy in [0, 1]."
    )
    rt_ms = models.PositiveIntegerField(
        "response time (ms)", null=True, blank=True, help_text="From page shown to answer."
    )
    answered_client_ms = models.BigIntegerField(
        "answered at (browser clock, ms)",
        null=True,
        blank=True,
        help_text="When the answer was given on the participant's browser clock, the clock "
        "of the media events (ms since 1970); the quality columns compare the two.",
    )
    revision = models.PositiveIntegerField(
        default=1, help_text="How many times the participant gave this answer."
    )
    answered_at = models.DateTimeField(auto_now_add=True)
    updated_at = models.DateTimeField(auto_now=True)

    class Meta:
        ordering = ["participant", "trial", "question"]
        constraints = [
            models.UniqueConstraint(
                fields=["participant", "trial", "question"], name="one_response_per_question"
            )
        ]

    def __str__(self) -> str:
        return f"{self.trial.key}/{self.question.key} by participant {self.participant_id}"


class MediaEvent(models.Model):
    """One thing that happened to a clip or page: play, pause, seek, end, error, shown."""

    class Kind(models.TextChoices):
        PAGE_SHOWN = "page_shown", "Page shown"
        PAGE_HIDDEN = "page_hidden", "Page hidden"
        PLAY = "play", "Play"
        PAUSE = "pause", "Pause"
        SEEK = "seek", "Seek"
        ENDED = "ended", "Ended"
        ERROR = "error", "Playback error"

    participant = models.ForeignKey(
        Participant, on_delete=models.CASCADE, related_name="media_events"
    )
    trial = models.ForeignKey(
        Trial, on_delete=models.RESTRICT, null=True, blank=True, related_name="media_events"
    )
    stimulus = models.ForeignKey(
        Stimulus, on_delete=models.SET_NULL, null=True, blank=True, related_name="media_events"
    )
    clip_position = models.PositiveSmallIntegerField(
        null=True, blank=True, help_text="1 or 2: which clip on the page."
    )
    kind = models.CharField(max_length=20, choices=Kind.choices)
    media_time_s = models.FloatField(
        null=True, blank=True, help_text="Playback position when it happened (s)."
    )
    client_time_ms = models.BigIntegerField(
        null=True, blank=True, help_text="Browser clock when it happened (ms since the epoch)."
    )
    detail = models.JSONField(default=dict, blank=True)
    created_at = models.DateTimeField(auto_now_add=True)

    class Meta:
        ordering = ["participant", "client_time_ms", "pk"]
        indexes = [models.Index(fields=["participant", "trial"])]

    def __str__(self) -> str:
        return f"{self.kind} by participant {self.participant_id}"
