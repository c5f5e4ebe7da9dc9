#!/usr/bin/python3
# Measures the convention of Cycles' Vector pass on a sequence render_sequence.py wrote (default
# tests/data/blender/sequence) and prints it with the residuals: for every surface pixel of frame N,
# the Position pass (world space, the point at the pixel centre) is carried to frames N-1 and N+1
# (static objects: as it is; the Sphere and the Cube: by their keyframed transforms, objects.json)
# and projected with those frames' cameras into pixels (x right, y down, row 0 at the top, texel
# (i, j)'s centre at (i + 0.5, j + 0.5)); the displacement from the pixel centre is set against each
# Vector channel pair under each sign of x and y, and against a fitted scale (units). Exit status 1
# when the measured convention is not the one the layout declares (assets/layouts/
# blender-cycles-sequence.json) or a residual exceeds --tolerance pixels.
#   /usr/bin/python3 assets/blender/check_vectors.py [DIR] [--tolerance PX]
# Needs python3-numpy and python3-openimageio (Debian's; not a pip environment's python3).
import glob
import json
import os
import re
import sys

import numpy as np
import OpenImageIO as oiio

LAYER = "ViewLayer."
PAIRS = {"XY": ("Vector.X", "Vector.Y"), "ZW": ("Vector.Z", "Vector.W")}
# Below, a hypothesis is (frame, sx, sy): stored = (sx * dx, sy * dy), (dx, dy) the displacement from
# this frame's pixel position to the point's position in that frame, x right, y down.
# What blender-cycles-sequence.json declares (and docs/import.md states):
#   XY = p(N-1) - p(N) with +y up: the motion quantity, direction to_previous, y up, pixels;
#   ZW = p(N) - p(N+1) with +y up: toward the next frame with the sign turned (a vector, scale -1).
DECLARED = {"XY": ("previous", 1, -1), "ZW": ("next", -1, 1)}
LAYOUT = os.path.join("assets", "layouts", "blender-cycles-sequence.json")


def words(frame, sx, sy):
    other = {"previous": "p(N-1)", "next": "p(N+1)"}[frame]
    text = "%s - p(N)" % other if sx == 1 else "p(N) - %s" % other
    return "%s, +y %s" % (text, "down" if sy == sx else "up")


def gblens_terms(frame, sx, sy):
    y = "down" if sy == sx else "up"
    if sx == 1:
        return 'a motion quantity: "units": "pixels", "direction": "to_%s", "y": "%s", "jitter": "excluded"' % (frame, y)
    return ('-1 x a motion "to_%s", "y": "%s" (no direction says so: a vector quantity with "scale": -1)'
            % (frame, y))


def layout_motion(path):
    """The layout's motion quantity on Vector.X/Y: (units, direction, y, jitter)."""
    with open(path) as f:
        layout = json.load(f)
    for t in layout["targets"]:
        names = t.get("source", {}).get("channels", [])
        for q in t.get("quantities", []):
            if q["quantity"] == "motion":
                ch = [names[c] if isinstance(c, int) else c for c in q["channels"]]
                return ch, (q.get("units", "pixels"), q.get("direction", "to_previous"), q.get("y"), q.get("jitter"))
    raise SystemExit("check_vectors.py: %s has no motion quantity" % path)


def read_exr(path):
    inp = oiio.ImageInput.open(path)
    if inp is None:
        raise SystemExit("check_vectors.py: cannot read %s: %s" % (path, oiio.geterror()))
    spec = inp.spec()
    pixels = inp.read_image(format="float")  # rows in file order: Blender's EXRs are top row first
    inp.close()
    names = [n[len(LAYER):] if n.startswith(LAYER) else n for n in spec.channelnames]
    return {n: pixels[..., i].astype(np.float64) for i, n in enumerate(names)}


def read_camera(path):
    with open(path) as f:
        c = json.load(f)
    return {"world_from_view": np.array(c["world_from_view"], float).reshape(4, 4),
            "clip_from_view": np.array(c["clip_from_view"], float).reshape(4, 4),
            "size": tuple(c["size"]), "time": c.get("time")}


def project(points, world_from_view, clip_from_view, size):
    """World points (n, 3) -> pixel coordinates (n, 2): x right, y down from the top edge."""
    h = np.concatenate([points, np.ones((len(points), 1))], axis=1)
    clip = (clip_from_view @ np.linalg.inv(world_from_view) @ h.T).T
    ndc = clip[:, :2] / clip[:, 3:4]
    w, hgt = size
    return np.stack([(ndc[:, 0] + 1) * 0.5 * w, (1 - ndc[:, 1]) * 0.5 * hgt], axis=1), clip[:, 3] > 0


def carry(points, ids, objects, pass_index, frame_from, frame_to):
    """Where each point is at frame_to: static ones where they are, moving ones by their transforms."""
    out = points.copy()
    for name, index in pass_index.items():
        sel = ids == index
        m = np.array(objects[str(frame_to)][name]) @ np.linalg.inv(np.array(objects[str(frame_from)][name]))
        out[sel] = (m[:3, :3] @ points[sel].T).T + m[:3, 3]
    return out


def stats(err):
    return (float(np.median(err)), float(np.percentile(err, 95)), float(err.max())) if len(err) else (0.0, 0.0, 0.0)


def fmt(s):
    return "median %.2e  p95 %.2e  max %.2e px" % s


def main():
    args = sys.argv[1:]
    tolerance = 0.01
    if "--tolerance" in args:
        i = args.index("--tolerance")
        tolerance = float(args[i + 1])
        del args[i:i + 2]
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    seq_dir = args[0] if args else os.path.join(root, "tests", "data", "blender", "sequence")
    frames = sorted(int(re.search(r"cycles_(\d+)\.exr$", p).group(1))
                    for p in glob.glob(os.path.join(seq_dir, "cycles_*.exr")))
    if not frames:
        raise SystemExit("check_vectors.py: no cycles_####.exr in %s" % seq_dir)
    with open(os.path.join(seq_dir, "objects.json")) as f:
        motion = json.load(f)
    objects, pass_index = motion["frames"], motion["pass_index"]
    ids_moving = np.array(list(pass_index.values()))

    # Per hypothesis (pair, frame, sx, sy): per-pixel errors on static pixels, on the moving objects (by
    # their keyframes, and as if static), and the sums of a least-squares scale fit.
    static_err, moving_err, as_static, fits, selfproj, magnitudes = {}, {}, {}, {}, [], {}
    counts = {"static": 0, "moving": 0}
    for n in frames:
        img = read_exr(os.path.join(seq_dir, "cycles_%04d.exr" % n))
        cam = read_camera(os.path.join(seq_dir, "camera_%04d.json" % n))
        if np.abs(cam["world_from_view"] - np.array(objects[str(n)]["Camera"])).max() > 1e-6:
            raise SystemExit("check_vectors.py: camera_%04d.json and objects.json disagree" % n)
        w, h = cam["size"]
        surface = img["Depth.Z"] < 1e9
        jj, ii = np.nonzero(surface)
        centre = np.stack([ii + 0.5, jj + 0.5], axis=1)
        pos = np.stack([img["Position." + a][surface] for a in "XYZ"], axis=1)
        ids = np.rint(img["IndexOB.X"][surface]).astype(int)
        static = ~np.isin(ids, ids_moving)
        counts["static"] += int(static.sum())
        counts["moving"] += int((~static).sum())
        here, _ = project(pos, cam["world_from_view"], cam["clip_from_view"], cam["size"])
        selfproj.append(np.linalg.norm(here - centre, axis=1))
        for target, m in (("previous", n - 1), ("next", n + 1)):
            world_from_view = np.array(objects[str(m)]["Camera"])  # the neighbour's camera, same lens
            there, front = project(carry(pos, ids, objects, pass_index, n, m), world_from_view,
                                   cam["clip_from_view"], cam["size"])
            disp = there - centre  # toward frame m, x right, y down
            still = project(pos, world_from_view, cam["clip_from_view"], cam["size"])[0] - centre  # as if static
            for pair, (cx, cy) in PAIRS.items():
                stored = np.stack([img[cx][surface], img[cy][surface]], axis=1)
                if target == "previous":
                    magnitudes.setdefault(pair, []).append(np.linalg.norm(stored[static], axis=1))
                for sx in (1, -1):
                    for sy in (1, -1):
                        e = np.linalg.norm(stored - disp * [sx, sy], axis=1)
                        key = (pair, target, sx, sy)
                        static_err.setdefault(key, []).append(e[static & front])
                        moving_err.setdefault(key, []).append(e[~static & front])
                        d = (disp * [sx, sy])[static & front]
                        s = stored[static & front]
                        fits.setdefault(key, []).append((float((s * d).sum()), float((d * d).sum())))
                        moved = ~static & front
                        as_static.setdefault(key, []).append(
                            np.linalg.norm(stored[moved] - still[moved] * [sx, sy], axis=1))

    cat = lambda d: {k: np.concatenate(v) for k, v in d.items()}
    static_err, moving_err, as_static = cat(static_err), cat(moving_err), cat(as_static)
    print("check_vectors.py: %s, frames %d..%d, %dx%d; surface pixels: %d static, %d on the Sphere and the Cube"
          % (seq_dir, frames[0], frames[-1], w, h, counts["static"], counts["moving"]))
    print("  Position pass projected by its own frame's camera: within %s of the pixel centres"
          % fmt(stats(np.concatenate(selfproj))))
    print("  median |stored - expected| on static pixels, expected = the displacement toward the frame, x right / y down,")
    print("  times the signs:              (+x,+y)   (+x,-y)   (-x,+y)   (-x,-y)")
    for pair in PAIRS:
        for target in ("previous", "next"):
            row = [np.median(static_err[(pair, target, sx, sy)]) for sx in (1, -1) for sy in (1, -1)]
            print("    Vector.%s vs toward %-8s %s" % (pair, target, "  ".join("%8.4f" % v for v in row)))

    ok = True
    print("Measured (p(F): the point's pixel position in frame F, x right, N this frame; pixels of the render):")
    for pair in PAIRS:
        key = min(((pair, t, sx, sy) for t in ("previous", "next") for sx in (1, -1) for sy in (1, -1)),
                  key=lambda k: np.median(static_err[k]))
        num, den = map(sum, zip(*fits[key]))
        scale = num / den
        s_stat, s_mov, s_still = stats(static_err[key]), stats(moving_err[key]), stats(as_static[key])
        size = stats(np.concatenate(magnitudes[pair]))
        print("  Vector.%s = %s   (least-squares scale %.6f: pixels; |vector| on static pixels: median %.2f, max %.2f px)"
              % (pair, words(*key[1:]), scale, size[0], size[2]))
        print("      static pixels:           %s" % fmt(s_stat))
        print("      Sphere and Cube pixels:  %s  (against their keyframed motion)" % fmt(s_mov))
        print("      the same taken as static: %s  (their own motion is in the pass)" % fmt(s_still))
        if key[1:] != DECLARED[pair]:
            print("      but check_vectors.py expects %s: the convention changed" % words(*DECLARED[pair]))
            ok = False
        if s_stat[2] > tolerance or s_mov[2] > tolerance or abs(scale - 1) > tolerance:
            print("      a residual exceeds --tolerance %g px" % tolerance)
            ok = False
        print("      in gblens's terms: %s" % gblens_terms(*key[1:]))
    layout = os.path.join(root, LAYOUT)
    if os.path.exists(layout):
        channels, declared = layout_motion(layout)
        want = ([LAYER + "Vector.X", LAYER + "Vector.Y"], ("pixels", "to_previous", "up", "excluded"))
        same = (channels, declared) == want
        print("  %s's motion quantity: %s %s: %s" % (LAYOUT, channels, declared,
                                                 "agrees" if same else "DISAGREES (want %s %s)" % want))
        ok = ok and same
    print("check_vectors.py: %s" % ("ok" if ok else "FAILED"))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
