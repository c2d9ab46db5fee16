"""Write the engine's texts into the module makemessages reads (after a registry change)."""

from pathlib import Path

from django.conf import settings
from django.core.management.base import BaseCommand

from studyplatform.lib.engine_texts import MODULE, engine_texts_module


class Command(BaseCommand):
    help = (
        "Write the names and help texts of the engine's techniques, parameters, manual "
        "alphabets and designs into studyplatform/admin/engine_texts.py, where makemessages "
        "finds them for the catalogues. Run it when the engine's registries change."
    )

    def handle(self, *args, **options):
        path = Path(settings.BASE_DIR) / MODULE
        path.write_text(engine_texts_module(), "utf-8")
        self.stdout.write(f"Wrote {path}.")
