"""Scenes (a glTF file, or objects added in code) and environments."""
import ctypes
import math
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import _native as N
from ._common import (U32_MAX, U64_MAX, Error, Handle, PathArg, as_c_double, as_c_float, c_float, c_int, c_path,
                      c_text, check, check_created, locked, logger)

Text = Union[str, bytes, None]
_PLURAL = {"node": "nodes", "mesh": "meshes", "material": "materials"}

# animation and variant indices: the last uint32 means "all" / "the default"
_INDEX_MAX = U32_MAX - 1


def _id(value: Any, what: str) -> int:
    """An object id (mvr_*_id: a uint32, 0 = none)."""
    return c_int(value, what, 0, U32_MAX)


def _f32(a: Any, cols: int, what: str, rows: Optional[int] = None) -> np.ndarray:
    """A C-contiguous float32 (rows, cols) copy of an array-like, checked."""
    arr = np.asarray(a, dtype=np.float32)
    if arr.ndim not in (1, 2) or arr.size % cols or (arr.ndim == 2 and arr.shape[1] != cols):
        raise ValueError("%s: an (N, %d) array expected, got shape %s" % (what, cols, arr.shape))
    arr = np.ascontiguousarray(arr.reshape(-1, cols))
    if rows is not None and arr.shape[0] != rows:
        raise ValueError("%s: %d rows of %d expected, got %d" % (what, rows, cols, arr.shape[0]))
    if not np.all(np.isfinite(arr)):
        raise ValueError("%s: NaN or infinite values" % what)
    return arr


def _ptr(arr: Optional[np.ndarray], ctype: Any) -> Any:
    return arr.ctypes.data_as(ctypes.POINTER(ctype)) if arr is not None else None


class Scene(Handle):
    """An mvr_scene: load a glTF file with Scene.load(path), or build one
    with Scene() and the add_* methods. Ids returned by add_* are ints (the
    C ids; 0 = none). Close it (or use `with`) to free it; a scene holds no
    GL, so it may be closed before or after the Context that rendered it."""

    _what = "mvr.Scene"

    def __init__(self) -> None:
        super().__init__()
        self.gltf_info: Optional[Dict[str, int]] = None  # for scenes from Scene.load
        self._logger = logger()
        desc = N.desc(N.mvr_scene_desc)
        desc.logger = self._logger
        out = ctypes.c_void_p()
        err = N.mvr_error()
        check_created(N.C.mvr_scene_create(ctypes.byref(desc), ctypes.byref(out), ctypes.byref(err)), err,
                      "mvr_scene_create")
        self._handle = out.value

    @classmethod
    def _adopt(cls, handle: int) -> "Scene":
        self = cls.__new__(cls)
        Handle.__init__(self)
        self.gltf_info = None
        self._logger = logger()
        self._handle = handle
        return self

    def _destroy(self, handle: int) -> None:
        N.C.mvr_scene_destroy(handle)

    def _check(self, result: int, what: str) -> None:
        check(result, lambda: N.text(N.C.mvr_scene_last_error(self._handle)), what)

    # ------------------------------------------------------------ loading

    @classmethod
    def load(cls, path: PathArg, *, scene: Optional[int] = None, strict: bool = False, memory_budget: int = 0,
             base_dir: Optional[PathArg] = None, allowed_root: Optional[PathArg] = None) -> "Scene":
        """Loads a .gltf or .glb file (mvr_gltf_load_file). scene: the index
        of the file's scene (None = its default); strict: missing images are
        errors; memory_budget: bytes (0 = 2 GiB); allowed_root: a folder
        whose files are admitted besides the file's own. Raises mvr.Error
        with the loader's message."""
        if N.C.mvr_gltf_load_file is None:
            raise Error("this mvr was built without the glTF loader (libmvr_gltf.so)", "MVR_ERROR_UNSUPPORTED")
        opts = N.desc(N.mvr_gltf_options)
        opts.scene = 0 if scene is None else c_int(scene, "scene", 0, _INDEX_MAX) + 1
        opts.strict = bool(strict)
        opts.memory_budget = c_int(memory_budget, "memory_budget", 0, U64_MAX)
        file_path = c_path(path, "path")
        keep = [c_path(base_dir, "base_dir"), c_path(allowed_root, "allowed_root")]
        opts.base_dir = keep[0]
        opts.file_access.allowed_root = keep[1]
        lg = logger()
        opts.logger = lg
        out = ctypes.c_void_p()
        info = N.out(N.mvr_gltf_info)
        err = N.mvr_error()
        r = N.C.mvr_gltf_load_file(file_path, ctypes.byref(opts), ctypes.byref(out), ctypes.byref(info),
                                   ctypes.byref(err))
        check_created(r, err, "mvr_gltf_load_file")
        self = cls._adopt(int(out.value or 0))
        self.gltf_info = {name: getattr(info, name) for name in N.mvr_gltf_info.field_names()}
        return self

    # ------------------------------------------------------------ adding objects

    @locked
    def add_image(self, rgba: Any, name: Text = None) -> int:
        """An RGBA8 image: a (height, width, 4) uint8 array, rows top first."""
        arr = np.ascontiguousarray(rgba, dtype=np.uint8)
        if arr.ndim != 3 or arr.shape[2] != 4:
            raise ValueError("add_image: a (height, width, 4) uint8 array expected, got shape %s" % (arr.shape,))
        d = N.desc(N.mvr_image_desc)
        d.width = c_int(arr.shape[1], "add_image: width", 0, U32_MAX)
        d.height = c_int(arr.shape[0], "add_image: height", 0, U32_MAX)
        d.rgba8 = _ptr(arr, ctypes.c_uint8)
        d.name = c_text(name, "name")
        out = N.Id()
        self._check(N.C.mvr_scene_add_image(self.handle, ctypes.byref(d), ctypes.byref(out)), "add_image")
        return out.id

    @locked
    def add_material(self, *, base_color: Sequence[float] = (1, 1, 1, 1), metallic: float = 1.0,
                     roughness: float = 1.0, emissive: Sequence[float] = (0, 0, 0), emissive_strength: float = 1.0,
                     alpha_mode: str = "opaque", alpha_cutoff: float = 0.5, double_sided: bool = False,
                     unlit: bool = False, base_color_texture: int = 0, metallic_roughness_texture: int = 0,
                     normal_texture: int = 0, emissive_texture: int = 0, occlusion_texture: int = 0, ior: float = 1.5,
                     name: Text = None) -> int:
        """A glTF metallic-roughness material (glTF's defaults); textures are
        image ids from add_image (TEXCOORD_0). Returns its id."""
        d = N.C.mvr_material_defaults()
        d.base_color_factor = as_c_float(base_color, 4, "base_color", 0.0)
        d.metallic_factor = c_float(metallic, "metallic", 0.0, 1.0)
        d.roughness_factor = c_float(roughness, "roughness", 0.0, 1.0)
        d.emissive_factor = as_c_float(emissive, 3, "emissive", 0.0)
        d.emissive_strength = c_float(emissive_strength, "emissive_strength", 0.0)
        d.alpha_mode = N.ALPHA_MODE(alpha_mode, "alpha_mode")
        d.alpha_cutoff = c_float(alpha_cutoff, "alpha_cutoff", 0.0)
        d.double_sided = bool(double_sided)
        d.unlit = bool(unlit)
        d.ior = c_float(ior, "ior", 0.0)  # KHR_materials_ior: 1 or more, 0 for the old 1/0 convention
        for role, image in (("base_color", base_color_texture), ("metallic_roughness", metallic_roughness_texture),
                            ("normal", normal_texture), ("emissive", emissive_texture),
                            ("occlusion", occlusion_texture)):
            getattr(d, role).image.id = _id(image, role + "_texture")
        keep = c_text(name, "name")
        d.name = keep
        # in a buffer with slack, like every descriptor (N.desc)
        dd = N.desc(N.mvr_material_desc)
        ctypes.memmove(ctypes.addressof(dd), ctypes.addressof(d), ctypes.sizeof(d))
        out = N.Id()
        self._check(N.C.mvr_scene_add_material(self.handle, ctypes.byref(dd), ctypes.byref(out)), "add_material")
        return out.id

    @locked
    def add_mesh(self, primitives: Union[None, Dict[str, Any], Sequence[Dict[str, Any]]] = None, *,
                 name: Text = None, **primitive: Any) -> int:
        """A mesh of one or more primitives. Each is a dict (or, for one
        primitive, keyword arguments) of: positions (N x 3), normals (N x 3),
        tangents (N x 4), texcoords0 / texcoords1 (N x 2), colors (N x 4,
        linear RGBA), indices (M, uint16 or uint32; none: non-indexed),
        material (an id; 0 = the default), mode ("triangles", "lines",
        "points"). Arrays are copied. Returns the mesh id."""
        if primitives is None:
            primitives = [primitive]
        elif primitive:
            raise TypeError("add_mesh: give primitives=[...] or one primitive's keyword arguments, not both")
        if isinstance(primitives, dict):
            primitives = [primitives]
        keep: List[Any] = []
        c_int(len(primitives), "add_mesh: primitive count", 0, U32_MAX)
        prims = (N.mvr_primitive_desc * len(primitives))()
        for k, p in enumerate(primitives):
            known = {"positions", "normals", "tangents", "texcoords0", "texcoords1", "colors", "indices",
                     "material", "mode"}
            unknown = set(p) - known
            if unknown:
                raise TypeError("add_mesh: primitive %d: unknown keys %s" % (k, ", ".join(sorted(unknown))))
            if p.get("positions") is None:
                raise ValueError("add_mesh: primitive %d has no positions" % k)
            pos = _f32(p["positions"], 3, "primitive %d positions" % k)
            n = pos.shape[0]
            d = prims[k]
            d.vertex_count = c_int(n, "add_mesh: primitive %d vertex count" % k, 0, U32_MAX)
            d.positions = _ptr(pos, ctypes.c_float)
            keep.append(pos)
            for attr, cols in (("normals", 3), ("tangents", 4), ("texcoords0", 2), ("texcoords1", 2),
                               ("colors", 4)):
                if p.get(attr) is not None:
                    a = _f32(p[attr], cols, "primitive %d %s" % (k, attr), rows=n)
                    keep.append(a)
                    setattr(d, attr, _ptr(a, ctypes.c_float))
            if p.get("indices") is not None:
                idx = np.asarray(p["indices"]).reshape(-1)
                if idx.size and idx.dtype.kind not in "iu":
                    raise ValueError("add_mesh: primitive %d: integer indices expected, got %s" % (k, idx.dtype))
                if idx.size and (idx.min() < 0 or idx.max() >= n):
                    raise ValueError("add_mesh: primitive %d: indices outside 0..%d" % (k, n - 1))
                if idx.dtype == np.uint16:
                    idx = np.ascontiguousarray(idx)
                    d.indices16 = _ptr(idx, ctypes.c_uint16)
                else:
                    idx = np.ascontiguousarray(idx, dtype=np.uint32)
                    d.indices32 = _ptr(idx, ctypes.c_uint32)
                d.index_count = c_int(idx.size, "add_mesh: primitive %d index count" % k, 0, U32_MAX)
                keep.append(idx)
            d.material.id = _id(p.get("material", 0) or 0, "add_mesh: primitive %d material" % k)
            d.mode = N.PRIMITIVE_MODE(p.get("mode", "triangles"), "mode")
        md = N.desc(N.mvr_mesh_desc)
        md.primitives = prims
        md.primitive_count = len(primitives)
        keep_name = c_text(name, "name")
        md.name = keep_name
        out = N.Id()
        self._check(N.C.mvr_scene_add_mesh(self.handle, ctypes.byref(md), ctypes.byref(out)), "add_mesh")
        return out.id

    @locked
    def add_light(self, type: str = "directional", *, color: Sequence[float] = (1, 1, 1), intensity: float = 1.0,
                  range: float = 0.0, inner_cone_angle: float = 0.0, outer_cone_angle: float = 0.0,
                  cast_shadows: bool = False, layers: int = 0) -> int:
        """A KHR_lights_punctual light (shines along its node's -Z): type
        "directional" (lux), "point" or "spot" (candela). Returns its id."""
        d = N.desc(N.mvr_light_desc)
        d.type = N.LIGHT_TYPE(type, "light type")
        d.color = as_c_float(color, 3, "color", 0.0)
        d.intensity = c_float(intensity, "intensity", 0.0)
        d.range = c_float(range, "range", 0.0)  # 0 = infinite
        # KHR_lights_punctual: 0 <= inner < outer <= pi/2 (the library judges the pair)
        d.inner_cone_angle = c_float(inner_cone_angle, "inner_cone_angle", 0.0, math.pi / 2)
        d.outer_cone_angle = c_float(outer_cone_angle, "outer_cone_angle", 0.0, math.pi / 2)
        d.cast_shadows = bool(cast_shadows)
        d.layers = c_int(layers, "layers", 0, U32_MAX)
        out = N.Id()
        self._check(N.C.mvr_scene_add_light(self.handle, ctypes.byref(d), ctypes.byref(out)), "add_light")
        return out.id

    @locked
    def add_camera(self, *, yfov: float = 0.0, aspect: float = 0.0, znear: float = 0.0, zfar: float = 0.0,
                   xmag: Optional[float] = None, ymag: Optional[float] = None) -> int:
        """A camera (put it on a node): perspective (yfov radians, 0 = 60
        degrees; aspect 0 = the viewport's), or orthographic when xmag and
        ymag (half extents) are given. Returns its id."""
        p = N.desc(N.mvr_projection)
        if xmag is not None or ymag is not None:
            p.type = N.PROJECTION_TYPE("orthographic")
            p.xmag, p.ymag = c_float(xmag or 0, "xmag"), c_float(ymag or 0, "ymag")
        else:
            p.yfov, p.aspect = c_float(yfov, "yfov", 0.0), c_float(aspect, "aspect", 0.0)
        p.znear, p.zfar = c_float(znear, "znear"), c_float(zfar, "zfar")
        out = N.Id()
        self._check(N.C.mvr_scene_add_camera(self.handle, ctypes.byref(p), ctypes.byref(out)), "add_camera")
        return out.id

    @locked
    def add_node(self, *, mesh: int = 0, light: int = 0, camera: int = 0, parent: int = 0,
                 translation: Sequence[float] = (0, 0, 0), rotation: Sequence[float] = (0, 0, 0, 1),
                 scale: Sequence[float] = (1, 1, 1), matrix: Any = None, name: Text = None) -> int:
        """A node: translation, rotation (quaternion x, y, z, w), scale, or a
        4x4 matrix (numpy layout: row-major, m[:3, 3] the translation);
        what it carries (mesh, light, camera ids) and its parent (a node id,
        0 = a root). Returns its id (the node id of the `ids` output)."""
        d = N.desc(N.mvr_node_desc)
        d.parent.id, d.mesh.id = _id(parent, "parent"), _id(mesh, "mesh")
        d.light.id, d.camera.id = _id(light, "light"), _id(camera, "camera")
        d.translation = as_c_double(translation, 3, "translation")
        d.rotation = as_c_double(rotation, 4, "rotation")
        d.scale = as_c_double(scale, 3, "scale")
        if matrix is not None:
            m = np.asarray(matrix, dtype=np.float64)
            if m.shape != (4, 4):
                raise ValueError("matrix: a 4x4 array expected, got shape %s" % (m.shape,))
            d.use_matrix = True
            d.matrix = as_c_double(m.T.reshape(-1), 16, "matrix")  # column-major
        keep = c_text(name, "name")
        d.name = keep
        out = N.Id()
        self._check(N.C.mvr_scene_add_node(self.handle, ctypes.byref(d), ctypes.byref(out)), "add_node")
        return out.id

    @locked
    def set_node_transform(self, node: int, translation: Sequence[float] = (0, 0, 0),
                           rotation: Sequence[float] = (0, 0, 0, 1), scale: Sequence[float] = (1, 1, 1)) -> None:
        """Sets a node's translation, rotation (quaternion x, y, z, w) and scale."""
        self._check(N.C.mvr_scene_set_node_transform(
            self.handle, N.Id(_id(node, "node")), as_c_double(translation, 3, "translation"),
            as_c_double(rotation, 4, "rotation"), as_c_double(scale, 3, "scale")), "set_node_transform")

    @locked
    def set_ambient(self, rgb: Sequence[float]) -> None:
        """Uniform ambient radiance from every direction (linear RGB, >= 0)."""
        N.C.mvr_scene_set_ambient(self.handle, as_c_float(rgb, 3, "ambient", 0.0))

    # ------------------------------------------------------------ queries

    @property
    @locked
    def info(self) -> Dict[str, Any]:
        """Counts (images, materials, meshes, nodes, ...) and world bounds."""
        i = N.out(N.mvr_scene_info)
        N.C.mvr_scene_get_info(self.handle, ctypes.byref(i))
        d = {name: getattr(i, name) for name in N.mvr_scene_info.field_names()}
        for k in ("bounds_min", "bounds_max", "max_light_intensity"):
            d[k] = tuple(d[k])
        return d

    @property
    @locked
    def camera_nodes(self) -> List[int]:
        """The node ids of nodes that carry a camera, in node order."""
        h = self.handle
        return [N.C.mvr_scene_camera_node(h, k).id for k in range(N.C.mvr_scene_camera_node_count(h))]

    # ------------------------------------------------------------ ids -> names

    def _name(self, fn: Any, kind: str, ident: Any) -> str:
        with self._lock:
            got = fn(self.handle, N.Id(_id(ident, kind)))
            if got is None:  # NULL: no such id ("" is an unnamed one)
                plural = _PLURAL[kind]
                raise KeyError("%s %r: the scene has %d %s (ids 1 .. their count)" % (
                    kind, ident, self.info[plural], plural))
        return N.text(got)

    def node_name(self, node: int) -> str:
        """The name of a node id (the `ids` output's channel 0; "" when
        unnamed); KeyError for an id the scene does not have."""
        return self._name(N.C.mvr_scene_node_name, "node", node)

    def mesh_name(self, mesh: int) -> str:
        """The name of a mesh id (the `ids` output's channel 1); as node_name."""
        return self._name(N.C.mvr_scene_mesh_name, "mesh", mesh)

    def material_name(self, material: int) -> str:
        """The name of a material id (the `ids` output's channel 2); as node_name."""
        return self._name(N.C.mvr_scene_material_name, "material", material)

    @property
    @locked
    def names(self) -> Dict[str, Dict[int, str]]:
        """Every id's name: {"nodes": {id: name}, "meshes": {...},
        "materials": {...}} (ids 1 .. the counts of `info`; "" when unnamed),
        to look up what the `ids` output names."""
        info = self.info
        return {key: {k: self._name(fn, kind, k) for k in range(1, info[key] + 1)}
                for key, kind, fn in (("nodes", "node", N.C.mvr_scene_node_name),
                                      ("meshes", "mesh", N.C.mvr_scene_mesh_name),
                                      ("materials", "material", N.C.mvr_scene_material_name))}

    @property
    @locked
    def animations(self) -> List[Tuple[str, float, float]]:
        """[(name, start, end)] in seconds, in the file's order."""
        h = self.handle
        out = []
        for k in range(N.C.mvr_scene_animation_count(h)):
            ai = N.out(N.mvr_animation_info)
            self._check(N.C.mvr_scene_get_animation_info(h, k, ctypes.byref(ai)), "animation info")
            out.append((N.text(ai.name), ai.start, ai.end))
        return out

    @locked
    def apply_animation(self, animation: Union[int, str], time: float, *, loop: bool = False) -> None:
        """Poses the scene at `time` seconds of an animation: its index, its
        name, or "all" (every animation at that time)."""
        index = self._animation_index(animation)
        wrap = N.ANIMATION_WRAP("loop" if loop else "clamp")
        self._check(N.C.mvr_scene_apply_animation(self.handle, index, c_float(time, "time"), wrap),
                    "apply_animation")

    def _animation_index(self, animation: Union[int, str]) -> int:
        if isinstance(animation, str):
            if animation == "all":
                return N.ANIMATION_ALL
            k = ctypes.c_uint32()
            self._check(N.C.mvr_scene_find_animation(self.handle, c_text(animation, "animation"), ctypes.byref(k)),
                        "animation")
            return k.value
        return c_int(animation, "animation", 0, _INDEX_MAX)

    @locked
    def reset_pose(self) -> None:
        """Back to the nodes' own transforms (before any animation)."""
        N.C.mvr_scene_reset_pose(self.handle)

    @property
    @locked
    def variants(self) -> List[str]:
        """Material variant names (KHR_materials_variants), in order."""
        h = self.handle
        return [N.text(N.C.mvr_scene_variant_name(h, k)) for k in range(N.C.mvr_scene_variant_count(h))]

    @locked
    def select_variant(self, variant: Union[int, str, None]) -> None:
        """Selects a material variant by name or index; None: the default."""
        if variant is None:
            index = N.VARIANT_DEFAULT
        elif isinstance(variant, str):
            k = ctypes.c_uint32()
            self._check(N.C.mvr_scene_find_variant(self.handle, c_text(variant, "variant"), ctypes.byref(k)),
                        "variant")
            index = k.value
        else:
            index = c_int(variant, "variant", 0, _INDEX_MAX)
        self._check(N.C.mvr_scene_select_variant(self.handle, index), "select_variant")


class Environment(Handle):
    """Image-based lighting (mvr_environment): source "neutral" (the built-in
    studio, Context.render's default), "uniform" (color: one radiance from
    everywhere), or an equirectangular image of linear radiance: pixels =
    (height, width, 3 or 4) floats, rows top first (Environment.from_file
    reads .hdr / .exr). intensity (> 0) multiplies it, rotation turns it
    (degrees about +Y); both can change later (the `intensity` and
    `rotation` properties) without prefiltering again. specular_size: the
    prefiltered cube face, a power of two 16..1024 (0 = 128);
    specular_samples: GGX samples per texel, 1..4096 (0 = 256)."""

    _what = "mvr.Environment"

    def __init__(self, source: str = "neutral", *, pixels: Any = None, color: Sequence[float] = (1, 1, 1),
                 intensity: float = 1.0, rotation: float = 0.0, specular_size: int = 0,
                 specular_samples: int = 0) -> None:
        super().__init__()
        if pixels is not None:
            source = "pixels"
        d = N.desc(N.mvr_environment_desc)
        d.source = N.ENV_SOURCE(source, "environment source")
        self.source = N.ENV_SOURCE.name(d.source)
        keep = None
        if d.source == N.ENV_SOURCE("pixels"):
            if pixels is None:
                raise ValueError("Environment: source 'pixels' needs pixels")
            a = np.asarray(pixels, dtype=np.float32)
            if a.ndim != 3 or a.shape[2] not in (3, 4):
                raise ValueError("Environment: pixels must be (height, width, 3 or 4), got %s" % (a.shape,))
            if a.shape[2] == 3:
                a = np.concatenate([a, np.ones(a.shape[:2] + (1,), np.float32)], axis=2)
            keep = np.ascontiguousarray(a)
            d.pixels = _ptr(keep, ctypes.c_float)
            d.width = c_int(keep.shape[1], "Environment: pixels width", 1, U32_MAX)
            d.height = c_int(keep.shape[0], "Environment: pixels height", 1, U32_MAX)
        rgb = as_c_float(color, 3, "color", 0.0)
        if not any(rgb):  # the library would read all 0 as (1, 1, 1)
            raise ValueError("color: %r is black: a uniform environment gives no light (environment=None "
                             "renders without one)" % (tuple(color),))
        d.color = rgb
        d.intensity = _intensity(intensity)
        d.rotation = c_float(rotation, "rotation")
        size = c_int(specular_size, "specular_size", 0, 1024)
        if size and (size < 16 or size & (size - 1)):
            raise ValueError("specular_size: %d is not a power of two in 16 .. 1024 (or 0 = 128)" % size)
        d.specular_size = size
        d.specular_samples = c_int(specular_samples, "specular_samples", 0, 4096)
        self._logger = logger()
        d.logger = self._logger
        out = ctypes.c_void_p()
        err = N.mvr_error()
        check_created(N.C.mvr_environment_create(ctypes.byref(d), ctypes.byref(out), ctypes.byref(err)), err,
                      "mvr_environment_create")
        self._handle = out.value

    @property
    @locked
    def intensity(self) -> float:
        """The multiplier of the radiance (> 0)."""
        return float(N.C.mvr_environment_intensity(self.handle))

    @intensity.setter
    @locked
    def intensity(self, value: float) -> None:
        N.C.mvr_environment_set_intensity(self.handle, _intensity(value))

    @property
    @locked
    def rotation(self) -> float:
        """The turn about +Y, in degrees."""
        return float(N.C.mvr_environment_rotation(self.handle))

    @rotation.setter
    @locked
    def rotation(self, degrees: float) -> None:
        N.C.mvr_environment_set_rotation(self.handle, c_float(degrees, "rotation"))

    def __repr__(self) -> str:
        if self.closed:
            return "Environment(%s, closed)" % self.source
        return "Environment(%s, intensity=%g, rotation=%g)" % (self.source, self.intensity, self.rotation)

    @classmethod
    def from_file(cls, path: PathArg, **kwargs: Any) -> "Environment":
        """An equirectangular .hdr / .exr (or any image OpenImageIO reads);
        kwargs as Environment's (intensity, rotation, ...)."""
        if N.C.mvr_image_read is None:
            raise Error("this mvr was built without image I/O (libmvr_image.so)", "MVR_ERROR_UNSUPPORTED")
        img = N.out(N.mvr_image_data)
        err = N.mvr_error()
        check_created(N.C.mvr_image_read(c_path(path, "path"), N.PIXEL_TYPE("f32"), ctypes.byref(img),
                                         ctypes.byref(err)), err, "mvr_image_read")
        try:
            count = img.width * img.height * 4
            pixels = np.ctypeslib.as_array(ctypes.cast(img.pixels, ctypes.POINTER(ctypes.c_float)), (count,))
            pixels = pixels.reshape(img.height, img.width, 4).copy()
        finally:
            N.C.mvr_image_free(ctypes.byref(img))
        return cls("pixels", pixels=pixels, **kwargs)

    def _destroy(self, handle: int) -> None:
        N.C.mvr_environment_destroy(handle)


def _intensity(value: Any) -> float:
    # > 0: the library reads 0 as 1; None (environment=None) is how to turn the light off
    return c_float(value, "intensity", 0.0, lo_open=True)
