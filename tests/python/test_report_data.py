"""The compare report's texel data read back in headless Chromium, every texel: a pair 23 texels wide
(odd: a finer pass's last texel has no right neighbour) and 300 rows tall (three bands of 128 rows,
the last one short) decodes on the page to exactly the bits OpenImageIO reads from the captures'
files, both sides (B is coded against A), whichever order the chunks arrive in; the FLIP pane shows
(in a screenshot, texel by texel) the colours of the FLIP map `compare -o` writes."""
import json
import os

import numpy as np
import OpenImageIO as oiio
import pytest

from chromium import Browser
from conftest import run

SIZE = (23, 300)


@pytest.fixture(scope="module")
def tall(tmp_path_factory):
    root = tmp_path_factory.mktemp("tall")
    common = ["--size", f"{SIZE[0]}x{SIZE[1]}", "--shadow-map-size", "64"]
    run("capture", *common, "--lights", "6", "-o", root / "a")
    run("capture", *common, "--lights", "40", "--time", "2", "-o", root / "b")  # lit otherwise: hdr and final differ
    code, _, _ = run("compare", root / "a", root / "b", "--report", root / "page", "-o", root / "diff", "-q", check=False)
    assert code == 2, code
    return root


@pytest.fixture(scope="module")
def browser():
    b = Browser()
    yield b
    b.close()


def file_values(capture, target):
    """The target's stored channels as the capture's EXR holds them, read by OpenImageIO: (channels,
    H, W) of uint32 (float32 bits, or the integer codes of the `TARGET.raw.CHANNEL` channels; an
    ImageBuf would convert them all to one type)."""
    m = json.load(open(os.path.join(capture, "manifest.json")))
    t = next(t for t in m["targets"] if t["name"] == target)
    file = oiio.ImageInput.open(os.path.join(capture, t["file"]))
    names, out = list(file.spec().channelnames), []
    for c in t["exr_channels"]:
        if t["type"] == "f32" or c["type"] == "uint":  # one channel at a time, in its own type: no conversion
            i = names.index(c["name"])
            kind = oiio.FLOAT if c["type"] == "float" else oiio.UINT32
            out.append(np.asarray(file.read_image(0, 0, i, i + 1, kind))[:, :, 0].view(np.uint32))
    file.close()
    return np.array(out)


def page_values(b, key, side):
    return np.array(b.evaluate(f"T[{json.dumps(key)}].{side}.stored.map(p => Array.from(p))"), dtype=np.uint32)


def test_every_texel_decodes_to_the_files_bits_in_any_chunk_order(tall, browser):
    b = browser
    b.navigate("file://" + str(tall / "page" / "index.html"))
    b.wait_for("!!document.body.dataset.shown")
    meta = b.evaluate("G.groups")
    for key, target in [("hdr", "hdr"), ("final", "final"), ("depth", "depth")]:
        chunks = [c["id"] for c in meta[key]["chunks"]]
        assert chunks[2:] == ["2.0", "2.1", "2.2"], chunks
        assert meta[key]["b_stored_against_a"], key
        # The last band first, then the others: what each predicts from comes in after it.
        b.evaluate(f"(() => {{ T[{json.dumps(key)}] = undefined; delete T[{json.dumps(key)}]; "
                   f"for (const id of ['2.2', '2.0', '2.1']) requestChunk({json.dumps(key)}, id); }})()")
        b.wait_for(f"(t => t && (t.failed || t.loaded.size === {len(chunks)}))(T[{json.dumps(key)}])")
        assert b.evaluate(f"T[{json.dumps(key)}].failed") is None
        if key != "depth":  # B's values are coded as B - A: a test of it needs them to differ
            assert np.count_nonzero(file_values(tall / "a", target) != file_values(tall / "b", target)) > 1000, key
        for side, capture in [("a", tall / "a"), ("b", tall / "b")]:
            want = file_values(capture, target)
            got = page_values(b, key, side).reshape(-1, SIZE[1], SIZE[0])
            assert got.shape[0] <= want.shape[0], (key, got.shape, want.shape)
            differ = np.argwhere(got != want[: got.shape[0]])
            assert differ.size == 0, (key, side, differ[:5].tolist())
    assert b.problems() == []


def test_the_flip_pane_shows_the_flip_map_compare_writes(tall, browser):
    b = browser
    b.navigate("file://" + str(tall / "page" / "index.html"))
    b.wait_for("!!document.body.dataset.shown")
    b.evaluate("document.querySelector(\"#summary tr[data-key='hdr'].pick\").click()")
    b.key("f", "KeyF")
    b.wait_for("document.body.dataset.shown === 'hdr|flipmap|a' && G.flipImage && G.flipImage.complete")
    b.wait_for("document.getElementById('flip-legend') !== null")
    # Where each texel lies on the page: the pane's box and the view (scale, origin).
    left, top = b.evaluate("(r => [r.left + window.scrollX, r.top + window.scrollY])(document.getElementById('pane-view').getBoundingClientRect())")
    s, ox, oy = map(float, b.evaluate("document.body.dataset.view").split("|"))
    assert s >= 1, s  # fit zoom of 23x300: texels of a pixel or more
    shot = tall / "flip_pane.png"
    b.screenshot(shot)
    page = np.asarray(oiio.ImageBuf(str(shot)).get_pixels(oiio.UINT8))
    # compare -o's map (RGBA through OpenImageIO, its legend below the map).
    written = np.asarray(oiio.ImageBuf(str(tall / "diff" / "flip_hdr.png")).get_pixels(oiio.UINT8))
    seen, colours = 0, set()
    for y in range(0, SIZE[1], 7):
        for x in range(SIZE[0]):
            px, py = left + (x + 0.5 - ox) * s, top + (y + 0.5 - oy) * s
            if not (0 <= py < page.shape[0] and 0 <= px < page.shape[1]) or y < oy:
                continue
            assert list(page[int(py), int(px), :3]) == list(written[y, x, :3]), (x, y)
            seen += 1
            colours.add(tuple(written[y, x, :3]))
    assert seen > 500 and len(colours) > 4, (seen, len(colours))  # a map, not a flat colour
    assert b.problems() == []
