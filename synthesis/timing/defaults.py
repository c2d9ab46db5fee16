"""The Variable model that ships with the platform, built from published statistics.

No fingerspelling recordings ship with the project, so the default model is trained on
holds and a transition line *derived from seed 000's published figures* (spec 02), and
says so in its metadata. Researchers replace it with a model trained on their own
recordings (``python -m synthesis.timing train``).

How the figures become training data (assumptions marked):
- Vocabulary: the words of seed 000 App. B (3-, 4- and 5+-letter lists), each spelled
  twice, plus the study words DAVID, MICHAEL, VICTOR.
- Hold means and σ by word length at normal speed (Table 4.1): 3 letters 100 ms (30),
  4 letters 90 ms (20), 5+ letters 80 ms (10). The last letter is held 1.5 times as long
  as the others (Fig. 4.3 shows "significantly" longer, without a number: assumption),
  keeping the word's mean hold at the table's value.
- Words with a double letter are spelled 22 % faster (§4.1, normal speed).
- Transitions: mean 216.11 ms and r = 0.44 with RMSD (§4.2.2); the spread of recorded
  transitions is taken as σ = 60 ms (their range 83–392 ms spans about five σ:
  assumption); slope = r·σ_t / σ_d and intercept = mean_t − slope·mean_d, with the
  distances d measured between this project's letter poses over the vocabulary.
"""

import itertools
from functools import cache

import numpy as np

from synthesis.timing.bayes import CLASS_STEP_MS, N_CLASSES, HoldClassifier
from synthesis.timing.features import word_features
from synthesis.timing.transitions import (
    PUBLISHED_RMSD_ERROR_MS,
    PUBLISHED_TRANSITION_R,
    TransitionModel,
    letter_distance,
)
from synthesis.timing.variable import VariableModel

VOCABULARY = (
    *("THE", "HER", "HIM", "BAT", "CAB", "ALL", "BUT", "NOT", "CAN", "OLD", "WHO", "MAN", "NEW"),
    *("SINK", "BELL", "DOOR", "WANT", "AQUA", "ENDS", "GRIP", "VAIN", "THIN", "ROTS", "ROMP"),
    *("PUNT", "PORT", "FAST", "TEAM", "VEIN"),
    *("HEAVEN", "GUITAR", "HOODIE", "ELEPHANT", "CRYPTOGRAPHY", "PSYCHIATRY", "ALUMNUS"),
    *("PEDANTIC", "ARREST", "POTATO", "MOVIE", "DAVID", "MICHAEL", "VICTOR"),
)
HOLD_MS_BY_LENGTH = {3: (100.0, 30.0), 4: (90.0, 20.0), 5: (80.0, 10.0)}
LAST_LETTER_FACTOR = 1.5
DOUBLE_LETTER_SPEEDUP = 0.22
TRANSITION_MEAN_MS = 216.11
TRANSITION_SD_MS = 60.0
TRANSITION_R = PUBLISHED_TRANSITION_R["rmsd"]
SEED = 2016
# What the default model's training holds are, in every output that names them.
SIMULATED_HOLDS = "holds simulated from seed 000 Table 4.1's means and spreads"
SOURCE = (
    "built from published statistics (Wheatland 2016, seed 000 Table 4.1, §4.1, §4.2.2) "
    "with the assumptions listed in synthesis/timing/defaults.py; not trained on recordings"
)


def has_double(word: str) -> bool:
    """Return True when *word* has the same letter twice in a row."""
    return any(a == b for a, b in itertools.pairwise(word))


def published_holds(rng: np.random.Generator) -> list[tuple[dict[str, str], float]]:
    """Return synthetic (features, hold_ms) samples that follow the published statistics."""
    samples = []
    for repeat in range(2):
        for word in VOCABULARY:
            if repeat and word in ("DAVID", "MICHAEL", "VICTOR"):
                continue
            n = len(word)
            mean, sd = HOLD_MS_BY_LENGTH[min(n, 5)]
            # The others' mean such that, with a longer last letter, the word's mean is the table's.
            others = mean * n / (n - 1 + LAST_LETTER_FACTOR)
            speed = 1.0 - DOUBLE_LETTER_SPEEDUP if has_double(word) else 1.0
            for k, values in enumerate(word_features(word)):
                centre = others * (LAST_LETTER_FACTOR if k == n - 1 else 1.0) * speed
                hold = rng.normal(centre, sd)
                samples.append(
                    (values, float(np.clip(hold, CLASS_STEP_MS, N_CLASSES * CLASS_STEP_MS)))
                )
    return samples


def model_holds() -> list[tuple[dict[str, str], float]]:
    """Return the default model's training holds (:func:`published_holds`, seed :data:`SEED`)."""
    return published_holds(np.random.default_rng(SEED))


def published_transitions() -> TransitionModel:
    """Return the transition line implied by the published mean, spread and correlation."""
    pairs = {(a, b) for word in VOCABULARY for a, b in itertools.pairwise(word)}
    distances = np.array([letter_distance(a, b) for a, b in sorted(pairs)])
    slope = TRANSITION_R * TRANSITION_SD_MS / distances.std()
    intercept = TRANSITION_MEAN_MS - slope * distances.mean()
    return TransitionModel(
        float(intercept), float(slope), "rmsd", TRANSITION_R, PUBLISHED_RMSD_ERROR_MS, len(pairs)
    )


@cache
def published_model() -> VariableModel:
    """Return the default Variable model (built once per process)."""
    samples = model_holds()
    classifier = HoldClassifier.fit(samples)
    return VariableModel(
        classifier,
        published_transitions(),
        {
            "name": "published-statistics",
            "source": SOURCE,
            "training": f"{len(samples)} {SIMULATED_HOLDS}, not recordings",
            "simulated": True,
            "training_holds": len(samples),
            "leave_one_out": classifier.leave_one_out(samples).to_dict(),
            "seed": SEED,
            "note": "transition r and mean error are the published values, not refitted",
        },
    )
