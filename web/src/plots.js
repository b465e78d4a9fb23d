// The plots (uPlot), one per group of series: coordinates, velocities, the relative energy and
// |L| errors (log scale), multipliers, residuals, other. Click a legend entry to hide or show a
// series; the cursor follows the page's time, and a click in a plot moves the time there.
import uPlot from 'uplot';
import { decodeArray } from './data.js';
import { el, num, saveDataUrl } from './format.js';
import { plotPng, plotSvg } from './plot_export.js';

const kGroups = [
  ['coordinates', 'Coordinates', false],
  ['velocities', 'Velocities', false],
  // the series' names say relative or absolute (the latter when the initial value is 0)
  ['energy_error', 'Energy error (log scale)', true],
  ['L_error', '|L| error (log scale)', true],
  ['multipliers', 'Multipliers (constraint forces)', false],
  ['residuals', 'Constraint residuals', false],
  ['other', 'Other', false],
];

const kColours = ['#1f77b4', '#d62728', '#2ca02c', '#ff7f0e', '#9467bd', '#8c564b', '#e377c2', '#17becf', '#7f7f7f', '#bcbd22'];

const decade = (v) => (v === null || v === undefined ? '' : v === 0 ? '0' : v.toExponential(0));
// uPlot's own labels round small ticks to 0 (1e-5 J shows as "0"): 3 significant digits instead
const tick = (v) => {
  if (v === null || v === undefined) return '';
  const a = Math.abs(v);
  if (a === 0) return '0';
  return a < 1e-3 || a >= 1e5 ? v.toExponential(1) : String(Number(v.toPrecision(3)));
};

// what an axis measures, from the series' quantities (the run's schema) and units; a
// coordinate's unit is "" when the scene does not say whether it is a length or an angle
const kQuantityWords = {
  coordinate: ['coordinate', 'm or rad'],
  coordinate_rate: ['coordinate rate', 'm/s or rad/s'],
  velocity: ['velocity', 'm/s'],
  angular_velocity: ['angular velocity', 'rad/s'],
  angular_momentum: ['angular momentum', 'kg·m²/s'],
  energy: ['energy', 'J'],
  jacobi: ['Jacobi integral', 'J'],
  multiplier: ['multiplier', ''],
  velocity_multiplier: ['multiplier', ''],
  constraint_residual: ['residual', ''],
  velocity_constraint_residual: ['residual', ''],
  conjugate_momentum: ['conjugate momentum', ''],
  relative_change: ['relative change', ''],
  energy_change: ['change', 'J'],
  angular_momentum_change: ['change', 'kg·m²/s'],
};

/** The y axis label of a plot of `members`: quantities and units, "1" when dimensionless. */
export function axisLabel(members) {
  const words = [...new Set(members.map((s) => (kQuantityWords[s.quantity] ?? [s.quantity ?? 'value'])[0]))];
  const units = [...new Set(members.map((s) => s.unit || (kQuantityWords[s.quantity] ?? [])[1] || '1'))];
  return `${words.join(', ')} (${units.join(', ')})`;
}

function width(box) {
  return Math.max(320, Math.floor(box.getBoundingClientRect().width || 800) - 4);
}

export function buildPlots(report, ts, player, root) {
  const plots = {};
  const section = el('section', { class: 'plots' }, el('h2', { text: 'Plots' }));
  root.append(section);
  const x = Array.from(ts);
  const series = report.series ?? [];
  // the scene's metrics that are instants (a crossing, the time of an extremum): a dashed
  // vertical line on every plot
  const marks = (report.metrics ?? []).filter((m) => m.instant && Number.isFinite(m.value))
    .map((m) => ({ t: m.value, label: `${m.name} = ${num(m.value, 5)} s` }));
  for (const [group, title, log] of kGroups) {
    const members = series.filter((s) => s.group === group);
    if (!members.length) continue;
    const box = el('div', { class: 'plot', 'data-group': group });
    const png = el('button', { type: 'button', class: 'download', 'data-format': 'png', title: 'this plot as a PNG image', text: 'PNG' });
    const svg = el('button', { type: 'button', class: 'download', 'data-format': 'svg', title: 'this plot as an SVG drawing', text: 'SVG' });
    section.append(el('h3', {}, title, ' ', png, svg), box);
    const data = [x];
    for (const s of members) {
      const v = Array.from(decodeArray(s.values));
      if (v.length !== x.length) throw new Error(`series ${s.name}: ${v.length} values for ${x.length} frames`);
      // a log scale cannot show 0 (an exact conservation at that frame): left as a gap
      data.push(log ? v.map((y) => (y > 0 ? y : null)) : v);
    }
    const yLabel = axisLabel(members);
    const opts = {
      width: width(section),
      height: 220,
      scales: { x: { time: false }, y: log ? { distr: 3 } : {} },
      axes: [{ label: 't (s)' }, {
        label: yLabel,
        size: 70,
        // a log axis labels its decades as 1e-14, not as rounded zeros
        values: (self, ticks) => ticks.map(log ? decade : tick),
      }],
      cursor: {
        drag: { x: true, y: false },
        points: { size: 6 },
        // the page's time sits between pixels: the cursor takes its frame, not the nearest pixel's
        dataIdx: (self, seriesIdx, closestIdx) => (self.rigidForcedIdx ?? closestIdx),
        move: (self, left, top) => [left, top],
      },
      legend: { live: true },
      hooks: {
        draw: [(self) => {
          const g = self.ctx;
          const r = devicePixelRatio || 1;
          g.save();
          g.strokeStyle = '#555';
          g.fillStyle = '#333';
          g.lineWidth = r;
          g.setLineDash([5 * r, 4 * r]);
          g.font = `${Math.round(11 * r)}px sans-serif`;
          for (const mk of marks) {
            const px = self.valToPos(mk.t, 'x', true);
            if (!(px >= self.bbox.left && px <= self.bbox.left + self.bbox.width)) continue;
            g.beginPath();
            g.moveTo(px, self.bbox.top);
            g.lineTo(px, self.bbox.top + self.bbox.height);
            g.stroke();
            g.fillText(mk.label, px + 4 * r, self.bbox.top + 12 * r);
          }
          g.restore();
        }],
      },
      series: [
        { label: 't (s)' },
        ...members.map((s, i) => ({
          label: s.unit ? `${s.name} (${s.unit})` : s.name,
          stroke: kColours[i % kColours.length],
          width: 1.25,
          spanGaps: false,
          value: (u, v) => (v === null || v === undefined ? '—' : v.toPrecision(7)),
        })),
      ],
    };
    const u = new uPlot(opts, data, box);
    u.rigidSeries = members.map((s) => ({ name: s.name, column: s.column ?? null, unit: s.unit ?? '' }));
    u.rigidMarks = marks;
    u.rigidYLabel = yLabel;
    plots[group] = u;
    const name = `${report.scene?.name ?? 'rigid'}-${group}`;
    const legend = () => opts.series.slice(1).map((s, i) => ({ label: s.label, colour: s.stroke, shown: u.series[i + 1].show }))
      .filter((s) => s.shown);
    png.addEventListener('click', () => saveDataUrl(plotPng(u, title, legend()), `${name}.png`));
    svg.addEventListener('click', () => {
      const shown = opts.series.slice(1).map((s, i) => ({ label: s.label, colour: s.stroke, values: data[i + 1] }))
        .filter((s, i) => u.series[i + 1].show);
      const text = plotSvg({
        title,
        xLabel: 't (s)',
        yLabel,
        log,
        x,
        series: shown,
        xRange: [u.scales.x.min, u.scales.x.max],
        yRange: [u.scales.y.min, u.scales.y.max],
        marks,
      });
      const url = URL.createObjectURL(new Blob([text], { type: 'image/svg+xml' }));
      saveDataUrl(url, `${name}.svg`);
      setTimeout(() => URL.revokeObjectURL(url), 10000);
    });
    u.over.addEventListener('click', () => {
      if (u.cursor.idx !== null && u.cursor.idx !== undefined) player.setIndex(u.cursor.idx);
    });
    // when the mouse leaves, the cursor goes back to the page's time
    u.over.addEventListener('mouseleave', () => requestAnimationFrame(() => placeCursor(u, player.index)));
  }
  const follow = (i) => { for (const u of Object.values(plots)) placeCursor(u, i); };
  player.onChange(follow);
  window.addEventListener('resize', () => {
    for (const u of Object.values(plots)) u.setSize({ width: width(section), height: 220 });
    follow(player.index);
  });
  follow(player.index);
  return plots;
}

function placeCursor(u, i) {
  const left = u.valToPos(u.data[0][i], 'x');
  u.rigidForcedIdx = i;
  u.setCursor({ left, top: u.over.clientHeight / 2 });
  u.rigidForcedIdx = null;
}
