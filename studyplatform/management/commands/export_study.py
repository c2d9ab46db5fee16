"""Write a study's definition as JSON, to a file or standard output."""

import json

from django.core.management.base import BaseCommand, CommandError

from studyplatform.exchange import export_study
from studyplatform.models import Study


class Command(BaseCommand):
    help = "Export a study definition (JSON) by its slug."

    def add_arguments(self, parser) -> None:
        parser.add_argument("slug")
        parser.add_argument("--out", help="File to write; standard output when omitted.")

    def handle(self, *args, slug: str, out: str | None, **options) -> None:
        study = Study.objects.filter(slug=slug).first()
        if study is None:
            raise CommandError(f"No study with slug '{slug}'.")
        text = json.dumps(export_study(study), indent=2, ensure_ascii=False) + "\n"
        if out:
            with open(out, "w", encoding="utf-8") as handle:
                handle.write(text)
        else:
            self.stdout.write(text, ending="")
