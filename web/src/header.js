// The header of the page: the scene, its parameters, the integrator and its step statistics,
// the conservation summary, the equations of motion (KaTeX, typeset lazily: equations.js), every
// body's inertia and the size rule of the page's data.
import { buildEquations } from './equations.js';
import { el, num, table, vec } from './format.js';

const kDiagnosticUnits = [
  [/^energy|^jacobi/, 'J'],
  [/L_norm|L_vertical/, 'kg·m²/s'],
  [/^p_/, ''],
];

function diagnosticUnit(name) {
  for (const [re, unit] of kDiagnosticUnits) if (re.test(name)) return unit;
  return '';
}

function inertiaMatrix(I) {
  return el('span', { class: 'matrix' }, ...I.map((row) => el('span', { text: row.map((x) => num(x)).join('  ') })));
}

// the page's size from its three big parts (data, script, style): serialising the whole page
// (outerHTML) to measure it takes seconds for a large one
function pageLength() {
  let n = 0;
  for (const e of document.querySelectorAll('script, style')) n += e.textContent.length;
  return n;
}

/** Builds the header into `root`; returns {equationsTypeset} (see buildEquations). */
export function buildHeader(report, root) {
  const h = el('header', { class: 'report-header' });
  const s = report.scene ?? {};
  h.append(el('h1', {}, `rigid — ${s.name ?? 'run'}`), el('p', { class: 'file', text: s.file ?? '' }));
  // the scene's metrics, first thing under the title: name = value unit (or why there is none)
  const metrics = report.metrics ?? [];
  if (metrics.length) {
    h.append(el('p', { class: 'metrics' }, ...metrics.map((m) => el('span', {
      class: 'metric',
      'data-name': m.name,
      title: m.note || (m.instant ? 'marked on the plots' : ''),
      text: m.value === null || m.value === undefined
        ? `${m.name}: none${m.note ? ` (${m.note})` : ''}`
        : `${m.name} = ${num(m.value, 6)}${m.unit ? ` ${m.unit}` : ''}`,
    }))));
  }
  if (s.description) h.append(el('pre', { class: 'description', text: s.description }));

  const cards = el('div', { class: 'cards' });
  const it = report.integrator ?? {};
  const stats = [
    ['method', it.method],
    ['dt', it.dt ? `${num(it.dt)} s` : null],
    ['tolerance', it.tolerance ? num(it.tolerance) : null],
    ['t_end', it.t_end !== undefined ? `${num(it.t_end)} s` : null],
    ['steps', it.steps],
    ['samples', it.samples],
    ['rhs evaluations', it.rhs_evaluations || null],
    ['wall time', it.wall_time_s !== undefined ? `${num(it.wall_time_s, 3)} s` : null],
  ].filter(([, v]) => v !== null && v !== undefined);
  cards.append(el('section', {}, el('h2', { text: 'Integrator' }),
    table(['', ''], stats.map(([k, v]) => [k, String(v)]), 'kv')));

  const params = report.parameters ?? [];
  if (params.length) {
    cards.append(el('section', {}, el('h2', { text: 'Parameters' }),
      table(['name', 'value', 'unit'], params.map((p) => [p.name, num(p.value), p.unit || '—']))));
  }

  const diag = Object.entries(report.diagnostics ?? {});
  if (diag.length) {
    cards.append(el('section', {}, el('h2', { text: 'Conservation' }),
      table(['quantity', 'value', 'unit'],
        diag.map(([k, v]) => [k, typeof v === 'number' ? num(v, 4) : String(v), diagnosticUnit(k) || '—']))));
  }
  h.append(cards);
  const warnings = report.warnings ?? [];
  if (warnings.length) {
    h.append(el('section', { class: 'warnings' }, el('h2', { text: 'Warnings' }),
      el('ul', {}, ...warnings.map((w) => el('li', { text: String(w) })))));
  }

  let equationsTypeset = () => Promise.resolve();
  if (report.equations_latex) {
    const eq = buildEquations(report.equations_latex);
    h.append(el('section', {}, el('h2', { text: 'Equations of motion' }), eq.box));
    equationsTypeset = eq.typeset;
  }

  const bodies = report.bodies ?? [];
  if (bodies.length) {
    h.append(el('section', {}, el('h2', { text: 'Bodies (inertia about the COM, body frame)' }),
      table(['body', 'shape', 'mass (kg)', 'COM (m)', 'I_com (kg·m²)', 'principal moments (kg·m²)', 'principal axes (columns)'],
        bodies.map((b) => [
          b.name + (b.free ? ' (free)' : ''),
          // what the 3D view draws for a body of no known shape (view3d.js)
          b.shape?.kind === 'inertia_only' || !b.shape
            ? (b.free ? 'box of equal inertia' : 'ellipsoid of equal inertia')
            : b.shape.kind,
          num(b.mass),
          vec(b.com),
          inertiaMatrix(b.inertia_com),
          vec(b.principal_moments),
          inertiaMatrix([0, 1, 2].map((r) => b.principal_axes.map((axis) => axis[r]))),
        ]), 'bodies')));
  }

  const f = report.frames ?? {};
  const size = report.size ?? {};
  const rule = f.rule ?? '';
  const note = size.bytes_note ?? '';
  h.append(el('p', { class: 'size-rule' },
    // the writer's note may already state the rule: then it is said once
    `Data: ${f.count} frames; ` + (note.includes(rule) ? note : [rule, note].filter((x) => x).join('; ')) +
    `. Page: about ${num(pageLength() / 1e6, 3)} MB.`));
  root.append(h);
  return { equationsTypeset };
}
