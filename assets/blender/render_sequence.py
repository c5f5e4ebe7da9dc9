# Renders a short animation of render_gbuffer.py's test scene with Cycles for gblens
# (assets/layouts/blender-cycles-sequence.json): a moving camera (translation and a small rotation), the
# Sphere translating and the Cube turning, keyed at every frame with linear interpolation and a speed
# that grows from frame to frame (so that motion toward the previous and the next frame differ),
# motion blur off. Per
# frame F: the view-layer passes as one multilayer EXR OUT_DIR/cycles_FFFF.exr and the camera sidecar
# OUT_DIR/camera_FFFF.json (render_gbuffer.py's, plus "time": (F - first) / fps seconds and "jitter": [0, 0]:
# Cycles samples pixels without moving the projection); and once,
# OUT_DIR/objects.json: the moving objects' and the camera's transforms for frames first-1 .. last+1
# (the frames Cycles' Vector pass looks at), which assets/blender/check_vectors.py checks the Vector
# pass against. `make fixtures` writes tests/data/blender/sequence so; docs/import.md explains.
#   blender -b --factory-startup -P assets/blender/render_sequence.py -- OUT_DIR [WIDTH HEIGHT] [--frames N] [--first F]
import json
import math
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import render_gbuffer as gbuffer  # noqa: E402  (the scene builder, the output settings and the sidecar)

# The passes each frame's EXR holds (Blender writes Combined whether asked or not).
PASSES = ("combined", "z", "normal", "position", "vector", "object_index", "diffuse_color")
# Motion, keyframed at every frame from first-1 to last+1 (the frames either side, which the Vector
# pass looks at, too) with linear interpolation between keys: segment k (frame first+k to first+k+1)
# moves STEP * (1 + ACCEL * k), so each frame's motion toward the next is larger than its motion from
# the previous one (1.33x at the first frame .. 1.14x at the fifth), and a vector toward the previous
# frame cannot pass for one toward the next with its sign turned (as it could at a constant speed).
# Camera: metres in world axes (Z up) and degrees added to its XYZ Euler angles, a median 3-4 pixels
# (up to 8.5) a frame at 96x64. The Sphere rises away from the camera, the Cube turns about its Z.
ACCEL = 0.25
CAMERA_STEP = (-0.12, 0.07, 0.05)
CAMERA_TURN_DEG = (0.3, 0.0, 0.5)
SPHERE_STEP = (0.0, 0.18, 0.06)
CUBE_TURN_DEG = 10.0
USAGE = "usage: blender -b --factory-startup -P render_sequence.py -- OUT_DIR [WIDTH HEIGHT] [--frames N] [--first F]"


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    opts = {"--frames": 5, "--first": 1}
    rest = []
    i = 0
    while i < len(argv):
        if argv[i] in opts:
            if i + 1 >= len(argv) or not argv[i + 1].lstrip("-").isdigit():
                raise SystemExit(USAGE)
            opts[argv[i]] = int(argv[i + 1])
            i += 2
        else:
            rest.append(argv[i])
            i += 1
    if len(rest) not in (1, 3) or opts["--frames"] < 1 or opts["--first"] < 1:
        raise SystemExit(USAGE)
    size = (int(rest[1]), int(rest[2])) if len(rest) == 3 else (96, 64)
    return rest[0], size, opts["--frames"], opts["--first"]


def keyframe(obj, path, first, last, step):
    """obj.<path> keyed at frames first-1 .. last+1: its value now plus step * travelled(k), k = frame -
    first; linear between the keys."""
    start = tuple(getattr(obj, path))
    for f in range(first - 1, last + 2):
        k = f - first
        travelled = k + ACCEL * k * (k - 1) / 2  # sum of segments 0 .. k-1 (k = -1: minus segment -1)
        setattr(obj, path, tuple(v + s * travelled for v, s in zip(start, step)))
        obj.keyframe_insert(path, frame=f)
    for fc in obj.animation_data.action.fcurves:
        if fc.data_path == path:
            for key in fc.keyframe_points:
                key.interpolation = "LINEAR"
    setattr(obj, path, start)


def animate(scene, cam, first, last):
    rad = math.radians
    sphere, cube = bpy.data.objects["Sphere"], bpy.data.objects["Cube"]
    keyframe(cam, "location", first, last, CAMERA_STEP)
    keyframe(cam, "rotation_euler", first, last, tuple(map(rad, CAMERA_TURN_DEG)))
    keyframe(sphere, "location", first, last, SPHERE_STEP)
    keyframe(cube, "rotation_euler", first, last, (0.0, 0.0, rad(CUBE_TURN_DEG)))
    scene.frame_start, scene.frame_end = first, last
    return {"Camera": cam, "Sphere": sphere, "Cube": cube}


def matrix_rows(m):
    return [[float(m[r][c]) for c in range(4)] for r in range(4)]


def main():
    out_dir, (width, height), count, first = parse_args()
    last = first + count - 1
    os.makedirs(out_dir, exist_ok=True)
    scene, cam = gbuffer.build_scene(width, height, False)
    gbuffer.configure_output(scene, False, PASSES)
    r = scene.render
    r.use_motion_blur = False  # with motion blur on, Cycles 3.4 writes the Vector pass as zeros
    r.use_file_extension = False
    fps = r.fps / r.fps_base
    moving = animate(scene, cam, first, last)

    # The transforms Cycles evaluates for the Vector pass: one frame either side of each rendered one.
    motion = {"fps": fps, "first": first, "last": last, "matrix_order": "row_major", "up": "z",
              "pass_index": {n: o.pass_index for n, o in moving.items() if n != "Camera"},
              "frames": {}}
    for f in range(first - 1, last + 2):
        scene.frame_set(f)
        motion["frames"][str(f)] = {n: matrix_rows(o.matrix_world) for n, o in moving.items()}

    for f in range(first, last + 1):
        scene.frame_set(f)
        exr = os.path.join(out_dir, "cycles_%04d.exr" % f)
        r.filepath = exr
        bpy.ops.render.render(write_still=True)
        with open(os.path.join(out_dir, "camera_%04d.json" % f), "w") as fh:
            fh.write(gbuffer.camera_json(scene, cam, width, height, {"time": (f - first) / fps, "jitter": [0.0, 0.0]}))
        print("render_sequence.py: wrote %s (%dx%d) and camera_%04d.json" % (exr, width, height, f))

    # Compact rows, one matrix a line (small diffs when regenerated).
    text = json.dumps({k: v for k, v in motion.items() if k != "frames"}, indent=2)[:-2]
    text += ',\n  "frames": {\n'
    text += ",\n".join('    "%s": {\n%s\n    }' % (f, ",\n".join('      "%s": %s' % (n, json.dumps(m)) for n, m in objs.items()))
                       for f, objs in motion["frames"].items())
    text += "\n  }\n}\n"
    json.loads(text)
    with open(os.path.join(out_dir, "objects.json"), "w") as fh:
        fh.write(text)
    print("render_sequence.py: wrote %d frames (%d..%d) and objects.json to %s" % (count, first, last, out_dir))


if __name__ == "__main__":
    main()
