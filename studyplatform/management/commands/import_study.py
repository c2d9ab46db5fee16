"""Create a study from a definition file exported by SignStudy."""

from django.contrib.auth import get_user_model
from django.core.management.base import BaseCommand, CommandError

from studyplatform.actions import StudyImportError, do_import_study
from studyplatform.lib import strict_json


class Command(BaseCommand):
    help = "Import a study definition (JSON) as a new study owned by --owner."

    def add_arguments(self, parser) -> None:
        parser.add_argument("file")
        parser.add_argument("--owner", required=True, help="Username of the new study's owner.")
        parser.add_argument("--slug", help="Slug of the new study (default: the file's).")

    def handle(self, *args, file: str, owner: str, slug: str | None, **options) -> None:
        user = get_user_model().objects.filter(username=owner).first()
        if user is None:
            raise CommandError(f"No user '{owner}'.")
        try:
            with open(file, "rb") as handle:
                data = strict_json.loads(handle.read())
        except OSError as error:
            raise CommandError(f"Cannot read {file}: {error.strerror}.") from None
        except strict_json.JsonRejected as error:
            raise CommandError(f"{file} is {error}.") from None
        try:
            result = do_import_study(data, owner=user, slug=slug)
        except StudyImportError as error:
            raise CommandError(f"{file}: {error}") from None
        for warning in result.warnings:
            self.stderr.write(self.style.WARNING(warning))
        self.stdout.write(
            self.style.SUCCESS(f"Imported '{result.study.title}' as '{result.study.slug}'.")
        )
