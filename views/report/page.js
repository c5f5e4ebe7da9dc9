// gblens compare report page (views/report/page.html inlines it): draws report.js's summary, and per
// group A, B, |A-B| x multiplier (from data/<key>.js), the heat map and FLIP map (img/), side by side,
// as a swipe (A left of the mouse, B right) or flipped with the F key; hovering shows both sides'
// stored and decoded values at the pixel. No framework, no network: everything is beside the page.
'use strict';
const G = { report: null, groups: {}, data: {}, waiting: {}, key: null, mode: 'side', side: 'a', mult: 1, exposure: 0,
            split: 0.5, zoom: 'fit', images: null };
const COLOUR = ['albedo', 'base_color', 'emission', 'radiance', 'display'];
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
function fmt(v) {
  if (v === null || v === undefined) return '-';
  if (typeof v === 'string') return v;
  if (!isFinite(v)) return isNaN(v) ? 'nan' : (v > 0 ? 'inf' : '-inf');
  return String(Number(v.toPrecision(6)));
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
  G.groups = data.groups;
  page.append(el('h1', {}, 'gblens compare: ', el('span', { class: r.result.replace(' ', '') }, r.result.toUpperCase()), ` (exit ${r.exit_code})`),
    el('div', { class: 'mono' }, 'A ' + r.a), el('div', { class: 'mono' }, 'B ' + r.b));
  if (r.mask) page.append(el('p', { id: 'mask' }, `mask ${r.mask.parts.join(',')}: ${r.mask.pixels} of ${r.mask.of} pixels (${fmt(100 * r.mask.pixels / r.mask.of)}%) reported apart; `,
                               el('a', { href: r.mask.image }, 'mask image'), ' (red: silhouettes, green: penumbra, blue: mask file)'));
  page.append(el('h2', {}, 'Summary'), summary(r), el('h2', { id: 'view-title' }, 'View'), controls(),
              el('div', { id: 'panes' }), el('div', { id: 'readout' }), el('h2', {}, 'Manifest fields that differ'), differences(r));
  document.addEventListener('keydown', (e) => { if (e.key === 'f' || e.key === 'F') flip(); });
  const first = r.groups.find((g) => g.result !== 'pass') || r.groups[0];
  if (first) show(first.key);
}

function indexPage(page, pairs) {
  const worst = pairs.reduce((w, p) => Math.max(w, p.exit_code), 0);
  page.append(el('h1', {}, `gblens compare: ${pairs.length} pairs, worst exit ${worst}`));
  const t = el('table', { id: 'pairs' }, el('tr', {}, ...['pair', 'result', 'A', 'B', 'not passing'].map((h) => el('th', {}, h))));
  for (const p of pairs) {
    const bad = p.groups.filter((g) => g.result !== 'pass').map((g) => g.key).concat(p.mismatches.map((m) => m.target));
    t.append(el('tr', { data: { key: p.name } }, el('td', {}, p.page ? el('a', { href: p.page }, p.name) : p.name),
      el('td', { class: p.result.replace(' ', ''), data: { field: 'result' } }, p.result.toUpperCase()),
      el('td', { class: 'mono' }, p.a), el('td', { class: 'mono' }, p.b), el('td', {}, p.error || bad.join(', '))));
  }
  page.append(t);
}

// ---- controls and views --------------------------------------------------------------------------
function controls() {
  const mode = (m, label) => el('button', { id: 'mode-' + m, onclick: () => { G.mode = m; draw(); } }, label);
  const range = (id, min, max, step, value, on) => el('input', { id, type: 'range', min, max, step, value, oninput: (e) => { on(Number(e.target.value)); draw(); } });
  return el('div', { id: 'controls' }, mode('side', 'side by side'), mode('swipe', 'swipe'), mode('flip', 'flip A/B (F)'),
    el('label', {}, 'difference x', range('mult', 1, 100, 1, 1, (v) => { G.mult = v; $('mult-value').textContent = v; }), el('span', { id: 'mult-value' }, '1')),
    el('label', {}, 'zoom ', el('select', { id: 'zoom', onchange: (e) => { G.zoom = e.target.value; draw(); } },
      ...['fit', '1', '2', '4', '8'].map((z) => el('option', { value: z }, z === 'fit' ? 'fit' : z + ':1')))),
    el('label', { id: 'exposure-label' }, 'exposure', range('exposure', -8, 8, 0.5, 0, (v) => { G.exposure = v; $('exposure-value').textContent = v; }), el('span', { id: 'exposure-value' }, '0')));
}

function flip() { G.side = G.mode === 'flip' && G.side === 'a' ? 'b' : 'a'; G.mode = 'flip'; draw(); }

function show(key) {
  G.key = key;
  for (const tr of document.querySelectorAll('#summary tr.pick')) tr.classList.toggle('shown', tr.dataset.key === key);
  $('view-title').textContent = 'View: ' + key;
  if (G.data[key]) return draw();
  $('panes').textContent = 'loading ' + G.groups[key].data + ' ...';
  G.waiting[key] = true;
  document.body.append(el('script', { src: G.groups[key].data }));
}

// report_data.cpp's packing undone: base64 -> inflate -> unshuffle the floats' bytes (when shuffled)
// -> planes back to `n` components interleaved per pixel.
async function unpack(b64, n, shuffled) {
  const bin = atob(b64), bytes = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; ++i) bytes[i] = bin.charCodeAt(i);
  const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream('deflate'));
  const inflated = new Uint8Array(await new Response(stream).arrayBuffer()), count = inflated.length / 4;
  const planar = new Uint8Array(inflated.length);
  if (shuffled) for (let j = 0; j < count; ++j) for (let b = 0; b < 4; ++b) planar[j * 4 + b] = inflated[b * count + j];
  else planar.set(inflated);
  const p = new Float32Array(planar.buffer), pixels = count / n, out = new Float32Array(count);
  for (let k = 0; k < n; ++k) for (let i = 0; i < pixels; ++i) out[i * n + k] = p[k * pixels + i];
  return out;
}

async function gblensData(d) {
  for (const s of ['a', 'b']) {
    d[s].stored = await unpack(d[s].stored, d[s].channels.length, d.shuffled);
    d[s].decoded = d[s].decoded === null ? d[s].stored : await unpack(d[s].decoded, d[s].components.length, d.shuffled);
  }
  d.error = await unpack(d.error, 1, d.shuffled);
  G.data[d.key] = d;
  if (G.key === d.key) draw();
}

// Display colour of one decoded pixel (components v) of a quantity kind, as bytes.
function srgb(c) { c = Math.min(Math.max(c, 0), 1); return 255 * (c <= 0.0031308 ? 12.92 * c : 1.055 * Math.pow(c, 1 / 2.4) - 0.055); }
function hue(n) { const h = (n * 0.618034) % 1, f = (k) => 255 * Math.max(0, Math.min(1, Math.abs(((h * 6 + k) % 6) - 3) - 1)); return [f(0), f(4), f(2)]; }
function pixelColour(kind, v, n, span, exposure) {
  if (COLOUR.includes(kind)) {
    if (v.some((c) => isNaN(c))) return [255, 0, 255];
    const k = Math.pow(2, exposure);
    return n >= 3 ? [srgb(v[0] * k), srgb(v[1] * k), srgb(v[2] * k)] : [srgb(v[0] * k), srgb(v[0] * k), srgb(v[0] * k)];
  }
  if (isNaN(v[0])) return [0, 0, 0];  // depth or position where no surface was drawn
  if (kind === 'normal') return [127.5 * (v[0] + 1), 127.5 * (v[1] + 1), 127.5 * (v[2] + 1)];
  if (['id', 'stencil', 'count'].includes(kind)) return v[0] === 0 ? [0, 0, 0] : hue(v[0]);
  const t = (k) => (v[k] - span[k][0]) / Math.max(span[k][1] - span[k][0], 1e-30);
  if (kind === 'depth') { const g = 255 * (1 - t(0)); return [g, g, g]; }  // near bright
  if (n >= 3) return [255 * t(0), 255 * t(1), 255 * t(2)];
  if (n === 2) return [255 * t(0), 255 * t(1), 0];
  return [255 * t(0), 255 * t(0), 255 * t(0)];
}

// The display ranges of a group: both sides' finite ranges; unit-range quantities keep [0, 1].
function spans(d) {
  return d.a.components.map((_, k) => {
    const r = [d.a.ranges[k], d.b.ranges[k]].filter((x) => x);
    let lo = Math.min(...r.map((x) => x[0])), hi = Math.max(...r.map((x) => x[1]));
    if (!isFinite(lo)) lo = 0, hi = 1;
    if (!['depth', 'position', 'motion'].includes(d.a.kind)) lo = Math.min(lo, 0), hi = Math.max(hi, 1);
    return [lo, hi];
  });
}

function canvasOf(d, side) {
  const c = el('canvas', { width: d.width, height: d.height }), ctx = c.getContext('2d');
  const img = ctx.createImageData(d.width, d.height), s = d[side], n = s.components.length, span = spans(d);
  const v = new Array(n);
  for (let i = 0; i < d.width * d.height; ++i) {
    for (let k = 0; k < n; ++k) v[k] = s.decoded[i * n + k];
    const [r, g, b] = pixelColour(d.a.kind, v, n, span, G.exposure);
    img.data.set([r, g, b, 255], i * 4);
  }
  ctx.putImageData(img, 0, 0);
  return c;
}

function diffCanvas(d) {
  const c = el('canvas', { width: d.width, height: d.height }), ctx = c.getContext('2d');
  const img = ctx.createImageData(d.width, d.height), unit = d.kind === 'normal' ? 180 : 1;
  for (let i = 0; i < d.width * d.height; ++i) {
    const e = d.error[i], g = isNaN(e) ? 0 : 255 * Math.min(1, (e * G.mult) / unit);
    img.data.set([g, g, g, 255], i * 4);
  }
  ctx.putImageData(img, 0, 0);
  return c;
}

function pane(id, label, node, w, h, zoom) {
  node.id = id;
  node.style.width = w * zoom + 'px';
  node.style.height = h * zoom + 'px';
  node.addEventListener('mousemove', (e) => hover(e, node, w, h));
  return el('div', { class: 'pane' }, el('div', { class: 'label', id: id + '-label' }, label), node);
}

// A heat map PNG (img/): its top-left width x height pixels (the map) at the views' zoom, its legend
// strip below them at its own size.
function mapPane(id, label, src, d, zoom) {
  const map = el('canvas', { width: d.width, height: d.height }), legend = el('canvas', { class: 'legend' });
  const img = el('img', { src });
  img.addEventListener('load', () => {
    map.getContext('2d').drawImage(img, 0, 0);
    // The legend at 1:1, as wide as its bar and labels (compare.h: 360 to 720 pixels from the left).
    legend.width = Math.min(img.naturalWidth, 720), legend.height = img.naturalHeight - d.height;
    legend.getContext('2d').drawImage(img, 0, d.height, legend.width, legend.height, 0, 0, legend.width, legend.height);
  });
  const box = pane(id, label, map, d.width, d.height, zoom);
  box.append(legend);
  return box;
}

function draw() {
  const d = G.data[G.key];
  if (!d) return;
  const g = G.report.groups.find((x) => x.key === G.key), extra = G.groups[G.key];
  d.kind = g.kind;
  for (const m of ['side', 'swipe', 'flip']) $('mode-' + m).classList.toggle('on', G.mode === m);
  $('exposure-label').style.display = COLOUR.includes(d.a.kind) ? '' : 'none';
  const key = `${G.key}|${G.exposure}`;
  if (!G.images || G.images.key !== key) G.images = { key, a: canvasOf(d, 'a'), b: canvasOf(d, 'b') };
  // fit: small frames at the largest whole zoom up to 480 pixels wide, large ones scaled to 640.
  const zoom = G.zoom !== 'fit' ? Number(G.zoom) : d.width >= 640 ? 640 / d.width : Math.max(1, Math.floor(480 / d.width));
  const panes = $('panes');
  panes.textContent = '';
  if (G.mode === 'side') {
    const copy = (src) => { const c = el('canvas', { width: d.width, height: d.height }); c.getContext('2d').drawImage(src, 0, 0); return c; };
    panes.append(pane('pane-a', 'A ' + d.a.target, copy(G.images.a), d.width, d.height, zoom),
                 pane('pane-b', 'B ' + d.b.target, copy(G.images.b), d.width, d.height, zoom),
                 pane('pane-diff', `|A-B| x ${G.mult} (white: ${fmt((g.kind === 'normal' ? 180 : 1) / G.mult)}${g.kind === 'normal' ? ' deg' : ''})`, diffCanvas(d), d.width, d.height, zoom));
    panes.append(mapPane('pane-heat', 'heat map', extra.heatmap, d, zoom));
    if (extra.flip) panes.append(mapPane('pane-flipmap', 'FLIP', extra.flip, d, zoom));
  } else {
    const c = el('canvas', { width: d.width, height: d.height });
    const box = pane('pane-view', '', c, d.width, d.height, zoom);
    panes.append(box);
    if (G.mode === 'swipe') {
      box.append(el('div', { id: 'swipe-line' }));
      c.addEventListener('mousemove', (e) => { const r = c.getBoundingClientRect(); G.split = (e.clientX - r.left) / r.width; swipe(c, d); });
      swipe(c, d);
    } else {
      c.getContext('2d').drawImage(G.images[G.side], 0, 0);
      $('pane-view-label').textContent = G.side === 'a' ? 'A (press F for B): ' + G.report.a : 'B (press F for A): ' + G.report.b;
    }
  }
  document.body.dataset.shown = `${G.key}|${G.mode}|${G.side}`;
}

function swipe(c, d) {
  const x = Math.max(0, Math.min(d.width, Math.round(G.split * d.width))), ctx = c.getContext('2d');
  ctx.drawImage(G.images.a, 0, 0);
  if (x < d.width) ctx.drawImage(G.images.b, x, 0, d.width - x, d.height, x, 0, d.width - x, d.height);
  const line = $('swipe-line');
  line.style.left = (x / d.width) * c.getBoundingClientRect().width + 'px';
  line.style.top = c.offsetTop + 'px';
  line.style.height = c.getBoundingClientRect().height + 'px';
  $('pane-view-label').textContent = `swipe: A left of x = ${x}, B right`;
}

// A box around the hovered pixel in every pane, so the readout's pixel is seen in A, B and the maps.
function mark(x, y, w, h) {
  for (const c of document.querySelectorAll('#panes .pane > canvas:not(.legend)')) {
    let m = c.parentNode.querySelector('.mark');
    if (!m) c.parentNode.append(m = el('div', { class: 'mark' }));
    const s = c.clientWidth / w;
    Object.assign(m.style, { left: c.offsetLeft + x * s - 1 + 'px', top: c.offsetTop + y * s - 1 + 'px', width: s + 'px', height: s + 'px' });
  }
}

// The readout: both sides' stored channels and decoded components at the pixel under the mouse.
function hover(e, node, w, h) {
  const r = node.getBoundingClientRect();
  const x = Math.floor(((e.clientX - r.left) * w) / r.width), y = Math.floor(((e.clientY - r.top) * h) / r.height);
  if (x < 0 || y < 0 || x >= w || y >= h) return;
  const d = G.data[G.key], i = y * w + x;
  mark(x, y, w, h);
  const t = el('table', { id: 'readout-table', data: { x, y } }, el('tr', {}, el('th', {}, `pixel ${x}, ${y}`), el('th', {}, 'A ' + d.a.target), el('th', {}, 'B ' + d.b.target)));
  const value = (side, s, k) => d[side][s][i * d[side][s === 'stored' ? 'channels' : 'components'].length + k];
  const rows = (what, names, s) => names.forEach((name, k) => {
    const differs = fmt(value('a', s, k)) !== fmt(value('b', s, k)) ? 'differs' : '';  // A and B apart: highlighted
    t.append(el('tr', {}, el('td', {}, `${what} ${name}`),
      ...['a', 'b'].map((side) => el('td', { class: differs, data: { side, what, index: k } }, fmt(value(side, s, k))))));
  });
  rows('stored', d.a.channels, 'stored');
  rows('decoded', d.a.components, 'decoded');
  t.append(el('tr', {}, el('td', {}, `error (${d.kind})`), el('td', { colspan: 2, data: { what: 'error' } }, fmt(d.error[i]))));
  $('readout').replaceChildren(t);
}
