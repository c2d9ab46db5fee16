"""Draw a capture's contact sheet: video frames beside the hand fitted to them.

A researcher checks a capture at a glance: for a few frames spread over the video,
the frame as filmed (above) and the avatar's hand posed with the fitted DOFs (below,
the forearm and wrist at rest: the fit transfers the handshape, not the hand's place).
"""

from pathlib import Path

import numpy as np

from synthesis.capture.recording import CapturedHand

TILE_PX = 200
N_FRAMES = 8


def contact_frames(hand: CapturedHand, n: int = N_FRAMES) -> np.ndarray:
    """Return up to *n* frame numbers spread evenly over the frames the hand was found in."""
    found = np.flatnonzero(hand.fit.found)
    if not found.size:
        return found
    picks = np.linspace(0, len(found) - 1, min(n, len(found)))
    return found[np.unique(np.round(picks).astype(int))]


def contact_sheet_png(
    hand: CapturedHand, video: str | Path, n: int = N_FRAMES, tile_px: int = TILE_PX
) -> bytes:
    """Return the contact sheet of *hand* captured from *video*, as PNG bytes."""
    import io

    from PIL import Image, ImageDraw

    from synthesis.avatar.hand_mesh import hand_avatar
    from synthesis.capture.video import read_frames
    from synthesis.render.renderer import Renderer
    from synthesis.render.scene import hand_close_up

    picks = contact_frames(hand, n)
    wanted = set(int(k) for k in picks)
    filmed = {}
    _, frames = read_frames(video)
    for number, frame in enumerate(frames):
        if number in wanted:
            filmed[number] = frame
        if len(filmed) == len(wanted):
            break
    avatar, camera = hand_avatar(hand.side), hand_close_up(hand.side)
    sheet = Image.new("RGB", (max(1, len(picks)) * tile_px, 2 * tile_px), "white")
    draw = ImageDraw.Draw(sheet)
    with Renderer(avatar, camera, tile_px, tile_px) as renderer:
        for column, number in enumerate(picks):
            x = column * tile_px
            if number in filmed:
                shot = Image.fromarray(filmed[number])
                shot.thumbnail((tile_px, tile_px))
                sheet.paste(shot, (x + (tile_px - shot.width) // 2, (tile_px - shot.height) // 2))
            fitted = renderer.frame(np.asarray(hand.fit.dofs_rad[number]))
            sheet.paste(Image.fromarray(fitted), (x, tile_px))
            residual = float(np.median(hand.fit.residual_mm[number]))
            draw.text((x + 6, 4), f"frame {number}", fill="black")
            draw.text((x + 6, tile_px + 4), f"fit {residual:.1f} mm", fill="white")
    buffer = io.BytesIO()
    sheet.save(buffer, format="PNG", optimize=True)
    return buffer.getvalue()


def write_contact_sheet(hand: CapturedHand, video: str | Path, out: str | Path) -> Path:
    """Write the contact sheet PNG of *hand* captured from *video* to *out*; return it."""
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_bytes(contact_sheet_png(hand, video))
    return out
