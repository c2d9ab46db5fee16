"""Delete personal data whose study's retention period has passed (for cron)."""

from django.core.management.base import BaseCommand

from studyplatform.actions import do_apply_retention


class Command(BaseCommand):
    help = (
        "Delete the personal data (personal answers, signed-answer videos, recruitment ids) "
        "of participants whose study's retention period has passed. Celery beat runs the "
        "same job daily; run this from cron where no beat runs."
    )

    def handle(self, *args, **options):
        result = do_apply_retention()
        self.stdout.write(
            f"Deleted {result.personal_answers} personal answer(s), {result.videos} signed-"
            f"answer video(s) and the recruitment ids of {result.recruitment_ids} participant(s)."
        )
