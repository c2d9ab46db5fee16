"""Load the demo studies and create the demo admin login, then print how to sign in."""

import secrets

from django.conf import settings
from django.contrib.auth import get_user_model
from django.core.management import call_command
from django.core.management.base import BaseCommand

from studyplatform.actions import do_import_study
from studyplatform.demo import DEMO_STUDIES
from studyplatform.models import Study

ADMIN_USERNAME = "admin"


class Command(BaseCommand):
    help = "Create the demo admin user and the demo studies (idempotent)."

    def add_arguments(self, parser) -> None:
        parser.add_argument(
            "--url", default="http://127.0.0.1:8000/", help="Where the demo is served."
        )
        parser.add_argument(
            "--render", action="store_true", help="Also render the demo studies' stimuli."
        )
        parser.add_argument("--workers", type=int, default=2, help="Rendering processes.")

    def handle(self, *args, url: str, render: bool, workers: int, **options) -> None:
        admin = self._ensure_admin()
        for build in DEMO_STUDIES:
            data = build()
            slug = data["study"]["slug"]
            if Study.objects.filter(slug=slug).exists():
                self.stdout.write(f"Demo study '{slug}' already loaded.")
                continue
            result = do_import_study(data, owner=admin, slug=slug)
            self.stdout.write(self.style.SUCCESS(f"Loaded demo study '{result.study.title}'."))
        if render:
            for build in DEMO_STUDIES:
                slug = build()["study"]["slug"]
                self.stdout.write(
                    f"Rendering the stimuli of '{slug}' (cached after the first run)…"
                )
                call_command("generate_stimuli", slug, workers=workers, stdout=self.stdout)
        password = (settings.VAR_DIR / "demo_admin_password").read_text().strip()
        self.stdout.write(
            "\n"
            f"  SignStudy demo:  {url}\n"
            f"  Admin:           {url}admin/\n"
            f"  Username:        {ADMIN_USERNAME}\n"
            f"  Password:        {password}\n"
            + "".join(
                f"  Take part:       {url}s/{build()['study']['slug']}/\n" for build in DEMO_STUDIES
            )
        )

    def _ensure_admin(self):
        """Return the demo superuser, creating it (or resetting a lost password)."""
        password_file = settings.VAR_DIR / "demo_admin_password"
        user_model = get_user_model()
        user = user_model.objects.filter(username=ADMIN_USERNAME).first()
        if user is not None and password_file.exists():
            return user
        password = secrets.token_urlsafe(12)
        if user is None:
            user = user_model.objects.create_superuser(ADMIN_USERNAME, "", password)
        else:
            user.set_password(password)
            user.save(update_fields=["password"])
        password_file.parent.mkdir(parents=True, exist_ok=True)
        password_file.write_text(password + "\n")
        password_file.chmod(0o600)
        return user
