"""Offscreen rendering of a posed avatar with pyrender: DOF vectors in, RGB frames out."""

from collections.abc import Callable, Iterator
from pathlib import Path

import numpy as np

from synthesis.avatar.model import Avatar
from synthesis.render import pyrender_compat as compat
from synthesis.render.backend import import_pyrender
from synthesis.render.scene import (
    CameraPath,
    CameraPreset,
    Light,
    look_at,
    portrait_lighting,
    project_px,
)
from synthesis.skeleton.kinematics import Pose

BACKGROUND_RGB = (0.42, 0.47, 0.53)
# Each pixel's alpha holds its luma for the anti-aliasing pass: the skin shader's through
# its LUMA_WEIGHTS define (Renderer._defines), the background's through the clear colour.
LUMA_WEIGHTS = (0.299, 0.587, 0.114)
SHADERS = Path(__file__).with_name("shaders")
# The key light's shadow map: the hands' shadows on the torso stay sharp at 1024 px (a
# texel is about 2 mm over the scene), and pyrender's 2048 cost a tenth of a frame.
SHADOW_MAP_PX = 1024
# Frames deformed together: large enough to vectorise skinning, small enough to keep
# memory flat on long clips.
BATCH_FRAMES = 32

Progress = Callable[[int, int], None]


def _edge_attributes(part) -> dict:
    """Return a part's colour edge as pyrender texture coordinates: (distance, red) and
    (green, blue) of the colour across; none for a part without an edge."""
    if part.edge_m is None:
        return {}
    across = np.asarray(part.across_rgb, dtype=np.float32)
    edge = np.asarray(part.edge_m, dtype=np.float32)
    return {"texcoord_0": np.column_stack([edge, across[:, 0]]), "texcoord_1": across[:, 1:3]}


class Renderer:
    """Render an avatar through one camera; use as a context manager or call close().

    *camera* is one camera, or a :class:`~synthesis.render.scene.CameraPath` whose
    frame k films frame k of :meth:`frames`. *antialias* smooths edges with one FXAA
    pass (:mod:`synthesis.render.antialias`).
    """

    def __init__(
        self,
        avatar: Avatar,
        camera: CameraPreset | CameraPath,
        width: int = 640,
        height: int = 480,
        lights: tuple[Light, ...] | None = None,
        background_rgb=BACKGROUND_RGB,
        antialias: bool = True,
    ) -> None:
        if width <= 0 or height <= 0 or width % 2 or height % 2:
            raise ValueError(f"Frame size must be positive and even, not {width}×{height}.")
        pyrender = import_pyrender()
        compat.set_shadow_map_size(pyrender, SHADOW_MAP_PX)
        self._pyrender = pyrender
        self.avatar, self.width, self.height = avatar, width, height
        self._fixed_lights = lights
        self.path = camera if isinstance(camera, CameraPath) else None
        if self.path is not None:
            camera = self.path.at(0)
        luma = float(np.dot(background_rgb, LUMA_WEIGHTS))
        self.scene = pyrender.Scene(bg_color=(*background_rgb, luma), ambient_light=(0.0,) * 3)
        self._camera_node = self.scene.add(
            pyrender.PerspectiveCamera(
                yfov=np.radians(camera.yfov_deg), aspectRatio=width / height, znear=0.05
            )
        )
        self._light_nodes: list = []
        self.set_camera(camera)
        self._materials = [
            pyrender.MetallicRoughnessMaterial(
                baseColorFactor=(1.0, 1.0, 1.0, 1.0),
                metallicFactor=0.0,
                roughnessFactor=0.55 if part.name.endswith("nails") else 0.75,
            )
            for part in avatar.parts
        ]
        self._colors = [np.asarray(part.colors_rgb, dtype=np.float32) for part in avatar.parts]
        self._edges = [_edge_attributes(part) for part in avatar.parts]
        self._primitives: list = []
        self._mesh = None
        self._staging: list[np.ndarray] | None = None
        self._uploaded = True
        # Only a light that casts a shadow costs a shadow pass (and the shader's lookup).
        casts = any(light.casts_shadow for light in self.lights)
        self._flags = (
            pyrender.RenderFlags.SHADOWS_DIRECTIONAL if casts else pyrender.RenderFlags.NONE
        )
        self.antialias = antialias
        self._fxaa = None
        self._renderer = pyrender.OffscreenRenderer(width, height)
        # pyrender looks its shaders up by file name in its program cache; pointing the
        # cache at the project's own shaders swaps the PBR model for a much cheaper one
        # (private attributes of the pinned pyrender-maintained 1.0.1).
        compat.install_program_cache(pyrender, self._renderer, str(SHADERS), self._defines)

    def set_camera(self, camera: CameraPreset) -> None:
        """Move the camera (and, unless lights were given, the portrait lights with it)."""
        self.camera = camera
        self._camera_node.camera.yfov = np.radians(camera.yfov_deg)
        self.scene.set_pose(self._camera_node, camera.pose())
        target = np.asarray(camera.target_m)
        distance = float(np.linalg.norm(np.asarray(camera.eye_m) - target))
        lights = self._fixed_lights or portrait_lighting(target, distance)
        same = [(light.name, light.kind) for light in lights] == [
            (light.name, light.kind) for light in getattr(self, "lights", ())
        ]
        self.lights = lights
        if same:
            # The same lights elsewhere: move them, which keeps their shadow maps (a
            # moving camera moves its lights every frame).
            for node, light in zip(self._light_nodes, lights, strict=True):
                node.light.intensity, node.light.color = light.intensity, light.color_rgb
                self.scene.set_pose(node, look_at(np.asarray(light.position_m), target))
            return
        for node in self._light_nodes:
            self.scene.remove_node(node)
        self._light_nodes = []
        for light in self.lights:
            node = compat.ordered_node_class(self._pyrender)(
                order=len(self._light_nodes),
                light=self._light(light),
                matrix=look_at(np.asarray(light.position_m), target),
            )
            self.scene.add_node(node)
            self._light_nodes.append(node)

    def _defines(self) -> dict[str, int | str]:
        """Return the skin shader's defines: the scene's number of lights of each kind,
        and the luma weights it writes into each pixel's alpha (:data:`LUMA_WEIGHTS`).

        A constant count lets the shader's light loops unroll: llvmpipe indexed the
        light uniforms in loops bounded by a uniform count slowly, a sixth of the
        upper body's frame time (bench/bench_render.py).
        """
        kinds = [light.kind for light in self.lights]
        return {
            "LIGHT_COUNT_DIRECTIONAL": kinds.count("directional"),
            "LIGHT_COUNT_POINT": kinds.count("point"),
            "LUMA_WEIGHTS": f"vec3({', '.join(str(w) for w in LUMA_WEIGHTS)})",
        }

    def _light(self, light: Light):
        pyrender = self._pyrender
        if light.kind == "directional":
            return pyrender.DirectionalLight(
                color=light.color_rgb, intensity=light.intensity, name=light.name
            )
        if light.kind == "point":
            return pyrender.PointLight(
                color=light.color_rgb, intensity=light.intensity, name=light.name
            )
        raise ValueError(f"Unknown light kind {light.kind!r} for light {light.name!r}.")

    def __enter__(self) -> "Renderer":
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def close(self) -> None:
        """Release the OpenGL context."""
        if self._renderer is not None:
            # Frees the anti-aliasing pass with the context.
            compat.delete_offscreen(self._renderer)
            self._renderer = None
            self._fxaa = None

    def _show(self, meshes: list[tuple[np.ndarray, np.ndarray]]) -> None:
        """Put the avatar's parts in the scene with these vertices and normals.

        The first call builds the scene's mesh; later ones change its primitives' data
        in place, and :meth:`_draw` writes it into the vertex buffers pyrender made
        (building primitives and buffers for every frame cost about a tenth of an
        upper-body frame).
        """
        if self._primitives:
            for primitive, (vertices, normals) in zip(self._primitives, meshes, strict=True):
                primitive.positions = vertices  # also forgets the primitive's bounds
                primitive.normals = normals
            # The directional lights' shadow volume follows the scene's bounds, which
            # pyrender caches on the mesh and the scene.
            compat.forget_bounds(self._mesh, self.scene)
            self._uploaded = False
            return
        pyrender = self._pyrender
        self._primitives = [
            pyrender.Primitive(
                positions=vertices.astype(np.float32),
                normals=normals.astype(np.float32),
                indices=part.faces,
                color_0=colors,
                material=material,
                **edge,
            )
            for part, (vertices, normals), material, colors, edge in zip(
                self.avatar.parts,
                meshes,
                self._materials,
                self._colors,
                self._edges,
                strict=True,
            )
        ]
        # One mesh, so that the parts are drawn in list order: pyrender keeps a scene's
        # meshes in a set, and an order that changes from run to run would change the
        # pixels where two parts meet at equal depth (nails on fingertips).
        self._mesh = pyrender.Mesh(self._primitives)
        self.scene.add(self._mesh)
        casters = [
            primitive
            for primitive, part in zip(self._primitives, self.avatar.parts, strict=True)
            if part.casts_shadow
        ]
        if len(casters) < len(self._primitives):
            compat.cast_shadows_from(self._renderer, self._mesh, casters)
        self._uploaded = True  # pyrender uploads a new mesh itself

    def _upload(self) -> None:
        """Write the primitives' changed vertex data into their buffers (context current).

        pyrender's vertex buffer interleaves position (3), normal (3), texture
        coordinates (2 + 2, here a colour edge) and colour (4) floats per vertex for
        primitives like ours, without tangents; only positions and normals change.
        """
        if self._uploaded or compat.vertex_buffer(self._primitives[0]) is None:
            return
        from OpenGL import GL

        for primitive, interleaved in zip(self._primitives, self._interleaved(), strict=True):
            interleaved[:, 0:3] = primitive.positions
            interleaved[:, 3:6] = primitive.normals
            GL.glBindBuffer(GL.GL_ARRAY_BUFFER, compat.vertex_buffer(primitive))
            GL.glBufferSubData(GL.GL_ARRAY_BUFFER, 0, interleaved.nbytes, interleaved)
        GL.glBindBuffer(GL.GL_ARRAY_BUFFER, 0)
        self._uploaded = True

    def _interleaved(self) -> list[np.ndarray]:
        """Return one float32 array per primitive as its vertex buffer lays it out, the
        columns that never change filled in."""
        if self._staging is None:
            self._staging = []
            for primitive in self._primitives:
                if primitive.tangents is not None:
                    raise RuntimeError("In-place vertex updates expect no tangents.")
                fixed = [primitive.texcoord_0, primitive.texcoord_1, primitive.color_0]
                self._staging.append(
                    np.hstack(
                        [primitive.positions, primitive.normals]
                        + [c for c in fixed if c is not None]
                    ).astype(np.float32)
                )
        return self._staging

    def frame(self, dofs_rad: np.ndarray) -> np.ndarray:
        """Return one frame (height, width, 3) uint8 of the avatar in a pose."""
        meshes = self.avatar.deform(np.asarray(dofs_rad)[None])
        self._show([(v[0], n[0]) for v, n in meshes])
        return self._draw()

    def _draw(self) -> np.ndarray:
        """Draw the scene and read back its colours, (height, width, 3) uint8."""
        after_draw = self._antialias if self.antialias else None
        return compat.render_color(
            self._pyrender,
            self._renderer,
            self.scene,
            self._flags,
            self.width,
            self.height,
            before_draw=self._upload,
            after_draw=after_draw,
        )

    def _antialias(self) -> None:
        """Smooth the drawn frame's edges (context current)."""
        if self._fxaa is None:
            from synthesis.render.antialias import Fxaa

            self._fxaa = Fxaa()
        self._fxaa.apply(self.width, self.height, self._screen_box())

    def _screen_box(self) -> tuple[int, int, int, int] | None:
        """Return the avatar's box on screen (left, bottom, right, top), OpenGL's pixels.

        The projected corners of the posed mesh's bounding box, two pixels wider for the
        edge pixels just outside the silhouette; None (the whole frame) when a corner is
        behind the camera.
        """
        # The shown vertices are the primitives' (only an anti-aliased frame needs them).
        positions = [primitive.positions for primitive in self._primitives]
        extent = np.array(
            [
                np.min([p.min(axis=0) for p in positions], axis=0),
                np.max([p.max(axis=0) for p in positions], axis=0),
            ]
        )
        corners = extent[np.indices((2, 2, 2)).reshape(3, -1).T, [0, 1, 2]]
        pixels = project_px(self.camera, corners, self.width, self.height)
        if np.isnan(pixels).any():
            return None
        pad = 2
        left = int(np.clip(np.floor(pixels[:, 0].min()) - pad, 0, self.width))
        right = int(np.clip(np.ceil(pixels[:, 0].max()) + pad, 0, self.width))
        top = int(np.clip(self.height - np.floor(pixels[:, 1].min()) + pad, 0, self.height))
        bottom = int(np.clip(self.height - np.ceil(pixels[:, 1].max()) - pad, 0, self.height))
        return left, bottom, right, top

    def frames(
        self, motion: np.ndarray | Pose, progress: Progress | None = None
    ) -> Iterator[np.ndarray]:
        """Yield one frame per frame of *motion*, reporting (done, total) to *progress*.

        *motion* is DOF vectors (n_frames, n_dofs) of the avatar's rig, or a
        :class:`~synthesis.skeleton.kinematics.Pose` of its skeleton (n_frames, n_joints, …).
        """
        if isinstance(motion, Pose):
            total = motion.quaternions.shape[0]

            def deform(start: int, stop: int):
                part = Pose(motion.quaternions[start:stop], motion.positions_m[start:stop])
                return self.avatar.deform_pose(part)
        else:
            motion = np.atleast_2d(motion)
            total = len(motion)

            def deform(start: int, stop: int):
                return self.avatar.deform(motion[start:stop])

        if self.path is not None and len(self.path) != total:
            raise ValueError(f"The camera path has {len(self.path)} frames, the motion {total}.")
        for start in range(0, total, BATCH_FRAMES):
            batch = deform(start, start + BATCH_FRAMES)
            for k in range(len(batch[0][0])):
                if self.path is not None:
                    self.set_camera(self.path.at(start + k))
                self._show([(v[k], n[k]) for v, n in batch])
                yield self._draw()
                if progress is not None:
                    progress(start + k + 1, total)
