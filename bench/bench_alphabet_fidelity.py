"""Score our alphabet's handshapes against real signers' (the benchmark of issue 16).

    .venv/bin/python bench/bench_alphabet_fidelity.py

The human letters are spoken-to-signed's ASL lexicon (a test dependency, read where the
package installed it). Each of our letters is seen as the human recording of the same
letter sees its hand (turned by the hand's fitted orientation, projected to the image
plane) and taken for the nearest human letter by orientation-free features
(synthesis.capture.fidelity). Prints each letter and what it is taken for, the score
(look-alikes G/Q, K/P, H/U, I/J as one; target of issue 16: at least 20 of 26, at most
two fist letters taken for another), the confusion table, and the same score for the
human letters fitted onto our hand (what our hand model can show at best).
"""

import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from synthesis.capture import read_pose
from synthesis.capture.fidelity import score_handshapes, seen_as, view_of
from synthesis.capture.lexicon import human_letter_files
from synthesis.fingerspelling import letter_pose
from synthesis.rigs.hand import HandModel


def main() -> int:
    model = HandModel()
    started = time.perf_counter()
    views = {
        k: view_of(model, *read_pose(p).hand("right")) for k, p in human_letter_files().items()
    }
    fitted = {k: seen_as(model, v.dofs_rad, v) for k, v in views.items()}
    human = {letter: view.features for letter, view in views.items()}
    ours = score_handshapes({k: seen_as(model, letter_pose(k), v) for k, v in views.items()}, human)
    elapsed = time.perf_counter() - started
    print("our letters, each taken for the nearest human letter:")
    print("  " + "  ".join(f"{k}→{v}" for k, v in ours.taken.items()))
    print(ours.summary())
    print(
        "confusions (human letter: our letters taken for it): "
        + "; ".join(f"{k}: {''.join(v)}" for k, v in ours.confusions().items())
    )
    print("human letters fitted onto our hand: " + score_handshapes(fitted, human).summary())
    print(f"({elapsed:.1f} s for 26 recordings)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
