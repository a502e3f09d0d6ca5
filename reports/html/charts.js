// The HTML report's script, part 2: quality-vs-cost charts (inline SVG, log time axis, Pareto
// front for the metric's direction) and the cost-of-accuracy tables.
(function () {
  const A = AA, el = A.el, sv = A.sv;

  /// Points of a scope. Scene: one per row. Suite: for each method, the mean quality and the
  /// mean of the median times over the scenes where every method has a value of the metric
  /// (the same scenes for every method, so the means compare like with like); the scenes left
  /// out, with why, are in `left` and shown under the chart and the table. A method that is not
  /// applicable on any scene of the run (a renderer-side method in a run of image scenes only)
  /// is left out of the suite means instead of emptying them; one not applicable on some
  /// scenes leaves those scenes out, like any other missing value.
  function collect(scope, sceneName, metric) {
    const pts = [], unplotted = [], left = [];
    const label = A.metricInfo(metric).label;
    if (scope === 'scene') {
      for (const r of A.rowsByScene.get(sceneName) || []) {
        const q = A.metricValue(r, metric), t = r.timing.total;
        const p = r.not_applicable ? { spec: r.spec, q: null, t: null, tmin: null, tmax: null, rows: [r] }
                                   : { spec: r.spec, q, t: t.median_ms, tmin: t.min_ms, tmax: t.max_ms, rows: [r] };
        if (r.not_applicable) unplotted.push({ p, why: 'not applicable: ' + r.not_applicable });
        else if (q === null) unplotted.push({ p, why: label + ' is null (' + A.nullReason(r, metric) + ')' });
        else if (!(t.median_ms > 0)) unplotted.push({ p, why: 'its time is 0 ms, which a log axis cannot show' });
        else pts.push(p);
      }
    } else {
      const used = [];
      const naEverywhere = new Map();  // spec → reason, for methods not applicable on every scene
      for (const spec of A.specs) {
        const rs = A.scenes.map(s => (A.rowsByScene.get(s.name) || []).find(r => r.spec === spec));
        if (rs.length && rs.every(r => r && r.not_applicable)) naEverywhere.set(spec, rs[0].not_applicable);
      }
      const specs = A.specs.filter(spec => !naEverywhere.has(spec));
      for (const s of A.scenes) {
        const rows = (A.rowsByScene.get(s.name) || []).filter(r => !naEverywhere.has(r.spec));
        const missing = specs.filter(spec => !rows.some(r => r.spec === spec));
        const bad = rows.filter(r => A.metricValue(r, metric) === null);
        if (missing.length) left.push({ scene: s.name, why: 'not run with ' + missing.join(', ') });
        else if (bad.length) {
          const reasons = [...new Set(bad.map(r => A.nullReason(r, metric)))];
          left.push({ scene: s.name, why: reasons.join('; ') +
            (bad.length < rows.length ? ' (' + bad.map(r => r.spec).join(', ') + ')' : '') });
        } else used.push(s.name);
      }
      for (const spec of A.specs) {
        if (naEverywhere.has(spec)) {
          unplotted.push({ p: { spec, q: null, t: null, tmin: null, tmax: null, rows: [] },
            why: 'not applicable on any scene of this run: ' + naEverywhere.get(spec) });
          continue;
        }
        const rows = used.map(n => A.rowsByScene.get(n).find(r => r.spec === spec));
        const mean = f => rows.reduce((s, r) => s + f(r), 0) / rows.length;
        const p = { spec, q: null, t: rows.length ? mean(r => r.timing.total.median_ms) : null, tmin: null, tmax: null, rows };
        if (!rows.length) unplotted.push({ p, why: 'no scene where every method has a value of ' + label });
        else {
          p.q = mean(r => A.metricValue(r, metric));
          if (p.t > 0) pts.push(p); else unplotted.push({ p, why: 'its time is 0 ms, which a log axis cannot show' });
        }
      }
    }
    const order = new Map(A.specs.map((s, i) => [s, i]));
    const all = pts.concat(unplotted.map(u => u.p)).sort((a, b) => order.get(a.spec) - order.get(b.spec));
    return { pts, unplotted, all, left };
  }

  /// "Mean over 8 of 9 scenes — left out: detail-texture (no edge pixels)." for the suite.
  function scopeNote(data) {
    const n = A.scenes.length, k = n - data.left.length;
    const text = 'Suite means over ' + (data.left.length ? k + ' of ' + n : 'all ' + n) + ' scenes' +
      (data.left.length ? ' — left out (not every method has a value there): ' +
        data.left.map(l => l.scene + ': ' + l.why).join('; ') : '') + '.';
    return el('p', { class: 'note scope-note', text });
  }

  /// The Pareto front: no other point is at least as fast and at least as good (better = +1:
  /// higher quality is better, -1: lower). Returned in increasing time.
  function paretoFront(pts, better) {
    const sorted = pts.slice().sort((a, b) => a.t - b.t || better * (b.q - a.q));
    const out = [];
    let best = -Infinity;
    for (const p of sorted) {
      if (better * p.q > best) { out.push(p); best = better * p.q; }
    }
    return out;
  }
  function dominator(p, pts, better) {
    let found = null;
    for (const o of pts) {
      if (o === p || !(o.t <= p.t && better * o.q >= better * p.q && (o.t < p.t || better * o.q > better * p.q))) continue;
      if (!found || o.t < found.t) found = o;
    }
    return found;
  }

  function logTicks(lo, hi) {
    const out = [];
    const e0 = Math.floor(Math.log10(lo)), e1 = Math.ceil(Math.log10(hi));
    for (const mants of [[1, 2, 5], [1, 2, 3, 4, 5, 6, 7, 8, 9]]) {
      out.length = 0;
      for (let e = e0; e <= e1; e++) for (const m of mants) {
        const v = Number((m * Math.pow(10, e)).toPrecision(6));
        if (v >= lo && v <= hi) out.push(v);
      }
      if (out.length >= 3) break;
    }
    return out;
  }
  function linTicks(lo, hi) {
    const raw = (hi - lo) / 6, mag = Math.pow(10, Math.floor(Math.log10(raw)));
    const step = [1, 2, 2.5, 5, 10].map(k => k * mag).find(s => s >= raw);
    const out = [];
    for (let v = Math.ceil(lo / step) * step; v <= hi + step * 1e-9; v += step) out.push(Number(v.toPrecision(12)));
    return out;
  }
  const tickText = v => String(Number(v.toPrecision(3)));

  function qualityText(metric, q) {
    const i = A.metricInfo(metric);
    return A.fmtMetric(metric, q) + (i.unit ? ' ' + i.unit : '');
  }

  function tipText(p, ctx) {
    const { scope, metric, base, better, dom, onFront } = ctx;
    const i = A.metricInfo(metric);
    const lines = [p.spec];
    lines.push(i.label + ': ' + qualityText(metric, p.q) + (scope === 'suite' ? ' (mean over ' + p.rows.length + ' scenes)' : ''));
    lines.push('time: ' + A.fmtMs(p.t) + ' ms' + (scope === 'scene' ? ' [' + A.fmtMs(p.tmin) + '–' + A.fmtMs(p.tmax) + ']' : ' (mean of medians)'));
    if (base && base !== p && base.q !== null) {
      const g = better * (p.q - base.q), dt = p.t - base.t;
      lines.push('vs none: ' + A.signed(g, v => A.fmtMetric(metric, v)) + (i.unit ? ' ' + i.unit : '') + ' quality, ' +
                 A.signed(dt, A.fmtMs) + ' ms' + (dt > 0 ? ' → ' + A.fmtSig(g / dt) + ' ' + (i.unit || 'Δ') + '/ms' : ''));
    }
    if (scope === 'scene') {
      const r = p.rows[0], c = r.cost;
      lines.push('rays/px ' + A.fmtSig(c.primary_rays_per_px) + ' + ' + A.fmtSig(c.shadow_rays_per_px) +
                 ' · tex/px ' + A.fmtSig(c.texture_lookups_per_px) + ' · shades/px ' + A.fmtSig(c.shading_evals_per_px) +
                 ' · taps/px ' + A.fmtSig(c.taps_per_px));
    }
    lines.push(onFront ? 'on the Pareto front' : dom ? 'dominated by ' + dom.spec + ' (as fast or faster, as good or better)' : '');
    return lines.filter(Boolean).join('\n');
  }

  function drawChart(box, scope, sceneName, metric, data) {
    const info = A.metricInfo(metric), better = info.better, pts = data.pts;
    if (scope === 'suite') box.append(scopeNote(data));
    if (!pts.length) {
      box.append(el('p', { class: 'note', text: 'No method has a value of ' + info.label + ' to plot here.' }));
      return;
    }
    const W = 660, H = 420, m = { l: 64, r: 18, t: 16, b: 52 };
    let lx0 = Math.log10(Math.min(...pts.map(p => p.t))), lx1 = Math.log10(Math.max(...pts.map(p => p.t)));
    if (lx1 - lx0 < 0.5) { const c = (lx0 + lx1) / 2; lx0 = c - 0.25; lx1 = c + 0.25; }
    const padx = (lx1 - lx0) * 0.07; lx0 -= padx; lx1 += padx;
    let y0 = Math.min(...pts.map(p => p.q)), y1 = Math.max(...pts.map(p => p.q));
    let floor = null;
    if (scope === 'scene' && info.psnr) {
      const f = A.sceneByName.get(sceneName).reference.noise_floor_psnr_db;
      if (typeof f === 'number') floor = f;
    }
    const floorIn = floor !== null && floor <= y1 + 6 && floor >= y0 - 6;
    if (floorIn) { y0 = Math.min(y0, floor); y1 = Math.max(y1, floor); }
    if (y1 - y0 < 1e-12) { const d = Math.abs(y0) * 0.05 || 0.5; y0 -= d; y1 += d; }
    const pady = (y1 - y0) * 0.08; y0 -= pady; y1 += pady;
    const X = t => m.l + (Math.log10(t) - lx0) / (lx1 - lx0) * (W - m.l - m.r);
    const Y = q => H - m.b - (q - y0) / (y1 - y0) * (H - m.t - m.b);
    const dirText = better > 0 ? 'higher is better ↑' : 'lower is better ↓';
    const svg = sv('svg', { viewBox: '0 0 ' + W + ' ' + H, role: 'group',
      'aria-label': (scope === 'suite' ? 'Suite mean: ' : 'Scene ' + sceneName + ': ') + info.label + ' (' + dirText + ') against time per frame; one focusable point per method' });
    const grid = sv('g', { class: 'grid' }), axis = sv('g', { class: 'axis' });
    for (const v of logTicks(Math.pow(10, lx0), Math.pow(10, lx1))) {
      const x = X(v);
      grid.append(sv('line', { x1: x, x2: x, y1: m.t, y2: H - m.b }));
      axis.append(sv('text', { x, y: H - m.b + 15, 'text-anchor': 'middle', text: tickText(v) }));
    }
    for (const v of linTicks(y0, y1)) {
      const y = Y(v);
      grid.append(sv('line', { x1: m.l, x2: W - m.r, y1: y, y2: y }));
      axis.append(sv('text', { x: m.l - 6, y: y + 4, 'text-anchor': 'end', text: A.fmtMetric(metric, v).replace(/\.?0+$/, '') || '0' }));
    }
    axis.append(sv('line', { x1: m.l, x2: W - m.r, y1: H - m.b, y2: H - m.b }));
    axis.append(sv('line', { x1: m.l, x2: m.l, y1: m.t, y2: H - m.b }));
    axis.append(sv('text', { class: 'axis-label', x: m.l + (W - m.l - m.r) / 2, y: H - 14, 'text-anchor': 'middle',
      text: 'time per frame, ms (' + (scope === 'suite' ? 'mean of per-scene medians' : 'median') + ', log scale) →' }));
    axis.append(sv('text', { class: 'axis-label', transform: 'translate(16 ' + (m.t + (H - m.t - m.b) / 2) + ') rotate(-90)',
      'text-anchor': 'middle', text: (scope === 'suite' ? 'mean ' : '') + info.label + (info.unit ? ' (' + info.unit + ')' : '') + ' — ' + dirText }));
    svg.append(grid, axis);
    if (floor !== null) {
      const label = 'reference noise floor ' + floor.toFixed(2) + ' dB';
      if (floorIn) {
        svg.append(sv('line', { class: 'floor', x1: m.l, x2: W - m.r, y1: Y(floor), y2: Y(floor) }));
        svg.append(sv('text', { class: 'floor-label', x: W - m.r - 4, y: Y(floor) - 4, 'text-anchor': 'end',
          text: label + (metric !== 'psnr_db' ? ' (whole image)' : '') }));
      } else {
        svg.append(sv('text', { class: 'floor-label', x: W - m.r - 4, y: m.t + 10, 'text-anchor': 'end',
          text: label + (floor > y1 ? ' (above the plot)' : ' (below the plot)') }));
      }
    }
    const front = paretoFront(pts, better);
    const onFront = new Set(front);
    if (front.length > 1) {
      let d = 'M' + X(front[0].t).toFixed(1) + ' ' + Y(front[0].q).toFixed(1);
      for (const p of front.slice(1)) d += ' H' + X(p.t).toFixed(1) + ' V' + Y(p.q).toFixed(1);
      svg.append(sv('path', { class: 'front', d }, sv('title', { text: 'Pareto front: no method is both faster and better than these' })));
    }
    const base = data.all.find(p => p.spec === 'none' && p.q !== null) || null;
    const placed = [];
    const fits = (x, y, w) => {
      const b = { x0: x, x1: x + w, y0: y - 10, y1: y + 2 };
      if (b.x0 < m.l || b.x1 > W - m.r || b.y0 < m.t || b.y1 > H - m.b) return null;
      for (const o of placed) if (!(b.x1 < o.x0 || b.x0 > o.x1 || b.y1 < o.y0 || b.y0 > o.y1)) return null;
      return b;
    };
    for (const p of pts) placed.push({ x0: X(p.t) - 5, x1: X(p.t) + 5, y0: Y(p.q) - 5, y1: Y(p.q) + 5 });
    const ordered = pts.filter(p => !onFront.has(p)).concat(front);
    for (const p of ordered) {
      const ctx = { scope, metric, base, better, onFront: onFront.has(p), dom: onFront.has(p) ? null : dominator(p, pts, better) };
      const text = tipText(p, ctx);
      const cx = X(p.t), cy = Y(p.q);
      const g = sv('g', { class: 'pt ' + (onFront.has(p) ? 'front-pt' : 'dominated'), tabindex: '0', role: 'button',
        'data-spec': p.spec, 'aria-label': text.replace(/\n/g, '; ') },
        sv('title', { text }),
        A.marker(p.spec, cx, cy, onFront.has(p) ? 5.5 : 4.5));
      if (onFront.has(p) || p.spec === 'none') {
        const w = p.spec.length * 6 + 4;
        for (const [dx, dy, anchor] of [[8, 4, 'start'], [8, -7, 'start'], [8, 15, 'start'], [-8, 4, 'end'], [-8, -7, 'end'], [-8, 15, 'end']]) {
          const b = fits(anchor === 'end' ? cx + dx - w : cx + dx, cy + dy, w);
          if (!b) continue;
          placed.push(b);
          g.append(sv('text', { x: (cx + dx).toFixed(1), y: (cy + dy).toFixed(1), 'text-anchor': anchor, text: p.spec }));
          break;
        }
      }
      g.addEventListener('mouseenter', e => A.showTip(text, g, e));
      g.addEventListener('mousemove', e => A.showTip(text, g, e));
      g.addEventListener('mouseleave', A.hideTip);
      g.addEventListener('focus', () => A.showTip(text, g, null));
      g.addEventListener('blur', A.hideTip);
      g.addEventListener('click', () => A.select(p.spec));
      g.addEventListener('keydown', e => { if (e.key === 'Enter' || e.key === ' ') { e.preventDefault(); A.select(p.spec); } });
      svg.append(g);
    }
    box.append(svg);
    box.append(el('div', { class: 'legend' }, ...pts.map(p => el('span', { 'data-spec': p.spec }, A.swatch(p.spec), ' ' + p.spec)),
      el('span', {}, el('i', { style: 'background:transparent;border:2px solid ' + getComputedStyle(document.documentElement).getPropertyValue('--front') }),
        'Pareto front (filled: on it; hollow: dominated)')));
    if (data.unplotted.length) {
      box.append(el('p', { class: 'unplotted' }, 'Not plotted: ' + data.unplotted.map(u => u.p.spec + ' — ' + u.why).join('; ') + '.'));
    }
  }

  /// Where two axes disagree on whether a method helps against none: better by one, worse by
  /// the other. Returns text for the method's cell, or null.
  function disagreement(p, base, metric, p2, base2, metric2) {
    if (!base || !base2 || !p2 || p === base || p.q === null || base.q === null || p2.q === null || base2.q === null) return null;
    const i1 = A.metricInfo(metric), i2 = A.metricInfo(metric2);
    const g1 = i1.better * (p.q - base.q), g2 = i2.better * (p2.q - base2.q);
    if (!(g1 * g2 < 0)) return null;
    const say = (info, m, g) => (g > 0 ? 'better' : 'worse') + ' than none by ' + info.label + ' (' +
      A.signed(info.better * g, v => A.fmtMetric(m, v)) + (info.unit ? ' ' + info.unit : '') + ')';
    return say(i1, metric, g1) + ', ' + say(i2, metric2, g2) + ': the metrics disagree on whether it helps. ' +
      (i2.rewards || '');
  }

  function costTable(box, scope, metric, data, metric2, data2) {
    const info = A.metricInfo(metric), better = info.better;
    const info2 = metric2 ? A.metricInfo(metric2) : null;
    const base2 = data2 ? data2.all.find(p => p.spec === 'none') || null : null;
    const p2Of = spec => data2 ? data2.all.find(q => q.spec === spec) || null : null;
    const gainUnit = info.unit || 'Δ';
    const base = data.all.find(p => p.spec === 'none') || null;
    const front = new Set(paretoFront(data.pts, better).map(p => p.spec));
    const th = (label, attrs, title) => el('th', Object.assign({ scope: 'col', title }, attrs || {}), el('button', { type: 'button' }, label));
    // GPU timings (aalab merge-gpu, docs/gpu.md): one column when any row carries them.
    const hasGpu = A.DATA.rows.some(r => r.gpu);
    const gpuSizes = hasGpu ? [...new Set(A.DATA.rows.filter(r => r.gpu).flatMap(r => Object.keys(r.gpu.sizes)))] : [];
    const gpuCell = (p) => {
      const timed = (p.rows || []).filter(r => r.gpu);
      if (!timed.length) return dash('no GPU timing for this method (only the post filters with a CUDA twin have one)');
      const mean = size => { const v = timed.map(r => r.gpu.sizes[size]).filter(Boolean).map(t => t.median_ms);
                             return v.length ? v.reduce((a, b) => a + b, 0) / v.length : null; };
      const ms = gpuSizes.map(mean);
      const g = timed[0].gpu;
      return num(ms[0] === null ? -1 : ms[0], ms.map(v => v === null ? '—' : A.fmtMs(v)).join(' / '),
        g.device + ', driver ' + g.driver + ', ' + g.kernels + ': median ms per frame at ' + gpuSizes.join(' / ') +
        (scope === 'suite' ? ' (mean over the scenes it ran on)' : '') + ', CUDA events; not CPU time');
    };
    // GPU raster timings (aalab run --gpu-timings with aalab_raster's JSON, docs/gpu.md "The
    // raster path"): the render-time methods drawn by OpenGL, one column when any row has one.
    const hasRaster = A.DATA.rows.some(r => r.gpu_raster);
    const rasterSizes = hasRaster ? [...new Set(A.DATA.rows.filter(r => r.gpu_raster).flatMap(r => Object.keys(r.gpu_raster.sizes)))] : [];
    const rasterCell = (p) => {
      const timed = (p.rows || []).filter(r => r.gpu_raster);
      if (!timed.length) return dash('no raster timing for this method (the raster path draws none, aaa on triangle scenes, MSAA, SSAA, scale43\'s render and TAA\'s jittered frame of triangle scenes)');
      const meanOf = (rows, pick) => { const v = rows.map(pick).filter(Boolean).map(t => t.median_ms);
                                       return v.length ? v.reduce((a, b) => a + b, 0) / v.length : null; };
      const ms = rasterSizes.map(size => meanOf(timed, r => r.gpu_raster.sizes[size]));
      const g = timed[0].gpu_raster;
      const what = g.device + ' (' + g.gl_version + '), ' + g.target_format + ' target, ' + g.samples + ' sample(s), MSAA resolve by ' +
        g.msaa_resolve + ': median GPU ms per frame (draw + resolve + encode) at ' + rasterSizes.join(' / ') +
        (scope === 'suite' ? ' (mean over the scenes it ran on)' : '') + ', GL timer queries; a forward renderer of this shading model, not CPU time';
      if (g.part !== 'render') return num(ms[0] === null ? -1 : ms[0], ms.map(v => v === null ? '—' : A.fmtMs(v)).join(' / '), what);
      // The render part of a render-scale method (its 4/3 target): the method's GPU time is this
      // render + its rescale and post filter, the row's CUDA-twin block (GPU ms), shown as a sum.
      const post = rasterSizes.map(size => meanOf(timed.filter(r => r.gpu), r => r.gpu.sizes[size]));
      const text = ms.map((v, i) => v === null ? '—' : A.fmtMs(v) + (post[i] === null ? '' : ' + ' + A.fmtMs(post[i]) + ' = ' + A.fmtMs(v + post[i]))).join(' / ');
      const render = ms.map((v, i) => v === null ? '—' : A.fmtMs(v) + ' ms' + (g.sizes[rasterSizes[i]] && g.sizes[rasterSizes[i]].render_size ? ' (' + g.sizes[rasterSizes[i]].render_size + ' target)' : '')).join(' / ');
      return num(ms[0] === null ? -1 : ms[0] + (post[0] || 0), text,
        'render + rescale and post filter: the render ' + render + ' drawn by the raster path on ' + what +
        (post.some(v => v !== null) ? '; plus the rescale and post filter ' + post.map(v => v === null ? '—' : A.fmtMs(v) + ' ms').join(' / ') +
                                       ' by the CUDA twin on ' + timed.find(r => r.gpu).gpu.device + ' (the GPU ms column)' : '; the rescale and post filter are not timed here (merge the CUDA twins\' file for them)'));
    };
    const table = el('table', { class: 'cost sortable' },
      el('caption', {}, 'Cost of accuracy' + (scope === 'suite' ? ' (suite means over ' + (A.scenes.length - data.left.length) + ' of ' + A.scenes.length + ' scenes)' : '') + ': what each method gains over ',
        el('code', { text: 'none' }), ' in ' + info.label + ' and what it adds in time.'),
      el('thead', {}, el('tr', {},
        th('Method', { 'data-type': 'text' }),
        th(info.label + (info.unit ? ' ' + info.unit : ''), { 'data-first': better > 0 ? 'descending' : 'ascending' }, info.help),
        th('Gain ' + gainUnit, { 'data-first': 'descending' }, better > 0 ? 'quality − none\'s quality' : 'none\'s value − this value (positive = less error)'),
        ...(info2 ? [th(info2.label + (info2.unit ? ' ' + info2.unit : ''), { 'data-first': info2.better > 0 ? 'descending' : 'ascending', class: 'perceptual' },
                        'the perceptual axis beside the chosen one: ' + info2.help +
                        (scope === 'suite' ? ' Suite mean over ' + (A.scenes.length - data2.left.length) + ' of ' + A.scenes.length + ' scenes (those where every method has it).' : '')),
                     th('Gain ' + (info2.unit || 'Δ'), { 'data-first': 'descending', class: 'perceptual' },
                        'perceptual gain over none (positive = better than none by ' + info2.label + ')')] : []),
        th('Time ms', {}, scope === 'suite' ? 'mean over scenes of the median time per frame' : 'median time per frame'),
        th('Added ms', {}, 'time − none\'s time'),
        ...(hasRaster ? [th('GPU raster ms ' + rasterSizes.join(' / '), {}, 'the method drawn by the raster path (aalab_raster, OpenGL) on ' +
                            A.DATA.rows.find(r => r.gpu_raster).gpu_raster.device + ': median ms at each size')] : []),
        ...(hasGpu ? [th('GPU ms ' + gpuSizes.join(' / '), {}, 'the post filter\'s CUDA twin on a GPU (aalab merge-gpu): median ms at each size')] : []),
        th(gainUnit + '/ms', { 'data-first': 'descending' }, 'gain ÷ time added, only when time added > 0'),
        th('Front', { 'data-first': 'descending' }, 'on the Pareto front of the chart'))));
    const body = el('tbody');
    const dash = (why) => el('td', { class: 'dash', title: why }, '—');
    const num = (v, text, title) => el('td', { class: 'num', 'data-v': v, title }, text);
    for (const p of data.all) {
      const tr = el('tr', { 'data-spec': p.spec });
      const p2 = p2Of(p.spec);
      const clash = info2 ? disagreement(p, base, metric, p2, base2, metric2) : null;
      tr.append(el('th', { scope: 'row', 'data-v': p.spec }, el('span', { class: 'method', text: p.spec }),
        clash ? el('span', { class: 'disagree', title: clash, 'aria-label': clash, tabindex: '0' },
          ' ⚠ ' + info.label + ' and ' + info2.label + ' disagree') : null));
      const un = data.unplotted.find(u => u.p === p);
      tr.append(p.q === null ? dash(un ? un.why : 'no value') : num(p.q, A.fmtMetric(metric, p.q)));
      const tOk = Number.isFinite(p.t);
      if (!base) {
        tr.append(dash('this run has no none row: nothing to compare with'));
      } else if (p.q === null || base.q === null) {
        tr.append(dash(p.q === null ? (un ? un.why : 'no value') : 'none has no value of ' + info.label));
      } else {
        const g = better * (p.q - base.q);
        tr.append(num(g, A.signed(g, v => A.fmtMetric(metric, v))));
      }
      if (info2) {
        if (!p2 || p2.q === null) tr.append(dash('no value of ' + info2.label), dash('no value of ' + info2.label));
        else {
          tr.append(num(p2.q, A.fmtMetric(metric2, p2.q)));
          if (!base2 || base2.q === null) tr.append(dash('none has no value of ' + info2.label));
          else {
            const g2 = info2.better * (p2.q - base2.q);
            tr.append(num(g2, A.signed(g2, v => A.fmtMetric(metric2, v))));
          }
        }
      }
      tr.append(tOk ? num(p.t, A.fmtMs(p.t), scope === 'scene' ? 'min–max ' + A.fmtMs(p.tmin) + '–' + A.fmtMs(p.tmax) + ' ms' : null)
                    : dash('time undefined'));
      let dt = null;
      if (!base || !tOk) tr.append(dash(!base ? 'no none row' : 'time undefined'));
      else {
        dt = p.t - base.t;
        const noisy = scope === 'scene' && p !== base && p.tmin <= base.tmax && base.tmin <= p.tmax;
        const td = num(dt, A.signed(dt, A.fmtMs) + (noisy ? ' ≈' : ''),
          noisy ? 'min–max ranges overlap with none\'s (' + A.fmtMs(base.tmin) + '–' + A.fmtMs(base.tmax) +
                  ' ms): within this run\'s timing noise' : null);
        tr.append(td);
      }
      if (hasRaster) tr.append(rasterCell(p));
      if (hasGpu) tr.append(gpuCell(p));
      if (p === base) tr.append(dash('the baseline: no gain, no time added'));
      else if (!base || p.q === null || base.q === null || dt === null) tr.append(dash('no gain or no time to divide'));
      else if (dt <= 0) tr.append(dash('time added is ' + A.fmtMs(dt) + ' ms (≤ 0): not measurably slower than none in this run, so a gain per ms is undefined (no division by zero or by a negative time)'));
      else {
        const g = better * (p.q - base.q);
        tr.append(num(g / dt, A.fmtSig(g / dt).replace('-', '−'), g < 0 ? 'negative: worse than none and slower' : null));
      }
      tr.append(front.has(p.spec) ? el('td', { class: 'front-mark', 'data-v': '1', title: 'on the Pareto front' }, '●')
                                  : el('td', { 'data-v': '0' }, ''));
      tr.addEventListener('click', () => A.select(p.spec));
      body.append(tr);
    }
    table.append(body);
    A.makeSortable(table);
    A.sortTable(table, info2 ? 5 : 3);  // by time, fastest first
    box.append(el('div', { class: 'table-wrap' }, table));
    if (scope === 'suite' && data.left.length) box.append(scopeNote(data));
    if (info2 && scope === 'suite' && data2.left.length) box.append(scopeNote(data2));
    if (info2) box.append(el('p', { class: 'note' }, '⚠ next to a method: ' + info.label + ' and ' + info2.label +
      ' disagree on whether it is better than none (hover for the numbers). Both are true statements about different things: ' +
      info.label + ' — ' + (info.rewards || info.help) + ' ' + info2.label + ' — ' + (info2.rewards || info2.help)));
    box.append(el('p', { class: 'note' }, better > 0
      ? 'Gain = quality − none\'s quality; '
      : 'Gain = none\'s ' + info.label + ' − this method\'s (lower is better, so a positive gain means less error); ',
      gainUnit + '/ms = gain ÷ time added, shown only when time added > 0 ms (else “—”, hover for why). ≈: the time difference is within the min–max spread. CPU times of this implementation; see the timing methodology.'));
  }

  function axisSelect(current, onPick) {
    return el('select', { onchange: e => onPick(e.target.value) },
      ...A.META.axis.map(n => el('option', { value: n, selected: n === current }, A.metricLabel(n) + (A.metricInfo(n).better > 0 ? ' ↑ higher is better' : ' ↓ lower is better'))));
  }
  function rewardsNote(metric) {
    const i = A.metricInfo(metric);
    return i.rewards ? el('p', { class: 'rewards' }, el('b', { text: i.label + ': ' }), i.rewards) : null;
  }

  function renderQC(qc) {
    const scope = qc.dataset.scope, sceneName = qc.dataset.scene, metric = A.state.metric;
    const metric2 = A.state.metric2 && A.state.metric2 !== metric ? A.state.metric2 : null;
    const active = document.activeElement;
    const hadFocus = qc.contains(active) && active.tagName === 'SELECT' ? active.dataset.which : null;
    qc.replaceChildren();
    qc.dataset.metric = (metric || '') + '|' + (metric2 || '');
    if (!metric) {
      qc.append(A.el('p', { class: 'note', text: 'No metric in this report has a known direction (better = higher or lower), so there is nothing to chart.' }));
      return;
    }
    const selectEl = axisSelect(metric, v => { A.state.metric = v; refreshActive(true); });
    selectEl.dataset.which = '1';
    const data = collect(scope, sceneName, metric);
    const chartBox = el('div', { class: 'chart-box' },
      el('div', { class: 'ctl' }, el('label', {}, 'Quality axis ', selectEl),
        el('span', { class: 'hint', text: 'Hover or Tab to a point for its numbers; Enter or click selects it in the gallery.' })),
      rewardsNote(metric));
    drawChart(chartBox, scope, sceneName, metric, data);
    let data2 = null, chartBox2 = null, select2 = null;
    if (A.state.metric2) {
      select2 = axisSelect(A.state.metric2, v => { A.state.metric2 = v; refreshActive(true); });
      select2.dataset.which = '2';
      chartBox2 = el('div', { class: 'chart-box perceptual' },
        el('div', { class: 'ctl' }, el('label', {}, 'Perceptual axis ', select2)));
      if (metric2) {
        data2 = collect(scope, sceneName, metric2);
        const note2 = rewardsNote(metric2);
        if (note2) chartBox2.append(note2);
        drawChart(chartBox2, scope, sceneName, metric2, data2);
      } else {
        chartBox2.append(el('p', { class: 'note', text: 'The same axis as the quality axis: pick another to see two views side by side.' }));
      }
    }
    const costBox = el('div', { class: 'cost-box' });
    costTable(costBox, scope, metric, data, metric2, data2);
    qc.append(chartBox2 ? el('div', { class: 'chart-pair' }, chartBox, chartBox2) : chartBox, costBox);
    if (hadFocus === '1') selectEl.focus();
    if (hadFocus === '2' && select2) select2.focus();
    markSelected(qc);
  }
  function markSelected(root) {
    for (const g of root.querySelectorAll('.pt')) g.classList.toggle('selected', g.dataset.spec === A.state.spec);
    for (const tr of root.querySelectorAll('table.cost tbody tr')) tr.classList.toggle('selected', tr.dataset.spec === A.state.spec);
  }
  function refreshActive(force) {
    const sec = A.sectionOf(A.state.view);
    if (!sec) return;
    for (const qc of sec.querySelectorAll('.qc')) if (force || qc.dataset.metric !== axesKey()) renderQC(qc);
  }
  const axesKey = () => (A.state.metric || '') + '|' + (A.state.metric2 && A.state.metric2 !== A.state.metric ? A.state.metric2 : '');
  A.hooks.render.push(sec => { for (const qc of sec.querySelectorAll('.qc')) if (qc.dataset.metric !== axesKey()) renderQC(qc); });
  A.hooks.select.push(() => { for (const qc of document.querySelectorAll('.qc')) markSelected(qc); });
  A.setMetric = m => { A.state.metric = m; refreshActive(true); };
  A.collect = collect;
  A.paretoFront = paretoFront;
})();
