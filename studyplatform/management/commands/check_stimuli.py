"""Check the clips of studies before anyone sees them (speeds, framing, size, contact, face)."""

from django.core.management.base import BaseCommand, CommandError

from studyplatform.lib.stimulus_checks import run_checks
from studyplatform.models import Study


class Command(BaseCommand):
    help = (
        "Check every rendered clip of the given studies (all when none is named) from its "
        "motion, without rendering: joint speeds against the keyed motion, hands in the "
        "frame and large enough, hands through the body, the face hidden."
    )

    def add_arguments(self, parser) -> None:
        parser.add_argument("slugs", nargs="*", metavar="slug")
        parser.add_argument(
            "--strict", action="store_true", help="exit with status 1 if any check warns"
        )

    def handle(self, *args, slugs: list[str], strict: bool, **options) -> None:
        studies = Study.objects.filter(slug__in=slugs) if slugs else Study.objects.all()
        unknown = sorted(set(slugs) - {study.slug for study in studies})
        if unknown:
            raise CommandError(f"No study with the slug {', '.join(unknown)}.")
        warned = 0
        for study in studies.order_by("pk"):
            checks = run_checks(study)
            warned += len(checks.warnings)
            self.stdout.write(
                f"{study.slug}: {checks.checked} clips checked, {len(checks.warnings)} warnings"
            )
            for line in checks.lines():
                self.stdout.write(f"  {line}")
        if strict and warned:
            raise CommandError(f"{warned} warnings.")
