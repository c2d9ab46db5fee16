"""Declare the study platform's Django app."""

from django.apps import AppConfig


class StudyPlatformConfig(AppConfig):
    """Configure the ``studyplatform`` app."""

    name = "studyplatform"
    verbose_name = "SignStudy"
    default_auto_field = "django.db.models.BigAutoField"

    def ready(self) -> None:
        """Connect the signal handlers (researcher permissions, known sign-in devices) and
        register the system checks."""
        from studyplatform import checks, signals  # noqa: F401
        from studyplatform.admin import signin  # noqa: F401
