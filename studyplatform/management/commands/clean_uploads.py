"""Delete signed-answer uploads that participants abandoned part-way (for cron)."""

from django.conf import settings
from django.core.management.base import BaseCommand, CommandError

from studyplatform.actions.uploads import do_remove_abandoned_uploads


class Command(BaseCommand):
    help = (
        "Delete unfinished signed-answer uploads nobody has added to for a while "
        "(default: SIGNSTUDY_PARTIAL_UPLOAD_MAX_AGE_HOURS). Celery beat runs the same job "
        "hourly; run this from cron where no beat runs."
    )

    def add_arguments(self, parser):
        parser.add_argument(
            "--older-than-hours",
            type=float,
            default=settings.SIGNSTUDY_PARTIAL_UPLOAD_MAX_AGE_HOURS,
            help="the age after which an untouched upload counts as abandoned",
        )

    def handle(self, *args, older_than_hours, **options):
        hours = older_than_hours
        try:
            removed = do_remove_abandoned_uploads(hours)
        except ValueError as error:
            raise CommandError(str(error)) from error
        self.stdout.write(f"Removed {len(removed)} abandoned upload(s) older than {hours:g} hours.")
