// The compare report's texels (views/report/texel_chunks.h writes them): chunk scripts loaded when a
// pane or the readout needs them, decoded into both sides' stored bits, decoded values and the error,
// painted coarse to fine into display images; values formatted at their storage's precision.
'use strict';
// x0, y0, dx, dy; a finer pass's texel lies midway between the known ones at -+(ox, oy) (texel_chunks.h)
const PASSES = [[0, 0, 4, 4, 0, 0], [2, 0, 4, 4, 2, 0], [0, 2, 2, 4, 0, 2], [1, 0, 2, 2, 1, 0], [0, 1, 1, 2, 0, 1]];
const CELL = [[4, 4], [2, 4], [2, 2], [1, 2], [1, 1]];  // what a pass's texel stands for until finer ones come
const BYTES = { u8: 1, i8: 1, u16: 2, i16: 2, f16: 2, u32: 4, f32: 4 };
const COLOUR = ['albedo', 'base_color', 'emission', 'radiance', 'display'];
const T = {};  // per group key: its arrays, the chunks loaded and the display images

// printf's %.<p>g: what gblens's C++ prints, so the page and the CLI agree digit for digit.
function gfmt(v, p) {
  if (!isFinite(v)) return isNaN(v) ? 'nan' : v > 0 ? 'inf' : '-inf';
  if (v === 0) return Object.is(v, -0) ? '-0' : '0';
  const trim = (s) => (s.includes('.') ? s.replace(/0+$/, '').replace(/\.$/, '') : s);
  const [m, x] = v.toExponential(p - 1).split('e'), e = Number(x);
  if (e < -4 || e >= p) return trim(m) + 'e' + (e < 0 ? '-' : '+') + String(Math.abs(e)).padStart(2, '0');
  return trim(v.toFixed(p - 1 - e));
}

function halfToFloat(h) {
  const s = h & 0x8000 ? -1 : 1, e = (h >> 10) & 31, m = h & 1023;
  if (e === 0) return s * m * Math.pow(2, -24);
  if (e === 31) return m ? NaN : s * Infinity;
  return s * (1 + m / 1024) * Math.pow(2, e - 15);
}

function groupOf(key) {
  if (T[key]) return T[key];
  const m = G.groups[key], n = m.width * m.height;
  const planes = (count, bytes) => Array.from({ length: count }, () => bytes === 1 ? new Uint8Array(n) : bytes === 2 ? new Uint16Array(n) : new Uint32Array(n));
  const side = (s) => ({ stored: planes(s.channels.length, BYTES[s.type]), decoded: s.decoded ? planes(s.components.length, 4) : null });
  const t = T[key] = { meta: m, w: m.width, h: m.height, a: side(m.a), b: side(m.b), error: new Uint32Array(n).fill(0x7fc00000),
                       loaded: new Set(), pending: new Set(), waiting: new Map(), failed: null, images: null };
  t.errorF = new Float32Array(t.error.buffer);
  for (const s of ['a', 'b']) if (t[s].decoded) t[s].decodedF = t[s].decoded.map((p) => new Float32Array(p.buffer));
  return t;
}

// The chunk of group t holding texel (x, y): its pass decides, and for the fine passes its band (texel_chunks.h).
function chunkOf(t, x, y) {
  const pass = y & 1 ? 4 : x & 1 ? 3 : y % 4 === 2 ? 2 : x % 4 === 2 ? 1 : 0;
  return pass === 0 ? '0' : pass <= 2 ? '1' : '2.' + Math.floor(y / t.meta.band);
}

function requestChunk(key, id) {
  const t = groupOf(key);
  if (t.loaded.has(id) || t.pending.has(id) || t.failed) return;
  t.pending.add(id);
  const s = document.createElement('script');
  s.charset = 'x-user-defined';  // each byte one character (texel_chunks.h deflatedLiteral)
  s.src = t.meta.stem + '.' + id + '.js';
  s.onerror = () => { t.failed = s.src + ' could not be loaded'; chunkArrived(key); };
  document.body.append(s);
}

// The chunks a chunk's passes predict from (texel_chunks.h): they are decoded before it.
const dependencies = (id) => (id === '0' ? [] : id === '1' ? ['0'] : ['0', '1']);

// Called by each chunk script: its bytes inflated, then decoded into the group's arrays and painted
// once the chunks it depends on are (scripts run in the order they arrive, not the order asked).
async function gblensChunk(key, id, size, text) {
  const t = groupOf(key), bytes = new Uint8Array(text.length);
  for (let i = 0; i < text.length; ++i) bytes[i] = text.charCodeAt(i) & 255;
  try {
    const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream('deflate'));
    const inflated = new Uint8Array(await new Response(stream).arrayBuffer());
    if (inflated.length !== size) throw new Error(`${inflated.length} bytes, ${size} expected`);
    t.waiting.set(id, inflated);
    for (const d of dependencies(id)) requestChunk(key, d);
    decodeWaiting(t);
  } catch (e) {
    t.failed = `${t.meta.stem}.${id}.js: ${e.message}`;
    t.pending.delete(id);
  }
  chunkArrived(key);
}

function decodeWaiting(t) {
  for (let again = true; again && !t.failed;) {
    again = false;
    for (const [id, inflated] of t.waiting) {
      if (!dependencies(id).every((d) => t.loaded.has(d))) continue;
      t.waiting.delete(id);
      try {
        decodeChunk(t, t.meta.chunks.find((c) => c.id === id), inflated);
      } catch (e) {
        t.failed = `${t.meta.stem}.${id}.js: ${e.message}`;
        return;
      }
      t.loaded.add(id), t.pending.delete(id), (again = true);
      if (t.images) paintChunk(t, id);
    }
  }
}

function decodeChunk(t, chunk, buf) {
  const m = t.meta;
  let off = 0;
  for (const p of chunk.passes) {
    const [x0, y0, dx, dy, ox, oy] = PASSES[p], cols = t.w > x0 ? Math.ceil((t.w - x0) / dx) : 0, rows = [];
    for (let y = y0; y < t.h; y += dy) if (y >= chunk.rows[0] && y < chunk.rows[1]) rows.push(y);
    const geom = { pass: p, x0, dx, ox, oy, rows, cols, row1: chunk.rows[1] };
    const arrays = [[t.a.stored, BYTES[m.a.type], null], [t.a.decoded, 4, null],
      [t.b.stored, BYTES[m.b.type], m.b_stored_against_a ? t.a.stored : null],
      [t.b.decoded, 4, m.b_decoded_against_a ? t.a.decoded : null], [m.error.rule ? null : [t.error], 4, null]];
    for (const [planes, bytes, ref] of arrays) if (planes) off = decodeArray(buf, off, bytes, planes, ref, geom, t.w);
    if (m.error.rule) for (const y of rows) for (let x = x0; x < t.w; x += dx) t.errorF[y * t.w + x] = unitError(t, y * t.w + x);
  }
  if (off !== buf.length) throw new Error(`${buf.length} bytes, ${off} read`);
}

// texel_chunks.cpp encodeTexels undone: byte planes -> zig-zag unfolded -> prediction added -> reference
// added. Kept in int32 arithmetic (masks and ToInt32 wrap as the C++ unsigned arithmetic does); a
// finer pass reads the texels of the passes before it, so those chunks are decoded first.
function decodeArray(buf, off, bytes, planes, ref, { pass, x0, dx, ox, oy, rows, cols, row1 }, width) {
  const count = cols * rows.length, mask = bytes === 4 ? -1 : (1 << (8 * bytes)) - 1, shift = 32 - 8 * bytes;
  const prev = new Int32Array(cols), cur = new Int32Array(cols), stride = planes.length * count, step = oy * width + ox;
  for (let p = 0; p < planes.length; ++p) {
    prev.fill(0);
    const out = planes[p], r = ref ? ref[p] : null;
    const delta = (at) => (((r ? out[at] - r[at] : out[at]) & mask) << shift) >> shift;  // signed, as the C++ signExtend
    for (let j = 0; j < rows.length; ++j) {
      const base = off + (p * rows.length + j) * cols, y = rows[j], at0 = y * width + x0, below = y + oy < row1;
      let left = 0, upLeft = 0, before = 0;
      for (let i = 0; i < cols; ++i) {
        const k = base + i, at = at0 + i * dx;
        const z = bytes === 4 ? buf[k] | (buf[k + stride] << 8) | (buf[k + 2 * stride] << 16) | (buf[k + 3 * stride] << 24)
                : bytes === 2 ? buf[k] | (buf[k + stride] << 8) : buf[k];
        const e = (z >>> 1) ^ -(z & 1);
        let d;
        if (pass === 0) {
          const up = prev[i];
          d = (e + left + up - upLeft) & mask;
          cur[i] = d, left = d, upLeft = up;
        } else {
          const first = delta(at - step);
          const mean = below && x0 + i * dx + ox < width ? Math.floor((first + delta(at + step)) / 2) : first;
          before = (e + before) & mask;
          d = (before + mean) & mask;
        }
        out[at] = r ? (d + r[at]) & mask : d;
      }
      if (pass === 0) prev.set(cur);
    }
  }
  return off + bytes * stride;
}

// The error where report_data.cpp found it to be the largest |A-B| of the stored units (compare.cpp's
// colour and exact metrics; sRGB codes as code / 255), rounded to float32 as compare stores it.
function unitError(t, i) {
  const n = Math.min(t.meta.a.channels.length, t.meta.b.channels.length, 4);
  let e = 0;
  for (let k = 0; k < n; ++k) {
    const u = storedValue(t.meta.a.units || t.meta.a.rules[k], t.a.stored[k][i]), v = storedValue(t.meta.b.units || t.meta.b.rules[k], t.b.stored[k][i]);
    const d = isNaN(u) || isNaN(v) ? (isNaN(u) && isNaN(v) ? 0 : Infinity) : u === v ? 0 : Math.abs(u - v);
    e = Math.max(e, d);
  }
  return Math.fround(e);
}

// ---- values ---------------------------------------------------------------------------------------
const BITS = new Uint32Array(1), FLOAT = new Float32Array(BITS.buffer);
function storedValue(rule, bits) {
  if (rule.float === 32) return (BITS[0] = bits), FLOAT[0];
  if (rule.float === 16) return halfToFloat(bits);
  if (rule.table !== undefined) return rule.table ? rule.table[bits] : null;
  const v = (rule.signed && bits >= 32768 ? bits - 65536 : bits) / rule.divisor;
  return rule.signed ? Math.max(v, -1) : v;
}

// Side s's decoded components at texel i (the probe's values; NaN where nothing was drawn).
function decodedValues(t, s, i) {
  const m = t.meta[s], d = t[s];
  if (d.decodedF) return d.decodedF.map((p) => p[i]);
  return m.rules.map((rule, k) => storedValue(rule, d.stored[k][i]));
}

// "187 -> 0.7333" for integers, "0.5 (0x3f000000)" for floats: the bits and what they are.
function storedText(t, s, k, i) {
  const rule = t.meta[s].rules[k], bits = t[s].stored[k][i], v = storedValue(rule, bits);
  if (rule.float) return `${gfmt(v, rule.float === 32 ? 9 : 5)} (0x${bits.toString(16).padStart(rule.float / 4, '0')})`;
  return v === null ? String(bits) : `${bits} -> ${gfmt(v, t.meta[s].digits)}`;
}

function decodedText(t, s, v) {
  const m = t.meta[s];
  if (isNaN(v)) return 'none (nothing drawn)';
  return m.integer ? String(v) : gfmt(v, m.digits);
}

// ---- display --------------------------------------------------------------------------------------
// sRGB encoding of [0, 1] for display, tabulated (16384 steps: under a quarter of an 8-bit level apart).
const SRGB = Float32Array.from({ length: 16385 }, (_, i) => { const c = i / 16384; return 255 * (c <= 0.0031308 ? 12.92 * c : 1.055 * Math.pow(c, 1 / 2.4) - 0.055); });
function srgb(c) { return c > 0 ? SRGB[Math.round(Math.min(c, 1) * 16384)] : 0; }
function hue(n) { const h = (n * 0.618034) % 1, f = (k) => 255 * Math.max(0, Math.min(1, Math.abs(((h * 6 + k) % 6) - 3) - 1)); return [f(0), f(4), f(2)]; }
// The display colour of components v[0..n) into o[0..2]: no array made per texel (paintChunk calls
// it for every texel of every side).
function colourInto(kind, colour, v, n, span, k, o) {
  if (colour) {
    for (let c = 0; c < n; ++c) if (isNaN(v[c])) return (o[0] = 255, o[1] = 0, o[2] = 255);
    if (n >= 3) return (o[0] = srgb(v[0] * k), o[1] = srgb(v[1] * k), o[2] = srgb(v[2] * k));
    return (o[0] = o[1] = o[2] = srgb(v[0] * k));
  }
  if (isNaN(v[0])) return (o[0] = o[1] = o[2] = 0);  // depth or position where no surface was drawn
  if (kind === 'normal') return (o[0] = 127.5 * (v[0] + 1), o[1] = 127.5 * (v[1] + 1), o[2] = 127.5 * (v[2] + 1));
  if (kind === 'id' || kind === 'stencil' || kind === 'count') {
    if (v[0] === 0) return (o[0] = o[1] = o[2] = 0);
    const h = hue(v[0]);
    return (o[0] = h[0], o[1] = h[1], o[2] = h[2]);
  }
  const u = (c) => (v[c] - span[c][0]) / Math.max(span[c][1] - span[c][0], 1e-30);
  if (kind === 'depth') return (o[0] = o[1] = o[2] = 255 * (1 - u(0)));  // near bright
  if (n >= 3) return (o[0] = 255 * u(0), o[1] = 255 * u(1), o[2] = 255 * u(2));
  if (n === 2) return (o[0] = 255 * u(0), o[1] = 255 * u(1), o[2] = 0);
  return (o[0] = o[1] = o[2] = 255 * u(0));
}

// Side s's decoded components at texel i into `out` (decodedValues without an array per call); their count.
function valuesInto(t, s, i, out) {
  const m = t.meta[s], d = t[s];
  if (d.decodedF) {
    for (let k = 0; k < d.decodedF.length; ++k) out[k] = d.decodedF[k][i];
    return d.decodedF.length;
  }
  for (let k = 0; k < m.rules.length; ++k) out[k] = storedValue(m.rules[k], d.stored[k][i]);
  return m.rules.length;
}

// The display ranges of a group: both sides' finite ranges; unit-range quantities keep [0, 1].
function spans(m) {
  return m.a.components.map((_, k) => {
    const r = [m.a.ranges[k], m.b.ranges[k]].filter((x) => x);
    let lo = Math.min(...r.map((x) => x[0])), hi = Math.max(...r.map((x) => x[1]));
    if (!isFinite(lo)) lo = 0, hi = 1;
    if (!['depth', 'position', 'motion'].includes(m.a.kind)) lo = Math.min(lo, 0), hi = Math.max(hi, 1);
    return [lo, hi];
  });
}

// |A-B| (the group's per-pixel error) into o: white is the group's largest error / the multiplier.
function diffInto(t, e, o) {
  if (isNaN(e)) return (o[0] = 0, o[1] = 0, o[2] = 60);  // not compared (neither side drew a surface)
  if (!isFinite(e)) return (o[0] = 255, o[1] = 0, o[2] = 255);
  const top = t.meta.error.max;
  return (o[0] = o[1] = o[2] = top > 0 ? 255 * Math.min(1, (e * G.mult) / top) : 0);
}

// The display images: per side (a, b, diff) three levels, one texel per 4x4 cell, per 2x2 cell and
// per texel, each opaque where its texels are loaded; drawn coarse to fine, they show the finest loaded.
const LEVELS = [4, 2, 1];
function resetImages(t) {
  t.images = {};
  for (const s of ['a', 'b', 'diff'])
    t.images[s] = LEVELS.map((f) => {
      const w = Math.ceil(t.w / f), h = Math.ceil(t.h / f), c = document.createElement('canvas');
      c.width = w, c.height = h;
      return { f, canvas: c, data: new ImageData(w, h) };
    });
  t.span = spans(t.meta);
  t.settings = `${G.exposure}|${G.mult}`;
  const loaded = t.meta.chunks.filter((c) => t.loaded.has(c.id));
  for (const c of loaded) paintChunk(t, c.id, false);
  if (loaded.length) flush(t);
}
// The display images' pixels into their canvases: every level, or those a chunk changed and only its rows.
function flush(t, chunk) {
  const finest = chunk ? Math.max(...chunk.passes) : 0, first = finest >= 3 ? 2 : finest >= 1 ? 1 : 0;  // pass 0 reaches every level
  for (const s of ['a', 'b', 'diff'])
    for (const l of t.images[s].slice(first)) {
      const y0 = chunk ? Math.floor(chunk.rows[0] / l.f) : 0, y1 = chunk ? Math.ceil(chunk.rows[1] / l.f) : l.data.height;
      l.canvas.getContext('2d').putImageData(l.data, 0, 0, 0, y0, l.data.width, y1 - y0);
    }
}

// The chunk's texels into every level they belong to (pass 0 to all three, passes 1, 2 to two).
function paintChunk(t, id, now = true) {
  const chunk = t.meta.chunks.find((c) => c.id === id), kind = t.meta.a.kind, colour = COLOUR.includes(kind);
  const k = Math.pow(2, G.exposure), v = new Float64Array(8), colours = [[0, 0, 0], [0, 0, 0], [0, 0, 0]];
  // The levels' pixel arrays and widths looked up once (ImageData's .data is a call into the browser).
  const pixels = ['a', 'b', 'diff'].map((s) => t.images[s].map((l) => l.data.data));
  const widths = t.images.a.map((l) => l.data.width);
  for (const p of chunk.passes) {
    const [x0, y0, dx, dy] = PASSES[p];
    for (let y = Math.max(y0, chunk.rows[0] + ((y0 - chunk.rows[0]) % dy + dy) % dy); y < chunk.rows[1]; y += dy) {
      for (let x = x0; x < t.w; x += dx) {
        const i = y * t.w + x;
        colourInto(kind, colour, v, valuesInto(t, 'a', i, v), t.span, k, colours[0]);
        colourInto(kind, colour, v, valuesInto(t, 'b', i, v), t.span, k, colours[1]);
        diffInto(t, t.errorF[i], colours[2]);
        for (let l = 0; l < 3; ++l) {
          const f = LEVELS[l];
          if (x % f || y % f) continue;
          const j = 4 * ((y / f) * widths[l] + x / f);
          for (let s = 0; s < 3; ++s) {
            const d = pixels[s][l], c = colours[s];
            d[j] = c[0], d[j + 1] = c[1], d[j + 2] = c[2], d[j + 3] = 255;
          }
        }
      }
    }
  }
  if (now) flush(t, chunk);
}
