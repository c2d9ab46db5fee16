"""Measure body capture: a rendered signer captured with Holistic and fitted back (issue 15).

Renders two sentences of the spine study's story (spine on, liveliness off, 480×360,
15 fps) whose body DOFs are known, captures each video with MediaPipe Holistic and fits
the upper body (synthesis.capture.armfit.fit_arms: trunk and head, then arms and
hands), and prints per sentence the elbows' and wrists' distance from the true ones
(median, mm), the trunk's turn against the true one (correlation, mean error in
degrees), then Holistic's throughput (video frames per second) and the fit's (frames
per second).

    .venv/bin/python bench/bench_body_capture.py
"""

import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import machine

from synthesis.capture.armfit import fit_arms
from synthesis.capture.video import capture_body
from synthesis.techniques import ClipRequest, build_motion, render_request

SENTENCES = (
    "INFORM-YOU BLUE MY FAVORITE COLOR.",
    "I LOST WHERE. I SEARCH, SEARCH, CAN'T FIND — SAD.",
)


PARAMETERS = {"rate_hz": 15.0, "spine": True, "liveliness": False, "width": 480, "height": 360}


def _summed(body, dofs: np.ndarray, part: str, motion: str) -> np.ndarray:
    columns = [i for i, n in enumerate(body.dof_names) if n.startswith(part) and n.endswith(motion)]
    return np.degrees(dofs[:, columns].sum(axis=1))


def main() -> int:
    print(machine.describe())
    capture_s = fit_s = frames = 0.0
    with tempfile.TemporaryDirectory() as directory:
        for number, text in enumerate(SENTENCES):
            request = ClipRequest.from_parameters("sentence", text, PARAMETERS)
            build = build_motion(request)
            path = Path(directory) / f"sentence{number}.mp4"
            render_request(request, path, build=build)
            started = time.perf_counter()
            recording = capture_body(path)
            capture_s += time.perf_counter() - started
            started = time.perf_counter()
            fit = fit_arms(build.rig, recording)
            fit_s += time.perf_counter() - started
            frames += recording.n_frames
            body, truth = build.rig, np.asarray(build.motion)
            n = min(len(truth), len(fit.dofs_rad))
            true_pose, fitted_pose = body.pose(truth[:n]), body.pose(fit.dofs_rad[:n])
            misses = []
            for joint in ("right_elbow", "right_wrist", "left_elbow", "left_wrist"):
                j = body.skeleton.index(joint)
                miss = np.linalg.norm(
                    fitted_pose.positions_m[:, j] - true_pose.positions_m[:, j], axis=1
                )
                misses.append(f"{joint.replace('_', ' ')} {np.median(miss) * 1000:.0f}")
            turn, fitted_turn = (
                _summed(body, d[:n], "spine", "rotation") for d in (truth, fit.dofs_rad)
            )
            print(f"  {text}")
            print(f"    {recording.n_frames} frames; median miss (mm): " + ", ".join(misses))
            print(
                f"    trunk turn: true range {np.ptp(turn):.0f}°, "
                f"fitted {np.ptp(fitted_turn):.0f}°, "
                f"correlation {np.corrcoef(turn, fitted_turn)[0, 1]:.2f}, "
                f"mean error {np.abs(turn - fitted_turn).mean():.1f}° "
                f"(left at rest: {np.abs(turn).mean():.1f}°)"
            )
    print(
        f"Holistic capture: {frames / capture_s:.1f} video frames/s; upper-body fit: "
        f"{frames / fit_s:.1f} frames/s ({frames:.0f} frames)"
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
