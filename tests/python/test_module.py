"""The gblens module against independent computations: targets against the EXR files read with
OpenImageIO's own Python binding; decoded normals, depths and positions against `gblens probe --json` at
sampled pixels and against a numpy reconstruction from the camera matrices; the Blender import in
Blender's own axes against the passes Cycles wrote; the probe, stats and check against the CLI's JSON;
memory shared with the frame and alive after it; errors with the CLI's messages."""
import gc
import json
import os

import numpy as np
import OpenImageIO as oiio
import pytest

import gblens
from conftest import SOURCE, cli_message, run, run_json

PIXELS = [(0, 0), (5, 30), (20, 12), (31, 18), (40, 25), (63, 35), (50, 3)]


def exr_channels(path):
    """name -> float64 or uint32 array (H, W) of every channel of an EXR, read by OpenImageIO."""
    inp = oiio.ImageInput.open(path)
    assert inp, oiio.geterror()
    spec = inp.spec()
    out = {}
    for i, name in enumerate(spec.channelnames):
        fmt = spec.channelformat(i)
        t = "uint" if fmt == oiio.UINT32 else "half" if fmt == oiio.HALF else "float"
        pixels = inp.read_image(0, 0, i, i + 1, fmt)
        out[name] = (t, np.asarray(pixels).reshape(spec.height, spec.width))
    inp.close()
    return out


def eye_ray_points(cam, w, h):
    """Eye-space points on each pixel centre's ray, from eye_from_clip alone (Vulkan clip: y down)."""
    xs, ys = np.meshgrid((np.arange(w) + 0.5) / w * 2 - 1, (np.arange(h) + 0.5) / h * 2 - 1)
    clip = np.stack([xs, ys, np.full_like(xs, 0.5), np.ones_like(xs)], axis=-1)
    e = clip @ cam["eye_from_clip"].T
    return e[..., :3] / e[..., 3:4]


def test_targets_are_the_exr_contents_without_a_copy(captures):
    f = gblens.open(captures["a"])
    manifest = json.load(open(os.path.join(captures["a"], "manifest.json")))
    assert sorted(f.targets) == sorted(t["name"] for t in manifest["targets"])
    for t in manifest["targets"]:
        arr = f.targets[t["name"]]
        exr = exr_channels(os.path.join(captures["a"], t["file"]))
        assert arr.shape == (t["height"], t["width"], len(t["channels"])), t["name"]
        assert arr.dtype == {"u8": np.uint8, "i8": np.int8, "u16": np.uint16, "i16": np.int16, "f16": np.float16, "f32": np.float32,
                             "u32": np.uint32}[t["type"]]
        if arr.dtype.kind == "i":  # signed integers: the EXR's raw channel holds their bits as unsigned
            arr = arr.view(arr.dtype.str.replace("i", "u"))
        for c, channel in enumerate(t["channels"]):
            raw = exr.get(f"{t['name']}.raw.{channel}")  # 8/16-bit integers: the stored integers
            kind, values = raw if raw else exr[f"{t['name']}.{channel}"]
            np.testing.assert_array_equal(arr[..., c].astype(np.float64), values.astype(np.float64), err_msg=t["name"])
    # No copy: the arrays are views of the frame's memory, kept alive by their base.
    hdr = f.targets["hdr"]
    assert not hdr.flags.owndata and hdr.base is not None
    assert np.shares_memory(hdr, f.targets["hdr"])
    expected = hdr.copy()
    del f
    gc.collect()
    np.testing.assert_array_equal(hdr, expected)  # still the frame's memory, alive through the array


def test_decoded_quantities_equal_probe_and_a_numpy_reconstruction(captures):
    f = gblens.open(captures["a"])
    cam, w, h = f.camera, f.width, f.height
    exr = exr_channels(os.path.join(captures["a"], "depth.exr"))
    z = exr["depth.Z"][1].astype(np.float64)
    ray = eye_ray_points(cam, w, h)
    eye = np.where(z[..., None] > 0, ray * (z / -ray[..., 2])[..., None], np.nan)
    world = np.concatenate([eye, np.ones((h, w, 1))], axis=-1) @ cam["world_from_eye"].T
    pos_eye, pos_world = f.position("depth", "eye"), f.position("depth", "world")
    assert np.array_equal(np.isnan(pos_eye[..., 0]), z <= 0)
    np.testing.assert_allclose(pos_eye, eye, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(pos_world, world[..., :3], rtol=1e-9, atol=1e-9)
    # The stored world positions (rgba32f) against the same reconstruction where a surface was drawn
    # (the position target has no background value: the sky holds what was cleared).
    surface = z > 0
    np.testing.assert_allclose(f.position("stored", "world")[surface], world[..., :3][surface], rtol=0, atol=2e-3)
    np.testing.assert_allclose(f["Position"][surface], world[..., :3][surface], rtol=0, atol=2e-3)
    # Hardware depth through eye_from_clip: the stored value as the quantity's value, positions from it.
    d = exr_channels(os.path.join(captures["a"], "depth_stencil.exr"))["depth_stencil.Depth"][1].astype(np.float64)
    xs, ys = np.meshgrid((np.arange(w) + 0.5) / w * 2 - 1, (np.arange(h) + 0.5) / h * 2 - 1)
    e = np.stack([xs, ys, d, np.ones_like(d)], axis=-1) @ cam["eye_from_clip"].T
    far = 0.0 if cam["reversed_z"] else 1.0
    hw = np.where((d != far)[..., None], e[..., :3] / e[..., 3:4], np.nan)
    np.testing.assert_allclose(f.position("HardwareDepth", "eye"), hw, rtol=1e-9, atol=1e-9)
    np.testing.assert_array_equal(f["HardwareDepth"], np.where(d != far, d, np.nan))  # scalars: (H, W)
    np.testing.assert_array_equal(f["Depth"], np.where(surface, z, np.nan))  # eye depth, as stored
    # Normals: view space, unit, where a surface was drawn; the stored values decoded by numpy (the
    # default is octahedral in rgba16_snorm: Meyer et al. 2010, sign(0) = +1).
    assert f.manifest["options"]["normal_format"] == "oct-rg16"
    ch = exr_channels(os.path.join(captures["a"], "normal_shadow.exr"))
    o = np.stack([ch[f"normal_shadow.raw.N.{c}"][1].astype(np.uint16).view(np.int16) for c in "UV"], -1)
    o = np.maximum(o.astype(np.float64) / 32767.0, -1.0)
    n = np.concatenate([o, 1.0 - np.abs(o).sum(-1, keepdims=True)], -1)
    fold = n[..., 2] < 0
    xy = n[fold, :2]
    n[fold, :2] = (1.0 - np.abs(xy[:, ::-1])) * np.where(xy >= 0, 1.0, -1.0)
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    np.testing.assert_allclose(f["Normal"], np.where(surface[..., None], n, np.nan), atol=1e-12)
    # The probe at sampled pixels: the same decoded values (the layout's space: view for normals, world
    # for the stored positions), the same reconstructions.
    for x, y in PIXELS:
        probe = run_json("probe", captures["a"], x, y, "--json")
        assert f.probe(x, y) == probe
        q = {e["name"]: e for e in probe["quantities"]}
        for name in ("Normal", "Depth", "HardwareDepth", "Albedo", "HDR", "PrimitiveId", "Position"):
            ours = f[name][y, x]
            if q[name]["values"]:
                np.testing.assert_allclose(ours, q[name]["values"], rtol=1e-12, atol=1e-12, err_msg=f"{name} at {x},{y}")
            else:
                assert np.isnan(ours).all(), f"{name} at {x},{y}"
        recon = {r["quantity"]: r for r in probe["reconstructions"]}
        if recon["Depth"]["valid"]:
            np.testing.assert_allclose(pos_world[y, x], recon["Depth"]["world"], rtol=1e-12, atol=1e-12)
            np.testing.assert_allclose(pos_eye[y, x], recon["Depth"]["eye"], rtol=1e-12, atol=1e-12)
    assert f.mask("surface").dtype == bool and np.array_equal(f.mask("surface"), z > 0)


def test_blender_import_comes_back_in_blenders_axes(captures):
    exr = os.path.join(SOURCE, "tests", "data", "blender", "cycles.exr")
    f = gblens.open(exr, layout="builtin:blender-cycles")
    ch = exr_channels(exr)
    passes = lambda name, comps: np.stack([ch[f"ViewLayer.{name}.{c}"][1] for c in comps], -1).astype(np.float64)
    position, normal, depth = passes("Position", "XYZ"), passes("Normal", "XYZ"), passes("Depth", "Z")[..., 0]
    surface = depth < 1e9
    # Stored quantities in the layout's own (Blender, Z-up world) axes: what Cycles wrote.
    np.testing.assert_allclose(f["Position"][surface], position[surface], rtol=1e-9, atol=1e-9)
    n = normal[surface] / np.linalg.norm(normal[surface], axis=-1, keepdims=True)
    np.testing.assert_allclose(f["Normal"][surface], n, atol=1e-9)
    # Positions from Depth and the camera, in Blender's axes, against the Position pass (Cycles traced
    # each ray within 0.005 px of the pixel centre: millimetres at these depths).
    from_depth = f.position("depth", "world")
    assert np.array_equal(~np.isnan(from_depth[..., 0]), surface)
    np.testing.assert_allclose(from_depth[surface], position[surface], atol=2e-3)
    # The probe agrees (its world is the layout's too); gblens's own Y-up world is Blender's (x, z, -y).
    for x, y in [(10, 80), (80, 45), (120, 60)]:
        probe = f.probe(x, y)
        assert probe == run_json("probe", captures["blender"], x, y, "--json")
        recon = next(r for r in probe["reconstructions"] if r["quantity"] == "Depth")
        np.testing.assert_allclose(from_depth[y, x], recon["world"], rtol=1e-12, atol=1e-12)
        p = from_depth[y, x]
        gblens_world = np.append([p[0], p[2], -p[1]], 1.0) @ f.camera["eye_from_world"].T
        np.testing.assert_allclose(gblens_world[:3], recon["eye"], rtol=1e-9, atol=1e-9)


def test_stats_check_and_save_equal_the_cli(captures, tmp_path):
    f = gblens.open(captures["a"])
    assert f.stats((8, 4, 20, 10)) == run_json("stats", captures["a"], "--rect", "8,4,20,10", "--json")
    assert f.stats("0,0,64,36", target="hdr") == run_json("stats", captures["a"], "--rect", "0,0,64,36", "--target", "hdr", "--json")
    code, out, _ = run("check", captures["a"], "--json", check=False)
    assert f.check() == json.loads(out)
    code, out, _ = run("check", captures["a"], "--json", "--policy", "denormal=fault", "--policy", "Normal.out_of_range=warn", check=False)
    assert f.check(["denormal=fault", "Normal.out_of_range=warn"]) == json.loads(out)
    assert f.check({"denormal": "fault", "Normal.out_of_range": "warn"}) == json.loads(out)
    with pytest.raises(gblens.ArgumentError) as e:
        f.check(["denormal=sometimes"])
    cli = cli_message(run("check", captures["a"], "--policy", "denormal=sometimes", check=False)[2], "check")
    assert str(e.value) == "policy=" + cli[len("--policy "):]
    f.save(tmp_path / "saved")
    assert gblens.compare(captures["a"], str(tmp_path / "saved"), flip=False).exit_code == 0


def test_errors_carry_the_cli_messages(captures, tmp_path):
    missing = str(tmp_path / "nowhere")
    with pytest.raises(gblens.Error) as e:
        gblens.open(missing)
    assert str(e.value) == cli_message(run("probe", missing, 0, 0, check=False)[2], "probe")
    exr = os.path.join(SOURCE, "tests", "data", "blender", "cycles.exr")
    with pytest.raises(gblens.Error) as e:
        gblens.open(exr, layout=str(tmp_path / "no-layout.json"))
    assert str(e.value) == cli_message(run("import", exr, "--layout", tmp_path / "no-layout.json", "-o", tmp_path / "x", check=False)[2], "import")
    assert not (tmp_path / "x").exists()
    with pytest.raises(gblens.ArgumentError) as e:  # the CLI's message, its flag named as the keyword
        gblens.compare(captures["a"], captures["b"], fail="abc")
    cli = cli_message(run("compare", captures["a"], captures["b"], "--fail", "abc", check=False)[2], "compare")
    assert cli.startswith("--fail abc") and str(e.value) == "fail=" + cli[len("--fail "):]
    with pytest.raises(gblens.Error) as e:
        gblens.compare(captures["a"], captures["b"], mask="silhouettes", exclude=["nope"])
    cli = cli_message(run("compare", captures["a"], captures["b"], "--exclude", "nope", check=False)[2], "compare")
    assert str(e.value) == (cli.replace("--exclude ", "exclude=", 1) if cli.startswith("--exclude") else cli)
    f = gblens.open(captures["a"])
    with pytest.raises(gblens.ArgumentError) as e:
        f.probe(64, 0)
    assert str(e.value).startswith("x=64, y=0: outside the 64x36 frame")
    with pytest.raises(KeyError):
        f["no_such_quantity"]
