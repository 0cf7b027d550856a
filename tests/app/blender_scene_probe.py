# Reads the scene blender/import_facecap.py saved (run as `blender -b
# SCENE.blend --python blender_scene_probe.py -- OUT.json RENDER.png FRAME...`)
# and writes to OUT.json its frame rate and range, render size, where it shows
# a point on the camera's axis, the face's
# keyed frames, its modifiers and, at each FRAME, where the face sits and how
# far the detail modifier moves each vertex of the subdivided mesh along its
# normal, with the vertex's UV (where there is a detail modifier); then
# renders the last FRAME 320 px wide (a quarter of 1280x720), 16 Cycles samples, its
# background transparent, into RENDER.png (none for "-"). blender_interop_test.cpp compares these with
# the track folder's frames.csv and detail maps, and the plate's frames.
import json
import sys

import bpy
import numpy
from bpy_extras.object_utils import world_to_camera_view
from mathutils import Vector

out_json, render_png = sys.argv[sys.argv.index("--") + 1:][:2]
frames = [int(f) for f in sys.argv[sys.argv.index("--") + 3:]]
scene = bpy.context.scene
face = next(o for o in scene.objects if o.type == "MESH" and o.data.shape_keys)
detail = face.modifiers.get("facecap detail")
group = face.vertex_groups["facecap_detail"].index if detail else -1
action = face.animation_data.action
report = {
    "fps": scene.render.fps / scene.render.fps_base,
    "frame_range": [scene.frame_start, scene.frame_end],
    "camera": scene.camera.name if scene.camera else None,
    "resolution": [scene.render.resolution_x, scene.render.resolution_y],
    "keyed_frames": sorted({k.co.x for c in action.fcurves for k in c.keyframe_points}),
    "modifiers": [[m.type, getattr(m, "subdivision_type", None), getattr(m, "levels", None)] for m in face.modifiers],
    "skin_vertices": sum(1 for v in face.data.vertices if any(g.group == group for g in v.groups)),
    "frames": {},
}
# Where the render shows a point on the camera's axis (pixel centres at integers).
axis = world_to_camera_view(scene, scene.camera, scene.camera.matrix_world @ Vector((0.0, 0.0, -10.0)))
report["axis_pixel"] = [axis.x * scene.render.resolution_x - 0.5, (1 - axis.y) * scene.render.resolution_y - 0.5]


def evaluated(show_detail):
    detail.show_viewport = show_detail
    bpy.context.view_layer.update()
    depsgraph = bpy.context.evaluated_depsgraph_get()
    return face.evaluated_get(depsgraph).to_mesh().copy()


def coordinates(mesh):
    co = numpy.empty(3 * len(mesh.vertices))
    mesh.vertices.foreach_get("co", co)
    return co.reshape(-1, 3)


for frame in frames:
    scene.frame_set(frame)
    report["frames"][str(frame)] = {"location": list(face.matrix_world.translation)}
    if not detail:
        continue
    plain, displaced = evaluated(False), evaluated(True)
    normals = numpy.empty(3 * len(plain.vertices))
    plain.vertices.foreach_get("normal", normals)
    moved = ((coordinates(displaced) - coordinates(plain)) * normals.reshape(-1, 3)).sum(axis=1) * 1000.0  # mm
    # Each vertex's UV, from its loops (one UV a vertex on the face's skin).
    corner_vertex = numpy.empty(len(plain.loops), dtype=numpy.int64)
    plain.loops.foreach_get("vertex_index", corner_vertex)
    corner_uv = numpy.empty(2 * len(plain.loops))
    plain.uv_layers[0].data.foreach_get("uv", corner_uv)
    uv = numpy.zeros((len(plain.vertices), 2))
    uv[corner_vertex] = corner_uv.reshape(-1, 2)
    # Every 16th vertex (a sample spread over the whole mesh).
    keep = numpy.arange(len(moved)) % 16 == 0
    report["frames"][str(frame)].update({"moved_mm": moved[keep].tolist(), "uv": uv[keep].tolist()})

if render_png != "-":  # the last frame, 320 px wide, the background transparent
    scene.render.engine = "CYCLES"
    scene.cycles.samples = 16
    scene.cycles.use_denoising = False
    scene.render.resolution_percentage = round(100 * 320 / scene.render.resolution_x)
    scene.render.film_transparent = True
    scene.render.image_settings.file_format = "PNG"
    scene.render.image_settings.color_mode = "RGBA"
    scene.render.filepath = render_png
    bpy.ops.render.render(write_still=True)

with open(out_json, "w") as f:
    json.dump(report, f)
