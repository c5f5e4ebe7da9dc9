// gblens compare report page (views/report/page.html inlines it with texels.js): report.js's summary,
// and per group A, B, |A-B| and the FLIP map in linked panes (wheel zoom about the mouse, drag to pan,
// values in texels when zoomed in), a swipe, a flip, both sides' stored bits and decoded values under
// the mouse, keys for all of it. No framework, no network: everything is beside the page.
'use strict';
const G = { report: null, groups: {}, key: null, mode: 'row', side: 'a', mult: 1, exposure: 0, split: 0.5,
            view: null, probe: null, values: true, drag: null };
const $ = (id) => document.getElementById(id);

function el(tag, attrs, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs || {})) {
    if (k === 'class') e.className = v; else if (k.startsWith('on')) e.addEventListener(k.slice(2), v);
    else if (k === 'data') Object.assign(e.dataset, v); else e.setAttribute(k, v);
  }
  for (const c of children) if (c !== null && c !== undefined) e.append(c instanceof Node ? c : String(c));
  return e;
}
// Counts exactly, other figures to 6 digits.
function fmt(v) {
  if (v === null || v === undefined) return '-';
  if (typeof v === 'string') return v;
  if (Number.isInteger(v) && Math.abs(v) <= Number.MAX_SAFE_INTEGER) return String(v);
  return gfmt(v, 6);
}
const num = (v, metric) => el('td', { class: 'num', data: metric ? { metric } : {} }, fmt(v));

// ---- summary -------------------------------------------------------------------------------------
const METRICS = { colour: ['max_abs', 'mean_abs', 'rmse', 'psnr_db'], normal: ['max_degrees', 'mean_degrees', 'p99_degrees'],
                  depth: ['max_abs', 'mean_abs', 'max_rel', 'mean_rel'], position: ['max_abs', 'mean_abs', 'max_rel', 'mean_rel'],
                  exact: ['max_abs', 'differing_pixels'] };
const FLIP_METRICS = ['mean', 'weighted_median', 'weighted_quartile_1', 'weighted_quartile_3', 'min', 'max'];

function figuresRow(g, f, first) {
  const tr = el('tr', { class: first ? 'pick' : 'apart', data: { key: g.key, covers: f.covers } });
  if (first) tr.addEventListener('click', () => show(g.key));
  tr.append(el('td', {}, first ? g.key : ''), el('td', {}, first ? g.kind : ''),
            el('td', { class: first ? g.result : 'dim', data: { field: 'result' } }, first ? g.result.toUpperCase() : 'apart'),
            el('td', { data: { field: 'covers' } }, f.covers), num(f.pixels, null));
  tr.lastChild.dataset.field = 'pixels';
  const figs = el('td', { class: 'mono' });
  for (const m of METRICS[g.kind] || []) figs.append(m + ' ', el('span', { class: 'num', data: { metric: m } }, fmt(f.metrics[m])), '  ');
  tr.append(figs, num(100 * f.over_fail / Math.max(f.pixels, 1)), num(100 * f.over_warn / Math.max(f.pixels, 1)));
  tr.children[6].dataset.field = 'percent_over_fail';
  tr.append(el('td', { class: 'mono' }, first ? `fail ${fmt(g.thresholds.fail)} (${fmt(g.thresholds.failpercent)}%), warn ${fmt(g.thresholds.warn)} (${fmt(g.thresholds.warnpercent)}%), hardfail ${fmt(g.thresholds.hardfail)}` : ''));
  return tr;
}

function summary(r) {
  const body = el('tbody');
  for (const g of r.groups) {
    body.append(figuresRow(g, g, true));
    for (const f of [g.masked, g.all]) if (f) body.append(figuresRow(g, f, false));
  }
  for (const f of r.flip) {
    const tr = el('tr', { class: 'pick', data: { key: 'flip.' + f.target, covers: f.covers } });
    const group = r.groups.find((g) => g.target === f.target);
    if (group) tr.addEventListener('click', () => show(group.key));
    const figs = el('td', { class: 'mono' });
    for (const m of FLIP_METRICS) figs.append(m + ' ', el('span', { class: 'num', data: { metric: m } }, fmt(f[m])), '  ');
    const t = f.thresholds;
    tr.append(el('td', {}, 'flip.' + f.target), el('td', {}, f.method), el('td', { class: f.result, data: { field: 'result' } }, f.result.toUpperCase()),
              el('td', { data: { field: 'covers' } }, f.covers), num(f.pixels), figs, el('td'), el('td'),
              el('td', { class: 'mono' }, t.fail === null && t.warn === null ? 'none (reported only)' : `fail ${fmt(t.fail)}, warn ${fmt(t.warn)} (mean)`));
    tr.children[4].dataset.field = 'pixels';
    body.append(tr);
  }
  for (const m of r.mismatches) body.append(el('tr', { data: { key: m.target } }, el('td', {}, m.target), el('td'),
    el('td', { class: 'mismatch', data: { field: 'result' } }, 'MISMATCH'), el('td', { colspan: 6 }, m.reason)));
  for (const s of r.skipped) body.append(el('tr', { data: { key: s.target } }, el('td', {}, s.target), el('td'),
    el('td', { class: 'skipped', data: { field: 'result' } }, 'SKIPPED'), el('td', { colspan: 6 }, s.reason)));
  const head = el('tr', {}, ...['quantity', 'metric', 'result', 'pixels covered', 'pixels', 'figures (over those pixels)',
                                '% over fail', '% over warn', 'thresholds'].map((h) => el('th', {}, h)));
  return el('table', { id: 'summary' }, el('thead', {}, head), body);
}

function differences(r) {
  if (!r.differences.length) return el('p', { class: 'dim' }, 'The manifests agree on every option, the scene, the lights, the device and the build.');
  const t = el('table', { id: 'differences' }, el('tr', {}, el('th', {}, 'field'), el('th', {}, 'A'), el('th', {}, 'B')));
  for (const d of r.differences)
    t.append(el('tr', {}, el('td', { class: 'mono' }, d.name), el('td', { class: 'mono' }, JSON.stringify(d.a)), el('td', { class: 'mono' }, JSON.stringify(d.b))));
  return t;
}

function gblensReport(data) {
  const page = $('page');
  page.textContent = '';
  if (data.kind === 'index') return indexPage(page, data.pairs);
  const r = G.report = data.report;
  G.groups = data.groups, G.magma = data.magma;
  // The first quantity's coarse chunk loads while the page is built (it is what is drawn first).
  const first = r.groups.find((g) => g.result !== 'pass') || r.groups[0];
  if (first && G.groups[first.key]) requestChunk(first.key, '0');
  page.append(el('h1', {}, 'gblens compare: ', el('span', { class: r.result.replace(' ', '') }, r.result.toUpperCase()), ` (exit ${r.exit_code})`),
    el('div', { class: 'mono' }, 'A ' + r.a), el('div', { class: 'mono' }, 'B ' + r.b));
  if (r.mask) page.append(el('p', { id: 'mask' }, `mask ${r.mask.parts.join(',')}: ${r.mask.pixels} of ${r.mask.of} pixels (${fmt(100 * r.mask.pixels / r.mask.of)}%) reported apart; `,
                               el('a', { href: r.mask.image }, 'mask image'), ' (red: silhouettes, green: penumbra, blue: mask file)'));
  page.append(el('h2', {}, 'Summary'), summary(r), el('h2', { id: 'view-title' }, 'View'), controls(),
              el('div', { id: 'panes' }), el('div', { id: 'readout' }), el('h2', {}, 'Manifest fields that differ'), differences(r));
  page.append(el('div', { id: 'help', hidden: '' }, el('h2', {}, 'Keys'), keyTable()));
  document.addEventListener('keydown', onKey);
  window.addEventListener('mouseup', () => { G.drag = null; });
  window.addEventListener('mousemove', onDrag);
  if (first) show(first.key);
}

// The pairs index page: indexPage in index.js.

// ---- keys ----------------------------------------------------------------------------------------
// The page's keys: one table for the handler and the help list (docs/report.md has the same rows).
const KEYS = [
  ['Space', 'flip A and B in place (the same zoom and pan)', () => flip()],
  ['S', 'swipe: A left of the mouse, B right of it', () => setMode('swipe')],
  ['R', 'A, B, |A-B| and FLIP side by side', () => setMode('row')],
  ['D', '|A-B| alone', () => setMode('diff')],
  ['F', 'the FLIP map alone (final and hdr)', () => setMode('flipmap')],
  ['N, PageDown', 'the next quantity', () => step(1)],
  ['P, PageUp', 'the previous quantity', () => step(-1)],
  ['Z', 'fit: undo zoom and pan', () => { G.view = null; draw(); }],
  ['+, -', 'zoom in, out about the probed texel', (k) => zoomBy(k === '-' ? 0.5 : 2, null)],
  ['arrows', 'move the probed texel', (k) => moveProbe(k)],
  ['G', 'values in texels on / off (zoomed in)', () => { G.values = !G.values; draw(); }],
  ['?', 'this list', () => { $('help').hidden = !$('help').hidden; }],
  ['wheel', 'zoom about the mouse, every pane alike', null],
  ['drag', 'pan, every pane alike', null],
  ['mouse over a pane', "both sides' stored bits and decoded values at the texel, and |A-B|", null],
];
const KEY_NAMES = { ' ': 'Space', PageDown: 'PageDown', PageUp: 'PageUp', ArrowLeft: 'arrows', ArrowRight: 'arrows',
                    ArrowUp: 'arrows', ArrowDown: 'arrows', '+': '+', '=': '+', '-': '-', '?': '?' };

function keyTable() {
  return el('table', { id: 'keys' }, ...KEYS.map(([k, what]) => el('tr', {}, el('td', { class: 'mono' }, k), el('td', {}, what))));
}

function onKey(e) {
  if (e.target.tagName === 'INPUT' || e.target.tagName === 'SELECT' || e.ctrlKey || e.metaKey || e.altKey) return;
  const name = KEY_NAMES[e.key] || e.key.toUpperCase();
  const row = KEYS.find(([k, , act]) => act && k.split(', ').includes(name));
  if (!row || !G.key) return;
  e.preventDefault();
  row[2](e.key);
}

function setMode(m) {
  if (m === 'flipmap' && !G.groups[G.key].flip) m = 'diff';  // no FLIP map for this quantity
  G.mode = m;
  draw();
}
function flip() { G.side = G.mode === 'flip' && G.side === 'a' ? 'b' : 'a'; G.mode = 'flip'; draw(); }
function step(d) {
  const keys = G.report.groups.map((g) => g.key), i = keys.indexOf(G.key);
  show(keys[(i + d + keys.length) % keys.length]);
}

// ---- controls ------------------------------------------------------------------------------------
function controls() {
  const mode = (m, label) => el('button', { id: 'mode-' + m, onclick: () => setMode(m) }, label);
  const range = (id, min, max, step, value, on) => el('input', { id, type: 'range', min, max, step, value, oninput: (e) => { on(Number(e.target.value)); draw(); } });
  return el('div', { id: 'controls' }, mode('row', 'side by side (R)'), mode('swipe', 'swipe (S)'),
    el('button', { id: 'mode-flip', onclick: flip }, 'flip A/B (Space)'), mode('diff', '|A-B| (D)'), mode('flipmap', 'FLIP (F)'),
    el('label', {}, '|A-B| x', range('mult', 1, 100, 1, 1, (v) => { G.mult = v; $('mult-value').textContent = v; }), el('span', { id: 'mult-value' }, '1')),
    el('label', { id: 'exposure-label' }, 'exposure', range('exposure', -8, 8, 0.5, 0, (v) => { G.exposure = v; $('exposure-value').textContent = v; }), el('span', { id: 'exposure-value' }, '0')),
    el('span', { id: 'zoom-label', class: 'mono' }), el('button', { onclick: () => { $('help').hidden = !$('help').hidden; } }, 'keys (?)'));
}

function show(key) {
  G.key = key;
  G.view = null;
  for (const tr of document.querySelectorAll('#summary tr.pick')) tr.classList.toggle('shown', tr.dataset.key === key);
  $('view-title').textContent = 'View: ' + key;
  draw();
}

// ---- panes: one view (zoom s, top-left texel ox, oy) shared by every pane ---------------------------
function fitScale(t) { return t.w >= 640 ? 640 / t.w : Math.max(1, Math.floor(480 / t.w)); }
function viewOf(t) {
  const fit = fitScale(t), vw = Math.round(t.w * fit), vh = Math.round(t.h * fit);
  if (!G.view) G.view = { s: fit, ox: 0, oy: 0 };
  const v = G.view;
  v.s = Math.min(Math.max(v.s, fit), 256);
  v.ox = Math.min(Math.max(v.ox, 0), t.w - vw / v.s), v.oy = Math.min(Math.max(v.oy, 0), t.h - vh / v.s);
  return { ...v, vw, vh, fit };
}

// Zoom by `k` keeping the texel at pane position (px, py) where it is (null: the probed texel or the centre).
function zoomBy(k, at) {
  const t = groupOf(G.key), v = viewOf(t);
  const [px, py] = at || (G.probe ? [(G.probe.x + 0.5 - v.ox) * v.s, (G.probe.y + 0.5 - v.oy) * v.s] : [v.vw / 2, v.vh / 2]);
  const tx = v.ox + px / v.s, ty = v.oy + py / v.s, s = Math.min(Math.max(v.s * k, v.fit), 256);
  G.view = { s, ox: tx - px / s, oy: ty - py / s };
  draw();
}

function moveProbe(k) {
  const t = groupOf(G.key), p = G.probe || { x: 0, y: 0 };
  const d = { ArrowLeft: [-1, 0], ArrowRight: [1, 0], ArrowUp: [0, -1], ArrowDown: [0, 1] }[k];
  probe(Math.min(Math.max(p.x + d[0], 0), t.w - 1), Math.min(Math.max(p.y + d[1], 0), t.h - 1));
}

// The chunks what is shown needs: the coarse pass always (first, alone), the half-resolution passes
// from 1/4 zoom on, the bands of rows in view from 1/2 on, the probed texel's chunk.
function neededChunks(t, v) {
  const ids = ['0'];
  if (v.s > 0.25) ids.push('1');
  if (v.s > 0.5)
    for (let b = Math.floor(v.oy / t.meta.band); b <= Math.floor(Math.min(t.h - 1, v.oy + v.vh / v.s) / t.meta.band); ++b) ids.push('2.' + b);
  return ids;
}
function requestShown(t, v) {
  requestChunk(G.key, '0');
  if (!t.loaded.has('0')) return;  // the coarse image first: on screen before anything finer is read
  for (const id of neededChunks(t, v)) requestChunk(G.key, id);
  if (G.probe) requestChunk(G.key, chunkOf(t, G.probe.x, G.probe.y));
}

function chunkArrived(key) { if (key === G.key) draw(); }

function paneBox(id, label, v) {
  const c = el('canvas', { id, width: v.vw, height: v.vh });
  c.style.width = v.vw + 'px', c.style.height = v.vh + 'px';
  c.addEventListener('wheel', (e) => { e.preventDefault(); zoomBy(e.deltaY < 0 ? 1.25 : 0.8, local(e, c)); }, { passive: false });
  c.addEventListener('mousedown', (e) => { if (e.button === 0) G.drag = { x: e.clientX, y: e.clientY, moved: false }; e.preventDefault(); });
  c.addEventListener('mousemove', (e) => onMove(e, c));
  return el('div', { class: 'pane' }, el('div', { class: 'label', id: id + '-label' }, label), el('div', { class: 'frame' }, c));
}
function local(e, c) { const r = c.getBoundingClientRect(); return [e.clientX - r.left, e.clientY - r.top]; }

// A drag pans wherever the mouse goes (the window listens), not only over the pane it began in.
function onDrag(e) {
  if (!G.drag || !G.view) return;
  const v = G.view;
  G.view = { s: v.s, ox: v.ox - (e.clientX - G.drag.x) / v.s, oy: v.oy - (e.clientY - G.drag.y) / v.s };
  G.drag.x = e.clientX, G.drag.y = e.clientY;
  draw();
}

function onMove(e, c) {
  const v = G.view, [px, py] = local(e, c);
  if (G.drag) return;
  if (G.mode === 'swipe') G.split = px / c.width;
  const t = groupOf(G.key);
  probe(Math.min(t.w - 1, Math.floor(v.ox + px / v.s)), Math.min(t.h - 1, Math.floor(v.oy + py / v.s)));
}

function probe(x, y) { G.probe = { x, y }; draw(); }

// One pane's image through the view, texel values on top. `side`: a, b or diff (their levels drawn
// coarse to fine), or null with `image` (the FLIP map) instead.
function paint(c, side, v, t, clipLeft, image) {
  const ctx = c.getContext('2d');
  ctx.imageSmoothingEnabled = false;
  const sx = Math.floor(v.ox), sy = Math.floor(v.oy);
  const sw = Math.min(t.w - sx, Math.ceil(v.vw / v.s) + 2), sh = Math.min(t.h - sy, Math.ceil(v.vh / v.s) + 2);
  ctx.save();
  if (clipLeft !== undefined) { ctx.beginPath(); ctx.rect(clipLeft, 0, v.vw - clipLeft, v.vh); ctx.clip(); }
  const dest = [(sx - v.ox) * v.s, (sy - v.oy) * v.s, sw * v.s, sh * v.s];
  if (image) ctx.drawImage(image, sx, sy, sw, sh, ...dest);
  else for (const l of t.images[side]) ctx.drawImage(l.canvas, sx / l.f, sy / l.f, sw / l.f, sh / l.f, ...dest);
  delete c.dataset.probedText;
  if (side && G.values && v.s >= 40) texelValues(ctx, t, v, side, sx, sy, sw, sh);
  ctx.restore();
}

// Each texel's value in it, at its storage's precision, in black or white against its colour.
function texelValues(ctx, t, v, what, sx, sy, sw, sh) {
  const size = Math.min(12, Math.floor(v.s / 5));
  ctx.font = `${size}px ui-monospace, monospace`;
  ctx.textAlign = 'center', ctx.textBaseline = 'middle';
  for (let y = sy; y < sy + sh; ++y)
    for (let x = sx; x < sx + sw; ++x) {
      const i = y * t.w + x;
      if (!t.loaded.has(chunkOf(t, x, y))) continue;
      const lines = what === 'diff' ? [gfmt(t.errorF[i], 4)] : decodedValues(t, what, i).map((d) => decodedText(t, what, d));
      const fine = t.images[what][2].data.data, lum = 0.3 * fine[4 * i] + 0.59 * fine[4 * i + 1] + 0.11 * fine[4 * i + 2];
      ctx.fillStyle = lum > 128 ? '#000' : '#fff';
      const cx = (x + 0.5 - v.ox) * v.s, cy = (y + 0.5 - v.oy) * v.s, h = size + 1;
      if (lines.some((l) => ctx.measureText(l).width > v.s - 2) || lines.length * h > v.s - 2) continue;  // never clipped
      lines.forEach((l, k) => ctx.fillText(l, cx, cy + (k - (lines.length - 1) / 2) * h));
      if (G.probe && G.probe.x === x && G.probe.y === y) ctx.canvas.dataset.probedText = lines.join('|');  // what the probed texel says
    }
}

function legend(t) {
  const c = el('canvas', { id: 'diff-legend', class: 'legend', width: 360, height: 34 }), ctx = c.getContext('2d');
  for (let x = 0; x < 300; ++x) { const g = Math.round((255 * x) / 299); ctx.fillStyle = `rgb(${g},${g},${g})`; ctx.fillRect(x, 0, 1, 14); }
  ctx.fillStyle = '#ddd', ctx.font = '11px system-ui, sans-serif', ctx.textBaseline = 'top';
  const top = t.meta.error.max / G.mult;
  ctx.textAlign = 'left', ctx.fillText('0', 0, 17);
  ctx.textAlign = 'center', ctx.fillText(gfmt(top / 2, 4), 150, 17);
  ctx.textAlign = 'right', ctx.fillText(gfmt(top, 4), 300, 17);
  const note = el('div', { class: 'dim legend-note' }, `${t.meta.error.unit}; white: ${gfmt(top, 7)} (the largest / ${G.mult}) and over`,
    t.meta.error.infinite ? '; magenta: infinite' : '', '; dark blue: not compared');
  return el('div', {}, c, note);
}

// The FLIP pane's legend: magma from 0 to 1 (the palette the map's PNG indexes), under the method
// of the FLIP entry whose map it is.
function flipLegend(map) {
  const method = G.report.flip.find((f) => f.heatmap === map).method;
  const c = el('canvas', { id: 'flip-legend', class: 'legend', width: 360, height: 34 }), ctx = c.getContext('2d');
  for (let x = 0; x < 300; ++x) {
    const i = 3 * Math.round((255 * x) / 299), m = G.magma;
    ctx.fillStyle = `rgb(${m[i]},${m[i + 1]},${m[i + 2]})`, ctx.fillRect(x, 0, 1, 14);
  }
  ctx.fillStyle = '#ddd', ctx.font = '11px system-ui, sans-serif', ctx.textBaseline = 'top';
  ctx.textAlign = 'left', ctx.fillText('0', 0, 17);
  ctx.textAlign = 'center', ctx.fillText(method, 150, 17);
  ctx.textAlign = 'right', ctx.fillText('1', 300, 17);
  return el('div', {}, c, el('div', { class: 'dim legend-note' }, `${method}: 0 no difference seen, 1 the largest FLIP measures`));
}

function draw() {
  if (!G.key) return;
  const t = groupOf(G.key), g = G.report.groups.find((x) => x.key === G.key), extra = G.groups[G.key];
  if (!t.images || t.settings !== `${G.exposure}|${G.mult}`) resetImages(t);
  const v = viewOf(t);
  requestShown(t, v);
  for (const m of ['row', 'swipe', 'flip', 'diff', 'flipmap']) $('mode-' + m).classList.toggle('on', G.mode === m);
  $('mode-flipmap').disabled = !extra.flip;
  $('exposure-label').style.display = COLOUR.includes(t.meta.a.kind) ? '' : 'none';
  $('zoom-label').textContent = v.s >= 1 ? `${gfmt(v.s, 3)} px per texel` : `1 px per ${gfmt(1 / v.s, 3)} texels`;
  const panes = $('panes');
  if (panes.dataset.layout !== `${G.key}|${G.mode}|${v.vw}`) {  // rebuilt when what is shown changes, else repainted
    panes.textContent = '';
    panes.dataset.layout = `${G.key}|${G.mode}|${v.vw}`;
    if (G.mode === 'row') {
      panes.append(paneBox('pane-a', 'A ' + t.meta.a.target, v), paneBox('pane-b', 'B ' + t.meta.b.target, v));
      const d = paneBox('pane-diff', `|A-B| (${t.meta.error.unit})`, v);
      d.append(legend(t));
      panes.append(d);
      if (extra.flip) {
        const f = paneBox('pane-flipmap', 'FLIP', v);
        f.append(flipLegend(extra.flip));
        panes.append(f);
      }
    } else {
      const box = paneBox('pane-view', '', v);
      if (G.mode === 'diff') box.append(legend(t));
      if (G.mode === 'flipmap') box.append(flipLegend(extra.flip));
      box.querySelector('.frame').append(el('div', { id: 'swipe-line' }), el('div', { class: 'tag', id: 'tag-a' }, 'A'), el('div', { class: 'tag', id: 'tag-b' }, 'B'));
      panes.append(box);
    }
    if (extra.flip) G.flipImage = G.flipImage && G.flipImage.key === extra.flip ? G.flipImage : Object.assign(el('img', { src: extra.flip }), { key: extra.flip, onload: () => draw() });
  }
  const flipReady = extra.flip && G.flipImage && G.flipImage.complete && G.flipImage.naturalWidth;
  const swipe = $('swipe-line');
  if (swipe) swipe.style.display = $('tag-a').style.display = $('tag-b').style.display = G.mode === 'swipe' ? '' : 'none';
  if (G.mode === 'row') {
    paint($('pane-a'), 'a', v, t);
    paint($('pane-b'), 'b', v, t);
    paint($('pane-diff'), 'diff', v, t);
    if (flipReady && $('pane-flipmap')) paint($('pane-flipmap'), null, v, t, undefined, G.flipImage);
  } else if (G.mode === 'swipe') {
    const x = Math.round(G.split * v.vw);
    paint($('pane-view'), 'a', v, t);
    paint($('pane-view'), 'b', v, t, x);
    Object.assign(swipe.style, { left: x + 'px', height: v.vh + 'px' });
    $('tag-a').style.left = Math.max(0, x - 22) + 'px', $('tag-b').style.left = Math.min(v.vw - 16, x + 6) + 'px';
    $('pane-view-label').textContent = `swipe: A left of the line, B right of it`;
  } else if (G.mode === 'flip') {
    paint($('pane-view'), G.side, v, t);
    $('pane-view-label').textContent = G.side === 'a' ? 'A (Space for B): ' + G.report.a : 'B (Space for A): ' + G.report.b;
  } else if (G.mode === 'diff') {
    paint($('pane-view'), 'diff', v, t);
    $('pane-view-label').textContent = `|A-B| (${t.meta.error.unit})`;
  } else if (flipReady) {
    paint($('pane-view'), null, v, t, undefined, G.flipImage);
    $('pane-view-label').textContent = 'FLIP';
  }
  mark(v);
  readout();
  // shown: the coarse image is on screen; complete: everything the zoom asks for is drawn.
  const complete = neededChunks(t, v).every((id) => t.loaded.has(id));
  document.body.dataset.shown = t.loaded.has('0') ? `${G.key}|${G.mode}|${G.side}` : '';
  document.body.dataset.complete = complete ? 'yes' : '';
  document.body.dataset.view = `${v.s}|${v.ox}|${v.oy}`;
}

// A box around the probed texel in every pane.
function mark(v) {
  for (const c of document.querySelectorAll('#panes canvas:not(.legend)')) {
    const f = c.parentNode;
    let m = f.querySelector('.mark');
    if (!G.probe) { if (m) m.remove(); continue; }
    if (!m) f.append(m = el('div', { class: 'mark' }));
    Object.assign(m.style, { left: (G.probe.x - v.ox) * v.s - 1 + 'px', top: (G.probe.y - v.oy) * v.s - 1 + 'px',
                             width: Math.max(v.s, 1) + 'px', height: Math.max(v.s, 1) + 'px' });
  }
}

// Both sides at the probed texel, each under its own channel and component names; |A-B| per component.
function readout() {
  const out = $('readout');
  if (!G.probe) return out.replaceChildren(el('p', { class: 'dim' }, 'Move the mouse over a pane: both sides\' values at the texel.'));
  const t = groupOf(G.key), { x, y } = G.probe, i = y * t.w + x, id = chunkOf(t, x, y);
  if (t.failed) return out.replaceChildren(el('p', { class: 'error' }, t.failed));
  if (!t.loaded.has(id)) return out.replaceChildren(el('p', { class: 'dim' }, `texel ${x}, ${y}: loading its values ...`));
  const block = (s) => {
    const m = t.meta[s], tab = el('table', { class: 'side', data: { side: s } });
    tab.append(el('tr', {}, el('th', { colspan: 2 }, `${s.toUpperCase()}: ${m.target} (${m.format})`)));
    m.channels.forEach((name, k) => tab.append(el('tr', {}, el('td', {}, 'stored ' + name),
      el('td', { data: { side: s, what: 'stored', index: k, name } }, storedText(t, s, k, i)))));
    tab.append(el('tr', {}, el('th', { colspan: 2 }, `${m.quantity}${m.space ? ' (' + m.space + ')' : ''}`)));
    decodedValues(t, s, i).forEach((d, k) => tab.append(el('tr', {}, el('td', {}, m.components[k]),
      el('td', { data: { side: s, what: 'decoded', index: k, name: m.components[k] } }, decodedText(t, s, d)))));
    return tab;
  };
  const da = decodedValues(t, 'a', i), db = decodedValues(t, 'b', i), diff = el('table', { class: 'side' }, el('tr', {}, el('th', { colspan: 2 }, '|A-B|')));
  if (da.length === db.length)
    da.forEach((a, k) => diff.append(el('tr', {}, el('td', {}, t.meta.a.components[k]),
      el('td', { class: a === db[k] ? '' : 'differs', data: { what: 'absdiff', index: k } }, gfmt(Math.abs(a - db[k]), 7)))));
  diff.append(el('tr', {}, el('td', {}, `error (${t.meta.error.unit})`), el('td', { data: { what: 'error' } }, isNaN(t.errorF[i]) ? 'not compared' : gfmt(t.errorF[i], 7))));
  out.replaceChildren(el('div', { id: 'readout-table', data: { x, y } }, el('div', { class: 'mono' }, `texel ${x}, ${y}`),
                                el('div', { class: 'sides' }, block('a'), block('b'), diff)));
}
