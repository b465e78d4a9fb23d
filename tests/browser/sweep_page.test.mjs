// The page of a sweep (rigid sweep --report) in a real browser: a 1-D grid, a 2-D grid and a
// sample of the physical pendulum, each with failing runs (a mass of 0 or less). No console
// error and nothing loaded; the heatmap is painted and the value the cursor reads over a cell is
// runs.csv's; a failed cell reads its error; the histogram's bins add up to the runs that
// succeeded; the failed runs are listed and drawn as crosses; the downloads are an SVG that
// parses and a PNG that decodes.
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { after, before, describe, test } from 'node:test';
import { launch, openPage, pixelStats, rigidExe, root, samplePages, screenshotPath } from './support.mjs';

const skip = samplePages && 'the sweep page is written by rigid itself';
const short = ['--set', 'simulation.t_end=0.02', '--set', 'simulation.output_dt=0.01', '--set', 'simulation.tolerance=1e-6'];

function sweepPage(args) {
  const dir = mkdtempSync(join(tmpdir(), 'rigid-sweep-'));
  execFileSync(rigidExe, ['sweep', join(root, 'examples', 'physical_pendulum.toml'), ...args, ...short, '-o', dir, '-q', '--report'],
    { stdio: ['ignore', 'ignore', 'inherit'] });
  return dir;
}

// runs.csv as {header, rows: [[cells]]}: numbers, then the error, last, whole (RFC 4180 quotes
// undone; these sweeps' errors hold no line break)
function runsCsv(dir) {
  const lines = readFileSync(join(dir, 'runs.csv'), 'utf8').trim().split('\n');
  const header = lines[0].split(',');
  const rows = lines.slice(1).map((l) => {
    const cells = l.split(',');
    let error = cells.slice(header.length - 1).join(',');
    if (error.startsWith('"')) error = error.slice(1, -1).replace(/""/g, '"');
    return [...cells.slice(0, header.length - 1), error];
  });
  return { header, rows };
}

async function download(page, button) {
  const [d] = await Promise.all([page.waitForEvent('download'), button.click()]);
  return { name: d.suggestedFilename(), bytes: readFileSync(await d.path()) };
}

async function parseSvg(page, text) {
  return page.evaluate((t) => {
    const doc = new DOMParser().parseFromString(t, 'image/svg+xml');
    const err = doc.querySelector('parsererror');
    return { error: err ? err.textContent : null, root: doc.documentElement.localName, rects: doc.querySelectorAll('rect').length };
  }, text);
}

let browser;
before(async () => { browser = await launch(); });
after(async () => { await browser?.close(); });

describe('sweep page: a 2-D grid as heatmaps', { skip }, () => {
  let page;
  let problems;
  let dir;
  before(async () => {
    dir = sweepPage(['--grid', 'L=0.5:2:6', '--grid', 'm=1:-0.25:6']);
    ({ page, problems } = await openPage(browser, join(dir, 'report.html')));
  });
  after(async () => { await page?.close(); });

  test('the heatmap canvas is painted', async () => {
    const stats = await page.evaluate(() => {
      const c = window.rigidReport.sweep.figures.energy_initial.canvas;
      const px = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
      const colours = new Set();
      let notWhite = 0;
      for (let i = 0; i < px.length; i += 4) {
        if (px[i] < 250 || px[i + 1] < 250 || px[i + 2] < 250) notWhite += 1;
        colours.add((px[i] >> 4) << 8 | (px[i + 1] >> 4) << 4 | (px[i + 2] >> 4));
      }
      return { share: notWhite / (px.length / 4), colours: colours.size };
    });
    // the cells fill most of the plot area (about 60 % of the canvas)
    assert.ok(stats.share > 0.3 && stats.colours > 10, JSON.stringify(stats));
    await page.locator('.sweep-figure[data-name=energy_initial] canvas').screenshot({ path: screenshotPath('sweep_heatmap.png') });
  });

  test('the cursor over a cell reads runs.csv', async () => {
    const { header, rows } = runsCsv(dir);
    const col = header.indexOf('energy_initial');
    const axes = await page.evaluate(() => window.rigidReport.sweep.data.layout.axes.map((a) => a.values));
    assert.deepEqual(axes, [[0.5, 0.8, 1.1, 1.4, 1.7, 2], [1, 0.75, 0.5, 0.25, 0, -0.25]]);
    let checked = 0;
    for (const [i, j] of [[0, 0], [2, 1], [5, 3], [3, 4], [1, 5]]) {
      const [x, y] = await page.evaluate(([a, b]) => window.rigidReport.sweep.figures.energy_initial.toClient(a, b), [axes[0][i], axes[1][j]]);
      await page.mouse.move(x, y);
      const readout = page.locator('.sweep-figure[data-name=energy_initial] .sweep-readout');
      const text = await readout.textContent();
      const run = Number(await readout.getAttribute('data-run'));
      // the grid runs x slowest: run = i · 6 + j
      assert.equal(run, i * 6 + j);
      const row = rows[run];
      assert.equal(Number(row[header.indexOf('L')]), axes[0][i]);
      if (row[row.length - 1]) {
        assert.ok(text.includes('failed: ') && text.includes(row[row.length - 1]), text);
      } else {
        const m = /energy_initial = (\S+)/.exec(text);
        assert.ok(m, text);
        assert.equal(Number(m[1]), Number(row[col]), text);
        checked += 1;
      }
    }
    assert.ok(checked >= 3);
  });

  test('the failed runs are listed by message', async () => {
    const { rows } = runsCsv(dir);
    const failed = rows.filter((r) => r[r.length - 1]).length;
    assert.equal(failed, 12);
    const counts = await page.locator('.sweep-failures li').evaluateAll((lis) => lis.map((li) => Number(li.dataset.count)));
    assert.equal(counts.reduce((a, b) => a + b, 0), failed);
    assert.match(await page.locator('.sweep-failures').textContent(), /mass must be positive/);
  });

  test('a heatmap downloads as an SVG that parses and a PNG that decodes', async () => {
    const box = page.locator('.sweep-figure[data-name=energy_initial]');
    const svg = await download(page, box.locator('button[data-format=svg]'));
    assert.match(svg.name, /\.svg$/);
    const parsed = await parseSvg(page, svg.bytes.toString('utf8'));
    assert.equal(parsed.error, null);
    assert.equal(parsed.root, 'svg');
    assert.ok(parsed.rects >= 36, `${parsed.rects} rects: a cell each`);
    const png = await download(page, box.locator('button[data-format=png]'));
    assert.deepEqual([...png.bytes.subarray(0, 8)], [0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]);
    const stats = await pixelStats(page, png.bytes);
    assert.ok(stats.notBackground > 0.1 && stats.colours > 10, JSON.stringify(stats));
    assert.deepEqual(problems, []);
  });
});

describe('sweep page: a sample as histograms and scatter plots', { skip }, () => {
  let page;
  let problems;
  let dir;
  before(async () => {
    dir = sweepPage(['--sample', 'm=uniform(-0.2,1)', '--sample', 'L=uniform(0.5,2)', '-n', '200', '--seed', '3']);
    ({ page, problems } = await openPage(browser, join(dir, 'report.html')));
  });
  after(async () => { await page?.close(); });

  test('each histogram\'s bins add up to the runs that succeeded', async () => {
    const { rows } = runsCsv(dir);
    const succeeded = rows.filter((r) => !r[r.length - 1]).length;
    assert.ok(succeeded > 100 && succeeded < 200, `${succeeded}`);
    const sums = await page.evaluate(() => Object.fromEntries(Object.entries(window.rigidReport.sweep.figures)
      .filter(([, f]) => f.bins).map(([n, f]) => [n, f.bins.counts.reduce((a, b) => a + b, 0)])));
    for (const name of ['energy_initial-histogram', 'energy_final-histogram']) assert.equal(sums[name], succeeded, name);
    // the failed runs, which have no value to bin, are counted in the title and marked in the legend
    const failed = rows.length - succeeded;
    const marks = await page.evaluate(() => {
      const f = window.rigidReport.sweep.figures['energy_initial-histogram'];
      return { title: f.spec.title, labels: f.spec.layers.filter((l) => l.kind === 'crosses').map((l) => l.label) };
    });
    assert.match(marks.title, new RegExp(`: ${succeeded} runs, ${failed} failed$`));
    assert.deepEqual(marks.labels, [`${failed} failed runs (no value, not binned)`]);
  });

  test('scatter plots against each input, the failed runs as crosses, the statistics', async () => {
    const { rows } = runsCsv(dir);
    const failed = rows.filter((r) => r[r.length - 1]).length;
    const figs = await page.evaluate(() => Object.fromEntries(Object.entries(window.rigidReport.sweep.figures)
      .map(([n, f]) => [n, f.spec.layers.map((l) => [l.kind, l.x ? l.x.length : l.counts.length])])));
    assert.deepEqual(figs['energy_initial-vs-m'], [['points', 200], ['crosses', failed]]);
    assert.deepEqual(figs['energy_initial-vs-L'], [['points', 200], ['crosses', failed]]);
    const head = await page.locator('table.sweep-statistics th').allTextContents();
    assert.deepEqual(head, ['column', 'count', 'mean', 'std', 'min', '5 %', '25 %', 'median', '75 %', '95 %', 'max']);
    const first = await page.locator('table.sweep-statistics tbody tr').first().locator('td').allTextContents();
    assert.equal(first[0], 'm');
    assert.equal(Number(first[1]), 200 - failed);
    const svg = await download(page, page.locator('.sweep-figure[data-name="energy_initial-histogram"] button[data-format=svg]'));
    const parsed = await parseSvg(page, svg.bytes.toString('utf8'));
    assert.equal(parsed.error, null);
    assert.equal(parsed.root, 'svg');
    await page.screenshot({ path: screenshotPath('sweep_sample.png'), fullPage: false });
    assert.deepEqual(problems, []);
  });
});

describe('sweep page: a 1-D grid as lines', { skip }, () => {
  test('a line and points per result, failed runs as crosses, an SVG download', async () => {
    const dir = sweepPage(['--grid', 'm=1:-1:9']);
    const { page, problems } = await openPage(browser, join(dir, 'report.html'));
    const layers = await page.evaluate(() => window.rigidReport.sweep.figures.energy_initial.spec.layers
      .map((l) => [l.kind, l.x.length, l.label ?? '']));
    // m = 0, -0.25, …, -1 fail: five runs
    assert.deepEqual(layers, [['line', 9, ''], ['points', 9, ''], ['crosses', 5, 'failed run']]);
    const label = await page.evaluate(() => window.rigidReport.sweep.figures.energy_initial.spec.xLabel);
    assert.equal(label, 'm');
    const svg = await download(page, page.locator('.sweep-figure[data-name=energy_initial] button[data-format=svg]'));
    const text = svg.bytes.toString('utf8');
    const parsed = await parseSvg(page, text);
    assert.equal(parsed.error, null);
    assert.equal(parsed.root, 'svg');
    assert.ok(text.includes('>m<') && text.includes('energy_initial (J)'));
    assert.deepEqual(problems, []);
    await page.close();
  });
});
