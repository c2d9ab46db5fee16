"""The five-sentence story of the spine study (spec 03 §5; seed 003 Fig. 13/14).

Glossed with its non-manual signals (synthesis.signing.nonmanual; the sign library adds
LITTLE's OO, SAD's and HAPPY's faces, SURPRISE's raised brows and BIG's CHA): the
childhood time clause as a topic, WHERE as a rhetorical question (raised brows in ASL),
a head shake over the negation, the colour as a topic and a nod asserting it.
"""

SPINE_STORY = (
    "[top LOOKING-BACK REMEMBER ME SMALL], HAVE LITTLE T-O-Y C-A-R.",
    "I LOST [rhq WHERE]. I SEARCH, SEARCH, [neg CAN'T FIND] — SAD.",
    "BUT SURPRISE — MY BROTHER GET NEW C-A-R, BIG, BLUE, GIVE-ME.",
    "INFORM-YOU [top BLUE] [assert MY FAVORITE COLOR].",
    "FINALLY HAVE C-A-R AGAIN — HAPPY!",
)
# The ASL-first demo's signed prompts (studyplatform/demo/signed.py attaches them to its
# texts), by the text they sign: signs from the library, fingerspelling for the rest.
DEMO_PROMPTS = {
    "consent": "[top S-T-O-R-Y LITTLE], ME INFORM-YOU. [q O-K]?",
    "clarity": "[whq C-L-E-A-R]?",
    "naturalness": "[whq N-A-T-U-R-A-L]?",
    "preferred": "[whq FAVORITE]?",
    "thank you": "[happy T-Y]!",
}
# Every sentence the demo signs in the signing view (the sign pairs aside).
DEMO_SENTENCES = (*SPINE_STORY, *DEMO_PROMPTS.values())
