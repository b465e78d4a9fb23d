// Entry of the report page: reads the run's data from the JSON script element and builds the
// page (header, 3D view, plots) into document.body. For tests and scripts it exposes
// window.rigidReport = {setTime(t), time(), ready, plots: {group: uPlot}, equationsTypeset()}
// (a sweep's page, sweep_page.js: {ready, sweep: {data, columns, figures}}):
// `ready` resolves once the page is built and drawn; the equations are typeset after it, a few
// at a time (equations.js), and equationsTypeset() resolves when every open block's are.
import { decodeArray, readReport } from './data.js';
import { el } from './format.js';
import { buildHeader } from './header.js';
import { Player } from './player.js';
import { buildPlots } from './plots.js';
import { buildView } from './view3d.js';
import { buildSweepPage } from './sweep_page.js';

function main() {
  const api = { plots: {} };
  let resolveReady;
  let rejectReady;
  api.ready = new Promise((res, rej) => { resolveReady = res; rejectReady = rej; });
  window.rigidReport = api;
  try {
    const data = document.getElementById('rigid-report-data');
    // a sweep's page (its data begin {"rigid_sweep_page":…}) or a run's
    if (data && /^\s*\{"rigid_sweep_page"/.test(data.textContent)) {
      api.sweep = buildSweepPage(JSON.parse(data.textContent), document.body);
      requestAnimationFrame(() => requestAnimationFrame(() => resolveReady()));
      return;
    }
    const report = readReport(data ? data.textContent : null);
    const ts = decodeArray(report.frames.t);
    const page = el('main', { class: 'rigid-report' });
    document.body.append(page);
    const header = buildHeader(report, page);
    api.equationsTypeset = header.equationsTypeset;
    const stage = el('section', { class: 'stage' }, el('h2', { text: 'Motion' }));
    page.append(stage);
    const player = new Player(ts, stage);
    api.setTime = (t) => player.setTime(t);
    api.time = () => player.time();
    try {
      api.view = buildView(report, player, stage);
    } catch (e) {
      // without WebGL (disabled, or no GPU and no software fallback) the rest of the page stands
      stage.append(el('p', { class: 'fatal', text: `The 3D view could not start: ${String(e.message).replace(/\.+$/, "")}. The header and the plots below are complete; open the page in a browser with WebGL to see the motion.` }));
    }
    api.plots = buildPlots(report, ts, player, page);
    requestAnimationFrame(() => requestAnimationFrame(() => resolveReady()));
  } catch (e) {
    document.body.append(el('pre', { class: 'fatal', text: `rigid report: ${e.message}` }));
    rejectReady(e);
    throw e;
  }
}

main();
