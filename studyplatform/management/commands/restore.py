"""Restore a backup archive and verify it."""

from pathlib import Path

from django.core.management.base import BaseCommand, CommandError

from studyplatform.management.backup import BackupError, restore_backup


class Command(BaseCommand):
    help = (
        "Restore an archive written by `backup` into this installation (migrate first), "
        "then check every row count and file checksum against the archive's manifest."
    )

    def add_arguments(self, parser):
        parser.add_argument("archive", help="the .tar.gz written by `backup`")
        parser.add_argument(
            "--replace", action="store_true", help="delete what the database holds before restoring"
        )

    def handle(self, *args, archive, replace, **options):
        try:
            summary = restore_backup(Path(archive), replace=replace)
        except BackupError as error:
            raise CommandError(str(error)) from error
        self.stdout.write(
            f"Restored and verified {summary.rows} rows and {summary.files} "
            f"files ({summary.bytes / 1e6:.1f} MB)."
        )
        if summary.withdrawn_again:
            numbers = ", ".join(f"#{n}" for n in summary.withdrawn_again)
            self.stdout.write(
                self.style.WARNING(
                    f"{len(summary.withdrawn_again)} participants had withdrawn after this backup "
                    f"was made and were withdrawn again, with their files: {numbers}."
                )
            )
