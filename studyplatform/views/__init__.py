"""Participant-facing and public views of the platform."""

from studyplatform.views.home import favicon, home

__all__ = ["favicon", "home"]
