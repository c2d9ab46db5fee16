"""Render a study's stimuli: every clip its trials show that is not rendered yet."""

import time
from pathlib import Path

from django.conf import settings
from django.core.management.base import BaseCommand, CommandError

from stimuli.clips import ClipError
from stimuli.manifest import generate, read_manifest, write_manifest
from studyplatform.actions.stimuli import do_generate_stimuli
from studyplatform.lib.stimuli import study_manifest
from studyplatform.models import Stimulus, Study
from studyplatform.tasks import SUBDIRECTORY


class Command(BaseCommand):
    help = (
        "Render the stimuli of a study (by slug): queue Celery jobs when a broker is "
        "configured and wait for them, else render here, with --workers processes."
    )

    def add_arguments(self, parser) -> None:
        parser.add_argument("study", nargs="?", default="", help="the study's slug")
        parser.add_argument("--workers", type=int, default=1,
                            help="local rendering processes (when no broker is set)")  # fmt: skip
        parser.add_argument("--force", action="store_true", help="render every clip again")
        parser.add_argument(
            "--rerender-open", action="store_true",
            help="on an open or closed study, re-render clips whose specification changed "
            "(another engine or new parameters); refused without it",
        )  # fmt: skip
        parser.add_argument(
            "--manifest", type=Path, metavar="PATH",
            help="write the study's stimulus manifest (JSON) here afterwards",
        )  # fmt: skip
        parser.add_argument(
            "--from-manifest", type=Path, metavar="PATH",
            help="render a manifest's clips into the media folder (no study)",
        )  # fmt: skip
        parser.add_argument("--timeout", type=float, default=3600.0,
                            help="seconds to wait for queued jobs (with a broker)")  # fmt: skip

    def handle(self, *args, study: str, workers: int, force: bool, timeout: float, **options):
        if options["from_manifest"] is not None:
            return self._render_manifest(options["from_manifest"])
        if not study:
            raise CommandError("Name a study (its slug), or give --from-manifest.")
        found = Study.objects.filter(slug=study).first()
        if found is None:
            raise CommandError(f"No study with the slug {study!r}.")
        started = time.perf_counter()
        eager = settings.CELERY_TASK_ALWAYS_EAGER
        if eager and workers > 1:
            try:
                result = self._render_with_pool(found, force, workers, options["rerender_open"])
            except ClipError as error:
                raise CommandError(str(error)) from None
        else:
            try:
                result = do_generate_stimuli(
                    found, force=force, rerender_open=options["rerender_open"]
                )
            except ClipError as error:
                raise CommandError(str(error)) from None
            if not eager:
                self._wait(result.stimulus_ids, timeout)
        stimuli = Stimulus.objects.filter(pk__in=result.stimulus_ids)
        failed = stimuli.filter(status=Stimulus.Status.FAILED)
        for stimulus in failed:
            self.stderr.write(f"  failed: {stimulus} — {stimulus.error}")
        self.stdout.write(
            f"{found.slug}: {result.total} clips, {result.queued} rendered, {result.ready} "
            f"already there, {failed.count()} failed ({time.perf_counter() - started:.1f} s)"
        )
        if options["manifest"] is not None:
            path = write_manifest(study_manifest(found), options["manifest"], found.slug)
            self.stdout.write(f"manifest written to {path}")
        if failed.exists():
            raise CommandError(f"{failed.count()} clip(s) failed; retry them from the admin.")

    def _render_manifest(self, path: Path) -> None:
        """Render every clip of the manifest at *path* that the media folder lacks."""
        try:
            entries = read_manifest(path)
        except ClipError as error:
            raise CommandError(str(error)) from None
        directory = Path(settings.MEDIA_ROOT) / SUBDIRECTORY

        def report(number: int, total: int, label: str) -> None:
            self.stdout.write(f"  {number}/{total} {label}")

        done, rendered = generate(entries, directory, report)
        self.stdout.write(f"{path}: {len(done)} clips, {rendered} rendered, into {directory}")

    def _render_with_pool(self, study: Study, force: bool, workers: int, rerender_open: bool):
        """Record the clips without queueing, then render them in *workers* processes."""
        from concurrent.futures import ProcessPoolExecutor
        from multiprocessing import get_context

        result = do_generate_stimuli(study, force=force, enqueue=False, rerender_open=rerender_open)
        rows = Stimulus.objects.filter(pk__in=result.stimulus_ids)
        pending = list(rows.exclude(status=Stimulus.Status.READY).values_list("pk", flat=True))
        from studyplatform import render_pool

        context = get_context("spawn")
        with ProcessPoolExecutor(
            workers, mp_context=context, initializer=render_pool.setup
        ) as pool:
            for number, status in enumerate(pool.map(render_pool.render, pending), start=1):
                self.stdout.write(f"  {number}/{len(pending)} {status}")
        return result

    def _wait(self, ids, timeout: float) -> None:
        """Poll until no clip of *ids* is pending or rendering (or the timeout)."""
        deadline = time.monotonic() + timeout
        open_states = (Stimulus.Status.PENDING, Stimulus.Status.RENDERING)
        while time.monotonic() < deadline:
            left = Stimulus.objects.filter(pk__in=ids, status__in=open_states).count()
            if not left:
                return
            self.stdout.write(f"  {len(ids) - left}/{len(ids)} done")
            time.sleep(2.0)
        raise CommandError(f"Gave up waiting after {timeout:.0f} s; the jobs keep running.")
