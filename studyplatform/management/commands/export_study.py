"""Write a study's definition as JSON, to a file or standard output."""

from django.core.management.base import BaseCommand, CommandError

from studyplatform.lib.bundle import definition_json, write_bundle
from studyplatform.lib.exchange import export_study
from studyplatform.models import Study


class Command(BaseCommand):
    help = "Export a study definition (JSON) by its slug."

    def add_arguments(self, parser) -> None:
        parser.add_argument("slug")
        parser.add_argument("--out", help="File to write; standard output when omitted.")
        parser.add_argument(
            "--with-media",
            action="store_true",
            help="write a .zip bundle with the ASL videos and recordings (needs --out)",
        )

    def handle(self, *args, slug: str, out: str | None, with_media: bool, **options) -> None:
        study = Study.objects.filter(slug=slug).first()
        if study is None:
            raise CommandError(f"No study with slug '{slug}'.")
        if with_media:
            if not out:
                raise CommandError("--with-media writes a zip file: give it --out.")
            with open(out, "wb") as handle:
                write_bundle(export_study(study), handle)
            return
        text = definition_json(export_study(study))
        if out:
            with open(out, "w", encoding="utf-8") as handle:
                handle.write(text)
        else:
            self.stdout.write(text, ending="")
