"""Draw the alphabet's MediaPipe landmarks as stick figures: front and side view per letter.

    .venv/bin/python scripts/handshape_sheet.py docs/img/alphabet-landmarks.png [LETTERS]

A check of the handshape data (synthesis/data/alphabets/asl.yaml) without rendering.
"""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from synthesis.fingerspelling.alphabet import LETTERS, alphabet
from synthesis.plotting import pyplot
from synthesis.rigs.hand import HandModel
from synthesis.rigs.landmarks import landmarks

CHAINS = {
    "thumb": (0, 1, 2, 3, 4),
    "index": (0, 5, 6, 7, 8),
    "middle": (9, 10, 11, 12),
    "ring": (13, 14, 15, 16),
    "pinky": (0, 17, 18, 19, 20),
    "palm": (5, 9, 13, 17),
}
COLOURS = {
    "thumb": "#d62728",
    "index": "#1f77b4",
    "middle": "#2ca02c",
    "ring": "#9467bd",
    "pinky": "#ff7f0e",
    "palm": "#777777",
}


def main() -> None:
    out = Path(sys.argv[1] if len(sys.argv) > 1 else "docs/img/alphabet-landmarks.png")
    letters = sys.argv[2] if len(sys.argv) > 2 else "".join(LETTERS)
    model = HandModel("right")
    table = alphabet("right")
    columns = 6 if len(letters) > 8 else min(3, len(letters))
    rows = -(-len(letters) // columns)
    plt = pyplot()
    figure, axes = plt.subplots(rows, columns * 2, figsize=(columns * 3.2, rows * 2.0))
    for k, letter in enumerate(letters):
        points = landmarks(model, table[letter].dofs_rad)
        front, side = axes.flat[2 * k], axes.flat[2 * k + 1]
        for name, chain in CHAINS.items():
            front.plot(
                points[list(chain), 0],
                -points[list(chain), 1],
                "-o",
                ms=2,
                lw=1.5,
                color=COLOURS[name],
            )
            side.plot(
                points[list(chain), 2],
                -points[list(chain), 1],
                "-o",
                ms=2,
                lw=1.5,
                color=COLOURS[name],
            )
        front.set_title(f"{letter} front", fontsize=9)
        side.set_title(f"{letter} side (camera left)", fontsize=7)
        for axis in (front, side):
            axis.set_xlim(-0.13, 0.13)
            axis.set_ylim(-0.13, 0.13)
            axis.set_aspect("equal")
            axis.set_xticks([])
            axis.set_yticks([])
    for axis in axes.flat[2 * len(letters) :]:
        axis.axis("off")
    figure.tight_layout()
    figure.savefig(out, dpi=110)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
