"""Render stimuli by id in this process (or a few): the background process of the admin."""

import os

from django.core.management.base import BaseCommand

from studyplatform.management.render_pool import render_many


class Command(BaseCommand):
    help = "Render the stimuli with the given ids that are not rendered yet."

    def add_arguments(self, parser) -> None:
        parser.add_argument("ids", nargs="+", type=int, metavar="id")
        parser.add_argument(
            "--workers",
            type=int,
            default=min(4, os.cpu_count() or 1),
            help="rendering processes (default: the cores, at most 4)",
        )

    def handle(self, *args, ids: list[int], workers: int, **options) -> None:
        def report(number: int, total: int, status: str) -> None:
            self.stdout.write(f"  {number}/{total} {status}")

        statuses = render_many(ids, workers, report)
        self.stdout.write(f"{len(statuses)} clips: {', '.join(sorted(set(statuses)))}")
