# Opens an .obj in Blender (run as `blender -b --factory-startup --python
# blender_obj_probe.py -- OBJ OUT.json`) with Blender's own OBJ importer and
# writes what it made of the file to OUT.json: its meshes, vertices, UV
# layers and materials, and of the first material's image texture, the file
# it loaded and its size. blender_interop_test.cpp compares them with the
# capture's files.
import json
import os
import sys

import bpy

obj, out_json = sys.argv[sys.argv.index("--") + 1:][:2]

bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.wm.obj_import(filepath=obj)
meshes = [o.data for o in bpy.data.objects if o.type == "MESH"]
report = {"meshes": len(meshes)}
if meshes:
    mesh = meshes[0]
    report.update({
        "vertices": len(mesh.vertices),
        "uv_layers": len(mesh.uv_layers),
        "materials": [m.name for m in mesh.materials if m is not None],
    })
    material = mesh.materials[0] if mesh.materials else None
    if material is not None and material.use_nodes:
        images = [n.image for n in material.node_tree.nodes if n.type == "TEX_IMAGE" and n.image is not None]
        if images:
            image = images[0]
            report["texture_file"] = os.path.realpath(bpy.path.abspath(image.filepath))
            report["texture_size"] = list(image.size)
            # The texture feeds the surface's base colour.
            bsdf = [n for n in material.node_tree.nodes if n.type == "BSDF_PRINCIPLED"]
            report["texture_is_base_colour"] = bool(bsdf) and any(
                link.from_node.type == "TEX_IMAGE" for link in bsdf[0].inputs["Base Color"].links)

with open(out_json, "w") as f:
    json.dump(report, f)
