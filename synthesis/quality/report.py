"""Check a clip's motion before anyone sees it: what was measured and what is wrong.

:func:`check_motion` runs every check on one motion against its keyed reference and
returns a :class:`ClipQuality`: the figures (peak speeds, hand sizes, depths, the face's
hidden share) and a :class:`Finding` for each limit crossed. The limits, and why each is
where it is:

- **speed**: a joint turning faster than :data:`SPEED_FACTOR` × its keyed peak. Issue
  53's fling reached 7.1 ×, and a joint at twice its keyed speed is caught. On the
  demo studies one built-in technique crosses it (measured): the data-driven Hermite
  join's elbow on P1 (3.0 ×; the stored human curve overshoots by 18°). The spine off
  is judged against the keyed motion with the spine off (:mod:`synthesis.quality.clip`).
- **frame**: any hand skin outside the frame in any frame, through a side or the top. A
  hand out through the bottom edge alone is lowered below the signing space, which the
  signing view's frame ends at (:mod:`synthesis.quality.visibility`): counted, not a
  finding.
- **size**: the dominant hand's box under :data:`HAND_MIN_PX` pixels (its 5th
  percentile over the clip, so a hand seen edge-on for a frame does not count): issue 52
  found fist letters at about 21 × 32 px that could not be told apart.
- **contact**: a hand's skin more than :data:`PENETRATION_M` inside the body's, a
  finger's thickness (a touch presses the skin; more goes through it).
- **face**: a hand over more than :data:`FACE_HIDDEN_SHARE` of the face for longer
  than :data:`FACE_HIDDEN_S`: signs at the face cover it briefly, the grammar on it
  (brows, mouth) must stay readable.
- **check**: the check itself could not run on the clip (its error, named).
"""

from dataclasses import asdict, dataclass

import numpy as np

from synthesis.quality.contact import BodySurface, penetration_m
from synthesis.quality.speed import compare_speeds
from synthesis.quality.visibility import measure_visibility
from synthesis.skeleton.kinematics import Pose

SPEED_FACTOR = 1.9
HAND_MIN_PX = 56.0
PENETRATION_M = 0.02
FACE_HIDDEN_SHARE, FACE_HIDDEN_S = 0.5, 0.5
CHECKS = ("speed", "frame", "size", "contact", "face", "check")


@dataclass(frozen=True)
class Finding:
    """One limit a clip crosses: the check's name, what is wrong, and the first frame."""

    check: str
    message: str
    frame: int


@dataclass(frozen=True)
class ClipQuality:
    """A clip's checked figures and its findings (none: nothing to warn of)."""

    figures: dict
    findings: tuple[Finding, ...]

    @property
    def ok(self) -> bool:
        return not self.findings

    def to_dict(self) -> dict:
        return {"figures": self.figures, "findings": [asdict(f) for f in self.findings]}

    @classmethod
    def from_dict(cls, data: dict) -> "ClipQuality":
        return cls(dict(data["figures"]), tuple(Finding(**f) for f in data["findings"]))


def _at(frame: int, rate_hz: float) -> str:
    return f"{frame / rate_hz:.2f} s"


def _hand(side: str) -> str:
    return f"the {side} hand" if side else "the hand"


def _speed_findings(check, rate_hz: float) -> list[Finding]:
    ratios = check.ratios()
    return [
        Finding(
            "speed",
            f"{check.names[j]} turns at {check.peak_deg_s[j]:,.0f} °/s at "
            f"{_at(int(check.peak_frame[j]), rate_hz)}, {ratios[j]:.1f} × the keyed "
            f"motion's {check.reference_deg_s[j]:,.0f} °/s",
            int(check.peak_frame[j]),
        )
        for j in check.too_fast(SPEED_FACTOR)
    ]


def _longest_run(flags: np.ndarray) -> tuple[int, int]:
    """Return (start, length) of the longest run of True in *flags* ((0, 0) if none)."""
    best, start = (0, 0), None
    for k, flag in enumerate(np.append(flags, False)):
        if flag and start is None:
            start = k
        elif not flag and start is not None:
            best = max(best, (start, k - start), key=lambda run: run[1])
            start = None
    return best


def _frame_findings(view, rate_hz: float) -> list[Finding]:
    """Return a finding for each hand that leaves the frame."""
    findings = []
    for k, side in enumerate(view.hands):
        out = np.flatnonzero(view.outside[:, k])
        if out.size:
            message = (
                f"{_hand(side)} leaves the frame in {out.size} frames, "
                f"first at {_at(out[0], rate_hz)}"
            )
            findings.append(Finding("frame", message, int(out[0])))
    return findings


def _contact_findings(sides, depth_m: np.ndarray, rate_hz: float) -> list[Finding]:
    """Return a finding for each hand whose skin goes deeper than the limit into the body."""
    findings = []
    for k, side in enumerate(sides):
        deepest = int(np.argmax(depth_m[:, k]))
        if depth_m[deepest, k] > PENETRATION_M:
            message = (
                f"{_hand(side)} goes {depth_m[deepest, k] * 100:.1f} cm into the body "
                f"at {_at(deepest, rate_hz)}"
            )
            findings.append(Finding("contact", message, deepest))
    return findings


def _size_findings(view, dominant: int) -> list[Finding]:
    """Return a finding when the dominant hand is too small to read (or not found)."""
    if not np.isfinite(view.hand_px).any():
        message = "no skin of the avatar's hands was found: hand size, frame and contact unchecked"
        return [Finding("size", message, 0)]
    small = float(np.percentile(view.hand_px[:, dominant], 5))
    if small >= HAND_MIN_PX:
        return []
    message = (
        f"{_hand(view.hands[dominant])} is {small:.0f} px at its smallest (5th percentile), "
        f"under {HAND_MIN_PX:.0f} px: handshapes are hard to tell apart; render it larger"
    )
    return [Finding("size", message, 0)]


def _face_findings(view, rate_hz: float) -> list[Finding]:
    """Return a finding when hands hide over half the face for too long."""
    if view.face_hidden is None:
        return []
    start, length = _longest_run(view.face_hidden > FACE_HIDDEN_SHARE)
    if length / rate_hz <= FACE_HIDDEN_S:
        return []
    message = (
        f"a hand hides over half the face for {length / rate_hz:.2f} s from {_at(start, rate_hz)}"
    )
    return [Finding("face", message, start)]


def _measured(value) -> float | None:
    """Return a figure rounded for the report, or None where nothing could be measured."""
    return round(float(value), 1) if np.isfinite(value) else None


def check_motion(
    avatar,
    camera,
    pose: Pose,
    reference: Pose,
    rate_hz: float,
    width: int,
    height: int,
    dominant: str = "right",
) -> ClipQuality:
    """Return the checks of *pose* (filmed by *camera* at *width* × *height*) against the
    keyed *reference* of the same item; *dominant* names the signing hand."""
    skeleton = avatar.rig.skeleton
    speeds = compare_speeds(pose, reference, skeleton.parents, skeleton.names, rate_hz)
    view = measure_visibility(avatar, camera, pose, width, height)
    depth = penetration_m(BodySurface.of(avatar), pose, view.hands)
    hand = view.hands.index(dominant) if dominant in view.hands else 0
    fastest = int(np.argmax(speeds.ratios()))
    figures = {
        "peak_joint": skeleton.names[fastest],
        "peak_deg_s": round(float(speeds.peak_deg_s[fastest]), 1),
        "keyed_peak_deg_s": round(float(speeds.reference_deg_s[fastest]), 1),
        "speed_ratio": round(float(speeds.ratios()[fastest]), 3),
        "hand_px_p5": _measured(np.percentile(view.hand_px[:, hand], 5)),
        "hand_px_median": _measured(np.median(view.hand_px[:, hand])),
        "frames_hand_outside": int(view.outside.any(axis=1).sum()),
        "frames_hand_lowered": int(view.lowered.any(axis=1).sum()),
        "penetration_cm": round(float(depth.max()) * 100, 2),
        "face_hidden_max": None
        if view.face_hidden is None
        else round(float(view.face_hidden.max()), 3),
        "n_frames": len(view.hand_px),
    }
    findings = [
        *_speed_findings(speeds, rate_hz),
        *_frame_findings(view, rate_hz),
        *_size_findings(view, hand),
        *_contact_findings(view.hands, depth, rate_hz),
        *_face_findings(view, rate_hz),
    ]
    return ClipQuality(
        figures, tuple(sorted(findings, key=lambda f: (CHECKS.index(f.check), f.frame)))
    )
