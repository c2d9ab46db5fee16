"""Register the researcher's admin pages; every one is limited to the user's own studies."""

from django.contrib import admin
from django.utils.translation import gettext_lazy

from studyplatform.admin import (  # noqa: F401
    avatars,
    conditions,
    design,
    participants,
    stimuli,
    studies,
)

# Fields a study definition exports (exchange.EXPORTED) that the admin's forms do not
# edit, with why; tests/studyplatform/test_admin_pages.py fails on any other one missing.
NOT_EDITED_HERE = {
    "Study": {"design": "written by the design builder's page, from its choices"},
    "Item": {
        "parameters": "set in a study definition (import, or a copy's JSON); the study "
        "page's item rows stay one line each"
    },
}

admin.site.site_header = "SignStudy"
admin.site.site_title = gettext_lazy("SignStudy admin")
admin.site.index_title = gettext_lazy("Studies, stimuli and responses")
