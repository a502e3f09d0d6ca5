// The HTML report's script, part 3: the gallery (the A/B comparison of abview.js against the
// reference, `none` or any two rows of the scene: `f` flips, 1–9 zoom to a crop window, pixel
// readout, |A − B|), zoomed crops of every method, heatmaps (one method, or several on one
// colour bar), edge mask, debug views; arrow-key navigation), the self-test behind
// `#selftest`, the two-rows test behind `#pairtest`, and the start-up call.
(function () {
  const A = AA, el = A.el, state = A.state;
  let G = null;  // the one gallery that exists: { host, scene, specs, parts }

  function rowOf(sceneName, spec) { return (A.rowsByScene.get(sceneName) || []).find(r => r.spec === spec) || null; }
  function outputOf(sceneName, spec) { const r = rowOf(sceneName, spec); return r && r.images ? r.images.output || null : null; }
  function autoCropZoom(scene) {
    const w = Math.max(1, ...scene.crops.map(c => c[2]));
    return Math.max(4, Math.min(8, Math.round(128 / w)));
  }
  function fileLink(path, label) { return el('a', { href: A.imgUrl(path) }, label); }
  function roleLabel(role) { const s = role.replace(/^debug_/, '').replace(/_/g, ' '); return s.charAt(0).toUpperCase() + s.slice(1); }

  function zoomSelect(label, values, current, onchange) {
    return el('label', {}, label + ' ', el('select', { onchange: e => onchange(Number(e.target.value)) },
      ...values.map(v => el('option', { value: v, selected: v === current }, v === 0 ? 'auto' : '×' + v))));
  }

  function build(host) {
    const scene = A.sceneByName.get(host.dataset.scene);
    const specs = (A.rowsByScene.get(scene.name) || []).map(r => r.spec);
    if (!specs.length) { host.replaceChildren(el('p', { class: 'note', text: 'No rows for this scene.' })); return; }
    const applicable = s => { const r = rowOf(scene.name, s); return r && !r.not_applicable; };
    // Open on a method that has an output on this scene (never a not-applicable row).
    if (!applicable(state.spec)) state.spec = specs.find(s => s !== 'none' && applicable(s)) || specs[0];
    const idx = A.scenes.indexOf(scene), n = A.scenes.length;
    if (!G || G.scene !== scene) state.crop = -1;  // a new scene opens on its whole image
    const g = el('div', { class: 'gallery', tabindex: '0', role: 'region',
      'aria-label': 'Gallery of ' + scene.name + '. Left and right arrows switch methods, up and down switch scenes.' });
    const hasNone = specs.includes('none');
    const cmp = v => el('label', {}, el('input', { type: 'radio', name: 'cmp-' + idx, value: v, checked: state.compare === v,
      disabled: v === 'none' && !hasNone, onchange: () => { state.compare = v; renderAB(); } }), ' ' + v);
    g.append(el('div', { class: 'bar' },
      el('span', {}, 'Scene ', el('b', { text: scene.name }), ' (' + (idx + 1) + '/' + n + ') ',
        el('button', { type: 'button', disabled: idx === 0, title: 'previous scene (↑)', onclick: () => moveScene(-1, false) }, '↑'),
        el('button', { type: 'button', disabled: idx === n - 1, title: 'next scene (↓)', onclick: () => moveScene(1, false) }, '↓')),
      el('span', {}, 'Compare with ', cmp('reference'), ' ', cmp('none'), ' ', cmp('two rows')),
      zoomSelect('A/B zoom', [0, 1, 2, 4, 8], state.abZoom, v => { state.abZoom = v; renderAB(); }),
      zoomSelect('Crop zoom', [0, 4, 6, 8], state.cropZoom, v => { state.cropZoom = v; renderCrops(); }),
      el('span', { class: 'hint', text: 'Click here, then ←/→ method, ↑/↓ scene, f flips A and B, 1–9 zoom to a crop window, 0 the whole image. Every image opens its file.' })));
    const methods = el('div', { class: 'methods', role: 'group', 'aria-label': 'Methods' },
      ...specs.map(s => el('button', { type: 'button', 'data-spec': s, 'aria-pressed': String(s === state.spec), onclick: () => A.select(s) }, s)));
    const parts = { summary: el('div', { class: 'summary' }), ab: el('div', { class: 'abview' }), links: el('p', { class: 'links' }),
      crops: el('div', { class: 'crops' }), maps: el('div', { class: 'figs' }), heat: el('div', { class: 'heat-panel' }), debug: el('div', { class: 'figs debug' }) };
    g.append(methods, parts.summary, parts.ab, parts.links,
      el('h4', { text: 'Zoomed crops — where none is furthest from the reference on edges (reference first)' }), parts.crops,
      el('h4', { text: 'Error maps and edge mask' }), parts.maps,
      el('h4', { text: 'Error maps of several methods — one scale, one colour bar' }), parts.heat,
      el('h4', { text: 'Debug views' }), parts.debug);
    g.addEventListener('keydown', onKey);
    host.replaceChildren(g);
    G = { host, scene, specs, parts, methods, g };
    renderCrops();
    renderSelected();
  }

  function onKey(e) {
    if (e.altKey || e.ctrlKey || e.metaKey || e.shiftKey) return;
    if (AAB.onKey(ctl(), e)) { e.preventDefault(); return; }  // f flips, 1–9 / 0 zoom
    if (e.target.closest && e.target.closest('input, select, textarea')) return;  // the slider and selects keep their arrows
    if (e.key === 'ArrowLeft' || e.key === 'ArrowRight') {
      const i = G.specs.indexOf(state.spec), d = e.key === 'ArrowLeft' ? -1 : 1;
      A.select(G.specs[(i + d + G.specs.length) % G.specs.length]);
      e.preventDefault();
    } else if (e.key === 'ArrowUp' || e.key === 'ArrowDown') {
      moveScene(e.key === 'ArrowUp' ? -1 : 1, true);
      e.preventDefault();
    }
  }

  function moveScene(d, focus) {
    const i = A.scenes.indexOf(G.scene) + d;
    if (i < 0 || i >= A.scenes.length) return;
    A.goScene(A.scenes[i].name);
    if (focus && G) G.g.focus();
  }

  function renderSelected() {
    if (!G) return;
    for (const b of G.methods.querySelectorAll('button')) b.setAttribute('aria-pressed', String(b.dataset.spec === state.spec));
    for (const c of G.parts.crops.querySelectorAll('.crop-cell')) c.classList.toggle('selected', c.dataset.spec === state.spec);
    renderSummary();
    renderAB();
    renderMaps();
  }

  function renderSummary() {
    const r = rowOf(G.scene.name, state.spec), s = G.scene;
    if (r.not_applicable) {
      G.parts.summary.replaceChildren(el('b', { class: 'method', text: r.spec }), ': not applicable — ' + r.not_applicable);
      return;
    }
    const bits = [];
    for (const name of Object.keys(r.metrics || {})) {
      const v = A.metricValue(r, name), i = A.metricInfo(name);
      bits.push(i.label + ' ' + (v === null ? '— (' + A.nullReason(r, name) + ')' : A.fmtMetric(name, v) + (i.unit ? ' ' + i.unit : '')));
    }
    const t = r.timing.total;
    if (r.supplied) bits.push('supplied by your pipeline, not run by aalab');
    bits.push('time ' + A.fmtMs(t.median_ms) + ' ms [' + A.fmtMs(t.min_ms) + '–' + A.fmtMs(t.max_ms) + ']');
    if (r.render_size && (r.render_size[0] !== s.width || r.render_size[1] !== s.height)) bits.push('rendered at ' + r.render_size[0] + '×' + r.render_size[1]);
    G.parts.summary.replaceChildren(el('b', { class: 'method', text: r.spec }), ': ' + bits.join(' · '));
  }

  // The images a pair selection names: a row's output or the scene's reference.
  function pairImage(s, key) {
    if (key === 'reference') return { path: s.images.reference_png, name: s.kind === 'image' ? 'reference (the user\'s)' : 'reference (' + s.reference.spp + ' spp)' };
    return { path: outputOf(s.name, key), name: key };
  }
  function pairChoices(s) { return ['reference'].concat(G.specs.filter(x => outputOf(s.name, x))); }
  function ctl() { return G && G.parts.ab._ab; }

  // The comparison itself (slider, flip, crop zoom, pixel readout, |A − B|) is abview.js's,
  // shared with the compare and sweep pages; state.split, diffGain, crop, pairA and pairB are its state.
  function renderAB() {
    if (!G) return;
    const s = G.scene;
    const o = { width: s.width, height: s.height, crops: s.crops, state, zoom: state.abZoom };
    let aPath, aName;
    if (state.compare === 'two rows') {
      const keys = pairChoices(s);
      if (state.pairA === null || !keys.includes(state.pairA)) state.pairA = keys.includes(state.spec) ? state.spec : keys[0];
      if (!keys.includes(state.pairB)) state.pairB = 'reference';
      o.choices = keys.map(k => ({ key: k, label: k, path: pairImage(s, k).path }));
      aPath = pairImage(s, state.pairA).path;
      aName = state.pairA;
    } else {
      o.a = { path: outputOf(s.name, state.spec), name: state.spec };
      o.b = state.compare === 'none' && outputOf(s.name, 'none') ? pairImage(s, 'none') : pairImage(s, 'reference');
      aPath = o.a.path;
      aName = state.spec;
    }
    const c = AAB.view(G.parts.ab, o);
    if (!c.setSplit) { G.parts.links.replaceChildren(); return; }
    const links = ['Files: ', fileLink(aPath, aName + (aPath === s.images.reference_png ? '' : ' output')), ' · ', fileLink(s.images.reference_png, 'reference PNG')];
    if (s.images.reference_exr) links.push(' · ', fileLink(s.images.reference_exr, 'reference EXR'), ' (display-linear float)');
    if (outputOf(s.name, 'none')) links.push(' · ', fileLink(outputOf(s.name, 'none'), 'none'));
    links.push(' · ', el('a', { href: 'report.json' }, 'report.json'));
    G.parts.links.replaceChildren(...links);
  }

  function renderCrops() {
    if (!G) return;
    const s = G.scene, W = s.width, H = s.height, box = G.parts.crops;
    box.replaceChildren();
    if (!s.crops.length) { box.append(el('p', { class: 'note', text: 'No crop windows: none has no edge error against the reference here.' })); return; }
    const z = state.cropZoom || autoCropZoom(s);
    const items = [{ label: 'reference', path: s.images.reference_png, spec: '' }]
      .concat(G.specs.map(sp => ({ label: sp, path: outputOf(s.name, sp), spec: sp })));
    s.crops.forEach((c, k) => {
      const strip = el('div', { class: 'crop-strip' });
      for (const it of items) {
        if (!it.path) continue;
        const cell = el('div', { class: 'crop-cell' + (it.spec && it.spec === state.spec ? ' selected' : ''), 'data-spec': it.spec, style: 'width:' + c[2] * z + 'px' },
          el('a', { class: 'crop', href: A.imgUrl(it.path), title: it.label + ' — crop ' + (k + 1) + ' (click opens the full image)',
            style: 'width:' + c[2] * z + 'px;height:' + c[3] * z + 'px' },
            el('img', { src: A.imgUrl(it.path), loading: 'lazy', alt: it.label + ', crop ' + (k + 1), width: W * z, height: H * z,
              style: 'left:' + -c[0] * z + 'px;top:' + -c[1] * z + 'px;width:' + W * z + 'px;height:' + H * z + 'px' })),
          it.spec ? el('button', { type: 'button', title: 'select ' + it.spec, onclick: () => A.select(it.spec) }, it.label)
                  : el('span', { class: 'hint', text: 'reference' }));
        strip.append(cell);
      }
      box.append(el('div', {}, el('div', { class: 'hint', text: 'Crop ' + (k + 1) + ': x ' + c[0] + ', y ' + c[1] + ', ' + c[2] + '×' + c[3] + ' px, ×' + z + ' nearest neighbour' }), strip));
    });
  }

  function figure(path, caption, W, H, pixelated) {
    return el('figure', {}, el('a', { href: A.imgUrl(path) },
      el('img', { src: A.imgUrl(path), loading: 'lazy', alt: caption, width: W, height: H, class: pixelated ? 'pixelated' : null })),
      el('figcaption', { text: caption }));
  }

  /// The page colours its heatmaps itself (SVG filters, applied with CSS): the absolute-error
  /// map is |output − reference| of the two PNGs (a `difference` blend), mean over RGB, full
  /// scale META.error_heatmap_max, through viridis; the FLIP map is stored as 8-bit grey and
  /// goes through magma. Tables are the colormaps of metrics/heatmap.cpp (META.colormaps).
  function ensureFilters() {
    if (document.getElementById('aalab-filters')) return;
    document.body.append(A.sv('svg', { id: 'aalab-filters', width: '0', height: '0', 'aria-hidden': 'true',
      style: 'position:absolute;width:0;height:0;overflow:hidden' },
      A.sv('filter', { id: 'aalab-magma', 'color-interpolation-filters': 'sRGB' }, A.sv('feComponentTransfer', {}, ...lut('magma')))));
    absErrorFilter(A.META.error_heatmap_max, 'aalab-abs-error');
  }
  function lut(name) {
    return ['R', 'G', 'B'].map((c, i) => A.sv('feFunc' + c, { type: 'table',
      tableValues: A.META.colormaps[name].map(e => (e[i] / 255).toFixed(4)).join(' ') }));
  }
  /// The id of the SVG filter that maps |output − reference| (mean over RGB) 0 → `full` onto
  /// viridis (made once per full scale).
  function absErrorFilter(full, id) {
    id = id || 'aalab-abs-error-' + String(full).replace(/[^0-9]/g, '_');
    if (document.getElementById(id)) return id;
    const k = (1 / (3 * full)).toFixed(6), row = k + ' ' + k + ' ' + k + ' 0 0 ';
    document.getElementById('aalab-filters').append(A.sv('filter', { id, 'color-interpolation-filters': 'sRGB', 'data-full': String(full) },
      A.sv('feColorMatrix', { type: 'matrix', values: row + row + row + '0 0 0 1 0' }),
      A.sv('feComponentTransfer', {}, ...lut('viridis'))));
    return id;
  }
  /// A heatmap drawn by the page: `layers` (image paths) stacked, each later one blended with
  /// `difference`, the stack through the SVG filter `filter`; clicking opens `link`.
  function heatFigure(layers, filter, link, caption, W, H) {
    ensureFilters();
    const stack = el('div', { class: 'heat', style: 'aspect-ratio:' + W + '/' + H + ';width:' + W + 'px;max-width:100%;filter:url(#' + filter + ')' },
      ...layers.map((p, i) => el('img', { src: A.imgUrl(p), loading: 'lazy', alt: i ? caption : '', width: W, height: H, class: i ? 'diff' : null })));
    return el('figure', {}, el('a', { href: A.imgUrl(link), title: 'opens ' + link }, stack), el('figcaption', { text: caption }));
  }

  /// Heatmaps of several methods on one scale: |output − reference| of each picked method
  /// through the same filter (0 → full scale), and one colour bar that states the scale.
  const HEAT_SCALES = [1, 0.5, 0.25, 0.125, 0.0625, 0.03125];
  function renderHeatmaps() {
    const s = G.scene, box = G.parts.heat;
    const outputs = G.specs.filter(sp => outputOf(s.name, sp));
    if (!outputs.length || !s.images.reference_png) { box.replaceChildren(el('p', { class: 'note', text: 'No outputs to map on this scene.' })); return; }
    if (!state.heatSpecs) state.heatSpecs = outputs.filter(sp => sp !== 'none').slice(0, 4);
    const picked = outputs.filter(sp => state.heatSpecs.includes(sp));
    const full = state.heatScale || A.META.error_heatmap_max;
    ensureFilters();
    const filter = absErrorFilter(full);
    const picks = el('div', { class: 'heat-picks', role: 'group', 'aria-label': 'methods to map' }, 'Methods: ',
      ...outputs.map(sp => el('label', { title: sp }, el('input', { type: 'checkbox', value: sp, checked: picked.includes(sp),
        onchange: e => { state.heatSpecs = e.target.checked ? state.heatSpecs.concat([sp]) : state.heatSpecs.filter(x => x !== sp); renderHeatmaps(); } }), ' ' + sp)));
    const scale = el('label', {}, 'full scale ', el('select', { class: 'heat-scale', 'aria-label': 'shared full scale',
      onchange: e => { state.heatScale = Number(e.target.value); renderHeatmaps(); } },
      ...HEAT_SCALES.map(v => el('option', { value: v, selected: v === full }, String(v)))));
    // Side by side in about 960 px, small frames magnified by a whole factor (nearest neighbour).
    const W = s.width, H = s.height, z = Math.max(1, Math.floor(Math.max(160, 960 / Math.max(1, picked.length)) / W));
    const figs = picked.map(sp => {
      const f = heatFigure([s.images.reference_png, outputOf(s.name, sp)], filter, outputOf(s.name, sp), sp, W, H);
      f.querySelector('.heat').style.width = W * z + 'px';
      f.dataset.spec = sp;
      return f;
    });
    box.replaceChildren(el('div', { class: 'bar' }, picks, scale), colourBar(full),
      figs.length ? el('div', { class: 'figs heat-row', 'data-filter': filter }, ...figs) : el('p', { class: 'note', text: 'Pick methods above.' }));
  }
  /// The viridis colour bar from 0 to `full` (sRGB-encoded units, mean over RGB), ticks at quarters.
  function colourBar(full) {
    const map = A.META.colormaps.viridis, Wb = 320, Hb = 14, L = 10;
    const id = 'aalab-bar-' + String(full).replace(/[^0-9]/g, '_');
    const stops = [];
    for (let i = 0; i <= 16; i++) {
      const e = map[Math.min(map.length - 1, Math.round(i / 16 * (map.length - 1)))];
      stops.push(A.sv('stop', { offset: (i / 16).toFixed(4), 'stop-color': 'rgb(' + e[0] + ',' + e[1] + ',' + e[2] + ')' }));
    }
    const ticks = [0, 0.25, 0.5, 0.75, 1].map(t => A.sv('g', {},
      A.sv('line', { x1: L + t * Wb, x2: L + t * Wb, y1: Hb + 2, y2: Hb + 6, stroke: 'currentColor' }),
      A.sv('text', { x: L + t * Wb, y: Hb + 18, 'text-anchor': 'middle', 'font-size': '11', fill: 'currentColor',
        text: (t === 1 ? '≥ ' : '') + A.fmtSig(t * full) })));
    return el('figure', { class: 'colour-bar', 'data-min': '0', 'data-max': String(full) },
      A.sv('svg', { width: String(Wb + 2 * L), height: String(Hb + 24), viewBox: '0 0 ' + (Wb + 2 * L) + ' ' + (Hb + 24), role: 'img',
        'aria-label': 'colour bar: 0 to ' + full },
        A.sv('defs', {}, A.sv('linearGradient', { id }, ...stops)),
        A.sv('rect', { x: L, y: 0, width: Wb, height: Hb, fill: 'url(#' + id + ')' }), ...ticks),
      el('figcaption', { text: 'One scale for every map here: |output − reference|, mean over RGB, sRGB-encoded units, 0 → ' +
        full + ' (viridis; larger errors saturate).' }));
  }

  function renderMaps() {
    const s = G.scene, r = rowOf(s.name, state.spec), images = (r && r.images) || {};
    const figs = [];
    if (images.output && s.images.reference_png) {
      figs.push(heatFigure([s.images.reference_png, images.output], 'aalab-abs-error', images.output,
        'Absolute error |output − reference| (mean over RGB; viridis, 0 → ≥ ' + A.META.error_heatmap_max + ' sRGB-encoded units) — ' + r.spec, s.width, s.height));
    }
    if (images.flip_map) {
      figs.push(heatFigure([images.flip_map], 'aalab-magma', images.flip_map, 'LDR-FLIP map (magma, 0 → 1) — ' + r.spec, s.width, s.height));
    }
    if (s.images.edge_mask) figs.push(figure(s.images.edge_mask, 'Edge mask (white = edge; ' + (100 * s.edge_pixel_fraction).toFixed(1) + '% of pixels; ' + (s.edge_mask_source || 'geometric') + ')', s.width, s.height, false));
    if (!figs.length || !r) figs.unshift(el('p', { class: 'note', text: 'No error heatmaps for ' + state.spec + ' in this report.' }));
    G.parts.maps.replaceChildren(...figs);
    renderHeatmaps();
    const dbg = Object.keys(images).filter(k => k.startsWith('debug_'));
    if (dbg.length) G.parts.debug.replaceChildren(...dbg.map(k => figure(images[k], roleLabel(k) + ' — ' + r.spec, s.width, s.height, true)));
    else G.parts.debug.replaceChildren(el('p', { class: 'note', text: A.DATA.settings.debug_views === 'true'
      ? state.spec + ' has no debug views.' : 'Debug views were not saved in this run (aalab run --debug-views saves the FXAA ones).' }));
  }

  A.hooks.render.push(sec => { for (const host of sec.querySelectorAll('.gallery-host')) if (!G || G.host !== host) build(host); });
  A.hooks.leave.push(sec => {
    for (const host of sec.querySelectorAll('.gallery-host')) {
      if (G && G.host === host) { host.replaceChildren(); G = null; }  // one gallery in the DOM at a time
    }
  });
  A.hooks.select.push(() => renderSelected());

  // ---- the two-rows test (only with #pairtest in the URL): used by tests/reports/html_browser_test ----
  // On the first scene with three outputs: A = B (difference blank), then A ≠ B (not blank),
  // then `f` twice (all of A, then all of B). Writes one line of facts into <pre id="pairtest">.
  A.pairTest = async function () {
    const out = [];
    const wait = async cond => { for (let i = 0; i < 200 && !cond(); i++) await new Promise(r => setTimeout(r, 25)); return cond(); };
    try {
      const s = A.scenes.find(x => (A.rowsByScene.get(x.name) || []).filter(r => r.images && r.images.output).length >= 3);
      if (!s) throw new Error('no scene with three outputs');
      A.goScene(s.name);
      const sec = A.sectionOf('scene-' + s.name), g = sec.querySelector('.gallery');
      sec.querySelector('.gallery .bar input[value="two rows"]').click();
      const specs = (A.rowsByScene.get(s.name) || []).filter(r => r.images && r.images.output && r.spec !== 'none').map(r => r.spec);
      const choose = async (a, b) => {
        for (const [cls, v] of [['pair-a', a], ['pair-b', b]]) {
          const sel = g.querySelector('select.' + cls);
          sel.value = v;
          sel.dispatchEvent(new Event('change', { bubbles: true }));
        }
        await wait(() => { const c = g.querySelector('canvas.diff'); return c && c.dataset.done; });
        return g.querySelector('canvas.diff');
      };
      const options = Array.from(g.querySelector('select.pair-a').options).map(o => o.value);
      let c = await choose(specs[0], specs[0]);
      out.push('options=' + options.join(','), 'same=' + specs[0] + ':' + c.dataset.differing);
      c = await choose(specs[0], specs[1]);
      out.push('pair=' + specs[0] + ':' + specs[1] + ':' + c.dataset.differing + ':' + c.dataset.max);
      const ab = () => g.querySelector('.ab');
      out.push('before=' + ab().dataset.shown);
      for (let k = 0; k < 2; k++) {
        g.dispatchEvent(new KeyboardEvent('keydown', { key: 'f', bubbles: true }));
        out.push('f' + (k + 1) + '=' + ab().dataset.shown + ':' + ab().dataset.shownSrc);
      }
      c = await choose('reference', specs[1]);
      out.push('ref=' + c.dataset.differing);
      c = await choose(specs[1], specs[0]);
      ctl().setSplit(50);
      // Several methods' heatmaps on one colour bar: every output picked, full scale 0.0625.
      const hp = g.querySelector('.heat-panel');
      for (let cb; (cb = Array.from(hp.querySelectorAll('input[type=checkbox]')).find(x => !x.checked));) cb.click();
      const scale = hp.querySelector('select.heat-scale');
      scale.value = '0.0625';
      scale.dispatchEvent(new Event('change', { bubbles: true }));
      const stacks = Array.from(hp.querySelectorAll('.heat-row .heat')), used = new Set(stacks.map(d => d.style.filter));
      const fid = hp.querySelector('.heat-row').dataset.filter, fm = document.getElementById(fid).querySelector('feColorMatrix');
      const bar = hp.querySelector('.colour-bar'), ticks = Array.from(bar.querySelectorAll('text')).map(t => t.textContent);
      out.push('heat=' + stacks.length + ':' + used.size + ':' + fm.getAttribute('values').split(' ')[0] + ':' + bar.dataset.max + ':' +
        ticks[0] + '..' + ticks[ticks.length - 1].replace(/[^0-9.]/g, '') + ':' +
        Array.from(hp.querySelectorAll('.heat-row figure')).map(f => f.dataset.spec).join(','));
      // Crop zoom and the pixel readout (abview.js's own exercise, on the same two rows).
      const more = await AAB.exercise(G.parts.ab, specs[0], specs[1]);
      out.push(...more.filter(f => /^(zoom|px|exception)/.test(f)));
      out.push('errors=' + A.errors.length);
    } catch (e) {
      out.push('exception=' + (e && e.message || e));
    }
    document.body.prepend(el('pre', { id: 'pairtest', text: out.join(' ') }));
  };

  // ---- self-test (only with #selftest in the URL): used by tests/reports/html_browser_test ----
  A.selfTest = async function () {
    const problems = [];
    let rows = 0, points = 0, galleries = 0;
    const srcs = new Set();
    const addSrc = p => { if (p && !/\.exr$/i.test(p)) srcs.add(A.imgUrl(p)); };
    try {
      for (const s of A.scenes) {
        A.goScene(s.name);
        const sec = A.sectionOf('scene-' + s.name);
        if (!sec || !sec.classList.contains('active')) { problems.push('scene view not shown: ' + s.name); continue; }
        for (const p of Object.values(s.images || {})) addSrc(p);
        for (const r of A.rowsByScene.get(s.name) || []) {
          for (const p of Object.values(r.images || {})) addSrc(p);
          if (Array.from(sec.querySelectorAll('table.metrics tr.row')).some(t => t.dataset.spec === r.spec && t.dataset.scene === s.name)) rows++;
          else problems.push('no table row: ' + s.name + ' × ' + r.spec);
          const unp = sec.querySelector('.qc .unplotted');
          if (Array.from(sec.querySelectorAll('.qc .pt')).some(g => g.dataset.spec === r.spec) || (unp && unp.textContent.includes(r.spec))) points++;
          else if (A.state.metric) problems.push('not in the chart: ' + s.name + ' × ' + r.spec);
          const btn = Array.from(sec.querySelectorAll('.gallery .methods button')).find(b => b.dataset.spec === r.spec);
          if (btn) { btn.click(); galleries++; } else problems.push('not in the gallery: ' + s.name + ' × ' + r.spec);
        }
        const g = sec.querySelector('.gallery'), before = A.state.spec;
        if (g) g.dispatchEvent(new KeyboardEvent('keydown', { key: 'ArrowRight', bubbles: true }));
        if ((A.rowsByScene.get(s.name) || []).length > 1 && A.state.spec === before) problems.push('ArrowRight did not switch the method on ' + s.name);
      }
      if (A.scenes.length > 1) {  // ArrowUp in the last scene's gallery goes to the one before
        const g = document.querySelector('section.view.active .gallery');
        if (g) g.dispatchEvent(new KeyboardEvent('keydown', { key: 'ArrowUp', bubbles: true }));
        if (A.state.view !== 'scene-' + A.scenes[A.scenes.length - 2].name) problems.push('ArrowUp did not switch the scene');
      }
      A.showView('suite');
      // The first screen shows a perceptual axis beside the default one (FLIP, or the
      // perceptual temporal error in a motion run), with what each axis rewards.
      if (A.META.perceptual_axis && A.state.metric !== A.META.perceptual_axis) {
        const sec = A.sectionOf('suite');
        if (!sec.querySelector('.qc .chart-box.perceptual svg, .qc .chart-box.perceptual .note')) problems.push('no perceptual axis beside the quality axis on the suite view');
        if (!sec.querySelector('table.cost th.perceptual')) problems.push('no perceptual column in the cost-of-accuracy table');
      }
      const def = A.state.metric;
      for (const m of A.META.axis) A.setMetric(m);
      A.setMetric(def);
      const pt = document.querySelector('section.view.active .qc .pt');
      if (pt) {  // keyboard focus on a point shows its numbers
        pt.focus();
        const t = document.getElementById('tooltip');
        if (t.hidden || !t.textContent.includes(pt.dataset.spec)) problems.push('focusing a chart point shows no tooltip');
        pt.blur();
      }
      const table = document.querySelector('table.metrics');
      if (table && table.tHead.rows[0].cells.length > 1) {  // sorting by the first numeric column
        table.tHead.rows[0].cells[1].querySelector('button').click();
        const th = table.tHead.rows[0].cells[1], desc = th.getAttribute('aria-sort') === 'descending';
        const keys = Array.from(table.tBodies[0].rows).map(r => r.cells[1].dataset.v).filter(v => v !== undefined).map(Number);
        if (!th.getAttribute('aria-sort') || keys.some((v, i) => i > 0 && (desc ? v > keys[i - 1] : v < keys[i - 1]))) problems.push('sorting a table failed');
      }
      for (const e of document.querySelectorAll('[href], [src]')) {
        const v = e.getAttribute('href') !== null ? e.getAttribute('href') : e.getAttribute('src');
        if (/^([a-z][a-z0-9+.-]*:|\/)/i.test(v)) problems.push('absolute or network URL: ' + v);
      }
      const failed = (await Promise.all(Array.from(srcs).map(src => new Promise(res => {
        const im = new Image();
        im.onload = () => res(im.naturalWidth > 0 ? null : src);
        im.onerror = () => res(src);
        im.src = src;
      })))).filter(Boolean);
      const ok = !problems.length && !failed.length && !A.errors.length;
      const lines = [(ok ? 'OK' : 'FAIL') + ' scenes=' + A.scenes.length + ' rows=' + rows + ' points=' + points + ' galleries=' + galleries +
        ' images=' + srcs.size + ' failed=' + failed.length + ' errors=' + A.errors.length + ' problems=' + problems.length]
        .concat(failed.map(f => 'failed image: ' + f), A.errors, problems);
      document.body.prepend(el('pre', { id: 'selftest', text: lines.join('\n') }));
    } catch (e) {
      document.body.prepend(el('pre', { id: 'selftest', text: 'FAIL exception: ' + (e && e.stack || e) + '\n' + A.errors.concat(problems).join('\n') }));
    }
  };
})();
AA.init();
