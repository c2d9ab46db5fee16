"""Turn a study design into the set of clips to render (pairs, counterbalancing, caching).

Depends on :mod:`synthesis` only; never on Django or :mod:`studyplatform`.
"""

from stimuli.design import balanced_pair_assignment

__all__ = ["balanced_pair_assignment"]
