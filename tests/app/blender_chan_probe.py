# Reads `track --chan`'s head.chan and camera.chan with Blender's Nuke .chan
# add-on (io_anim_nuke_chan: rotation order ZXY, Nuke's default, y up made z
# up) onto an empty and a camera, and writes where that camera sees given
# points of the head (run as `blender -b --factory-startup --python
# blender_chan_probe.py -- OUT.json HEAD.chan CAMERA.chan WIDTH HEIGHT
# POINTS.json ORDER`): POINTS.json maps a frame to points in the head's own
# (model) space, OUT.json the same frame to their pixels (pixel centres at
# integers, y down). blender_interop_test.cpp compares them with where the
# fit put the landmarks.
import json
import sys

import bpy
from bpy_extras.object_utils import world_to_camera_view
from mathutils import Vector

args = sys.argv[sys.argv.index("--") + 1:]
out_json, head_chan, camera_chan = args[0], args[1], args[2]
width, height = int(args[3]), int(args[4])
points_json, order = args[5], args[6]

bpy.ops.wm.read_homefile(use_empty=True)
bpy.ops.preferences.addon_enable(module="io_anim_nuke_chan")
scene = bpy.context.scene
scene.render.resolution_x, scene.render.resolution_y = width, height
scene.render.resolution_percentage = 100
head = bpy.data.objects.new("head", None)
camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
for o in (head, camera):
    scene.collection.objects.link(o)
scene.camera = camera
# The camera's sensor has the plate's aspect, as the chan's vertical field of view needs.
for target, chan, sensor in ((head, head_chan, {}),
                             (camera, camera_chan, {"sensor_width": 36.0, "sensor_height": 36.0 * height / width})):
    bpy.context.view_layer.objects.active = target
    bpy.ops.import_scene.import_chan(filepath=chan, rotation_order=order, z_up=True, **sensor)

report = {}
with open(points_json) as f:
    frames = json.load(f)
for frame, points in frames.items():
    scene.frame_set(int(frame))
    pixels = []
    for p in points:
        v = world_to_camera_view(scene, camera, head.matrix_world @ Vector(p))
        pixels.append([v.x * width - 0.5, (1 - v.y) * height - 0.5])
    report[frame] = pixels
with open(out_json, "w") as f:
    json.dump(report, f)
