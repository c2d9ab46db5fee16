"""Delete media files once nothing points at them."""

from django.db import transaction

from studyplatform.lib.media import files_in_use


def delete_unused_files_on_commit(storage, names) -> None:
    """Delete those of *names* from *storage* that no row points at, once the
    transaction commits (checked then, so a row saved meanwhile keeps its file)."""
    names = {name for name in names if name}
    if not names:
        return

    def delete() -> None:
        for name in names - files_in_use(names):
            storage.delete(name)

    transaction.on_commit(delete)
