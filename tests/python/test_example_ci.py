"""The intended CI use of the gblens module (docs/python.md): render a frame, compare it with a golden
capture by meaning, assert on the figures, and leave the report page for a reviewer when it fails. The
golden capture stands for one a project commits (here made by `gblens capture` with the same options,
as tests/golden/golden.sh makes the project's own); the thresholds are golden.sh's."""
import os

import pytest

import gblens
from conftest import SOURCE, run

OPTIONS = dict(size=(160, 90), lights=16, time=2.5, shadow_map_size=256)
# About one step of each target's storage format, on at most 0.1 % of the pixels (tests/golden/golden.sh).
THRESHOLDS = dict(warn=0, failpercent=0.1,
                  fail={"": 0.004, "hdr": 0.01, "normal_shadow.Normal": 0.1, "normal_shadow.Shadow": 0.004,
                        "depth": 1e-6, "depth_stencil.HardwareDepth": 1e-6, "shadow_map": 1e-6,
                        "depth_stencil.Stencil": 0, "coverage_masked": 0, "coverage_full": 0})


@pytest.fixture(scope="module")
def golden(tmp_path_factory):
    path = tmp_path_factory.mktemp("golden") / "temple"
    run("capture", "builtin:temple", "--size", "160x90", "--lights", 16, "--time", 2.5, "--shadow-map-size", 256, "-o", path)
    return str(path)


def test_render_matches_the_golden_capture(golden, tmp_path):
    frame = gblens.render("builtin:temple", **OPTIONS)
    result = gblens.compare(golden, frame, **THRESHOLDS)
    if not result.passed:
        result.report(tmp_path / "report")  # the page a reviewer opens from the CI job's artifacts
    assert result.passed, result.text
    assert result.groups["normal_shadow.Normal"]["metrics"]["max_degrees"] <= 0.1
    assert result.groups["depth"]["max_error"] <= 1e-6
    assert result.flip[0]["target"] == "final" and result.flip[0]["mean"] < 0.01


def test_a_changed_frame_fails_with_the_quantities_that_moved(golden):
    result = gblens.compare(golden, gblens.render("builtin:temple", **{**OPTIONS, "time": 2.6}), **THRESHOLDS)
    assert not result.passed and result.exit_code == 2
    assert {"hdr", "final"} <= {key for key, g in result.groups.items() if g["result"] == "fail"}


def test_an_imported_gbuffer_against_its_own_passes():
    # Blender's passes through the shipped layout: the decoded normals are unit, in Blender's axes.
    frame = gblens.open(os.path.join(SOURCE, "tests", "data", "blender", "cycles.exr"), layout="builtin:blender-cycles")
    normals = frame["Normal"][frame.mask("surface")]
    assert abs((normals ** 2).sum(axis=-1) - 1).max() < 1e-6
    assert frame.check()["counts"]["nan"] == 0
