# Displaces a refined mesh by its detail map in Blender (run as `blender -b
# --factory-startup --python blender_displace_probe.py -- MESH.obj MAP.png
# DETAIL.json OUT.json`): imports the mesh with Blender's OBJ importer, loads
# the map as non-colour data and adds a Displace modifier set up as
# DETAIL.json's "blender_displace" says (UV coordinates, midlevel, strength),
# then writes to OUT.json each vertex's UV and how far the modifier moved it
# along its normal. blender_interop_test.cpp compares that with the map.
import json
import sys

import bpy

mesh_file, map_file, detail_json, out_json = sys.argv[sys.argv.index("--") + 1:][:4]
with open(detail_json) as f:
    settings = json.load(f)["blender_displace"]

bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.wm.obj_import(filepath=mesh_file)
obj = next(o for o in bpy.data.objects if o.type == "MESH")
image = bpy.data.images.load(map_file)
image.colorspace_settings.name = "Non-Color"
texture = bpy.data.textures.new("facecap_detail", type="IMAGE")
texture.image = image
modifier = obj.modifiers.new("facecap_detail", "DISPLACE")
modifier.texture = texture
modifier.texture_coords = settings["texture_coordinates"]
modifier.uv_layer = obj.data.uv_layers[0].name
modifier.mid_level = settings["midlevel"]
modifier.strength = settings["strength_cm"]

mesh = obj.data
# Each vertex's UV (the OBJ's per-corner UVs; one per vertex on the face region).
uvs = [None] * len(mesh.vertices)
for loop in mesh.loops:
    if uvs[loop.vertex_index] is None:
        uvs[loop.vertex_index] = list(mesh.uv_layers[0].data[loop.index].uv)
evaluated = obj.evaluated_get(bpy.context.evaluated_depsgraph_get()).to_mesh()
moved = [(evaluated.vertices[i].co - v.co).dot(v.normal) for i, v in enumerate(mesh.vertices)]
report = {"vertices": len(mesh.vertices), "image_depth": image.depth, "is_float": image.is_float,
          "uv": uvs, "moved": moved}
with open(out_json, "w") as f:
    json.dump(report, f)
