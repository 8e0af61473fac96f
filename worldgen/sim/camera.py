"""A pinhole camera drawn offscreen with OpenGL on the CPU: moderngl on a standalone EGL context, which Mesa's
llvmpipe provides headless (no GPU, no display).

**Geometry.** A camera sensor looks along its frame's +x with +z up, as Gazebo's do; the image is in the ROS
optical frame (z forward, x right, y down): ``optical = OPTICAL_FROM_SENSOR · sensor``. A point at optical
(X, Y, Z) lands at pixel ``u = fx·X/Z + cx``, ``v = fy·Y/Z + cy`` — exactly what the camera_info's K says, in
ROS's convention that pixel (u, v) has its centre at integer u, v. The projection matrix (:func:`gl_projection`)
is built from K itself, so the picture and the published K cannot disagree: Gazebo's plugin puts cx at
(width + 1)/2, half a pixel right of the image's middle (its own renderer keeps the axis in the middle, so
Gazebo's pictures sit one pixel off its own K; these do not). The framebuffer is drawn with image row 0 in its
first row, so reading it back needs no flip.

**Light.** Gazebo's default scene: ambient 0.4, and the sun (direction (−0.5, 0.1, −0.9), diffuse 0.8), so a
surface of colour c shows ``c · (0.4 + 0.8 · max(0, n·l))``, on whichever side of a face the camera is; the
background is Gazebo's default grey (0.7). Light is worked out at the corners (exact for flat faces, whose
corners all face alike; smooth enough on cylinders and spheres), which keeps llvmpipe's per-pixel work to a
colour and a depth test. No shadows, no specular, no anti-aliasing.

**Flat on the ground.** Ground planes are drawn pushed back a little in depth (``glPolygonOffset``), so that a
marking whose top is level with the floor shows whole instead of flickering with it.

The renderer knows nothing of scenes or sessions: :mod:`.camera_scene` hands it meshes and poses.
"""

from __future__ import annotations

import numpy as np

from ..core.errors import InputError

OPTICAL_FROM_SENSOR = np.array([[0.0, -1.0, 0.0], [0.0, 0.0, -1.0], [1.0, 0.0, 0.0]])
SUN_DIRECTION = (-0.5, 0.1, -0.9)       # Gazebo's default sun
AMBIENT, DIFFUSE = 0.4, 0.8             # Gazebo's default scene ambient and sun diffuse
BACKGROUND = (0.7, 0.7, 0.7)            # Gazebo's default scene background
PACKAGES = "libegl1 libegl-mesa0 libgl1-mesa-dri"   # Debian/Ubuntu: EGL and Mesa's llvmpipe

_VERTEX = """
#version 330
uniform mat4 view_projection;
uniform mat4 model;
uniform vec3 eye;
uniform vec3 to_sun;
uniform float ambient;
uniform float diffuse;
in vec3 in_position;
in vec3 in_normal;
in vec3 in_color;
out vec3 v_color;
void main() {
    vec4 world = model * vec4(in_position, 1.0);
    vec3 n = normalize(mat3(model) * in_normal);
    if (dot(n, eye - world.xyz) < 0.0) n = -n;
    v_color = min(in_color * (ambient + diffuse * max(dot(n, to_sun), 0.0)), vec3(1.0));
    gl_Position = view_projection * world;
}
"""
_FRAGMENT = """
#version 330
in vec3 v_color;
out vec4 f_color;
void main() {
    f_color = vec4(v_color, 1.0);
}
"""


# -- the pinhole model ---------------------------------------------------------------------------------------------

def intrinsics(fx: float, fy: float, cx: float, cy: float) -> np.ndarray:
    """K as a 3 × 3 matrix."""
    return np.array([[fx, 0.0, cx], [0.0, fy, cy], [0.0, 0.0, 1.0]])


def view_matrix(sensor_pose: np.ndarray) -> np.ndarray:
    """World → optical frame (4 × 4), for a sensor frame at world pose ``sensor_pose`` (4 × 4)."""
    rotation = OPTICAL_FROM_SENSOR @ sensor_pose[:3, :3].T
    view = np.eye(4)
    view[:3, :3] = rotation
    view[:3, 3] = -rotation @ sensor_pose[:3, 3]
    return view


def gl_projection(k: np.ndarray, width: int, height: int, near: float, far: float) -> np.ndarray:
    """Optical frame → OpenGL clip coordinates, so that a point lands on the pixel K puts it on (window
    x = u + ½, window y = v + ½: image row 0 is the framebuffer's first row) and depth runs from ``near`` to
    ``far`` along the optical axis."""
    fx, fy, cx, cy = k[0, 0], k[1, 1], k[0, 2], k[1, 2]
    return np.array([
        [2 * fx / width, 0.0, 2 * (cx + 0.5) / width - 1, 0.0],
        [0.0, 2 * fy / height, 2 * (cy + 0.5) / height - 1, 0.0],
        [0.0, 0.0, (far + near) / (far - near), -2 * far * near / (far - near)],
        [0.0, 0.0, 1.0, 0.0],
    ])


def project(points, sensor_pose: np.ndarray, k: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Pixel coordinates (N × 2: u, v) and depths Z (N) of world ``points`` (N × 3) seen by a sensor frame at
    ``sensor_pose`` through K (what a node computes from camera_info and tf)."""
    p = np.asarray(points, float).reshape(-1, 3)
    optical = p @ view_matrix(sensor_pose)[:3, :3].T + view_matrix(sensor_pose)[:3, 3]
    z = optical[:, 2]
    uv = optical[:, :2] / z[:, None] * [k[0, 0], k[1, 1]] + [k[0, 2], k[1, 2]]
    return uv, z


BAYER = {"rggb": ((0, 0), (1, 1)), "bggr": ((1, 1), (0, 0)), "gbrg": ((1, 0), (0, 1)), "grbg": ((0, 1), (1, 0))}


def encoded(rgb: np.ndarray, encoding: str) -> tuple[bytes, int]:
    """An RGB picture (height × width × 3 uint8) as the data and row step (bytes) of a sensor_msgs/Image with
    ``encoding``: rgb8, bgr8, mono8 (luma 0.299 R + 0.587 G + 0.114 B), rgb16 and mono16 (little-endian, ×257),
    or bayer_XXXX8 (each pixel keeps the one channel its place in the 2 × 2 pattern names)."""
    height, width = rgb.shape[:2]
    if encoding == "rgb8":
        return rgb.tobytes(), width * 3
    if encoding == "bgr8":
        return rgb[:, :, ::-1].tobytes(), width * 3
    if encoding in ("mono8", "mono16"):
        luma = np.rint(rgb.astype(np.float32) @ np.array([0.299, 0.587, 0.114], np.float32))
        if encoding == "mono8":
            return luma.astype(np.uint8).tobytes(), width
        return (luma.astype("<u2") * 257).tobytes(), width * 2
    if encoding == "rgb16":
        return (rgb.astype("<u2") * 257).tobytes(), width * 6
    if encoding.startswith("bayer_") and encoding[6:10] in BAYER:
        (ry, rx), (by, bx) = BAYER[encoding[6:10]]
        out = rgb[:, :, 1].copy()
        out[ry::2, rx::2] = rgb[ry::2, rx::2, 0]
        out[by::2, bx::2] = rgb[by::2, bx::2, 2]
        return out.tobytes(), width
    raise ValueError(f"unknown image encoding {encoding!r}")


# -- OpenGL --------------------------------------------------------------------------------------------------------

def open_context():
    """A standalone OpenGL 3.3 context on EGL; :class:`InputError` naming what to install when there is none."""
    try:
        import moderngl
    except ImportError:
        raise InputError("the simulated camera needs the Python package moderngl, which is not installed",
                         hint="pip install moderngl; or use --robot burger, which has no camera") from None
    try:
        return moderngl.create_standalone_context(backend="egl", require=330)
    except Exception as err:   # noqa: BLE001  (glcontext raises plain Exceptions: no libEGL, no device …)
        reason = (str(err).strip().splitlines() or [type(err).__name__])[0]
        raise InputError(f"no OpenGL context for the simulated camera ({reason})",
                         hint=f"install EGL and Mesa's software renderer: sudo apt-get install {PACKAGES}; or use "
                              "--robot burger, which has no camera") from None


class Mesh:
    """Triangles in the GPU's memory (corners, normals, colours), drawn at a pose given each time."""

    def __init__(self, ctx, program, corners: np.ndarray, normals: np.ndarray, colors: np.ndarray):
        data = np.hstack([corners, normals, colors]).astype("f4")
        self.ctx = ctx
        with ctx:
            self.vbo = ctx.buffer(data.tobytes())
            self.vao = ctx.vertex_array(program, [(self.vbo, "3f 3f 3f", "in_position", "in_normal", "in_color")])
        self.count = len(data)

    def release(self) -> None:
        with self.ctx:
            self.vao.release()
            self.vbo.release()


class Renderer:
    """One OpenGL context and its shader; an offscreen framebuffer per image size, made when first needed. Every
    call makes the context current first (``with ctx``), so that several renderers in one process (several
    sessions) do not draw into each other's."""

    def __init__(self):
        self.ctx = open_context()
        with self.ctx:
            self.program = self.ctx.program(vertex_shader=_VERTEX, fragment_shader=_FRAGMENT)
            sun = -np.asarray(SUN_DIRECTION, float)
            self.program["to_sun"].value = tuple(sun / np.linalg.norm(sun))
            self.program["ambient"].value = AMBIENT
            self.program["diffuse"].value = DIFFUSE
        self.targets: dict[tuple[int, int], object] = {}

    def mesh(self, corners: np.ndarray, normals: np.ndarray, colors: np.ndarray) -> Mesh | None:
        """The triangles in GPU memory (None when there are none)."""
        if len(corners) == 0:
            return None
        return Mesh(self.ctx, self.program, corners, normals, colors)

    def _target(self, width: int, height: int):
        key = (width, height)
        if key not in self.targets:
            color = self.ctx.renderbuffer(key, components=4)
            depth = self.ctx.depth_renderbuffer(key)
            self.targets[key] = self.ctx.framebuffer(color_attachments=[color], depth_attachment=depth)
        return self.targets[key]

    def render(self, k: np.ndarray, width: int, height: int, near: float, far: float, sensor_pose: np.ndarray,
               draws) -> np.ndarray:
        """The picture (height × width × 3, uint8 RGB, row 0 at the top) that a camera with intrinsics ``k`` and
        clip distances ``near``/``far`` takes from a sensor frame at world pose ``sensor_pose``. ``draws`` are
        ``(mesh, pose, behind)``: a :class:`Mesh` at world pose ``pose`` (4 × 4); ``behind`` pushes it back in
        depth a little, so that what lies flat on it (floor markings on the ground plane) shows."""
        import moderngl

        view_projection = gl_projection(k, width, height, near, far) @ view_matrix(sensor_pose)
        with self.ctx:
            fbo = self._target(width, height)
            fbo.use()
            fbo.clear(*BACKGROUND, 1.0, depth=1.0)
            self.ctx.enable(moderngl.DEPTH_TEST)
            self.ctx.disable(moderngl.CULL_FACE)
            self.program["view_projection"].write(view_projection.T.astype("f4").tobytes())
            self.program["eye"].value = tuple(float(v) for v in sensor_pose[:3, 3])
            for mesh, pose, behind in draws:
                self.ctx.polygon_offset = (1.0, 4.0) if behind else (0.0, 0.0)
                self.program["model"].write(np.asarray(pose, float).T.astype("f4").tobytes())
                mesh.vao.render(moderngl.TRIANGLES)
            self.ctx.polygon_offset = (0.0, 0.0)
            data = fbo.read(components=3, alignment=1)
        return np.frombuffer(data, np.uint8).reshape(height, width, 3)

    def close(self) -> None:
        with self.ctx:
            for fbo in self.targets.values():
                for attachment in list(fbo.color_attachments) + [fbo.depth_attachment]:
                    attachment.release()
                fbo.release()
            self.targets.clear()
            self.program.release()
        self.ctx.release()
