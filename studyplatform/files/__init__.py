"""Keep and check the files the platform stores: what a file is, where it lives, how it is
served, and the withdrawal ledger kept beside the database.

Below the models (their file fields use :mod:`.storage`); nothing here queries the database.
"""
