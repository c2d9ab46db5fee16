"""Back up the database and all media into one archive."""

from pathlib import Path

from django.core.management.base import BaseCommand
from django.utils import timezone

from studyplatform.management.backup import make_backup


class Command(BaseCommand):
    help = (
        "Write the database (all studies, participants, answers, accounts) and every public "
        "and private media file to a .tar.gz archive with a manifest of row counts and "
        "checksums; `restore` reads it back and verifies it."
    )

    def add_arguments(self, parser):
        parser.add_argument(
            "out",
            nargs="?",
            help="the archive to write (default: var/backups/signstudy-<time>.tar.gz)",
        )

    def handle(self, *args, out=None, **options):
        from django.conf import settings

        stamp = timezone.now().strftime("%Y%m%d-%H%M%S")
        path = Path(out) if out else settings.VAR_DIR / "backups" / f"signstudy-{stamp}.tar.gz"
        summary = make_backup(path)
        self.stdout.write(
            f"Backed up {summary.rows} rows and {summary.files} files "
            f"({summary.bytes / 1e6:.1f} MB) to {path}."
        )
