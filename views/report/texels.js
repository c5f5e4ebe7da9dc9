// The compare report's texels (views/report/texel_chunks.h writes them): chunk scripts loaded when a
// pane or the readout needs them, decoded into both sides' stored bits, decoded values and the error,
// painted coarse to fine into display images; values formatted at their storage's precision.
'use strict';
const PASSES = [[0, 0, 4, 4], [2, 0, 4, 4], [0, 2, 2, 4], [1, 0, 2, 2], [0, 1, 1, 2]];  // x0, y0, dx, dy
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
                       loaded: new Set(), pending: new Set(), failed: null, images: null };
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

// Called by each chunk script: its bytes inflated, decoded into the group's arrays, painted.
async function gblensChunk(key, id, size, text) {
  const t = groupOf(key), bytes = new Uint8Array(text.length);
  for (let i = 0; i < text.length; ++i) bytes[i] = text.charCodeAt(i) & 255;
  try {
    const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream('deflate'));
    const inflated = new Uint8Array(await new Response(stream).arrayBuffer());
    if (inflated.length !== size) throw new Error(`${inflated.length} bytes, ${size} expected`);
    decodeChunk(t, t.meta.chunks.find((c) => c.id === id), inflated);
    t.loaded.add(id);
    if (t.images) paintChunk(t, id);
  } catch (e) {
    t.failed = `${t.meta.stem}.${id}.js: ${e.message}`;
  }
  t.pending.delete(id);
  chunkArrived(key);
}

function decodeChunk(t, chunk, buf) {
  const m = t.meta;
  let off = 0;
  for (const p of chunk.passes) {
    const [x0, y0, dx, dy] = PASSES[p], cols = t.w > x0 ? Math.ceil((t.w - x0) / dx) : 0, rows = [];
    for (let y = y0; y < t.h; y += dy) if (y >= chunk.rows[0] && y < chunk.rows[1]) rows.push(y);
    const geom = { x0, dx, rows, cols };
    const arrays = [[t.a.stored, BYTES[m.a.type], null], [t.a.decoded, 4, null],
      [t.b.stored, BYTES[m.b.type], m.b_stored_against_a ? t.a.stored : null],
      [t.b.decoded, 4, m.b_decoded_against_a ? t.a.decoded : null], [m.error.rule ? null : [t.error], 4, null]];
    for (const [planes, bytes, ref] of arrays) if (planes) off = decodeArray(buf, off, bytes, planes, ref, geom, t.w);
    if (m.error.rule) for (const y of rows) for (let x = x0; x < t.w; x += dx) t.errorF[y * t.w + x] = unitError(t, y * t.w + x);
  }
  if (off !== buf.length) throw new Error(`${buf.length} bytes, ${off} read`);
}

// texel_chunks.cpp encodeTexels undone: byte planes -> zig-zag unfolded -> prediction added -> reference
// added. Kept in int32 arithmetic (masks and ToInt32 wrap as the C++ unsigned arithmetic does).
function decodeArray(buf, off, bytes, planes, ref, { x0, dx, rows, cols }, width) {
  const count = cols * rows.length, mask = bytes === 4 ? -1 : (1 << (8 * bytes)) - 1;
  const prev = new Int32Array(cols), cur = new Int32Array(cols), stride = planes.length * count;
  for (let p = 0; p < planes.length; ++p) {
    prev.fill(0);
    const out = planes[p], r = ref ? ref[p] : null;
    for (let j = 0; j < rows.length; ++j) {
      const base = off + (p * rows.length + j) * cols, at0 = rows[j] * width + x0;
      let left = 0, upLeft = 0;
      for (let i = 0; i < cols; ++i) {
        const k = base + i;
        const z = bytes === 4 ? buf[k] | (buf[k + stride] << 8) | (buf[k + 2 * stride] << 16) | (buf[k + 3 * stride] << 24)
                : bytes === 2 ? buf[k] | (buf[k + stride] << 8) : buf[k];
        const up = prev[i], d = (((z >>> 1) ^ -(z & 1)) + left + up - upLeft) & mask;
        cur[i] = d, left = d, upLeft = up;
        const at = at0 + i * dx;
        out[at] = r ? (d + r[at]) & mask : d;
      }
      prev.set(cur);
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
function pixelColour(kind, v, span, exposure) {
  const n = v.length;
  if (COLOUR.includes(kind)) {
    if (v.some((c) => isNaN(c))) return [255, 0, 255];
    const k = Math.pow(2, exposure);
    return n >= 3 ? [srgb(v[0] * k), srgb(v[1] * k), srgb(v[2] * k)] : [srgb(v[0] * k), srgb(v[0] * k), srgb(v[0] * k)];
  }
  if (isNaN(v[0])) return [0, 0, 0];  // depth or position where no surface was drawn
  if (kind === 'normal') return [127.5 * (v[0] + 1), 127.5 * (v[1] + 1), 127.5 * (v[2] + 1)];
  if (['id', 'stencil', 'count'].includes(kind)) return v[0] === 0 ? [0, 0, 0] : hue(v[0]);
  const u = (k) => (v[k] - span[k][0]) / Math.max(span[k][1] - span[k][0], 1e-30);
  if (kind === 'depth') { const g = 255 * (1 - u(0)); return [g, g, g]; }  // near bright
  if (n >= 3) return [255 * u(0), 255 * u(1), 255 * u(2)];
  if (n === 2) return [255 * u(0), 255 * u(1), 0];
  return [255 * u(0), 255 * u(0), 255 * u(0)];
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

// |A-B| (the group's per-pixel error) scaled so white is the group's largest error / the multiplier.
function diffColour(t, e) {
  if (isNaN(e)) return [0, 0, 60];     // not compared (neither side drew a surface)
  if (!isFinite(e)) return [255, 0, 255];
  const top = t.meta.error.max, g = top > 0 ? 255 * Math.min(1, (e * G.mult) / top) : 0;
  return [g, g, g];
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
function flush(t) { for (const s of ['a', 'b', 'diff']) for (const l of t.images[s]) l.canvas.getContext('2d').putImageData(l.data, 0, 0); }

// The chunk's texels into every level they belong to (pass 0 to all three, passes 1, 2 to two).
function paintChunk(t, id, now = true) {
  const chunk = t.meta.chunks.find((c) => c.id === id), kind = t.meta.a.kind, sides = ['a', 'b', 'diff'];
  for (const p of chunk.passes) {
    const [x0, y0, dx, dy] = PASSES[p];
    for (let y = y0; y < t.h; y += dy) {
      if (y < chunk.rows[0] || y >= chunk.rows[1]) continue;
      for (let x = x0; x < t.w; x += dx) {
        const i = y * t.w + x, colours = [pixelColour(kind, decodedValues(t, 'a', i), t.span, G.exposure),
          pixelColour(kind, decodedValues(t, 'b', i), t.span, G.exposure), diffColour(t, t.errorF[i])];
        for (let l = 0; l < 3; ++l) {
          const f = LEVELS[l];
          if (x % f || y % f) continue;
          for (let s = 0; s < 3; ++s) {
            const level = t.images[sides[s]][l], d = level.data.data, j = 4 * ((y / f) * level.data.width + x / f), c = colours[s];
            d[j] = c[0], d[j + 1] = c[1], d[j + 2] = c[2], d[j + 3] = 255;
          }
        }
      }
    }
  }
  if (now) flush(t);
}
