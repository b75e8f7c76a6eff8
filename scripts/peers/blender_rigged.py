# Writes tests/data/peers/rigged.gltf (+ rigged.bin) with Blender's own glTF exporter (Debian's
# blender package, 3.4.1; exporter 3.4.50):
#
#   blender -b --factory-startup --python scripts/peers/blender_rigged.py -- OUT_DIR
#
# The model: a vertical capped tube (Blender +Z up; glTF +Y up after export), radius 0.35, 3 units
# tall, 24 segments x 17 rings + 2 cap centres = 410 vertices, smooth normals, no UVs; a Principled
# BSDF with an orange base colour (roughness 0.5, metallic 0).
# The rig: an armature of 3 bones in a chain along the tube (bone0 0..1, bone1 1..2, bone2 2..3);
# every vertex is weighted to the bones by a hat function of its height (1 at a bone's middle, 0 one
# unit away), normalised: the vertices between two bones' middles (240 of 410) have 2 influences,
# those below the first middle or above the last follow one bone.
# A shape key "bulge" pushes the middle of the tube outwards (a Gaussian of the height, up to 0.25).
# One action over 2 seconds (frames 0..48 at 24 fps, Bezier keys at 0, 24, 48): the bones rotate
# about their local Z (Blender's -Y, glTF's +Z, towards the camera) by (8, 30, 35) degrees at 1 s,
# bending the tube to the camera's left (73 degrees at the tip), then by (-5, -20, -30) degrees at
# 2 s, past straight to the right; the bulge goes 0 -> 1 -> 0 (its weight is 0.5 at 0.5 s).
# Export: skins, morph targets with their normals (no tangents), animations sampled at every frame
# (49 LINEAR keys per channel, translation / rotation / scale of each bone and the mesh's weights),
# the armature's and the shape key's actions merged into one glTF animation named "bend"
# (export_nla_strips=False). One perspective camera (aspect 1) in front of the tube. No lights.
# Nothing random: two runs write the same bytes.
import math
import os
import sys

import bpy
from mathutils import Quaternion, Vector

argv = sys.argv[sys.argv.index('--') + 1:] if '--' in sys.argv else []
out_dir = os.path.abspath(argv[0] if argv else os.path.join(os.path.dirname(__file__), '..', '..',
                                                             'tests', 'data', 'peers'))

SEGMENTS = 24
RINGS = 17
RADIUS = 0.35
HEIGHT = 3.0
BONES = 3
FPS = 24

# empty scene
for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj, do_unlink=True)
scene = bpy.context.scene
scene.render.resolution_x = 256
scene.render.resolution_y = 256
scene.render.resolution_percentage = 100
scene.render.fps = FPS
scene.render.fps_base = 1.0
scene.frame_start = 0
scene.frame_end = 2 * FPS
scene.frame_set(0)

# the tube: rings of SEGMENTS vertices from z = 0 to z = HEIGHT, a fan-capped end at each side
verts = []
for r in range(RINGS):
    z = HEIGHT * r / (RINGS - 1)
    for s in range(SEGMENTS):
        a = 2.0 * math.pi * s / SEGMENTS
        verts.append((RADIUS * math.cos(a), RADIUS * math.sin(a), z))
bottom = len(verts)
verts.append((0.0, 0.0, 0.0))
top = len(verts)
verts.append((0.0, 0.0, HEIGHT))
faces = []
for r in range(RINGS - 1):
    for s in range(SEGMENTS):
        a, b = r * SEGMENTS + s, r * SEGMENTS + (s + 1) % SEGMENTS
        faces.append((a, b, b + SEGMENTS, a + SEGMENTS))
for s in range(SEGMENTS):
    faces.append((bottom, (s + 1) % SEGMENTS, s))
    last = (RINGS - 1) * SEGMENTS
    faces.append((top, last + s, last + (s + 1) % SEGMENTS))
mesh = bpy.data.meshes.new('tube')
mesh.from_pydata(verts, [], faces)
mesh.update()
for poly in mesh.polygons:
    poly.use_smooth = True
tube = bpy.data.objects.new('tube', mesh)
scene.collection.objects.link(tube)

mat = bpy.data.materials.new('orange')
mat.use_nodes = True
bsdf = mat.node_tree.nodes['Principled BSDF']
bsdf.inputs['Base Color'].default_value = (0.8, 0.3, 0.08, 1.0)
bsdf.inputs['Roughness'].default_value = 0.5
bsdf.inputs['Metallic'].default_value = 0.0
mesh.materials.append(mat)

# the armature: a chain of BONES bones straight up the tube
arm_data = bpy.data.armatures.new('rig')
rig = bpy.data.objects.new('rig', arm_data)
scene.collection.objects.link(rig)
bpy.context.view_layer.objects.active = rig
rig.select_set(True)
bpy.ops.object.mode_set(mode='EDIT')
bone_len = HEIGHT / BONES
parent = None
for i in range(BONES):
    eb = arm_data.edit_bones.new('bone%d' % i)
    eb.head = (0.0, 0.0, i * bone_len)
    eb.tail = (0.0, 0.0, (i + 1) * bone_len)
    eb.roll = 0.0
    if parent is not None:
        eb.parent = parent
        eb.use_connect = True
    parent = eb
bpy.ops.object.mode_set(mode='OBJECT')

# smooth weights: a hat function of the height around each bone's middle
groups = [tube.vertex_groups.new(name='bone%d' % i) for i in range(BONES)]
for v, co in enumerate(verts):
    z = co[2]
    w = []
    for i in range(BONES):
        mid = (i + 0.5) * bone_len
        w.append(max(0.0, 1.0 - abs(z - mid) / bone_len))
    if z <= 0.5 * bone_len:
        w = [1.0] + [0.0] * (BONES - 1)
    elif z >= HEIGHT - 0.5 * bone_len:
        w = [0.0] * (BONES - 1) + [1.0]
    total = sum(w)
    for i in range(BONES):
        if w[i] > 0.0:
            groups[i].add([v], w[i] / total, 'REPLACE')
tube.parent = rig
mod = tube.modifiers.new('armature', 'ARMATURE')
mod.object = rig

# the shape key: the middle bulges out
tube.shape_key_add(name='Basis', from_mix=False)
bulge = tube.shape_key_add(name='bulge', from_mix=False)
for v, co in enumerate(verts):
    x, y, z = co
    r = math.hypot(x, y)
    if r < 1e-9:
        continue
    g = 0.25 * math.exp(-((z - 0.5 * HEIGHT) / 0.5) ** 2)
    bulge.data[v].co = (x + x / r * g, y + y / r * g, z)
bulge.value = 0.0

# the action: bend right, back past straight to the left; bulge 0 -> 1 -> 0
rig.animation_data_create()
rig.animation_data.action = bpy.data.actions.new('bend')
keys = [(0, (0.0, 0.0, 0.0), 0.0),
        (FPS, (8.0, 30.0, 35.0), 1.0),
        (2 * FPS, (-5.0, -20.0, -30.0), 0.0)]
for frame, angles, value in keys:
    for i in range(BONES):
        pb = rig.pose.bones['bone%d' % i]
        pb.rotation_mode = 'QUATERNION'
        # about the bone's local Z: world -Y for a bone pointing up with roll 0, so the tube bends
        # in the XZ plane, across the camera's view (positive angles: to the left, seen from -Y)
        pb.rotation_quaternion = Quaternion((0.0, 0.0, 1.0), math.radians(angles[i]))
        pb.keyframe_insert(data_path='rotation_quaternion', frame=frame)
    bulge.value = value
    bulge.keyframe_insert(data_path='value', frame=frame)
mesh.shape_keys.animation_data.action.name = 'bulge'
scene.frame_set(0)

# the camera (Blender is +Z up): in front of the tube (-Y), a little above its middle
cam_data = bpy.data.cameras.new('camera')
cam_data.lens = 50.0
cam_data.sensor_width = 36.0
cam_data.sensor_fit = 'AUTO'
cam_data.clip_start = 0.1
cam_data.clip_end = 100.0
cam = bpy.data.objects.new('camera', cam_data)
scene.collection.objects.link(cam)
cam.location = (0.8, -7.5, 2.2)
cam.rotation_euler = (Vector((0.0, 0.0, 1.5)) - cam.location).to_track_quat('-Z', 'Y').to_euler()
scene.camera = cam

bpy.ops.export_scene.gltf(
    filepath=os.path.join(out_dir, 'rigged.gltf'),
    export_format='GLTF_SEPARATE',
    export_apply=False,
    export_cameras=True,
    export_lights=False,
    export_normals=True,
    export_tangents=False,
    export_texcoords=True,
    export_yup=True,
    export_extras=False,
    export_skins=True,
    export_all_influences=False,
    export_def_bones=False,
    export_morph=True,
    export_morph_normal=True,
    export_morph_tangent=False,
    export_animations=True,
    export_frame_range=True,
    export_frame_step=1,
    export_force_sampling=True,
    export_optimize_animation_size=False,
    export_nla_strips=False,
    export_nla_strips_merged_animation_name='bend',
    export_anim_single_armature=True,
    export_reset_pose_bones=True,
    export_current_frame=False,
)
print('wrote', os.path.join(out_dir, 'rigged.gltf'))
