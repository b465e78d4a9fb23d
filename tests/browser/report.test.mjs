// The report page in a real browser (Debian's chromium via playwright-core): it loads from
// file:// with no console error and no network request, draws the bodies, follows the time
// slider, and its plots show trajectory.csv's values at the cursor.
import assert from 'node:assert/strict';
import { readFileSync, statSync } from 'node:fs';
import { join } from 'node:path';
import { after, before, describe, test } from 'node:test';
import { launch, openPage, pixelStats, readCsv, screenshotPath, writeReport } from './support.mjs';

// float32 rounding to nearest: |f32(x) − x| ≤ 2⁻²⁴ |x| (half an ulp), plus the smallest
// normal float32 for values that underflow
const kF32Rel = 2 ** -24;
const kF32Abs = 1.2e-38;

function nearF32(got, want) {
  return Math.abs(got - want) <= kF32Rel * Math.abs(want) + kF32Abs;
}

const cases = [
  {
    scene: 'examples/tennis_racket.toml',
    name: 'tennis_racket',
    // free body: ω in the velocities, energy and |L| errors on a log scale
    expected: { velocities: ['racket.wx', 'racket.wy', 'racket.wz'] },
    logPlots: ['energy_error', 'L_error'],
    maxBytes: 2e6,
  },
  {
    scene: 'examples/double_pendulum.toml',
    name: 'double_pendulum',
    expected: { coordinates: ['theta1', 'theta2'], velocities: ['theta1_dot', 'theta2_dot'] },
    logPlots: ['energy_error'],
    maxBytes: 2e6,
  },
];

let browser;
before(async () => { browser = await launch(); });
after(async () => { await browser?.close(); });

for (const c of cases) {
  describe(c.name, () => {
    let dir;
    let html;
    let page;
    let problems;
    before(async () => {
      dir = writeReport(c.scene);
      html = join(dir, 'report.html');
      ({ page, problems } = await openPage(browser, html));
    });
    after(async () => { await page?.close(); });

    test('is one small file that references nothing on the network', () => {
      const bytes = statSync(html).size;
      assert.ok(bytes <= c.maxBytes, `report.html is ${bytes} B, more than ${c.maxBytes} B`);
      const text = readFileSync(html, 'utf8');
      // namespace strings such as "http://www.w3.org/2000/svg" are not resources; these are
      const resource = /(?:\bsrc|\bhref)\s*=\s*["']?\s*(?:https?:)?\/\/|url\(\s*["']?\s*(?:https?:)?\/\/|@import/i.exec(text);
      assert.equal(resource, null, `report.html references a resource: ${resource?.[0]}`);
    });

    test('loads from file:// with no console error and no request', async () => {
      await page.waitForTimeout(200);
      assert.deepEqual(problems, []);
      const title = await page.title();
      assert.ok(title.startsWith('rigid — '), `title: ${title}`);
      // the equations, when the run has them, are typeset (after `ready`, when the page is
      // idle): KaTeX output and no fallback source; these scenes' blocks are short, none collapsed
      const eq = await page.evaluate(async () => {
        await window.rigidReport.equationsTypeset();
        return {
          latex: JSON.parse(document.getElementById('rigid-report-data').textContent).equations_latex,
          typeset: document.querySelectorAll('.equations .katex').length,
          pending: document.querySelectorAll('.equations .pending').length,
          collapsed: document.querySelectorAll('.equations details').length,
          failed: [...document.querySelectorAll('.equations .note, .equations .katex-error')].map((e) => e.textContent),
        };
      });
      if (eq.latex) {
        assert.ok(eq.typeset >= 1, 'the equations were not typeset');
        assert.equal(eq.pending, 0);
        assert.equal(eq.collapsed, 0);
        assert.deepEqual(eq.failed, []);
      }
    });

    test('the 3D view is drawn and the time slider changes the frame', async () => {
      const canvas = page.locator('canvas').first();
      await page.evaluate(() => window.rigidReport.setTime(0));
      await page.waitForTimeout(100);
      const first = await canvas.screenshot();
      const stats = await pixelStats(page, first);
      // a blank canvas is one colour; the bodies, grid and arrows make many and cover > 1 %
      assert.ok(stats.colours > 10 && stats.notBackground > 0.01, `canvas looks blank: ${JSON.stringify(stats)}`);

      // a click at 60 % of the slider: a user moving it
      const slider = page.locator('input.time-slider');
      const box = await slider.boundingBox();
      await page.mouse.click(box.x + 0.6 * box.width, box.y + box.height / 2);
      await page.waitForTimeout(150);
      const t = await page.evaluate(() => window.rigidReport.time());
      assert.ok(t > 0, `time after moving the slider: ${t}`);
      const second = await canvas.screenshot();
      const diff = await pixelStats(page, first, second);
      // the bodies moved: more than 0.2 % of the pixels changed
      assert.ok(diff.changed > 0.002, `the frame did not change: ${JSON.stringify(diff)}`);

      // keys: → and ← step one frame (the slider has the focus: it must not step twice)
      const frame = () => page.evaluate(() => {
        const ts = Object.values(window.rigidReport.plots)[0].data[0];
        return ts.indexOf(window.rigidReport.time());
      });
      const k0 = await frame();
      await page.keyboard.press('ArrowRight');
      assert.equal(await frame(), k0 + 1, '→ steps one frame');
      await page.keyboard.press('ArrowLeft');
      await page.keyboard.press('ArrowLeft');
      assert.equal(await frame(), k0 - 1, '← steps one frame');
      // space plays and pauses
      await page.keyboard.press(' ');
      await page.waitForTimeout(400);
      await page.keyboard.press(' ');
      const k1 = await frame();
      assert.ok(k1 > k0 - 1, `space did not play (frame ${k1})`);
      await page.waitForTimeout(200);
      assert.equal(await frame(), k1, 'space did not pause');
      await page.screenshot({ path: screenshotPath(`${c.name}.png`), fullPage: true });
      await canvas.screenshot({ path: screenshotPath(`${c.name}-3d.png`) });
    });

    test('each plot has its series and the cursor shows trajectory.csv at the time', async () => {
      const csv = readCsv(join(dir, 'trajectory.csv'));
      const tIndex = csv.columns.indexOf('t');
      const info = await page.evaluate(() => {
        const out = {};
        for (const [group, u] of Object.entries(window.rigidReport.plots)) {
          out[group] = { series: u.rigidSeries, labels: u.series.map((s) => s.label), log: u.scales.y.distr === 3 };
        }
        return out;
      });
      for (const [group, columns] of Object.entries(c.expected)) {
        assert.ok(info[group], `no plot '${group}' (plots: ${Object.keys(info)})`);
        const got = info[group].series.map((s) => s.column);
        for (const col of columns) assert.ok(got.includes(col), `plot '${group}' lacks ${col} (has ${got})`);
      }
      for (const group of c.logPlots) {
        assert.ok(info[group], `no plot '${group}' (plots: ${Object.keys(info)})`);
        assert.ok(info[group].log, `plot '${group}' is not on a log scale`);
        assert.ok(info[group].series.length >= 1);
      }

      // a frame about 37 % into the run: not the first, not a round time
      const ts = await page.evaluate(() => window.rigidReport.plots[Object.keys(window.rigidReport.plots)[0]].data[0]);
      const k = Math.floor(0.37 * (ts.length - 1));
      await page.evaluate((t) => window.rigidReport.setTime(t), ts[k]);
      await page.waitForTimeout(50);
      assert.equal(await page.evaluate(() => window.rigidReport.time()), ts[k]);
      // the csv row at that time: the one whose t rounds to the frame's float32 time
      const row = csv.rows.reduce((best, r) => (Math.abs(r[tIndex] - ts[k]) < Math.abs(best[tIndex] - ts[k]) ? r : best));
      assert.ok(nearF32(ts[k], row[tIndex]), `frame time ${ts[k]} is no row's t (nearest ${row[tIndex]})`);

      // the expected value of a series from trajectory.csv's row: the column itself, or for the
      // errors the same double formula as the writer, |x − x(0)| / |x(0)|, or |x − x(0)| when the
      // series says so in its name (the writer's choice when |x(0)| is not larger than the
      // largest change, checked below), so both round the same double to float32
      const at = (r, name) => r[csv.columns.indexOf(name)];
      const expected = (group, column, name) => {
        const source = (r) => {
          if (group === 'L_error' && column.endsWith('.L')) {
            const b = column.slice(0, -2);
            // the writer's √(x² + y² + z²), in its order: a change of 1e-15 is all rounding, so
            // another formula (Math.hypot) could differ by an ulp and make the comparison fail
            const [x, y, z] = [at(r, `${b}.Lx`), at(r, `${b}.Ly`), at(r, `${b}.Lz`)];
            return Math.sqrt(x * x + y * y + z * z);
          }
          return at(r, column);
        };
        const x = source(row);
        if (x === undefined || Number.isNaN(x)) return undefined;
        if (group !== 'energy_error' && group !== 'L_error') return x;
        const x0 = source(csv.rows[0]);
        const absolute = !name.includes('/');
        // E(0) that is the round-off of 0 (the double pendulum from rest at V = 0) gives the
        // absolute change: a relative one would divide by ~1e-15
        if (group === 'energy_error' && Math.abs(x0) < 1e-12) {
          assert.ok(absolute, `plot '${group}': E(0) = ${x0} J is round-off, but the series is '${name}'`);
        }
        return absolute ? Math.abs(x - x0) : Math.abs(x - x0) / Math.abs(x0);
      };
      let compared = 0;
      // under the cursor: each series' own index (uPlot's cursor.idxs, what its legend shows)
      const under = await page.evaluate(() => Object.fromEntries(Object.entries(window.rigidReport.plots).map(
        ([g, u]) => [g, { idxs: [...u.cursor.idxs], values: u.series.map((s, i) => u.data[i][u.cursor.idxs[i]]) }])));
      for (const [group, { idxs, values }] of Object.entries(under)) {
        idxs.forEach((idx, i) => assert.equal(idx, k, `plot '${group}', series ${i}: cursor at frame ${idx}, the page's time is frame ${k}`));
        info[group].series.forEach((s, i) => {
          const want = s.column ? expected(group, s.column, s.name) : undefined;
          if (want === undefined) return;  // a series with no source in trajectory.csv
          // a log plot leaves an exact 0 as a gap (null)
          const got = values[i + 1] === null && want === 0 && info[group].log ? 0 : values[i + 1];
          assert.ok(nearF32(got, want), `plot '${group}', ${s.name} at t = ${ts[k]}: ${got}, trajectory.csv gives ${want}`);
          compared += 1;
        });
      }
      assert.ok(compared >= Object.values(c.expected).flat().length, `only ${compared} values compared`);

      // a click on a legend entry hides its series, a second shows it again
      const group = Object.keys(c.expected)[0];
      const entry = page.locator(`.plot[data-group="${group}"] .u-legend .u-series`).nth(1);
      const shown = () => page.evaluate((g) => window.rigidReport.plots[g].series[1].show, group);
      assert.equal(await shown(), true);
      await entry.click();
      assert.equal(await shown(), false, 'the legend click did not hide the series');
      await entry.click();
      assert.equal(await shown(), true);
    });
  });
}

test('without WebGL the page says why the 3D view is missing and keeps the header and plots', async () => {
  const dir = writeReport('examples/double_pendulum.toml');
  const page = await browser.newPage();
  // a browser with no WebGL: every webgl/webgl2 context request fails, as with --disable-webgl
  await page.addInitScript(() => {
    const get = HTMLCanvasElement.prototype.getContext;
    HTMLCanvasElement.prototype.getContext = function (type, ...rest) {
      return /webgl/i.test(type) ? null : get.call(this, type, ...rest);
    };
  });
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  await page.goto(`file://${join(dir, 'report.html')}`);
  await page.evaluate(() => window.rigidReport.ready);
  const note = await page.evaluate(() => document.querySelector('.stage .fatal')?.textContent ?? '');
  assert.match(note, /^The 3D view could not start: .*WebGL/);
  assert.deepEqual(await page.evaluate(() => Object.keys(window.rigidReport.plots)),
    ['coordinates', 'velocities', 'energy_error', 'other']);
  assert.deepEqual(errors, []);
  await page.close();
});
