// The HTML report's script: the motion player of --frames runs. Per scene with a sequence:
// the selected method's frame beside the reference's frame (play, pause, step, scrub, speed,
// zoom), a chart of every method's temporal error per frame with the current frame marked,
// and a table of the temporal metrics. Everything comes from the embedded report JSON
// (scenes[].sequence, rows[].frames); nothing is drawn for still runs.
(function () {
  const A = AA, el = A.el, sv = A.sv;
  const players = new Set();

  function seriesOf(row, name) { return row.frames && row.frames.series ? row.frames.series[name] || [] : []; }

  function chart(rows, n, name, marker) {
    const Wd = 640, Hd = 190, L = 56, R = 12, T = 10, B = 30;
    let max = 0;
    for (const r of rows) for (const v of seriesOf(r, name)) if (typeof v === 'number') max = Math.max(max, v);
    if (!(max > 0)) max = 1;
    const x = f => L + (n > 1 ? f / (n - 1) : 0) * (Wd - L - R);
    const y = v => T + (1 - v / max) * (Hd - T - B);
    const svg = sv('svg', { viewBox: '0 0 ' + Wd + ' ' + Hd, width: Wd, height: Hd, role: 'img',
      'aria-label': A.metricLabel(name) + ' per frame, one line per method' });
    svg.append(sv('line', { x1: L, y1: y(0), x2: Wd - R, y2: y(0), stroke: '#888' }),
      sv('line', { x1: L, y1: T, x2: L, y2: y(0), stroke: '#888' }));
    for (const t of [0, 0.5, 1]) {
      const lab = sv('text', { x: L - 4, y: y(max * t) + 4, 'text-anchor': 'end', 'font-size': 10 });
      lab.textContent = A.fmtSig(max * t);
      svg.append(lab);
    }
    const xl = sv('text', { x: (L + Wd - R) / 2, y: Hd - 6, 'text-anchor': 'middle', 'font-size': 11 });
    xl.textContent = 'frame (0 … ' + (n - 1) + '); ' + A.metricLabel(name) + ' from frame t−1 to t, lower is steadier';
    svg.append(xl);
    for (const r of rows) {
      const pts = [];
      seriesOf(r, name).forEach((v, f) => { if (typeof v === 'number') pts.push(x(f).toFixed(1) + ',' + y(v).toFixed(1)); });
      if (!pts.length) continue;
      const line = sv('polyline', { points: pts.join(' '), fill: 'none', stroke: A.colour(r.spec), 'stroke-width': 1.5 });
      const tip = sv('title');
      tip.textContent = r.spec;
      line.append(tip);
      svg.append(line);
    }
    svg.append(marker);
    return { svg, x, top: T, bottom: y(0) };
  }

  function table(rows) {
    const names = ['temporal_rmse', 'temporal_edge_rmse', 'temporal_psnr_db', 'psnr_db', 'edge_psnr_db'];
    const head = el('tr', {}, el('th', { text: 'method' }), ...names.map(n => el('th', { text: A.metricLabel(n),
      title: (A.metricInfo(n) || {}).help || n })));
    const body = rows.map(r => el('tr', { 'data-spec': r.spec }, el('td', { text: r.spec }),
      ...names.map(n => {
        const v = A.metricValue(r, n);
        return el('td', { class: 'num', text: v === null ? '—' : A.fmtMetric(n, v), title: v === null ? A.nullReason(r, n) || '' : '' });
      })));
    return el('table', { class: 'metrics temporal' }, el('thead', {}, head), el('tbody', {}, ...body));
  }

  function build(host) {
    if (host.dataset.built) return;
    host.dataset.built = '1';
    const scene = A.sceneByName.get(host.dataset.scene);
    const seq = scene && scene.sequence;
    const rows = (A.rowsByScene.get(host.dataset.scene) || []).filter(r => r.frames && r.frames.images && r.frames.images.length);
    if (!seq || !rows.length) { host.replaceChildren(el('p', { class: 'note', text: 'No frame sequence for this scene.' })); return; }
    const n = seq.frames;
    const P = { frame: 0, spec: rows.some(r => r.spec === A.state.spec) ? A.state.spec : rows[0].spec, timer: null, fps: 8, zoom: 0 };
    const row = () => rows.find(r => r.spec === P.spec);
    const auto = () => Math.max(1, Math.min(4, Math.floor(480 / scene.width)));
    const style = () => 'image-rendering: pixelated; width: ' + scene.width * (P.zoom || auto()) + 'px';
    const imgM = el('img', { alt: 'method frame', style: style() });
    const imgR = el('img', { alt: 'reference frame', style: style() });
    const capM = el('figcaption'), capR = el('figcaption');
    const label = el('span', { class: 'frame-label', style: 'margin: 0 10px; font-variant-numeric: tabular-nums' });
    const slider = el('input', { type: 'range', min: 0, max: n - 1, value: 0, 'aria-label': 'frame',
      oninput: e => { stop(); show(Number(e.target.value)); } });
    const playBtn = el('button', { type: 'button', onclick: () => (P.timer ? stop() : play()) }, 'Play');
    const marker = sv('line', { stroke: '#d55e00', 'stroke-dasharray': '3 2' });
    const ch = chart(rows, n, 'temporal_rmse', marker);
    const preload = [];
    function warm() {  // fetch every frame of the shown pair once, so playback does not stall
      for (const p of row().frames.images.concat(seq.reference_frames)) { const im = new Image(); im.src = A.imgUrl(p); preload.push(im); }
    }
    function show(f) {
      P.frame = (f + n) % n;
      const r = row();
      imgM.src = A.imgUrl(r.frames.images[P.frame]);
      imgR.src = A.imgUrl(seq.reference_frames[P.frame]);
      const te = seriesOf(r, 'temporal_rmse')[P.frame];
      capM.textContent = r.spec + ', frame ' + P.frame;
      capR.textContent = 'reference, frame ' + P.frame;
      label.textContent = 'frame ' + P.frame + ' / ' + (n - 1) + (typeof te === 'number' ? ' · temporal RMSE from frame ' + (P.frame - 1) + ': ' + A.fmtSig(te) : '');
      slider.value = String(P.frame);
      const xf = ch.x(P.frame);
      for (const [k, v] of [['x1', xf], ['x2', xf], ['y1', ch.top], ['y2', ch.bottom]]) marker.setAttribute(k, v);
    }
    function play() { if (P.timer) return; P.timer = setInterval(() => show(P.frame + 1), 1000 / P.fps); playBtn.textContent = 'Pause'; }
    function stop() { if (P.timer) clearInterval(P.timer); P.timer = null; playBtn.textContent = 'Play'; }
    const methodSel = el('select', { 'aria-label': 'method', onchange: e => { P.spec = e.target.value; warm(); show(P.frame); } },
      ...rows.map(r => el('option', { value: r.spec, selected: r.spec === P.spec }, r.spec)));
    const fpsSel = el('select', { 'aria-label': 'frames per second', onchange: e => { P.fps = Number(e.target.value); if (P.timer) { stop(); play(); } } },
      ...[2, 4, 8, 15, 30].map(v => el('option', { value: v, selected: v === P.fps }, v + ' fps')));
    const zoomSel = el('select', { 'aria-label': 'zoom', onchange: e => { P.zoom = Number(e.target.value); imgM.style.cssText = imgR.style.cssText = style(); } },
      ...[0, 1, 2, 4, 8].map(v => el('option', { value: v, selected: v === P.zoom }, v === 0 ? 'auto' : '×' + v)));
    const bar = el('div', { class: 'bar player-bar' },
      el('button', { type: 'button', title: 'previous frame', onclick: () => { stop(); show(P.frame - 1); } }, '◀'),
      playBtn,
      el('button', { type: 'button', title: 'next frame', onclick: () => { stop(); show(P.frame + 1); } }, '▶'),
      slider, label, el('label', { style: 'margin-right: 8px' }, 'Method ', methodSel), fpsSel, el('label', { style: 'margin-left: 8px' }, 'Zoom ', zoomSel));
    const figs = el('div', { class: 'figs', style: 'display: flex; gap: 12px; flex-wrap: wrap' },
      el('figure', {}, imgM, capM), el('figure', {}, imgR, capR));
    const facts = el('p', { class: 'note', text: n + ' frames' + (seq.moves ? '' : ' of a still scene') +
      '; building the scene and BVH at every frame took ' + A.fmtMs(seq.scene_and_bvh_ms) + ' ms in all, the references ' +
      A.fmtMs(seq.reference_ms) + ' ms. Metrics in the tables are pooled over the frames (mean); temporal metrics compare ' +
      'each method\'s frame-to-frame change with the reference\'s.' });
    const legend = el('p', { class: 'legend' }, ...rows.map(r => el('span', { style: 'margin-right: 12px' },
      el('span', { style: 'display: inline-block; width: 14px; height: 3px; vertical-align: middle; background: ' + A.colour(r.spec) }),
      ' ' + r.spec)));
    host.replaceChildren(bar, figs, el('h4', { text: 'Temporal error per frame (every method)' }), ch.svg, legend, table(rows), facts);
    host.addEventListener('aalab-stop', stop);
    players.add(host);
    warm();
    show(0);
  }

  A.hooks.render.push(sec => { for (const h of sec.querySelectorAll('.player-host')) build(h); });
  A.hooks.leave.push(sec => { for (const h of sec.querySelectorAll('.player-host')) h.dispatchEvent(new Event('aalab-stop')); });
})();
