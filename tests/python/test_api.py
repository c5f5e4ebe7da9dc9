"""The Python module as a new user discovers it: a version, a docstring on every class, function,
method and property, signatures that inspect.signature reads and that equal the shipped gblens.pyi
(parsed here with ast), errors that are gblens.Error subclasses naming the keyword argument, scalars
as (H, W), quantities that are there, and every example of docs/python.md run as written."""
import ast
import inspect
import os
import re
import shutil

import numpy as np
import pytest

import gblens
from conftest import SMALL, SOURCE, run

STUB = os.path.join(os.path.dirname(gblens.__file__), "gblens.pyi")


def public(obj):
    return {n: getattr(obj, n) for n in dir(obj) if not n.startswith("_") or n == "__getitem__"}


def stub():
    tree = ast.parse(open(STUB).read())
    out = {"": {}}
    for node in tree.body:
        if isinstance(node, ast.FunctionDef):
            out[""][node.name] = node
        elif isinstance(node, ast.ClassDef):
            out[node.name] = {n.name: n for n in node.body  # the names public() takes (not __len__)
                              if isinstance(n, ast.FunctionDef) and (not n.name.startswith("_") or n.name == "__getitem__")}
    return out


def stub_parameters(fn):
    """(name, kind, default) of a stub's def, in order."""
    a = fn.args
    out = []
    defaults = [None] * (len(a.args) - len(a.defaults)) + list(a.defaults)
    for p, d in zip(a.args, defaults):
        out.append((p.arg, "positional", None if d is None else ast.literal_eval(d)))
    for p, d in zip(a.kwonlyargs, a.kw_defaults):
        out.append((p.arg, "keyword", None if d is None else ast.literal_eval(d)))
    if a.kwarg:
        out.append((a.kwarg.arg, "var_keyword", None))
    return out


def module_parameters(fn):
    kinds = {inspect.Parameter.POSITIONAL_OR_KEYWORD: "positional", inspect.Parameter.KEYWORD_ONLY: "keyword",
             inspect.Parameter.VAR_KEYWORD: "var_keyword"}
    return [(p.name, kinds[p.kind], None if p.default is inspect.Parameter.empty else p.default)
            for p in inspect.signature(fn).parameters.values()]


def test_version_is_the_projects():
    cmake = open(os.path.join(SOURCE, "CMakeLists.txt")).read()
    assert gblens.__version__ == re.search(r"project\(gblens VERSION ([0-9.]+)", cmake).group(1)


def test_every_public_name_has_a_docstring():
    assert gblens.__doc__ and "Frame" in gblens.__doc__
    for name, obj in public(gblens).items():
        assert (obj.__doc__ or "").strip(), name
    for cls in (gblens.Frame, gblens.Sequence, gblens.Result):
        for name, member in public(cls).items():
            doc = member.__doc__ if not isinstance(member, property) else member.fget.__doc__ or member.__doc__
            assert (doc or "").strip(), f"{cls.__name__}.{name}"
    # Numpy style: the functions that take arguments say so under "Parameters".
    for fn in (gblens.open, gblens.compare, gblens.render, gblens.Frame.probe, gblens.Frame.stats, gblens.open_sequence,
               gblens.motion, gblens.flicker, gblens.Sequence.array, gblens.Sequence.frame):
        assert "Parameters\n----------" in inspect.getdoc(fn), fn.__name__


def test_signatures_are_inspectable_and_equal_the_stub():
    s = stub()
    module_functions = {n for n, o in public(gblens).items() if callable(o) and not isinstance(o, type)}
    assert module_functions == set(s[""]), "functions: module vs gblens.pyi"
    for name in module_functions:
        assert module_parameters(getattr(gblens, name)) == stub_parameters(s[""][name]), name
    for cls in (gblens.Frame, gblens.Sequence, gblens.Result):
        members = public(cls)
        methods = {n for n, m in members.items() if not isinstance(m, property)}
        properties = {n for n, m in members.items() if isinstance(m, property)}
        declared = s[cls.__name__]
        stub_properties = {n for n, f in declared.items() if any(getattr(d, "id", "") == "property" for d in f.decorator_list)}
        assert properties == stub_properties, cls.__name__
        assert methods == set(declared) - stub_properties, cls.__name__
        for name in methods:
            assert module_parameters(getattr(cls, name)) == stub_parameters(declared[name]), f"{cls.__name__}.{name}"


def test_errors_are_gblens_errors_naming_the_argument(captures):
    f = gblens.open(captures["a"])
    assert issubclass(gblens.ArgumentError, gblens.Error) and issubclass(gblens.ArgumentError, ValueError)
    assert issubclass(gblens.QuantityError, gblens.Error) and issubclass(gblens.QuantityError, KeyError)
    with pytest.raises(gblens.ArgumentError, match=r"^x=-1, y=0: outside the 64x36 frame"):
        f.probe(-1, 0)
    with pytest.raises(gblens.ArgumentError, match=r"^x=0, y=36: outside"):
        f.probe(0, 36)
    with pytest.raises(gblens.QuantityError, match="no quantity of that name"):
        f["no_such_quantity"]
    with pytest.raises(gblens.ArgumentError, match=r"^fail=abc"):
        gblens.compare(f, f, fail="abc")
    with pytest.raises(gblens.ArgumentError, match=r"^warn_flip="):
        gblens.compare(f, f, warn_flip="x")
    with pytest.raises(gblens.ArgumentError, match=r"^rect="):
        f.stats((0, 0, 100, 10))
    with pytest.raises(gblens.ArgumentError, match=r'^target="nope"'):
        f.stats((0, 0, 4, 4), target="nope")
    with pytest.raises(gblens.ArgumentError, match=r'^space="up"'):
        f.position(space="up")
    with pytest.raises(gblens.ArgumentError, match=r"^lights="):
        gblens.render(size=(8, 8), lights="many")
    with pytest.raises(gblens.Error):  # an unreadable input: the base class
        gblens.open(os.path.join(captures["root"], "nowhere"))


def test_scalars_are_two_dimensional_and_quantities_are_there(captures):
    f = gblens.open(captures["a"])
    assert f["Depth"].shape == (f.height, f.width)
    assert f["Stencil"].shape == (f.height, f.width)
    assert f["Normal"].shape == (f.height, f.width, 3)
    for name in f.quantities:  # every name listed can be read
        assert f[name].ndim in (2, 3), name
    # A default capture computes no primitive ids: listed apart with the reason, not among quantities.
    plain = gblens.open(captures["plain"])
    assert "PrimitiveId" not in plain.quantities and "primitive_id off" in plain.missing_quantities["PrimitiveId"]
    with pytest.raises(gblens.Error, match="does not hold target primitive_id"):
        plain["PrimitiveId"]


def examples():
    text = open(os.path.join(SOURCE, "docs", "python.md")).read()
    return re.findall(r"```python\n(.*?)```", text, re.S)


@pytest.mark.parametrize("index", range(len(examples())))
def test_every_docs_example_runs(index, tmp_path, monkeypatch):
    """Each ```python block of docs/python.md, run as written in a folder holding what it names: the
    golden capture (made with the example's own options), the sequence "walk" and the Blender fixture."""
    code = examples()[index]
    compile(code, f"docs/python.md example {index}", "exec")  # a SyntaxError fails here
    monkeypatch.chdir(tmp_path)
    if "golden/temple" in code:
        run("capture", "builtin:temple", "--size", "160x90", "--lights", "16", "--time", "2.5", "--shadow-map-size", "256",
            "-o", tmp_path / "golden" / "temple")
    if '"walk"' in code:  # the sequence the Sequences example names, made as its comment says
        run("capture", "builtin:temple", "--size", "64x36", "--sequence", "3", "--time-step", "0.1", "--camera-motion", "orbit",
            "--motion", "on", "-o", tmp_path / "walk")
    for name in ("cycles.exr", "camera.json"):  # the Blender passes and their camera sidecar
        shutil.copy(os.path.join(SOURCE, "tests", "data", "blender", name), tmp_path / name)
    exec(compile(code, f"docs/python.md example {index}", "exec"), {"__name__": "__docs__"})


def test_save_is_lossless(captures, tmp_path):
    """A frame saved again keeps every light's description (lights.json, read here as JSON) and
    compares identical with nothing only on one side."""
    import json
    f = gblens.open(captures["a"])
    f.save(tmp_path / "saved")
    original = json.load(open(os.path.join(captures["a"], "lights.json")))
    saved = json.load(open(tmp_path / "saved" / "lights.json"))
    assert original["lights"] and all("desc" in l for l in original["lights"])
    assert saved["lights"] == original["lights"]
    r = gblens.compare(captures["a"], str(tmp_path / "saved"), flip=False)
    assert r.exit_code == 0 and r.json["only_in_a"] == [] and r.json["only_in_b"] == []


def test_statistics_cover_the_pixels_they_say(captures):
    """Each decoded series' figures are over the pixel set its surfaces_only names: every pixel of the
    rectangle, or the surface pixels; checked against numpy over the module's own arrays."""
    f = gblens.open(captures["plain"])
    s = f.stats((0, 0, f.width, f.height))
    surface = f.mask("surface")
    assert 0 < s["surface_pixels"] == int(surface.sum()) < s["pixels"]
    for q in s["quantities"]:
        expected = s["surface_pixels"] if q["surfaces_only"] else s["pixels"]
        assert q["count"] + q["nan"] + q["+inf"] + q["-inf"] == expected, (q["series"], q["count"], expected)
    depth = next(q for q in s["quantities"] if q["series"] == "Depth")
    assert depth["surfaces_only"] is True
    assert abs(depth["mean"] - float(np.nanmean(f["Depth"][surface]))) <= 1e-9 * abs(depth["mean"])
