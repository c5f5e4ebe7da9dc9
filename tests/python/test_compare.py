"""gblens.compare against `gblens compare --json` on the same pair (the same figures, mask and verdict);
its per-pixel errors against numpy over the two frames' targets; gblens.render against a `gblens capture`
of the same options (identical frames); gblens.error against `gblens error --json`; the report, JUnit
and image files written from Python."""
import json
import os

import numpy as np

import gblens
from conftest import SMALL, run


def without_paths(report):
    report = json.loads(json.dumps(report))
    report.pop("a"), report.pop("b"), report.pop("seconds")  # seconds: wall time, not a figure
    for g in report["groups"]:
        g.pop("heatmap")
    for f in report["flip"]:
        f.pop("heatmap")
    if report["mask"]:
        report["mask"].pop("image")
    return report


def test_figures_equal_the_cli(captures, tmp_path):
    result = gblens.compare(captures["a"], captures["b"], mask="silhouettes", fail={"": 0.01, "hdr": 0.05}, warn=0)
    code, out, _ = run("compare", captures["a"], captures["b"], "--mask", "silhouettes", "--fail", "0.01", "--fail",
                       "hdr=0.05", "--warn", "0", "--json", "-", check=False)
    assert result.exit_code == code == 2 and not result.passed
    assert without_paths(result.json) == without_paths(json.loads(out))
    assert result.groups["hdr"]["covers"] == "unmasked" and result.groups["hdr"]["masked"]["covers"] == "masked"
    # The per-pixel error of hdr: the largest |A - B| over the channels, from the two frames' arrays.
    a, b = gblens.open(captures["a"]), gblens.open(captures["b"])
    expected = np.abs(a.targets["hdr"].astype(np.float64) - b.targets["hdr"].astype(np.float64)).max(axis=-1)
    errors = result.errors("hdr")
    assert errors.dtype == np.float32 and not errors.flags.owndata
    np.testing.assert_allclose(errors, expected, rtol=1e-6)
    assert int((result.mask != 0).sum()) == result.json["mask"]["pixels"]
    # Files for CI: the page, JUnit, the images.
    result.report(str(tmp_path / "page"))
    result.junit(str(tmp_path / "junit.xml"), name="temple")
    result.write_images(str(tmp_path / "images"))
    assert (tmp_path / "page" / "index.html").exists() and (tmp_path / "junit.xml").exists()
    assert (tmp_path / "images" / "hdr.png").exists() and (tmp_path / "images" / "mask.png").exists()


def test_render_is_the_frame_capture_renders(captures):
    frame = gblens.render("builtin:temple", size=(64, 36), lights=6, shadow_map_size=256, primitive_id=True,
                          position="rgba32f", position_space="world")
    assert frame.width == 64 and frame.height == 36
    result = gblens.compare(captures["a"], frame)
    assert result.exit_code == 0, result.text
    with np.testing.assert_raises(gblens.Error):
        gblens.render(size="12")


def test_error_equals_the_cli():
    options = dict(size=(32, 18), lights=2, shadow_map_size=128)
    figures = gblens.error("builtin:temple", **options)
    _, out, _ = run("error", "--size", "32x18", "--lights", "2", "--shadow-map-size", "128", "--json")
    assert figures == json.loads(out)
