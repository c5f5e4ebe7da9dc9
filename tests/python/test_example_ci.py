"""The intended CI use of the gblens module (docs/python.md): render the frame a golden capture holds,
compare it with the golden capture by meaning, assert on the figures, and leave the report page for a
reviewer when it fails. The golden capture and thresholds are the project's own (tests/golden)."""
import os

import gblens
from conftest import SOURCE

GOLDEN = os.path.join(SOURCE, "tests", "golden", "temple")
# tests/golden/golden.sh's thresholds: about one storage step, on at most 0.1 % of the pixels.
THRESHOLDS = dict(warn=0, failpercent=0.1,
                  fail={"": 0.004, "hdr": 0.01, "normal_shadow.N": 0.1, "normal_shadow.Shadow": 0.004, "depth": 1e-6,
                        "depth_stencil.Depth": 1e-6, "shadow_map": 1e-6, "depth_stencil.Stencil": 0,
                        "coverage_masked": 0, "coverage_full": 0})


def test_render_matches_the_golden_capture(tmp_path):
    frame = gblens.render("builtin:temple", size=(160, 90), lights=16, time=2.5, shadow_map_size=256)
    result = gblens.compare(GOLDEN, frame, **THRESHOLDS)
    if not result.passed:
        result.report(str(tmp_path / "report"))  # the page a reviewer opens from the CI job's artifacts
    assert result.passed, result.text
    assert result.groups["normal_shadow.N"]["metrics"]["max_degrees"] <= 0.1
    assert result.groups["depth"]["max_error"] <= 1e-6
    assert result.flip[0]["target"] == "final" and result.flip[0]["mean"] < 0.01


def test_an_imported_gbuffer_against_its_own_passes():
    # Blender's passes through the shipped layout: the decoded normals are unit, in Blender's axes.
    frame = gblens.open(os.path.join(SOURCE, "tests", "data", "blender", "cycles.exr"), layout="builtin:blender-cycles")
    normals = frame["Normal"][frame.mask("surface")]
    assert abs((normals ** 2).sum(axis=-1) - 1).max() < 1e-6
    assert frame.check()["counts"]["nan"] == 0
