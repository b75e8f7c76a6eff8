# Writes tests/data/peers/variants.gltf (+ variants.bin) with Blender's own glTF exporter (Debian's
# blender package, 3.4.1; exporter 3.4.50), which writes KHR_materials_variants from its "Material
# Variants" data (the add-on preference KHR_materials_variants_ui, set here):
#
#   blender -b --factory-startup --python scripts/peers/blender_variants.py -- OUT_DIR
#
# The model: one mesh "board", a flat 2 x 1 rectangle facing the camera, split in two quads: the
# left one in material slot 0 ("paint", white), the right one in slot 1 ("frame", grey). The
# exporter makes one glTF primitive per slot. All materials are Principled BSDF, roughness 0.5,
# metallic 0.
# Variants (made in this order): "red", "blue", "ruby". The paint slot maps "red" and "ruby" to the
# material "paint_red" (base colour (0.8, 0.05, 0.05)), "blue" to "paint_blue" ((0.05, 0.05, 0.8));
# the frame slot has no mapping (it keeps "frame" in every variant). The exporter numbers the
# variants in the order the mappings first name them, so the file's variants are "red", "ruby",
# "blue", and its primitive 0 has two mappings: {material paint_red (0), variants [0, 1]} and
# {material paint_blue (1), variants [2]}; primitive 1 has none. Blender also lists the extension
# in extensionsRequired.
# One perspective camera (aspect 1) in front of the board. No lights.
# Nothing random: two runs write the same bytes.
import os
import sys

import bpy
from mathutils import Vector

argv = sys.argv[sys.argv.index('--') + 1:] if '--' in sys.argv else []
out_dir = os.path.abspath(argv[0] if argv else os.path.join(os.path.dirname(__file__), '..', '..',
                                                             'tests', 'data', 'peers'))

# the exporter writes variants only with its Material Variants UI on (it registers the properties)
prefs = bpy.context.preferences.addons['io_scene_gltf2'].preferences
prefs.KHR_materials_variants_ui = True

for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj, do_unlink=True)
scene = bpy.context.scene
scene.render.resolution_x = 256
scene.render.resolution_y = 256
scene.render.resolution_percentage = 100


def material(name, rgb):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    bsdf = mat.node_tree.nodes['Principled BSDF']
    bsdf.inputs['Base Color'].default_value = (rgb[0], rgb[1], rgb[2], 1.0)
    bsdf.inputs['Roughness'].default_value = 0.5
    bsdf.inputs['Metallic'].default_value = 0.0
    return mat


paint = material('paint', (0.8, 0.8, 0.8))
frame = material('frame', (0.3, 0.3, 0.3))
paint_red = material('paint_red', (0.8, 0.05, 0.05))
paint_blue = material('paint_blue', (0.05, 0.05, 0.8))

# the board in Blender's XZ plane (facing -Y, the camera), 2 wide, 1 tall: left quad, right quad
verts = [(-1.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0), (-1.0, 0.0, 1.0),
         (0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (1.0, 0.0, 1.0), (0.0, 0.0, 1.0)]
faces = [(0, 1, 2, 3), (4, 5, 6, 7)]
mesh = bpy.data.meshes.new('board')
mesh.from_pydata(verts, [], faces)
mesh.update()
mesh.materials.append(paint)
mesh.materials.append(frame)
mesh.polygons[0].material_index = 0
mesh.polygons[1].material_index = 1
board = bpy.data.objects.new('board', mesh)
scene.collection.objects.link(board)

# the variants, as the add-on's "Add Material Variant" operator makes them
variants = scene.gltf2_KHR_materials_variants_variants
for i, name in enumerate(('red', 'blue', 'ruby')):
    v = variants.add()
    v.variant_idx = i
    v.name = name

# the paint slot's variant materials, as "Add a new Variant Slot" + "Assign To Variant" make them
for mat, indices in ((paint_red, (0, 2)), (paint_blue, (1,))):
    prim = mesh.gltf2_variant_mesh_data.add()
    prim.material_slot_index = 0
    prim.material = mat
    for idx in indices:
        p = prim.variants.add()
        p.variant.variant_idx = idx
        p.variant.name = variants[idx].name
# the materials the slots have outside any variant ("Assign as Original")
for slot, mat in ((0, paint), (1, frame)):
    d = mesh.gltf2_variant_default_materials.add()
    d.material_slot_index = slot
    d.default_material = mat

# the camera (Blender is +Z up): in front of the board (-Y), looking at its middle
cam_data = bpy.data.cameras.new('camera')
cam_data.lens = 50.0
cam_data.sensor_width = 36.0
cam_data.sensor_fit = 'AUTO'
cam_data.clip_start = 0.1
cam_data.clip_end = 100.0
cam = bpy.data.objects.new('camera', cam_data)
scene.collection.objects.link(cam)
cam.location = (0.0, -3.5, 0.5)
cam.rotation_euler = (Vector((0.0, 0.0, 0.5)) - cam.location).to_track_quat('-Z', 'Y').to_euler()
scene.camera = cam

bpy.ops.export_scene.gltf(
    filepath=os.path.join(out_dir, 'variants.gltf'),
    export_format='GLTF_SEPARATE',
    export_apply=False,
    export_cameras=True,
    export_lights=False,
    export_normals=True,
    export_tangents=False,
    export_texcoords=False,
    export_yup=True,
    export_extras=False,
    export_animations=False,
)
print('wrote', os.path.join(out_dir, 'variants.gltf'))
