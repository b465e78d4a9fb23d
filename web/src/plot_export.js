// A plot as a picture: PNG from uPlot's canvas (on white, with the title and the legend drawn
// in), and SVG written here from the plot's own data (its series, scales, axis labels and the
// metric marks), so that a figure for a slide or a paper scales without blur.

const xmlEscape = (s) => String(s).replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;').replace(/"/g, '&quot;');

/** Ticks of [lo, hi]: steps of 1, 2 or 5 × 10^k, about `count` of them; decades on a log scale. */
export function ticks(lo, hi, log, count = 6) {
  if (!(hi > lo)) return [lo];
  if (log) {
    const out = [];
    for (let e = Math.ceil(Math.log10(lo)); e <= Math.floor(Math.log10(hi)); e += 1) out.push(10 ** e);
    // a range within one decade: its ends
    return out.length ? out : [lo, hi];
  }
  const raw = (hi - lo) / count;
  const p = 10 ** Math.floor(Math.log10(raw));
  const step = [1, 2, 5, 10].map((m) => m * p).find((s) => s >= raw) ?? 10 * p;
  const out = [];
  for (let v = Math.ceil(lo / step) * step; v <= hi + 1e-9 * step; v += step) out.push(Math.abs(v) < 1e-12 * step ? 0 : v);
  return out;
}

/**
 * The SVG text of a plot: `spec` = {title, xLabel, yLabel, log, x (array), series: [{label,
 * colour, values (numbers or null: a gap)}], xRange [lo, hi], yRange [lo, hi], marks: [{t,
 * label}]}. 800 × 420 user units, a white background.
 */
export function plotSvg(spec, width = 800, height = 420, fmt = (v) => String(Number(v.toPrecision(4)))) {
  const m = { left: 84, right: 16, top: 34, bottom: 54 + 16 * Math.ceil(spec.series.length / 3) };
  const pw = width - m.left - m.right;
  const ph = height - m.top - m.bottom;
  const [x0, x1] = spec.xRange;
  const [y0, y1] = spec.yRange;
  const fy = spec.log ? Math.log10 : (v) => v;
  const X = (v) => m.left + ((v - x0) / (x1 - x0 || 1)) * pw;
  const Y = (v) => m.top + ph - ((fy(v) - fy(y0)) / (fy(y1) - fy(y0) || 1)) * ph;
  const r = (v) => Math.round(v * 100) / 100;
  const out = [];
  out.push(`<svg xmlns="http://www.w3.org/2000/svg" width="${width}" height="${height}" viewBox="0 0 ${width} ${height}" font-family="sans-serif" font-size="12">`);
  out.push(`<rect width="${width}" height="${height}" fill="#ffffff"/>`);
  out.push(`<text x="${m.left}" y="20" font-size="14" font-weight="bold">${xmlEscape(spec.title)}</text>`);
  out.push(`<defs><clipPath id="area"><rect x="${m.left}" y="${m.top}" width="${pw}" height="${ph}"/></clipPath></defs>`);
  // grid and ticks
  for (const t of ticks(x0, x1, false)) {
    out.push(`<line x1="${r(X(t))}" y1="${m.top}" x2="${r(X(t))}" y2="${m.top + ph}" stroke="#e6e6e6"/>`);
    out.push(`<text x="${r(X(t))}" y="${m.top + ph + 16}" text-anchor="middle">${xmlEscape(fmt(t))}</text>`);
  }
  for (const t of ticks(y0, y1, spec.log)) {
    out.push(`<line x1="${m.left}" y1="${r(Y(t))}" x2="${m.left + pw}" y2="${r(Y(t))}" stroke="#e6e6e6"/>`);
    out.push(`<text x="${m.left - 6}" y="${r(Y(t)) + 4}" text-anchor="end">${xmlEscape(spec.log ? t.toExponential(0) : fmt(t))}</text>`);
  }
  out.push(`<rect x="${m.left}" y="${m.top}" width="${pw}" height="${ph}" fill="none" stroke="#444"/>`);
  out.push(`<text x="${m.left + pw / 2}" y="${m.top + ph + 36}" text-anchor="middle">${xmlEscape(spec.xLabel)}</text>`);
  out.push(`<text transform="translate(16 ${m.top + ph / 2}) rotate(-90)" text-anchor="middle">${xmlEscape(spec.yLabel)}</text>`);
  // the series, a path each; a null (or a non-positive value on a log scale) breaks the line
  out.push('<g clip-path="url(#area)" fill="none" stroke-width="1.25">');
  for (const s of spec.series) {
    let d = '';
    let pen = false;
    for (let i = 0; i < spec.x.length; i += 1) {
      const v = s.values[i];
      if (v === null || v === undefined || !Number.isFinite(v) || (spec.log && !(v > 0))) { pen = false; continue; }
      d += `${pen ? 'L' : 'M'}${r(X(spec.x[i]))} ${r(Y(v))}`;
      pen = true;
    }
    if (d) out.push(`<path d="${d}" stroke="${xmlEscape(s.colour)}"/>`);
  }
  out.push('</g>');
  for (const mk of spec.marks ?? []) {
    if (!(mk.t >= x0 && mk.t <= x1)) continue;
    out.push(`<line x1="${r(X(mk.t))}" y1="${m.top}" x2="${r(X(mk.t))}" y2="${m.top + ph}" stroke="#555" stroke-dasharray="5 4"/>`);
    out.push(`<text x="${r(X(mk.t)) + 4}" y="${m.top + 12}" fill="#333">${xmlEscape(mk.label)}</text>`);
  }
  // legend under the plot, three to a row
  spec.series.forEach((s, i) => {
    const lx = m.left + (i % 3) * (pw / 3);
    const ly = m.top + ph + 54 + 16 * Math.floor(i / 3);
    out.push(`<line x1="${lx}" y1="${ly - 4}" x2="${lx + 18}" y2="${ly - 4}" stroke="${xmlEscape(s.colour)}" stroke-width="2"/>`);
    out.push(`<text x="${lx + 24}" y="${ly}">${xmlEscape(s.label)}</text>`);
  });
  out.push('</svg>');
  return out.join('\n');
}

/** A PNG data: URL of the uPlot `u`: its canvas on white, the title above and the legend below. */
export function plotPng(u, title, series) {
  const src = u.ctx.canvas;
  const ratio = src.width / Math.max(1, u.width);
  const rows = Math.ceil(series.length / 3);
  const c = document.createElement('canvas');
  c.width = src.width;
  c.height = src.height + Math.round((28 + 18 * rows) * ratio);
  const g = c.getContext('2d');
  g.fillStyle = '#ffffff';
  g.fillRect(0, 0, c.width, c.height);
  g.fillStyle = '#222222';
  g.font = `bold ${Math.round(14 * ratio)}px sans-serif`;
  g.fillText(title, 8 * ratio, 18 * ratio);
  g.drawImage(src, 0, Math.round(26 * ratio));
  g.font = `${Math.round(12 * ratio)}px sans-serif`;
  series.forEach((s, i) => {
    const x = (8 + (i % 3) * (u.width / 3)) * ratio;
    const y = src.height + (26 + 14 + 18 * Math.floor(i / 3)) * ratio;
    g.strokeStyle = s.colour;
    g.lineWidth = 2 * ratio;
    g.beginPath();
    g.moveTo(x, y - 4 * ratio);
    g.lineTo(x + 18 * ratio, y - 4 * ratio);
    g.stroke();
    g.fillStyle = '#222222';
    g.fillText(s.label, x + 24 * ratio, y);
  });
  return c.toDataURL('image/png');
}
