// Two images side by side, the one comparison view every aalab page shares: the run page's
// gallery (gallery.js), `aalab compare --html` and the sweep page (both mount it with
// AAB.autoMount from a `.abview-host` element's data-ab JSON). It draws the A and B selects
// (when given choices), an A/B slider, `f` flipping between all of A and all of B, zoom to each
// crop window (buttons, keys 1–9, 0 for the whole image; nearest-neighbour magnification), a
// pixel readout under the pointer (x, y in frame pixels, A, B and |A − B| in 8-bit levels) and
// |A − B| on a canvas with a gain and the count of differing pixels.
// A page opened from disk (not served over http) may not read its images' pixels: then the counts and the
// readout's values say they need the page served over http (the images are still drawn).
// Plain ES2017 in the page, no libraries.
'use strict';
const AAB = (function () {
  function el(tag, attrs, ...kids) {
    const e = document.createElement(tag);
    for (const k in attrs || {}) {
      const v = attrs[k];
      if (v === null || v === undefined || v === false) continue;
      if (k === 'text') e.textContent = v;
      else if (k.startsWith('on')) e.addEventListener(k.slice(2), v);
      else e.setAttribute(k, v === true ? '' : v);
    }
    for (const c of kids) if (c !== null && c !== undefined) e.append(c);
    return e;
  }
  function imgUrl(path) { return String(path).split('/').map(encodeURIComponent).join('/'); }
  const NEED_HTTP = 'need the page served over http (browsers do not let a page read the pixels of files opened from disk)';

  /// A fresh view state (the run page keeps its own in AA.state with the same fields).
  function newState(a, b) { return { split: 50, diffGain: 4, crop: -1, pairA: a, pairB: b }; }

  /// Where image `im` ({path, crops?}) lies in frame pixels for crop `k` (-1: the whole frame):
  /// its own crop file when it has one, else the whole frame; null when it has neither.
  function placement(im, k, crops, W, H) {
    if (k >= 0 && im.crops && im.crops[k]) { const c = crops[k]; return { path: im.crops[k], x: c[0], y: c[1], w: c[2], h: c[3] }; }
    return im.path ? { path: im.path, x: 0, y: 0, w: W, h: H } : null;
  }
  /// Magnification of a crop window: about 480 px on its longer side, ×2 … ×32.
  function cropZoom(c) { return Math.max(2, Math.min(32, Math.floor(480 / Math.max(c[2], c[3])))); }
  function load(p) {
    return new Promise((res, rej) => { const im = new Image(); im.onload = () => res(im); im.onerror = () => rej(new Error('cannot load ' + p)); im.src = imgUrl(p); });
  }

  /// Fills `host` with the comparison. o: { width, height (frame pixels), crops: [[x, y, w, h]],
  /// state (newState), zoom (whole-frame magnification, 0 = auto), and either choices
  /// ([{key, label, path?, crops?: [path per window]}], A and B picked from them by
  /// state.pairA / state.pairB) or a and b ({path, name, crops?}) }. Returns the host's
  /// controller (the same object on every call for one host): flip(), setSplit(v), zoomTo(k),
  /// choose(a, b), readAt(x, y), done (a promise, settled when the difference is drawn).
  function view(host, o) {
    const st = o.state, W = o.width, H = o.height, crops = o.crops || [];
    const ctl = host._ab || (host._ab = { host });
    ctl.opts = o;
    let a = o.a, b = o.b, bar = null;
    if (o.choices) {
      const keys = o.choices.map(c => c.key);
      if (!keys.includes(st.pairA)) st.pairA = keys[0];
      if (!keys.includes(st.pairB)) st.pairB = keys[Math.min(1, keys.length - 1)];
      const pick = k => { const c = o.choices.find(x => x.key === k); return { path: c.path, crops: c.crops, name: c.label }; };
      a = pick(st.pairA);
      b = pick(st.pairB);
      const sel = (label, key, cls) => el('label', {}, label + ' ', el('select', { class: cls, 'aria-label': 'image ' + label,
        onchange: e => { st[key] = e.target.value; view(host, o); } },
        ...o.choices.map(c => el('option', { value: c.key, selected: c.key === st[key] }, c.label))));
      bar = el('div', { class: 'pair-bar' }, sel('A', 'pairA', 'pair-a'), ' vs ', sel('B', 'pairB', 'pair-b'),
        ' ', el('button', { type: 'button', class: 'flip', title: 'show A, then B, then A… (key f)', onclick: () => ctl.flip() }, 'flip (f)'));
    }
    const whole = !!(placement(a, -1, crops, W, H) && placement(b, -1, crops, W, H) && a.path && b.path);
    if (!(st.crop >= -1 && st.crop < crops.length)) st.crop = -1;
    if (st.crop < 0 && !whole) st.crop = crops.length ? 0 : -1;
    const k = st.crop, c = k >= 0 ? crops[k] : [0, 0, W, H];
    const vp = { x: c[0], y: c[1], w: c[2], h: c[3] };
    const z = k >= 0 ? cropZoom(c) : (o.zoom || Math.max(1, Math.min(8, Math.floor(960 / W))));
    const sa = placement(a, k, crops, W, H), sb = placement(b, k, crops, W, H);
    const kids = bar ? [bar] : [];
    if (!sa || !sb) {
      kids.push(el('p', { class: 'note', text: 'No ' + (!sa ? 'image for ' + a.name : 'image to compare with') + ' here.' }));
      host.replaceChildren(...kids);
      ctl.setSplit = null;
      ctl.done = Promise.resolve();
      return ctl;
    }
    // The crop windows: buttons (keys 1–9; 0 = the whole image).
    if (crops.length) {
      const nav = el('div', { class: 'ab-nav', role: 'group', 'aria-label': 'zoom to a crop window' }, 'Zoom ');
      if (whole) nav.append(el('button', { type: 'button', 'data-crop': '-1', 'aria-pressed': String(k < 0), title: 'key 0', onclick: () => ctl.zoomTo(-1) }, 'whole image'));
      crops.forEach((w, i) => nav.append(el('button', { type: 'button', 'data-crop': String(i), 'aria-pressed': String(k === i),
        title: 'key ' + (i + 1) + ': x ' + w[0] + ', y ' + w[1] + ', ' + w[2] + '×' + w[3] + ' px', onclick: () => ctl.zoomTo(i) }, 'crop ' + (i + 1))));
      nav.append(el('span', { class: 'hint', text: k >= 0 ? ' crop ' + (k + 1) + ': x ' + vp.x + ', y ' + vp.y + ', ' + vp.w + '×' + vp.h + ' px, ×' + z + ' nearest neighbour' : ' ×' + z }));
      kids.push(nav);
    }
    // The slider: A everywhere, B clipped to the right of the split.
    const place = s => 'left:' + (s.x - vp.x) * z + 'px;top:' + (s.y - vp.y) * z + 'px;width:' + s.w * z + 'px;height:' + s.h * z + 'px';
    const imgA = el('img', { class: 'a', src: imgUrl(sa.path), alt: a.name, width: String(sa.w), height: String(sa.h), draggable: 'false', style: place(sa) });
    const imgB = el('img', { src: imgUrl(sb.path), alt: b.name, width: String(sb.w), height: String(sb.h), draggable: 'false', style: place(sb) });
    const bdiv = el('div', { class: 'b' }, imgB);
    const line = el('div', { class: 'line' });
    const ab = el('div', { class: 'ab' + (z > 1 ? ' zoomed' : ''), style: 'width:' + vp.w * z + 'px;height:' + vp.h * z + 'px',
      'data-viewport': [vp.x, vp.y, vp.w, vp.h].join(','), 'data-z': String(z),
      title: 'Drag to move the split (f flips): left ' + a.name + ', right ' + b.name },
      imgA, bdiv, line, el('span', { class: 'tag', style: 'left:4px', text: '◀ ' + a.name }),
      el('span', { class: 'tag', style: 'right:4px', text: b.name + ' ▶' }));
    if (k < 0) {
      crops.forEach((w, i) => ab.append(el('div', { class: 'crop-box',
        style: 'left:' + w[0] * z + 'px;top:' + w[1] * z + 'px;width:' + w[2] * z + 'px;height:' + w[3] * z + 'px' },
        el('span', { text: String(i + 1) }))));
    }
    const range = el('input', { type: 'range', class: 'ab-range', min: '0', max: '100', step: '0.5', value: String(st.split),
      'aria-label': 'A/B split: left ' + a.name + ', right ' + b.name });
    const readout = el('p', { class: 'readout', text: 'Pixel readout: point at the images.' });
    const setSplit = v => {
      st.split = Math.max(0, Math.min(100, v));
      bdiv.style.clipPath = 'inset(0 0 0 ' + st.split + '%)';
      line.style.left = st.split + '%';
      range.value = String(st.split);
      // What is on screen: all of A, all of B, or a split of the two.
      ab.dataset.shown = st.split >= 100 ? 'A' : st.split <= 0 ? 'B' : 'split';
      ab.dataset.shownSrc = st.split >= 100 ? sa.path : st.split <= 0 ? sb.path : '';
    };
    setSplit(st.split);
    range.addEventListener('input', () => setSplit(Number(range.value)));
    // Frame pixel under the pointer on an element drawn at ×z from the viewport's corner.
    const pixelAt = (e, node) => {
      const r = node.getBoundingClientRect();
      return [vp.x + Math.max(0, Math.min(vp.w - 1, Math.floor((e.clientX - r.left) / r.width * vp.w))),
              vp.y + Math.max(0, Math.min(vp.h - 1, Math.floor((e.clientY - r.top) / r.height * vp.h)))];
    };
    let drag = false;
    const fromEvent = e => { const r = ab.getBoundingClientRect(); setSplit((e.clientX - r.left) / r.width * 100); };
    ab.addEventListener('pointerdown', e => { drag = true; if (ab.setPointerCapture && e.pointerId !== undefined) try { ab.setPointerCapture(e.pointerId); } catch (x) { /* synthetic */ } fromEvent(e); });
    ab.addEventListener('pointermove', e => { if (drag) fromEvent(e); ctl.readAt(...pixelAt(e, ab)); });
    ab.addEventListener('pointerup', () => { drag = false; });
    ab.addEventListener('pointercancel', () => { drag = false; });
    kids.push(el('div', { class: 'ab-wrap', style: 'width:min(100%,' + vp.w * z + 'px)' }, el('div', { class: 'ab-scroll' }, ab), range), readout);
    // |A − B| per channel (the 2D context's 'difference' composite), times a gain ('lighter' doubles it).
    const canvas = el('canvas', { class: 'diff', width: vp.w, height: vp.h, style: 'width:' + vp.w * z + 'px;height:' + vp.h * z + 'px' });
    canvas.addEventListener('pointermove', e => ctl.readAt(...pixelAt(e, canvas)));
    const stats = el('span', { class: 'diff-stats', text: 'computing…' });
    const gain = el('select', { 'aria-label': 'difference gain', onchange: e => { st.diffGain = Number(e.target.value); view(host, o); } },
      ...[1, 2, 4, 8, 16, 32].map(v => el('option', { value: v, selected: v === st.diffGain }, '×' + v)));
    kids.push(el('div', { class: 'diff-wrap' }, el('h4', { text: 'Absolute difference |' + a.name + ' − ' + b.name + '|' + (k >= 0 ? ', crop ' + (k + 1) : '') }),
      el('p', { class: 'links' }, 'gain ', gain, ' · ', stats),
      el('div', { class: 'ab-wrap', style: 'width:min(100%,' + vp.w * z + 'px)' }, el('div', { class: 'ab-scroll' }, canvas))));
    host.replaceChildren(...kids);

    Object.assign(ctl, {
      ab, canvas, readout, vp, z, pixA: null, pixB: null, names: [a.name, b.name],
      setSplit,
      flip() { setSplit(st.split >= 100 ? 0 : 100); },
      zoomTo(i) { if (i === st.crop || i >= crops.length || (i < 0 && !whole)) return; st.crop = i; view(host, o); },
      choose(x, y) { st.pairA = x; st.pairB = y; view(host, o); },
      /// The readout at frame pixel (x, y): A, B and |A − B| in 8-bit levels where readable.
      readAt(x, y) {
        const base = 'x ' + x + ', y ' + y;
        readout.dataset.x = String(x);
        readout.dataset.y = String(y);
        if (!ctl.pixA) {
          readout.dataset.a = readout.dataset.b = readout.dataset.d = 'unknown';
          readout.textContent = base + ' · values ' + NEED_HTTP;
          return;
        }
        const i = ((y - vp.y) * vp.w + (x - vp.x)) * 4, pa = ctl.pixA, pb = ctl.pixB;
        const va = [pa[i], pa[i + 1], pa[i + 2]], vb = [pb[i], pb[i + 1], pb[i + 2]], d = va.map((v, j) => Math.abs(v - vb[j]));
        readout.dataset.a = va.join(',');
        readout.dataset.b = vb.join(',');
        readout.dataset.d = d.join(',');
        readout.textContent = base + ' · A ' + a.name + ': ' + va.join(' ') + ' · B ' + b.name + ': ' + vb.join(' ') +
          ' · |A − B|: ' + d.join(' ') + ' (RGB, 8-bit levels)';
      },
    });
    const token = ctl.token = (ctl.token || 0) + 1;
    ctl.done = Promise.all([load(sa.path), load(sb.path)]).then(([ia, ib]) => {
      if (ctl.token !== token) return;
      const draw = (ctx, im, s) => ctx.drawImage(im, s.x - vp.x, s.y - vp.y, s.w, s.h);
      const ctx = canvas.getContext('2d');
      ctx.globalCompositeOperation = 'copy';
      draw(ctx, ia, sa);
      ctx.globalCompositeOperation = 'difference';
      draw(ctx, ib, sb);
      let text;
      try {
        const read = (im, s) => {
          const cv = document.createElement('canvas');
          cv.width = vp.w; cv.height = vp.h;
          const x = cv.getContext('2d');
          draw(x, im, s);
          return x.getImageData(0, 0, vp.w, vp.h).data;
        };
        ctl.pixA = read(ia, sa);
        ctl.pixB = read(ib, sb);
        let differ = 0, max = 0;
        for (let i = 0; i < ctl.pixA.length; i += 4) {
          let m = 0;
          for (let j = 0; j < 3; j++) m = Math.max(m, Math.abs(ctl.pixA[i + j] - ctl.pixB[i + j]));
          if (m) differ++;
          if (m > max) max = m;
        }
        canvas.dataset.differing = String(differ);
        canvas.dataset.max = String(max);
        text = differ + ' of ' + vp.w * vp.h + ' pixels differ; largest difference ' + max + ' of 255 levels';
      } catch (e) {
        ctl.pixA = ctl.pixB = null;
        canvas.dataset.differing = 'unknown';
        text = 'pixel counts ' + NEED_HTTP;
      }
      ctx.globalCompositeOperation = 'lighter';
      for (let g = 1; g < st.diffGain; g *= 2) ctx.drawImage(canvas, 0, 0);
      ctx.globalCompositeOperation = 'source-over';
      canvas.dataset.done = '1';
      stats.textContent = text;
    }, err => { stats.textContent = String(err.message); canvas.dataset.done = 'error'; });
    return ctl;
  }

  /// The keys of the view: f flips, 1–9 zoom to a crop window, 0 shows the whole image.
  /// Returns true when `e` was one of them (the caller then prevents its default).
  function onKey(ctl, e) {
    if (!ctl || !ctl.setSplit || e.altKey || e.ctrlKey || e.metaKey) return false;
    if (e.target && e.target.closest && e.target.closest('input[type=text], textarea')) return false;
    if (e.key === 'f') { ctl.flip(); return true; }
    if (/^[0-9]$/.test(e.key)) { ctl.zoomTo(Number(e.key) - 1); return true; }
    return false;
  }

  // ---- the plain pages (compare, sweep): every .abview-host, its data in data-ab ----
  let active = null;
  function autoMount() {
    const hosts = Array.from(document.querySelectorAll('.abview-host'));
    for (const h of hosts) {
      const d = JSON.parse(h.dataset.ab);
      const ctl = view(h, { width: d.width, height: d.height, crops: d.crops, choices: d.choices, state: newState(d.a, d.b) });
      h.addEventListener('pointerdown', () => { active = h._ab; });
      h.addEventListener('focusin', () => { active = h._ab; });
      if (!active) active = ctl;
    }
    document.addEventListener('keydown', e => { if (onKey(active, e)) e.preventDefault(); });
    if (/abtest/.test(location.hash) && hosts.length) {
      const errors = [];
      window.addEventListener('error', e => errors.push(String(e.message || e.type)), true);
      const go = () => exercise(hosts[0]).then(out => {
        out.push('hosts=' + hosts.length, 'errors=' + errors.length);
        document.body.prepend(el('pre', { id: 'abtest', text: out.join(' ') }));
      });
      if (document.readyState === 'complete') setTimeout(go, 0); else window.addEventListener('load', () => setTimeout(go, 0));
    }
  }

  /// Drives the view in `host` as a user would and returns the facts seen (tests/reports/
  /// html_browser_test reads them): A = B, then the first two different choices (or `a`, `b`),
  /// `f` twice, key 1 (crop 1), the readout at the pixel of crop 1 where A and B differ most
  /// (the first such in row order; its centre when unreadable), key 2 when there is a second
  /// crop, key 0.
  async function exercise(host, a, b) {
    const out = [];
    const key = k => host.dispatchEvent(new KeyboardEvent('keydown', { key: k, bubbles: true }));
    const ctl = () => host._ab;
    const settle = async () => { await ctl().done; };
    try {
      const keys = ctl().opts.choices.map(c => c.key);
      a = a || keys[0];
      b = b || keys.find(x => x !== a);
      out.push('options=' + keys.join('|'));
      ctl().choose(a, a);
      await settle();
      out.push('same=' + a + ':' + ctl().canvas.dataset.differing);
      ctl().choose(a, b);
      await settle();
      out.push('pair=' + a + ':' + b + ':' + ctl().canvas.dataset.differing + ':' + ctl().canvas.dataset.max);
      out.push('before=' + ctl().ab.dataset.shown);
      for (let i = 0; i < 2; i++) {
        key('f');
        out.push('f' + (i + 1) + '=' + ctl().ab.dataset.shown + ':' + ctl().ab.dataset.shownSrc);
      }
      ctl().setSplit(50);
      key('1');
      await settle();
      const c = ctl(), vp = c.vp;
      out.push('zoom1=' + c.ab.dataset.viewport + ':x' + c.z + ':' + c.canvas.dataset.differing);
      let px = [vp.x + (vp.w >> 1), vp.y + (vp.h >> 1)];
      if (c.pixA) {
        let best = -1;
        for (let y = 0; y < vp.h; y++) for (let x = 0; x < vp.w; x++) {
          const i = (y * vp.w + x) * 4;
          const d = Math.abs(c.pixA[i] - c.pixB[i]) + Math.abs(c.pixA[i + 1] - c.pixB[i + 1]) + Math.abs(c.pixA[i + 2] - c.pixB[i + 2]);
          if (d > best) { best = d; px = [vp.x + x, vp.y + y]; }
        }
      }
      // A real pointer move over the centre of that pixel on the zoomed slider.
      const r = c.ab.getBoundingClientRect();
      c.ab.dispatchEvent(new PointerEvent('pointermove', { bubbles: true, clientX: r.left + (px[0] - vp.x + 0.5) * c.z, clientY: r.top + (px[1] - vp.y + 0.5) * c.z }));
      const d = c.readout.dataset;
      out.push('px=' + d.x + ',' + d.y + ':a=' + d.a + ':b=' + d.b + ':d=' + d.d);
      if (c.opts.crops && c.opts.crops.length > 1) {
        key('2');
        await settle();
        out.push('zoom2=' + ctl().ab.dataset.viewport + ':' + ctl().ab.querySelector('img.a').getAttribute('src'));
      }
      key('0');
      await settle();
      out.push('zoom0=' + ctl().ab.dataset.viewport);
    } catch (e) {
      out.push('exception=' + (e && e.message || e));
    }
    return out;
  }

  return { el, imgUrl, newState, view, onKey, autoMount, exercise };
})();
