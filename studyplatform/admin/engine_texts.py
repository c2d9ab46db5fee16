"""The engine's texts the researcher's pages show, marked for the catalogues.

Written by ``manage.py write_engine_texts`` from the engine's registries
(studyplatform/lib/engine_texts.py); do not edit it by hand.
"""

from django.utils.translation import gettext_noop

TEXTS = (
    gettext_noop("Source"),
    gettext_noop(
        "What the conditions animate: the engine's alphabet spelled with the timing, a "
        "simulated capture (timing sampled from the Variable model plus capture noise; "
        "labelled simulated), or a recording that every timing retimes."
    ),
    gettext_noop("the engine's alphabet"),
    gettext_noop("a simulated capture"),
    gettext_noop("a recording"),
    gettext_noop("Recording"),
    gettext_noop("A BVH or .pose recording of the word (source 'recording')."),
    gettext_noop("Alphabet"),
    gettext_noop("The manual alphabet the word is spelled in (a study sets it for all its words)."),
    gettext_noop("ASL (American Sign Language)"),
    gettext_noop("Libras (Língua Brasileira de Sinais)"),
    gettext_noop("Timing"),
    gettext_noop("How long each letter is held and each transition takes."),
    gettext_noop("Motion capture (the performance as performed)"),
    gettext_noop("Variable (naïve Bayes holds, pose-distance transitions)"),
    gettext_noop("Constant"),
    gettext_noop("Normalized constant (Constant scaled to the Variable model's length)"),
    gettext_noop("simple (equal holds)"),
    gettext_noop("Hold ms"),
    gettext_noop("Constant and Normalized: each letter's hold but the last."),
    gettext_noop("ms"),
    gettext_noop("Last hold ms"),
    gettext_noop("Constant and Normalized: the last letter's hold."),
    gettext_noop("Transition ms"),
    gettext_noop("Constant and Normalized: each transition."),
    gettext_noop("Model"),
    gettext_noop(
        "A trained Variable model (JSON; python -m synthesis.timing train); empty: the one "
        "built from published statistics."
    ),
    gettext_noop("Timing file"),
    gettext_noop("A word timing saved as JSON, used instead."),
    gettext_noop("Library"),
    gettext_noop(
        "A sign library (YAML) to use instead of the one shipped (synthesis/data/signs.yaml)."
    ),
    gettext_noop(
        "How long each transition between signs lasts; 0: the library's own. Seed 001's "
        "captured transitions lasted 540 ms on average."
    ),
    gettext_noop("Lexicon"),
    gettext_noop(
        "A lexicon of recorded signs (python -m synthesis.transitions lexicon): every gloss "
        "is played as recorded, joined by the transition technique. Liveliness noise is not "
        "added to recordings."
    ),
    gettext_noop("Spine"),
    gettext_noop(
        "Seed 003's automated spine bend and twist and clavicle motion, with staggered "
        "onsets; off leaves them out and changes nothing else that is signed."
    ),
    gettext_noop("Spine formula"),
    gettext_noop(
        "seed (the default): §3.1's bend c0·smoothstep(|V_reach|/L_arm) and one-way twist as "
        "printed (it bends the torso about 11° with the hands in front of the chest and 15° "
        "with the arms at rest; hands placed on the body go with it); comfort: SignStudy's "
        "variant, bending only for the horizontal reach beyond a 0.25 m comfort radius and "
        "twisting both ways (a departure from seed 003, named in every condition's "
        "description)."
    ),
    gettext_noop("seed 003 as printed"),
    gettext_noop("comfort-radius variant (SignStudy's, not the seed's)"),
    gettext_noop("Spine bend deg"),
    gettext_noop(
        "Seed 003's c0, the largest torso bend toward the hands' reach, in degrees (the seed "
        "prints no value; the default is this project's)."
    ),
    gettext_noop("°"),
    gettext_noop("Spine twist deg"),
    gettext_noop(
        "Seed 003's c1, the largest torso twist, in degrees (the seed prints no value; the "
        "default is this project's)."
    ),
    gettext_noop("Clavicle raise deg"),
    gettext_noop(
        "Seed 003's c2, the largest shoulder raise, in degrees (the seed prints no value; the "
        "default is this project's)."
    ),
    gettext_noop("Clavicle forward deg"),
    gettext_noop(
        "Seed 003's c3, the largest shoulder forward, in degrees (the seed prints no value; "
        "the default is this project's)."
    ),
    gettext_noop("Spine twist weight x"),
    gettext_noop(
        "Seed 003's X_w, the twist's weight on the hands' lateral reach (V_w = ⟨X_w, Y_w, 0⟩; "
        "the seed prints no value)."
    ),
    gettext_noop("Spine twist weight y"),
    gettext_noop(
        "Seed 003's Y_w, the twist's weight on the hands' one-sided forward reach (V_w = "
        "⟨X_w, Y_w, 0⟩; the seed prints no value)."
    ),
    gettext_noop("Face"),
    gettext_noop(
        "on: the sentence's non-manual signals (brows, eyes, mouth, head shakes and nods over "
        "the glosses they mark), blinks at phrase boundaries and gaze leading the head; "
        "neutral: blinks and gaze only, an expressionless face; off: a still face. Changes "
        "only the face's channels and the head's non-manual movements."
    ),
    gettext_noop("non-manual signals"),
    gettext_noop("neutral face"),
    gettext_noop("still face"),
    gettext_noop("Liveliness"),
    gettext_noop(
        "Small, slow noise on every joint (smaller and faster distally, larger on the weak "
        "side), seeded per item."
    ),
    gettext_noop("Transition"),
    gettext_noop(
        "How the arms move from one sign to the next; the signs themselves stay as they are "
        "(except blended, which makes each sign from rest and back and overlaps them)."
    ),
    gettext_noop("keyed (the engine's monotone cubics between keys)"),
    gettext_noop("linear (seed 001 baseline)"),
    gettext_noop("simple Hermite (seed 001 baseline)"),
    gettext_noop("data-driven Hermite (seed 001)"),
    gettext_noop("data-driven B-spline (seed 001)"),
    gettext_noop("concatenated with linear blending (seed 004)"),
    gettext_noop("Blend overlap ms"),
    gettext_noop(
        "Blended only: how long each sign's decay overlaps the next one's attack. 0: the "
        "shortest attack or decay of the sentence's signs, so no blend reaches a sign's keys "
        "(longer attacks then play partly unblended); 1000: seed 004's fixed 1 s. Applies to "
        "synthesized signs and recorded lexicons alike; a sign or recording shorter than "
        "twice the overlap is refused, by name."
    ),
    gettext_noop("Transition db"),
    gettext_noop(
        "A transition database (python -m synthesis.transitions build); empty: the built-in "
        "one, built from simulated captures."
    ),
    gettext_noop("Hand"),
    gettext_noop(
        "full: every DOF of the hand; reduced: the curves seed 002 finds irrelevant or "
        "redundant in this clip's motion are fixed or rebuilt from others; reconstructed: the "
        "digits rebuilt from a few of their markers (seed 000)."
    ),
    gettext_noop("full hand"),
    gettext_noop("reduced DOFs (seed 002)"),
    gettext_noop("reconstructed from sparse markers (seed 000 ch. 3)"),
    gettext_noop("Hand range deg"),
    gettext_noop("Reduced: a curve moving less than this becomes its mean (seed 002: 1 or 5)."),
    gettext_noop("deg"),
    gettext_noop("Hand rmsd"),
    gettext_noop(
        "Reduced: curves closer than this (standardised RMS deviation, either sign) are "
        "related (seed 002: 0.3 or 0.5)."
    ),
    gettext_noop("Hand markers"),
    gettext_noop(
        "Reconstructed: how many markers are kept (the most influential by PCA; seed 000 used "
        "3 and 6)."
    ),
    gettext_noop("Hand method"),
    gettext_noop(
        "Reconstructed: locally weighted regression to principal components (seed 000 §3.2) "
        "or the nearest of 1,000 k-means poses (§3.1)."
    ),
    gettext_noop("locally weighted regression"),
    gettext_noop("nearest k-means pose"),
    gettext_noop("Hand database"),
    gettext_noop(
        "Reconstructed: a pose database (python -m synthesis.hands database: recordings, "
        "words, simulated captures); empty: the engine's alphabet."
    ),
    gettext_noop("Avatar"),
    gettext_noop(
        "human: a realistic signer built from MakeHuman's CC0 body (face with ARKit "
        "expressions, eyes, brows, hair, a long-sleeved top); simple: the engine's first "
        "avatar, meshed from round cones (studies made with it keep its look)."
    ),
    gettext_noop("human signer"),
    gettext_noop("simple avatar"),
    gettext_noop("Body"),
    gettext_noop(
        "The human signer's body, a MakeHuman preset (gender, age, build): neutral, woman, "
        "man, older woman, older man; or custom, shaped by the macro values below."
    ),
    gettext_noop("neutral"),
    gettext_noop("woman"),
    gettext_noop("man"),
    gettext_noop("older woman"),
    gettext_noop("older man"),
    gettext_noop("custom"),
    gettext_noop("Skin tone"),
    gettext_noop("The human signer's skin tone; the top's colour stands apart from it."),
    gettext_noop("light"),
    gettext_noop("medium"),
    gettext_noop("dark"),
    gettext_noop("Body gender"),
    gettext_noop(
        "0 female … 1 male (a custom body only; MakeHuman's macro value, 0.5 its default)."
    ),
    gettext_noop("Body age"),
    gettext_noop(
        "0.5 is 25 years, 1 is 90 (a custom body only; MakeHuman's macro value, 0.5 its default)."
    ),
    gettext_noop("Body muscle"),
    gettext_noop(
        "0 least … 1 most muscular (a custom body only; MakeHuman's macro value, 0.5 its default)."
    ),
    gettext_noop("Body weight"),
    gettext_noop(
        "0 lightest … 1 heaviest build (a custom body only; MakeHuman's macro value, 0.5 its "
        "default)."
    ),
    gettext_noop("Body height"),
    gettext_noop(
        "0 shortest … 1 tallest (the rig keeps its size: proportions change) (a custom body "
        "only; MakeHuman's macro value, 0.5 its default)."
    ),
    gettext_noop("Body proportions"),
    gettext_noop(
        "0 uncommon … 1 idealised proportions (a custom body only; MakeHuman's macro value, "
        "0.5 its default)."
    ),
    gettext_noop("Avatar file"),
    gettext_noop(
        "A humanoid glTF 2.0 or VRM avatar (.glb/.vrm) that films the clip instead of the "
        "built-in signers: its bones are mapped to the engine's and the motion retargeted "
        "onto them, its ARKit morph targets or VRM expressions play the face. Its SHA-256 is "
        "part of the clip's hash."
    ),
    gettext_noop("View"),
    gettext_noop("Camera and avatar: the hand close-up or the upper body."),
    gettext_noop("hand close-up"),
    gettext_noop("upper body"),
    gettext_noop("Side"),
    gettext_noop("The signer's dominant hand."),
    gettext_noop("right"),
    gettext_noop("left"),
    gettext_noop("Width"),
    gettext_noop("Clip width."),
    gettext_noop("px"),
    gettext_noop("Height"),
    gettext_noop("Clip height."),
    gettext_noop("Rate hz"),
    gettext_noop("Frame rate."),
    gettext_noop("Hz"),
    gettext_noop("Seed"),
    gettext_noop("Seed of the item's performance and noise (shared by its conditions)."),
    gettext_noop("Performance"),
    gettext_noop("Timing model"),
    gettext_noop("Sign library"),
    gettext_noop("Automated spine motion"),
    gettext_noop("Liveliness noise"),
    gettext_noop("Inter-sign transitions"),
    gettext_noop("Hand DOFs"),
    gettext_noop("All ordered pairs: every item with every pair of conditions, both orders"),
    gettext_noop(
        "Balanced assignment: every item meets every pair once, each order on half the items "
        "(seed 000 §5.3; needs an even number of items)"
    ),
    gettext_noop("Single-clip ratings: every item in every condition"),
    gettext_noop(
        "Latin-square rotation: single-clip ratings, each item once per participant, its "
        "condition rotated across participants"
    ),
)
