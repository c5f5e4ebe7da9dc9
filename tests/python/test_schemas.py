"""The JSON that `probe`, `stats`, `check` and `compare` print is an interface: every output here, on
gblens's own frames and on an imported Blender frame (another renderer's layout), is validated against
its JSON Schema in docs/schemas (python3-jsonschema, Draft 2020-12), carries the schema's format and
version, and keeps the same keys whichever layout the frame has. The schemas can fail: an output
with a key taken away or added is refused."""
import copy
import json
import os

import jsonschema
import pytest

from conftest import SOURCE, run, run_json

SCHEMAS = os.path.join(SOURCE, "docs", "schemas")


def schema(name):
    s = json.load(open(os.path.join(SCHEMAS, name + ".schema.json")))
    jsonschema.Draft202012Validator.check_schema(s)
    return s


def valid(name, document):
    s = schema(name)
    errors = sorted(jsonschema.Draft202012Validator(s).iter_errors(document), key=lambda e: list(e.path))
    assert not errors, f"{name}: " + "; ".join(f"{list(e.path)}: {e.message[:200]}" for e in errors[:5])
    assert document["format"] == s["properties"]["format"]["const"]
    assert document["version"] == s["properties"]["version"]["const"]


def test_every_schema_is_a_schema_with_a_version():
    for name in ("probe", "stats", "check", "compare", "motion", "flicker", "history", "check-sequence"):
        s = schema(name)
        assert s["properties"]["version"]["const"] >= 1
        assert name in s["title"]


@pytest.mark.parametrize("pixel", [(20, 12), (45, 30), (0, 0), (63, 35)])
def test_probe_on_native_and_imported_frames_has_one_shape(captures, pixel):
    native = run_json("probe", captures["a"], *pixel, "--json")
    imported = run_json("probe", captures["blender"], *pixel, "--json")
    valid("probe", native)
    valid("probe", imported)
    assert native["native"] is True and imported["native"] is False
    # Scripts written against one read the other: the same keys, null where the frame has nothing.
    assert set(native) == set(imported)
    assert set(native["decoded"]) == set(imported["decoded"])
    assert set(native["position"]) == set(imported["position"])
    assert imported["hdr"] is None and imported["shadow_map"] is None
    # What the Blender layout holds is decoded for it too (its albedo and normal passes).
    assert imported["decoded"]["albedo"] is not None and imported["decoded"]["specular"] is None


def test_probe_with_reference_is_valid(captures):
    valid("probe", run_json("probe", captures["a"], 20, 12, "--json", "--reference"))


def test_stats_and_check_are_valid(captures):
    for c in ("a", "blender"):
        valid("stats", run_json("stats", captures[c], "--rect", "0,0,32,18", "--json"))
        code, out, _ = run("check", captures[c], "--json", check=False)
        assert code in (0, 1)
        valid("check", json.loads(out))
    stats = run_json("stats", captures["a"], "--rect", "0,0,64,36", "--target", "primitive_id", "--json")
    valid("stats", stats)
    assert any("ids" in q for q in stats["quantities"])


def test_compare_reports_are_valid(captures, tmp_path):
    for a, b, extra in [("a", "b", ["--mask", "silhouettes"]), ("a", "a", []), ("a", "blender", ["--flip", "off"])]:
        out = tmp_path / f"{a}-{b}.json"
        run("compare", captures[a], captures[b], *extra, "--json", out, "-q", check=False)
        valid("compare", json.load(open(out)))
    listing = tmp_path / "pairs.txt"
    listing.write_text(f"{captures['a']} {captures['b']} moved\n{captures['a']} {tmp_path / 'missing'} gone\n")
    run("compare", "--pairs", listing, "--flip", "off", "--json", tmp_path / "pairs.json", "-q", check=False)
    pairs = json.load(open(tmp_path / "pairs.json"))
    assert [p["name"] for p in pairs] == ["moved", "gone"]
    for p in pairs:
        valid("compare", p)
    assert pairs[1]["error"] and pairs[1]["result"] == "file error"


def test_the_schemas_refuse_a_changed_shape(captures):
    probe = run_json("probe", captures["a"], 20, 12, "--json")
    for change in ("drop", "add", "retype"):
        doc = copy.deepcopy(probe)
        if change == "drop":
            del doc["decoded"]
        elif change == "add":
            doc["decoded"]["roughness"] = 0.5
        else:
            doc["pixel"] = "20,12"
        with pytest.raises(AssertionError):
            valid("probe", doc)


def test_motion_and_flicker_on_blenders_sequence_are_valid(tmp_path):
    """Blender's animation (tests/data/blender/sequence): the report of its vectors, and of one whose y
    the schema refuses when a pair's key is taken away."""
    seq = tmp_path / "seq"
    run("import", os.path.join(SOURCE, "tests", "data", "blender", "sequence", "cycles_####.exr"), "--layout",
        "builtin:blender-cycles-sequence", "--frames", "1..5", "-o", seq)
    motion = run_json("motion", seq, "--json")
    valid("motion", motion)
    assert motion["verdict"] == "agrees" and len(motion["pairs"]) == 4
    broken = copy.deepcopy(motion)
    del broken["pairs"][0]["pixels"]
    with pytest.raises(AssertionError):
        valid("motion", broken)
    checked = run_json("check", seq, "--json")
    valid("check-sequence", checked)
    for f in checked["frames"]:
        valid("check", f["check"])
    valid("motion", checked["temporal"]["motion"])
    assert checked["temporal"]["motion_severity"] == "fault"
    flicker = run_json("flicker", seq, "--quantity", "DiffCol", "--json")
    valid("flicker", flicker)
    assert flicker["frames"] == 5 and flicker["components"] >= 3
