"""Route the platform's URLs."""

from django.conf import settings
from django.contrib import admin
from django.urls import path, re_path

from studyplatform import views

urlpatterns = [
    path("", views.home, name="home"),
    path("admin/", admin.site.urls),
    path("s/<slug:slug>/", views.study_welcome, name="study_welcome"),
    path("p/<str:token>/", views.resume, name="participant_resume"),
    path("p/<str:token>/<int:number>/", views.page, name="participant_page"),
    path("p/<str:token>/answer/", views.save_answer, name="participant_answer"),
    path("p/<str:token>/events/", views.log_events, name="participant_events"),
    path(
        "p/<str:token>/<int:number>/signed/<slug:question>/",
        views.upload_signed_answer,
        name="participant_signed_answer",
    ),
    path("p/<str:token>/language/", views.set_language, name="participant_language"),
    path("p/<str:token>/done/", views.done, name="participant_done"),
    path("p/<str:token>/withdraw/", views.withdraw, name="participant_withdraw"),
    path(
        "p/<str:token>/answers/<int:response>/video/",
        views.participant_answer_video,
        name="participant_answer_video",
    ),
    path("jsi18n/<str:language>/", views.javascript_catalog, name="javascript_catalog"),
    path("private/<path:path>", views.private_media, name="private_media"),
    path("clips/<path:path>", views.uploaded_clip, name="uploaded_clip"),
    # Browsers ask for /favicon.ico on pages that name no icon (e.g. file downloads).
    path("favicon.ico", views.favicon),
]

handler400 = "studyplatform.views.errors.bad_request"
handler403 = "studyplatform.views.errors.permission_denied"
handler404 = "studyplatform.views.errors.page_not_found"
handler500 = "studyplatform.views.errors.server_error"

if settings.SIGNSTUDY_SERVE_MEDIA:
    urlpatterns += [
        re_path(rf"^{settings.MEDIA_URL.lstrip('/')}(?P<path>.*)$", views.media, name="media")
    ]
