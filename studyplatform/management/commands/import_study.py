"""Create a study from a definition file exported by SignStudy."""

from django.contrib.auth import get_user_model
from django.core.management.base import BaseCommand, CommandError

from studyplatform.actions import StudyImportError, do_import_study
from studyplatform.lib import strict_json
from studyplatform.lib.bundle import BundleRejected, read_bundle


class Command(BaseCommand):
    help = (
        "Import a study definition (JSON, or a .zip bundle with its media) as a new study "
        "owned by --owner."
    )

    def add_arguments(self, parser) -> None:
        parser.add_argument("file")
        parser.add_argument("--owner", required=True, help="Username of the new study's owner.")
        parser.add_argument("--slug", help="Slug of the new study (default: the file's).")

    def handle(self, *args, file: str, owner: str, slug: str | None, **options) -> None:
        user = get_user_model().objects.filter(username=owner).first()
        if user is None:
            raise CommandError(f"No user '{owner}'.")
        files = None
        try:
            handle = open(file, "rb")  # noqa: SIM115 (a bundle's files are read from it below)
        except OSError as error:
            raise CommandError(f"Cannot read {file}: {error.strerror}.") from None
        with handle:
            try:
                if handle.read(4) == b"PK\x03\x04":
                    handle.seek(0)
                    data, files = read_bundle(handle)
                else:
                    handle.seek(0)
                    data = strict_json.loads(handle.read())
            except (strict_json.JsonRejected, BundleRejected) as error:
                raise CommandError(f"{file} is {error}.") from None
            try:
                result = do_import_study(data, owner=user, slug=slug, files=files)
            except StudyImportError as error:
                raise CommandError(f"{file}: {error}") from None
        for warning in result.warnings:
            self.stderr.write(self.style.WARNING(warning))
        self.stdout.write(
            self.style.SUCCESS(f"Imported '{result.study.title}' as '{result.study.slug}'.")
        )
