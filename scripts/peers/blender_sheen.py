# Writes tests/data/peers/sheen.gltf (+ sheen.bin, sheen_color.png) with Blender's own glTF exporter
# (Debian's blender package, 3.4: it writes KHR_materials_sheen from a Velvet BSDF in the material,
# its Color as sheenColorFactor / sheenColorTexture and its Sigma as sheenRoughnessFactor):
#
#   blender -b --factory-startup --python scripts/peers/blender_sheen.py -- OUT_DIR [TMP_DIR]
#
# The model: a smooth UV sphere (64 x 32 segments) on the left, a Principled BSDF (dark blue base,
# roughness 0.8, metallic 0) plus a Velvet BSDF (color (1, 0.55, 0.3), sigma 0.35): a sheen
# sphere; a smooth torus on the right, a Principled BSDF (dark red base, roughness 0.6) plus a
# Velvet BSDF whose color is a generated 64 x 64 texture of soft stripes (white and light blue,
# sigma 0.7): cloth-like, with a sheen color texture. One perspective camera (aspect 1). No lights.
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
scene = bpy.context.scene
scene.render.resolution_x = SIZE
scene.render.resolution_y = SIZE
scene.render.resolution_percentage = 100

# the sheen color texture: stripes along u, white to light blue (sRGB-encoded in the PNG)
pixels = []
for y in range(TEX):
    for x in range(TEX):
        t = 0.5 + 0.5 * math.cos(2.0 * math.pi * 4.0 * (x + 0.5) / TEX)
        pixels += [1.0 - 0.6 * t, 1.0 - 0.3 * t, 1.0, 1.0]
img = bpy.data.images.new('sheen_color', TEX, TEX, alpha=False)
img.pixels.foreach_set(pixels)
img.filepath_raw = os.path.join(tmp_dir, 'sheen_color.png')
img.file_format = 'PNG'
img.save()


def sheen_material(name, base, roughness, sheen, sigma, image=None):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes = mat.node_tree.nodes
    links = mat.node_tree.links
    bsdf = nodes['Principled BSDF']
    bsdf.inputs['Base Color'].default_value = base + (1.0,)
    bsdf.inputs['Roughness'].default_value = roughness
    bsdf.inputs['Metallic'].default_value = 0.0
    velvet = nodes.new('ShaderNodeBsdfVelvet')
    velvet.inputs['Color'].default_value = sheen + (1.0,)
    velvet.inputs['Sigma'].default_value = sigma
    if image is not None:
        tex = nodes.new('ShaderNodeTexImage')
        tex.image = image
        links.new(tex.outputs['Color'], velvet.inputs['Color'])
    add = nodes.new('ShaderNodeAddShader')
    links.new(bsdf.outputs['BSDF'], add.inputs[0])
    links.new(velvet.outputs['BSDF'], add.inputs[1])
    links.new(add.outputs['Shader'], nodes['Material Output'].inputs['Surface'])
    return mat


bpy.ops.mesh.primitive_uv_sphere_add(segments=64, ring_count=32, radius=0.9, location=(-1.05, 0.0, 0.0))
sphere = bpy.context.active_object
sphere.name = 'sheen_sphere'
bpy.ops.object.shade_smooth()
sphere.data.materials.append(sheen_material('sheen_sphere', (0.02, 0.04, 0.15), 0.8, (1.0, 0.55, 0.3), 0.35))

bpy.ops.mesh.primitive_torus_add(major_segments=64, minor_segments=24, major_radius=0.7, minor_radius=0.28,
                                 location=(1.05, 0.0, 0.0), rotation=(math.radians(70.0), 0.0, 0.0))
torus = bpy.context.active_object
torus.name = 'sheen_cloth'
bpy.ops.object.shade_smooth()
torus.data.materials.append(sheen_material('sheen_cloth', (0.25, 0.02, 0.03), 0.6, (1.0, 1.0, 1.0), 0.7, img))

cam_data = bpy.data.cameras.new('camera')
cam_data.lens = 50.0
cam_data.sensor_width = 36.0
cam_data.sensor_fit = 'AUTO'
cam_data.clip_start = 0.1
cam_data.clip_end = 100.0
cam = bpy.data.objects.new('camera', cam_data)
scene.collection.objects.link(cam)
cam.location = (0.0, -6.4, 0.9)
cam.rotation_euler = (Vector((0.0, 0.0, 0.0)) - cam.location).to_track_quat('-Z', 'Y').to_euler()
scene.camera = cam

bpy.ops.export_scene.gltf(
    filepath=os.path.join(out_dir, 'sheen.gltf'),
    export_format='GLTF_SEPARATE',
    export_apply=True,
    export_cameras=True,
    export_lights=False,
    export_normals=True,
    export_texcoords=True,
    export_yup=True,
    export_image_format='AUTO',
)
print('wrote', os.path.join(out_dir, 'sheen.gltf'))
