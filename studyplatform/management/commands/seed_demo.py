"""Load the demo studies and create the demo admin login, then print how to sign in."""

import secrets

from django.conf import settings
from django.contrib.auth import get_user_model
from django.core.management import call_command
from django.core.management.base import BaseCommand

from studyplatform.actions import do_import_study
from studyplatform.demo import DEMO_SETUP, DEMO_SIGNED, DEMO_STUDIES
from studyplatform.models import Study
from synthesis.capture.lexicon import LexiconMissing

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
        ready = []
        for build in DEMO_STUDIES:
            data = build()
            slug = data["study"]["slug"]
            study = Study.objects.filter(slug=slug).first()
            if study is not None:
                self.stdout.write(f"Demo study '{slug}' already loaded.")
            else:
                study = do_import_study(data, owner=admin, slug=slug).study
                self.stdout.write(self.style.SUCCESS(f"Loaded demo study '{study.title}'."))
            if self._set_up(study):
                ready.append(slug)
        if render:
            self._sign_prompts()
        if render and ready:
            self.stdout.write(
                f"Rendering the stimuli of {', '.join(repr(slug) for slug in ready)} "
                "(cached after the first run)…"
            )
            call_command("generate_stimuli", *ready, workers=workers, stdout=self.stdout)
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

    def _set_up(self, study: Study) -> bool:
        """Attach what the demo study needs besides its definition; return whether it can
        be rendered."""
        setup = DEMO_SETUP.get(study.slug)
        if setup is None:
            return True
        try:
            attached = setup(study)
        except LexiconMissing as error:
            self.stderr.write(self.style.WARNING(f"'{study.slug}' is not rendered: {error}"))
            return False
        if attached:
            self.stdout.write(f"Attached {attached} recording(s) to '{study.slug}'.")
        return True

    def _sign_prompts(self) -> None:
        """Render and attach the avatar-signed prompts of the ASL-first demos."""
        for slug, sign in DEMO_SIGNED.items():
            study = Study.objects.filter(slug=slug).first()
            if study is None:
                continue
            attached = sign(study)
            if attached:
                self.stdout.write(
                    f"Signed {attached} prompt(s) of '{slug}' with the avatar (labelled as "
                    "avatar-signed demo material)."
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
