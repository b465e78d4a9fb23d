// The page of a sweep (src/report/sweep_page.cpp writes its data, "rigid_sweep_page": 1): the
// statistics of every result, the failed runs by message, and a figure per result: against the
// swept value (a 1-D grid), a heatmap over two grid axes, or for a sample (and a grid of three or
// more axes) a histogram and a scatter against each swept input. Failed runs are red crosses at
// their inputs. Exposes window.rigidReport.sweep = {data, columns, figures: {name: Figure}}.
import { el, num, table } from './format.js';
import { Figure, kFailedColour, range } from './sweep_figure.js';

const kLittleEndian = new Uint8Array(new Uint32Array([1]).buffer)[0] === 1;
const kColour = '#1f77b4';
const kMostRunsListed = 20;  // a failure group lists this many of its runs
const kMostGroupsOpen = 10;  // failure groups listed open; the others under a <details>
const kMostBins = 50;

/** A "f64:BASE64" or "u32:BASE64" array (little-endian), or a plain array. */
export function decodeColumn(v) {
  if (Array.isArray(v)) return v;
  const colon = v.indexOf(':');
  const tag = v.slice(0, colon);
  const size = { f64: 8, u32: 4 }[tag];
  if (!size) throw new Error(`unknown array encoding "${tag}"`);
  const bin = atob(v.slice(colon + 1));
  if (bin.length % size) throw new Error(`${tag} array of ${bin.length} bytes (not a multiple of ${size})`);
  const bytes = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i += 1) bytes[i] = bin.charCodeAt(i);
  if (kLittleEndian) return tag === 'f64' ? new Float64Array(bytes.buffer) : new Uint32Array(bytes.buffer);
  const dv = new DataView(bytes.buffer);
  const n = bin.length / size;
  const out = tag === 'f64' ? new Float64Array(n) : new Uint32Array(n);
  for (let i = 0; i < n; i += 1) out[i] = tag === 'f64' ? dv.getFloat64(8 * i, true) : dv.getUint32(4 * i, true);
  return out;
}

const withUnit = (name, unit) => (unit ? `${name} (${unit})` : name);

/** count, mean, std (n − 1), min, max and the quantiles (linear interpolation) of finite values. */
export function statistics(values) {
  const v = Array.from(values).filter(Number.isFinite).sort((a, b) => a - b);
  const n = v.length;
  if (!n) return { count: 0 };
  const mean = v.reduce((a, b) => a + b, 0) / n;
  const std = n > 1 ? Math.sqrt(v.reduce((a, b) => a + (b - mean) ** 2, 0) / (n - 1)) : 0;
  const q = (p) => {
    const h = (n - 1) * p;
    const lo = Math.floor(h);
    return lo + 1 < n ? v[lo] + (h - lo) * (v[lo + 1] - v[lo]) : v[lo];
  };
  const quantiles = {};
  for (const p of ['0.05', '0.25', '0.5', '0.75', '0.95']) quantiles[p] = q(Number(p));
  return { count: n, mean, std, min: v[0], max: v[n - 1], quantiles };
}

/** Equal-width bins over the finite values: about √n of them (at most 50); the last is closed. */
export function histogram(values) {
  const v = Array.from(values).filter(Number.isFinite);
  if (!v.length) return { edges: [0, 1], counts: [0] };
  // a loop, not Math.min(...v): a spread of a million arguments overflows the stack
  let lo = Infinity;
  let hi = -Infinity;
  for (const x of v) { lo = Math.min(lo, x); hi = Math.max(hi, x); }
  if (hi === lo) {
    const d = lo === 0 ? 0.5 : Math.abs(lo) * 0.05;
    lo -= d;
    hi += d;
  }
  const k = Math.max(1, Math.min(kMostBins, Math.ceil(Math.sqrt(v.length))));
  const edges = Array.from({ length: k + 1 }, (_, i) => lo + ((hi - lo) * i) / k);
  edges[k] = hi;
  const counts = new Array(k).fill(0);
  for (const x of v) counts[Math.min(k - 1, Math.floor(((x - lo) / (hi - lo)) * k))] += 1;
  return { edges, counts };
}

function addStyle() {
  document.head.append(el('style', {}, [
    '.sweep-figure { display: inline-block; vertical-align: top; margin: 0 1rem 1rem 0; }',
    '.sweep-figure canvas { display: block; border: 1px solid #eee; cursor: crosshair; }',
    '.sweep-readout { font-family: ui-monospace, monospace; font-size: 0.8rem; min-height: 1.2em; color: #333; max-width: 640px; }',
    '.sweep-failures li { margin: 0.2rem 0; }',
    '.sweep-failures .message { font-family: ui-monospace, monospace; font-size: 0.8rem; white-space: pre-wrap; color: #8a1c1c; }',
    '.sweep-note { color: #555; font-size: 0.85rem; }',
  ].join('\n')));
}

export function buildSweepPage(data, root) {
  if (data.rigid_sweep_page !== 1) throw new Error(`sweep page: schema version ${data.rigid_sweep_page}, expected 1`);
  addStyle();
  const runs = data.runs;
  const columns = {};
  for (const c of data.columns) {
    const values = decodeColumn(c.values);
    if (values.length !== runs) throw new Error(`column ${c.name}: ${values.length} values for ${runs} runs`);
    columns[c.name] = { ...c, values };
  }
  const error = decodeColumn(data.error);
  const failed = Array.from(error, (e) => e !== 0);
  const messageOf = (r) => (error[r] ? data.messages[error[r] - 1] : '');
  const runOf = columns.run ? columns.run.values : Array.from({ length: runs }, (_, i) => i);
  const swept = data.swept.map((n) => columns[n]);
  const results = data.columns.filter((c) => c.name !== 'run' && !c.swept).map((c) => columns[c.name]);
  const layout = data.layout;
  const succeeded = runs - data.failures;

  const page = el('main', { class: 'rigid-report rigid-sweep' });
  root.append(page);
  page.append(el('h1', { text: `Sweep ${data.title}` }));
  if (data.description) page.append(el('p', { class: 'file', text: data.description }));
  const shape = layout.kind === 'grid'
    ? `a grid of ${layout.axes.map((a) => `${a.values.length} ${a.name}`).join(' \u00d7 ')}`
    : `a sample of ${data.swept.join(', ')}`;
  page.append(el('p', { class: 'sweep-summary', text: `${runs} runs (${shape}); ${succeeded} succeeded, ${data.failures} failed.` }));

  // statistics of the results (summary.json's), and of a sample's inputs (computed here)
  const statsRows = [];
  const statsOf = (c) => (data.statistics[c.name] ?? statistics(Array.from(c.values).filter((_, r) => !failed[r])));
  const rows = layout.kind === 'sample' ? [...swept, ...results] : results;
  for (const c of rows) {
    const s = statsOf(c);
    const q = s.quantiles ?? {};
    statsRows.push([withUnit(c.name, c.unit), String(s.count), num(s.mean), num(s.std), num(s.min), num(q['0.05']),
      num(q['0.25']), num(q['0.5']), num(q['0.75']), num(q['0.95']), num(s.max)]);
  }
  page.append(el('h2', { text: 'Statistics' }),
    el('p', { class: 'sweep-note', text: 'Over the runs that succeeded and have a finite value; std with n \u2212 1; quantiles by linear interpolation.' }),
    table(['column', 'count', 'mean', 'std', 'min', '5 %', '25 %', 'median', '75 %', '95 %', 'max'], statsRows, 'sweep-statistics'));

  // the failed runs, by message, the most frequent first
  if (data.failures > 0) {
    const groups = new Map();
    for (let r = 0; r < runs; r += 1) {
      if (!error[r]) continue;
      if (!groups.has(error[r])) groups.set(error[r], []);
      groups.get(error[r]).push(runOf[r]);
    }
    const sorted = [...groups.entries()].sort((a, b) => b[1].length - a[1].length || a[1][0] - b[1][0]);
    const item = ([k, rs]) => {
      const shown = rs.slice(0, kMostRunsListed).join(', ') + (rs.length > kMostRunsListed ? `, \u2026 (${rs.length - kMostRunsListed} more)` : '');
      return el('li', { 'data-count': String(rs.length) },
        `${rs.length} run${rs.length === 1 ? '' : 's'} (run${rs.length === 1 ? '' : 's'} ${shown}): `,
        el('span', { class: 'message', text: data.messages[k - 1] }));
    };
    const list = el('ul', { class: 'sweep-failures' }, ...sorted.slice(0, kMostGroupsOpen).map(item));
    page.append(el('h2', { text: `Failed runs (${data.failures})` }), list);
    // the rest of a long list (messages that name each run's value) folded under one line
    if (sorted.length > kMostGroupsOpen) {
      const rest = sorted.slice(kMostGroupsOpen);
      const runsLeft = rest.reduce((a, [, rs]) => a + rs.length, 0);
      page.append(el('details', {},
        el('summary', { text: `${rest.length} other message${rest.length === 1 ? '' : 's'} in ${runsLeft} run${runsLeft === 1 ? '' : 's'}` }),
        el('ul', { class: 'sweep-failures' }, ...rest.map(item))));
    }
  }

  const figures = {};
  const plots = el('section', { class: 'plots' }, el('h2', { text: 'Plots' }));
  page.append(plots);
  const inputsText = (r) => swept.map((c) => `${c.name} = ${num(c.values[r])}${c.unit ? ` ${c.unit}` : ''}`).join(', ');
  const runText = (r, c) => (failed[r]
    ? `run ${runOf[r]} (${inputsText(r)}) failed: ${messageOf(r)}`
    : `run ${runOf[r]}: ${inputsText(r)}: ${c.name} = ${c.values[r]}${c.unit ? ` ${c.unit}` : ''}`);
  const add = (fig, describe) => {
    figures[fig.spec.name] = fig;
    plots.append(fig.element(describe));
  };
  const failedRuns = [];
  for (let r = 0; r < runs; r += 1) if (failed[r]) failedRuns.push(r);
  const crosses = (x) => ({ kind: 'crosses', x: failedRuns.map((r) => x.values[r]), y: null, runs: failedRuns.map((r) => runOf[r]), rows: failedRuns, colour: kFailedColour, label: 'failed run' });
  const okValues = (c) => Array.from(c.values, (v, r) => (failed[r] ? NaN : v));
  const noValue = (c) => okValues(c).every((v) => !Number.isFinite(v));

  for (const c of results) {
    if (noValue(c)) {
      plots.append(el('p', { class: 'sweep-note', text: `${c.name}: no run has a finite value (${data.failures} failed; the others give NaN, e.g. an event that did not happen), nothing to plot.` }));
      continue;
    }
    const yv = okValues(c);
    if (layout.kind === 'grid' && layout.axes.length === 1) {
      const x = swept[0];
      const order = Array.from({ length: runs }, (_, r) => r).sort((a, b) => x.values[a] - x.values[b]);
      const layers = [
        { kind: 'line', x: order.map((r) => x.values[r]), y: order.map((r) => yv[r]), colour: kColour },
        { kind: 'points', x: Array.from(x.values), y: yv, runs: Array.from(runOf), rows: Array.from({ length: runs }, (_, r) => r), colour: kColour },
      ];
      if (failedRuns.length) layers.push(crosses(x));
      add(new Figure({ name: c.name, title: `${c.name} against ${x.name}`, xLabel: withUnit(x.name, x.unit), yLabel: withUnit(c.name, c.unit),
        xRange: range(x.values), yRange: range(yv), layers }), (hit) => runText(hit.layer.rows[hit.index], c));
    } else if (layout.kind === 'grid' && layout.axes.length === 2) {
      const [ax, ay] = layout.axes;
      const [cx, cy] = swept;
      const n = runs;
      const cell = new Array(n).fill(-1);  // the run of each cell (x slowest, as the grid runs)
      const ix = new Map(ax.values.map((v, i) => [v, i]));
      const iy = new Map(ay.values.map((v, i) => [v, i]));
      for (let r = 0; r < n; r += 1) cell[ix.get(cx.values[r]) * ay.values.length + iy.get(cy.values[r])] = r;
      const values = cell.map((r) => yv[r]);
      const [lo, hi] = range(values, 0);
      const xr = range(ax.values, 0);
      const yr = range(ay.values, 0);
      const fig = new Figure({
        name: c.name, title: `${c.name} over ${cx.name} and ${cy.name}`, xLabel: withUnit(cx.name, cx.unit), yLabel: withUnit(cy.name, cy.unit),
        xRange: spanOf(ax.values, xr), yRange: spanOf(ay.values, yr), colourBar: { range: [lo, hi], label: withUnit(c.name, c.unit) },
        layers: [{ kind: 'cells', xs: ax.values, ys: ay.values, values, runs: cell.map((r) => runOf[r]), rows: cell, failed: cell.map((r) => failed[r]) }],
      });
      // a legend entry for the crosses the cells of failed runs carry
      if (failedRuns.length) fig.spec.layers.push({ kind: 'crosses', x: [], y: null, colour: kFailedColour, label: 'failed run' });
      add(fig, (hit) => runText(hit.layer.rows[hit.index], c));
    } else {
      const h = histogram(yv);
      const binned = h.counts.reduce((a, b) => a + b, 0);
      // a failed run has no value to bin: the title counts it and the legend marks it
      const failedNote = failedRuns.length ? `, ${failedRuns.length} failed` : '';
      const layers = [{ kind: 'bars', edges: h.edges, counts: h.counts, colour: kColour }];
      if (failedRuns.length) layers.push({ kind: 'crosses', x: [], y: null, colour: kFailedColour, label: `${failedRuns.length} failed run${failedRuns.length === 1 ? '' : 's'} (no value, not binned)` });
      const fig = new Figure({ name: `${c.name}-histogram`, title: `${c.name}: ${binned} runs${failedNote}`, xLabel: withUnit(c.name, c.unit), yLabel: 'runs',
        xRange: [h.edges[0], h.edges[h.edges.length - 1]], yRange: [0, Math.max(...h.counts) * 1.08 || 1],
        layers });
      fig.bins = h;
      add(fig, (hit) => `${num(h.edges[hit.index])} \u2264 ${c.name} ${hit.index === h.counts.length - 1 ? '\u2264' : '<'} ${num(h.edges[hit.index + 1])}${c.unit ? ` ${c.unit}` : ''}: ${h.counts[hit.index]} runs`);
      for (const x of swept) {
        const layers = [{ kind: 'points', x: Array.from(x.values), y: yv, runs: Array.from(runOf), rows: Array.from({ length: runs }, (_, r) => r), colour: kColour, radius: runs > 2000 ? 1.5 : 2.5 }];
        if (failedRuns.length) layers.push(crosses(x));
        add(new Figure({ name: `${c.name}-vs-${x.name}`, title: `${c.name} against ${x.name}`, xLabel: withUnit(x.name, x.unit), yLabel: withUnit(c.name, c.unit),
          xRange: range(x.values), yRange: range(yv), layers }), (hit) => runText(hit.layer.rows[hit.index], c));
      }
    }
  }
  return { data, columns, figures, failed };
}

// the extent of a heatmap's axis: its cells' outer edges
function spanOf(values, [lo, hi]) {
  if (values.length === 1) {
    const d = values[0] === 0 ? 0.5 : Math.abs(values[0]) * 0.05;
    return [values[0] - d, values[0] + d];
  }
  const sorted = [...values].sort((a, b) => a - b);
  return [lo - (sorted[1] - sorted[0]) / 2, hi + (sorted[sorted.length - 1] - sorted[sorted.length - 2]) / 2];
}
