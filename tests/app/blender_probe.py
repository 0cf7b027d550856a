# Opens a .glb in Blender (run as `blender -b --factory-startup --python
# blender_probe.py -- GLB OUT.json MASK.png WIDTH HEIGHT TIME`) with Blender's
# own glTF importer, writes what it made of the file to OUT.json, and renders
# the scene through the imported camera at TIME seconds into MASK.png, whose
# alpha is the face's coverage. blender_interop_test.cpp compares both with
# what the file says.
import json
import sys

import numpy

# Debian 12's Blender 3.4 glTF add-on still uses numpy.bool, which numpy 1.24
# removed; the alias it meant is the builtin.
if not hasattr(numpy, "bool") or numpy.bool is not bool:
    numpy.bool = bool

import bpy  # noqa: E402

glb, out_json, mask_png = sys.argv[sys.argv.index("--") + 1:][:3]
width, height = (int(v) for v in sys.argv[sys.argv.index("--") + 4:][:2])
seconds = float(sys.argv[sys.argv.index("--") + 6])

bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=glb)
scene = bpy.context.scene
report = {"fps": scene.render.fps / scene.render.fps_base, "meshes": [], "cameras": 0}


def keyframes(action):
    frames = set()
    for curve in action.fcurves:
        frames.update(round(k.co[0], 3) for k in curve.keyframe_points)
    return len(frames)


for obj in bpy.data.objects:
    if obj.type == "CAMERA":
        report["cameras"] += 1
        scene.camera = obj
    if obj.type != "MESH":
        continue
    mesh = obj.data
    shape_keys = mesh.shape_keys.key_blocks[1:] if mesh.shape_keys else []  # [0] is the basis
    images = []
    for material in mesh.materials:
        if material and material.use_nodes:
            images += [list(n.image.size) for n in material.node_tree.nodes if n.type == "TEX_IMAGE" and n.image]
    entry = {
        "name": obj.name,
        "vertices": len(mesh.vertices),
        "shape_keys": [k.name for k in shape_keys],
        "materials": len(mesh.materials),
        "images": images,
        "node_keys": keyframes(obj.animation_data.action) if obj.animation_data and obj.animation_data.action else 0,
    }
    key_anim = mesh.shape_keys.animation_data if mesh.shape_keys else None
    entry["shape_key_keys"] = keyframes(key_anim.action) if key_anim and key_anim.action else 0
    report["meshes"].append(entry)

# The scene through the file's camera at the requested time, the background
# transparent: the alpha channel is where the face is.
frame = seconds * report["fps"]
scene.frame_set(int(frame), subframe=frame - int(frame))
scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = 4
scene.cycles.use_denoising = False
scene.render.film_transparent = True
scene.render.resolution_x, scene.render.resolution_y = width, height
scene.render.resolution_percentage = 100
scene.render.image_settings.file_format = "PNG"
scene.render.image_settings.color_mode = "RGBA"
scene.render.filepath = mask_png
bpy.ops.render.render(write_still=True)

with open(out_json, "w") as f:
    json.dump(report, f)
