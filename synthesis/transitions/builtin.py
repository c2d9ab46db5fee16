"""The built-in transition database: simulated captures, built once and kept on disk.

Used when a condition asks for data-driven transitions without naming a database. It is
built from the engine's simulated captures (:mod:`synthesis.transitions.simulate`), so
every description of a condition that uses it says so.
"""

from functools import cache
from pathlib import Path

import numpy as np

from synthesis.diskcache import cached
from synthesis.transitions.database import DatabaseError, TransitionDatabase, build_database
from synthesis.transitions.search import DescriptorSearch
from synthesis.transitions.simulate import simulated_captures

BUILT_IN = {"signers": 3, "sentences": 6, "seed": 0}
# The descriptor search data-driven conditions use: the seed's own distance, which won
# the leave-one-out evaluation on the simulated database (docs/transitions.md).
SEARCH_WEIGHTING = "raw"


def built_in_database() -> TransitionDatabase:
    """Return the built-in database (simulated captures), from the disk cache when kept."""

    def compute() -> TransitionDatabase:
        return build_database(simulated_captures(**BUILT_IN))

    def encode(database: TransitionDatabase) -> dict[str, np.ndarray]:
        return {"json": np.frombuffer(database.to_json().encode(), np.uint8)}

    def decode(arrays: dict[str, np.ndarray]) -> TransitionDatabase:
        return TransitionDatabase.from_json(arrays["json"].tobytes().decode())

    key = "transitions-{signers}x{sentences}-{seed}".format(**BUILT_IN)
    return cached(key, ("numpy", "scipy"), compute, encode, decode)


def database_search(path: str = "") -> DescriptorSearch:
    """Return the search over the database at *path* (the built-in one when empty).

    Kept per process and file version: a worker that renders many clips reads the file
    once, and again when it changes.
    """
    try:
        version = Path(path).stat().st_mtime_ns if path else 0
    except OSError as error:
        raise DatabaseError(f"{path}: cannot be read ({error}).") from None
    return _search(path, version)


@cache
def _search(path: str, version: int) -> DescriptorSearch:
    database = TransitionDatabase.read(path) if path else built_in_database()
    return DescriptorSearch(database, SEARCH_WEIGHTING)
