"""Define a study and the conditions and items it compares.

Source: spec 06 "What a researcher configures".
"""

from functools import cached_property

from django.conf import settings
from django.contrib.contenttypes.fields import GenericRelation
from django.core.exceptions import ValidationError
from django.core.validators import MaxValueValidator, MinValueValidator
from django.db import models
from django.utils.translation import gettext, ngettext
from django.utils.translation import gettext_lazy as _

from studyplatform.rules import check_condition, check_study_values
from synthesis.fingerspelling.alphabets import DEFAULT_ALPHABET, alphabet_choices
from synthesis.techniques.request import REQUEST_PARAMETERS
from synthesis.techniques.timing import trained_on_simulated


def position_field() -> models.SmallIntegerField:
    """Return the field that orders a study's rows (conditions, items, blocks …)."""
    # Signed: a row can go before the others without renumbering them.
    return models.SmallIntegerField(
        _("position"),
        default=0,
        help_text=_(
            "Order: lower comes first; a negative number puts it before the others. "
            "New rows left at 0 are numbered after the existing ones."
        ),
    )


# The engine's clip size parameters: their bounds are the fields', and their defaults
# the size of a study made before it was a setting. A new study films in HD.
_FILMING = {p.name: p for p in REQUEST_PARAMETERS if p.name in ("width", "height")}
CLIP_SIZE = (1280, 720)
LEGACY_CLIP_SIZE = (_FILMING["width"].default, _FILMING["height"].default)


def _clip_size_validators(name: str) -> list:
    """Return the engine's bounds of clip size parameter *name* as field validators."""
    parameter = _FILMING[name]
    return [MinValueValidator(parameter.minimum), MaxValueValidator(parameter.maximum)]


def default_thank_you_text() -> str:
    """Return a new study's thank-you text, in the researcher's language (who edits it)."""
    return gettext("Thank you for taking part in this study.")


def manual_alphabets() -> list[tuple[str, str]]:
    """Return the engine's manual alphabets as choices, named in the researcher's language."""
    return [(code, gettext(name)) for code, name in alphabet_choices()]


def interface_languages() -> list[tuple[str, str]]:
    """Return the languages a participant's pages can be in (settings.LANGUAGES)."""
    return list(settings.LANGUAGES)


class Study(models.Model):
    """A perceptual study: its settings, what participants see first and last."""

    class Status(models.TextChoices):
        DRAFT = "draft", _("Draft")
        PILOT = "pilot", _("Pilot (responses flagged, excluded from analysis)")
        OPEN = "open", _("Open")
        CLOSED = "closed", _("Closed")

    class ConsentMode(models.TextChoices):
        IMPLICIT = "implicit", _("Continuing means consent")
        EXPLICIT = "explicit", _("Explicit consent checkbox")

    class Devices(models.TextChoices):
        ANY = "any", _("Any device")
        DESKTOP = "desktop", _("Desktop or laptop only")
        MOBILE = "mobile", _("Phone or tablet only")

    # True on the draft do_import_study creates and fills: the action made it a moment
    # ago and opens it only once every row is in, so its rows need not ask the database
    # whether it is locked (two queries a row, most of an import's time).
    being_filled = False

    owner = models.ForeignKey(
        settings.AUTH_USER_MODEL,
        verbose_name=_("owner"),
        on_delete=models.PROTECT,
        related_name="studies",
        help_text=_("The researcher who owns the study; only they (and superusers) see it."),
    )
    slug = models.SlugField(
        _("slug"),
        max_length=80,
        unique=True,
        help_text=_("Short name used in the participant link and in exported data."),
    )
    title = models.CharField(_("title"), max_length=200)
    description = models.TextField(
        _("description"), blank=True, help_text=_("Shown on the study's welcome page.")
    )
    status = models.CharField(
        _("status"), max_length=10, choices=Status.choices, default=Status.DRAFT, db_index=True
    )
    language = models.CharField(
        _("language"),
        max_length=10,
        choices=interface_languages,
        default="en",
        help_text=_(
            "The language of the participant's pages: their buttons and messages. "
            "Write the study's own texts in it too."
        ),
    )
    follow_browser_language = models.BooleanField(
        _("follow browser language"),
        default=False,
        help_text=_(
            "Show the pages in the participant's browser language where it is one "
            "of the interface's languages, else in the study's language."
        ),
    )
    sign_language = models.CharField(
        _("sign language"),
        max_length=40,
        default="ASL",
        help_text=_(
            "The sign language's name as participants know it (ASL, Libras, TİD, "
            "BSL …): the pages use it wherever they name the signing."
        ),
    )
    manual_alphabet = models.CharField(
        _("manual alphabet"),
        max_length=20,
        choices=manual_alphabets,
        default=DEFAULT_ALPHABET,
        help_text=_(
            "The manual alphabet the study's fingerspelled words are spelled in "
            "(the engine's alphabet files; a condition or an item may set another)."
        ),
    )
    # A new study films in HD: at 640 × 480 a fist letter's hand was about 21 × 32 px and
    # A, E, M, N, S, T could not be told apart (issue 52). A study made before the
    # setting existed, or imported from a definition without it, keeps LEGACY_CLIP_SIZE.
    clip_width = models.PositiveSmallIntegerField(
        _("clip width"),
        default=CLIP_SIZE[0],
        validators=_clip_size_validators("width"),
        help_text=_(
            "Pixels. Every rendered condition's clips, unless a condition sets its own "
            "size. 1280 × 720 by default, so letters and hands read at the size "
            "participants see them."
        ),
    )
    clip_height = models.PositiveSmallIntegerField(
        _("clip height"),
        default=CLIP_SIZE[1],
        validators=_clip_size_validators("height"),
        help_text=_("Pixels (see clip width)."),
    )
    phone_clips_side_by_side = models.BooleanField(
        _("phone clips side by side"),
        default=False,
        help_text=_(
            "On a phone held upright, show a page's two clips side by side (small, "
            "kept at the top while the questions scroll) instead of one under the other at "
            "the screen's full width."
        ),
    )
    asl_first = models.BooleanField(
        _("signing first"),
        default=False,
        help_text=_(
            "Show each prompt's sign-language video first and large, with the written "
            "text secondary."
        ),
    )
    allow_english_only = models.BooleanField(
        _("allow written text only"),
        default=True,
        help_text=_("Let participants switch the study to its written text only."),
    )
    consent_text = models.TextField(_("consent text"), blank=True)
    consent_mode = models.CharField(
        _("consent mode"), max_length=10, choices=ConsentMode.choices, default=ConsentMode.IMPLICIT
    )
    thank_you_text = models.TextField(
        _("thank you text"), blank=True, default=default_thank_you_text
    )
    completion_code = models.CharField(
        _("completion code"),
        max_length=64,
        blank=True,
        help_text=_("Code shown at the end, e.g. for a recruitment service."),
    )
    unique_completion_codes = models.BooleanField(
        _("unique completion codes"),
        default=False,
        help_text=(
            _(
                "Give each participant a code of their own (the code above, if any, then a "
                "dash and 8 random characters), so a recruitment service's submissions can be "
                "matched to participants one by one."
            )
        ),
    )
    redirect_url = models.URLField(
        _("redirect url"),
        blank=True,
        max_length=500,
        help_text=(
            _(
                "Where to send participants at the end (automatically, after a few seconds). "
                "Recruitment parameters kept from the link and the completion code can be "
                "inserted, e.g. https://app.prolific.com/submissions/complete?cc={CODE}&pid="
                "{PROLIFIC_PID}."
            )
        ),
    )
    allowed_devices = models.CharField(
        _("allowed devices"), max_length=10, choices=Devices.choices, default=Devices.ANY
    )
    one_sitting = models.BooleanField(
        _("one sitting"), default=False, help_text=_("The study must be completed in one sitting.")
    )
    shared_computer = models.BooleanField(
        _("shared computer"),
        default=False,
        help_text=(
            _(
                "For a lab computer that participants take in turns: when one finishes, the "
                "study link starts afresh in that browser, and the thank-you page has a button "
                "for the next participant. The study link with ?new=1 starts afresh even if "
                "the one before left without finishing."
            )
        ),
    )
    time_limit_minutes = models.PositiveIntegerField(
        _("time limit minutes"),
        null=True,
        blank=True,
        validators=[MinValueValidator(1)],
        help_text=_("Empty: no limit."),
    )
    personal_data_retention_days = models.PositiveIntegerField(
        _("keep personal data for (days)"),
        null=True,
        blank=True,
        validators=[MinValueValidator(1)],
        help_text=(
            _(
                "Days after a participant finishes (or last took part) until their personal "
                "data is deleted: answers marked personal (name, e-mail), signed-answer videos "
                "and recruitment ids. Their other answers stay, anonymous. Empty: keep."
            )
        ),
    )
    target_n = models.PositiveIntegerField(
        _("target N"), null=True, blank=True, help_text=_("Number of participants wanted.")
    )
    allow_back = models.BooleanField(
        _("allow back"),
        default=True,
        help_text=_("Show a Prev button; answers can be changed until the end."),
    )
    replay_limit = models.PositiveSmallIntegerField(
        _("replay limit"),
        null=True,
        blank=True,
        help_text=_("Plays allowed per clip; empty means unlimited."),
    )
    require_full_view = models.BooleanField(
        _("require full view"),
        default=False,
        help_text=_("Participants must watch every clip to its end before answering."),
    )
    rotate_conditions = models.BooleanField(
        _("rotate conditions"),
        default=False,
        help_text=(
            _(
                "Latin-square rotation: participant n sees the trial blocks' conditions relabelled "
                "by row n of a balanced Latin square, so cells balance over every k participants "
                "(k conditions). Needs every condition rendered for every item."
            )
        ),
    )
    randomize_positions = models.BooleanField(
        _("randomize positions"),
        default=True,
        help_text=_("Swap Clip 1 and Clip 2 at random per participant (seeded, reproducible)."),
    )
    allow_identical_clips = models.BooleanField(
        _("identical clips intended"),
        default=False,
        help_text=(
            _(
                "Conditions may render the same clip for an item (say, a control identical by "
                "design). Off: generating stimuli and opening the study are refused while two "
                "conditions of an item would show identical clips."
            )
        ),
    )
    version = models.PositiveSmallIntegerField(
        _("version"),
        default=1,
        editable=False,
        help_text=_("1 for a new study; a new version counts on."),
    )
    previous_version = models.ForeignKey(
        "self",
        verbose_name=_("previous version"),
        on_delete=models.SET_NULL,
        null=True,
        blank=True,
        editable=False,
        related_name="next_versions",
        help_text=_("The study this version was made from; its participants stay with it."),
    )
    design = models.JSONField(
        _("design"),
        default=dict,
        blank=True,
        editable=False,
        help_text=_("What the design builder last built: its choices and the blocks it made."),
    )
    created_at = models.DateTimeField(_("created at"), auto_now_add=True)
    updated_at = models.DateTimeField(_("updated at"), auto_now=True)

    signed_templates = models.ManyToManyField(
        "studyplatform.SignedTemplate",
        verbose_name=_("signed templates"),
        blank=True,
        related_name="studies",
        help_text=(
            _(
                "Signed texts you recorded once (consent, instructions, thank-you, what the "
                "buttons do): they sign those texts where this study has no video of its own."
            )
        ),
    )
    asl_videos = GenericRelation("studyplatform.AslVideo", verbose_name=_("ASL videos"))

    class Meta:
        verbose_name = _("study")
        verbose_name_plural = _("studies")
        ordering = ["-created_at", "pk"]

    def __str__(self) -> str:
        return self.title

    def clean(self) -> None:
        odd = [name for name in ("clip_width", "clip_height") if (getattr(self, name) or 0) % 2]
        if odd:
            # H.264 (the clips' codec, 4:2:0) encodes only even sizes.
            raise ValidationError(dict.fromkeys(odd, _("Clip sizes are even numbers of pixels.")))
        check_study_values(self)

    @property
    def design_locked(self) -> bool:
        """Return whether the design can no longer change: the study is open or closed,
        or a participant who is not a pilot has taken it, whatever its status says.

        Participants' answers refer to its conditions, items, questions and pages; a
        change would alter what past answers mean, so it goes into a new version.
        """
        return self.status in {self.Status.OPEN, self.Status.CLOSED} or self.real_participants > 0

    @property
    def lock_reason(self) -> str:
        """Say why the design is locked ("" if it is not), for the admin's notes."""
        if self.status in {self.Status.OPEN, self.Status.CLOSED}:
            return gettext("the study is %(status)s") % {
                "status": str(self.get_status_display()).lower()
            }
        taken = self.real_participants
        if not taken:
            return ""
        return ngettext(
            "%(count)d participant has taken it", "%(count)d participants have taken it", taken
        ) % {"count": taken}

    @cached_property
    def real_participants(self) -> int:
        """Return how many participants (pilots aside) have taken the study.

        Read once per instance: the admin asks for every inline row's permissions, and a
        page is one instance's view (check_unlocked reads the database afresh).
        """
        return self.count_real_participants()

    def count_real_participants(self) -> int:
        """Count the participants (pilots aside) in the database now."""
        if self.pk is None:
            return 0
        return self.participants.filter(is_pilot=False).count()

    @property
    def is_accepting_participants(self) -> bool:
        """Return whether the participant link works (pilot or open)."""
        return self.status in {self.Status.PILOT, self.Status.OPEN}


def check_unlocked(study: Study | None) -> None:
    """Raise ValidationError if *study*'s design is locked (see Study.design_locked).

    The stored status counts: a form that opens a study checks its other rows against
    the draft they still belong to.
    """
    from django.core.exceptions import ValidationError

    if study is None or study.being_filled:
        return
    locked = [Study.Status.OPEN, Study.Status.CLOSED]
    if Study.objects.filter(pk=study.pk, status__in=locked).exists():
        raise ValidationError(
            _(
                "“%(title)s” is %(status)s: its design is locked. "
                "Make a new version of the study to change it."
            )
            % {"title": study.title, "status": str(study.get_status_display()).lower()}
        )
    taken = study.count_real_participants()
    if taken:
        raise ValidationError(
            ngettext(
                "“%(title)s” has been taken by %(count)d participant: its design is locked "
                "whatever its status. Make a new version of the study to change it.",
                "“%(title)s” has been taken by %(count)d participants: its design is locked "
                "whatever its status. Make a new version of the study to change it.",
                taken,
            )
            % {"title": study.title, "count": taken}
        )


class Condition(models.Model):
    """One animation technique compared in a study (e.g. the Variable timing model), or
    a set of clips the researcher brings (a filmed signer, another lab's animation)."""

    class Source(models.TextChoices):
        RENDERED = "rendered", _("Rendered by the engine")
        UPLOADED = "uploaded", _("Uploaded clips (one video per item)")

    study = models.ForeignKey(
        Study, verbose_name=_("study"), on_delete=models.CASCADE, related_name="conditions"
    )
    key = models.SlugField(
        _("key"), max_length=40, help_text=_("Name used in exported data, e.g. 'variable'.")
    )
    label = models.CharField(
        _("label"), max_length=100, help_text=_("Name shown in the admin and reports.")
    )
    description = models.TextField(_("description"), blank=True)
    is_simulated = models.BooleanField(
        _("is simulated"),
        default=False,
        help_text=(
            _(
                "A simulated stand-in (e.g. a simulated reference performance instead of a "
                "motion capture recording); labelled 'simulated' everywhere it appears."
            )
        ),
    )
    source = models.CharField(
        _("clips"),
        max_length=10,
        choices=Source.choices,
        default=Source.RENDERED,
        help_text=_(
            "Rendered: the engine renders each item with this condition's settings. "
            "Uploaded: you upload one video per item (MP4, WebM or MOV) on the study's "
            "Uploaded clips page; the condition has no settings."
        ),
    )
    avatar = models.ForeignKey(
        "studyplatform.Avatar",
        verbose_name=_("avatar"),
        on_delete=models.PROTECT,
        null=True,
        blank=True,
        related_name="conditions",
        help_text=_(
            "Film this condition's clips with your own avatar (Avatars in the menu) "
            "instead of the built-in signer; the avatar settings below then stay at their "
            "defaults."
        ),
    )
    parameters = models.JSONField(
        _("parameters"),
        default=dict,
        blank=True,
        help_text=(
            _(
                'The techniques\' settings for this condition, e.g. {"timing": "variable", '
                '"source": "simulated"}; checked against the technique registry on save '
                "(python -m synthesis techniques lists every parameter). Leave out a setting "
                "to take its default."
            )
        ),
    )
    position = position_field()

    class Meta:
        verbose_name = _("condition")
        verbose_name_plural = _("conditions")
        ordering = ["study", "position", "pk"]
        constraints = [
            models.UniqueConstraint(fields=["study", "key"], name="condition_key_unique_in_study")
        ]

    def __str__(self) -> str:
        return f"{self.label} (simulated)" if self.simulated else self.label

    @cached_property
    def simulated(self) -> bool:
        """Return whether what this condition shows rests on simulated data: marked so,
        or timed by a Variable model trained on simulated holds (the built-in one)."""
        if self.is_simulated:
            return True
        return not self.is_uploaded and trained_on_simulated(self.parameters or {})

    @property
    def is_uploaded(self) -> bool:
        """Return whether the condition's clips are uploaded files, not rendered."""
        return self.source == self.Source.UPLOADED

    def clean(self) -> None:
        check_unlocked(self.study if self.study_id else None)
        if self.is_uploaded and self.avatar_id is not None:
            raise ValidationError({"avatar": _("Uploaded clips are not filmed with an avatar.")})
        if not self.is_uploaded:
            check_condition(self)
        elif self.parameters:
            raise ValidationError(
                {
                    "parameters": _(
                        "A condition of uploaded clips renders nothing: leave its "
                        "settings empty (they would change nothing participants see)."
                    )
                }
            )
