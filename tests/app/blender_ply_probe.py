# Opens a .ply in Blender (run as `blender -b --factory-startup --python
# blender_ply_probe.py -- PLY OUT.json`) with Blender's own PLY importer and
# writes what it made of the file to OUT.json: its objects, vertices, faces,
# UV layers and colour attributes, and the colours' mean as Blender holds
# them (linear RGB). blender_interop_test.cpp compares them with the file.
import json
import sys

import bpy

ply, out_json = sys.argv[sys.argv.index("--") + 1:][:2]

bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_mesh.ply(filepath=ply)
meshes = [o.data for o in bpy.data.objects if o.type == "MESH"]
report = {"meshes": len(meshes)}
if meshes:
    mesh = meshes[0]
    report.update({
        "vertices": len(mesh.vertices),
        "faces": len(mesh.polygons),
        "uv_layers": len(mesh.uv_layers),
        "colour_attributes": len(mesh.color_attributes),
    })
    if mesh.color_attributes:
        colours = mesh.color_attributes[0].data
        report["colour_mean"] = [sum(c.color[k] for c in colours) / max(1, len(colours)) for k in range(3)]

with open(out_json, "w") as f:
    json.dump(report, f)
