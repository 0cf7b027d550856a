# Plays a point cache in Blender (run as `blender -b --factory-startup
# --python blender_pc2_probe.py -- REST.ply CACHE.pc2 OUT.json FRAMES
# VERTICES`, the last two comma-separated): imports the rest mesh with
# Blender's PLY importer, adds a Mesh Cache modifier reading the PC2 file (its
# defaults: frame start 0, one sample a frame), and writes to OUT.json where
# the chosen vertices are at each chosen scene frame, as Blender evaluates
# them. blender_interop_test.cpp compares them with the cache's samples.
import json
import sys

import bpy

rest, cache, out_json, frames, vertices = sys.argv[sys.argv.index("--") + 1:][:5]
frames = [int(f) for f in frames.split(",")]
vertices = [int(v) for v in vertices.split(",")]

bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_mesh.ply(filepath=rest)
obj = next(o for o in bpy.data.objects if o.type == "MESH")
modifier = obj.modifiers.new("facecap", "MESH_CACHE")
modifier.cache_format = "PC2"
modifier.filepath = cache
scene = bpy.context.scene
report = {"vertices": len(obj.data.vertices), "frames": {}}
for frame in frames:
    scene.frame_set(frame)
    evaluated = obj.evaluated_get(bpy.context.evaluated_depsgraph_get())
    mesh = evaluated.to_mesh()
    report["frames"][str(frame)] = [list(mesh.vertices[v].co) for v in vertices]
    evaluated.to_mesh_clear()

with open(out_json, "w") as f:
    json.dump(report, f)
