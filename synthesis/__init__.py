"""The animation engine: skeletons, BVH, kinematics, the ASL hand alphabet, timing, rendering.

Pure numpy/scipy code; never imports Django, :mod:`studyplatform`, :mod:`stimuli` or
:mod:`analysis`.
"""

__all__: list[str] = []
