"""Test offscreen rendering: lights, cameras, determinism, left-handed signers, progress."""

import numpy as np
import pytest

from synthesis.avatar.hand_mesh import hand_avatar
from synthesis.fingerspelling.alphabet import letter_pose
from synthesis.render.renderer import BACKGROUND_RGB, Renderer
from synthesis.render.scene import hand_close_up, portrait_lighting, upper_body_front

pytestmark = pytest.mark.usefixtures("renderable")


def _foreground(frame: np.ndarray) -> np.ndarray:
    background = np.round(np.asarray(BACKGROUND_RGB) * 255)
    return np.abs(frame.astype(float) - background).sum(axis=-1) > 12


def test_portrait_lighting_has_four_lights_and_only_the_key_casts_shadows():
    lights = portrait_lighting((0, 0, 0), 1.0)
    assert [light.name for light in lights] == ["key", "fill", "rim", "extra fill"]
    assert [light.name for light in lights if light.casts_shadow] == ["key"]
    # The renderer shadows directional lights only, and the key is the only one.
    assert [light.kind for light in lights].count("directional") == 1
    rim = next(light for light in lights if light.name == "rim")
    assert rim.position_m[2] < 0  # behind the signer


def test_still_shows_the_hand_and_is_deterministic():
    avatar = hand_avatar("right")
    with Renderer(avatar, hand_close_up("right"), 160, 120) as renderer:
        first = renderer.frame(letter_pose("B"))
        second = renderer.frame(letter_pose("B"))
        fist = renderer.frame(letter_pose("A"))
    assert first.shape == (120, 160, 3) and first.dtype == np.uint8
    covered = _foreground(first).mean()
    assert 0.03 < covered < 0.6
    assert np.array_equal(first, second)
    assert _foreground(fist).sum() < _foreground(first).sum()  # a fist covers less than B


def test_shader_programs_are_compiled_once_per_renderer(monkeypatch):
    """Regression: pyrender's cache key changed with every OSMesa make-current, so each
    frame compiled its shaders again (and kept the old programs)."""
    from synthesis.render.backend import import_pyrender

    program = import_pyrender().shader_program.ShaderProgram
    compiled = []
    real = program._add_to_context

    def counting(self):
        compiled.append(self)
        return real(self)

    monkeypatch.setattr(program, "_add_to_context", counting)
    motion = np.stack([letter_pose(c) for c in "ABCDEF"])
    with Renderer(hand_avatar("right"), hand_close_up(), 64, 48) as renderer:
        first = list(renderer.frames(motion[:1]))
        after_one = len(compiled)
        rest = list(renderer.frames(motion))
    assert after_one > 0 and len(compiled) == after_one  # six more frames, no new programs
    assert np.array_equal(first[0], rest[0])


def test_lights_reach_the_shader_in_the_order_given():
    """Regression: pyrender numbers lights in its set's order, which followed memory
    addresses, so the shader summed them in a different order from run to run and the
    last bits of some pixels changed. Several renderers alive at once have their nodes at
    different addresses; each must still list its lights in the given order."""
    avatar = hand_avatar("right")
    renderers = [Renderer(avatar, hand_close_up(), 16, 12) for _ in range(6)]
    try:
        for renderer in renderers:
            lights = [node.light for node in renderer.scene.light_nodes]  # set order
            assert [light.name for light in lights] == [light.name for light in renderer.lights]
    finally:
        for renderer in renderers:
            renderer.close()


def _unshadowed(camera) -> tuple:
    """Return the portrait lights with no shadow (a renderer's choice)."""
    from dataclasses import replace

    target = np.asarray(camera.target_m)
    distance = float(np.linalg.norm(np.asarray(camera.eye_m) - target))
    return tuple(
        replace(light, casts_shadow=False) for light in portrait_lighting(target, distance)
    )


@pytest.mark.parametrize("shadowed", [True, False])
def test_only_parts_that_cast_shadows_are_drawn_into_the_shadow_map(monkeypatch, shadowed):
    """With the portrait's shadowed key, the nails (on the fingertips, which cast their
    shadow) are skipped by the shadow pass and the colour pass still draws every part;
    with lights that cast no shadow there is no shadow pass at all."""
    from synthesis.render.backend import import_pyrender

    inner_class = import_pyrender().renderer.Renderer
    drawn = []
    real = inner_class._bind_and_draw_primitive

    def recording(self, primitive, pose, program, flags):
        drawn.append((primitive, bool(flags & import_pyrender().RenderFlags.DEPTH_ONLY)))
        return real(self, primitive, pose, program, flags)

    monkeypatch.setattr(inner_class, "_bind_and_draw_primitive", recording)
    avatar = hand_avatar("right")
    assert [part.casts_shadow for part in avatar.parts] == [True, False]  # skin, nails
    lights = None if shadowed else _unshadowed(hand_close_up())
    with Renderer(avatar, hand_close_up(), 64, 48, lights=lights) as renderer:
        renderer.frame(letter_pose("B"))
        skin, nails = renderer._primitives
    assert [primitive for primitive, depth in drawn if depth] == ([skin] if shadowed else [])
    assert [primitive for primitive, depth in drawn if not depth] == [skin, nails]


def test_a_scene_without_a_directional_light_is_lit_by_its_point_lights():
    """The skin shader's light loops run to the scene's own counts (compile-time
    constants): none of a kind, and another count than the portrait's, must work."""
    from synthesis.render.scene import Light

    camera = hand_close_up()
    target = np.asarray(camera.target_m)
    near = Light("near", "point", tuple(target + np.array([0.0, 0.0, 0.3])), 0.2)
    more = Light("more", "point", tuple(target + np.array([0.3, 0.0, 0.3])), 0.2)
    frames = {}
    for name, lights in (("one", (near,)), ("two", (near, more))):
        with Renderer(hand_avatar("right"), camera, 96, 72, lights=lights) as renderer:
            frames[name] = renderer.frame(letter_pose("B")).astype(float)
    hand = _foreground(frames["one"])
    assert frames["one"][hand].mean() > 20  # lit, not black
    assert frames["two"][hand].mean() > frames["one"][hand].mean() + 5  # the second adds


def test_frames_after_the_first_equal_a_fresh_renderers():
    """Later frames rewrite the vertex buffers in place: each must equal the frame a new
    renderer draws from scratch for the same pose (shadows follow the moved bounds)."""
    poses = np.stack([letter_pose(c) for c in "AYB"])
    avatar = hand_avatar("right")
    with Renderer(avatar, hand_close_up(), 96, 72) as renderer:
        streamed = list(renderer.frames(poses))
    for pose, frame in zip(poses, streamed, strict=True):
        with Renderer(avatar, hand_close_up(), 96, 72) as fresh:
            assert np.array_equal(fresh.frame(pose), frame)
    assert not np.array_equal(streamed[0], streamed[1])


def test_left_handed_signer_is_the_mirror_image():
    masks = {}
    for side in ("right", "left"):
        with Renderer(hand_avatar(side), hand_close_up(side), 160, 120) as renderer:
            masks[side] = _foreground(renderer.frame(letter_pose("L", side)))
    mirrored = masks["right"][:, ::-1]
    overlap = (mirrored & masks["left"]).sum() / (mirrored | masks["left"]).sum()
    assert overlap > 0.9


def test_frames_report_progress_and_accept_poses():
    avatar = hand_avatar("right")
    motion = np.stack([letter_pose(c) for c in "ABC"])
    calls = []
    with Renderer(avatar, hand_close_up(), 64, 48) as renderer:
        from_dofs = list(renderer.frames(motion, progress=lambda d, t: calls.append((d, t))))
        from_pose = list(renderer.frames(avatar.rig.pose(motion)))
    assert calls == [(1, 3), (2, 3), (3, 3)]
    assert all(np.array_equal(a, b) for a, b in zip(from_dofs, from_pose, strict=True))


def test_upper_body_camera_frames_the_signer():
    from synthesis.avatar.body_mesh import body_avatar

    avatar = body_avatar("right")
    with Renderer(avatar, upper_body_front(), 160, 120) as renderer:
        mask = _foreground(renderer.frame(avatar.rig.neutral()))
    rows = np.flatnonzero(mask.any(axis=1))
    assert rows.min() < 20  # the head near the top
    assert mask[:, 60:100].mean() > 0.3  # the torso fills the middle


def test_the_cuff_is_a_straight_edge_through_the_meshs_triangles():
    """The sleeve ends in a smooth line across the forearm (within 2.5 px of an arc at
    this close-up's 4 px a millimetre, where the 20,000-triangle skin's facets turn the
    arc into a polygon; it used to follow the decimated mesh's triangle edges, a zigzag
    of about 10 px here)."""
    from synthesis.avatar.body_mesh import body_avatar
    from synthesis.render.scene import CameraPreset

    body = body_avatar("right")
    camera = CameraPreset("cuff", (-0.22, 0.97, 0.3), (-0.22, 0.97, 0.0), 30.0)
    with Renderer(body, camera, 640, 480) as renderer:
        frame = renderer.frame(np.zeros(len(body.rig.dofs))).astype(float)
    dark = frame.sum(axis=-1) < 200  # the top; skin and background are brighter
    skin = (frame[..., 0] - frame[..., 2]) > 40
    rows = []
    for column in range(frame.shape[1]):
        # Where the column passes from the sleeve straight onto skin.
        above = np.zeros_like(skin[:, column])
        for gap in range(1, 9):
            above[gap:] |= dark[:-gap, column]
        onto_skin = skin[:, column] & above
        if onto_skin.any() and skin[:, column].sum() > 100:
            rows.append((column, np.argmax(onto_skin)))
    assert len(rows) > 60, "the sleeve should end on skin across the forearm"
    # The middle of the forearm: at its sides the arc turns out of view.
    columns, first = np.array(rows[len(rows) // 10 : -len(rows) // 10]).T
    # Seen from a little above, the cuff round the forearm is an arc.
    arc = np.polyval(np.polyfit(columns, first, 2), columns)
    assert np.abs(first - arc).max() <= 2.5


def test_odd_frame_sizes_are_refused():
    with pytest.raises(ValueError, match="even"):
        Renderer(hand_avatar("right"), hand_close_up(), 161, 120)


def test_clips_are_byte_identical_across_runs_and_worker_counts(tmp_path):
    """Same inputs, same bytes (spec 01): in one process, or split over two (each worker
    filmed by its share of the close-up's camera path)."""
    from synthesis.fingerspelling.spelling import spell
    from synthesis.render.clip import render_clip
    from synthesis.render.follow import follow_hand

    avatar = hand_avatar("right")
    motion = spell("NAIL", rate_hz=30)
    assert len(motion) >= 48  # enough frames for two workers
    camera = follow_hand(avatar, motion, hand_close_up(), 30, 96, 72)
    paths = [tmp_path / f"clip{k}.mp4" for k in range(3)]
    for path, workers in zip(paths, (1, 1, 2), strict=True):
        render_clip(avatar, motion, camera, path, 30, width=96, height=72, workers=workers)
    first = paths[0].read_bytes()
    assert paths[1].read_bytes() == first
    assert paths[2].read_bytes() == first


def test_a_bad_platform_setting_is_named(monkeypatch):
    from synthesis.render.backend import RenderUnavailable, select_platform

    monkeypatch.setenv("PYOPENGL_PLATFORM", "glx")
    with pytest.raises(RenderUnavailable, match="PYOPENGL_PLATFORM='glx' cannot render"):
        select_platform()


def test_a_closed_renderer_collected_later_leaves_the_next_ones_framebuffers_alone():
    """Regression: pyrender's delete keeps its shadow framebuffer's name, and a renderer
    collected later (it sits in a reference cycle) deleted it again in the context that
    was current then: another renderer's framebuffer (GLError 1282 in its next frame).
    pyrender hid it with a full gc.collect() on every close; ours forgets the name."""
    import gc

    avatar, camera = hand_avatar("right"), hand_close_up()
    pose = letter_pose("B")
    first = Renderer(avatar, camera, 64, 48)
    first.frame(pose)
    inner = first._renderer._renderer
    first.close()
    with Renderer(avatar, camera, 64, 48) as second:
        before = second.frame(pose)
        platform = second._renderer._platform
        platform.make_current()
        del inner
        gc.collect()  # the first renderer's __del__, with the second's context current
        platform.make_uncurrent()
        assert np.array_equal(second.frame(pose), before)
