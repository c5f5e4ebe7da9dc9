"""The compare report in a real browser (headless Chromium over the DevTools protocol, network off): no
console errors or non-file requests; the summary rows equal `compare --json`, counts exactly; the hover
readout gives each side's stored bits and decoded values as `gblens probe` reads them, under each
side's own channel names; wheel zoom keeps the texel under the mouse, every pane alike, and prints
values in texels; drag pans; the swipe shows A left of the mouse and B right of it and follows it;
Space flips; N/P step through the quantities; the docs list the page's keys. JUnit XML has the schemas' required elements and a
failing quantity is a failing test case; --pairs writes an index page. Screenshots are kept under the
test's folder (build/pytest) for people to look at."""
import json
import math
import re
import os
import xml.etree.ElementTree as ET

import numpy as np
import OpenImageIO as oiio
import pytest

from chromium import Browser
from conftest import run, run_json

HOVER = [(20, 12), (45, 30), (3, 33)]


@pytest.fixture(scope="module")
def report(captures, tmp_path_factory):
    out = tmp_path_factory.mktemp("report")
    code, _, _ = run("compare", captures["a"], captures["b"], "--mask", "silhouettes", "--report", out / "page",
                     "--junit", out / "junit.xml", "--json", out / "report.json", "-q", check=False)
    assert code == 2  # the lights move between the two: hdr and final fail
    # The pixel where hdr differs most (read here with OpenImageIO): hovered first, for the screenshot.
    hdr = [np.asarray(oiio.ImageBuf(os.path.join(captures[s], "hdr.exr")).get_pixels(oiio.FLOAT)) for s in "ab"]
    y, x = np.unravel_index(np.abs(hdr[0] - hdr[1]).max(axis=-1).argmax(), hdr[0].shape[:2])
    return {"dir": out, "json": json.load(open(out / "report.json")), "hover": [(int(x), int(y)), *HOVER], **captures}


@pytest.fixture(scope="module")
def browser():
    b = Browser()
    yield b
    b.close()


def number(text):
    return {"inf": math.inf, "-inf": -math.inf}[text] if text in ("inf", "-inf") else float(text)


def close(shown, value):
    value = math.inf if value == "inf" else value
    if isinstance(value, float) and math.isinf(value):
        return shown == value
    return abs(shown - value) <= 1e-5 * max(abs(value), 1e-300) + 1e-12


def rect(b, selector):
    """The element's box in the viewport (scrolled into view: mouse events land in the viewport)."""
    return b.evaluate(f"(() => {{ const e = document.querySelector(\"{selector}\"); e.scrollIntoView({{block: 'center'}}); "
                      "const r = e.getBoundingClientRect(); return [r.left, r.top, r.width, r.height]; })()")


# Per-column sums of a canvas's pixels (read through a copy made for reading back, so the page's own
# canvases are not read and Chromium has nothing to warn about).
COLUMNS = """(id => { const c = document.getElementById(id), t = document.createElement('canvas');
  t.width = c.width, t.height = c.height;
  const x = t.getContext('2d', {willReadFrequently: true});
  x.drawImage(c, 0, 0);
  const d = x.getImageData(0, 0, c.width, c.height).data;
  const s = new Array(c.width).fill(0);
  for (let i = 0; i < d.length; i += 4) s[(i / 4) % c.width] += d[i] * 3 + d[i + 1] * 5 + d[i + 2] * 7;
  return s; })"""


def show(b, key):
    x0, y0, w0, h0 = rect(b, f"#summary tr[data-key='{key}'].pick")
    b.click(x0 + 10, y0 + h0 / 2)
    b.wait_for(f"document.body.dataset.shown === '{key}|row|a' && document.body.dataset.complete === 'yes'")


def hover(b, pane, x, y, w=64, h=36):
    """Moves the mouse over texel (x, y) of a pane at fit zoom; returns the readout's cells."""
    left, top, width, height = rect(b, pane)
    b.mouse(left + (x + 0.5) * width / w, top + (y + 0.5) * height / h)
    b.wait_for(f"(t => t && t.dataset.x === '{x}' && t.dataset.y === '{y}')(document.getElementById('readout-table'))")
    return b.evaluate("""[...document.querySelectorAll('#readout-table td[data-what]')].map(td => ({side: td.dataset.side,
      what: td.dataset.what, index: td.dataset.index, name: td.dataset.name, text: td.textContent}))""")


def digits_close(text, value, digits):
    """`text` is `value` printed to `digits` significant digits (from a float32 copy: one float32 ulp more)."""
    shown = float(text)
    if value == 0:
        return shown == 0
    unit = 10.0 ** (math.floor(math.log10(abs(value))) - digits + 1)
    return abs(shown - value) <= 0.51 * unit + 1.2e-7 * abs(value)


def check_side(cells, probe, side, quantity, target):
    """The readout's stored bits and decoded values of one side against `gblens probe` on its capture."""
    channels = next(t for t in probe["targets"] if t["target"] == target)
    decoded = next(q for q in probe["quantities"] if q["name"] == quantity)["values"]
    stored = [c for c in cells if c.get("side") == side and c["what"] == "stored"]
    assert [c["name"] for c in stored] == [c["name"] for c in channels["channels"][:len(stored)]]
    for cell, channel in zip(stored, channels["channels"]):
        if channels["type"] in ("f32", "f16"):  # "VALUE (0xBITS)": the bits exactly, the value to the float's digits
            value, bits = cell["text"].split(" (")
            assert bits == channel["bits"] + ")", (cell, channel)
            kind = np.float32 if channels["type"] == "f32" else np.float16  # the digits tell this float apart
            assert kind(float(value)) == kind(channel["value"]), (cell, channel)
        else:  # "RAW -> VALUE"
            raw, value = cell["text"].split(" -> ")
            assert int(raw) == int(channel["bits"], 16), (cell, channel)
            assert digits_close(value, channel["value"], 4 if channels["type"].endswith("8") else 6), (cell, channel)
    shown = [c for c in cells if c.get("side") == side and c["what"] == "decoded"]
    assert len(shown) == len(decoded)
    for cell, value in zip(shown, decoded):
        digits = {"f32": 7, "f16": 4, "u8": 4, "i8": 4}.get(channels["type"], 6)  # storageDigits, by hand
        assert digits_close(cell["text"], value, digits), (cell, value)


def test_page_summary(report, browser):
    b, r = browser, report["json"]
    b.navigate("file://" + str(report["dir"] / "page" / "index.html"))
    b.wait_for("!!document.body.dataset.shown")
    b.screenshot(report["dir"] / "summary.png")
    # Summary rows: every group's figures over each pixel set, as compare --json has them; counts exact.
    rows = b.evaluate("""[...document.querySelectorAll('#summary tbody tr')].map(tr => ({key: tr.dataset.key, covers: tr.dataset.covers,
      result: tr.querySelector('[data-field=result]').textContent, pixels: (tr.querySelector('[data-field=pixels]') || {}).textContent,
      metrics: Object.fromEntries([...tr.querySelectorAll('[data-metric]')].map(e => [e.dataset.metric, e.textContent]))}))""")
    for g in r["groups"]:
        for figures in [g, g["masked"], g["all"]]:
            if figures is None:
                continue
            row = [x for x in rows if x["key"] == g["key"] and x["covers"] == figures["covers"]]
            assert len(row) == 1, (g["key"], figures["covers"])
            assert row[0]["pixels"] == str(figures["pixels"])
            for name, value in figures["metrics"].items():
                if name in row[0]["metrics"]:
                    if isinstance(value, int):
                        assert row[0]["metrics"][name] == str(value), (g["key"], name)
                    assert close(number(row[0]["metrics"][name]), value), (g["key"], figures["covers"], name)
            assert sum(1 for m in row[0]["metrics"] if m in figures["metrics"]) >= 2
        first = next(x for x in rows if x["key"] == g["key"])
        assert first["result"] == g["result"].upper()
    for f in r["flip"]:
        row = next(x for x in rows if x["key"] == "flip." + f["target"])
        assert int(row["pixels"]) == f["pixels"] and row["result"] == f["result"].upper()
        for name in ("mean", "weighted_median", "max"):
            assert close(number(row["metrics"][name]), f[name])
    assert {x["key"] for x in rows} >= {s["target"] for s in r["skipped"]}
    assert b.problems() == []


def test_hover_shows_both_captures_bits_and_values(report, browser):
    """Albedo (8-bit sRGB) and hdr (float32): each side's stored bits and decoded values at a texel, as
    `gblens probe` reads them from that side's capture."""
    b = browser
    b.navigate("file://" + str(report["dir"] / "page" / "index.html"))
    b.wait_for("!!document.body.dataset.shown")
    for key, quantity, target, pixels in [("albedo_specular.Albedo", "Albedo", "albedo_specular", HOVER[:1]),
                                          ("hdr", "HDR", "hdr", report["hover"]), ("depth", "Depth", "depth", HOVER[1:2])]:
        show(b, key)
        for x, y in pixels:
            cells = hover(b, "#pane-a", x, y)
            probes = {side: run_json("probe", report[side], x, y, "--json") for side in "ab"}
            for side in ("a", "b"):
                check_side(cells, probes[side], side, quantity, target)
            # |A-B| per component, from the two probes here; the error as compare --json's largest bounds it.
            values = [next(q for q in probes[s]["quantities"] if q["name"] == quantity)["values"] for s in "ab"]
            diffs = [c for c in cells if c["what"] == "absdiff"]
            assert len(diffs) == len(values[0])
            for cell, va, vb in zip(diffs, *values):
                assert digits_close(cell["text"], abs(va - vb), 7) or abs(va - vb) < 1e-6 * max(abs(va), 1e-30), (cell, va, vb)
            error = next(c for c in cells if c["what"] == "error")["text"]
            group = next(g for g in report["json"]["groups"] if g["key"] == key)
            if key != "depth":  # colour: the largest channel difference
                assert digits_close(error, max(abs(va - vb) for va, vb in zip(*values)), 7) or float(error) == 0
            assert float(error) <= group["all"]["metrics"]["max_abs" if key != "depth" else "max_rel"] * (1 + 1e-6) + 1e-12
            if (x, y) == report["hover"][0]:
                b.screenshot(report["dir"] / "hover.png")
    assert b.problems() == []


def test_each_side_is_read_under_its_own_names(captures, tmp_path, browser):
    """A's normals octahedral (N.U, N.V), B's rgba16f (N.X, N.Y, N.Z): each side's cells under its names."""
    other = tmp_path / "rgba16f"
    run("capture", "--size", "64x36", "--lights", "6", "--shadow-map-size", "256", "--normal-format", "rgba16f", "-o", other)
    run("compare", captures["plain"], other, "--report", tmp_path / "page", "-q", check=False)
    b = browser
    b.navigate("file://" + str(tmp_path / "page" / "index.html"))
    b.wait_for("!!document.body.dataset.shown")
    show(b, "normal_shadow.Normal")
    cells = hover(b, "#pane-b", 40, 20)
    for side, capture in (("a", captures["plain"]), ("b", str(other))):
        check_side(cells, run_json("probe", capture, 40, 20, "--json"), side, "Normal", "normal_shadow")
    names = {s: [c["name"] for c in cells if c.get("side") == s and c["what"] == "stored"] for s in "ab"}
    assert names["a"][:2] == ["N.U", "N.V"] and names["b"][:3] == ["N.X", "N.Y", "N.Z"], names
    assert b.problems() == []


def view(b):
    s, ox, oy = map(float, b.evaluate("document.body.dataset.view").split("|"))
    return s, ox, oy


def test_zoom_pan_values_in_texels_swipe_flip_and_keys(report, browser):
    b = browser
    b.navigate("file://" + str(report["dir"] / "page" / "index.html"))
    b.wait_for("!!document.body.dataset.shown")
    show(b, "hdr")
    a_cols, b_cols = b.evaluate(COLUMNS + "('pane-a')"), b.evaluate(COLUMNS + "('pane-b')")
    assert a_cols != b_cols

    # Wheel zoom about the mouse: the texel under it stays under it; every pane has the same view.
    left, top, width, height = rect(b, "#pane-a")
    s0, _, _ = view(b)
    mx, my = round(left + width * 0.3), round(top + height * 0.6)  # whole pixels: events carry whole pixels
    texel = ((mx - left) / s0, (my - top) / s0)
    b.mouse(mx, my)  # probes the texel under the mouse
    for _ in range(12):
        b.call("Input.dispatchMouseEvent", type="mouseWheel", x=mx, y=my, deltaX=0, deltaY=-100)
    b.wait_for("document.body.dataset.complete === 'yes'")
    s, ox, oy = view(b)
    assert s == pytest.approx(s0 * 1.25 ** 12)
    now = b.evaluate("(() => { const r = document.getElementById('pane-a').getBoundingClientRect(); return [r.left, r.top]; })()")
    assert (ox + (mx - now[0]) / s, oy + (my - now[1]) / s) == pytest.approx(texel, abs=0.5 / s)
    marks = b.evaluate("[...document.querySelectorAll('#panes .mark')].map(m => m.style.left + ',' + m.style.top)")
    assert len(marks) >= 3 and len(set(marks)) == 1, marks

    # Values in texels: the probed texel's text is its decoded value at the storage's precision.
    probed = b.evaluate("document.getElementById('readout-table').dataset.x + ',' + document.getElementById('readout-table').dataset.y")
    x, y = map(int, probed.split(","))
    b.wait_for("!!document.getElementById('pane-a').dataset.probedText")
    text = b.evaluate("document.getElementById('pane-a').dataset.probedText")
    decoded = next(q for q in run_json("probe", report["a"], x, y, "--json")["quantities"] if q["name"] == "HDR")["values"]
    assert len(text.split("|")) == len(decoded)
    for shown, value in zip(text.split("|"), decoded):
        assert digits_close(shown, value, 7), (shown, value)
    b.screenshot(report["dir"] / "zoomed.png")

    # Drag pans every pane alike by the mouse's movement in texels.
    b.mouse(mx, my, "mousePressed", "left", 1)
    b.mouse(mx + 2 * s, my + s)  # two texels right and one down: the image follows, so its origin goes back
    b.mouse(mx + 2 * s, my + s, "mouseReleased", "left", 1)
    s2, ox2, oy2 = view(b)
    assert s2 == s and (ox2, oy2) == pytest.approx((ox - 2, oy - 1), abs=1 / s)  # events carry whole pixels

    # Z fits again; swipe (S): A left of the mouse, B right; it follows the mouse.
    b.key("z", "KeyZ")
    b.wait_for("document.body.dataset.view.split('|')[1] === '0'")
    b.key("s", "KeyS")
    b.wait_for("document.body.dataset.shown === 'hdr|swipe|a'")
    left, top, width, height = rect(b, "#pane-view")
    shown = []
    for split in (16, 48):  # texel columns
        b.mouse(left + split * width / 64, top + height / 2)
        b.wait_for(f"document.getElementById('tag-b').style.left !== '' && document.getElementById('swipe-line').style.left === '{round(split * width / 64)}px'")
        cols = b.evaluate(COLUMNS + "('pane-view')")
        at = round(split * width / 64)
        assert cols[:at] == a_cols[:at] and cols[at:] == b_cols[at:], split
        shown.append(cols)
    assert shown[0] != shown[1]
    b.screenshot(report["dir"] / "swipe.png")

    # Space flips A and B in place.
    sides = []
    for n in range(3):
        b.key(" ", "Space")
        b.wait_for(f"document.body.dataset.shown === 'hdr|flip|{'ab'[n % 2]}'")
        sides.append(b.evaluate(COLUMNS + "('pane-view')"))
    assert sides[0] == a_cols and sides[1] == b_cols and sides[2] == a_cols

    # N / P: the next and previous quantity in the summary's order; R back to side by side.
    keys = [g["key"] for g in report["json"]["groups"]]
    b.key("n", "KeyN")
    b.wait_for(f"document.body.dataset.shown.startsWith('{keys[(keys.index('hdr') + 1) % len(keys)]}|')")
    b.key("p", "KeyP")
    b.wait_for("document.body.dataset.shown.startsWith('hdr|')")
    b.key("r", "KeyR")
    b.wait_for("document.body.dataset.shown === 'hdr|row|a'")
    b.key("?", "Slash")
    assert b.evaluate("!document.getElementById('help').hidden")
    assert b.problems() == []


def test_the_docs_list_the_pages_keys(report, browser):
    b = browser
    b.navigate("file://" + str(report["dir"] / "page" / "index.html"))
    b.wait_for("!!document.body.dataset.shown")
    page = b.evaluate("[...document.querySelectorAll('#keys tr')].map(tr => [...tr.children].map(td => td.textContent))")
    docs = open(os.path.join(os.path.dirname(__file__), "..", "..", "docs", "report.md")).read()
    table = docs.split("<!-- page keys -->")[1].split("<!-- /page keys -->")[0]
    cells = lambda line: [c.strip().strip("`").replace("\\|", "|") for c in re.split(r"(?<!\\)\|", line.strip()[1:-1])]
    rows = [cells(line) for line in table.strip().splitlines()[2:]]
    assert rows == page


def test_junit_has_the_required_elements(report):
    root = ET.parse(report["dir"] / "junit.xml").getroot()
    assert root.tag == "testsuites"
    suites = root.findall("testsuite")
    assert len(suites) == 1
    suite = suites[0]
    for attribute in ("name", "tests", "failures", "errors", "time", "timestamp", "hostname"):
        assert attribute in suite.attrib, attribute
    assert suite.find("properties") is not None and suite.find("system-out") is not None and suite.find("system-err") is not None
    cases = {c.get("name"): c for c in suite.findall("testcase")}
    for c in cases.values():
        assert c.get("classname") and c.get("time") is not None
    r = report["json"]
    failing = {g["key"] for g in r["groups"] if g["result"] == "fail"} | {"flip." + f["target"] for f in r["flip"] if f["result"] == "fail"}
    assert failing, "the pair was made to fail"
    for g in r["groups"]:
        failure = cases[g["key"]].find("failure")
        assert (failure is not None) == (g["key"] in failing), g["key"]
        if failure is not None:
            assert failure.get("message") and failure.get("type")
    assert int(suite.get("failures")) == len(failing) and int(suite.get("tests")) == len(cases)
    for s in r["skipped"]:
        assert cases[s["target"]].find("skipped") is not None


def test_pairs_index_page(report, browser):
    out = report["dir"] / "pairs"
    out.mkdir()
    (out / "list.txt").write_text(f"# a pair that passes and one that fails\n{report['a']} {report['a']} same\n"
                                  f"{report['a']} {report['b']} moved\n")
    code, _, _ = run("compare", "--pairs", out / "list.txt", "--report", out / "report", "--junit", out / "junit.xml",
                     "--flip", "off", "-q", check=False)
    assert code == 2
    assert (out / "report" / "same" / "index.html").exists() and (out / "report" / "moved" / "index.html").exists()
    assert len(ET.parse(out / "junit.xml").getroot().findall("testsuite")) == 2
    browser.navigate("file://" + str(out / "report" / "index.html"))
    browser.wait_for("document.querySelectorAll('#pairs tr[data-key]').length === 2")
    results = browser.evaluate("[...document.querySelectorAll('#pairs tr[data-key]')].map(tr => tr.dataset.key + ' ' + tr.querySelector('[data-field=result]').textContent)")
    assert results == ["same PASS", "moved FAIL"]
    browser.screenshot(out / "index.png")
    assert browser.problems() == []
