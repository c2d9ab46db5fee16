"""Render studies' stimuli: every clip their trials show that is not rendered yet."""

import dataclasses
import time
from pathlib import Path

from django.conf import settings
from django.core.management.base import BaseCommand, CommandError

from stimuli.clips import ClipError
from stimuli.manifest import generate, read_manifest, write_manifest
from studyplatform.actions.stimuli import GenerateOptions, do_generate_stimuli
from studyplatform.lib.stimuli import SUBDIRECTORY, study_manifest, uploaded_manifest
from studyplatform.models import Stimulus, Study


class Command(BaseCommand):
    help = (
        "Render the stimuli of one or more studies (by slug): queue Celery jobs when a "
        "broker is configured and wait for them, else render here, with --workers processes."
    )

    def add_arguments(self, parser) -> None:
        parser.add_argument("studies", nargs="*", metavar="study", help="the studies' slugs")
        parser.add_argument(
            "--workers",
            type=int,
            default=1,
            help="local rendering processes (when no broker is set)",
        )
        parser.add_argument("--force", action="store_true", help="render every clip again")
        parser.add_argument(
            "--rerender-open",
            action="store_true",
            help="on an open or closed study, re-render clips whose specification changed "
            "(another engine or new parameters); refused without it",
        )
        parser.add_argument(
            "--allow-identical",
            action="store_true",
            help="render even where two conditions of an item would give identical clips",
        )
        parser.add_argument(
            "--manifest",
            type=Path,
            metavar="PATH",
            help="write the study's stimulus manifest (JSON) here afterwards",
        )
        parser.add_argument(
            "--from-manifest",
            type=Path,
            metavar="PATH",
            help="render a manifest's clips into the media folder (no study)",
        )
        parser.add_argument(
            "--timeout",
            type=float,
            default=3600.0,
            help="seconds to wait for queued jobs (with a broker)",
        )

    def handle(
        self, *args, studies: list[str], workers: int, force: bool, timeout: float, **options
    ):
        if options["from_manifest"] is not None:
            return self._render_manifest(options["from_manifest"])
        if not studies:
            raise CommandError("Name a study (its slug), or give --from-manifest.")
        if options["manifest"] is not None and len(studies) > 1:
            raise CommandError("--manifest writes one study's manifest: name one study.")
        found = self._studies(studies)
        started = time.perf_counter()
        eager = settings.CELERY_TASK_ALWAYS_EAGER
        generation = GenerateOptions(
            force=force,
            rerender_open=options["rerender_open"],
            allow_identical=options["allow_identical"],
        )
        try:
            if eager and workers > 1:
                results = self._render_with_pool(found, generation, workers)
            else:
                results = [do_generate_stimuli(study, generation) for study in found]
                if not eager:
                    self._wait([pk for result in results for pk in result.stimulus_ids], timeout)
        except ClipError as error:
            raise CommandError(str(error)) from None
        failures = self._report(found, results, time.perf_counter() - started)
        if options["manifest"] is not None:
            path = write_manifest(
                study_manifest(found[0]),
                options["manifest"],
                found[0].slug,
                uploaded_manifest(found[0]),
            )
            self.stdout.write(f"manifest written to {path}")
        if failures:
            raise CommandError(f"{failures} clip(s) failed; retry them from the admin.")

    def _studies(self, slugs: list[str]) -> list[Study]:
        found = []
        for slug in slugs:
            study = Study.objects.filter(slug=slug).first()
            if study is None:
                raise CommandError(f"No study with the slug {slug!r}.")
            found.append(study)
        return found

    def _report(self, found: list[Study], results, seconds: float) -> int:
        """Print each study's clips and failures; return how many failed."""
        failures = 0
        for study, result in zip(found, results, strict=True):
            failed = Stimulus.objects.filter(
                pk__in=result.stimulus_ids, status=Stimulus.Status.FAILED
            )
            for stimulus in failed:
                self.stderr.write(f"  failed: {stimulus} — {stimulus.error}")
            failures += failed.count()
            missing = f", {result.missing} not uploaded yet" if result.missing else ""
            self.stdout.write(
                f"{study.slug}: {result.total} clips, {result.queued} rendered, {result.ready} "
                f"already there, {failed.count()} failed{missing} ({seconds:.1f} s)"
            )
        return failures

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

    def _render_with_pool(
        self, studies: list[Study], generation: GenerateOptions, workers: int
    ) -> list:
        """Record the studies' clips without queueing, then render them in *workers*
        processes, one pool for all (a pool per study would leave processes idle as each
        study ends)."""
        from studyplatform.management.render_pool import render_many

        recording = dataclasses.replace(generation, enqueue=False)
        results = [do_generate_stimuli(study, recording) for study in studies]

        def report(number: int, total: int, status: str) -> None:
            self.stdout.write(f"  {number}/{total} {status}")

        render_many([pk for result in results for pk in result.stimulus_ids], workers, report)
        return results

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
