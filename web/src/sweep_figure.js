// The sweep page's figures: a line with points, a scatter, a histogram and a heatmap, drawn by
// one routine onto a "painter" that is either a canvas (the page, and the PNG download) or an SVG
// text (the SVG download), so that the picture and the files show the same thing. The cursor
// reads a figure through pick(): the run, bin or cell under it.
import { ticks } from './plot_export.js';
import { el, num, saveDataUrl } from './format.js';

const xmlEscape = (s) => String(s).replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;').replace(/"/g, '&quot;');
const tick = (v) => String(Number(v.toPrecision(4)));
export const kFailedColour = '#d62728';
const kNoValueColour = '#d9d9d9';

// viridis at nine stops (matplotlib's colour map, sampled every 1/8), linearly interpolated
const kViridis = [[68, 1, 84], [71, 44, 122], [59, 81, 139], [44, 113, 142], [33, 144, 141],
  [39, 173, 129], [92, 200, 99], [170, 220, 50], [253, 231, 37]];
export function viridis(f) {
  const t = Math.min(1, Math.max(0, f)) * (kViridis.length - 1);
  const i = Math.min(kViridis.length - 2, Math.floor(t));
  const a = kViridis[i];
  const b = kViridis[i + 1];
  const c = a.map((v, k) => Math.round(v + (b[k] - v) * (t - i)));
  return `rgb(${c[0]},${c[1]},${c[2]})`;
}

class CanvasPainter {
  constructor(ctx) { this.g = ctx; }
  rect(x, y, w, h, { fill, stroke } = {}) {
    if (fill) { this.g.fillStyle = fill; this.g.fillRect(x, y, w, h); }
    if (stroke) { this.g.strokeStyle = stroke; this.g.lineWidth = 1; this.g.strokeRect(x, y, w, h); }
  }
  path(points, { stroke, width = 1, dash = null }) {
    const g = this.g;
    g.strokeStyle = stroke;
    g.lineWidth = width;
    g.setLineDash(dash ?? []);
    g.beginPath();
    let pen = false;
    for (const p of points) {
      if (!p) { pen = false; continue; }
      if (pen) g.lineTo(p[0], p[1]); else g.moveTo(p[0], p[1]);
      pen = true;
    }
    g.stroke();
    g.setLineDash([]);
  }
  circle(x, y, r, { fill, stroke }) {
    const g = this.g;
    g.beginPath();
    g.arc(x, y, r, 0, 2 * Math.PI);
    if (fill) { g.fillStyle = fill; g.fill(); }
    if (stroke) { g.strokeStyle = stroke; g.lineWidth = 1; g.stroke(); }
  }
  text(x, y, s, { anchor = 'start', size = 12, bold = false, rotate = false, fill = '#222' } = {}) {
    const g = this.g;
    g.save();
    g.fillStyle = fill;
    g.font = `${bold ? 'bold ' : ''}${size}px sans-serif`;
    g.textAlign = anchor === 'middle' ? 'center' : anchor;
    g.translate(x, y);
    if (rotate) g.rotate(-Math.PI / 2);
    g.fillText(s, 0, 0);
    g.restore();
  }
  clip(x, y, w, h) { this.g.save(); this.g.beginPath(); this.g.rect(x, y, w, h); this.g.clip(); }
  unclip() { this.g.restore(); }
}

class SvgPainter {
  constructor(width, height) {
    this.out = [`<svg xmlns="http://www.w3.org/2000/svg" width="${width}" height="${height}" viewBox="0 0 ${width} ${height}" font-family="sans-serif" font-size="12">`];
    this.clips = 0;
  }
  static r(v) { return Math.round(v * 100) / 100; }
  rect(x0, y0, w0, h0, { fill, stroke } = {}) {
    const r = SvgPainter.r;
    // SVG draws no rectangle of a negative size (a descending axis)
    const [x, w] = w0 < 0 ? [x0 + w0, -w0] : [x0, w0];
    const [y, h] = h0 < 0 ? [y0 + h0, -h0] : [y0, h0];
    this.out.push(`<rect x="${r(x)}" y="${r(y)}" width="${r(w)}" height="${r(h)}" fill="${fill ?? 'none'}"${stroke ? ` stroke="${stroke}"` : ''}/>`);
  }
  path(points, { stroke, width = 1, dash = null }) {
    const r = SvgPainter.r;
    let d = '';
    let pen = false;
    for (const p of points) {
      if (!p) { pen = false; continue; }
      d += `${pen ? 'L' : 'M'}${r(p[0])} ${r(p[1])}`;
      pen = true;
    }
    if (d) this.out.push(`<path d="${d}" fill="none" stroke="${stroke}" stroke-width="${width}"${dash ? ` stroke-dasharray="${dash.join(' ')}"` : ''}/>`);
  }
  circle(x, y, rad, { fill, stroke }) {
    const r = SvgPainter.r;
    this.out.push(`<circle cx="${r(x)}" cy="${r(y)}" r="${rad}" fill="${fill ?? 'none'}"${stroke ? ` stroke="${stroke}"` : ''}/>`);
  }
  text(x, y, s, { anchor = 'start', size = 12, bold = false, rotate = false, fill = '#222' } = {}) {
    const r = SvgPainter.r;
    const place = rotate ? `transform="translate(${r(x)} ${r(y)}) rotate(-90)"` : `x="${r(x)}" y="${r(y)}"`;
    this.out.push(`<text ${place} text-anchor="${anchor}"${size !== 12 ? ` font-size="${size}"` : ''}${bold ? ' font-weight="bold"' : ''}${fill !== '#222' ? ` fill="${fill}"` : ''}>${xmlEscape(s)}</text>`);
  }
  clip(x, y, w, h) {
    this.clips += 1;
    const id = `area${this.clips}`;
    this.out.push(`<defs><clipPath id="${id}"><rect x="${x}" y="${y}" width="${w}" height="${h}"/></clipPath></defs><g clip-path="url(#${id})">`);
  }
  unclip() { this.out.push('</g>'); }
  text_() { return `${this.out.join('\n')}\n</svg>\n`; }
}

// [lo, hi] of the finite values, widened by 5 % (or to a unit interval around one value)
export function range(values, pad = 0.05) {
  let lo = Infinity;
  let hi = -Infinity;
  for (const v of values) {
    if (Number.isFinite(v)) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
  }
  if (!(hi >= lo)) return [0, 1];
  if (hi === lo) {
    const d = lo === 0 ? 1 : Math.abs(lo) * 0.1;
    return [lo - d, hi + d];
  }
  const d = (hi - lo) * pad;
  return [lo - d, hi + d];
}

/**
 * A figure: `spec` = {title, xLabel, yLabel, xRange, yRange, name (file name stem), layers,
 * colourBar: {range, label} (a heatmap's)}. Layers, drawn in order:
 * {kind: 'line' | 'points' | 'crosses', x, y, runs, colour, label} (a null y: no point; a
 * cross with a null y sits on the lower edge: a failed run), {kind: 'bars', edges, counts,
 * colour}, {kind: 'cells', xs, ys, values (xs.length × ys.length, x slowest), runs, failed}.
 * `describe(hit)` turns what pick() finds into the cursor's text.
 */
export class Figure {
  constructor(spec) {
    this.spec = spec;
    this.width = 640;
    this.height = 360;
  }

  margins() {
    const legend = this.spec.layers.some((l) => l.label) ? 18 : 0;
    return { left: 84, right: this.spec.colourBar ? 96 : 16, top: 30, bottom: 48 + legend };
  }

  // the data → pixel maps of a width × height drawing
  frame(width, height) {
    const m = this.margins();
    const pw = width - m.left - m.right;
    const ph = height - m.top - m.bottom;
    const [x0, x1] = this.spec.xRange;
    const [y0, y1] = this.spec.yRange;
    return {
      m, pw, ph,
      X: (v) => m.left + ((v - x0) / (x1 - x0 || 1)) * pw,
      Y: (v) => m.top + ph - ((v - y0) / (y1 - y0 || 1)) * ph,
      x: (px) => x0 + ((px - m.left) / pw) * (x1 - x0),
      y: (py) => y0 + ((m.top + ph - py) / ph) * (y1 - y0),
    };
  }

  paint(p, width, height) {
    const s = this.spec;
    const f = this.frame(width, height);
    const { m, pw, ph, X, Y } = f;
    p.rect(0, 0, width, height, { fill: '#ffffff' });
    p.text(m.left, 18, s.title, { size: 14, bold: true });
    for (const t of ticks(s.xRange[0], s.xRange[1], false)) {
      p.path([[X(t), m.top], [X(t), m.top + ph]], { stroke: '#e6e6e6' });
      p.text(X(t), m.top + ph + 16, tick(t), { anchor: 'middle' });
    }
    for (const t of ticks(s.yRange[0], s.yRange[1], false)) {
      p.path([[m.left, Y(t)], [m.left + pw, Y(t)]], { stroke: '#e6e6e6' });
      p.text(m.left - 6, Y(t) + 4, tick(t), { anchor: 'end' });
    }
    p.clip(m.left, m.top, pw, ph);
    for (const l of s.layers) this.paintLayer(p, l, f);
    p.unclip();
    p.rect(m.left, m.top, pw, ph, { stroke: '#444' });
    p.text(m.left + pw / 2, m.top + ph + 36, s.xLabel, { anchor: 'middle' });
    p.text(16, m.top + ph / 2, s.yLabel, { anchor: 'middle', rotate: true });
    // the legend: one entry per labelled layer, under the plot
    let lx = m.left;
    for (const l of s.layers.filter((k) => k.label)) {
      const ly = m.top + ph + 58;
      if (l.kind === 'crosses') this.cross(p, lx + 8, ly - 4, l.colour);
      else p.circle(lx + 8, ly - 4, 3, { fill: l.colour });
      p.text(lx + 18, ly, l.label);
      lx += 30 + 7 * l.label.length;
    }
    if (s.colourBar) this.paintColourBar(p, f, width);
  }

  cross(p, x, y, colour) {
    p.path([[x - 4, y - 4], [x + 4, y + 4]], { stroke: colour, width: 2 });
    p.path([[x - 4, y + 4], [x + 4, y - 4]], { stroke: colour, width: 2 });
  }

  paintLayer(p, l, { m, ph, X, Y }) {
    if (l.kind === 'line') {
      p.path(Array.from(l.x, (x, i) => (Number.isFinite(x) && Number.isFinite(l.y[i]) ? [X(x), Y(l.y[i])] : null)),
        { stroke: l.colour, width: 1.5 });
    } else if (l.kind === 'points') {
      for (let i = 0; i < l.x.length; i += 1) {
        if (Number.isFinite(l.x[i]) && Number.isFinite(l.y[i])) p.circle(X(l.x[i]), Y(l.y[i]), l.radius ?? 2.5, { fill: l.colour });
      }
    } else if (l.kind === 'crosses') {
      for (let i = 0; i < l.x.length; i += 1) {
        const y = l.y && Number.isFinite(l.y[i]) ? Y(l.y[i]) : m.top + ph - 6;
        if (Number.isFinite(l.x[i])) this.cross(p, X(l.x[i]), y, l.colour);
      }
    } else if (l.kind === 'bars') {
      for (let k = 0; k < l.counts.length; k += 1) {
        if (!l.counts[k]) continue;
        const x = X(l.edges[k]);
        p.rect(x, Y(l.counts[k]), X(l.edges[k + 1]) - x, Y(0) - Y(l.counts[k]), { fill: l.colour, stroke: '#ffffff' });
      }
    } else if (l.kind === 'cells') {
      const xe = edges(l.xs);
      const ye = edges(l.ys);
      const [lo, hi] = this.spec.colourBar.range;
      for (let i = 0; i < l.xs.length; i += 1) {
        for (let j = 0; j < l.ys.length; j += 1) {
          const k = i * l.ys.length + j;
          const v = l.values[k];
          const fill = l.failed[k] || !Number.isFinite(v) ? kNoValueColour : viridis((v - lo) / (hi - lo || 1));
          const x = X(xe[i]);
          const y = Y(ye[j + 1]);
          // a hair wider than the cell, so that neighbours leave no seam when anti-aliased
          p.rect(x, y, X(xe[i + 1]) - x + 0.5, Y(ye[j]) - y + 0.5, { fill });
          if (l.failed[k]) this.cross(p, X(l.xs[i]), Y(l.ys[j]), kFailedColour);
        }
      }
    }
  }

  paintColourBar(p, { m, ph }, width) {
    const [lo, hi] = this.spec.colourBar.range;
    const x = width - m.right + 14;
    const steps = 64;
    for (let k = 0; k < steps; k += 1) {
      const y = m.top + ph - ((k + 1) / steps) * ph;
      p.rect(x, y, 14, ph / steps + 0.5, { fill: viridis((k + 0.5) / steps) });
    }
    p.rect(x, m.top, 14, ph, { stroke: '#444' });
    for (const t of ticks(lo, hi, false, 5)) {
      const y = m.top + ph - ((t - lo) / (hi - lo || 1)) * ph;
      p.path([[x + 14, y], [x + 18, y]], { stroke: '#444' });
      p.text(x + 20, y + 4, tick(t));
    }
    p.text(width - 8, m.top + ph / 2, this.spec.colourBar.label, { anchor: 'middle', rotate: true });
  }

  /** What lies under the CSS-pixel point (px, py) of the page's canvas, or null. */
  pick(px, py) {
    const f = this.frame(this.width, this.height);
    if (px < f.m.left || px > f.m.left + f.pw || py < f.m.top || py > f.m.top + f.ph) return null;
    const x = f.x(px);
    for (const l of [...this.spec.layers].reverse()) {
      if (l.kind === 'cells') {
        const i = locate(edges(l.xs), x);
        const j = locate(edges(l.ys), f.y(py));
        if (i >= 0 && j >= 0) return { layer: l, index: i * l.ys.length + j, i, j };
      } else if (l.kind === 'bars') {
        const k = locate(l.edges, x);
        if (k >= 0) return { layer: l, index: k };
      } else if (l.kind === 'points' || l.kind === 'crosses') {
        let best = -1;
        let bestD = 8 * 8;  // within 8 px
        for (let i = 0; i < l.x.length; i += 1) {
          if (!Number.isFinite(l.x[i])) continue;
          const yy = l.y && Number.isFinite(l.y[i]) ? f.Y(l.y[i]) : (l.kind === 'crosses' ? f.m.top + f.ph - 6 : NaN);
          const d = (f.X(l.x[i]) - px) ** 2 + (yy - py) ** 2;
          if (d < bestD) { bestD = d; best = i; }
        }
        if (best >= 0) return { layer: l, index: best };
      }
    }
    return null;
  }

  /** The page's client coordinates of the data point (x, y) (for tests and scripts). */
  toClient(x, y) {
    const f = this.frame(this.width, this.height);
    const b = this.canvas.getBoundingClientRect();
    return [b.left + f.X(x), b.top + f.Y(y)];
  }

  svg() {
    const p = new SvgPainter(800, 450);
    this.paint(p, 800, 450);
    return p.text_();
  }

  png() {
    const c = document.createElement('canvas');
    c.width = 1600;
    c.height = 900;
    const g = c.getContext('2d');
    g.scale(2, 2);
    this.paint(new CanvasPainter(g), 800, 450);
    return c.toDataURL('image/png');
  }

  /** The figure's block: a title with its downloads, the canvas, and the cursor's reading. */
  element(describe) {
    const png = el('button', { type: 'button', class: 'download', 'data-format': 'png', title: 'this plot as a PNG image', text: 'PNG' });
    const svg = el('button', { type: 'button', class: 'download', 'data-format': 'svg', title: 'this plot as an SVG drawing', text: 'SVG' });
    png.addEventListener('click', () => saveDataUrl(this.png(), `${this.spec.name}.png`));
    svg.addEventListener('click', () => {
      const url = URL.createObjectURL(new Blob([this.svg()], { type: 'image/svg+xml' }));
      saveDataUrl(url, `${this.spec.name}.svg`);
      setTimeout(() => URL.revokeObjectURL(url), 10000);
    });
    const ratio = window.devicePixelRatio || 1;
    const canvas = el('canvas', { width: String(Math.round(this.width * ratio)), height: String(Math.round(this.height * ratio)) });
    canvas.style.width = `${this.width}px`;
    canvas.style.height = `${this.height}px`;
    const g = canvas.getContext('2d');
    g.scale(ratio, ratio);
    this.paint(new CanvasPainter(g), this.width, this.height);
    this.canvas = canvas;
    const readout = el('div', { class: 'sweep-readout', text: '\u00a0' });
    this.readout = readout;
    canvas.addEventListener('mousemove', (ev) => {
      const b = canvas.getBoundingClientRect();
      const hit = this.pick(ev.clientX - b.left, ev.clientY - b.top);
      readout.textContent = hit ? describe(hit) : '\u00a0';
      readout.dataset.run = hit && hit.layer.runs ? String(hit.layer.runs[hit.index]) : '';
    });
    canvas.addEventListener('mouseleave', () => { readout.textContent = '\u00a0'; readout.dataset.run = ''; });
    return el('div', { class: 'sweep-figure', 'data-name': this.spec.name },
      el('h3', {}, this.spec.title, ' ', png, svg), canvas, readout);
  }
}

// the cell edges of sorted or unsorted axis values: halfway between neighbours, half a step
// beyond the ends (one value: ±0.5, or ±5 % of it)
export function edges(values) {
  const n = values.length;
  if (n === 1) {
    const d = values[0] === 0 ? 0.5 : Math.abs(values[0]) * 0.05;
    return [values[0] - d, values[0] + d];
  }
  const out = [values[0] - (values[1] - values[0]) / 2];
  for (let i = 1; i < n; i += 1) out.push((values[i - 1] + values[i]) / 2);
  out.push(values[n - 1] + (values[n - 1] - values[n - 2]) / 2);
  return out;
}

// the interval [e[k], e[k+1]) holding v (the last closed), for ascending or descending edges
function locate(e, v) {
  const up = e[e.length - 1] >= e[0];
  for (let k = 0; k + 1 < e.length; k += 1) {
    const a = up ? e[k] : e[k + 1];
    const b = up ? e[k + 1] : e[k];
    if (v >= a && (v < b || (k === e.length - 2 && v <= b))) return k;
  }
  return -1;
}

export { num };
