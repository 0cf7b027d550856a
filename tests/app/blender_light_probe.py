# Renders a white Lambertian sphere lit only by import_facecap.py's footage
# light (add_footage_light) with the 9 given lighting coefficients, and
# writes what Cycles made of it (run as `blender -b --factory-startup --python
# blender_light_probe.py -- IMPORT_SCRIPT OUT.json l0 ... l8`): for each
# pixel whose centre sees the sphere well inside its outline, the centre's
# position in the sphere's radii, in the camera's frame (x right, y up), and
# the rendered RGB. The sphere is convex, so nothing shadows it but itself
# where it faces away: what it shows is the world's irradiance over pi, which
# blender_interop_test.cpp compares with facecap's own shading, l^T SH(n).
import json
import os
import sys

import bpy
import numpy

args = sys.argv[sys.argv.index("--") + 1:]
script, out_json, lighting = args[0], args[1], [float(v) for v in args[2:11]]
sys.path.insert(0, os.path.dirname(os.path.abspath(script)))
import import_facecap  # noqa: E402  (its main() runs only as Blender's --python script)

bpy.ops.wm.read_homefile(use_empty=True)
scene = bpy.context.scene
scene.world = bpy.data.worlds.new("footage light")
import_facecap.add_footage_light(scene, {0: lighting})
scene.frame_set(0)

bpy.ops.mesh.primitive_uv_sphere_add(segments=192, ring_count=96, radius=1.0)
sphere = bpy.context.active_object
bpy.ops.object.shade_smooth()
material = bpy.data.materials.new("white")
material.use_nodes = True
bsdf = material.node_tree.nodes["Principled BSDF"]
diffuse = material.node_tree.nodes.new("ShaderNodeBsdfDiffuse")
diffuse.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
diffuse.inputs["Roughness"].default_value = 0.0  # Lambertian
output = material.node_tree.nodes["Material Output"]
material.node_tree.links.new(diffuse.outputs[0], output.inputs["Surface"])
sphere.data.materials.append(material)

# An orthographic camera on -y looking along +y: facecap's viewer frame
# (x right, y up, z toward the viewer) is Blender's (x, z, -y) here.
camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
scene.collection.objects.link(camera)
camera.data.type = "ORTHO"
camera.data.ortho_scale = 2.2
camera.location = (0.0, -10.0, 0.0)
camera.rotation_euler = (numpy.pi / 2, 0.0, 0.0)
scene.camera = camera

size = 64
scene.render.engine = "CYCLES"
scene.cycles.samples = 1024
scene.cycles.use_denoising = False
scene.render.resolution_x = scene.render.resolution_y = size
scene.render.resolution_percentage = 100
scene.render.film_transparent = True
scene.render.image_settings.file_format = "OPEN_EXR"
scene.render.image_settings.color_depth = "32"
scene.render.image_settings.color_mode = "RGBA"
exr = os.path.splitext(out_json)[0] + ".exr"
scene.render.filepath = exr
bpy.ops.render.render(write_still=True)

image = bpy.data.images.load(exr)
pixels = numpy.array(image.pixels[:]).reshape(size, size, 4)  # rows from the bottom up
samples = []
for row in range(size):
    for column in range(size):
        x = ((column + 0.5) / size - 0.5) * camera.data.ortho_scale
        y = ((row + 0.5) / size - 0.5) * camera.data.ortho_scale
        if x * x + y * y < 0.9 ** 2:
            samples.append([x, y] + pixels[row, column, :3].tolist())
with open(out_json, "w") as f:
    json.dump({"samples": samples}, f)
