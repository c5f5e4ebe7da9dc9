"""The compare report in a real browser (headless Chromium over the DevTools protocol, network off): no
console errors or non-file requests; the summary rows equal `compare --json`; the swipe shows A left of
the mouse and B right of it and follows the mouse; the F key flips between A and B; the hover readout
at a pixel equals `gblens probe` on both captures. JUnit XML has the schemas' required elements and a
failing quantity is a failing test case; --pairs writes an index page. Screenshots are kept under the
test's folder (build/pytest) for people to look at."""
import json
import math
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


def test_page_summary_views_and_hover(report, browser):
    b, r = browser, report["json"]
    b.navigate("file://" + str(report["dir"] / "page" / "index.html"))
    b.wait_for("!!document.body.dataset.shown")
    b.screenshot(report["dir"] / "summary.png")
    # Summary rows: every group's figures over each pixel set, as compare --json has them.
    rows = b.evaluate("""[...document.querySelectorAll('#summary tbody tr')].map(tr => ({key: tr.dataset.key, covers: tr.dataset.covers,
      result: tr.querySelector('[data-field=result]').textContent, pixels: (tr.querySelector('[data-field=pixels]') || {}).textContent,
      metrics: Object.fromEntries([...tr.querySelectorAll('[data-metric]')].map(e => [e.dataset.metric, e.textContent]))}))""")
    for g in r["groups"]:
        for figures in [g, g["masked"], g["all"]]:
            if figures is None:
                continue
            row = [x for x in rows if x["key"] == g["key"] and x["covers"] == figures["covers"]]
            assert len(row) == 1, (g["key"], figures["covers"])
            assert int(row[0]["pixels"]) == figures["pixels"]
            for name, value in figures["metrics"].items():
                if name in row[0]["metrics"]:
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

    # Albedo (8-bit sRGB) and hdr (float): A and B side by side; hovering a pixel shows both sides'
    # stored and decoded values, as `gblens probe` gives them.
    for key, quantity, target, pixels in [("albedo_specular.Albedo", "Albedo", "albedo_specular", HOVER[:1]),
                                          ("hdr", "HDR", "hdr", report["hover"])]:
        x0, y0, w0, h0 = rect(b, f"#summary tr[data-key='{key}'].pick")
        b.click(x0 + 10, y0 + h0 / 2)
        b.wait_for(f"document.body.dataset.shown === '{key}|side|a'")
        for x, y in pixels:
            left, top, width, height = rect(b, "#pane-a")  # again: a full-page screenshot may scroll the page
            b.mouse(left + (x + 0.5) * width / 64, top + (y + 0.5) * height / 36)
            b.wait_for(f"(t => t && t.dataset.x === '{x}' && t.dataset.y === '{y}')(document.getElementById('readout-table'))")
            cells = b.evaluate("""Object.fromEntries([...document.querySelectorAll('#readout-table td[data-side]')].map(
              td => [td.dataset.side + '.' + td.dataset.what + '.' + td.dataset.index, td.textContent]))""")
            for side in ("a", "b"):
                probe = run_json("probe", report[side], x, y, "--json")
                decoded = next(q for q in probe["quantities"] if q["name"] == quantity)["values"]
                channels = next(t for t in probe["targets"] if t["target"] == target)["channels"]
                stored = [c["value"] for c in channels[:len(decoded)]]
                for k in range(len(decoded)):  # float32 in the data file: six digits shown
                    assert close(float(cells[f"{side}.decoded.{k}"]), decoded[k]), (key, side, x, y, k)
                    assert close(float(cells[f"{side}.stored.{k}"]), stored[k]), (key, side, x, y, k)
            if (x, y) == report["hover"][0]:
                b.screenshot(report["dir"] / "hover.png")

    # Swipe: A left of the mouse, B right; moving the mouse moves the split.
    a_cols, b_cols = b.evaluate(COLUMNS + "('pane-a')"), b.evaluate(COLUMNS + "('pane-b')")
    assert a_cols != b_cols
    bx, by, bw, bh = rect(b, "#mode-swipe")
    b.click(bx + bw / 2, by + bh / 2)
    b.wait_for("document.body.dataset.shown === 'hdr|swipe|a'")
    left, top, width, height = rect(b, "#pane-view")
    shown = []
    for split in (16, 48):
        b.mouse(left + split * width / 64, top + height / 2)
        cols = b.evaluate(COLUMNS + "('pane-view')")
        assert cols[:split] == a_cols[:split] and cols[split:] == b_cols[split:], split
        shown.append(cols)
    assert shown[0] != shown[1]
    b.screenshot(report["dir"] / "swipe.png")

    # Flip: the F key alternates A and B in place.
    sides = []
    for n in range(3):
        b.key("f", "KeyF")
        b.wait_for(f"document.body.dataset.shown === 'hdr|flip|{'ab'[n % 2]}'")
        sides.append(b.evaluate(COLUMNS + "('pane-view')"))
        b.screenshot(report["dir"] / f"flip_{'ab'[n % 2]}.png")
    assert sides[0] == a_cols and sides[1] == b_cols and sides[2] == a_cols
    assert b.evaluate("1") == 1 and b.problems() == []


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
