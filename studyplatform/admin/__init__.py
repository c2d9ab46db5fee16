"""Register the researcher's admin pages; every one is limited to the user's own studies."""

from django.contrib import admin

from studyplatform.admin import (  # noqa: F401
    avatars,
    conditions,
    design,
    participants,
    stimuli,
    studies,
)

admin.site.site_header = "SignStudy"
admin.site.site_title = "SignStudy admin"
admin.site.index_title = "Studies, stimuli and responses"
