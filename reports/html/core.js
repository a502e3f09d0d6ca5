// The HTML report's script, part 1: data, helpers, views, sortable tables, selection.
// Plain ES2017 in the page, no libraries; everything it draws comes from the embedded JSON.
'use strict';
const AA = (function () {
  const SELFTEST = /selftest/.test(location.hash);
  const errors = [];
  window.addEventListener('error', function (e) {
    const t = e.target;
    if (t && t.tagName === 'IMG') errors.push('image failed: ' + t.getAttribute('src'));
    else errors.push('error: ' + (e.message || e.type) + (e.filename ? ' at ' + e.lineno : ''));
  }, true);
  window.addEventListener('unhandledrejection', function (e) { errors.push('unhandled rejection: ' + e.reason); });
  const origError = console.error.bind(console);
  console.error = function () { errors.push('console.error: ' + Array.from(arguments).join(' ')); origError.apply(null, arguments); };

  const DATA = JSON.parse(document.getElementById('aalab-data').textContent);
  const META = JSON.parse(document.getElementById('aalab-meta').textContent);
  document.documentElement.classList.add('js');
  const SVGNS = 'http://www.w3.org/2000/svg';

  const scenes = DATA.scenes;
  const sceneByName = new Map(scenes.map(s => [s.name, s]));
  const rowsByScene = new Map(scenes.map(s => [s.name, []]));
  const specs = [];
  for (const r of DATA.rows) {
    if (!rowsByScene.has(r.scene)) rowsByScene.set(r.scene, []);
    rowsByScene.get(r.scene).push(r);
    if (!specs.includes(r.spec)) specs.push(r.spec);
  }
  const families = [];
  function family(spec) {
    const m = /^[a-z]+[0-9]*/i.exec(spec);
    return m ? m[0] : spec;
  }
  for (const s of specs) if (!families.includes(family(s))) families.push(family(s));
  // One colour and marker per method in every chart (reports/html_method_style.h: the colour
  // is the family's, the marker a shape of radius 1 as an SVG path), from META.method_styles.
  const FALLBACK_STYLE = { colour: '#7f7f7f', marker: 'circle', path: 'M-1,0a1,1 0 1,0 2,0a1,1 0 1,0 -2,0Z' };
  function styleOf(spec) { return (META.method_styles || {})[spec] || FALLBACK_STYLE; }
  function colour(spec) { return styleOf(spec).colour; }
  /// The method's marker centred at (x, y), radius r (an SVG path, class "mk").
  function marker(spec, x, y, r, fill) {
    const s = styleOf(spec);
    return sv('path', { class: 'mk', d: s.path, transform: 'translate(' + x.toFixed(1) + ' ' + y.toFixed(1) + ') scale(' + r + ')',
      fill: fill || s.colour, stroke: s.colour, 'vector-effect': 'non-scaling-stroke', 'data-marker': s.marker });
  }
  /// A small legend swatch: the method's marker in a 14 × 14 SVG.
  function swatch(spec) { return sv('svg', { class: 'swatch', width: '14', height: '14', viewBox: '-7 -7 14 14', 'aria-hidden': 'true' }, marker(spec, 0, 0, 5)); }

  const state = {
    metric: META.default_axis,
    metric2: META.perceptual_axis || null,  // the perceptual axis shown beside it (null: none)
    view: null,
    // The first method with an output somewhere (not one that is not applicable everywhere).
    spec: specs.find(s => s !== 'none' && DATA.rows.some(r => r.spec === s && !r.not_applicable)) || specs[0],
    compare: 'reference',
    abZoom: 0,  // 0 = auto
    cropZoom: 0,
    split: 50,
    crop: -1,  // the A/B view's crop window (-1: the whole image)
    pairA: null, pairB: 'reference',  // the two rows compared in 'two rows' mode (null A: the selected method)
    diffGain: 4,
  };

  // ---- helpers ----
  const el = AAB.el;  // abview.js, shared with the compare and sweep pages
  function sv(tag, attrs, ...kids) {
    const e = document.createElementNS(SVGNS, tag);
    for (const k in attrs || {}) {
      const v = attrs[k];
      if (v === null || v === undefined) continue;
      if (k === 'text') e.textContent = v;
      else if (k.startsWith('on')) e.addEventListener(k.slice(2), v);
      else e.setAttribute(k, v);
    }
    for (const c of kids) if (c !== null && c !== undefined) e.append(c);
    return e;
  }
  function fmtMs(v) { return v < 1 ? v.toFixed(3) : v < 100 ? v.toFixed(2) : v.toFixed(1); }
  function fmtSig(v) {
    if (v === 0) return '0';
    const a = Math.abs(v);
    return a >= 1e-4 && a < 1e6 ? String(Number(v.toPrecision(4))) : v.toExponential(3);
  }
  function isDb(name) { return /_db$/.test(name); }
  function fmtMetric(name, v) { return isDb(name) ? v.toFixed(2) : fmtSig(v); }
  /// A signed difference: '+1.23', '−0.50', '±0'.
  function signed(v, fmt) { return (v > 0 ? '+' : v < 0 ? '−' : '±') + fmt(Math.abs(v)); }
  function metricInfo(name) {
    return META.metrics[name] || { label: name, unit: '', better: 0, help: '', psnr: false };
  }
  function metricLabel(name) { const i = metricInfo(name); return i.label + (i.unit ? ' (' + i.unit + ')' : ''); }
  const imgUrl = AAB.imgUrl;
  function metricValue(row, name) {
    const v = row.metrics ? row.metrics[name] : undefined;
    return typeof v === 'number' ? v : null;
  }
  function nullReason(row, name) {
    if (!row.metrics || !(name in row.metrics)) return 'not computed';
    const why = (row.null_reasons && row.null_reasons[name]) || 'null';
    return why === 'empty mask' ? 'no edge pixels (empty edge mask)' : why;
  }

  // ---- tooltip (hover and keyboard focus) ----
  const tip = document.getElementById('tooltip');
  function showTip(text, anchor, evt) {
    tip.textContent = text;
    tip.hidden = false;
    let x, y;
    if (evt && evt.clientX !== undefined && evt.type.startsWith('mouse')) { x = evt.clientX + 14; y = evt.clientY + 14; }
    else { const r = anchor.getBoundingClientRect(); x = r.right + 8; y = r.bottom + 4; }
    const w = tip.offsetWidth, h = tip.offsetHeight;
    if (x + w > window.innerWidth - 4) x = Math.max(4, x - w - 28);
    if (y + h > window.innerHeight - 4) y = Math.max(4, y - h - 28);
    tip.style.left = x + 'px';
    tip.style.top = y + 'px';
  }
  function hideTip() { tip.hidden = true; }

  // ---- sortable tables (click or Enter/Space on the header buttons) ----
  function makeSortable(table) {
    const head = table.tHead.rows[0];
    Array.from(head.cells).forEach((th, i) => {
      const b = th.querySelector('button');
      if (b) b.addEventListener('click', () => sortTable(table, i));
    });
  }
  function sortTable(table, col) {
    const th = table.tHead.rows[0].cells[col];
    const cur = th.getAttribute('aria-sort');
    const dir = cur ? (cur === 'ascending' ? 'descending' : 'ascending') : (th.dataset.first || 'ascending');
    for (const o of table.tHead.rows[0].cells) o.removeAttribute('aria-sort');
    th.setAttribute('aria-sort', dir);
    const text = th.dataset.type === 'text';
    const body = table.tBodies[0];
    const key = r => {
      const v = r.cells[col] && r.cells[col].dataset.v;
      if (v === undefined || v === '') return null;
      return text ? v : Number(v);
    };
    const rows = Array.from(body.rows);
    rows.sort((a, b) => {
      const ka = key(a), kb = key(b);
      if (ka === null || kb === null) return ka === kb ? 0 : ka === null ? 1 : -1;  // nulls last
      const c = text ? ka.localeCompare(kb) : ka - kb;
      return dir === 'ascending' ? c : -c;
    });
    for (const r of rows) body.appendChild(r);
  }

  // ---- views (Suite / one scene at a time) ----
  const hooks = { render: [], leave: [], select: [] };
  function viewFromHash() {
    let h = location.hash.slice(1);
    try { h = decodeURIComponent(h); } catch (e) { return null; }
    if (h === 'suite') return h;
    if (h.startsWith('scene-') && sceneByName.has(h.slice(6))) return h;
    return null;
  }
  function sectionOf(view) {
    return Array.from(document.querySelectorAll('section.view')).find(s => s.dataset.view === view) || null;
  }
  function showView(view) {
    const sec = sectionOf(view);
    if (!sec) return;
    if (state.view && state.view !== view) {
      const old = sectionOf(state.view);
      if (old) { old.classList.remove('active'); for (const f of hooks.leave) f(old); }
    }
    state.view = view;
    sec.classList.add('active');
    for (const a of document.querySelectorAll('nav.views a')) {
      if (a.dataset.view === view) a.setAttribute('aria-current', 'page'); else a.removeAttribute('aria-current');
    }
    for (const f of hooks.render) f(sec);
  }
  function goScene(name) {
    history.replaceState(null, '', '#scene-' + encodeURIComponent(name));
    showView('scene-' + name);
  }
  function select(spec) {
    state.spec = spec;
    for (const f of hooks.select) f(spec);
  }
  hooks.select.push(spec => {
    for (const tr of document.querySelectorAll('table.metrics tr.row')) tr.classList.toggle('selected', tr.dataset.spec === spec);
  });

  function init() {
    for (const t of document.querySelectorAll('table.sortable')) makeSortable(t);
    for (const tr of document.querySelectorAll('table.metrics tr.row')) {
      tr.addEventListener('click', e => { if (!e.target.closest('a,button')) select(tr.dataset.spec); });
    }
    window.addEventListener('hashchange', () => { const v = viewFromHash(); if (v) showView(v); });
    showView(viewFromHash() || 'suite');
    select(state.spec);
    if (/pairtest/.test(location.hash)) {  // tests/reports/html_browser_test: any two rows side by side
      if (document.readyState === 'complete') setTimeout(() => AA.pairTest(), 0);
      else window.addEventListener('load', () => setTimeout(() => AA.pairTest(), 0));
    }
    if (SELFTEST) {
      if (document.readyState === 'complete') setTimeout(() => AA.selfTest(), 0);
      else window.addEventListener('load', () => setTimeout(() => AA.selfTest(), 0));
    }
  }

  return { DATA, META, state, scenes, sceneByName, rowsByScene, specs, families, colour, styleOf, marker, swatch, family, el, sv,
           fmtMs, fmtSig, fmtMetric, signed, metricInfo, metricLabel, imgUrl, metricValue, nullReason,
           showTip, hideTip, makeSortable, sortTable, hooks, showView, sectionOf, goScene, select, init, errors,
           SELFTEST };
})();
