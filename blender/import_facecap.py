# Brings a `facecap track` output folder into Blender as one animated scene:
#
#   blender --python blender/import_facecap.py -- DIR [--video INPUT] [--glb FILE] [--subdivisions N]
#                                                       [--even-light] [--whole-face] [--save FILE.blend]
#
# - imports DIR/animation.glb (`track --gltf`) with Blender's own glTF importer: the face
#   with its shape keys and their keys, the head's keys and the fitted camera, which
#   becomes the scene's camera, the render the input's size (DIR/identity.json, else the
#   video's) with the lens shifted half a pixel onto facecap's principal point (W/2, H/2 in
#   pixel-centre coordinates); `transform --gltf` and `swap --gltf` files come in alike with --glb FILE and
#   no DIR (then nothing but the file and the video is read);
# - plays it at the input's frame rate (read from DIR/frames.csv, else from the keys'
#   spacing; 29.97 fps as 30 / 1.001) with each video frame on the Blender frame of the
#   same number (the glTF importer keys at whole frames per second only, so its keys are
#   retimed), the scene's range the keys';
# - with DIR/detail (`track --refine --detail-maps`), adds the refinement's per-frame
#   detail: a Subdivision Surface modifier (Simple, N levels, 1 by default: four faces a
#   face, about the refinement's finest level on a 720p face) and a Displace
#   modifier reading the maps as an image sequence (non-colour data, UV coordinates,
#   midlevel and strength as DIR/detail/detail.json says, in the file's metres), over the
#   face's skin only (the vertex group "facecap_detail": the mouth's and eyes' part has no
#   map), so that frame N shows DIR/detail/frame_N.png;
# - where DIR/frames.csv has the refinement's lighting (`track --refine`), lights the world
#   as the footage was lit, keyed frame by frame (add_footage_light; --even-light keeps a
#   white world), with the albedo and footage read as raw data and the view transform Raw,
#   so that the render is albedo x shading as facecap's own renders are;
# - with --video, holds the skin out where the face matte is 0 (the scalp, ears and neck of
#   the model's face region), so that the footage's own hair, ears, neck and collar show
#   there (add_face_matte; --whole-face renders the whole region, as does a scene without
#   footage); the matte is the image named "face_matte" in the file (every `track`,
#   `transform` and `swap --gltf` file carries one, used by no material), else
#   DIR/face_matte.png;
# - with --video (the tracked input), puts the footage behind the face: the camera's
#   background in the viewport and, in the compositor, under the render (whose background
#   is then transparent), video frame N on frame N.
#
# It starts from an empty scene (run it from the command line: what Blender opened with
# is let go). With --save (and `blender -b`), it writes the scene to a .blend file and
# Blender can quit.
# Checked with Debian 12's Blender 3.4 (tests/app/blender_interop_test.cpp).
import argparse
import csv
import json
import os
import struct
import sys
import tempfile

import numpy

# Debian 12's Blender 3.4 glTF add-on still uses numpy.bool, which numpy 1.24
# removed; the alias it meant is the builtin.
if "bool" not in vars(numpy):
    numpy.bool = bool

import bpy  # noqa: E402

DETAIL_GROUP = "facecap_detail"


def parse_arguments():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    parser = argparse.ArgumentParser(prog="blender --python import_facecap.py --",
                                     description="Bring a facecap track folder into Blender.")
    parser.add_argument("dir", nargs="?", help="the folder `facecap track ... -o DIR --gltf` wrote")
    parser.add_argument("--glb", help="the animation to import (default DIR/animation.glb): a later shot's "
                        "DIR/animation_shot<N>.glb, or the file of `transform --gltf` or `swap --gltf` (then "
                        "DIR may be left out)")
    parser.add_argument("--subdivisions", type=int, default=1,
                        help="Simple subdivision levels under the detail maps (default 1, about the "
                        "refinement's finest level on a 720p face; 0 displaces the model's own vertices)")
    parser.add_argument("--video", help="the tracked input: seen behind the face through the camera (viewport) "
                        "and composited under it in renders, frame N under frame N")
    parser.add_argument("--even-light", action="store_true",
                        help="light the face evenly (a white world) even where DIR/frames.csv has the "
                        "refinement's lighting")
    parser.add_argument("--whole-face", action="store_true",
                        help="render the whole face region (scalp to neck) even where DIR/face_matte.png "
                        "would leave all but the narrow face to the footage (--video)")
    parser.add_argument("--save", help="write the scene to this .blend file")
    return parser.parse_args(argv)


def fail(message):
    print("import_facecap: " + message, file=sys.stderr)
    sys.exit(1)


def blender_rate(rate):
    """Frames per second as Blender's fps and fps_base (29.97 as 30 / 1.001)."""
    fps = max(1, round(rate))
    base = fps / rate
    return fps, 1.0 if abs(base - 1.0) < 1e-4 else base


def csv_frame_rate(frames_csv):
    """The input's frames per second from frames.csv's frame numbers and
    times; None for a photo or a single frame."""
    with open(frames_csv, newline="") as f:
        rows = [(int(r["frame"]), float(r["time"])) for r in csv.DictReader(f) if r.get("time")]
    if len(rows) < 2 or rows[-1][1] <= rows[0][1]:
        return None
    return (rows[-1][0] - rows[0][0]) / (rows[-1][1] - rows[0][1])


def load_image(path, what=None):
    """An image Blender can read, as non-colour data; fails naming it (`what`,
    else the file) where it cannot."""
    image = bpy.data.images.load(os.path.abspath(path))
    if image.size[0] == 0 or image.size[1] == 0:  # Blender loads what it cannot decode as an empty image
        fail("cannot read %s: not an image Blender can decode (cut short or damaged?)" % (what or path))
    image.colorspace_settings.name = "Non-Color"
    return image


def glb_image_bytes(glb, name):
    """The encoded bytes of the image called `name` in a .glb file (stored in
    a buffer view of its binary chunk), or None where it has none."""
    with open(glb, "rb") as f:
        data = f.read()
    try:
        magic, _, _ = struct.unpack_from("<III", data, 0)
        json_length, json_type = struct.unpack_from("<II", data, 12)
        if magic != 0x46546C67 or json_type != 0x4E4F534A:
            return None
        doc = json.loads(data[20:20 + json_length])
        bin_at = 20 + json_length
        bin_length, bin_type = struct.unpack_from("<II", data, bin_at)
        if bin_type != 0x004E4942:
            return None
        for image in doc.get("images", []):
            if image.get("name") == name and "bufferView" in image:
                view = doc["bufferViews"][image["bufferView"]]
                start = bin_at + 8 + view.get("byteOffset", 0)
                if start + view["byteLength"] > bin_at + 8 + bin_length:
                    return None
                return data[start:start + view["byteLength"]]
    except (struct.error, ValueError, KeyError, IndexError, TypeError):
        return None  # the glTF importer has read the file: what is odd here is the matte's alone
    return None


def load_image_bytes(data, name, what):
    """An image from its encoded bytes, packed into the scene (so a saved
    .blend holds it), as non-colour data; fails naming it (`what`) where
    Blender cannot decode it."""
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, name)
        with open(path, "wb") as f:
            f.write(data)
        image = load_image(path, what)
        image.pack()
    image.name = name
    return image


def keyed_frames(actions):
    """The frames the actions have keys on, each once, in order."""
    return sorted({round(k.co.x, 4) for a in actions for c in a.fcurves for k in c.keyframe_points})


def key_frame_rate(actions, keyed_at):
    """Frames per second from the keys' spacing (one key a video frame; a
    lost frame's missing key leaves a double step, which the median ignores),
    the keys having been put at `keyed_at` frames per second; None without two keys."""
    frames = keyed_frames(actions)
    steps = sorted(b - a for a, b in zip(frames, frames[1:]))
    return keyed_at / steps[len(steps) // 2] if steps else None


def retime(actions, factor):
    """Multiplies every key's frame (and its handles') by `factor`; keys that
    land within a thousandth of a whole frame are put on it."""
    for action in actions:
        for curve in action.fcurves:
            for key in curve.keyframe_points:
                frame = key.co.x * factor
                if abs(frame - round(frame)) < 1e-3:
                    frame = float(round(frame))
                shift = frame - key.co.x
                key.co.x = frame
                key.handle_left.x += shift
                key.handle_right.x += shift
            curve.update()


def imported_actions(objects):
    actions = []
    for obj in objects:
        if obj.animation_data and obj.animation_data.action:
            actions.append(obj.animation_data.action)
        keys = obj.data.shape_keys if obj.type == "MESH" else None
        if keys and keys.animation_data and keys.animation_data.action:
            actions.append(keys.animation_data.action)
    return actions


def key_range(actions):
    frames = keyed_frames(actions)
    return (int(round(frames[0])), int(round(frames[-1]))) if frames else (0, 0)


def detail_sequence(detail_dir):
    """The maps' first frame number, their count and detail.json's settings."""
    with open(os.path.join(detail_dir, "detail.json")) as f:
        info = json.load(f)
    numbers = sorted(int(n[6:12]) for n in os.listdir(detail_dir)
                     if n.startswith("frame_") and n.endswith(".png") and n[6:12].isdigit())
    if not numbers:
        return None
    if numbers != list(range(numbers[0], numbers[0] + len(numbers))):
        fail(detail_dir + " has gaps in its frame numbers (maps of another run?)")
    return numbers[0], len(numbers), info


def add_detail(face, detail_dir, subdivisions):
    sequence = detail_sequence(detail_dir)
    if sequence is None:
        print("import_facecap: " + detail_dir + " has no maps; no detail added")
        return
    first, count, info = sequence
    # The face's skin: the polygons of the material named "face" (the other
    # part, the mouth's and eyes', lies outside the maps' UV islands).
    mesh = face.data
    skin = [i for i, m in enumerate(mesh.materials) if m and m.name.startswith("face")]
    group = face.vertex_groups.new(name=DETAIL_GROUP)
    vertices = {v for p in mesh.polygons if p.material_index in skin for v in p.vertices}
    group.add(sorted(vertices), 1.0, "REPLACE")

    image = load_image(os.path.join(detail_dir, "frame_%06d.png" % first))
    image.source = "SEQUENCE"
    texture = bpy.data.textures.new("facecap detail", type="IMAGE")
    texture.image = image
    texture.extension = "EXTEND"
    # Scene frame F shows map F: Blender's image number is (F - start + 1) + offset.
    texture.image_user.frame_start = first
    texture.image_user.frame_offset = first - 1
    texture.image_user.frame_duration = count
    texture.image_user.use_auto_refresh = True

    if subdivisions > 0:
        subdivide = face.modifiers.new("facecap subdivision", "SUBSURF")
        subdivide.subdivision_type = "SIMPLE"
        subdivide.levels = subdivisions
        subdivide.render_levels = subdivisions
        subdivide.uv_smooth = "NONE"
    settings = info["blender_displace"]
    displace = face.modifiers.new("facecap detail", "DISPLACE")
    displace.texture = texture
    displace.texture_coords = settings["texture_coordinates"]
    displace.uv_layer = mesh.uv_layers[0].name
    displace.mid_level = settings["midlevel"]
    displace.strength = settings["strength_cm"] / 100.0  # glTF's metres
    displace.vertex_group = DETAIL_GROUP
    print("import_facecap: detail maps %06d-%06d on %d vertices of the face" % (first, first + count - 1,
                                                                              len(vertices)))


def add_face_matte(face, image):
    """Holds out the face's skin by the face matte (a Blender image: the
    file's, or DIR/face_matte.png): where the matte is 0 (the scalp, ears and
    neck of the model's face region) the render is transparent and the
    footage under it shows, with a soft edge on the narrow face. A Holdout
    shader mixed into each skin material by the matte, read through the
    skin's UVs (the mouth and eyes keep theirs)."""
    materials = [m for m in face.data.materials if m and m.name.startswith("face") and m.use_nodes]
    for material in materials:
        nodes, links = material.node_tree.nodes, material.node_tree.links
        output = next(n for n in nodes if n.type == "OUTPUT_MATERIAL" and n.is_active_output)
        surface = output.inputs["Surface"]
        if not surface.is_linked:
            continue
        shader = surface.links[0].from_socket
        matte = nodes.new("ShaderNodeTexImage")
        matte.image = image
        matte.extension = "EXTEND"
        uv = nodes.new("ShaderNodeUVMap")
        uv.uv_map = face.data.uv_layers[0].name
        links.new(uv.outputs["UV"], matte.inputs["Vector"])
        mix = nodes.new("ShaderNodeMixShader")
        links.new(matte.outputs["Color"], mix.inputs["Fac"])
        links.new(nodes.new("ShaderNodeHoldout").outputs[0], mix.inputs[1])  # Fac 0: the footage
        links.new(shader, mix.inputs[2])  # Fac 1: the face
        links.new(mix.outputs[0], surface)
    print("import_facecap: the face held out by %s (%d material(s))" % (image.name, len(materials)))


def centre_on_principal_point(camera, size):
    """facecap's principal point is (W/2, H/2) with pixel centres at integers
    (identity.json's principal_point_px), half a pixel right of and below the
    frame's centre, where a glTF camera looks; Blender's lens shift moves the
    view by that half pixel, so that the face lands where the fit put it. The
    shift's unit is the side the sensor fits (the glTF importer's: the
    height), or the larger side."""
    fit = camera.data.sensor_fit
    unit = size[1] if fit == "VERTICAL" else size[0] if fit == "HORIZONTAL" else max(size)
    camera.data.shift_x = -0.5 / unit
    camera.data.shift_y = 0.5 / unit


def image_size(folder):
    """The input's width and height from identity.json (any shot's)."""
    names = ["identity.json"] + sorted(n for n in os.listdir(folder) if n.startswith("identity_shot"))
    for name in names:
        path = os.path.join(folder, name)
        if os.path.isfile(path):
            with open(path) as f:
                size = json.load(f).get("image_size")
            if size:
                return int(size[0]), int(size[1])
    return None


def csv_lighting(frames_csv):
    """Each refined frame's 9 lighting coefficients (frames.csv's l0..l8), by frame."""
    with open(frames_csv, newline="") as f:
        reader = csv.DictReader(f)
        if "l0" not in (reader.fieldnames or []):
            return {}
        return {int(r["frame"]): [float(r["l%d" % i]) for i in range(9)]
                for r in reader if all(r.get("l%d" % i) for i in range(9))}


def add_footage_light(scene, lighting):
    """The world as the refinement found the footage lit, keyed frame by frame.

    facecap shades a surface of normal n, in the viewer's frame (x right, y up,
    z toward the camera), by l^T SH(n), SH(n) = (1, x, y, z, xy, xz, yz,
    x^2 - y^2, 3 z^2 - 1) (eq. 4.9): an irradiance over pi. A world whose
    radiance is L(w) = l0 + 3/2 (l1 x + l2 y + l3 z) + 4 (l4 xy + ... + l8 (3 z^2
    - 1)) gives a Lambertian surface that shading: each SH band of the radiance
    is scaled by the cosine lobe's A_l / pi = 1, 2/3, 1/4 (Ramamoorthi and
    Hanrahan 2001), which undoes it. Blender's world directions are glTF's
    camera frame turned to z up: x = X, y = Z, z = -Y (the camera at the origin
    looking along +Y). facecap's albedo and shading multiply pixel values, so
    the albedo and the footage are read as raw data and the view transform is
    Raw: the render is albedo x shading, as facecap's own renders are."""
    world = scene.world
    world.use_nodes = True
    nodes, links = world.node_tree.nodes, world.node_tree.links
    background = next(n for n in nodes if n.type == "BACKGROUND")

    def node(kind, operation=None, *inputs):
        n = nodes.new(kind)
        if operation:
            n.operation = operation
        for i, value in enumerate(inputs):
            if isinstance(value, (int, float)):
                n.inputs[i].default_value = value
            else:
                links.new(value, n.inputs[i])
        return n.outputs[0]

    def math(operation, a, b):
        return node("ShaderNodeMath", operation, a, b)

    direction = nodes.new("ShaderNodeSeparateXYZ")
    links.new(nodes.new("ShaderNodeTexCoord").outputs["Generated"], direction.inputs[0])
    x, y, z = direction.outputs[0], direction.outputs[2], math("MULTIPLY", direction.outputs[1], -1.0)
    terms = [x, y, z, math("MULTIPLY", x, y), math("MULTIPLY", x, z), math("MULTIPLY", y, z),
             math("SUBTRACT", math("MULTIPLY", x, x), math("MULTIPLY", y, y)),
             math("SUBTRACT", math("MULTIPLY", math("MULTIPLY", z, z), 3.0), 1.0)]
    band_scale = [1.0] + [1.5] * 3 + [4.0] * 5
    coefficients = [nodes.new("ShaderNodeValue") for _ in range(9)]
    radiance = coefficients[0].outputs[0]
    for k in range(1, 9):
        radiance = math("ADD", radiance, math("MULTIPLY", coefficients[k].outputs[0], terms[k - 1]))
    links.new(math("MAXIMUM", radiance, 0.0), background.inputs["Strength"])
    background.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    for frame, l in sorted(lighting.items()):
        for k in range(9):
            socket = coefficients[k].outputs[0]
            socket.default_value = band_scale[k] * l[k]
            socket.keyframe_insert("default_value", frame=frame)
    if world.node_tree.animation_data and world.node_tree.animation_data.action:
        for curve in world.node_tree.animation_data.action.fcurves:
            for key in curve.keyframe_points:
                key.interpolation = "LINEAR"
    for image in bpy.data.images:  # the albedo (the detail maps are already)
        image.colorspace_settings.name = "Non-Color"
    for clip in bpy.data.movieclips:
        clip.colorspace_settings.name = "Non-Color"
    scene.view_settings.view_transform = "Raw"
    print("import_facecap: the world lit as the footage was (%d frames of lighting)" % len(lighting))


def add_plate(scene, camera, video):
    """The footage behind the face: the camera's background in the viewport,
    and under the render in the compositor (the render's background
    transparent, the view transform Standard so that the plate keeps its
    colours; add_footage_light makes both raw). Clip frame 1, the video's
    first, plays on scene frame 0."""
    clip = bpy.data.movieclips.load(os.path.abspath(video))
    if clip.frame_duration == 0:
        fail("cannot read %s: no frames Blender can decode" % video)
    clip.frame_start = 0
    scene.active_clip = clip
    if camera:
        camera.data.show_background_images = True
        background = camera.data.background_images.new()
        background.source = "MOVIE_CLIP"
        background.clip = clip
    scene.render.film_transparent = True
    scene.view_settings.view_transform = "Standard"
    scene.use_nodes = True
    tree = scene.node_tree
    layers = next((n for n in tree.nodes if n.type == "R_LAYERS"), None) or tree.nodes.new("CompositorNodeRLayers")
    composite = next((n for n in tree.nodes if n.type == "COMPOSITE"), None) or \
        tree.nodes.new("CompositorNodeComposite")
    plate = tree.nodes.new("CompositorNodeMovieClip")
    plate.clip = clip
    fit = tree.nodes.new("CompositorNodeScale")  # the clip's pixels onto the render's, at any percentage
    fit.space = "RENDER_SIZE"
    fit.frame_method = "STRETCH"
    over = tree.nodes.new("CompositorNodeAlphaOver")
    tree.links.new(plate.outputs["Image"], fit.inputs["Image"])
    tree.links.new(fit.outputs["Image"], over.inputs[1])
    tree.links.new(layers.outputs["Image"], over.inputs[2])
    tree.links.new(over.outputs["Image"], composite.inputs["Image"])
    print("import_facecap: %s behind the face (%d frames)" % (os.path.basename(video), clip.frame_duration))
    return clip


def main():
    args = parse_arguments()
    if not 0 <= args.subdivisions <= 6:
        fail("--subdivisions must be 0 to 6 (each level has four times the faces of the one before)")
    if not args.dir and not args.glb:
        fail("give the track folder (DIR) or the animation (--glb FILE)")
    if args.dir and not os.path.isdir(args.dir):
        fail(args.dir + " is not a folder")
    glb = args.glb or os.path.join(args.dir, "animation.glb")
    if not os.path.isfile(glb):
        fail(glb + " not found (run `facecap track ... --gltf`)")
    if args.video and not os.path.isfile(args.video):
        fail(args.video + " not found")
    # The track folder's files, where one is given.
    def in_folder(name):
        path = os.path.join(args.dir, name) if args.dir else None
        return path if path and os.path.exists(path) else None

    # An empty scene (Blender's startup cube would sit around the camera, at
    # the origin), lit evenly by a white world so that the face shows its albedo.
    bpy.ops.wm.read_homefile(use_empty=True)
    scene = bpy.context.scene
    scene.world = bpy.data.worlds.new("facecap")
    scene.world.color = (1.0, 1.0, 1.0)
    keyed_at = 30
    scene.render.fps, scene.render.fps_base = keyed_at, 1.0  # what the importer keys at
    before = set(bpy.data.objects)
    try:
        bpy.ops.import_scene.gltf(filepath=glb)
    except RuntimeError as e:  # the importer's own message, on one line
        fail("cannot read %s: %s" % (glb, " ".join(str(e).split())))
    objects = [o for o in bpy.data.objects if o not in before]
    actions = imported_actions(objects)
    # The input's rate: frames.csv's where the folder is a track's, else the keys'.
    frames_csv = in_folder("frames.csv")
    rate = csv_frame_rate(frames_csv) if frames_csv else key_frame_rate(actions, keyed_at)
    fps, fps_base = blender_rate(rate) if rate else (keyed_at, 1.0)
    scene.render.fps, scene.render.fps_base = fps, fps_base
    if fps / fps_base != keyed_at:
        retime(actions, fps / fps_base / keyed_at)
    scene.frame_start, scene.frame_end = key_range(actions)
    scene.frame_set(scene.frame_start)
    cameras = [o for o in objects if o.type == "CAMERA"]
    if cameras:
        scene.camera = cameras[0]
    clip = add_plate(scene, cameras[0] if cameras else None, args.video) if args.video else None
    size = (image_size(args.dir) if args.dir else None) or (tuple(clip.size) if clip else None)
    if size:  # the camera sees what the video frame shows
        scene.render.resolution_x, scene.render.resolution_y = size
        scene.render.resolution_percentage = 100
        if scene.camera:
            centre_on_principal_point(scene.camera, size)
    faces = [o for o in objects if o.type == "MESH"]
    if not faces:
        fail(glb + " holds no mesh")
    lighting = csv_lighting(frames_csv) if frames_csv else {}
    if lighting and not args.even_light:
        add_footage_light(scene, lighting)  # after add_plate: the plate too is read raw
    if clip and not args.whole_face:  # with no footage behind, a held-out neck would render black
        embedded = glb_image_bytes(glb, "face_matte")
        matte_png = in_folder("face_matte.png")
        if embedded:
            add_face_matte(faces[0], load_image_bytes(embedded, "face_matte.png", "the face matte in " + glb))
        elif matte_png:  # a file written before the matte travelled in it
            add_face_matte(faces[0], load_image(matte_png))
    detail_dir = in_folder("detail")
    if detail_dir:
        add_detail(faces[0], detail_dir, args.subdivisions)
    print("import_facecap: %s at %.3f fps, frames %d-%d" % (os.path.basename(glb), fps / fps_base,
                                                             scene.frame_start, scene.frame_end))
    if args.save:
        bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(args.save))


if __name__ == "__main__":  # run by Blender (--python); a probe may import the functions
    main()
