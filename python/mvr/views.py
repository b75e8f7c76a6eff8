"""View sets: layouts around a scene, a file's camera, or camera poses and
intrinsics given as numpy arrays; and each view's camera metadata."""
import ctypes
import math
from typing import TYPE_CHECKING, Any, Dict, List, Optional, Sequence, Tuple

import numpy as np

from . import _native as N
from ._common import U32_MAX, Error, Handle, c_float, c_floats, c_int, check, check_created, locked

if TYPE_CHECKING:  # scene.py does not import views.py: no cycle at run time either
    from .scene import Scene

# the library's limits (include/mvr/mvr_views.h, mvr_framing.h)
MAX_VIEWS = 1024          # MVR_VIEW_SET_MAX_VIEWS
_MAX_ASPECT = 65536.0     # mvr_framing_desc.aspect in [1/65536, 65536]
_MAX_IPD = 1e9            # mvr_framing_desc.ipd in [0, 1e9]
_MIN_YFOV, _MAX_YFOV = 1e-3, 3.1  # mvr_framing_desc.yfov: 0 or in [1e-3, 3.1] radians
_MAX_RADIUS = 1e9         # mvr_framing_desc.radius in [0, 1e9]
_MAX_MARGIN = 0.9         # mvr_framing_desc.margin in [0, 0.9]

# frustum half-angles the library takes (core/view_set.c: |angle| < 1.5707)
_MAX_ANGLE = 1.5707


def _mat(cols16: Any) -> np.ndarray:
    """16 doubles, column-major (C) -> a 4x4 numpy array (M @ p)."""
    return np.array(cols16[:], dtype=np.float64).reshape(4, 4).T.copy()


class Camera:
    """A view's camera metadata (mvr_view_camera), for a layer of some size.

    width, height: the view's viewport in pixels. K (3x3) = [[fx, 0, cx],
    [0, fy, cy], [0, 0, 1]] is the pinhole of the OpenCV / COLMAP camera (x
    right, y down, looking along +Z) with pixel k covering [k, k + 1) from
    the image's top-left corner: a camera point (X, Y, Z) lands at
    u = fx X / Z + cx, v = fy Y / Z + cy, which is column u, row v of the
    arrays render() returns (rows top to bottom). world_to_camera and
    camera_to_world (4x4, numpy layout: M @ [x, y, z, 1]) use the OpenGL
    camera (x right, y up, looking along -Z: glTF's, NeRF's
    transforms.json); flip its y and z axes for OpenCV's. projection is
    the OpenGL clip matrix (z in [-1, 1]). Orthographic views have
    perspective False and no pinhole (K is None, fx .. cy are 0)."""

    def __init__(self, c: Any) -> None:
        self.width, self.height = c.width, c.height
        self.perspective = bool(c.perspective)
        self.fx, self.fy, self.cx, self.cy = c.fx, c.fy, c.cx, c.cy
        self.projection = _mat(c.projection)
        self.world_to_camera = _mat(c.world_to_camera)
        self.camera_to_world = _mat(c.camera_to_world)

    @property
    def K(self) -> Optional[np.ndarray]:
        """The 3x3 pinhole matrix (None for an orthographic view)."""
        if not self.perspective:
            return None
        return np.array([[self.fx, 0.0, self.cx], [0.0, self.fy, self.cy], [0.0, 0.0, 1.0]])

    @property
    def position(self) -> np.ndarray:
        """The camera centre in world coordinates."""
        return self.camera_to_world[:3, 3].copy()

    def project(self, points: Any) -> Tuple[np.ndarray, np.ndarray]:
        """World points (N x 3) -> pixel coordinates (N x 2: column u, row
        v; continuous, pixel k covers [k, k + 1)) and depth along the view
        axis (N: positive in front of the camera)."""
        p = np.asarray(points, dtype=np.float64).reshape(-1, 3)
        cam = p @ self.world_to_camera[:3, :3].T + self.world_to_camera[:3, 3]
        z = -cam[:, 2]  # OpenCV's Z
        if not self.perspective:
            raise Error("project: an orthographic view has no pinhole")
        u = self.fx * cam[:, 0] / z + self.cx
        v = self.fy * -cam[:, 1] / z + self.cy
        return np.stack([u, v], axis=1), z

    def to_dict(self) -> Dict[str, Any]:
        """JSON-ready: lists for the matrices (rows)."""
        return {"width": self.width, "height": self.height, "perspective": self.perspective, "fx": self.fx,
                "fy": self.fy, "cx": self.cx, "cy": self.cy, "projection": self.projection.tolist(),
                "world_to_camera": self.world_to_camera.tolist(),
                "camera_to_world": self.camera_to_world.tolist()}

    def __repr__(self) -> str:
        return "Camera(%dx%d, fx=%.6g, fy=%.6g, cx=%.6g, cy=%.6g, position=%s)" % (
            self.width, self.height, self.fx, self.fy, self.cx, self.cy, np.round(self.position, 6).tolist())


def look_at(eye: Sequence[float], target: Sequence[float], up: Sequence[float] = (0.0, 1.0, 0.0)) -> np.ndarray:
    """A camera_to_world matrix (4x4, OpenGL camera: looking along -Z) at
    eye looking at target."""
    e, t, u = (np.asarray(c_floats(v, 3, name), dtype=np.float64)
               for v, name in ((eye, "eye"), (target, "target"), (up, "up")))
    f = t - e
    if not np.linalg.norm(f) > 0:
        raise ValueError("look_at: eye and target are the same point")
    f = f / np.linalg.norm(f)
    s = np.cross(f, u)
    if not np.linalg.norm(s) > 1e-12:
        raise ValueError("look_at: up is parallel to the viewing direction")
    s = s / np.linalg.norm(s)
    m = np.eye(4)
    m[:3, 0], m[:3, 1], m[:3, 2], m[:3, 3] = s, np.cross(s, f), -f, e
    return m


def _quaternion(r: np.ndarray) -> np.ndarray:
    """Rotation matrix -> unit quaternion (x, y, z, w)."""
    t = r[0, 0] + r[1, 1] + r[2, 2]
    if t > 0:
        s = math.sqrt(t + 1.0) * 2
        q = ((r[2, 1] - r[1, 2]) / s, (r[0, 2] - r[2, 0]) / s, (r[1, 0] - r[0, 1]) / s, 0.25 * s)
    elif r[0, 0] > r[1, 1] and r[0, 0] > r[2, 2]:
        s = math.sqrt(1.0 + r[0, 0] - r[1, 1] - r[2, 2]) * 2
        q = (0.25 * s, (r[0, 1] + r[1, 0]) / s, (r[0, 2] + r[2, 0]) / s, (r[2, 1] - r[1, 2]) / s)
    elif r[1, 1] > r[2, 2]:
        s = math.sqrt(1.0 + r[1, 1] - r[0, 0] - r[2, 2]) * 2
        q = ((r[0, 1] + r[1, 0]) / s, 0.25 * s, (r[1, 2] + r[2, 1]) / s, (r[0, 2] - r[2, 0]) / s)
    else:
        s = math.sqrt(1.0 + r[2, 2] - r[0, 0] - r[1, 1]) * 2
        q = ((r[0, 2] + r[2, 0]) / s, (r[1, 2] + r[2, 1]) / s, 0.25 * s, (r[1, 0] - r[0, 1]) / s)
    qa = np.array(q)
    return qa / np.linalg.norm(qa)


def _stack(a: Any, shape: Tuple[int, int], what: str) -> np.ndarray:
    arr = np.asarray(a, dtype=np.float64)
    if arr.shape == shape:
        arr = arr[None]
    if arr.ndim != 3 or arr.shape[1:] != shape:
        raise ValueError("%s: a %s array or a stack of them expected, got shape %s" % (what, shape, arr.shape))
    if not np.all(np.isfinite(arr)):
        raise ValueError("%s: NaN or infinite values" % what)
    return arr


class Views(Handle):
    """An mvr_view_set: one view per layer of a render. Make one with
    Views.layout (around a scene), Views.from_camera (a file's camera) or
    Views.from_poses (numpy poses and intrinsics)."""

    _what = "mvr.Views"

    def __init__(self, handle: int) -> None:
        super().__init__()
        self._handle = handle

    def _destroy(self, handle: int) -> None:
        N.C.mvr_view_set_destroy(handle)

    @classmethod
    def layout(cls, scene: "Scene", layout: str = "stereo", *, count: int = 0, aspect: float = 1.0,
               ipd: float = 0.0, rows: int = 0, elevation: Any = None, yfov: float = 0.0,
               radius: float = 0.0, margin: Optional[float] = None, hemisphere: str = "full", seed: int = 0,
               min_spacing: float = 0.0, up: str = "y", fit: str = "box") -> "Views":
        """Views laid out around the scene (mvr_view_set_frame_scene):
        layout "stereo", "cube", "ring", "grid", "sphere", "orbit" or
        "random"; count 0 = the layout's own (2, 6, 8, 9, 50, 24, 50), at
        most 1024; aspect = width / height of the images (1/65536 ..
        65536); ipd 0 = 1/30 of the framing distance; orbit: rows (rings;
        0 = 3).

        Camera sampling (mvr render's --fov ... --up; 0 and None are the
        defaults): elevation: stereo, ring and grid: one angle in radians,
        inside (-pi/2, pi/2), the views look down at the scene from (None =
        30 degrees, MVR_FRAMING_DEFAULT_ELEVATION; 0.0 = level); orbit's
        rings (lowest, highest), inside (-pi/2, pi/2) (None = -15 and 60
        degrees); sphere's and random's band, in [-pi/2, pi/2] (None = the
        whole sphere). yfov: the vertical field of view in radians, [1e-3,
        3.1] (0 = 50 degrees; not for cube). radius: the cameras' distance
        from the centre of the scene's bounds, (0, 1e9] (0 = fitted).
        margin: the box fit (the default), each view as close as keeps
        every corner of the bounding box inside the image less `margin` of
        its half-size, [0, 0.9] (None = 0.05); not with radius. fit "box"
        (the default) or "sphere" (the bounding sphere, 5% spare: with
        elevation=0.0 mvr's framing before issue 35; not with margin or
        radius). Cube takes none of these. hemisphere "upper" (sphere,
        random, orbit): no view below the centre's horizon. seed and
        min_spacing (random): the same views for the same seed (any int in
        [0, 2**64)), none two closer than min_spacing radians seen from
        the centre, [0, pi] (0 = 0.5 sqrt(band area / count)). up "y"
        (glTF's) or "z" (a Z-up world, Blender's): the axis the layouts
        orbit and the cameras' up follows."""
        d = N.desc(N.mvr_framing_desc)
        d.layout = N.LAYOUT(layout, "layout")
        layout = N.LAYOUT.name(d.layout)  # the canonical name, for the checks below
        d.views, d.rows = c_int(count, "count", 0, MAX_VIEWS), c_int(rows, "rows", 0, U32_MAX)
        d.aspect = c_float(aspect, "aspect", 1.0 / _MAX_ASPECT, _MAX_ASPECT)
        d.ipd = c_float(ipd, "ipd", 0.0, _MAX_IPD)
        if elevation is not None and layout == "cube":
            raise ValueError("cube: its six 90-degree views stand at the centre: elevation does not apply")
        if elevation is not None and layout in ("stereo", "ring", "grid"):
            e = c_float(elevation, "elevation", -math.pi / 2, math.pi / 2)
            if not abs(e) < math.pi / 2:
                raise ValueError("elevation: %r radians is not inside (-pi/2, pi/2)" % (e,))
            d.elevation, d.level = e, e == 0.0
        elif elevation is not None:
            lo, hi = c_floats(elevation, 2, "elevation")
            band = layout in ("sphere", "random")
            for name, e in (("elevation[0]", lo), ("elevation[1]", hi)):
                if not (abs(e) <= math.pi / 2 if band else abs(e) < math.pi / 2):
                    raise ValueError("%s: %r radians is not inside %s" %
                                     (name, e, "[-pi/2, pi/2]" if band else "(-pi/2, pi/2)"))
            if lo > hi:
                raise ValueError("elevation: (lowest, highest) expected, got %r" % (tuple(elevation),))
            d.elevation_min, d.elevation_max = lo, hi
        yfov = c_float(yfov, "yfov", 0.0, _MAX_YFOV)
        if 0.0 < yfov < _MIN_YFOV:
            raise ValueError("yfov: %r radians is below %g (0 = 50 degrees)" % (yfov, _MIN_YFOV))
        d.yfov = yfov
        d.radius = c_float(radius, "radius", 0.0, _MAX_RADIUS)
        if margin is not None:
            if d.radius > 0:
                raise ValueError("radius and margin: give the distance or fit the box, not both")
            d.fit_box, d.margin = True, c_float(margin, "margin", 0.0, _MAX_MARGIN)
        if fit not in ("box", "sphere"):
            raise ValueError("fit: 'box' or 'sphere', not %r" % (fit,))
        if fit == "sphere":
            if d.fit_box or d.radius > 0:
                raise ValueError("fit 'sphere': not with margin or radius")
            d.fit_sphere = True
        d.hemisphere = N.HEMISPHERE(hemisphere, "hemisphere")
        d.seed = c_int(seed, "seed", 0, 2 ** 64 - 1)
        d.min_spacing = c_float(min_spacing, "min_spacing", 0.0, math.pi)
        d.up = N.UP_AXIS(up, "up")
        if N.HEMISPHERE.name(d.hemisphere) == "upper" and layout not in ("sphere", "random", "orbit"):
            raise ValueError("hemisphere: 'upper' is for the sphere, random and orbit layouts, not %r" % (layout,))
        if layout == "cube" and (d.yfov or d.radius or d.fit_box or d.fit_sphere or elevation is not None):
            raise ValueError("cube: its six 90-degree views stand at the centre: yfov, radius, margin, fit and "
                             "elevation do not apply")
        out = ctypes.c_void_p()
        err = N.mvr_error()
        with scene._lock:
            check_created(N.C.mvr_view_set_frame_scene(scene.handle, ctypes.byref(d), ctypes.byref(out),
                                                       ctypes.byref(err)), err, "mvr_view_set_frame_scene")
        return cls(int(out.value or 0))

    @classmethod
    def default(cls, scene: "Scene", size: Tuple[int, int] = (640, 480)) -> "Views":
        """The views `mvr render FILE` (and mvr-viewer) show a scene from at
        size = (width, height): its first camera node as a stereo pair
        (Views.from_camera(scene, 0, count=2)) when it has one, else the
        stereo framing at the size's aspect (the library's default: from 30
        degrees above, the bounding box fitted with a 5% margin). Context.render(views=None)
        renders these."""
        try:
            width, height = size
        except (TypeError, ValueError):
            raise ValueError("size: (width, height) expected, got %r" % (size,)) from None
        width, height = c_int(width, "size: width", 1, U32_MAX), c_int(height, "size: height", 1, U32_MAX)
        if scene.camera_nodes:
            return cls.from_camera(scene, 0, count=2)
        return cls.layout(scene, "stereo", aspect=width / height)

    @classmethod
    def from_camera(cls, scene: "Scene", camera: int = 0, *, count: int = 1, ipd: float = 0.0) -> "Views":
        """Views from a camera of the scene (mvr_view_set_from_camera):
        camera = its index among scene.camera_nodes; count eyes (1 .. 1024)
        ipd apart along the camera's x axis (1 = the camera itself; ipd 0 =
        1/30 of the camera's distance to the scene)."""
        count = c_int(count, "count", 1, MAX_VIEWS)
        ipd = c_float(ipd, "ipd", 0.0, _MAX_IPD)
        out = ctypes.c_void_p()
        err = N.mvr_error()
        with scene._lock:
            nodes = scene.camera_nodes
            if not 0 <= camera < len(nodes):
                raise Error("from_camera: the scene has %d camera nodes; %r is not one" % (len(nodes), camera))
            camera = c_int(camera, "camera", 0, len(nodes) - 1)
            check_created(N.C.mvr_view_set_from_camera(scene.handle, N.Id(nodes[camera]), count, ipd,
                                                       ctypes.byref(out), ctypes.byref(err)), err,
                          "mvr_view_set_from_camera")
        return cls(int(out.value or 0))

    @classmethod
    def from_poses(cls, camera_to_world: Any, intrinsics: Any = None, size: Optional[Sequence[float]] = None, *,
                   yfov: float = 0.0, znear: float = 0.0, zfar: float = 0.0, convention: str = "opengl",
                   origin: Optional[Sequence[float]] = None) -> "Views":
        """Views from camera poses: camera_to_world is (4, 4) or (N, 4, 4)
        (rigid: rotation and translation; convention "opengl": the camera
        looks along -Z with +Y up, as Camera.camera_to_world, glTF and
        NeRF's transforms.json; "opencv": along +Z with +Y down, as COLMAP
        and OpenCV). intrinsics: K, (3, 3) or (N, 3, 3) pinhole matrices in
        pixels of an image of size = (width, height) (pixel k covers
        [k, k + 1)); rendered at that size, Views.camera gives the same K;
        at another size K scales with it. Without intrinsics: a symmetric
        perspective of yfov radians (0 = 60 degrees). znear 0 = 0.05, zfar
        0 = infinite. origin: the point the GPU sees as 0 (None = the
        views' centroid)."""
        poses = _stack(camera_to_world, (4, 4), "camera_to_world")
        flip = {"opengl": np.diag([1.0, 1.0, 1.0]), "opencv": np.diag([1.0, -1.0, -1.0])}
        if convention not in flip:
            raise ValueError("convention: 'opengl' or 'opencv', got %r" % (convention,))
        n = c_int(poses.shape[0], "camera_to_world: pose count", 1, MAX_VIEWS)
        yfov = c_float(yfov, "yfov", 0.0)  # 0 = 60 degrees
        if yfov >= math.pi:
            raise ValueError("yfov: %r radians must be below pi" % (yfov,))
        # znear / zfar: numbers here; their range is the view set's to judge (its message names the view)
        znear, zfar = (float(z) for z in (znear, zfar))
        ks = None
        if intrinsics is not None:
            ks = _stack(intrinsics, (3, 3), "intrinsics")
            if ks.shape[0] == 1:
                ks = np.repeat(ks, n, axis=0)
            if ks.shape[0] != n:
                raise ValueError("intrinsics: %d matrices for %d poses" % (ks.shape[0], n))
            if size is None:
                raise ValueError("intrinsics need size=(width, height): the image they are in pixels of")
            width, height = c_floats(size, 2, "size")
            if not (width > 0 and height > 0):
                raise ValueError("size: positive width and height expected, got %r" % (size,))
        views = (N.mvr_view_desc * n)()
        for i in range(n):
            m = poses[i]
            r = m[:3, :3] @ flip[convention]
            if not np.allclose(m[3], [0, 0, 0, 1], atol=1e-9):
                raise ValueError("camera_to_world[%d]: the last row must be (0, 0, 0, 1)" % i)
            if not np.allclose(r.T @ r, np.eye(3), atol=1e-6) or np.linalg.det(r) < 0:
                raise ValueError("camera_to_world[%d]: not a rotation (scaled, sheared or mirrored)" % i)
            v = views[i]
            v.position[:] = m[:3, 3].tolist()
            v.orientation[:] = _quaternion(r).tolist()
            p = v.projection
            p.znear, p.zfar = znear, zfar
            if ks is None:
                p.type = N.PROJECTION_TYPE("perspective")
                p.yfov = yfov
                continue
            k = ks[i]
            fx, fy, cx, cy = k[0, 0], k[1, 1], k[0, 2], k[1, 2]
            if abs(k[0, 1]) > 1e-12 or not np.allclose(k[2], [0, 0, 1]) or abs(k[1, 0]) > 1e-12:
                raise ValueError("intrinsics[%d]: [[fx, 0, cx], [0, fy, cy], [0, 0, 1]] expected (no skew)" % i)
            if not (fx > 0 and fy > 0):
                raise ValueError("intrinsics[%d]: fx and fy must be positive" % i)
            # the image's edges, seen from the camera: u = 0 and u = width,
            # v = 0 (top) and v = height; GL's up is OpenCV's -y
            p.type = N.PROJECTION_TYPE("frustum")
            p.angle_left = math.atan(-cx / fx)
            p.angle_right = math.atan((width - cx) / fx)
            p.angle_up = math.atan(cy / fy)
            p.angle_down = math.atan(-(height - cy) / fy)
            for name in ("angle_left", "angle_right", "angle_up", "angle_down"):
                if abs(getattr(p, name)) >= _MAX_ANGLE:
                    raise ValueError("intrinsics[%d]: the image's edge reaches 90 degrees from the axis (%s)" %
                                     (i, name))
        d = N.desc(N.mvr_view_set_desc)
        d.view_count = n
        d.views = views
        if origin is not None:
            d.origin_set = True
            d.origin[:] = c_floats(origin, 3, "origin")
        out = ctypes.c_void_p()
        err = N.mvr_error()
        check_created(N.C.mvr_view_set_create(ctypes.byref(d), ctypes.byref(out), ctypes.byref(err)), err,
                      "mvr_view_set_create")
        return cls(int(out.value or 0))

    @locked
    def __len__(self) -> int:
        """The number of views (one layer each)."""
        return N.C.mvr_view_set_count(self.handle)

    @locked
    def camera(self, index: int, width: int, height: int) -> Camera:
        """View `index`'s Camera on a layer of width x height pixels."""
        n = len(self)
        if not 0 <= index < n:
            raise Error("camera: view %r of %d views" % (index, n))
        index = c_int(index, "index", 0, n - 1)
        width, height = c_int(width, "width", 0, U32_MAX), c_int(height, "height", 0, U32_MAX)
        c = N.out(N.mvr_view_camera)
        h = self.handle
        check(N.C.mvr_view_set_get_camera(h, index, width, height, ctypes.byref(c)),
              lambda: N.text(N.C.mvr_view_set_last_error(h)), "mvr_view_set_get_camera(%d, %dx%d)" %
              (index, width, height))
        return Camera(c)

    @locked
    def cameras(self, width: int, height: int) -> List[Camera]:
        """Every view's Camera on layers of width x height pixels."""
        return [self.camera(i, width, height) for i in range(len(self))]
