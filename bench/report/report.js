// Bounce's benchmark report: the records of one `bounce bench` run (window.BOUNCE_REPORT, from
// report-data.js) as plots, tables and an image viewer. Plain JavaScript and SVG, no library: the page
// opens from disk with no network. Images come as scripts (images/STEM.js calls bounceImage with the
// radiance as half floats): a page opened from file:// may run scripts from its folder but may not read
// the pixels of images it loads, and exposure and the error map need the radiance.
'use strict';

(function () {
  const data = window.BOUNCE_REPORT;
  if (!data || !Array.isArray(data.results)) throw new Error('report-data.js did not load or holds no results');

  const SVG = 'http://www.w3.org/2000/svg';
  const PALETTE = ['#1f77b4', '#ff7f0e', '#2ca02c', '#d62728', '#9467bd', '#8c564b', '#e377c2', '#17becf',
    '#bcbd22', '#e6550d', '#393b79', '#637939'];

  // ---------------------------------------------------------------------------------------------
  // Records

  // JSON has no infinity: the bench writes "inf" for a render that failed (NaN/Inf in its image).
  function num(v) {
    if (typeof v === 'number') return v;
    if (v === 'inf') return Infinity;
    if (v === '-inf') return -Infinity;
    return NaN;
  }
  const records = data.results.map((r, index) => Object.assign({ index }, r));
  const scenes = [...new Set(records.map((r) => r.scene))];
  const techniques = [...new Set(records.map((r) => r.technique))];
  const colourOf = (technique) => technique === 'path-tracer' ? '#888' :
    PALETTE[techniques.indexOf(technique) % PALETTE.length];
  // The cost of the image shown: its still frames (the mean of which it is) times the median frame; one
  // frame for a record that predates the figure.
  const imageMs = (r) => r.imageMs !== undefined ? num(r.imageMs) : num(r.totalMs);
  const fullError = (r) => num(r.error && r.error.full ? r.error.full.relativeRmse : NaN);
  const label = (r) => r.technique + ' (' + r.settings + ')';
  const fmt = (v, digits) => Number.isFinite(v) ? v.toPrecision(digits || 3) : String(v);

  function el(tag, attrs, text) {
    const e = tag.startsWith('svg:') ? document.createElementNS(SVG, tag.slice(4)) : document.createElement(tag);
    for (const [k, v] of Object.entries(attrs || {})) e.setAttribute(k, v);
    if (text !== undefined) e.textContent = text;
    return e;
  }

  // ---------------------------------------------------------------------------------------------
  // Log-log plots

  // 0.05, 2, 500, 20k, 3M: short labels for log axes.
  function tickText(v) {
    if (v >= 1e6) return +(v / 1e6).toPrecision(2) + 'M';
    if (v >= 1e3) return +(v / 1e3).toPrecision(2) + 'k';
    return String(+v.toPrecision(2));
  }

  function logRange(values) {
    const v = values.filter((x) => Number.isFinite(x) && x > 0);
    if (!v.length) return [0.1, 10];
    let lo = Math.min(...v), hi = Math.max(...v);
    if (hi / lo < 4) { lo /= 2; hi *= 2; }
    return [Math.pow(10, Math.floor(Math.log10(lo) * 4) / 4), Math.pow(10, Math.ceil(Math.log10(hi) * 4) / 4)];
  }

  // An SVG with log axes over xs and ys; returns {svg, x(v), y(v)}.
  function logAxes(xs, ys, xLabel, yLabel) {
    const W = 560, H = 360, L = 60, R = 16, T = 12, B = 44;
    const [x0, x1] = logRange(xs), [y0, y1] = logRange(ys);
    const x = (v) => L + (Math.log10(v) - Math.log10(x0)) / (Math.log10(x1) - Math.log10(x0)) * (W - L - R);
    const y = (v) => H - B - (Math.log10(v) - Math.log10(y0)) / (Math.log10(y1) - Math.log10(y0)) * (H - T - B);
    const svg = el('svg:svg', { width: W, height: H, viewBox: `0 0 ${W} ${H}` });
    const axis = el('svg:g', { class: 'axis' });
    // 1, 2, 5 per decade over up to two decades, else the decades alone.
    const ticks = (lo, hi) => {
      const out = [], steps = Math.log10(hi / lo) > 2.5 ? [1] : [1, 2, 5];
      for (let e = Math.floor(Math.log10(lo)); e <= Math.ceil(Math.log10(hi)); ++e)
        for (const m of steps) {
          const v = m * Math.pow(10, e);
          if (v >= lo * 0.999 && v <= hi * 1.001) out.push(v);
        }
      return out;
    };
    for (const v of ticks(x0, x1)) {
      axis.append(el('svg:line', { class: 'grid', x1: x(v), x2: x(v), y1: T, y2: H - B }));
      axis.append(el('svg:text', { x: x(v), y: H - B + 14, 'text-anchor': 'middle' }, tickText(v)));
    }
    for (const v of ticks(y0, y1)) {
      axis.append(el('svg:line', { class: 'grid', x1: L, x2: W - R, y1: y(v), y2: y(v) }));
      axis.append(el('svg:text', { x: L - 4, y: y(v) + 4, 'text-anchor': 'end' }, tickText(v)));
    }
    axis.append(el('svg:path', { d: `M${L},${T}V${H - B}H${W - R}`, fill: 'none' }));
    axis.append(el('svg:text', { x: (L + W - R) / 2, y: H - 8, 'text-anchor': 'middle' }, xLabel));
    axis.append(el('svg:text', { x: 14, y: (T + H - B) / 2, 'text-anchor': 'middle',
      transform: `rotate(-90 14 ${(T + H - B) / 2})` }, yLabel));
    svg.append(axis);
    return { svg, x, y };
  }

  // The runs no other run of their size beats in both time and error, as the bench marked them
  // (results.json's "pareto", app/bench_report.cpp), one front per image size and GL renderer (a merge of
  // shards run on several machines: their times do not compare), fastest first.
  function paretoFronts(runs) {
    const fronts = new Map();
    for (const r of runs.filter((x) => x.pareto && x.pareto.full)) {
      const key = `${r.size} ${r.renderer || ''}`;
      if (!fronts.has(key)) fronts.set(key, []);
      fronts.get(key).push(r);
    }
    return [...fronts.values()].map((f) => f.sort((a, b) => imageMs(a) - imageMs(b)));
  }

  // Speed against error: one circle per run of the scene (path-tracer rows included), the path
  // tracer's rows joined by a line, the Pareto front dashed.
  function drawSpeedPlot(scene) {
    // Camera-path runs measure moving frames, not an image's time and error: they have their own plot.
    const runs = records.filter((r) => r.scene === scene && !r.sequence);
    const box = document.getElementById('plot');
    box.replaceChildren();
    const plot = logAxes(runs.map(imageMs), runs.map(fullError),
      'GPU ms to the image: frames averaged x median ms (path tracer: CPU ms)', 'relative RMSE against full');
    const clampY = (v) => Number.isFinite(v) ? v : NaN;
    const tracer = runs.filter((r) => r.technique === 'path-tracer').sort((a, b) => imageMs(a) - imageMs(b));
    if (tracer.length > 1)
      plot.svg.append(el('svg:polyline', { class: 'tracer',
        points: tracer.map((r) => `${plot.x(imageMs(r))},${plot.y(fullError(r))}`).join(' ') }));
    const fronts = paretoFronts(runs);
    const front = fronts.flat();
    for (const f of fronts)
      if (f.length > 1)
        plot.svg.append(el('svg:polyline', { class: 'pareto',
          points: f.map((r) => `${plot.x(imageMs(r))},${plot.y(fullError(r))}`).join(' ') }));
    for (const r of runs) {
      const e = clampY(fullError(r));
      // A failed render (infinite error) sits on the top edge, hollow, so that it is still one point per run.
      const cy = Number.isFinite(e) && e > 0 ? plot.y(e) : 12;
      const c = el('svg:circle', { class: 'run', r: 5, cx: plot.x(Math.max(imageMs(r), 1e-6)), cy,
        fill: Number.isFinite(e) ? colourOf(r.technique) : 'none', 'data-index': r.index });
      c.append(el('svg:title', {}, `${label(r)}\n${fmt(imageMs(r))} ms to the image (${r.imageFrames || 1} frames of ` +
        `${fmt(num(r.totalMs))} ms), relative RMSE ${fmt(e)}` +
        (front.includes(r) ? '\nPareto front' : '')));
      c.addEventListener('click', () => selectRun(r));
      c.addEventListener('mouseenter', () => {
        document.getElementById('hover').textContent = c.firstChild.textContent.replace(/\n/g, ' | ');
      });
      plot.svg.append(c);
    }
    box.append(plot.svg, el('p', { id: 'hover', class: 'hint' }, '\u00a0'));
    const legend = el('p', { class: 'hint' });
    for (const t of [...new Set(runs.map((r) => r.technique))]) {
      const s = el('span', { class: 'swatch' });
      s.style.background = colourOf(t);
      legend.append(s, document.createTextNode(t + '  '));
    }
    box.append(legend);
  }

  // Progressive runs recorded with "curve": their error after every step against the GPU time so far,
  // beside the path tracer's rows.
  function drawConvergence(scene) {
    const box = document.getElementById('convergence');
    box.replaceChildren();
    const curves = records.filter((r) => r.scene === scene && Array.isArray(r.curve) && r.curve.length);
    if (!curves.length) return;
    const tracer = records.filter((r) => r.scene === scene && r.technique === 'path-tracer')
      .sort((a, b) => imageMs(a) - imageMs(b));
    const xs = tracer.map(imageMs), ys = tracer.map(fullError);
    for (const r of curves) for (const p of r.curve) { xs.push(num(p.elapsedMs)); ys.push(num(p.relativeRmseFull)); }
    box.append(el('h3', {}, 'Convergence of progressive runs'));
    const plot = logAxes(xs, ys, 'ms so far (GPU; path tracer: CPU)', 'relative RMSE against full');
    const line = (pts, cls, colour) => {
      const p = el('svg:polyline', { class: cls, points: pts.map(([a, b]) => `${plot.x(a)},${plot.y(b)}`).join(' ') });
      if (colour) p.setAttribute('style', `fill:none;stroke:${colour};stroke-width:1.5`);
      plot.svg.append(p);
    };
    if (tracer.length) line(tracer.map((r) => [imageMs(r), fullError(r)]), 'tracer');
    // One colour per curve (two runs of one technique differ in their settings), named below the plot.
    const legend = el('p', { class: 'hint' });
    curves.forEach((r, i) => {
      const pts = r.curve.map((p) => [num(p.elapsedMs), num(p.relativeRmseFull)])
        .filter(([a, b]) => a > 0 && b > 0 && Number.isFinite(a) && Number.isFinite(b));
      const colour = PALETTE[(techniques.indexOf(r.technique) + i) % PALETTE.length];
      line(pts, 'curve', colour);
      plot.svg.lastChild.append(el('svg:title', {}, label(r)));
      const sw = el('span', { class: 'swatch' });
      sw.style.background = colour;
      legend.append(sw, document.createTextNode(label(r) + '  '));
    });
    const sw = el('span', { class: 'swatch' });
    sw.style.background = '#999';
    legend.append(sw, document.createTextNode('path tracer'));
    box.append(plot.svg, legend);
  }

  // ---------------------------------------------------------------------------------------------
  // Images

  const images = new Map(); // id -> {width, height, rgb: Float32Array}
  const waiting = new Map(); // id -> [resolve, reject]

  function halfToFloat(h) {
    const s = h & 0x8000 ? -1 : 1, e = (h >> 10) & 0x1f, f = h & 0x3ff;
    if (e === 0) return s * f * Math.pow(2, -24);
    if (e === 31) return f ? NaN : s * Infinity;
    return s * (1 + f / 1024) * Math.pow(2, e - 15);
  }

  // Called by images/STEM.js.
  window.bounceImage = function (id, width, height, base64) {
    const bytes = atob(base64);
    const rgb = new Float32Array(width * height * 3);
    for (let i = 0; i < rgb.length; ++i)
      rgb[i] = halfToFloat(bytes.charCodeAt(2 * i) | (bytes.charCodeAt(2 * i + 1) << 8));
    images.set(id, { width, height, rgb });
    const w = waiting.get(id);
    if (w) { waiting.delete(id); w[0](images.get(id)); }
  };

  function loadImage(id) {
    if (images.has(id)) return Promise.resolve(images.get(id));
    return new Promise((resolve, reject) => {
      waiting.set(id, [resolve, reject]);
      const s = el('script', { src: id + '.js' });
      s.onerror = () => { waiting.delete(id); reject(new Error('cannot load ' + id + '.js')); };
      document.head.append(s);
    });
  }

  // Box-downsamples img by an integer factor to width x height (the bench compares a render with a
  // smaller reference the same way).
  function downsample(img, width, height) {
    if (img.width === width && img.height === height) return img;
    const fx = img.width / width, fy = img.height / height;
    if (!Number.isInteger(fx) || !Number.isInteger(fy)) return null;
    const rgb = new Float32Array(width * height * 3);
    for (let y = 0; y < img.height; ++y)
      for (let x = 0; x < img.width; ++x)
        for (let c = 0; c < 3; ++c)
          rgb[((Math.floor(y / fy) * width) + Math.floor(x / fx)) * 3 + c] += img.rgb[(y * img.width + x) * 3 + c];
    for (let i = 0; i < rgb.length; ++i) rgb[i] /= fx * fy;
    return { width, height, rgb };
  }

  // A and B at one size: the larger box-downsampled to the smaller when one divides the other.
  function sameSize(a, b) {
    if (a.width * a.height >= b.width * b.height) {
      const d = downsample(a, b.width, b.height);
      return d ? [d, b] : null;
    }
    const d = downsample(b, a.width, a.height);
    return d ? [a, d] : null;
  }

  const srgb = (v) => {
    const l = Number.isFinite(v) ? Math.min(Math.max(v, 0), 1) : (v > 0 ? 1 : 0);
    return Math.round(255 * (l <= 0.0031308 ? 12.92 * l : 1.055 * Math.pow(l, 1 / 2.4) - 0.055));
  };

  // The error map's colours: a perceptually ordered ramp (viridis' end points and three stops between)
  // over [0, scale]; NaN/Inf in magenta.
  const RAMP = [[68, 1, 84], [59, 82, 139], [33, 145, 140], [94, 201, 98], [253, 231, 37]];
  function rampColour(t) {
    if (!Number.isFinite(t)) return [255, 0, 255];
    const u = Math.min(Math.max(t, 0), 1) * (RAMP.length - 1), i = Math.min(Math.floor(u), RAMP.length - 2);
    const f = u - i;
    return RAMP[i].map((c, k) => Math.round(c + f * (RAMP[i + 1][k] - c)));
  }
  // Per-pixel relative error: mean over channels of |A - B| over the mean of B plus 0.01 (dark pixels).
  function pixelError(a, b, p) {
    let d = 0, m = 0;
    for (let c = 0; c < 3; ++c) { d += Math.abs(a.rgb[p * 3 + c] - b.rgb[p * 3 + c]); m += b.rgb[p * 3 + c]; }
    return (d / 3) / (m / 3 + 0.01);
  }

  const view = { a: null, b: null, mode: 'a', exposure: 0, split: 0.5, errorScale: 0.25, zoom: 1, panX: 0, panY: 0,
    run: null, stats: null };

  // Draws the canvas from A and B in the current mode; the one transform (zoom, pan) applies to all modes.
  // Draws the canvas from A and B in the current mode; the one transform (zoom, pan) applies to all modes.
  // Images of different sizes (a render and its smaller reference) are shown at the larger size, the
  // smaller one's pixels repeated; the error is taken as the bench takes it, between the larger one
  // box-downsampled and the smaller one, and each of its pixels covers its block.
  function draw() {
    const canvas = document.getElementById('view');
    const info = document.getElementById('image-info');
    const a = images.get(view.a), b = images.get(view.b);
    if (!a || !b) return;
    const pair = sameSize(a, b);
    if (!pair) { info.textContent = `A is ${a.width}x${a.height}, B ${b.width}x${b.height}: no common size.`; return; }
    const [A, B] = pair; // at the smaller size
    const big = a.width >= b.width ? a : b;
    const w = big.width, h = big.height, f = w / A.width;
    if (canvas.width !== w || canvas.height !== h) { canvas.width = w; canvas.height = h; fit(); }
    const errors = new Float32Array(A.width * A.height);
    let sum = 0, max = 0, bad = 0;
    for (let p = 0; p < errors.length; ++p) {
      const e = errors[p] = pixelError(A, B, p);
      if (Number.isFinite(e)) { sum += e; max = Math.max(max, e); } else ++bad;
    }
    const ctx = canvas.getContext('2d');
    const out = ctx.createImageData(w, h);
    const gain = Math.pow(2, view.exposure);
    const splitX = Math.round(view.split * w);
    for (let y = 0; y < h; ++y)
      for (let x = 0; x < w; ++x) {
        const p = y * w + x, small = Math.floor(y / f) * A.width + Math.floor(x / f);
        let rgb;
        if (view.mode === 'error') rgb = rampColour(errors[small] / view.errorScale);
        else {
          const src = view.mode === 'b' || (view.mode === 'split' && x >= splitX) ? b : a;
          const q = src.width === w ? p : small;
          rgb = [0, 1, 2].map((c) => srgb(src.rgb[q * 3 + c] * gain));
        }
        out.data.set([rgb[0], rgb[1], rgb[2], 255], p * 4);
      }
    ctx.putImageData(out, 0, 0);
    view.stats = { mean: sum / (errors.length - bad || 1), max, nonFinite: bad, width: A.width, height: A.height };
    const shown = { a: 'A', b: 'B', split: 'A left, B right', error: 'error map' }[view.mode];
    info.replaceChildren(
      document.createTextNode(`${shown}: A ${a.width}x${a.height}, B ${b.width}x${b.height}` +
        (f > 1 ? `; the error between the larger box-downsampled to ${A.width}x${A.height} and the smaller` : '') +
        `. Per-pixel relative error: mean ${fmt(view.stats.mean)}, max ${fmt(max)}` +
        (bad ? `, ${bad} non-finite` : '') + '. '),
      el('a', { href: view.a + '.exr' }, 'A (EXR)'), document.createTextNode(' '),
      el('a', { href: view.b + '.exr' }, 'B (EXR)'));
    document.getElementById('legend-text').textContent =
      view.mode === 'error' ? `0 to ${view.errorScale} (and above), magenta: NaN/Inf` : '';
    document.getElementById('legend').style.visibility = view.mode === 'error' ? 'visible' : 'hidden';
    applyTransform();
  }

  // The canvas is drawn at the image's size and scaled by CSS (nearest neighbour); the split line is an
  // overlay, so that it stays one screen pixel wide at any zoom.
  function applyTransform() {
    const canvas = document.getElementById('view');
    canvas.style.transform = `translate(${view.panX}px, ${view.panY}px) scale(${view.zoom})`;
    const line = document.getElementById('split-line');
    line.style.display = view.mode === 'split' ? 'block' : 'none';
    line.style.left = `${view.panX + Math.round(view.split * canvas.width) * view.zoom}px`;
  }

  function fit() {
    const stage = document.getElementById('stage'), canvas = document.getElementById('view');
    view.zoom = Math.min(stage.clientWidth / canvas.width, stage.clientHeight / canvas.height) || 1;
    view.panX = (stage.clientWidth - canvas.width * view.zoom) / 2;
    view.panY = (stage.clientHeight - canvas.height * view.zoom) / 2;
    applyTransform();
  }

  function showImages(a, b) {
    view.a = a;
    view.b = b;
    document.getElementById('image-a').value = a;
    document.getElementById('image-b').value = b;
    document.body.dataset.loaded = 'false';
    return Promise.all([loadImage(a), loadImage(b)]).then(() => {
      draw();
      document.body.dataset.loaded = 'true';
    }, (err) => {
      console.error(err.message);
      document.getElementById('image-info').textContent = err.message;
      document.body.dataset.loaded = 'error';
    });
  }

  // Every image of the scene: each run's, then the references its runs were compared with.
  function sceneImages(scene) {
    const list = [];
    for (const r of records.filter((x) => x.scene === scene && x.image)) list.push([r.image, `#${r.index} ${label(r)}`]);
    const refs = new Set();
    for (const r of records.filter((x) => x.scene === scene && x.references))
      for (const id of Object.values(r.references)) refs.add(id);
    for (const id of refs) list.push([id, 'reference ' + id.replace(/^images\/ref-/, '')]);
    // A camera-path run's measured frames and their references (its player shows them); the last is the
    // run's own image and reference, listed above.
    for (const r of records.filter((x) => x.scene === scene && x.sequence))
      for (const f of r.sequence.frames.filter((x) => x.image && x.image !== r.image))
        list.push([f.image, `#${r.index} ${label(r)} frame ${f.index}`],
          [f.reference, `#${r.index} reference of frame ${f.index}`]);
    return list;
  }

  function fillSelects(scene) {
    for (const sel of ['image-a', 'image-b']) {
      const s = document.getElementById(sel);
      s.replaceChildren(...sceneImages(scene).map(([id, text]) => el('option', { value: id }, text)));
    }
  }

  // ---------------------------------------------------------------------------------------------
  // One run: its command, passes as a stacked bar and a table, counters, memory.

  function table(head, rows) {
    const t = el('table');
    const tr = el('tr');
    for (const h of head) tr.append(el('th', {}, h));
    t.append(tr);
    for (const row of rows) {
      const r = el('tr');
      row.forEach((v, i) => r.append(el('td', i === 0 ? { class: 'text' } : {}, v)));
      t.append(r);
    }
    return t;
  }

  function runDetails(r) {
    const box = document.getElementById('run-details');
    box.replaceChildren();
    box.append(el('h3', {}, `${label(r)} on ${r.scene}, ${r.size}`));
    if (num(r.nonFiniteValues) > 0) box.append(el('p', { class: 'failed' }, `${r.nonFiniteValues} NaN/Inf values`));
    const errs = Object.entries(r.error || {}).map(([paths, e]) => `${paths} ${fmt(num(e.relativeRmse))}`);
    box.append(el('p', {}, `${fmt(num(r.totalMs))} ms per frame, ${r.imageFrames || 1} frames averaged: ` +
      `${fmt(imageMs(r))} ms to the image; relative RMSE: ${errs.join(', ')}`));
    if (r.command) box.append(el('code', { class: 'command' }, r.command));
    if (r.image) {
      // The bench's own tone-mapped PNG (exposure 0), linked to the EXR it was made from.
      const link = el('a', { href: r.image + '.exr', title: 'the EXR (linear radiance)' });
      link.append(el('img', { src: r.image + '.png', alt: label(r), class: 'thumbnail' }));
      box.append(link);
    }
    const passes = r.passes || [];
    if (passes.length) {
      const total = passes.reduce((s, p) => s + num(p.medianMs), 0) || 1;
      const W = 560, H = 26;
      const bar = el('svg:svg', { width: W, height: H, class: 'passes' });
      let x = 0;
      passes.forEach((p, i) => {
        const w = num(p.medianMs) / total * W;
        const rect = el('svg:rect', { x, y: 2, width: Math.max(w, 0), height: H - 4, fill: PALETTE[i % PALETTE.length] });
        rect.append(el('svg:title', {}, `${p.pass}: ${fmt(num(p.medianMs))} ms (${fmt(100 * num(p.medianMs) / total, 2)}%)`));
        bar.append(rect);
        if (w > 40) bar.append(el('svg:text', { x: x + 3, y: H / 2 + 4, fill: '#fff' }, p.pass));
        x += w;
      });
      box.append(el('h4', {}, 'Passes (median GPU ms)'), bar);
      box.append(table(['pass', 'ms', 'bound ms', 'efficiency', 'limiter'], passes.map((p) => [p.pass,
        fmt(num(p.medianMs)), p.boundMs !== undefined ? fmt(num(p.boundMs)) : '-',
        p.efficiency !== undefined ? fmt(num(p.efficiency), 2) : '-', p.limiter || '-'])));
    }
    const counters = Object.entries(r.counters || {});
    if (counters.length) box.append(el('h4', {}, 'Counters'), table(['counter', 'value'], counters.map(([k, v]) => [k, fmt(num(v), 6)])));
    const bytes = Object.entries(r.bytesAllocated || {}).sort((a, b) => num(b[1]) - num(a[1]));
    if (bytes.length)
      box.append(el('h4', {}, 'Memory by resource'), table(['resource', 'MiB'],
        bytes.map(([k, v]) => [k, (num(v) / 1048576).toFixed(3)])));
  }

  // ---------------------------------------------------------------------------------------------
  // A camera-path run (bench "path"): its error and frame time over the sequence, and a player that
  // shows its measured frames in the viewer beside their references (flip, split, error map as for any
  // image).

  const player = { run: null, at: 0, timer: null };

  // Linear axes over frame numbers and a value; returns {svg, x(v), y(v)}.
  function linearAxes(frames, ys, yLabel) {
    const W = 560, H = 200, L = 60, R = 16, T = 12, B = 36;
    const finite = ys.filter(Number.isFinite);
    const y1 = finite.length ? Math.max(...finite) * 1.1 || 1 : 1;
    const x = (v) => L + v / Math.max(frames - 1, 1) * (W - L - R);
    const y = (v) => H - B - v / y1 * (H - T - B);
    const svg = el('svg:svg', { width: W, height: H, viewBox: `0 0 ${W} ${H}`, class: 'sequence-plot' });
    const axis = el('svg:g', { class: 'axis' });
    for (let i = 0; i <= 4; ++i) {
      const v = y1 * i / 4;
      axis.append(el('svg:line', { class: 'grid', x1: L, x2: W - R, y1: y(v), y2: y(v) }));
      axis.append(el('svg:text', { x: L - 4, y: y(v) + 4, 'text-anchor': 'end' }, tickText(v)));
    }
    for (let i = 0; i <= 4; ++i) {
      const f = Math.round((frames - 1) * i / 4);
      axis.append(el('svg:text', { x: x(f), y: H - B + 14, 'text-anchor': 'middle' }, String(f)));
    }
    axis.append(el('svg:path', { d: `M${L},${T}V${H - B}H${W - R}`, fill: 'none' }));
    axis.append(el('svg:text', { x: (L + W - R) / 2, y: H - 4, 'text-anchor': 'middle' }, 'frame'));
    axis.append(el('svg:text', { x: 14, y: (T + H - B) / 2, 'text-anchor': 'middle',
      transform: `rotate(-90 14 ${(T + H - B) / 2})` }, yLabel));
    svg.append(axis);
    return { svg, x, y };
  }

  function sequencePlot(frames, count, key, yLabel, colour) {
    const pts = frames.filter((f) => Number.isFinite(num(f[key])));
    const plot = linearAxes(count, pts.map((f) => num(f[key])), yLabel);
    plot.svg.append(el('svg:polyline', { class: 'series', style: `fill:none;stroke:${colour};stroke-width:1.5`,
      points: pts.map((f) => `${plot.x(f.index)},${plot.y(num(f[key]))}`).join(' ') }));
    for (const f of pts) {
      const c = el('svg:circle', { r: 2.5, cx: plot.x(f.index), cy: plot.y(num(f[key])), fill: colour });
      c.append(el('svg:title', {}, `frame ${f.index}: ${fmt(num(f[key]))}`));
      plot.svg.append(c);
    }
    return plot;
  }

  // Shows measured frame number `i` (of the run's frames with an image) in the viewer.
  function showSequenceFrame(i) {
    const shown = player.run.sequence.frames.filter((f) => f.image);
    if (!shown.length) return Promise.resolve();
    player.at = (i + shown.length) % shown.length;
    const f = shown[player.at];
    document.getElementById('sequence-slider').value = player.at;
    document.getElementById('sequence-frame').textContent = `frame ${f.index} of ${player.run.sequence.frameCount}: ` +
      `relative RMSE ${fmt(num(f.relativeRmse))}` + (f.flicker !== undefined ? `, flicker ${fmt(num(f.flicker))}` : '') +
      (f.stillRelativeRmse !== undefined ? `, still ${fmt(num(f.stillRelativeRmse))}` : '') + `, ${fmt(num(f.ms))} ms`;
    for (const c of document.querySelectorAll('#sequence line.now')) {
      c.setAttribute('x1', c.dataset.x0 * 1 + f.index * c.dataset.dx);
      c.setAttribute('x2', c.getAttribute('x1'));
    }
    return showImages(f.image, f.reference);
  }

  function stopPlaying() {
    if (player.timer) clearInterval(player.timer);
    player.timer = null;
    const b = document.getElementById('sequence-play');
    if (b) b.textContent = 'play';
  }

  function sequenceDetails(r, box) {
    stopPlaying();
    player.run = r;
    const q = r.sequence, frames = q.frames || [];
    const shown = frames.filter((f) => f.image);
    const part = el('div', { id: 'sequence' });
    part.append(el('h4', {}, `Camera path ${q.path}: ${q.frameCount} frames, indirect light at 1/${q.indirectScale}`));
    part.append(el('p', {}, `relative RMSE (${r.lightPaths}) over frames iK and iK+1, K = ${q.every}: mean ` +
      `${fmt(num(q.meanRelativeRmse))}, second half ${fmt(num(q.secondHalfMeanRelativeRmse))}, worst ` +
      `${fmt(num(q.worstRelativeRmse))}; flicker ${fmt(num(q.flicker))}` +
      (q.secondHalfFlicker !== undefined ? `, second half ${fmt(num(q.secondHalfFlicker))}` : '') +
      (q.meanStillRatio !== undefined ? `; moving / still (${q.stillFrames} still frames) ${fmt(num(q.meanStillRatio))}` +
        (q.secondHalfStillRatio !== undefined ? `, second half ${fmt(num(q.secondHalfStillRatio))}` : '') : '') +
      `; ${fmt(num(q.meanMs))} ms per frame`));
    const error = sequencePlot(frames, q.frameCount, 'relativeRmse', 'relative RMSE', PALETTE[0]);
    const ms = sequencePlot(frames, q.frameCount, 'ms', 'GPU ms', PALETTE[1]);
    for (const p of [error, ms]) {
      const now = el('svg:line', { class: 'now', y1: 12, y2: 164, stroke: '#d62728',
        'data-x0': p.x(0), 'data-dx': p.x(1) - p.x(0) });
      p.svg.append(now);
      part.append(p.svg);
    }
    const controls = el('div', { class: 'controls' });
    const back = el('button', { id: 'sequence-back', title: 'previous measured frame' }, 'step back');
    const play = el('button', { id: 'sequence-play' }, 'play');
    const next = el('button', { id: 'sequence-next', title: 'next measured frame' }, 'step');
    const slider = el('input', { id: 'sequence-slider', type: 'range', min: 0, max: Math.max(shown.length - 1, 0),
      step: 1, value: 0 });
    back.addEventListener('click', () => { stopPlaying(); showSequenceFrame(player.at - 1); });
    next.addEventListener('click', () => { stopPlaying(); showSequenceFrame(player.at + 1); });
    slider.addEventListener('input', () => { stopPlaying(); showSequenceFrame(Number(slider.value)); });
    play.addEventListener('click', () => {
      if (player.timer) { stopPlaying(); return; }
      play.textContent = 'pause';
      player.timer = setInterval(() => showSequenceFrame(player.at + 1), 500);
    });
    controls.append(back, play, next, slider, el('span', { id: 'sequence-frame' }));
    part.append(el('p', { class: 'hint' }, 'The measured frames in the viewer above: A the frame, B its path-tracer ' +
      'reference (its own camera and lights).'), controls);
    box.append(part);
    return showSequenceFrame(Math.max(shown.length - 1, 0));
  }

  function selectRun(r) {
    view.run = r;
    for (const c of document.querySelectorAll('circle.run'))
      c.classList.toggle('selected', Number(c.dataset.index) === r.index);
    for (const row of document.querySelectorAll('tr.run-row'))
      row.classList.toggle('selected', Number(row.dataset.index) === r.index);
    runDetails(r);
    if (r.sequence) return sequenceDetails(r, document.getElementById('run-details'));
    stopPlaying();
    const refs = r.references || {};
    const ref = refs.full || Object.values(refs)[0];
    if (r.image) return showImages(r.image, ref || r.image);
    return Promise.resolve();
  }

  function drawRunTable(scene) {
    const t = document.getElementById('run-table');
    t.replaceChildren();
    const head = el('tr');
    for (const h of ['#', 'technique', 'parameters', 'size', 'light paths', 'ms per frame', 'frames', 'ms to the image',
      'rel. RMSE (own)', 'rel. RMSE (full)'])
      head.append(el('th', {}, h));
    t.append(head);
    for (const r of records.filter((x) => x.scene === scene)) {
      const own = r.error && r.error[r.lightPaths] ? num(r.error[r.lightPaths].relativeRmse) : NaN;
      const tr = el('tr', { class: 'run-row', 'data-index': r.index });
      for (const [v, cls] of [[r.index], [r.technique, 'text'], [r.settings, 'text'], [r.size], [r.lightPaths],
        [fmt(num(r.totalMs))], [r.sequence ? `path of ${r.sequence.frameCount}` : r.imageFrames || 1],
        [r.sequence ? '-' : fmt(imageMs(r))], [fmt(own)], [r.sequence ? '-' : fmt(fullError(r))]])
        tr.append(el('td', cls ? { class: cls } : {}, String(v)));
      tr.addEventListener('click', () => selectRun(r));
      t.append(tr);
    }
  }

  function showScene(scene) {
    for (const b of document.querySelectorAll('#scenes button')) b.classList.toggle('current', b.textContent === scene);
    document.getElementById('scene-name').textContent = scene;
    drawSpeedPlot(scene);
    drawConvergence(scene);
    drawRunTable(scene);
    fillSelects(scene);
    const first = records.find((r) => r.scene === scene && r.technique !== 'path-tracer' && r.image) ||
      records.find((r) => r.scene === scene && r.image);
    return first ? selectRun(first) : Promise.resolve();
  }

  // ---------------------------------------------------------------------------------------------
  // Wiring

  document.getElementById('renderer').textContent =
    `GL renderer: ${data.renderer} (${data.platform}). ${records.length} rows. Timings compare only within one run.`;
  // What the bench says first (a merge's missing tasks, several renderers' timings: app/bench_shard.cpp).
  for (const note of data.notes || [])
    document.getElementById('notes').append(el('p', { class: 'note' }, note));
  const nav = document.getElementById('scenes');
  for (const s of scenes) {
    const b = el('button', {}, s);
    b.addEventListener('click', () => showScene(s));
    nav.append(b);
  }
  const setMode = (m) => { view.mode = m; document.getElementById('mode').value = m; draw(); };
  document.getElementById('image-a').addEventListener('change', (e) => showImages(e.target.value, view.b));
  document.getElementById('image-b').addEventListener('change', (e) => showImages(view.a, e.target.value));
  document.getElementById('mode').addEventListener('change', (e) => setMode(e.target.value));
  const exposure = document.getElementById('exposure');
  const setExposure = (v) => {
    view.exposure = Math.min(Math.max(v, -8), 8);
    exposure.value = view.exposure;
    document.getElementById('exposure-value').textContent = view.exposure;
    draw();
  };
  exposure.addEventListener('input', () => setExposure(Number(exposure.value)));
  document.getElementById('split').addEventListener('input', (e) => {
    view.split = Number(e.target.value);
    if (view.mode !== 'split') setMode('split'); else draw();
  });
  document.getElementById('error-scale').addEventListener('change', (e) => { view.errorScale = Number(e.target.value); draw(); });
  document.addEventListener('keydown', (e) => {
    if (e.target.tagName === 'INPUT' && e.target.type !== 'range') return;
    if (e.key === 'f' || e.key === ' ') { setMode(view.mode === 'a' ? 'b' : 'a'); e.preventDefault(); }
    else if (e.key === 's') setMode('split');
    else if (e.key === 'e') setMode(view.mode === 'error' ? 'a' : 'error');
    else if (e.key === '+' || e.key === '=') setExposure(view.exposure + 0.5);
    else if (e.key === '-') setExposure(view.exposure - 0.5);
    else if (e.key === '0') fit();
  });
  const stage = document.getElementById('stage');
  stage.addEventListener('wheel', (e) => {
    e.preventDefault();
    const rect = stage.getBoundingClientRect(), mx = e.clientX - rect.left, my = e.clientY - rect.top;
    const k = Math.pow(1.0015, -e.deltaY);
    view.panX = mx - (mx - view.panX) * k;
    view.panY = my - (my - view.panY) * k;
    view.zoom *= k;
    applyTransform();
  }, { passive: false });
  let drag = null;
  stage.addEventListener('mousedown', (e) => { drag = [e.clientX - view.panX, e.clientY - view.panY]; });
  window.addEventListener('mouseup', () => { drag = null; });
  window.addEventListener('mousemove', (e) => {
    if (!drag) return;
    view.panX = e.clientX - drag[0];
    view.panY = e.clientY - drag[1];
    applyTransform();
  });
  // The colour bar of the error map.
  const bar = document.getElementById('colour-bar').getContext('2d');
  for (let x = 0; x < 256; ++x) {
    const [r, g, b] = rampColour(x / 255);
    bar.fillStyle = `rgb(${r},${g},${b})`;
    bar.fillRect(x, 0, 1, 12);
  }
  // For tests and scripting: the viewer's state (read-only use).
  window.bounceReport = { view, showScene, showImages, selectRun, rampColour, records };
  if (scenes.length) showScene(scenes[0]);
})();
