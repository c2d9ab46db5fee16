"""Reads the platform's views, admin and actions share: pure queries and derivations.

Writes live in :mod:`studyplatform.actions`; nothing here changes the database.
"""
