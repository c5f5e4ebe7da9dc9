"""Sequences in the gblens module (open_sequence, Sequence, motion, flicker) against independent paths:
two sequences made by the gblens binary here (the committed Blender fixture imported with --frames,
and builtin:temple rendered with --sequence and an orbiting camera); each frame opened alone with
gblens.open("SEQ@N"); sequence.json, the Blender sidecars and the frames' manifests read with json;
`gblens motion --json` and `gblens flicker --json` run as subprocesses, `gblens motion -o`'s maps read
with OpenImageIO; numpy's own standard deviation over the stacked frames; the CLI's one-line messages."""
import json
import os

import numpy as np
import OpenImageIO as oiio
import pytest

import gblens
from conftest import SOURCE, cli_message, run, run_json

BLENDER = os.path.join(SOURCE, "tests", "data", "blender", "sequence")


@pytest.fixture(scope="module")
def sequences(tmp_path_factory):
    root = tmp_path_factory.mktemp("sequences")
    blender, temple = str(root / "blender"), str(root / "temple")
    run("import", os.path.join(BLENDER, "cycles_####.exr"), "--layout", "builtin:blender-cycles-sequence", "--frames", "1..5",
        "-o", blender)
    run("capture", "builtin:temple", "--size", "64x36", "--sequence", "3", "--time-step", "0.1", "--camera-motion", "orbit",
        "--motion", "on", "-o", temple)
    return {"blender": blender, "temple": temple, "root": root}


KINDS = ["blender", "temple"]


def manifest(path):
    return json.load(open(os.path.join(path, "sequence.json")))


@pytest.mark.parametrize("kind", KINDS)
def test_frames_and_arrays_are_each_frame_opened_alone(sequences, kind):
    path = sequences[kind]
    seq = gblens.open_sequence(path)
    listed = manifest(path)["frames"]
    assert len(seq) == len(listed) and seq.frames == [f["frame"] for f in listed]
    assert seq.path == path and seq.manifest["format"] == "gblens-sequence"
    first = gblens.open(f"{path}@{seq.frames[0]}")
    T, H, W = len(seq), first.height, first.width
    for name in ("Depth", "Normal"):
        stack = seq.array(name)
        assert stack.dtype == np.float64
        assert stack.shape == ((T, H, W) if name == "Depth" else (T, H, W, 3)), name
        np.testing.assert_array_equal(seq[name], stack)  # seq[name] is array(name)
        for k, n in enumerate(seq.frames):
            alone = gblens.open(f"{path}@{n}")[name]
            np.testing.assert_array_equal(stack[k], alone, err_msg=f"{name} frame {n}")  # NaN where NaN, else equal
            assert np.isfinite(stack[k]).any()
    # A stored target: the texels as Frame.targets has them, in their type.
    target = "depth"
    stored = seq.array(target, stored=True)
    for k, n in enumerate(seq.frames):
        alone = gblens.open(f"{path}@{n}").targets[target]
        assert stored.dtype == alone.dtype and stored.shape == (T, *alone.shape)
        np.testing.assert_array_equal(stored[k], alone)
    # Frames by position and by number: the capture folders sequence.json names.
    assert seq[0].path == os.path.join(path, listed[0]["dir"]) and seq[-1].path == os.path.join(path, listed[-1]["dir"])
    assert seq.frame(seq.frames[1]).path == os.path.join(path, listed[1]["dir"])
    assert [f.path for f in seq] == [os.path.join(path, f["dir"]) for f in listed]  # iteration stops at the end


def test_times_and_jitters_are_the_sources(sequences):
    """Blender's: the camera sidecars Blender's script wrote; gblens's: each frame's manifest (options)."""
    seq = gblens.open_sequence(sequences["blender"])
    sidecars = [json.load(open(os.path.join(BLENDER, f"camera_{n:04d}.json"))) for n in seq.frames]
    assert seq.times == [s["time"] for s in sidecars]
    assert seq.jitters == [tuple(s["jitter"]) for s in sidecars]
    seq = gblens.open_sequence(sequences["temple"])
    frames = manifest(sequences["temple"])["frames"]
    options = [json.load(open(os.path.join(sequences["temple"], f["dir"], "manifest.json")))["options"] for f in frames]
    assert seq.times == [o["time"] for o in options] and seq.times == pytest.approx([0.0, 0.1, 0.2])
    assert seq.jitters == [(0.0, 0.0)] * 3  # --jitter off: zero, said


def exr_channel(path, name):
    inp = oiio.ImageInput.open(path)
    assert inp, oiio.geterror()
    spec = inp.spec()
    i = list(spec.channelnames).index(name)
    values = np.asarray(inp.read_image(0, 0, i, i + 1, oiio.FLOAT)).reshape(spec.height, spec.width)
    inp.close()
    return values


@pytest.mark.parametrize("kind", KINDS)
def test_motion_agrees_and_is_the_clis(sequences, kind, tmp_path):
    path = sequences[kind]
    report = gblens.motion(path)
    maps = report.pop("maps")
    assert report == run_json("motion", path, "--json")  # every key and number, as the CLI prints them
    assert report["verdict"] == "agrees", report["findings"]
    assert gblens.motion(gblens.open_sequence(path))["pairs"] == report["pairs"]  # a Sequence or its folder
    run("motion", path, "-o", tmp_path / "maps")
    assert len(maps) == len(report["pairs"]) == len(gblens.open_sequence(path)) - 1
    for m, pair in zip(maps, report["pairs"]):
        assert (m["previous"], m["current"]) == (pair["previous"], pair["current"])
        assert m["error"].dtype == np.float32 and m["class"].dtype == np.uint32 and m["error"].shape == m["class"].shape
        counts = np.bincount(m["class"].ravel(), minlength=5)
        px = pair["pixels"]
        assert list(counts[1:]) == [px["static"], px["moving"], px["disoccluded"], px["wrong"]]
        assert counts[1:].sum() == px["surface"]
        # What `gblens motion -o` wrote for the pair, read by OpenImageIO.
        exr = str(tmp_path / "maps" / f"pair_{pair['current']:04d}.exr")
        np.testing.assert_array_equal(m["error"], exr_channel(exr, "motion.error"))
        np.testing.assert_array_equal(m["class"], exr_channel(exr, "motion.class").astype(np.uint32))


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("name", ["Depth", "Normal"])
def test_flicker_without_reprojection_is_numpys_std(sequences, kind, name):
    """The same pixel in every frame: the standard deviation (ddof 1) and the largest step between
    consecutive frames over the stacked arrays, computed by numpy, on the pixels every frame saw."""
    path = sequences[kind]
    seq = gblens.open_sequence(path)
    r = gblens.flicker(seq, name, reproject=False)
    maps = r.pop("maps")
    assert r == run_json("flicker", path, "--quantity", name, "--no-reproject", "--json")
    stack = seq.array(name)
    if stack.ndim == 3:
        stack = stack[..., None]
    everywhere = np.isfinite(stack[..., 0]).all(axis=0)
    assert everywhere.sum() > 0.3 * everywhere.size
    np.testing.assert_array_equal(maps["seen"] == len(seq), everywhere)
    assert maps["seen"].dtype == np.uint32 and maps["stddev"].dtype == np.float32
    sd = maps["stddev"].reshape(stack.shape[1:])
    step = maps["max_step"].reshape(stack.shape[1:])
    expected = np.std(stack, axis=0, ddof=1)
    # float32 storage (a relative 6e-8), and the one-pass sum of squares: an absolute error of about
    # sqrt(1e-16 * mean^2) = 1e-8 |value| where the deviation is near 0.
    scale = np.nanmax(np.abs(stack))
    np.testing.assert_allclose(sd[everywhere], expected[everywhere], rtol=1e-6, atol=1e-7 * scale)
    assert expected[everywhere].max() > 1e-4 * scale  # the frames do differ: the check is not 0 == 0
    expected_step = np.abs(np.diff(stack, axis=0)).max(axis=0).astype(np.float32)
    np.testing.assert_array_equal(step[everywhere], expected_step[everywhere])
    assert np.isnan(sd[maps["seen"] < 2]).all()


def test_flicker_reprojected_is_the_clis(sequences):
    path = sequences["blender"]
    r = gblens.flicker(path, "DiffCol", reference=3)
    maps = r.pop("maps")
    assert r == run_json("flicker", path, "--quantity", "DiffCol", "--reference", "3", "--json")
    assert r["reference"] == 3 and maps["stddev"].shape == (64, 96, 3) and maps["seen"].max() == 5


def test_bad_input_raises_the_clis_line(sequences):
    temple, root = sequences["temple"], sequences["root"]
    capture = os.path.join(temple, "frame_0000")  # a capture, no sequence
    for command, call in (("motion", lambda p: gblens.motion(p)), ("flicker", lambda p: gblens.flicker(p, "Depth")),
                          ("motion", gblens.open_sequence)):
        for p in (capture, str(root / "nowhere")):
            code, _, err = run(command, p, *(["--quantity", "Depth"] if command == "flicker" else []), check=False)
            assert code == 2
            with pytest.raises(gblens.Error) as e:
                call(p)
            assert str(e.value) == cli_message(err, command)
    seq = gblens.open_sequence(temple)
    _, _, err = run("probe", f"{temple}@99", "0", "0", check=False)
    for call in (lambda: seq.frame(99), lambda: gblens.open(f"{temple}@99")):
        with pytest.raises(gblens.Error) as e:
            call()
        assert str(e.value) == cli_message(err, "probe") and "no frame 99 (frames 0..2)" in str(e.value)
    _, _, err = run("probe", temple, "0", "0", check=False)  # the folder where one capture is expected
    with pytest.raises(gblens.Error) as e:
        gblens.open(temple)
    assert str(e.value) == cli_message(err, "probe") and "@N" in str(e.value)
    with pytest.raises(IndexError):
        seq[3]
    with pytest.raises(gblens.QuantityError, match="no quantity of that name"):
        seq["nope"]
    with pytest.raises(gblens.ArgumentError, match=r'^name="nope": not a target'):
        seq.array("nope", stored=True)
    # Flags named as the keywords, the rest of the CLI's line unchanged.
    for kwargs, flags, keyword in (({"reference": 9}, ["--reference", "9"], "reference="),
                                   ({"quantity": "nope"}, ["--quantity", "nope"], "quantity=")):
        _, _, err = run("flicker", temple, *(["--quantity", "Depth"] if "quantity" not in kwargs else []), *flags, check=False)
        with pytest.raises(gblens.ArgumentError) as e:
            gblens.flicker(temple, **{"quantity": "Depth", **kwargs})
        assert str(e.value) == cli_message(err, "flicker").replace(f"{flags[0]} ", keyword)
    _, _, err = run("motion", temple, "--motion", "Depth", check=False)
    with pytest.raises(gblens.ArgumentError) as e:
        gblens.motion(temple, motion="Depth")
    assert str(e.value) == cli_message(err, "motion").replace("--motion ", "motion=")
    with pytest.raises(gblens.ArgumentError, match=r"^bound=-1"):
        gblens.motion(temple, bound=-1)
