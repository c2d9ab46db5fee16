"""Write synthesis/data/letter_routes.json: the route of every letter-to-letter transition.

Run after changing the alphabet or the routes (about a minute):

    python scripts/letter_routes.py
"""

import json
import time
from pathlib import Path

from synthesis.fingerspelling.routes import compute_table

OUT = Path(__file__).resolve().parent.parent / "synthesis" / "data" / "letter_routes.json"


def main() -> None:
    """Choose every pair's route and write the table."""
    start = time.perf_counter()
    table = compute_table()
    OUT.write_text(json.dumps(table, indent=1, sort_keys=True) + "\n", encoding="utf-8")
    counts = {}
    for route in table["routes"].values():
        counts[route] = counts.get(route, 0) + 1
    print(f"wrote {OUT} ({len(table['routes'])} pairs in {time.perf_counter() - start:.0f} s)")
    for route, count in sorted(counts.items(), key=lambda item: -item[1]):
        print(f"  {route}: {count}")


if __name__ == "__main__":
    main()
