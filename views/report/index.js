// gblens compare --pairs: the index page (views/report/page.html inlines it after page.js, whose
// gblensReport calls indexPage). One row per pair with thumbnails of A and of the worst |A-B|, coloured
// by verdict, sorted by a clicked column header, filtered by name/path text and by result.
'use strict';

function indexPage(page, pairs) {
  // Self-contained (its own element helper): page.js's helpers are not an interface of this file.
  const make = (tag, attrs, ...children) => {
    const e = document.createElement(tag);
    for (const [k, v] of Object.entries(attrs || {})) {
      if (k === 'class') e.className = v; else if (k === 'data') Object.assign(e.dataset, v);
      else if (k.startsWith('on')) e.addEventListener(k.slice(2), v); else e.setAttribute(k, v);
    }
    for (const c of children) if (c !== null && c !== undefined) e.append(c instanceof Node ? c : String(c));
    return e;
  };
  const num = (v) => (typeof v === 'number' ? String(Number(v.toPrecision(4))) : String(v));
  // Most severe first when sorted by result (ascending): what a reviewer must look at first.
  const SEVERITY = { 'file error': 4, fail: 3, mismatch: 2, warn: 1, pass: 0 };
  const cls = (result) => result.replace(' ', '');
  // The group the diff thumbnail shows (thumbnail.cpp picks it the same way).
  const worstGroup = (p) => p.groups.find((g) => g.result === 'fail') || p.groups.find((g) => g.result === 'warn') || p.groups[0];

  const worstExit = pairs.reduce((w, p) => Math.max(w, p.exit_code), 0);
  page.append(make('h1', {}, `gblens compare: ${pairs.length} pairs, worst exit ${worstExit}`));

  // ---- rows, built once; sorting re-orders them and filtering hides them ----
  const rows = pairs.map((p, order) => {
    const bad = p.groups.filter((g) => g.result !== 'pass').map((g) => g.key).concat(p.mismatches.map((m) => m.target));
    const thumbs = p.thumbnails || {};
    const thumb = (src, what) => make('td', { class: 'thumb' },
      src ? make(p.page ? 'a' : 'span', p.page ? { href: p.page } : {}, make('img', { src, alt: `${what} of ${p.name}`, data: { thumb: what } })) : '');
    const w = worstGroup(p);
    const tr = make('tr', { class: 'verdict-' + cls(p.result), data: { key: p.name } },
      thumb(thumbs.a, 'a'), thumb(thumbs.diff, 'diff'),
      make('td', { data: { field: 'name' } }, p.page ? make('a', { href: p.page }, p.name) : p.name),
      make('td', { class: cls(p.result), data: { field: 'result' } }, p.result.toUpperCase()),
      make('td', { class: 'mono', data: { field: 'a' } }, p.a), make('td', { class: 'mono', data: { field: 'b' } }, p.b),
      make('td', { data: { field: 'bad' } }, p.error || bad.join(', ')),
      make('td', { class: 'mono', data: { field: 'worst' } }, w ? `${w.key}: max ${num(w.max_error)}` : ''));
    return { p, order, tr };
  });

  // ---- sorting: a header click sorts ascending, a second click on it descending ----
  const COLUMNS = [
    { title: 'thumbnail A' }, { title: '|A\u2212B| (worst)' },
    { title: 'pair', key: (r) => r.p.name },
    { title: 'result', key: (r) => -SEVERITY[r.p.result] },  // ascending: most severe first
    { title: 'A', key: (r) => r.p.a }, { title: 'B', key: (r) => r.p.b },
    { title: 'not passing' }, { title: 'worst figure' }];
  const sort = { column: -1, direction: 1 };
  const compare = (x, y) => (typeof x === 'number' ? x - y : x.localeCompare(y, undefined, { numeric: true }));
  const head = make('tr');
  COLUMNS.forEach((c, i) => {
    const th = make('th', c.key ? { class: 'sortable', data: { column: String(i) }, title: 'sort by ' + c.title } : {}, c.title);
    if (c.key) th.addEventListener('click', () => {
      sort.direction = sort.column === i ? -sort.direction : 1;
      sort.column = i;
      order();
    });
    head.append(th);
  });
  const body = make('tbody');
  const table = make('table', { id: 'pairs' }, make('thead', {}, head), body);

  function order() {
    const c = COLUMNS[sort.column];
    // Array.sort is stable: equal keys keep the list's order (in either direction).
    const sorted = c ? rows.slice().sort((x, y) => sort.direction * compare(c.key(x), c.key(y)) || x.order - y.order) : rows;
    for (const r of sorted) body.append(r.tr);
    head.querySelectorAll('th').forEach((th, i) => {
      th.textContent = COLUMNS[i].title + (i === sort.column ? (sort.direction > 0 ? ' \u25b2' : ' \u25bc') : '');
    });
  }

  // ---- filtering: name/path text and one checkbox per result present ----
  const text = make('input', { id: 'filter', type: 'search', placeholder: 'filter by pair or path (/)', size: '32' });
  const results = Object.keys(SEVERITY).filter((res) => pairs.some((p) => p.result === res));
  const boxes = {};
  const checks = results.map((res) => {
    boxes[res] = make('input', { type: 'checkbox', id: 'show-' + cls(res), checked: '' });
    boxes[res].addEventListener('change', filter);
    return make('label', { class: cls(res) }, boxes[res], ' ' + res);
  });
  const count = make('span', { id: 'count' });
  text.addEventListener('input', filter);

  function filter() {
    const needle = text.value.trim().toLowerCase();
    let shown = 0;
    for (const r of rows) {
      const hit = !needle || [r.p.name, r.p.a, r.p.b].some((s) => s.toLowerCase().includes(needle));
      r.tr.hidden = !(hit && boxes[r.p.result].checked);
      shown += r.tr.hidden ? 0 : 1;
    }
    count.textContent = `${shown} of ${rows.length} pairs shown`;
  }

  // '/' focuses the filter box (as many sites do), unless one is typing in it already.
  document.addEventListener('keydown', (e) => {
    if (e.key === '/' && document.activeElement !== text) {
      e.preventDefault();
      text.focus();
    }
  });

  page.append(make('div', { id: 'controls' }, text, ...checks, count), table);
  order();
  filter();
}
