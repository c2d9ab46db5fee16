"""Write a study clip's motion as GLB (with the avatar, face and camera) or BVH."""

from pathlib import Path

from django.core.management.base import BaseCommand, CommandError

from stimuli.clips import ClipError
from studyplatform.lib.motion import stimulus_motion
from studyplatform.models import Stimulus


class Command(BaseCommand):
    help = "Export what participants saw in one clip as GLB (Blender, Unity) or BVH."

    def add_arguments(self, parser):
        parser.add_argument("study", help="the study's slug")
        parser.add_argument("condition", help="the condition's key")
        parser.add_argument("item", help="the item's key")
        parser.add_argument(
            "--out", type=Path, required=True, help="FILE.glb or FILE.bvh (the extension chooses)"
        )

    def handle(self, *args, **options):
        stimulus = (
            Stimulus.objects.filter(
                condition__study__slug=options["study"],
                condition__key=options["condition"],
                item__key=options["item"],
            )
            .select_related("condition__study", "item")
            .first()
        )
        if stimulus is None:
            raise CommandError("No such clip: check the study's slug, condition and item keys.")
        out = options["out"]
        try:
            data, _ = stimulus_motion(stimulus, out.suffix.lower().lstrip("."))
        except (ClipError, ValueError) as error:
            raise CommandError(str(error)) from None
        out.write_bytes(data)
        self.stdout.write(f"wrote {out} ({len(data)} bytes)")
