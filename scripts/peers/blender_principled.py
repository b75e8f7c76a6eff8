# Writes tests/data/peers/principled.gltf (+ principled.bin and the texture PNGs) with Blender's own
# glTF exporter (Debian's blender package, 3.4.1; exporter 3.4.50), from Principled BSDF materials:
# the material extensions that exporter writes from the Principled BSDF, together in one file.
#
#   blender -b --factory-startup --python scripts/peers/blender_principled.py -- OUT_DIR [TMP_DIR]
#
# What the exporter reads (io_scene_gltf2/blender/exp/gltf2_blender_gather_materials_*.py):
# - KHR_materials_clearcoat: the Principled BSDF's Clearcoat and Clearcoat Roughness; an image
#   texture linked to them (here through a Separate Color node: its Red to Clearcoat, its Green to
#   Clearcoat Roughness) is packed into one texture, clearcoat in R, clearcoat roughness in G, both
#   factors 1.
# - KHR_materials_specular: only from Specular / Specular Tint away from Blender's defaults (0.5, 0):
#   specularColorFactor = 0.08 Specular / F0(IOR) * ((1 - tint) + tint * baseColor / luminance),
#   no specularFactor.
# - KHR_materials_ior: IOR, but only when transmission, volume or specular is also written (an IOR
#   alone, with Specular at 0.5 and no tint, is not exported); Blender's default IOR is 1.45.
# - KHR_materials_transmission: Transmission.
# - KHR_materials_volume: only with transmission, and only from a "glTF Material Output" node group
#   whose Thickness input is not 0 (thicknessFactor); attenuationColor and attenuationDistance
#   (1 / Density) from a Volume Absorption node on the material output's Volume.
# - KHR_materials_emissive_strength: Emission x Emission Strength; when a component exceeds 1 the
#   exporter divides emissiveFactor by the largest and writes it as emissiveStrength. With an
#   emission texture the factor is (1, 1, 1) x strength.
#
# The model (Blender: +Z up, the camera on -Y looking +Y; glTF: +Y up), smooth UV spheres (48 x 24
# segments, radius 0.45) unless said otherwise:
# - top left "clearcoat": red dielectric base (0.6, 0.06, 0.04), roughness 0.5; clearcoat and
#   clearcoat roughness from principled_clearcoat.png (64 x 64, Non-Color): R = soft stripes across
#   u (0 .. 1), G = soft stripes across v (0.05 .. 0.45).
# - top middle "specular_tint": dark blue base (0.04, 0.08, 0.25), roughness 0.3, Specular 0.8,
#   Specular Tint 1 (KHR_materials_specular with a specularColorFactor above 1, and ior 1.45).
# - top right "ior": grey base (0.18, 0.18, 0.18), roughness 0.2, IOR 1.8 and Specular 0.08 / 0.08 x
#   F0(1.8) (the Specular that matches that IOR): KHR_materials_ior 1.8 with specularColorFactor 1.
# - bottom left "emissive": a smooth torus, near-black base (0.02), roughness 0.4, emission from
#   principled_emission.png (64 x 64, sRGB: soft coloured bands, at most about 0.27 linear) with
#   Emission Strength 2.5 (KHR_materials_emissive_strength 2.5, emissiveFactor (1, 1, 1)).
# - bottom right "glass": radius 0.5, white base, roughness 0, Transmission 1, IOR 1.45; glTF
#   Material Output Thickness 1.0 (the diameter); Volume Absorption colour (0.95, 0.55, 0.25),
#   density 1.25 (attenuationDistance 0.8). Behind it (0.9 further back) "backdrop": a 2 x 1.6
#   plane facing the camera, roughness 0.8, base colour principled_backdrop.png (64 x 64, sRGB,
#   smooth colour gradients), so that the refraction shows.
# One perspective camera (aspect 1). No lights. Nothing random.
import math
import os
import sys

import bpy
from mathutils import Vector

argv = sys.argv[sys.argv.index('--') + 1:] if '--' in sys.argv else []
out_dir = os.path.abspath(argv[0] if argv else os.path.join(os.path.dirname(__file__), '..', '..',
                                                             'tests', 'data', 'peers'))
tmp_dir = os.path.abspath(argv[1] if len(argv) > 1 else out_dir)
SIZE = 256
TEX = 64

for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj, do_unlink=True)
for mat in list(bpy.data.materials):
    bpy.data.materials.remove(mat)
scene = bpy.context.scene
scene.render.resolution_x = SIZE
scene.render.resolution_y = SIZE
scene.render.resolution_percentage = 100


def soft(t):
    """0 .. 1 .. 0 over one period, smooth (no sharp edges to refract or to sample a texel over)"""
    return 0.5 - 0.5 * math.cos(2.0 * math.pi * t)


def make_image(name, fn, colorspace):
    pixels = []
    for y in range(TEX):
        for x in range(TEX):
            u, v = (x + 0.5) / TEX, (y + 0.5) / TEX
            pixels += list(fn(u, v)) + [1.0]
    img = bpy.data.images.new(name, TEX, TEX, alpha=False)
    img.colorspace_settings.name = colorspace
    img.pixels.foreach_set(pixels)
    img.filepath_raw = os.path.join(tmp_dir, name + '.png')
    img.file_format = 'PNG'
    img.save()
    return img


# R: clearcoat, 4 soft stripes across u; G: clearcoat roughness 0.05 .. 0.45, 3 soft stripes across v
clearcoat_img = make_image('principled_clearcoat',
                           lambda u, v: (soft(4.0 * u), 0.05 + 0.4 * soft(3.0 * v), 0.0), 'Non-Color')
# soft coloured bands (sRGB-encoded values, at most 0.57: about 0.27 linear)
emission_img = make_image('principled_emission',
                          lambda u, v: (0.57 * soft(3.0 * u), 0.45 * soft(3.0 * u + 0.33), 0.57 * soft(2.0 * v)),
                          'sRGB')
backdrop_img = make_image('principled_backdrop',
                          lambda u, v: (0.15 + 0.75 * soft(1.5 * u), 0.15 + 0.7 * soft(1.5 * v + 0.25),
                                        0.2 + 0.5 * soft(u + v)),
                          'sRGB')


def principled_material(name, base, roughness):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    bsdf = mat.node_tree.nodes['Principled BSDF']
    bsdf.inputs['Base Color'].default_value = base + (1.0,)
    bsdf.inputs['Roughness'].default_value = roughness
    bsdf.inputs['Metallic'].default_value = 0.0
    return mat, bsdf


def image_node(mat, img):
    tex = mat.node_tree.nodes.new('ShaderNodeTexImage')
    tex.image = img
    tex.interpolation = 'Linear'
    return tex


def sphere(name, location, mat, radius=0.45):
    bpy.ops.mesh.primitive_uv_sphere_add(segments=48, ring_count=24, radius=radius, location=location)
    obj = bpy.context.active_object
    obj.name = name
    obj.data.name = name
    bpy.ops.object.shade_smooth()
    obj.data.materials.append(mat)
    return obj


TOP, BOTTOM = 0.58, -0.58

# clearcoat and clearcoat roughness from one texture (R and G)
mat, bsdf = principled_material('clearcoat', (0.6, 0.06, 0.04), 0.5)
tex = image_node(mat, clearcoat_img)
sep = mat.node_tree.nodes.new('ShaderNodeSeparateColor')
mat.node_tree.links.new(tex.outputs['Color'], sep.inputs['Color'])
mat.node_tree.links.new(sep.outputs['Red'], bsdf.inputs['Clearcoat'])
mat.node_tree.links.new(sep.outputs['Green'], bsdf.inputs['Clearcoat Roughness'])
sphere('clearcoat', (-1.15, 0.0, TOP), mat)

# a tinted specular
mat, bsdf = principled_material('specular_tint', (0.04, 0.08, 0.25), 0.3)
bsdf.inputs['Specular'].default_value = 0.8
bsdf.inputs['Specular Tint'].default_value = 1.0
sphere('specular_tint', (0.0, 0.0, TOP), mat)

# IOR 1.8, with the Specular that matches it (Blender's dielectric F0 is 0.08 Specular)
IOR = 1.8
mat, bsdf = principled_material('ior', (0.18, 0.18, 0.18), 0.2)
bsdf.inputs['IOR'].default_value = IOR
bsdf.inputs['Specular'].default_value = ((IOR - 1.0) / (IOR + 1.0)) ** 2 / 0.08
sphere('ior', (1.15, 0.0, TOP), mat)

# emission texture x strength 2.5
mat, bsdf = principled_material('emissive', (0.02, 0.02, 0.02), 0.4)
tex = image_node(mat, emission_img)
mat.node_tree.links.new(tex.outputs['Color'], bsdf.inputs['Emission'])
bsdf.inputs['Emission Strength'].default_value = 2.5
bpy.ops.mesh.primitive_torus_add(major_segments=64, minor_segments=24, major_radius=0.36, minor_radius=0.16,
                                 location=(-0.95, 0.0, BOTTOM), rotation=(math.radians(60.0), 0.0, 0.0))
torus = bpy.context.active_object
torus.name = 'emissive'
torus.data.name = 'emissive'
bpy.ops.object.shade_smooth()
torus.data.materials.append(mat)

# glass: transmission, volume (thickness from the glTF Material Output group, absorption node)
mat, bsdf = principled_material('glass', (1.0, 1.0, 1.0), 0.0)
bsdf.inputs['Transmission'].default_value = 1.0
bsdf.inputs['IOR'].default_value = 1.45
group = bpy.data.node_groups.new('glTF Material Output', 'ShaderNodeTree')
group.inputs.new('NodeSocketFloat', 'Occlusion')
group.inputs.new('NodeSocketFloat', 'Thickness').default_value = 0.0
group.nodes.new('NodeGroupOutput')
group.nodes.new('NodeGroupInput')
gltf_settings = mat.node_tree.nodes.new('ShaderNodeGroup')
gltf_settings.node_tree = group
gltf_settings.inputs['Thickness'].default_value = 1.0
absorption = mat.node_tree.nodes.new('ShaderNodeVolumeAbsorption')
absorption.inputs['Color'].default_value = (0.95, 0.55, 0.25, 1.0)
absorption.inputs['Density'].default_value = 1.25
mat.node_tree.links.new(absorption.outputs['Volume'], mat.node_tree.nodes['Material Output'].inputs['Volume'])
sphere('glass', (0.75, 0.0, BOTTOM), mat, radius=0.5)

# a coloured backdrop behind the glass
mat, bsdf = principled_material('backdrop', (1.0, 1.0, 1.0), 0.8)
tex = image_node(mat, backdrop_img)
mat.node_tree.links.new(tex.outputs['Color'], bsdf.inputs['Base Color'])
bpy.ops.mesh.primitive_plane_add(size=1.0, location=(0.75, 0.9, BOTTOM), rotation=(math.radians(90.0), 0.0, 0.0))
plane = bpy.context.active_object
plane.name = 'backdrop'
plane.data.name = 'backdrop'
plane.scale = (2.0, 1.6, 1.0)
plane.data.materials.append(mat)

cam_data = bpy.data.cameras.new('camera')
cam_data.lens = 50.0
cam_data.sensor_width = 36.0
cam_data.sensor_fit = 'AUTO'
cam_data.clip_start = 0.1
cam_data.clip_end = 100.0
cam = bpy.data.objects.new('camera', cam_data)
scene.collection.objects.link(cam)
cam.location = (0.05, -5.4, 0.4)
cam.rotation_euler = (Vector((0.05, 0.0, -0.12)) - cam.location).to_track_quat('-Z', 'Y').to_euler()
scene.camera = cam

bpy.ops.export_scene.gltf(
    filepath=os.path.join(out_dir, 'principled.gltf'),
    export_format='GLTF_SEPARATE',
    export_apply=True,
    export_cameras=True,
    export_lights=False,
    export_normals=True,
    export_texcoords=True,
    export_yup=True,
    export_image_format='AUTO',
)
print('wrote', os.path.join(out_dir, 'principled.gltf'))
