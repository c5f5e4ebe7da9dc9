# Renders a G-buffer with Blender's Cycles for gblens (assets/layouts/blender-cycles.json): the
# view-layer passes as one multilayer EXR (OUT_DIR/cycles.exr) and the camera as a sidecar JSON
# (OUT_DIR/camera.json). Without --scene it builds a small test scene in code (`make fixtures` writes
# tests/data/blender/ so, and tests/data/blender/ortho with --ortho --full-float); with --scene it
# renders the .blend Blender opened. docs/import.md explains.
#   blender -b --factory-startup -P assets/blender/render_gbuffer.py -- OUT_DIR [WIDTH HEIGHT] [--ortho] [--full-float]
#   blender -b my.blend -P assets/blender/render_gbuffer.py -- OUT_DIR --scene [--full-float]
# --ortho: the test scene through an orthographic camera; --full-float: colour passes in float32
# ("Float (Full)") instead of half. render_sequence.py renders an animation of the same scene.
import json
import math
import os
import sys

import bpy
import mathutils

# The test scene: (name, primitive, location, size, object pass index, material), Blender world
# coordinates (Z up). tests/unit/test_blender_import.cpp repeats the locations and both indices.
OBJECTS = [
    ("Floor", "plane", (0.0, 0.0, 0.0), 8.0, 1, "Grey"),
    ("Cube", "cube", (-1.2, 0.4, 0.5), 1.0, 2, "Red"),
    ("Sphere", "sphere", (1.1, -0.2, 0.7), 0.7, 3, "Blue"),
    ("Cone", "cone", (2.4, 1.2, 0.6), 0.6, 4, "Red"),
    ("Lamp", "sphere", (-0.3, -1.6, 0.25), 0.25, 5, "Glow"),
]
# name -> (material pass index, base colour, emission strength)
MATERIALS = {"Grey": (1, (0.5, 0.5, 0.5), 0.0), "Red": (2, (0.8, 0.1, 0.05), 0.0),
             "Blue": (3, (0.05, 0.2, 0.8), 0.0), "Glow": (4, (1.0, 0.7, 0.3), 4.0)}
CAMERA_LOCATION = (4.5, -5.5, 3.2)
CAMERA_TARGET = (0.0, 0.3, 0.4)
CAMERA_LENS_MM = 35.0
ORTHO_SCALE = 9.0  # --ortho: the view's width in metres

PASSES = ("combined", "z", "normal", "position", "object_index", "material_index", "diffuse_color", "emit")
USAGE = ("usage: blender -b --factory-startup -P render_gbuffer.py -- OUT_DIR [WIDTH HEIGHT] [--ortho] [--full-float]\n"
         "       blender -b SCENE.blend -P render_gbuffer.py -- OUT_DIR --scene [--full-float]")


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    flags = {f: f in argv for f in ("--scene", "--ortho", "--full-float")}
    argv = [a for a in argv if a not in flags]
    own = flags["--scene"]
    if len(argv) not in (1, 3) or (own and (len(argv) != 1 or flags["--ortho"])):
        raise SystemExit(USAGE)
    size = (int(argv[1]), int(argv[2])) if len(argv) == 3 else (160, 90)
    return argv[0], size, own, flags["--ortho"], flags["--full-float"]


def make_material(name, index, colour, emission):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    bsdf = m.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*colour, 1.0)
    bsdf.inputs["Roughness"].default_value = 0.5
    bsdf.inputs["Emission"].default_value = (*colour, 1.0)
    bsdf.inputs["Emission Strength"].default_value = emission
    m.pass_index = index
    m.cycles.sample_as_light = False
    return m


def add_object(name, kind, location, size, pass_index, material):
    ops = bpy.ops.mesh
    if kind == "plane":
        ops.primitive_plane_add(size=size, location=location)
    elif kind == "cube":
        ops.primitive_cube_add(size=size, location=location)
    elif kind == "sphere":
        ops.primitive_uv_sphere_add(radius=size, location=location, segments=48, ring_count=24)
        bpy.ops.object.shade_smooth()
    elif kind == "cone":
        ops.primitive_cone_add(radius1=size, depth=2.0 * size, location=location, vertices=32)
    obj = bpy.context.active_object
    obj.name = name
    obj.pass_index = pass_index
    obj.data.materials.append(material)
    return obj


def build_scene(width, height, ortho):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    materials = {n: make_material(n, *v) for n, v in MATERIALS.items()}
    for name, kind, location, size, index, material in OBJECTS:
        obj = add_object(name, kind, location, size, index, materials[material])
        if MATERIALS[material][2] > 0.0:  # emissive: seen by the camera only (no fireflies on others)
            obj.visible_diffuse = obj.visible_glossy = False

    # One sun with sharp shadows (angle 0), a world that is seen but lights nothing and an emissive
    # object that is not sampled as a light: direct light from one light only, so one sample per
    # pixel gives a clean image (as a rasteriser would).
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", type="SUN"))
    sun.data.energy, sun.data.angle = 4.0, 0.0
    sun.rotation_euler = (math.radians(40), math.radians(10), math.radians(30))
    scene.collection.objects.link(sun)
    world = bpy.data.worlds.new("World")
    world.color = (0.05, 0.06, 0.08)
    world.cycles_visibility.diffuse = world.cycles_visibility.glossy = False
    world.cycles_visibility.transmission = world.cycles_visibility.scatter = False
    scene.world = world

    cam = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    cam.data.lens = CAMERA_LENS_MM
    if ortho:
        cam.data.type = "ORTHO"
        cam.data.ortho_scale = ORTHO_SCALE
    cam.data.clip_start, cam.data.clip_end = 0.1, 100.0
    cam.location = CAMERA_LOCATION
    scene.collection.objects.link(cam)
    # Aim at the target: the camera looks down its -Z with +Y up (Blender's convention).
    direction = mathutils.Vector(CAMERA_TARGET) - mathutils.Vector(CAMERA_LOCATION)
    cam.rotation_euler = direction.to_track_quat("-Z", "Y").to_euler()
    scene.camera = cam

    r = scene.render
    r.engine = "CYCLES"
    r.resolution_x, r.resolution_y, r.resolution_percentage = width, height, 100
    r.film_transparent = False
    scene.cycles.device = "CPU"
    scene.cycles.seed = 0
    scene.cycles.use_denoising = False
    # A G-buffer holds one surface per pixel, at the pixel centre. Cycles takes depth, position and
    # the indices from a pixel's first sample but averages normals over all samples (shorter than
    # unit where samples see different surfaces); one sample through a 0.01 px wide pixel filter
    # (within 0.005 px of the centre) makes every pass describe the same point.
    scene.cycles.samples = 1
    scene.cycles.filter_width = 0.01
    scene.cycles.max_bounces = 0
    return scene, cam


def own_scene():
    """The scene of the opened .blend, as it is, with notes where its settings make the passes differ
    from a G-buffer's one surface per pixel centre."""
    scene = bpy.context.scene
    cam = scene.camera
    if cam is None or cam.data.type not in ("PERSP", "ORTHO"):
        raise SystemExit("render_gbuffer.py: the scene needs a perspective or orthographic camera (gblens "
                         "reconstructs positions through a projection matrix; a panoramic camera has none)")
    scene.render.engine = "CYCLES"
    if scene.cycles.use_denoising:  # it changes only Combined, and Debian's Blender has no OpenImageDenoise
        print("render_gbuffer.py: note: denoising turned off (Combined is rendered without it)")
        scene.cycles.use_denoising = False
    if scene.cycles.samples > 1:
        print("render_gbuffer.py: note: %d samples: Cycles averages the Normal pass over them (not unit "
              "length where samples see different surfaces)" % scene.cycles.samples)
    if scene.cycles.filter_width > 0.01:
        print("render_gbuffer.py: note: pixel filter %.2f px: Depth, Position and the indices come from "
              "a ray up to %.3f px from the pixel centre" % (scene.cycles.filter_width, scene.cycles.filter_width / 2))
    if scene.view_layers[0].name != "ViewLayer":
        print('render_gbuffer.py: note: the view layer is "%s": replace "ViewLayer." in the layout\'s '
              "channel names" % scene.view_layers[0].name)
    return scene, cam


def configure_output(scene, full_float, passes=PASSES):
    """Every pass the layout reads, on the first view layer, into one multilayer EXR: colour passes
    in half float (float32 with --full-float); Blender keeps Depth, Normal, Position, Vector and the
    indices in float32 regardless. Passes not in `passes` are turned off (render_sequence.py's list
    has no Combined)."""
    layer = scene.view_layers[0]
    for p in PASSES + ("vector",):
        setattr(layer, "use_pass_" + p, p in passes)
    r = scene.render
    # No dates, times or file names in the EXR header: a regenerated fixture differs only where the
    # pixels do.
    for stamp in ("date", "time", "render_time", "frame", "frame_range", "memory", "hostname", "camera",
                  "lens", "scene", "marker", "filename", "sequencer_strip", "note"):
        setattr(r, "use_stamp_" + stamp, False)
    img = r.image_settings
    img.file_format = "OPEN_EXR_MULTILAYER"
    img.color_depth = "32" if full_float else "16"
    img.exr_codec = "ZIP"


def camera_json(scene, cam, width, height, extra=None):
    """The sidecar (docs/layout-format.md, "camera"): Blender's camera transform (world_from_view: the
    view looks down -Z, +Y up, world Z up) and calc_matrix_camera's OpenGL projection (y up, z -1..1),
    row-major as mathutils indexes them (m[row][col]). Blender keeps matrices in float32; these are
    the doubles of those floats, so gblens sees the numbers Cycles used. `extra`: more fields (a
    sequence's "time")."""
    depsgraph = bpy.context.evaluated_depsgraph_get()
    proj = cam.calc_matrix_camera(depsgraph, x=width, y=height, scale_x=scene.render.pixel_aspect_x,
                                  scale_y=scene.render.pixel_aspect_y)
    rows = lambda m: ",\n".join("    " + ", ".join(repr(float(m[r][c])) for c in range(4)) for r in range(4))
    fields = {"matrix_order": "row_major", "convention": "gl", "view_handedness": "right", "up": "z",
              "image_origin": "top", "size": [width, height],
              "projection": "orthographic" if cam.data.type == "ORTHO" else "perspective", **(extra or {})}
    text = "{\n"
    text += "".join("  %s: %s,\n" % (json.dumps(k), json.dumps(v)) for k, v in fields.items())
    text += '  "world_from_view": [\n%s],\n' % rows(cam.matrix_world)
    text += '  "clip_from_view": [\n%s]\n}\n' % rows(proj)
    json.loads(text)  # the hand-formatted text is JSON
    return text


def main():
    out_dir, (width, height), own, ortho, full_float = parse_args()
    os.makedirs(out_dir, exist_ok=True)
    scene, cam = own_scene() if own else build_scene(width, height, ortho)
    configure_output(scene, full_float)
    r = scene.render
    width = r.resolution_x * r.resolution_percentage // 100
    height = r.resolution_y * r.resolution_percentage // 100
    exr = os.path.join(out_dir, "cycles.exr")
    r.filepath = exr
    r.use_file_extension = False
    bpy.ops.render.render(write_still=True)
    with open(os.path.join(out_dir, "camera.json"), "w") as f:
        f.write(camera_json(scene, cam, width, height))
    print("render_gbuffer.py: wrote %s (%dx%d) and camera.json" % (exr, width, height))


if __name__ == "__main__":  # render_sequence.py imports this file for its scene and output settings
    main()
