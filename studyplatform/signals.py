"""Keep the "Researchers" group's permissions in step with the models after migrating."""

from django.db.models.signals import post_migrate
from django.dispatch import receiver

RESEARCHERS_GROUP = "Researchers"

# What a researcher may do with each model; object-level rules in the admin then limit
# every permission to the researcher's own studies.
RESEARCHER_PERMISSIONS: dict[str, tuple[str, ...]] = {
    "study": ("add", "change", "delete", "view"),
    "condition": ("add", "change", "delete", "view"),
    "item": ("add", "change", "delete", "view"),
    "question": ("add", "change", "delete", "view"),
    "answeroption": ("add", "change", "delete", "view"),
    "block": ("add", "change", "delete", "view"),
    "trial": ("add", "change", "delete", "view"),
    "stimulus": ("add", "change", "delete", "view"),
    "aslvideo": ("add", "change", "delete", "view"),
    "signedtemplate": ("add", "change", "delete", "view"),
    "recording": ("add", "delete", "view"),
    "avatar": ("add", "change", "delete", "view"),
    "participant": ("delete", "view"),
    "personalanswer": ("view",),
    "response": ("view",),
    "mediaevent": ("view",),
    "withdrawal": ("view",),
}


@receiver(post_migrate)
def sync_researchers_group(sender, app_config=None, using="default", **kwargs) -> None:
    """Create the Researchers group and grant it RESEARCHER_PERMISSIONS."""
    if app_config is None or app_config.label != "studyplatform":
        return
    from django.contrib.auth.models import Group, Permission

    codenames = [
        f"{action}_{model}"
        for model, actions in RESEARCHER_PERMISSIONS.items()
        for action in actions
    ]
    group, _ = Group.objects.using(using).get_or_create(name=RESEARCHERS_GROUP)
    permissions = Permission.objects.using(using).filter(
        content_type__app_label="studyplatform", codename__in=codenames
    )
    group.permissions.set(permissions)
