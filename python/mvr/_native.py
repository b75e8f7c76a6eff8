"""ctypes mirrors of mvr's C structs, enums and functions (include/mvr/*.h).

Field names and order are the C ones, enums are c_int, bool is c_bool.
tests/python/test_layout.py compares every struct's size and every field's
offset and size, and every enum value used here, with what a C program
compiled against the headers prints (tests/python/py_reference.c), so a C
struct that grows without this file fails the tests.

Structs the library writes (out-parameters) are given to it inside a zeroed
buffer with slack (`out`), and so are descriptors (`desc`): a library whose
structs grew past these mirrors then writes into the slack, and reads its new
trailing fields as zero, their default, instead of past the end of memory.
"""
import ctypes
from typing import Any, Dict, List, Optional, Sequence, Tuple
from ctypes import (POINTER, Structure, c_bool, c_char, c_char_p, c_double, c_float, c_int, c_int32, c_size_t,
                    c_uint8, c_uint16, c_uint32, c_uint64, c_void_p, CFUNCTYPE)

from . import _lib

# ---------------------------------------------------------------- enums


class Enum:
    """A C enum: Python names (lower case) to C constants and their values."""

    def __init__(self, c_type: str, members: Sequence[Tuple[Optional[str], str]]) -> None:
        self.c_type = c_type
        self.values: Dict[str, int] = {}   # python name -> int
        self.c_names: Dict[str, str] = {}  # python name -> C constant name
        for value, (py, c) in enumerate(members):
            if py is not None:
                self.values[py] = value
                self.c_names[py] = c

    def __call__(self, name: Any, what: Optional[str] = None) -> int:
        """The C value of a name (or of a valid int); ValueError naming `what`."""
        if isinstance(name, int) and not isinstance(name, bool):
            if name in self.values.values():
                return name
        elif isinstance(name, str) and name.lower() in self.values:
            return self.values[name.lower()]
        raise ValueError("%s: %r is not one of %s" % (what or self.c_type, name, ", ".join(self.values)))

    def name(self, value: int) -> str:
        """The Python name of a C value (str(value) for an unknown one)."""
        for k, v in self.values.items():
            if v == value:
                return k
        return str(value)


def _seq(c_type: str, prefix: str, names: List[str]) -> Enum:
    return Enum(c_type, [(n, prefix + n.upper()) for n in names])


RESULT = Enum("mvr_result", [("ok", "MVR_OK")] + [(n, "MVR_ERROR_" + n.upper()) for n in (
    "invalid_argument", "out_of_memory", "unsupported", "no_display", "context", "gl", "shader", "framebuffer",
    "io", "parse", "invalid_asset", "internal")])
LOG_LEVEL = _seq("mvr_log_level", "MVR_LOG_", ["default", "error", "warning", "info", "debug"])
LOG_ID = _seq("mvr_log_id", "MVR_LOG_ID_", ["general", "error_result", "context", "provider_fallback",
                                           "extension_dropped", "driver_bug", "gl_debug", "gl_error", "shader"])
PROVIDER = _seq("mvr_context_provider", "MVR_CONTEXT_PROVIDER_",
                ["default", "surfaceless", "device", "pbuffer", "osmesa", "external"])
GL_API = _seq("mvr_gl_api", "MVR_GL_API_", ["default", "gles", "desktop"])
ALPHA_MODE = _seq("mvr_alpha_mode", "MVR_ALPHA_", ["opaque", "mask", "blend"])
PRIMITIVE_MODE = _seq("mvr_primitive_mode", "MVR_PRIMITIVE_", ["triangles", "lines", "points"])
LIGHT_TYPE = _seq("mvr_light_type", "MVR_LIGHT_", ["directional", "point", "spot"])
PROJECTION_TYPE = _seq("mvr_projection_type", "MVR_PROJECTION_", ["perspective", "frustum", "orthographic", "matrix"])
FILTER = _seq("mvr_filter", "MVR_FILTER_", ["default", "nearest", "linear", "nearest_mipmap_nearest",
                                             "linear_mipmap_nearest", "nearest_mipmap_linear",
                                             "linear_mipmap_linear"])
WRAP = _seq("mvr_wrap", "MVR_WRAP_", ["default", "repeat", "clamp_to_edge", "mirrored_repeat"])
ANIMATION_WRAP = Enum("mvr_animation_wrap", [("clamp", "MVR_ANIMATION_CLAMP"), ("loop", "MVR_ANIMATION_LOOP")])
ENV_SOURCE = Enum("mvr_environment_source", [("neutral", "MVR_ENVIRONMENT_NEUTRAL"),
                                             ("pixels", "MVR_ENVIRONMENT_PIXELS"),
                                             ("uniform", "MVR_ENVIRONMENT_UNIFORM")])
VIEW_PATH = _seq("mvr_view_path", "MVR_VIEW_PATH_", ["auto", "multiview", "loop"])
MATERIAL_PATH = _seq("mvr_material_path", "MVR_MATERIAL_PATH_", ["auto", "arrays", "per_material", "per_draw"])
SKINNING_PATH = _seq("mvr_skinning_path", "MVR_SKINNING_PATH_", ["auto", "vertex", "preskin"])
DEPTH_MODE = _seq("mvr_depth_mode", "MVR_DEPTH_MODE_", ["auto", "reversed_z", "standard"])
TRANSPARENCY = _seq("mvr_transparency_order", "MVR_TRANSPARENCY_ORDER_", ["auto", "centroid", "per_view"])
TONE_MAP = Enum("mvr_tone_map", [("none", "MVR_TONE_MAP_NONE"), ("aces", "MVR_TONE_MAP_ACES"),
                                 ("pbr_neutral", "MVR_TONE_MAP_KHR_PBR_NEUTRAL")])
COLOR_FORMAT = _seq("mvr_color_format", "MVR_COLOR_FORMAT_", ["default", "rgba8", "rgba16f", "rgba32f"])
ANTI_ALIASING = _seq("mvr_anti_aliasing", "MVR_ANTI_ALIASING_", ["default", "none", "msaa", "supersample", "auto"])
SHADOW_MODE = Enum("mvr_shadow_mode", [("default", "MVR_SHADOWS_DEFAULT"), ("all", "MVR_SHADOWS_ALL"),
                                       ("off", "MVR_SHADOWS_OFF")])
EXPOSURE_MODE = _seq("mvr_exposure_mode", "MVR_EXPOSURE_", ["linear", "ev100", "camera", "auto"])
BACKGROUND = Enum("mvr_background", [("color", "MVR_BACKGROUND_COLOR"), ("environment", "MVR_BACKGROUND_ENVIRONMENT"),
                                     ("blur", "MVR_BACKGROUND_BLUR")])
READBACK = _seq("mvr_readback_format", "MVR_READBACK_", ["rgba8", "rgba32f"])
LAYOUT = _seq("mvr_view_layout", "MVR_LAYOUT_", ["stereo", "cube", "ring", "grid", "sphere", "orbit", "random"])
UP_AXIS = _seq("mvr_up_axis", "MVR_UP_", ["y", "z"])
HEMISPHERE = _seq("mvr_hemisphere", "MVR_HEMISPHERE_", ["full", "upper"])
PIXEL_TYPE = _seq("mvr_pixel_type", "MVR_PIXEL_", ["u8", "f32"])
# per-view outputs (mvr_target_desc.outputs, mvr_renderer_read_output)
OUTPUT = _seq("mvr_output", "MVR_OUTPUT_", ["color", "depth", "distance", "normal", "ids", "coverage"])
NORMAL_SPACE = _seq("mvr_normal_space", "MVR_NORMAL_SPACE_", ["world", "camera"])

ENUMS = [RESULT, LOG_LEVEL, LOG_ID, PROVIDER, GL_API, ALPHA_MODE, PRIMITIVE_MODE, LIGHT_TYPE, PROJECTION_TYPE, FILTER,
         WRAP, ANIMATION_WRAP, ENV_SOURCE, VIEW_PATH, MATERIAL_PATH, SKINNING_PATH, DEPTH_MODE, TRANSPARENCY, TONE_MAP,
         COLOR_FORMAT, ANTI_ALIASING, SHADOW_MODE, EXPOSURE_MODE, BACKGROUND, READBACK, LAYOUT, PIXEL_TYPE, OUTPUT,
         NORMAL_SPACE, UP_AXIS, HEMISPHERE]

# channels and type of each output as read back (mvr_output_pixel_size bytes a pixel)
OUTPUT_PIXEL = {"color": (4, "uint8"), "depth": (1, "float32"), "distance": (1, "float32"),
                "normal": (3, "float32"), "ids": (4, "uint32"), "coverage": (1, "float32")}

ERROR_MESSAGE_SIZE = 512
CAPS_STRING_SIZE = 256
IMAGE_MAX_LEVELS = 15
ANIMATION_ALL = 0xFFFFFFFF
VARIANT_DEFAULT = 0xFFFFFFFF

# ---------------------------------------------------------------- structs

LOG_FN = CFUNCTYPE(None, c_int, c_int, c_char_p, c_void_p)
GET_PROC_FN = CFUNCTYPE(c_void_p, c_char_p, c_void_p)
IS_CURRENT_FN = CFUNCTYPE(c_bool, c_void_p)
GLTF_READ_FN = CFUNCTYPE(c_int, c_char_p, c_uint64, POINTER(c_void_p), POINTER(c_size_t), c_void_p)
GLTF_RELEASE_FN = CFUNCTYPE(None, c_void_p, c_void_p)


class S(Structure):
    """Base of the mirrors: lists its fields for the layout test."""

    @classmethod
    def field_names(cls) -> List[str]:
        return [f[0] for f in cls._fields_]


def _struct(name: str, fields: List[Tuple[str, Any]]) -> Any:
    cls: Any = type(name, (S,), {"_fields_": fields})
    cls.c_name = name  # nested structs: their tag (struct mvr_material_specular)
    return cls


class Id(S):
    """mvr_image_id, mvr_mesh_id, ...: one uint32, 0 = none."""
    _fields_ = [("id", c_uint32)]
    c_name = "mvr_node_id"


mvr_error = _struct("mvr_error", [("result", c_int), ("message", c_char * ERROR_MESSAGE_SIZE)])
mvr_logger = _struct("mvr_logger", [("fn", LOG_FN), ("user_data", c_void_p), ("level", c_int)])
mvr_context_desc = _struct("mvr_context_desc", [
    ("provider", c_int), ("api", c_int), ("device_index", c_int), ("debug", c_bool),
    ("get_proc_address", GET_PROC_FN), ("get_proc_user_data", c_void_p), ("logger", mvr_logger),
    ("is_current", IS_CURRENT_FN), ("is_current_user_data", c_void_p)])
mvr_caps_ext = _struct("mvr_caps_ext", [(n, c_bool) for n in (
    "ovr_multiview", "ovr_multiview2", "ovr_multiview_multisampled_render_to_texture", "ext_clip_control",
    "ext_disjoint_timer_query", "khr_debug", "ext_texture_filter_anisotropic", "ext_color_buffer_float",
    "ext_color_buffer_half_float", "oes_texture_float_linear", "program_binary", "multiview_msaa_array", "etc2",
    "astc_ldr", "s3tc", "rgtc", "bptc")])
mvr_caps_limits = _struct("mvr_caps_limits", [(n, c_int) for n in (
    "max_views_ovr", "max_array_texture_layers", "max_texture_size", "uniform_buffer_offset_alignment",
    "max_uniform_block_size", "max_uniform_buffer_bindings", "max_samples", "max_combined_texture_image_units",
    "max_draw_buffers", "program_binary_formats")] + [("max_anisotropy", c_float)])
mvr_caps_bugs = _struct("mvr_caps_bugs", [(n, c_bool) for n in (
    "timer_query_in_multiview_undefined", "multiview_level_zero_only", "mediump_is_fp16",
    "multiview_pass_defers_raster", "half_float_sampling_slow")])
mvr_caps = _struct("mvr_caps", [
    ("api", c_int), ("gl_major", c_int), ("gl_minor", c_int)] +
    [(n, c_char * CAPS_STRING_SIZE) for n in ("vendor", "renderer", "version", "glsl_version", "egl_vendor",
                                              "egl_version", "egl_device")] +
    [("ext", mvr_caps_ext), ("limits", mvr_caps_limits), ("bugs", mvr_caps_bugs), ("is_software", c_bool)])

mvr_scene_desc = _struct("mvr_scene_desc", [("logger", mvr_logger)])
mvr_image_level = _struct("mvr_image_level", [("data", c_void_p), ("size", c_size_t)])
mvr_image_desc = _struct("mvr_image_desc", [
    ("width", c_uint32), ("height", c_uint32), ("rgba8", POINTER(c_uint8)), ("name", c_char_p), ("format", c_int),
    ("level_count", c_uint32), ("levels", mvr_image_level * IMAGE_MAX_LEVELS)])
mvr_sampler_desc = _struct("mvr_sampler_desc", [("mag_filter", c_int), ("min_filter", c_int),
                                                ("wrap_s", c_int), ("wrap_t", c_int)])
mvr_texture_transform = _struct("mvr_texture_transform", [
    ("enabled", c_bool), ("offset", c_float * 2), ("rotation", c_float), ("scale", c_float * 2)])
mvr_texture_ref = _struct("mvr_texture_ref", [("image", Id), ("sampler", mvr_sampler_desc), ("texcoord", c_uint32),
                                              ("transform", mvr_texture_transform)])
T = mvr_texture_ref
mvr_material_specular = _struct("mvr_material_specular", [
    ("enabled", c_bool), ("factor", c_float), ("color_factor", c_float * 3), ("texture", T), ("color_texture", T)])
mvr_material_clearcoat = _struct("mvr_material_clearcoat", [
    ("factor", c_float), ("roughness_factor", c_float), ("texture", T), ("roughness_texture", T),
    ("normal_texture", T), ("normal_scale", c_float)])
mvr_material_sheen = _struct("mvr_material_sheen", [
    ("color_factor", c_float * 3), ("roughness_factor", c_float), ("color_texture", T), ("roughness_texture", T)])
mvr_material_transmission = _struct("mvr_material_transmission", [("factor", c_float), ("texture", T)])
mvr_material_volume = _struct("mvr_material_volume", [
    ("thickness_factor", c_float), ("thickness_texture", T), ("attenuation_distance", c_float),
    ("attenuation_color", c_float * 3)])
mvr_material_iridescence = _struct("mvr_material_iridescence", [
    ("factor", c_float), ("texture", T), ("ior", c_float), ("thickness_minimum", c_float),
    ("thickness_maximum", c_float), ("thickness_texture", T)])
mvr_material_anisotropy = _struct("mvr_material_anisotropy", [
    ("strength", c_float), ("rotation", c_float), ("texture", T)])
mvr_material_spec_gloss = _struct("mvr_material_spec_gloss", [
    ("enabled", c_bool), ("specular_factor", c_float * 3), ("glossiness_factor", c_float), ("texture", T)])
mvr_material_desc = _struct("mvr_material_desc", [
    ("base_color_factor", c_float * 4), ("metallic_factor", c_float), ("roughness_factor", c_float),
    ("emissive_factor", c_float * 3), ("emissive_strength", c_float), ("normal_scale", c_float),
    ("occlusion_strength", c_float), ("alpha_cutoff", c_float), ("alpha_mode", c_int), ("double_sided", c_bool),
    ("unlit", c_bool), ("base_color", T), ("metallic_roughness", T), ("normal", T), ("occlusion", T),
    ("emissive", T), ("name", c_char_p), ("ior", c_float), ("specular", mvr_material_specular),
    ("clearcoat", mvr_material_clearcoat), ("sheen", mvr_material_sheen),
    ("transmission", mvr_material_transmission), ("volume", mvr_material_volume), ("dispersion", c_float),
    ("iridescence", mvr_material_iridescence), ("anisotropy", mvr_material_anisotropy),
    ("spec_gloss", mvr_material_spec_gloss)])
_pf = POINTER(c_float)
mvr_primitive_desc = _struct("mvr_primitive_desc", [
    ("vertex_count", c_uint32), ("positions", _pf), ("normals", _pf), ("tangents", _pf), ("texcoords0", _pf),
    ("texcoords1", _pf), ("colors", _pf), ("index_count", c_uint32), ("indices16", POINTER(c_uint16)),
    ("indices32", POINTER(c_uint32)), ("mode", c_int), ("material", Id), ("joints0", POINTER(c_uint16)),
    ("weights0", _pf), ("joints1", POINTER(c_uint16)), ("weights1", _pf), ("targets", c_void_p),
    ("target_count", c_uint32)])
mvr_mesh_desc = _struct("mvr_mesh_desc", [
    ("primitives", POINTER(mvr_primitive_desc)), ("primitive_count", c_uint32), ("name", c_char_p),
    ("weights", _pf), ("weight_count", c_uint32)])
mvr_light_desc = _struct("mvr_light_desc", [
    ("type", c_int), ("color", c_float * 3), ("intensity", c_float), ("range", c_float),
    ("inner_cone_angle", c_float), ("outer_cone_angle", c_float), ("cast_shadows", c_bool), ("layers", c_uint32)])
mvr_projection = _struct("mvr_projection", [
    ("type", c_int), ("yfov", c_double), ("aspect", c_double), ("angle_left", c_double), ("angle_right", c_double),
    ("angle_down", c_double), ("angle_up", c_double), ("xmag", c_double), ("ymag", c_double), ("znear", c_double),
    ("zfar", c_double), ("matrix", c_double * 16)])
mvr_node_desc = _struct("mvr_node_desc", [
    ("parent", Id), ("translation", c_double * 3), ("rotation", c_double * 4), ("scale", c_double * 3),
    ("use_matrix", c_bool), ("matrix", c_double * 16), ("mesh", Id), ("light", Id), ("camera", Id),
    ("name", c_char_p)])
mvr_animation_info = _struct("mvr_animation_info", [
    ("name", c_char_p), ("start", c_double), ("end", c_double), ("channels", c_uint32), ("samplers", c_uint32)])
mvr_scene_info = _struct("mvr_scene_info", [(n, c_uint32) for n in (
    "images", "materials", "meshes", "primitives", "nodes", "lights", "cameras", "skins", "joints", "animations",
    "morph_targets")] + [("bounds_min", c_double * 3), ("bounds_max", c_double * 3),
                         ("max_light_intensity", c_float * 3)])

mvr_viewport = _struct("mvr_viewport", [("x", c_int32), ("y", c_int32), ("width", c_uint32), ("height", c_uint32)])
mvr_view_desc = _struct("mvr_view_desc", [
    ("position", c_double * 3), ("orientation", c_double * 4), ("projection", mvr_projection),
    ("viewport", mvr_viewport), ("disabled", c_bool), ("light_layers", c_uint32)])
mvr_view_set_desc = _struct("mvr_view_set_desc", [
    ("view_count", c_uint32), ("views", POINTER(mvr_view_desc)), ("origin_set", c_bool), ("origin", c_double * 3)])
mvr_view_camera = _struct("mvr_view_camera", [
    ("width", c_uint32), ("height", c_uint32), ("perspective", c_bool), ("fx", c_double), ("fy", c_double),
    ("cx", c_double), ("cy", c_double), ("projection", c_double * 16), ("world_to_camera", c_double * 16),
    ("camera_to_world", c_double * 16)])
mvr_framing_desc = _struct("mvr_framing_desc", [
    ("layout", c_int), ("views", c_uint32), ("ipd", c_double), ("aspect", c_double), ("rows", c_uint32),
    ("elevation_min", c_double), ("elevation_max", c_double), ("yfov", c_double), ("radius", c_double),
    ("fit_box", c_bool), ("margin", c_double), ("hemisphere", c_int), ("seed", c_uint64), ("min_spacing", c_double),
    ("up", c_int), ("elevation", c_double), ("level", c_bool), ("fit_sphere", c_bool)])

mvr_environment_desc = _struct("mvr_environment_desc", [
    ("source", c_int), ("pixels", _pf), ("width", c_uint32), ("height", c_uint32), ("color", c_float * 3),
    ("intensity", c_float), ("rotation", c_float), ("specular_size", c_uint32), ("specular_samples", c_uint32),
    ("logger", mvr_logger)])

mvr_renderer_overrides = _struct("mvr_renderer_overrides", [
    ("view_path", c_int), ("material_path", c_int), ("depth_mode", c_int), ("culling", c_int),
    ("instancing", c_int), ("msaa_multiview", c_int), ("force_inert_features", c_bool),
    ("ubo_alignment", c_uint32), ("skinning_path", c_int), ("disable_features", c_uint32),
    ("disable_image_formats", c_uint32), ("tuning", c_int), ("anisotropic", c_int)])
mvr_tuning_desc = _struct("mvr_tuning_desc", [("mode", c_int), ("frame_cost", c_void_p), ("user", c_void_p)])
mvr_renderer_desc = _struct("mvr_renderer_desc", [
    ("context", c_void_p), ("view_path", c_int), ("logger", mvr_logger), ("material_path", c_int),
    ("disable_culling", c_bool), ("program_cache_dir", c_char_p), ("disable_instancing", c_bool),
    ("depth_mode", c_int), ("transparency_order", c_int), ("oversized_images", c_int),
    ("overrides", mvr_renderer_overrides), ("skinning_path", c_int), ("tuning", mvr_tuning_desc)])
mvr_target_desc = _struct("mvr_target_desc", [
    ("width", c_uint32), ("height", c_uint32), ("layers", c_uint32), ("color_format", c_int),
    ("external_color_texture", c_uint32), ("external_level", c_uint32), ("external_base_layer", c_uint32),
    ("samples", c_uint32), ("supersample", c_uint32), ("anti_aliasing", c_int), ("outputs", c_uint32)])
mvr_read_desc = _struct("mvr_read_desc", [
    ("first_layer", c_uint32), ("layer_count", c_uint32), ("format", c_int), ("output", c_int)])
mvr_shadow_desc = _struct("mvr_shadow_desc", [
    ("mode", c_int), ("map_size", c_uint32), ("cascades", c_uint32), ("distance", c_double),
    ("slope_bias", c_float), ("constant_bias", c_float), ("normal_bias", c_float)])
mvr_render_desc = _struct("mvr_render_desc", [
    ("clear_color", c_float * 4), ("exposure", c_float), ("tone_map", c_int), ("shadows", mvr_shadow_desc),
    ("exposure_mode", c_int), ("ev100", c_double), ("aperture", c_double), ("shutter", c_double), ("iso", c_double),
    ("exposure_compensation", c_float), ("exposure_key", c_float), ("ev100_min", c_float), ("ev100_max", c_float),
    ("exposure_per_view", c_bool), ("dither", c_bool), ("environment", c_void_p), ("background", c_int),
    ("background_blur", c_float), ("environment_samples", c_uint32), ("normal_space", c_int),
    ("output_alpha_cutoff", c_float)])
mvr_auto_choice = _struct("mvr_auto_choice", [
    ("state", c_int), ("prior", c_int), ("chosen", c_int), ("candidates", c_int * 2), ("samples", c_uint32 * 2),
    ("cost_ms", c_double * 2), ("margin", c_double), ("retunes", c_uint32)])
mvr_auto_skinning_choice = _struct("mvr_auto_skinning_choice", [
    ("state", c_int), ("prior", c_int), ("chosen", c_int), ("candidates", c_int * 2), ("samples", c_uint32 * 2),
    ("cost_ms", c_double * 2), ("margin", c_double), ("retunes", c_uint32)])
mvr_auto_material_choice = _struct("mvr_auto_material_choice", [
    ("state", c_int), ("prior", c_int), ("chosen", c_int), ("candidates", c_int * 2), ("samples", c_uint32 * 2),
    ("cost_ms", c_double * 2), ("margin", c_double), ("retunes", c_uint32)])
mvr_frame_stats = _struct("mvr_frame_stats", [
    ("view_path", c_int), ("views", c_uint32), ("passes", c_uint32), ("multiview_passes", c_uint32),
    ("draws", c_uint32), ("draw_calls", c_uint32), ("instanced_draw_calls", c_uint32), ("program_binds", c_uint32),
    ("texture_binds", c_uint32), ("ubo_range_binds", c_uint32), ("upload_bytes", c_uint64),
    ("view_upload_bytes", c_uint64), ("compacted_bytes", c_uint64), ("programs_compiled", c_uint32),
    ("program_cache_hits", c_uint32), ("program_binary_loads", c_uint32), ("program_binary_rejects", c_uint32),
    ("depth_mode", c_int), ("transparency_order", c_int), ("blend_diverged_chunks", c_uint32),
    ("blend_fallback_passes", c_uint32), ("material_path", c_int), ("texture_groups", c_uint32),
    ("culled", c_uint32), ("sanitized", c_uint32), ("samples", c_uint32), ("anti_aliasing", c_int),
    ("msaa_multiview", c_bool), ("resolves", c_uint32), ("supersample", c_uint32), ("sub_passes", c_uint32 * 3),
    ("shadow_passes", c_uint32), ("shadow_layers", c_uint32), ("shadow_draws", c_uint32),
    ("exposure_mode", c_int), ("exposure_ev100", c_double), ("tone_mapper", c_int), ("post_passes", c_uint32),
    ("luminance_passes", c_uint32), ("env_prefilter_passes", c_uint32), ("env_prefilter_ms", c_double),
    ("background_draws", c_uint32), ("cpu_ms", c_double), ("gpu_ms", c_double), ("images_downscaled", c_uint32),
    ("joints", c_uint32), ("skinning_path", c_int), ("morph_targets_active", c_uint32),
    ("animation_upload_bytes", c_uint64), ("preskin_passes", c_uint32), ("transmission_copies", c_uint32),
    ("transmission_bytes", c_uint64), ("images_compressed", c_uint32), ("images_unsampleable", c_uint32),
    ("outputs", c_uint32), ("output_blend_passes", c_uint32), ("exposure_measured_views", c_uint32),
    ("exposure_log2_luminance", c_double), ("auto_choice", mvr_auto_choice),
    ("auto_skinning", mvr_auto_skinning_choice), ("auto_material", mvr_auto_material_choice)])

# mvr_gltf.h
mvr_gltf_file_access = _struct("mvr_gltf_file_access", [
    ("allowed_root", c_char_p), ("read", GLTF_READ_FN), ("release", GLTF_RELEASE_FN), ("user_data", c_void_p)])
mvr_gltf_options = _struct("mvr_gltf_options", [
    ("scene", c_uint32), ("base_dir", c_char_p), ("max_file_bytes", c_uint64), ("max_vertices", c_uint64),
    ("max_indices", c_uint64), ("max_image_dimension", c_uint32), ("max_nodes", c_uint32), ("logger", mvr_logger),
    ("memory_budget", c_uint64), ("max_images", c_uint32), ("file_access", mvr_gltf_file_access),
    ("strict", c_bool)])
mvr_gltf_info = _struct("mvr_gltf_info", [
    ("warnings", c_uint32), ("camera_nodes", c_uint32), ("images_missing", c_uint32), ("images_decoded", c_uint32),
    ("buffers_read", c_uint32), ("memory_budget", c_uint64), ("memory_peak", c_uint64),
    ("json_bytes_estimate", c_uint64), ("animation_channels_ignored", c_uint32),
    ("images_occlusion_packed", c_uint32)])
# mvr_image.h
mvr_image_data = _struct("mvr_image_data", [("width", c_uint32), ("height", c_uint32), ("type", c_int),
                                            ("pixels", c_void_p)])

STRUCTS = [Id, mvr_error, mvr_logger, mvr_context_desc, mvr_caps_ext, mvr_caps_limits, mvr_caps_bugs, mvr_caps,
           mvr_scene_desc, mvr_image_level, mvr_image_desc, mvr_sampler_desc, mvr_texture_transform,
           mvr_texture_ref, mvr_material_specular, mvr_material_clearcoat, mvr_material_sheen,
           mvr_material_transmission, mvr_material_volume, mvr_material_iridescence, mvr_material_anisotropy,
           mvr_material_spec_gloss, mvr_material_desc, mvr_primitive_desc, mvr_mesh_desc, mvr_light_desc,
           mvr_projection, mvr_node_desc, mvr_animation_info, mvr_scene_info, mvr_viewport, mvr_view_desc,
           mvr_view_set_desc, mvr_view_camera, mvr_framing_desc, mvr_environment_desc, mvr_renderer_overrides,
           mvr_renderer_desc, mvr_target_desc, mvr_read_desc, mvr_shadow_desc, mvr_render_desc, mvr_frame_stats,
           mvr_gltf_file_access, mvr_gltf_options, mvr_gltf_info, mvr_image_data]

_SLACK = 4096


def out(cls: Any) -> Any:
    """A zeroed struct inside a buffer with slack (see the module's doc)."""
    buf = (c_uint8 * (ctypes.sizeof(cls) + _SLACK))()
    s = cls.from_buffer(buf)
    s._mvr_buffer = buf  # keeps the memory alive with the struct
    return s


desc = out

# ---------------------------------------------------------------- functions

P = c_void_p
PP = POINTER(c_void_p)
PE = POINTER(mvr_error)
R = c_int  # mvr_result


class _Functions:
    """The C functions, declared below (None where the library lacks one)."""

    def __getattr__(self, name: str) -> Any:  # for the type checker: set dynamically by _decl
        raise AttributeError(name)


C = _Functions()


def _decl(lib: Any, name: str, restype: Any, *args: Any) -> None:
    setattr(C, name, _lib.fn(lib, name, restype, *args))


core = _lib.core
_decl(core, "mvr_result_name", c_char_p, c_int)
_decl(core, "mvr_context_create", R, POINTER(mvr_context_desc), PP, PE)
_decl(core, "mvr_context_destroy", None, P)
_decl(core, "mvr_context_make_current", R, P)
_decl(core, "mvr_context_release_current", R, P)  # None in a libmvr older than it
_decl(core, "mvr_context_last_error", c_char_p, P)
_decl(core, "mvr_context_caps", POINTER(mvr_caps), P)
_decl(core, "mvr_context_get_provider", c_int, P)
_decl(core, "mvr_context_provider_name", c_char_p, c_int)
_decl(core, "mvr_scene_create", R, POINTER(mvr_scene_desc), PP, PE)
_decl(core, "mvr_scene_destroy", None, P)
_decl(core, "mvr_scene_last_error", c_char_p, P)
_decl(core, "mvr_scene_add_image", R, P, POINTER(mvr_image_desc), POINTER(Id))
_decl(core, "mvr_material_defaults", mvr_material_desc)
_decl(core, "mvr_scene_add_material", R, P, POINTER(mvr_material_desc), POINTER(Id))
_decl(core, "mvr_scene_add_mesh", R, P, POINTER(mvr_mesh_desc), POINTER(Id))
_decl(core, "mvr_scene_add_light", R, P, POINTER(mvr_light_desc), POINTER(Id))
_decl(core, "mvr_scene_add_camera", R, P, POINTER(mvr_projection), POINTER(Id))
_decl(core, "mvr_scene_add_node", R, P, POINTER(mvr_node_desc), POINTER(Id))
_decl(core, "mvr_scene_set_node_transform", R, P, Id, POINTER(c_double), POINTER(c_double), POINTER(c_double))
_decl(core, "mvr_scene_set_ambient", None, P, POINTER(c_float))
_decl(core, "mvr_scene_get_info", None, P, POINTER(mvr_scene_info))
_decl(core, "mvr_scene_camera_node_count", c_uint32, P)
_decl(core, "mvr_scene_camera_node", Id, P, c_uint32)
_decl(core, "mvr_scene_animation_count", c_uint32, P)
_decl(core, "mvr_scene_get_animation_info", R, P, c_uint32, POINTER(mvr_animation_info))
_decl(core, "mvr_scene_find_animation", R, P, c_char_p, POINTER(c_uint32))
_decl(core, "mvr_scene_apply_animation", R, P, c_uint32, c_double, c_int)
_decl(core, "mvr_scene_reset_pose", None, P)
_decl(core, "mvr_scene_variant_count", c_uint32, P)
_decl(core, "mvr_scene_variant_name", c_char_p, P, c_uint32)
_decl(core, "mvr_scene_find_variant", R, P, c_char_p, POINTER(c_uint32))
_decl(core, "mvr_scene_select_variant", R, P, c_uint32)
_decl(core, "mvr_scene_selected_variant", c_uint32, P)
_decl(core, "mvr_view_set_create", R, POINTER(mvr_view_set_desc), PP, PE)
_decl(core, "mvr_view_set_destroy", None, P)
_decl(core, "mvr_view_set_count", c_uint32, P)
_decl(core, "mvr_view_set_get_camera", R, P, c_uint32, c_uint32, c_uint32, POINTER(mvr_view_camera))
_decl(core, "mvr_view_set_last_error", c_char_p, P)
_decl(core, "mvr_view_set_frame_scene", R, P, POINTER(mvr_framing_desc), PP, PE)
_decl(core, "mvr_view_set_from_camera", R, P, Id, c_uint32, c_double, PP, PE)
_decl(core, "mvr_environment_create", R, POINTER(mvr_environment_desc), PP, PE)
_decl(core, "mvr_environment_destroy", None, P)
_decl(core, "mvr_environment_intensity", c_float, P)
_decl(core, "mvr_environment_rotation", c_float, P)
_decl(core, "mvr_environment_set_intensity", None, P, c_float)
_decl(core, "mvr_environment_set_rotation", None, P, c_float)
_decl(core, "mvr_scene_node_name", c_char_p, P, Id)
_decl(core, "mvr_scene_mesh_name", c_char_p, P, Id)
_decl(core, "mvr_scene_material_name", c_char_p, P, Id)
_decl(core, "mvr_renderer_create", R, POINTER(mvr_renderer_desc), PP, PE)
_decl(core, "mvr_renderer_destroy", None, P)
_decl(core, "mvr_renderer_last_error", c_char_p, P)
_decl(core, "mvr_target_create", R, P, POINTER(mvr_target_desc), PP)
_decl(core, "mvr_target_destroy", None, P)
_decl(core, "mvr_renderer_render", R, P, P, P, P, POINTER(mvr_render_desc))
_decl(core, "mvr_renderer_read_layer", R, P, P, c_uint32, c_int, c_void_p, c_size_t)
_decl(core, "mvr_renderer_get_stats", None, P, POINTER(mvr_frame_stats))
_decl(core, "mvr_render_desc_choose_exposure", None, P, POINTER(mvr_render_desc))
_decl(core, "mvr_view_path_name", c_char_p, c_int)
_decl(core, "mvr_material_path_name", c_char_p, c_int)
_decl(core, "mvr_depth_mode_name", c_char_p, c_int)
_decl(core, "mvr_renderer_read_output", R, P, P, c_uint32, c_int, c_void_p, c_size_t)
_decl(core, "mvr_output_name", c_char_p, c_int)
_decl(core, "mvr_output_pixel_size", c_size_t, c_int)
# asynchronous readback (Context.render_stream)
_decl(core, "mvr_view_set_get_view", R, P, c_uint32, POINTER(mvr_view_desc))
_decl(core, "mvr_view_set_get_origin", R, P, POINTER(c_double))
_decl(core, "mvr_readback_create", R, P, PP)
_decl(core, "mvr_readback_destroy", None, P)
_decl(core, "mvr_renderer_begin_read", R, P, P, POINTER(mvr_read_desc), P)
_decl(core, "mvr_renderer_finish_read", R, P, P, c_void_p, c_size_t)
# mvr_gltf.h, mvr_image.h (None when the build has no glTF / image I/O)
_decl(_lib.gltf, "mvr_gltf_load_file", R, c_char_p, POINTER(mvr_gltf_options), PP, POINTER(mvr_gltf_info), PE)
_decl(_lib.image, "mvr_image_read", R, c_char_p, c_int, POINTER(mvr_image_data), PE)
_decl(_lib.image, "mvr_image_free", None, POINTER(mvr_image_data))


def text(b: Optional[bytes]) -> str:
    """A C string (bytes or NULL) as str."""
    return b.decode("utf-8", "replace") if b else ""


def result_name(r: int) -> str:
    """mvr_result_name(r)."""
    return text(C.mvr_result_name(r))
