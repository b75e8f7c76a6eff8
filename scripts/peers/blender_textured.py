# Writes tests/data/peers/textured.gltf (+ textured.bin, textured_basecolor.png, textured_normal.png)
# with Blender's own glTF exporter (Debian's blender package):
#
#   blender -b --factory-startup --python scripts/peers/blender_textured.py -- OUT_DIR
#
# The model: Suzanne with one level of subdivision applied, smooth shaded, Blender's own UVs; a
# Principled BSDF (roughness 0.45, metallic 0) whose base colour is a generated 256 x 256 colour
# checker and whose normal comes from a generated 256 x 256 tangent-space normal map of round bumps;
# one perspective camera (aspect 1) looking at it; no lights.
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

# empty scene
for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj, do_unlink=True)
scene = bpy.context.scene
scene.render.resolution_x = SIZE
scene.render.resolution_y = SIZE
scene.render.resolution_percentage = 100


def hsv(h, s, v):
    i = int(h * 6.0) % 6
    f = h * 6.0 - int(h * 6.0)
    p, q, t = v * (1 - s), v * (1 - f * s), v * (1 - (1 - f) * s)
    return [(v, t, p), (q, v, p), (p, v, t), (p, q, v), (t, p, v), (v, p, q)][i]


def make_image(name, pixels, non_color):
    img = bpy.data.images.new(name, SIZE, SIZE, alpha=False)
    if non_color:
        img.colorspace_settings.name = 'Non-Color'
    img.pixels.foreach_set(pixels)
    img.filepath_raw = os.path.join(tmp_dir, name + '.png')
    img.file_format = 'PNG'
    img.save()
    return img


# base colour: an 8 x 8 checker, hue across, light/dark alternating (values are sRGB-encoded in the PNG)
base = []
for y in range(SIZE):
    for x in range(SIZE):
        cx, cy = x * 8 // SIZE, y * 8 // SIZE
        r, g, b = hsv(cx / 8.0, 0.65, 0.95 if (cx + cy) % 2 == 0 else 0.45)
        base += [r, g, b, 1.0]
base_img = make_image('textured_basecolor', base, False)

# normal map: a 4 x 4 grid of round bumps (height h = cos^2 of the distance to the cell centre)
normal = []
cells = 4
for y in range(SIZE):
    for x in range(SIZE):
        fx = (x + 0.5) / SIZE * cells
        fy = (y + 0.5) / SIZE * cells
        dx, dy = fx - math.floor(fx) - 0.5, fy - math.floor(fy) - 0.5
        d = math.hypot(dx, dy)
        if d < 0.4:
            # h = 0.15 cos^2(pi d / 0.8); gradient along (dx, dy)
            g = -0.15 * math.pi / 0.8 * math.sin(2 * math.pi * d / 0.8) * cells
            gx, gy = (g * dx / d, g * dy / d) if d > 1e-6 else (0.0, 0.0)
        else:
            gx = gy = 0.0
        n = Vector((-gx, -gy, 1.0)).normalized()
        normal += [n.x * 0.5 + 0.5, n.y * 0.5 + 0.5, n.z * 0.5 + 0.5, 1.0]
normal_img = make_image('textured_normal', normal, True)

# the model
bpy.ops.mesh.primitive_monkey_add(size=2.0, location=(0.0, 0.0, 0.0))
monkey = bpy.context.active_object
monkey.name = 'Suzanne'
bpy.ops.object.shade_smooth()
mod = monkey.modifiers.new('subdivision', 'SUBSURF')
mod.levels = 1
mod.render_levels = 1

mat = bpy.data.materials.new('textured')
mat.use_nodes = True
nodes = mat.node_tree.nodes
links = mat.node_tree.links
bsdf = nodes['Principled BSDF']
bsdf.inputs['Roughness'].default_value = 0.45
bsdf.inputs['Metallic'].default_value = 0.0
tex = nodes.new('ShaderNodeTexImage')
tex.image = base_img
links.new(tex.outputs['Color'], bsdf.inputs['Base Color'])
ntex = nodes.new('ShaderNodeTexImage')
ntex.image = normal_img
nmap = nodes.new('ShaderNodeNormalMap')
nmap.inputs['Strength'].default_value = 1.0
links.new(ntex.outputs['Color'], nmap.inputs['Color'])
links.new(nmap.outputs['Normal'], bsdf.inputs['Normal'])
monkey.data.materials.append(mat)

# the camera (Blender is +Z up; Suzanne faces -Y)
cam_data = bpy.data.cameras.new('camera')
cam_data.lens = 50.0
cam_data.sensor_width = 36.0
cam_data.sensor_fit = 'AUTO'
cam_data.clip_start = 0.1
cam_data.clip_end = 100.0
cam = bpy.data.objects.new('camera', cam_data)
scene.collection.objects.link(cam)
cam.location = (1.7, -4.3, 1.1)
cam.rotation_euler = (Vector((0.0, 0.0, 0.05)) - cam.location).to_track_quat('-Z', 'Y').to_euler()
scene.camera = cam

bpy.ops.export_scene.gltf(
    filepath=os.path.join(out_dir, 'textured.gltf'),
    export_format='GLTF_SEPARATE',
    export_apply=True,
    export_cameras=True,
    export_lights=False,
    export_tangents=True,
    export_normals=True,
    export_texcoords=True,
    export_yup=True,
    export_image_format='AUTO',
)
print('wrote', os.path.join(out_dir, 'textured.gltf'))
