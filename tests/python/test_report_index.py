"""The pairs index page of `gblens compare --pairs LIST --report DIR` in headless Chromium (network off):
rows and verdicts, sorting by a header click (result by severity), the name/path filter and the result
checkboxes with their count line, the thumbnails shown, a file error in red; and, independently of
gblens, the thumbnails' pixels against the captures' files (OpenImageIO and numpy)."""
import json
import os

import numpy as np
import OpenImageIO as oiio
import pytest

from chromium import Browser
from conftest import SMALL, run

LIST_ORDER = ["same", "moved", "broken", "another", "big"]
RESULTS = {"same": "PASS", "moved": "FAIL", "broken": "FILE ERROR", "another": "PASS", "big": "FAIL"}
SEVERITY = ["FILE ERROR", "FAIL", "MISMATCH", "WARN", "PASS"]


@pytest.fixture(scope="module")
def index(captures, tmp_path_factory):
    out = tmp_path_factory.mktemp("index")
    # A wider pair (400 pixels: reduced to 160 with blocks of 2 and 3 columns) besides the 64x36 fixtures.
    wide = [*SMALL[2:], "--size", "400x226"]
    run("capture", *wide, "-o", out / "wide_a")
    run("capture", *wide, "--time", "0.25", "-o", out / "wide_b")
    a, b = captures["a"], captures["b"]
    (out / "list.txt").write_text(f"{a} {a} same\n{a} {b} moved\n{out / 'nothere'} {a} broken\n{b} {b} another\n"
                                  f"wide_a wide_b big\n")
    code, _, _ = run("compare", "--pairs", out / "list.txt", "--report", out / "report", "--flip", "off", "-q",
                     check=False)
    assert code == 4  # the worst pair's: the missing capture
    return {"dir": out, "report": out / "report", "a": a, "b": b, "wide_a": str(out / "wide_a"), "wide_b": str(out / "wide_b")}


@pytest.fixture(scope="module")
def browser(index):
    b = Browser()
    b.navigate("file://" + str(index["report"] / "index.html"))
    b.wait_for(f"document.querySelectorAll('#pairs tr[data-key]').length === {len(LIST_ORDER)}")
    b.wait_for("[...document.querySelectorAll('#pairs img')].every(i => i.complete)")
    yield b
    b.close()


def rows(b, visible_only=True):
    """[(name, result text)] of the table's rows in their order (hidden rows left out)."""
    return [tuple(r) for r in b.evaluate(
        "[...document.querySelectorAll('#pairs tr[data-key]')]" + (".filter(tr => !tr.hidden)" if visible_only else "") +
        ".map(tr => [tr.dataset.key, tr.querySelector('[data-field=result]').textContent])")]


def click(b, selector):
    """A real mouse click at the element's centre (scrolled into view)."""
    x, y, w, h = b.evaluate(f"(() => {{ const e = document.querySelector(\"{selector}\"); e.scrollIntoView({{block: 'center'}}); "
                            "const r = e.getBoundingClientRect(); return [r.left, r.top, r.width, r.height]; })()")
    b.click(x + w / 2, y + h / 2)


def header(b, title):
    return b.evaluate(f"[...document.querySelectorAll('#pairs th')].find(th => th.textContent.startsWith('{title}')).textContent")


def count_line(b):
    return b.evaluate("document.getElementById('count').textContent")


def test_rows_and_sorting(index, browser):
    b = browser
    assert rows(b) == [(n, RESULTS[n]) for n in LIST_ORDER]
    assert count_line(b) == "5 of 5 pairs shown"
    b.screenshot(index["dir"] / "index.png")
    # The result column: most severe first, equal results in the list's order; a second click reverses.
    click(b, "#pairs th[data-column='3']")
    shown = rows(b)
    assert [r for _, r in shown] == sorted(RESULTS.values(), key=SEVERITY.index)
    assert [n for n, _ in shown] == ["broken", "moved", "big", "same", "another"]
    assert header(b, "result") == "result \u25b2"
    b.screenshot(index["dir"] / "sorted_result.png")
    click(b, "#pairs th[data-column='3']")
    assert [r for _, r in rows(b)] == sorted(RESULTS.values(), key=SEVERITY.index)[::-1]
    assert header(b, "result") == "result \u25bc"
    # The pair column by name; the result header loses its arrow.
    click(b, "#pairs th[data-column='2']")
    assert [n for n, _ in rows(b)] == sorted(LIST_ORDER)
    assert header(b, "pair") == "pair \u25b2" and header(b, "result") == "result"
    click(b, "#pairs th[data-column='2']")
    assert [n for n, _ in rows(b)] == sorted(LIST_ORDER, reverse=True)
    assert b.problems() == []


def test_filter(index, browser):
    b = browser
    clear = "(() => { const f = document.getElementById('filter'); f.value = ''; f.dispatchEvent(new Event('input')); })()"
    b.key("/", "Slash")  # focuses the filter box, and is not typed into it
    assert b.evaluate("document.activeElement.id") == "filter"
    assert b.evaluate("document.getElementById('filter').value") == ""
    b.call("Input.insertText", text="mo")  # by name
    assert rows(b) == [("moved", "FAIL")]
    assert count_line(b) == "1 of 5 pairs shown"
    b.evaluate(clear)
    b.call("Input.insertText", text="wide_")  # by path: only the big pair's captures are in wide_a, wide_b
    assert [n for n, _ in rows(b)] == ["big"]
    assert count_line(b) == "1 of 5 pairs shown"
    b.evaluate(clear)
    assert count_line(b) == "5 of 5 pairs shown"
    # One checkbox per result present; unticking "pass" hides the passing pairs.
    assert b.evaluate("[...document.querySelectorAll('#controls input[type=checkbox]')].map(c => c.id)") == \
        ["show-fileerror", "show-fail", "show-pass"]
    click(b, "#show-pass")
    assert b.evaluate("document.getElementById('show-pass').checked") is False
    assert sorted(n for n, _ in rows(b)) == ["big", "broken", "moved"]
    assert count_line(b) == "3 of 5 pairs shown"
    b.screenshot(index["dir"] / "filtered.png")
    click(b, "#show-pass")
    assert len(rows(b)) == 5
    assert b.problems() == []


def test_thumbnails_and_colours(index, browser):
    b = browser
    thumbs = b.evaluate("Object.fromEntries([...document.querySelectorAll('#pairs tr[data-key]')].map(tr => [tr.dataset.key, "
                        "[...tr.querySelectorAll('img')].map(i => [i.dataset.thumb, i.complete, i.naturalWidth, i.naturalHeight])]))")
    for name in LIST_ORDER:
        if name == "broken":
            assert thumbs[name] == []
            continue
        assert [t[0] for t in thumbs[name]] == ["a", "diff"]
        for _, complete, w, h in thumbs[name]:
            assert complete and 0 < w <= 160 and h > 0
    assert thumbs["big"][0][2:] == [160, 90] and thumbs["same"][0][2:] == [64, 36]
    # The file error: red text (page.html's .fileerror), its error in the row, a red row.
    colour = b.evaluate("getComputedStyle(document.querySelector(\"#pairs tr[data-key='broken'] [data-field=result]\")).color")
    r, g, bl = (int(v) for v in colour[colour.index("(") + 1:colour.index(")")].split(",")[:3])
    assert r >= 200 and g < 150 and bl < 150, colour
    assert "nothere" in b.evaluate("document.querySelector(\"#pairs tr[data-key='broken'] [data-field=bad]\").textContent")
    assert "verdict-fileerror" in b.evaluate("document.querySelector(\"#pairs tr[data-key='broken']\").className")
    # The index data names the files; null for the pair that did not load.
    data = json.loads((index["report"] / "report.js").read_text()[len("gblensReport("):-3])
    by_name = {p["name"]: p for p in data["pairs"]}
    assert by_name["broken"]["thumbnails"] is None
    assert by_name["moved"]["thumbnails"] == {"a": "moved/thumb_a.png", "diff": "moved/thumb_diff.png"}
    assert b.problems() == []


def pixels(path):
    return np.asarray(oiio.ImageBuf(str(path)).get_pixels(oiio.FLOAT))


def png(path):
    return np.asarray(oiio.ImageBuf(str(path)).get_pixels(oiio.UINT8)).astype(np.int64)


def blocks(h, w, th, tw):
    """Each thumbnail pixel's source rows and columns: [y*h//th, (y+1)*h//th) and likewise."""
    return [(y * h // th, (y + 1) * h // th) for y in range(th)], [(x * w // tw, (x + 1) * w // tw) for x in range(tw)]


def reduce(img, th, tw, how):
    ys, xs = blocks(img.shape[0], img.shape[1], th, tw)
    return np.array([[how(img[y0:y1, x0:x1].reshape(-1, img.shape[2]), axis=0) for x0, x1 in xs] for y0, y1 in ys])


@pytest.mark.parametrize("name,capture", [("same", "a"), ("moved", "a"), ("big", "wide_a")])
def test_thumbnail_of_a(index, name, capture):
    """thumb_a.png: A's `final` (final.png holds the target's bytes), box-filtered to at most 160 wide."""
    final = png(os.path.join(index[capture], "final.png"))[..., :3]
    thumb = png(index["report"] / name / "thumb_a.png")
    h, w = final.shape[:2]
    tw = min(w, 160)
    th = round(h * tw / w)
    assert thumb.shape[:2] == (th, tw)
    expected = reduce(final.astype(np.float64), th, tw, np.mean)
    assert np.abs(thumb[..., :3] - expected).max() <= 2


@pytest.mark.parametrize("name,a,b", [("same", "a", "a"), ("another", "b", "b"), ("moved", "a", "b"), ("big", "wide_a", "wide_b")])
def test_thumbnail_of_the_difference(index, name, a, b):
    """thumb_diff.png: the worst group's heat map max-pooled: black where nothing differs, and every block
    holding a clear difference of the worst quantity (read from the captures' EXR files) not black."""
    report = json.load(open(index["report"] / name / "report.json"))
    groups = report["groups"]
    worst = next((g for r in ("fail", "warn") for g in groups if g["result"] == r), groups[0])
    thumb = png(index["report"] / name / "thumb_diff.png")[..., :3]
    lit = thumb.max(axis=-1) > 0
    if a == b:
        assert not lit.any()
        return
    assert worst["key"] == "hdr" and worst["result"] == "fail"  # the lights move: hdr fails first
    diff = np.abs(pixels(os.path.join(index[a], "hdr.exr"))[..., :3] - pixels(os.path.join(index[b], "hdr.exr"))[..., :3]).max(axis=-1)
    assert int((diff > 0).sum()) == worst["metrics"]["differing_pixels"]  # the same pixels as gblens's
    h, w = diff.shape
    assert thumb.shape[:2] == (round(h * min(w, 160) / w), min(w, 160))
    pooled = reduce(diff[..., None], thumb.shape[0], thumb.shape[1], np.max)[..., 0]
    assert not (lit & (pooled == 0)).any()        # lit only where something differs
    assert lit[pooled >= 0.01 * diff.max()].all()  # clear differences shown (a tiny one may map to black)
    assert lit[np.unravel_index(pooled.argmax(), pooled.shape)]
    # The reduction itself: each channel's maximum over the block of the pair page's full heat map (its
    # legend strip below the map left out), so that one differing pixel keeps its colour.
    maps = index["report"].parent / f"maps-{name}"  # the page carries no heat map images: compare -o writes them
    run("compare", index[a], index[b], "-o", maps, "--json", maps.with_suffix(".json"), "-q", check=False)
    heatmap = next(g for g in json.load(open(maps.with_suffix(".json")))["groups"] if g["key"] == "hdr")["heatmap"]
    full = png(heatmap)[:h, :w, :3]
    assert np.array_equal(thumb, reduce(full, thumb.shape[0], thumb.shape[1], np.max))
