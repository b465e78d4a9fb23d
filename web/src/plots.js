// The plots (uPlot), one per group of series: coordinates, velocities, the relative energy and
// |L| errors (log scale), multipliers, residuals, other. Click a legend entry to hide or show a
// series; the cursor follows the page's time, and a click in a plot moves the time there.
import uPlot from 'uplot';
import { decodeArray } from './data.js';
import { el } from './format.js';

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

function width(box) {
  return Math.max(320, Math.floor(box.getBoundingClientRect().width || 800) - 4);
}

export function buildPlots(report, ts, player, root) {
  const plots = {};
  const section = el('section', { class: 'plots' }, el('h2', { text: 'Plots' }));
  root.append(section);
  const x = Array.from(ts);
  const series = report.series ?? [];
  for (const [group, title, log] of kGroups) {
    const members = series.filter((s) => s.group === group);
    if (!members.length) continue;
    const box = el('div', { class: 'plot', 'data-group': group });
    section.append(el('h3', { text: title }), box);
    const data = [x];
    for (const s of members) {
      const v = Array.from(decodeArray(s.values));
      if (v.length !== x.length) throw new Error(`series ${s.name}: ${v.length} values for ${x.length} frames`);
      // a log scale cannot show 0 (an exact conservation at that frame): left as a gap
      data.push(log ? v.map((y) => (y > 0 ? y : null)) : v);
    }
    const units = [...new Set(members.map((s) => s.unit).filter((u) => u))];
    const opts = {
      width: width(section),
      height: 220,
      scales: { x: { time: false }, y: log ? { distr: 3 } : {} },
      axes: [{ label: 't (s)' }, {
        label: units.join(', '),
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
    plots[group] = u;
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
