// What the run page draws of the scene and what it gives for slides: the double pendulum's two
// rods and pivot (dark pixels along the rod between the pivot and the bob, which go when the
// rods are hidden), the Atwood machine's ropes and the stiff dumbbell's spring (likewise), the tennis racket's flip (its drawn frame turns by 180° relative to L between
// t = 0 and the middle of its first two flips), the scene's metrics in the header and marked on
// the plots, the units of every axis, and the PNG and SVG downloads.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { after, before, describe, test } from 'node:test';
import { launch, openPage, pixelStats, readCsv, samplePages, screenshotPath, writeReport } from './support.mjs';

const skip = samplePages && 'pages assembled by make_sample.py have no links or metrics';

let browser;
before(async () => { browser = await launch(); });
after(async () => { await browser?.close(); });

// Samples the 3D view's canvas at CSS-pixel points; for each, whether a pixel within `within` CSS
// px of it is dark (every channel below 0x70: the rods are #3b3b3b lit, ropes #4a3a28, springs
// #23344f, the background #f7f7f7, the grid #bbbbbb and #dddddd, the bodies' colours each have
// a channel above 0x70).
async function darkAt(page, points, within = 2) {
  return page.evaluate(([pts, rad]) => {
    const view = window.rigidReport.view;
    view.render();
    const src = view.canvas;
    const scale = src.width / src.getBoundingClientRect().width;
    const c = document.createElement('canvas');
    c.width = src.width;
    c.height = src.height;
    const g = c.getContext('2d');
    g.drawImage(src, 0, 0);
    const px = g.getImageData(0, 0, c.width, c.height).data;
    const r = Math.ceil(rad * scale);
    return pts.map(([x, y]) => {
      for (let dy = -r; dy <= r; dy += 1) {
        for (let dx = -r; dx <= r; dx += 1) {
          if (dx * dx + dy * dy > r * r + 2 * r) continue;
          const i = Math.round(y * scale + dy);
          const j = Math.round(x * scale + dx);
          if (i < 0 || j < 0 || i >= c.height || j >= c.width) continue;
          const k = 4 * (i * c.width + j);
          if (px[k] < 0x70 && px[k + 1] < 0x70 && px[k + 2] < 0x70) return true;
        }
      }
      return false;
    });
  }, [points, within]);
}

async function settle(page) {
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
}

async function setToggle(page, label, on) {
  const box = page.locator('.toggles label', { hasText: label }).locator('input');
  if ((await box.isChecked()) !== on) await box.click();
  await settle(page);
}

async function download(page, button) {
  const [d] = await Promise.all([page.waitForEvent('download'), button.click()]);
  return { name: d.suggestedFilename(), bytes: readFileSync(await d.path()) };
}

describe('double pendulum: two rods and a pivot', { skip }, () => {
  let page;
  let problems;
  before(async () => {
    const dir = writeReport('examples/double_pendulum.toml');
    ({ page, problems } = await openPage(browser, join(dir, 'report.html')));
  });
  after(async () => { await page?.close(); });

  test('the data name a pivot at the origin for bob1 and a rod from bob2 to bob1', async () => {
    const links = await page.evaluate(() => JSON.parse(document.getElementById('rigid-report-data').textContent).links);
    assert.equal(links.length, 2);
    assert.deepEqual([links[0].body, links[0].to, links[0].to_point], [0, null, [0, 0, 0]]);
    assert.deepEqual([links[1].body, links[1].to], [1, 0]);
    assert.deepEqual(await page.evaluate(() => window.rigidReport.view.pivots), [[0, 0, 0]]);
  });

  for (const t of [0, 2.5]) {
    test(`at t = ${t} s the rods are drawn between the pivot and the bobs`, async () => {
      await page.evaluate((tt) => window.rigidReport.setTime(tt), t);
      await settle(page);
      const ends = await page.evaluate(() => window.rigidReport.view.links());
      assert.equal(ends.length, 2);
      // the rods are 1 m (l1 = l2 = 1): the ends as drawn, from the frame's poses (float32)
      for (const [a, b] of ends) assert.ok(Math.abs(Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]) - 1) < 1e-5);
      // points along each rod between 30 % and 70 % of its length (clear of the pivot's sphere
      // and the bobs' markers, which are within 0.1 m of the ends here)
      const points = await alongLinks(page, ends);
      assert.deepEqual(await darkAt(page, points), points.map(() => true), 'a dark pixel at each point along the rods');
      await page.locator('.canvas-box canvas').screenshot({ path: screenshotPath(`double_pendulum_rods_t${t}.png`) });
      // the control: with the rods hidden the same points are background
      await setToggle(page, 'rods and pivots', false);
      assert.deepEqual(await darkAt(page, points), points.map(() => false), 'no dark pixel there without the rods');
      await setToggle(page, 'rods and pivots', true);
    });
  }

  test('every plot axis has its unit', async () => {
    const labels = await page.evaluate(() => Object.fromEntries(Object.entries(window.rigidReport.plots)
      .map(([g, u]) => [g, [u.axes[0].label, u.axes[1].label]])));
    assert.deepEqual(labels.coordinates, ['t (s)', 'coordinate (m or rad)']);
    assert.deepEqual(labels.velocities, ['t (s)', 'coordinate rate (m/s or rad/s)']);
    // E(0) is the round-off of 0 here: the change itself, in J
    assert.deepEqual(labels.energy_error, ['t (s)', 'change (J)']);
    assert.deepEqual(problems, []);
  });
});

// points between 30 % and 70 % along each link [a, b], projected to CSS pixels
async function alongLinks(page, ends) {
  const points = [];
  for (const [a, b] of ends) {
    const pa = await page.evaluate((p) => window.rigidReport.view.project(p), a);
    const pb = await page.evaluate((p) => window.rigidReport.view.project(p), b);
    for (const f of [0.3, 0.4, 0.5, 0.6, 0.7]) points.push([pa[0] + f * (pb[0] - pa[0]), pa[1] + f * (pb[1] - pa[1])]);
  }
  return points;
}

describe('Atwood machine: the constraints\' ropes', { skip }, () => {
  let page;
  let problems;
  before(async () => {
    const dir = writeReport('examples/atwood.toml');
    ({ page, problems } = await openPage(browser, join(dir, 'report.html')));
  });
  after(async () => { await page?.close(); });

  test('the data name a rope from each weight to where it leaves the pulley, and no rod', async () => {
    const links = await page.evaluate(() => JSON.parse(document.getElementById('rigid-report-data').textContent).links);
    assert.deepEqual(links.map((l) => [l.rule, l.body, l.to, l.to_point]), [['rope', 0, null, [-0.1, 0, 0]], ['rope', 1, null, [0.1, 0, 0]]]);
    assert.deepEqual(await page.evaluate(() => window.rigidReport.view.pivots), []);
  });

  for (const t of [0, 0.9]) {
    test(`at t = ${t} s each rope runs from its weight to the pulley`, async () => {
      await page.evaluate((tt) => window.rigidReport.setTime(tt), t);
      await settle(page);
      const ends = await page.evaluate(() => window.rigidReport.view.links());
      // the closed form of the scene's comment: weight 1 falls by a t²/2, a = 1.635 m/s², and
      // weight 2 rises as much; the frame's poses are float32 (1e-5 m)
      const fall = (0.5 * 1.635 * t * t);
      assert.ok(Math.hypot(ends[0][0][0] + 0.1, ends[0][0][1], ends[0][0][2] + 1 + fall) < 1e-5, JSON.stringify(ends[0]));
      assert.ok(Math.hypot(ends[1][0][0] - 0.1, ends[1][0][1], ends[1][0][2] + 1 - fall) < 1e-5, JSON.stringify(ends[1]));
      assert.deepEqual(ends.map((e) => e[1]), [[-0.1, 0, 0], [0.1, 0, 0]]);
      const points = await alongLinks(page, ends);
      assert.deepEqual(await darkAt(page, points), points.map(() => true), 'a dark pixel at each point along the ropes');
      await page.locator('.canvas-box canvas').screenshot({ path: screenshotPath(`atwood_ropes_t${t}.png`) });
      await setToggle(page, 'rods and pivots', false);
      assert.deepEqual(await darkAt(page, points), points.map(() => false), 'no dark pixel there without the ropes');
      await setToggle(page, 'rods and pivots', true);
      assert.deepEqual(problems, []);
    });
  }
});

describe('stiff dumbbell: a spring between two particles', { skip }, () => {
  let page;
  let problems;
  before(async () => {
    const dir = writeReport('examples/stiff_dumbbell.toml');
    ({ page, problems } = await openPage(browser, join(dir, 'report.html')));
  });
  after(async () => { await page?.close(); });

  test('the data name the spring and no rod from the motion', async () => {
    const links = await page.evaluate(() => JSON.parse(document.getElementById('rigid-report-data').textContent).links);
    assert.deepEqual(links.map((l) => [l.rule, l.body, l.to]), [['spring', 0, 1]]);
  });

  test('the coil is drawn between the particles, as long as they are apart', async () => {
    await page.evaluate(() => window.rigidReport.setTime(1.3));
    await settle(page);
    const ends = await page.evaluate(() => window.rigidReport.view.links());
    assert.equal(ends.length, 1);
    // the steady radius of the scene's comment: the particles are 2 r = 1.00020004 m apart
    const [a, b] = ends[0];
    assert.ok(Math.abs(Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]) - 2 * 0.50010002) < 1e-5);
    // every cross-section of the coil has a point within its radius of the axis: search a disc
    // of the coil's projected radius (+2 px) around points along the axis
    const radius = (await page.evaluate(() => window.rigidReport.view.linkRadii))[0];
    const mid = a.map((x, i) => (x + b[i]) / 2);
    const [pm, pz] = await Promise.all([mid, [mid[0], mid[1], mid[2] + radius]]
      .map((p) => page.evaluate((q) => window.rigidReport.view.project(q), p)));
    const [pa, pb] = await Promise.all([a, b].map((p) => page.evaluate((q) => window.rigidReport.view.project(q), p)));
    const axis = Math.hypot(pb[0] - pa[0], pb[1] - pa[1]);
    const across = Math.hypot(pz[0] - pm[0], pz[1] - pm[1]);
    assert.ok(axis > 100 && across > 2 && across < axis / 5, `${axis} px along, ${across} px across`);
    const points = await alongLinks(page, ends);
    assert.deepEqual(await darkAt(page, points, across + 2), points.map(() => true), 'the coil near each point along the spring');
    await page.locator('.canvas-box canvas').screenshot({ path: screenshotPath('stiff_dumbbell_spring.png') });
    await setToggle(page, 'rods and pivots', false);
    assert.deepEqual(await darkAt(page, points, across + 2), points.map(() => false), 'nothing dark there without it');
    await setToggle(page, 'rods and pivots', true);
    assert.deepEqual(problems, []);
  });
});

describe('tennis racket: the flip, the metrics, the downloads', { skip }, () => {
  let dir;
  let page;
  let problems;
  let summary;
  let csv;
  before(async () => {
    dir = writeReport('examples/tennis_racket.toml');
    summary = JSON.parse(readFileSync(join(dir, 'summary.json'), 'utf8'));
    csv = readCsv(join(dir, 'trajectory.csv'));
    ({ page, problems } = await openPage(browser, join(dir, 'report.html')));
  });
  after(async () => { await page?.close(); });

  test('the drawn body frame turns by 180° relative to L between t = 0 and the middle of two flips', async () => {
    // the flips are the sign changes of ω_y (the scene's comment), found here from the CSV
    const wy = csv.columns.indexOf('racket.wy');
    const t = csv.columns.indexOf('t');
    const flips = [];
    for (let r = 1; r < csv.rows.length && flips.length < 2; r += 1) {
      const [a, b] = [csv.rows[r - 1][wy], csv.rows[r][wy]];
      if (Math.sign(a) !== Math.sign(b)) flips.push(csv.rows[r - 1][t] + (a / (a - b)) * (csv.rows[r][t] - csv.rows[r - 1][t]));
    }
    assert.equal(flips.length, 2);
    const L = ['racket.Lx', 'racket.Ly', 'racket.Lz'].map((c) => csv.rows[0][csv.columns.indexOf(c)]);
    const angleToL = async (time) => {
      await page.evaluate((tt) => window.rigidReport.setTime(tt), time);
      const [w, x, y, z] = await page.evaluate(() => window.rigidReport.view.bodyQuaternion(0));
      // the body's y axis in the world: the second column of R(q)
      const yB = [2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)];
      const c = (yB[0] * L[0] + yB[1] * L[1] + yB[2] * L[2]) / (Math.hypot(...yB) * Math.hypot(...L));
      return (Math.acos(Math.max(-1, Math.min(1, c))) * 180) / Math.PI;
    };
    // ω(0) = (0.01, 1, 0.01): y is within 1° of L = I ω; half-way between the flips ω ≈ −ω_y e_y,
    // within 1° of −L; at a flip ω_y = 0, so L ⊥ y (to the frame's 0.1 s spacing: ±3°)
    assert.ok((await angleToL(0)) < 1.5, 'y along L at t = 0');
    const atFlip = await angleToL(flips[0]);
    assert.ok(Math.abs(atFlip - 90) < 5, `y ⊥ L at the first flip (${atFlip}°)`);
    const flipped = await angleToL((flips[0] + flips[1]) / 2);
    assert.ok(flipped > 178.5, `y against L half-way between the flips (${flipped}°)`);
    // the flip time the scene reports is the first sign change (to the output step, 0.05 s)
    assert.ok(Math.abs(summary.metrics.first_flip.value - flips[0]) < 0.05);
    // a free body's frame is shown by default
    assert.equal(await page.locator('.toggles label', { hasText: 'body frames' }).locator('input').isChecked(), true);
    await settle(page);
    await page.locator('.canvas-box canvas').screenshot({ path: screenshotPath('tennis_racket_flipped.png') });
  });

  test('the metrics are in the header with their units, and the flip is marked on the plots', async () => {
    const texts = await page.locator('.metrics .metric').allTextContents();
    assert.equal(texts.length, Object.keys(summary.metrics).length);
    const flip = summary.metrics.first_flip;
    assert.equal(flip.unit, 's');
    const shown = texts.find((s) => s.startsWith('first_flip = '));
    assert.ok(shown?.endsWith(' s'), shown);
    // six significant digits of the summary's value
    assert.ok(Math.abs(Number(shown.slice('first_flip = '.length, -2)) - flip.value) <= 5e-6 * flip.value, shown);
    assert.ok(texts.some((s) => s.startsWith('energy_drift')));
    const marks = await page.evaluate(() => Object.values(window.rigidReport.plots).map((u) => u.rigidMarks.map((m) => m.t)));
    for (const m of marks) assert.deepEqual(m, [flip.value]);
  });

  test('every plot axis names its units from the run schema', async () => {
    const unitOf = Object.fromEntries(summary.schema.columns.map((c) => [c.name, c.unit]));
    const plots = await page.evaluate(() => Object.entries(window.rigidReport.plots)
      .map(([g, u]) => ({ group: g, x: u.axes[0].label, y: u.axes[1].label, series: u.rigidSeries })));
    assert.ok(plots.length >= 3);
    for (const p of plots) {
      assert.equal(p.x, 't (s)');
      assert.match(p.y, /\(.+\)$/, `${p.group}: a unit in parentheses`);
      for (const s of p.series) {
        // a plotted column carries the schema's unit; the relative errors are dimensionless ("1")
        if (s.name === s.column) assert.equal(s.unit, unitOf[s.column], s.name);
        const unit = s.unit || '1';
        assert.ok(p.y.includes(`(${unit}`) || p.y.includes(` ${unit})`) || p.y.includes(` ${unit},`),
          `${p.group}: "${p.y}" lacks ${s.name}'s unit ${unit}`);
      }
    }
  });

  test('each plot downloads as a PNG that decodes and is not blank, and as an SVG that parses', async () => {
    const groups = await page.locator('.plots h3').count();
    assert.ok(groups >= 3);
    for (let i = 0; i < groups; i += 1) {
      const h3 = page.locator('.plots h3').nth(i);
      const png = await download(page, h3.locator('button[data-format=png]'));
      assert.match(png.name, /\.png$/);
      assert.deepEqual([...png.bytes.subarray(0, 8)], [0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]);
      const stats = await pixelStats(page, png.bytes);
      assert.ok(stats.pixels > 300 * 200 && stats.notBackground > 0.01 && stats.colours > 4, JSON.stringify(stats));

      const svg = await download(page, h3.locator('button[data-format=svg]'));
      assert.match(svg.name, /\.svg$/);
      const parsed = await page.evaluate((text) => {
        const doc = new DOMParser().parseFromString(text, 'image/svg+xml');
        const err = doc.querySelector('parsererror');
        return {
          error: err ? err.textContent : null,
          root: doc.documentElement.localName,
          paths: doc.querySelectorAll('path').length,
          dashed: doc.querySelectorAll('line[stroke-dasharray]').length,
          texts: [...doc.querySelectorAll('text')].map((t) => t.textContent),
        };
      }, svg.bytes.toString('utf8'));
      assert.equal(parsed.error, null);
      assert.equal(parsed.root, 'svg');
      const series = await page.evaluate((k) => Object.values(window.rigidReport.plots)[k].rigidSeries.length, i);
      assert.equal(parsed.paths, series, 'one path per series');
      assert.equal(parsed.dashed, 1, 'the first flip marked');
      assert.ok(parsed.texts.includes('t (s)'));
    }
  });

  test('the 3D view downloads as a PNG that is not blank', async () => {
    const png = await download(page, page.locator('.toggles button.download'));
    assert.match(png.name, /\.png$/);
    const stats = await pixelStats(page, png.bytes);
    assert.ok(stats.notBackground > 0.02 && stats.colours > 8, JSON.stringify(stats));
    assert.deepEqual(problems, []);
  });
});
