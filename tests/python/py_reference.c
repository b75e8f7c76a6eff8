/* The C side of the Python package's tests (tests/python):
 *   py_reference layout
 *       prints sizeof and every field's offset and size of each struct the
 *       package mirrors (python/mvr/_native.py), and the enum values it uses:
 *         S name size / F struct field offset size / E CONSTANT value
 *   py_reference load FILE
 *       loads a glTF file; prints "ok" or the loader's message (exit 1)
 *   py_reference render FILE OUT LAYOUT VIEWS WxH ENV VIEW_PATH [OUTPUTS]
 *       FILE framed by LAYOUT (VIEWS views, aspect W/H), rendered at WxH under
 *       ENV (neutral | none) with the exposure mvr render chooses, the clear
 *       colour (0.1, 0.2, 0.3, 1), VIEW_PATH (auto | multiview | loop); writes
 *       OUT/color_K.bin (the layer's RGBA8 bytes as mvr_renderer_read_layer
 *       gives them: rows bottom to top), OUT/camera_K.txt (mvr_view_camera,
 *       %.17g), and for OUTPUTS (a comma list such as depth,normal,ids)
 *       OUT/<output>_K.bin as mvr_renderer_read_output gives them.
 */
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mvr/mvr.h"
#include "mvr/mvr_gltf.h"
#include "mvr/mvr_image.h"

#define S(T) printf("S %s %zu\n", #T, sizeof(T))
#define SN(name, T) printf("S %s %zu\n", name, sizeof(T))
#define F(T, f) printf("F %s %s %zu %zu\n", #T, #f, offsetof(T, f), sizeof(((T *)0)->f))
#define FN(name, T, f) printf("F %s %s %zu %zu\n", name, #f, offsetof(T, f), sizeof(((T *)0)->f))
#define E(c) printf("E %s %d\n", #c, (int)(c))

typedef struct mvr_material_specular mat_specular;
typedef struct mvr_material_clearcoat mat_clearcoat;
typedef struct mvr_material_sheen mat_sheen;
typedef struct mvr_material_transmission mat_transmission;
typedef struct mvr_material_volume mat_volume;
typedef struct mvr_material_iridescence mat_iridescence;
typedef struct mvr_material_anisotropy mat_anisotropy;
typedef struct mvr_material_spec_gloss mat_spec_gloss;

static void layout_structs(void)
{
    S(mvr_node_id); F(mvr_node_id, id);
    S(mvr_error); F(mvr_error, result); F(mvr_error, message);
    S(mvr_logger); F(mvr_logger, fn); F(mvr_logger, user_data); F(mvr_logger, level);
    S(mvr_context_desc); F(mvr_context_desc, provider); F(mvr_context_desc, api); F(mvr_context_desc, device_index);
    F(mvr_context_desc, debug); F(mvr_context_desc, get_proc_address); F(mvr_context_desc, get_proc_user_data);
    F(mvr_context_desc, logger); F(mvr_context_desc, is_current); F(mvr_context_desc, is_current_user_data);
    S(mvr_caps_ext); F(mvr_caps_ext, ovr_multiview); F(mvr_caps_ext, ovr_multiview2);
    F(mvr_caps_ext, ovr_multiview_multisampled_render_to_texture); F(mvr_caps_ext, ext_clip_control);
    F(mvr_caps_ext, ext_disjoint_timer_query); F(mvr_caps_ext, khr_debug); F(mvr_caps_ext, ext_texture_filter_anisotropic);
    F(mvr_caps_ext, ext_color_buffer_float); F(mvr_caps_ext, ext_color_buffer_half_float); F(mvr_caps_ext, oes_texture_float_linear); F(mvr_caps_ext, program_binary);
    F(mvr_caps_ext, multiview_msaa_array); F(mvr_caps_ext, etc2); F(mvr_caps_ext, astc_ldr); F(mvr_caps_ext, s3tc);
    F(mvr_caps_ext, rgtc); F(mvr_caps_ext, bptc);
    S(mvr_caps_limits); F(mvr_caps_limits, max_views_ovr); F(mvr_caps_limits, max_array_texture_layers);
    F(mvr_caps_limits, max_texture_size); F(mvr_caps_limits, uniform_buffer_offset_alignment);
    F(mvr_caps_limits, max_uniform_block_size); F(mvr_caps_limits, max_uniform_buffer_bindings);
    F(mvr_caps_limits, max_samples); F(mvr_caps_limits, max_combined_texture_image_units);
    F(mvr_caps_limits, max_draw_buffers); F(mvr_caps_limits, program_binary_formats); F(mvr_caps_limits, max_anisotropy);
    S(mvr_caps_bugs); F(mvr_caps_bugs, timer_query_in_multiview_undefined); F(mvr_caps_bugs, multiview_level_zero_only);
    F(mvr_caps_bugs, mediump_is_fp16); F(mvr_caps_bugs, multiview_pass_defers_raster);
    F(mvr_caps_bugs, half_float_sampling_slow);
    S(mvr_caps); F(mvr_caps, api); F(mvr_caps, gl_major); F(mvr_caps, gl_minor); F(mvr_caps, vendor);
    F(mvr_caps, renderer); F(mvr_caps, version); F(mvr_caps, glsl_version); F(mvr_caps, egl_vendor);
    F(mvr_caps, egl_version); F(mvr_caps, egl_device); F(mvr_caps, ext); F(mvr_caps, limits); F(mvr_caps, bugs);
    F(mvr_caps, is_software);
    S(mvr_scene_desc); F(mvr_scene_desc, logger);
    S(mvr_image_level); F(mvr_image_level, data); F(mvr_image_level, size);
    S(mvr_image_desc); F(mvr_image_desc, width); F(mvr_image_desc, height); F(mvr_image_desc, rgba8);
    F(mvr_image_desc, name); F(mvr_image_desc, format); F(mvr_image_desc, level_count); F(mvr_image_desc, levels);
    S(mvr_sampler_desc); F(mvr_sampler_desc, mag_filter); F(mvr_sampler_desc, min_filter); F(mvr_sampler_desc, wrap_s);
    F(mvr_sampler_desc, wrap_t);
    S(mvr_texture_transform); F(mvr_texture_transform, enabled); F(mvr_texture_transform, offset);
    F(mvr_texture_transform, rotation); F(mvr_texture_transform, scale);
    S(mvr_texture_ref); F(mvr_texture_ref, image); F(mvr_texture_ref, sampler); F(mvr_texture_ref, texcoord);
    F(mvr_texture_ref, transform);
    SN("mvr_material_specular", mat_specular); FN("mvr_material_specular", mat_specular, enabled);
    FN("mvr_material_specular", mat_specular, factor); FN("mvr_material_specular", mat_specular, color_factor);
    FN("mvr_material_specular", mat_specular, texture); FN("mvr_material_specular", mat_specular, color_texture);
    SN("mvr_material_clearcoat", mat_clearcoat); FN("mvr_material_clearcoat", mat_clearcoat, factor);
    FN("mvr_material_clearcoat", mat_clearcoat, roughness_factor); FN("mvr_material_clearcoat", mat_clearcoat, texture);
    FN("mvr_material_clearcoat", mat_clearcoat, roughness_texture);
    FN("mvr_material_clearcoat", mat_clearcoat, normal_texture); FN("mvr_material_clearcoat", mat_clearcoat, normal_scale);
    SN("mvr_material_sheen", mat_sheen); FN("mvr_material_sheen", mat_sheen, color_factor);
    FN("mvr_material_sheen", mat_sheen, roughness_factor); FN("mvr_material_sheen", mat_sheen, color_texture);
    FN("mvr_material_sheen", mat_sheen, roughness_texture);
    SN("mvr_material_transmission", mat_transmission); FN("mvr_material_transmission", mat_transmission, factor);
    FN("mvr_material_transmission", mat_transmission, texture);
    SN("mvr_material_volume", mat_volume); FN("mvr_material_volume", mat_volume, thickness_factor);
    FN("mvr_material_volume", mat_volume, thickness_texture); FN("mvr_material_volume", mat_volume, attenuation_distance);
    FN("mvr_material_volume", mat_volume, attenuation_color);
    SN("mvr_material_iridescence", mat_iridescence); FN("mvr_material_iridescence", mat_iridescence, factor);
    FN("mvr_material_iridescence", mat_iridescence, texture); FN("mvr_material_iridescence", mat_iridescence, ior);
    FN("mvr_material_iridescence", mat_iridescence, thickness_minimum);
    FN("mvr_material_iridescence", mat_iridescence, thickness_maximum);
    FN("mvr_material_iridescence", mat_iridescence, thickness_texture);
    SN("mvr_material_anisotropy", mat_anisotropy); FN("mvr_material_anisotropy", mat_anisotropy, strength);
    FN("mvr_material_anisotropy", mat_anisotropy, rotation); FN("mvr_material_anisotropy", mat_anisotropy, texture);
    SN("mvr_material_spec_gloss", mat_spec_gloss); FN("mvr_material_spec_gloss", mat_spec_gloss, enabled);
    FN("mvr_material_spec_gloss", mat_spec_gloss, specular_factor);
    FN("mvr_material_spec_gloss", mat_spec_gloss, glossiness_factor); FN("mvr_material_spec_gloss", mat_spec_gloss, texture);
    S(mvr_material_desc); F(mvr_material_desc, base_color_factor); F(mvr_material_desc, metallic_factor);
    F(mvr_material_desc, roughness_factor); F(mvr_material_desc, emissive_factor); F(mvr_material_desc, emissive_strength);
    F(mvr_material_desc, normal_scale); F(mvr_material_desc, occlusion_strength); F(mvr_material_desc, alpha_cutoff);
    F(mvr_material_desc, alpha_mode); F(mvr_material_desc, double_sided); F(mvr_material_desc, unlit);
    F(mvr_material_desc, base_color); F(mvr_material_desc, metallic_roughness); F(mvr_material_desc, normal);
    F(mvr_material_desc, occlusion); F(mvr_material_desc, emissive); F(mvr_material_desc, name); F(mvr_material_desc, ior);
    F(mvr_material_desc, specular); F(mvr_material_desc, clearcoat); F(mvr_material_desc, sheen);
    F(mvr_material_desc, transmission); F(mvr_material_desc, volume); F(mvr_material_desc, dispersion);
    F(mvr_material_desc, iridescence); F(mvr_material_desc, anisotropy); F(mvr_material_desc, spec_gloss);
    S(mvr_primitive_desc); F(mvr_primitive_desc, vertex_count); F(mvr_primitive_desc, positions);
    F(mvr_primitive_desc, normals); F(mvr_primitive_desc, tangents); F(mvr_primitive_desc, texcoords0);
    F(mvr_primitive_desc, texcoords1); F(mvr_primitive_desc, colors); F(mvr_primitive_desc, index_count);
    F(mvr_primitive_desc, indices16); F(mvr_primitive_desc, indices32); F(mvr_primitive_desc, mode);
    F(mvr_primitive_desc, material); F(mvr_primitive_desc, joints0); F(mvr_primitive_desc, weights0);
    F(mvr_primitive_desc, joints1); F(mvr_primitive_desc, weights1); F(mvr_primitive_desc, targets);
    F(mvr_primitive_desc, target_count);
    S(mvr_mesh_desc); F(mvr_mesh_desc, primitives); F(mvr_mesh_desc, primitive_count); F(mvr_mesh_desc, name);
    F(mvr_mesh_desc, weights); F(mvr_mesh_desc, weight_count);
    S(mvr_light_desc); F(mvr_light_desc, type); F(mvr_light_desc, color); F(mvr_light_desc, intensity);
    F(mvr_light_desc, range); F(mvr_light_desc, inner_cone_angle); F(mvr_light_desc, outer_cone_angle);
    F(mvr_light_desc, cast_shadows); F(mvr_light_desc, layers);
    S(mvr_projection); F(mvr_projection, type); F(mvr_projection, yfov); F(mvr_projection, aspect);
    F(mvr_projection, angle_left); F(mvr_projection, angle_right); F(mvr_projection, angle_down);
    F(mvr_projection, angle_up); F(mvr_projection, xmag); F(mvr_projection, ymag); F(mvr_projection, znear);
    F(mvr_projection, zfar); F(mvr_projection, matrix);
    S(mvr_node_desc); F(mvr_node_desc, parent); F(mvr_node_desc, translation); F(mvr_node_desc, rotation);
    F(mvr_node_desc, scale); F(mvr_node_desc, use_matrix); F(mvr_node_desc, matrix); F(mvr_node_desc, mesh);
    F(mvr_node_desc, light); F(mvr_node_desc, camera); F(mvr_node_desc, name);
    S(mvr_animation_info); F(mvr_animation_info, name); F(mvr_animation_info, start); F(mvr_animation_info, end);
    F(mvr_animation_info, channels); F(mvr_animation_info, samplers);
    S(mvr_scene_info); F(mvr_scene_info, images); F(mvr_scene_info, materials); F(mvr_scene_info, meshes);
    F(mvr_scene_info, primitives); F(mvr_scene_info, nodes); F(mvr_scene_info, lights); F(mvr_scene_info, cameras);
    F(mvr_scene_info, skins); F(mvr_scene_info, joints); F(mvr_scene_info, animations); F(mvr_scene_info, morph_targets);
    F(mvr_scene_info, bounds_min); F(mvr_scene_info, bounds_max); F(mvr_scene_info, max_light_intensity);
    S(mvr_viewport); F(mvr_viewport, x); F(mvr_viewport, y); F(mvr_viewport, width); F(mvr_viewport, height);
    S(mvr_view_desc); F(mvr_view_desc, position); F(mvr_view_desc, orientation); F(mvr_view_desc, projection);
    F(mvr_view_desc, viewport); F(mvr_view_desc, disabled); F(mvr_view_desc, light_layers);
    S(mvr_view_set_desc); F(mvr_view_set_desc, view_count); F(mvr_view_set_desc, views); F(mvr_view_set_desc, origin_set);
    F(mvr_view_set_desc, origin);
    S(mvr_view_camera); F(mvr_view_camera, width); F(mvr_view_camera, height); F(mvr_view_camera, perspective);
    F(mvr_view_camera, fx); F(mvr_view_camera, fy); F(mvr_view_camera, cx); F(mvr_view_camera, cy);
    F(mvr_view_camera, projection); F(mvr_view_camera, world_to_camera); F(mvr_view_camera, camera_to_world);
    S(mvr_framing_desc); F(mvr_framing_desc, layout); F(mvr_framing_desc, views); F(mvr_framing_desc, ipd);
    F(mvr_framing_desc, aspect); F(mvr_framing_desc, rows); F(mvr_framing_desc, elevation_min);
    F(mvr_framing_desc, elevation_max); F(mvr_framing_desc, yfov); F(mvr_framing_desc, radius);
    F(mvr_framing_desc, fit_box); F(mvr_framing_desc, margin); F(mvr_framing_desc, hemisphere);
    F(mvr_framing_desc, seed); F(mvr_framing_desc, min_spacing); F(mvr_framing_desc, up);
    F(mvr_framing_desc, elevation); F(mvr_framing_desc, level); F(mvr_framing_desc, fit_sphere);
    S(mvr_environment_desc); F(mvr_environment_desc, source); F(mvr_environment_desc, pixels);
    F(mvr_environment_desc, width); F(mvr_environment_desc, height); F(mvr_environment_desc, color);
    F(mvr_environment_desc, intensity); F(mvr_environment_desc, rotation); F(mvr_environment_desc, specular_size);
    F(mvr_environment_desc, specular_samples); F(mvr_environment_desc, logger);
    S(mvr_renderer_overrides); F(mvr_renderer_overrides, view_path); F(mvr_renderer_overrides, material_path);
    F(mvr_renderer_overrides, depth_mode); F(mvr_renderer_overrides, culling); F(mvr_renderer_overrides, instancing);
    F(mvr_renderer_overrides, msaa_multiview); F(mvr_renderer_overrides, force_inert_features);
    F(mvr_renderer_overrides, ubo_alignment); F(mvr_renderer_overrides, skinning_path);
    F(mvr_renderer_overrides, disable_features); F(mvr_renderer_overrides, disable_image_formats);
    F(mvr_renderer_overrides, tuning); F(mvr_renderer_overrides, anisotropic);
    S(mvr_tuning_desc); F(mvr_tuning_desc, mode); F(mvr_tuning_desc, frame_cost); F(mvr_tuning_desc, user);
    S(mvr_auto_choice); F(mvr_auto_choice, state); F(mvr_auto_choice, prior); F(mvr_auto_choice, chosen);
    F(mvr_auto_choice, candidates); F(mvr_auto_choice, samples); F(mvr_auto_choice, cost_ms);
    F(mvr_auto_choice, margin); F(mvr_auto_choice, retunes);
    S(mvr_auto_material_choice); F(mvr_auto_material_choice, state); F(mvr_auto_material_choice, prior);
    F(mvr_auto_material_choice, chosen); F(mvr_auto_material_choice, candidates);
    F(mvr_auto_material_choice, samples); F(mvr_auto_material_choice, cost_ms);
    F(mvr_auto_material_choice, margin); F(mvr_auto_material_choice, retunes);
    S(mvr_auto_skinning_choice); F(mvr_auto_skinning_choice, state); F(mvr_auto_skinning_choice, prior);
    F(mvr_auto_skinning_choice, chosen); F(mvr_auto_skinning_choice, candidates);
    F(mvr_auto_skinning_choice, samples); F(mvr_auto_skinning_choice, cost_ms);
    F(mvr_auto_skinning_choice, margin); F(mvr_auto_skinning_choice, retunes);
    S(mvr_renderer_desc); F(mvr_renderer_desc, context); F(mvr_renderer_desc, view_path); F(mvr_renderer_desc, logger);
    F(mvr_renderer_desc, material_path); F(mvr_renderer_desc, disable_culling); F(mvr_renderer_desc, program_cache_dir);
    F(mvr_renderer_desc, disable_instancing); F(mvr_renderer_desc, depth_mode); F(mvr_renderer_desc, transparency_order);
    F(mvr_renderer_desc, oversized_images); F(mvr_renderer_desc, overrides); F(mvr_renderer_desc, skinning_path);
    F(mvr_renderer_desc, tuning);
    S(mvr_target_desc); F(mvr_target_desc, width); F(mvr_target_desc, height); F(mvr_target_desc, layers);
    F(mvr_target_desc, color_format); F(mvr_target_desc, external_color_texture); F(mvr_target_desc, external_level);
    F(mvr_target_desc, external_base_layer); F(mvr_target_desc, samples); F(mvr_target_desc, supersample);
    F(mvr_target_desc, anti_aliasing); F(mvr_target_desc, outputs);
    S(mvr_read_desc); F(mvr_read_desc, first_layer); F(mvr_read_desc, layer_count); F(mvr_read_desc, format);
    F(mvr_read_desc, output);
    S(mvr_shadow_desc); F(mvr_shadow_desc, mode); F(mvr_shadow_desc, map_size); F(mvr_shadow_desc, cascades);
    F(mvr_shadow_desc, distance); F(mvr_shadow_desc, slope_bias); F(mvr_shadow_desc, constant_bias);
    F(mvr_shadow_desc, normal_bias);
    S(mvr_render_desc); F(mvr_render_desc, clear_color); F(mvr_render_desc, exposure); F(mvr_render_desc, tone_map);
    F(mvr_render_desc, shadows); F(mvr_render_desc, exposure_mode); F(mvr_render_desc, ev100);
    F(mvr_render_desc, aperture); F(mvr_render_desc, shutter); F(mvr_render_desc, iso);
    F(mvr_render_desc, exposure_compensation); F(mvr_render_desc, exposure_key); F(mvr_render_desc, ev100_min);
    F(mvr_render_desc, ev100_max); F(mvr_render_desc, exposure_per_view); F(mvr_render_desc, dither);
    F(mvr_render_desc, environment); F(mvr_render_desc, background); F(mvr_render_desc, background_blur);
    F(mvr_render_desc, environment_samples); F(mvr_render_desc, normal_space);
    F(mvr_render_desc, output_alpha_cutoff);
    S(mvr_frame_stats); F(mvr_frame_stats, view_path); F(mvr_frame_stats, views); F(mvr_frame_stats, passes);
    F(mvr_frame_stats, multiview_passes); F(mvr_frame_stats, draws); F(mvr_frame_stats, draw_calls);
    F(mvr_frame_stats, instanced_draw_calls); F(mvr_frame_stats, program_binds); F(mvr_frame_stats, texture_binds);
    F(mvr_frame_stats, ubo_range_binds); F(mvr_frame_stats, upload_bytes); F(mvr_frame_stats, view_upload_bytes);
    F(mvr_frame_stats, compacted_bytes); F(mvr_frame_stats, programs_compiled); F(mvr_frame_stats, program_cache_hits);
    F(mvr_frame_stats, program_binary_loads); F(mvr_frame_stats, program_binary_rejects); F(mvr_frame_stats, depth_mode);
    F(mvr_frame_stats, transparency_order); F(mvr_frame_stats, blend_diverged_chunks);
    F(mvr_frame_stats, blend_fallback_passes); F(mvr_frame_stats, material_path); F(mvr_frame_stats, texture_groups);
    F(mvr_frame_stats, culled); F(mvr_frame_stats, sanitized); F(mvr_frame_stats, samples);
    F(mvr_frame_stats, anti_aliasing); F(mvr_frame_stats, msaa_multiview); F(mvr_frame_stats, resolves);
    F(mvr_frame_stats, supersample); F(mvr_frame_stats, sub_passes); F(mvr_frame_stats, shadow_passes);
    F(mvr_frame_stats, shadow_layers); F(mvr_frame_stats, shadow_draws); F(mvr_frame_stats, exposure_mode);
    F(mvr_frame_stats, exposure_ev100); F(mvr_frame_stats, tone_mapper); F(mvr_frame_stats, post_passes);
    F(mvr_frame_stats, luminance_passes); F(mvr_frame_stats, env_prefilter_passes); F(mvr_frame_stats, env_prefilter_ms);
    F(mvr_frame_stats, background_draws); F(mvr_frame_stats, cpu_ms); F(mvr_frame_stats, gpu_ms);
    F(mvr_frame_stats, images_downscaled); F(mvr_frame_stats, joints); F(mvr_frame_stats, skinning_path);
    F(mvr_frame_stats, morph_targets_active); F(mvr_frame_stats, animation_upload_bytes);
    F(mvr_frame_stats, preskin_passes); F(mvr_frame_stats, transmission_copies); F(mvr_frame_stats, transmission_bytes);
    F(mvr_frame_stats, images_compressed); F(mvr_frame_stats, images_unsampleable); F(mvr_frame_stats, outputs);
    F(mvr_frame_stats, output_blend_passes); F(mvr_frame_stats, exposure_measured_views);
    F(mvr_frame_stats, exposure_log2_luminance); F(mvr_frame_stats, auto_choice);
    F(mvr_frame_stats, auto_skinning);
    F(mvr_frame_stats, auto_material);
    S(mvr_gltf_file_access); F(mvr_gltf_file_access, allowed_root); F(mvr_gltf_file_access, read);
    F(mvr_gltf_file_access, release); F(mvr_gltf_file_access, user_data);
    S(mvr_gltf_options); F(mvr_gltf_options, scene); F(mvr_gltf_options, base_dir); F(mvr_gltf_options, max_file_bytes);
    F(mvr_gltf_options, max_vertices); F(mvr_gltf_options, max_indices); F(mvr_gltf_options, max_image_dimension);
    F(mvr_gltf_options, max_nodes); F(mvr_gltf_options, logger); F(mvr_gltf_options, memory_budget);
    F(mvr_gltf_options, max_images); F(mvr_gltf_options, file_access); F(mvr_gltf_options, strict);
    S(mvr_gltf_info); F(mvr_gltf_info, warnings); F(mvr_gltf_info, camera_nodes); F(mvr_gltf_info, images_missing);
    F(mvr_gltf_info, images_decoded); F(mvr_gltf_info, buffers_read); F(mvr_gltf_info, memory_budget);
    F(mvr_gltf_info, memory_peak); F(mvr_gltf_info, json_bytes_estimate); F(mvr_gltf_info, animation_channels_ignored);
    F(mvr_gltf_info, images_occlusion_packed);
    S(mvr_image_data); F(mvr_image_data, width); F(mvr_image_data, height); F(mvr_image_data, type);
    F(mvr_image_data, pixels);
}

static void layout_enums(void)
{
    E(MVR_OK); E(MVR_ERROR_INVALID_ARGUMENT); E(MVR_ERROR_OUT_OF_MEMORY); E(MVR_ERROR_UNSUPPORTED);
    E(MVR_ERROR_NO_DISPLAY); E(MVR_ERROR_CONTEXT); E(MVR_ERROR_GL); E(MVR_ERROR_SHADER); E(MVR_ERROR_FRAMEBUFFER);
    E(MVR_ERROR_IO); E(MVR_ERROR_PARSE); E(MVR_ERROR_INVALID_ASSET); E(MVR_ERROR_INTERNAL);
    E(MVR_LOG_DEFAULT); E(MVR_LOG_ERROR); E(MVR_LOG_WARNING); E(MVR_LOG_INFO); E(MVR_LOG_DEBUG);
    E(MVR_LOG_ID_GENERAL); E(MVR_LOG_ID_ERROR_RESULT); E(MVR_LOG_ID_CONTEXT); E(MVR_LOG_ID_PROVIDER_FALLBACK);
    E(MVR_LOG_ID_EXTENSION_DROPPED); E(MVR_LOG_ID_DRIVER_BUG); E(MVR_LOG_ID_GL_DEBUG); E(MVR_LOG_ID_GL_ERROR);
    E(MVR_LOG_ID_SHADER);
    E(MVR_CONTEXT_PROVIDER_DEFAULT); E(MVR_CONTEXT_PROVIDER_SURFACELESS); E(MVR_CONTEXT_PROVIDER_DEVICE);
    E(MVR_CONTEXT_PROVIDER_PBUFFER); E(MVR_CONTEXT_PROVIDER_OSMESA); E(MVR_CONTEXT_PROVIDER_EXTERNAL);
    E(MVR_GL_API_DEFAULT); E(MVR_GL_API_GLES); E(MVR_GL_API_DESKTOP);
    E(MVR_ALPHA_OPAQUE); E(MVR_ALPHA_MASK); E(MVR_ALPHA_BLEND);
    E(MVR_PRIMITIVE_TRIANGLES); E(MVR_PRIMITIVE_LINES); E(MVR_PRIMITIVE_POINTS);
    E(MVR_LIGHT_DIRECTIONAL); E(MVR_LIGHT_POINT); E(MVR_LIGHT_SPOT);
    E(MVR_PROJECTION_PERSPECTIVE); E(MVR_PROJECTION_FRUSTUM); E(MVR_PROJECTION_ORTHOGRAPHIC); E(MVR_PROJECTION_MATRIX);
    E(MVR_FILTER_DEFAULT); E(MVR_FILTER_NEAREST); E(MVR_FILTER_LINEAR); E(MVR_FILTER_NEAREST_MIPMAP_NEAREST);
    E(MVR_FILTER_LINEAR_MIPMAP_NEAREST); E(MVR_FILTER_NEAREST_MIPMAP_LINEAR); E(MVR_FILTER_LINEAR_MIPMAP_LINEAR);
    E(MVR_WRAP_DEFAULT); E(MVR_WRAP_REPEAT); E(MVR_WRAP_CLAMP_TO_EDGE); E(MVR_WRAP_MIRRORED_REPEAT);
    E(MVR_ANIMATION_CLAMP); E(MVR_ANIMATION_LOOP);
    E(MVR_ENVIRONMENT_NEUTRAL); E(MVR_ENVIRONMENT_PIXELS); E(MVR_ENVIRONMENT_UNIFORM);
    E(MVR_VIEW_PATH_AUTO); E(MVR_VIEW_PATH_MULTIVIEW); E(MVR_VIEW_PATH_LOOP);
    E(MVR_MATERIAL_PATH_AUTO); E(MVR_MATERIAL_PATH_ARRAYS); E(MVR_MATERIAL_PATH_PER_MATERIAL);
    E(MVR_MATERIAL_PATH_PER_DRAW);
    E(MVR_SKINNING_PATH_AUTO); E(MVR_SKINNING_PATH_VERTEX); E(MVR_SKINNING_PATH_PRESKIN);
    E(MVR_DEPTH_MODE_AUTO); E(MVR_DEPTH_MODE_REVERSED_Z); E(MVR_DEPTH_MODE_STANDARD);
    E(MVR_TRANSPARENCY_ORDER_AUTO); E(MVR_TRANSPARENCY_ORDER_CENTROID); E(MVR_TRANSPARENCY_ORDER_PER_VIEW);
    E(MVR_TONE_MAP_NONE); E(MVR_TONE_MAP_ACES); E(MVR_TONE_MAP_KHR_PBR_NEUTRAL);
    E(MVR_COLOR_FORMAT_DEFAULT); E(MVR_COLOR_FORMAT_RGBA8); E(MVR_COLOR_FORMAT_RGBA16F); E(MVR_COLOR_FORMAT_RGBA32F);
    E(MVR_ANTI_ALIASING_DEFAULT); E(MVR_ANTI_ALIASING_NONE); E(MVR_ANTI_ALIASING_MSAA);
    E(MVR_ANTI_ALIASING_SUPERSAMPLE); E(MVR_ANTI_ALIASING_AUTO);
    E(MVR_SHADOWS_DEFAULT); E(MVR_SHADOWS_ALL); E(MVR_SHADOWS_OFF);
    E(MVR_EXPOSURE_LINEAR); E(MVR_EXPOSURE_EV100); E(MVR_EXPOSURE_CAMERA); E(MVR_EXPOSURE_AUTO);
    E(MVR_BACKGROUND_COLOR); E(MVR_BACKGROUND_ENVIRONMENT); E(MVR_BACKGROUND_BLUR);
    E(MVR_READBACK_RGBA8); E(MVR_READBACK_RGBA32F);
    E(MVR_LAYOUT_STEREO); E(MVR_LAYOUT_CUBE); E(MVR_LAYOUT_RING); E(MVR_LAYOUT_GRID); E(MVR_LAYOUT_SPHERE);
    E(MVR_LAYOUT_ORBIT); E(MVR_LAYOUT_RANDOM); E(MVR_UP_Y); E(MVR_UP_Z); E(MVR_HEMISPHERE_FULL);
    E(MVR_HEMISPHERE_UPPER);
    E(MVR_PIXEL_U8); E(MVR_PIXEL_F32);
    E(MVR_ERROR_MESSAGE_SIZE); E(MVR_CAPS_STRING_SIZE); E(MVR_IMAGE_MAX_LEVELS);
    E(MVR_OUTPUT_COLOR); E(MVR_OUTPUT_DEPTH); E(MVR_OUTPUT_DISTANCE); E(MVR_OUTPUT_NORMAL); E(MVR_OUTPUT_IDS);
    E(MVR_OUTPUT_COVERAGE);
    E(MVR_NORMAL_SPACE_WORLD); E(MVR_NORMAL_SPACE_CAMERA);
}

static int load(const char *path)
{
    mvr_scene *scene = NULL;
    mvr_error err;
    if (mvr_gltf_load_file(path, NULL, &scene, NULL, &err) != MVR_OK) {
        printf("%s\n", err.message);
        return 1;
    }
    mvr_scene_destroy(scene);
    printf("ok\n");
    return 0;
}

static int write_file(const char *dir, const char *name, uint32_t k, const void *data, size_t size)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s_%u.bin", dir, name, k);
    FILE *f = fopen(path, "wb");
    if (!f || fwrite(data, 1, size, f) != size) {
        fprintf(stderr, "py_reference: cannot write %s\n", path);
        if (f)
            fclose(f);
        return 1;
    }
    return fclose(f) != 0;
}

static int write_camera(const char *dir, uint32_t k, const mvr_view_camera *c)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/camera_%u.txt", dir, k);
    FILE *f = fopen(path, "w");
    if (!f)
        return 1;
    fprintf(f, "width %u\nheight %u\nperspective %d\nfx %.17g\nfy %.17g\ncx %.17g\ncy %.17g\n", c->width, c->height,
            (int)c->perspective, c->fx, c->fy, c->cx, c->cy);
    const double *m[3] = {c->projection, c->world_to_camera, c->camera_to_world};
    const char *names[3] = {"projection", "world_to_camera", "camera_to_world"};
    for (int j = 0; j < 3; ++j) {
        fprintf(f, "%s", names[j]);
        for (int i = 0; i < 16; ++i)
            fprintf(f, " %.17g", m[j][i]);
        fprintf(f, "\n");
    }
    return fclose(f) != 0;
}

static int render(int argc, char **argv)
{
    if (argc < 9) {
        fprintf(stderr, "usage: py_reference render FILE OUT LAYOUT VIEWS WxH ENV VIEW_PATH [OUTPUTS]\n");
        return 2;
    }
    const char *file = argv[2], *out = argv[3], *layout = argv[4], *env_name = argv[7], *path = argv[8];
    uint32_t views_n = (uint32_t)strtoul(argv[5], NULL, 10), w = 0, h = 0;
    if (sscanf(argv[6], "%ux%u", &w, &h) != 2 || !w || !h)
        return 2;
    static const char *layouts[] = {"stereo", "cube", "ring", "grid", "sphere", "orbit"};
    mvr_framing_desc fd = {.views = views_n, .aspect = (double)w / (double)h};
    for (int i = 0; i < 6; ++i)
        if (strcmp(layout, layouts[i]) == 0)
            fd.layout = (mvr_view_layout)i;
    mvr_renderer_desc rd = {.view_path = strcmp(path, "loop") == 0        ? MVR_VIEW_PATH_LOOP
                                         : strcmp(path, "multiview") == 0 ? MVR_VIEW_PATH_MULTIVIEW
                                                                          : MVR_VIEW_PATH_AUTO};
    mvr_target_desc td = {.width = w, .height = h, .anti_aliasing = MVR_ANTI_ALIASING_NONE}; /* as test_render.py asks (samples=1) */
    mvr_output outputs[8];
    uint32_t output_count = 0;
    if (argc > 9) {
        char list[256];
        snprintf(list, sizeof list, "%s", argv[9]);
        for (char *tok = strtok(list, ","); tok && output_count < 8; tok = strtok(NULL, ","))
            for (int o = 1; o < MVR_OUTPUT_COUNT; ++o)
                if (strcmp(tok, mvr_output_name((mvr_output)o)) == 0) {
                    outputs[output_count++] = (mvr_output)o;
                    td.outputs |= MVR_OUTPUT_BIT(o);
                }
    }

    int rc = 1;
    mvr_error err;
    mvr_context *ctx = NULL;
    mvr_scene *scene = NULL;
    mvr_view_set *views = NULL;
    mvr_environment *env = NULL;
    mvr_renderer *renderer = NULL;
    mvr_target *target = NULL;
    void *pixels = NULL;
    mvr_context_desc cd = {0};
    if (mvr_context_create(&cd, &ctx, &err) != MVR_OK) {
        fprintf(stderr, "py_reference: %s\n", err.message);
        return 77;
    }
    if (mvr_gltf_load_file(file, NULL, &scene, NULL, &err) != MVR_OK ||
        mvr_view_set_frame_scene(scene, &fd, &views, &err) != MVR_OK) {
        fprintf(stderr, "py_reference: %s\n", err.message);
        goto done;
    }
    mvr_render_desc desc = {.clear_color = {0.1f, 0.2f, 0.3f, 1.0f}, .exposure = 1.0f};
    if (strcmp(env_name, "neutral") == 0) {
        mvr_environment_desc ed = {.source = MVR_ENVIRONMENT_NEUTRAL};
        if (mvr_environment_create(&ed, &env, &err) != MVR_OK) {
            fprintf(stderr, "py_reference: %s\n", err.message);
            goto done;
        }
        desc.environment = env;
    }
    mvr_render_desc_choose_exposure(scene, &desc);
    rd.context = ctx;
    td.layers = mvr_view_set_count(views);
    if (mvr_renderer_create(&rd, &renderer, &err) != MVR_OK) {
        fprintf(stderr, "py_reference: %s\n", err.message);
        goto done;
    }
    if (mvr_target_create(renderer, &td, &target) != MVR_OK ||
        mvr_renderer_render(renderer, scene, views, target, &desc) != MVR_OK) {
        fprintf(stderr, "py_reference: %s\n", mvr_renderer_last_error(renderer));
        goto done;
    }
    size_t most = (size_t)w * h * 16;
    pixels = malloc(most);
    if (!pixels)
        goto done;
    for (uint32_t k = 0; k < td.layers; ++k) {
        mvr_view_camera cam;
        if (mvr_renderer_read_layer(renderer, target, k, MVR_READBACK_RGBA8, pixels, (size_t)w * h * 4) != MVR_OK ||
            write_file(out, "color", k, pixels, (size_t)w * h * 4) ||
            mvr_view_set_get_camera(views, k, w, h, &cam) != MVR_OK || write_camera(out, k, &cam)) {
            fprintf(stderr, "py_reference: layer %u: %s\n", k, mvr_renderer_last_error(renderer));
            goto done;
        }
        for (uint32_t i = 0; i < output_count; ++i) {
            size_t size = (size_t)w * h * mvr_output_pixel_size(outputs[i]);
            if (mvr_renderer_read_output(renderer, target, k, outputs[i], pixels, size) != MVR_OK ||
                write_file(out, mvr_output_name(outputs[i]), k, pixels, size)) {
                fprintf(stderr, "py_reference: layer %u: %s\n", k, mvr_renderer_last_error(renderer));
                goto done;
            }
        }
    }
    rc = 0;
done:
    free(pixels);
    mvr_target_destroy(target);
    mvr_renderer_destroy(renderer);
    mvr_environment_destroy(env);
    mvr_view_set_destroy(views);
    mvr_scene_destroy(scene);
    mvr_context_destroy(ctx);
    return rc;
}

int main(int argc, char **argv)
{
    if (argc >= 2 && strcmp(argv[1], "layout") == 0) {
        layout_structs();
        layout_enums();
        return 0;
    }
    if (argc >= 3 && strcmp(argv[1], "load") == 0)
        return load(argv[2]);
    if (argc >= 2 && strcmp(argv[1], "render") == 0)
        return render(argc, argv);
    fprintf(stderr, "usage: py_reference layout | load FILE | render FILE OUT LAYOUT VIEWS WxH ENV VIEW_PATH [OUTPUTS]\n");
    return 2;
}
