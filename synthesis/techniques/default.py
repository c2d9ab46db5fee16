"""The engine's own registry: its item kinds and techniques, in pipeline order.

Apart from :mod:`synthesis.techniques.registry` so that the plug-ins import the
registry's classes and the registry imports none of them back.
"""

from synthesis.techniques.registry import Registry


def default_registry() -> Registry:
    """Return the engine's item kinds and techniques, in pipeline order."""
    from synthesis.techniques import (
        avatar,
        face,
        hand,
        kinds,
        liveliness,
        signs,
        source,
        spine,
        timing,
        transition,
    )

    return Registry(
        kinds={kind.name: kind for kind in (kinds.WORD, kinds.SENTENCE, kinds.SIGN_PAIR)},
        techniques=[
            source.TECHNIQUE,
            timing.TECHNIQUE,
            signs.TECHNIQUE,
            spine.TECHNIQUE,
            face.TECHNIQUE,
            liveliness.TECHNIQUE,
            transition.TECHNIQUE,
            hand.TECHNIQUE,
            avatar.TECHNIQUE,
        ],
    )
