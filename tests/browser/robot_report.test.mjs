// The report page of a robot run: MuJoCo's humanoid pinned at the torso (21 hinges, 12 moving
// bodies) and arm7.urdf. The page names the file's joints as its coordinates and its moving
// links as its bodies, and the 3D view draws the links where the run puts them: the first and
// last frames differ, and one time drawn twice gives the same pixels. The long blocks of the
// equations (the tree's intermediates, the mass matrix) start collapsed under a summary that
// counts them, and are typeset when opened.
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { after, before, describe, test } from 'node:test';
import { launch, openPage, pixelStats, rigidExe, root, samplePages, screenshotPath } from './support.mjs';

const kHumanoid = '/usr/share/mujoco/model/humanoid/humanoid.xml';

/**
 * The moving bodies and their joints of an MJCF or URDF file, read from the file itself (not
 * from rigid): MJCF bodies with a hinge or slide of their own (a body without one is welded to
 * its parent, a free root is pinned), URDF child links of a joint that is not fixed. Each in
 * file order, which is depth-first for both.
 */
function movingLinks(path) {
  const text = readFileSync(path, 'utf8').replace(/<!--[\s\S]*?-->/g, '');
  const bodies = [];
  const joints = [];
  if (path.endsWith('.urdf')) {
    for (const m of text.matchAll(/<joint\s+name="([^"]+)"\s+type="([^"]+)"[\s\S]*?<child\s+link="([^"]+)"/g)) {
      if (m[2] === 'fixed') continue;
      joints.push(m[1]);
      bodies.push(m[3]);
    }
    return { bodies, joints };
  }
  // MJCF: a stack of open bodies; a <joint> (not a <freejoint>) belongs to the innermost one
  const stack = [];
  for (const m of text.matchAll(/<body\b[^>]*?\bname="([^"]+)"[^>]*?(\/?)>|<\/body>|<joint\b[^>]*?\bname="([^"]+)"/g)) {
    if (m[0].startsWith('</body')) {
      stack.pop();
    } else if (m[0].startsWith('<body')) {
      if (m[2] !== '/') stack.push(m[1]);
    } else if (stack.length) {
      joints.push(m[3]);
      const body = stack[stack.length - 1];
      if (!bodies.includes(body)) bodies.push(body);
    }
  }
  return { bodies, joints };
}

function writeRobotReport(model, args) {
  const dir = mkdtempSync(join(tmpdir(), 'rigid-browser-robot-'));
  execFileSync(rigidExe, ['run', model, '--report', '-o', dir, ...args], { stdio: ['ignore', 'ignore', 'inherit'] });
  return join(dir, 'report.html');
}

const cases = [
  {
    name: 'humanoid',
    model: kHumanoid,
    // from MuJoCo's pose (arms raised, bent at the elbows) the arms fall under gravity
    args: ['--pin-free-root', '--set', 'simulation.t_end=1', '--report-frames', '40'],
    eomArgs: ['--pin-free-root'],
    // the blocks opened by the equations test: the mass matrix (a whole humanoid is ~10 s of
    // typesetting on the test machines)
    open: /^M\(q\)/,
    dof: 21,
    nBodies: 12,
    // measured: 1.7 % of the 1168 × 560 canvas changes between t = 0 and t = 1 s (the arms);
    // about a tenth of that still fails a view that draws nothing or nothing that moves
    minChanged: 0.002,
  },
  {
    name: 'arm7',
    model: join(root, 'examples', 'arm7.urdf'),
    // q = 0 is the upright equilibrium: tilted at joint2, the arm swings down
    args: ['--set', 'joint2.initial=0.6', '--set', 'simulation.t_end=1', '--report-frames', '20'],
    eomArgs: [],
    open: /./,
    dof: 7,
    nBodies: 7,
    // measured: 3.1 %; from q = 0 (no tilt) the arm stays put and 0 % changes
    minChanged: 0.002,
  },
];

let browser;
before(async () => { if (!samplePages) browser = await launch(); });
after(async () => { await browser?.close(); });

for (const c of cases) {
  const skip = samplePages ? 'pages assembled by make_sample.py read TOML scenes only'
    : !existsSync(c.model) && `${c.model} is not installed`;
  describe(c.name, { skip }, () => {
    let page;
    let problems;
    before(async () => {
      ({ page, problems } = await openPage(browser, writeRobotReport(c.model, c.args)));
    });
    after(async () => { await page?.close(); });

    test('names the joints as coordinates and the moving links as bodies', async () => {
      const want = movingLinks(c.model);
      assert.equal(want.joints.length, c.dof, `the file's joints: ${want.joints}`);
      assert.equal(want.bodies.length, c.nBodies, `the file's moving bodies: ${want.bodies}`);
      const got = await page.evaluate(() => ({
        coordinates: window.rigidReport.plots.coordinates.rigidSeries.map((s) => s.name),
        velocities: window.rigidReport.plots.velocities.rigidSeries.map((s) => s.name),
        // the header's table of bodies, first column
        bodies: [...document.querySelectorAll('table.bodies tbody tr')].map((tr) => tr.cells[0].textContent),
      }));
      assert.deepEqual(got.coordinates, want.joints);
      assert.deepEqual(got.velocities, want.joints.map((j) => `${j}_dot`));
      assert.deepEqual(got.bodies, want.bodies);
      assert.deepEqual(problems, []);
    });

    test('the 3D view draws the links and they move between the first and last frame', async (t) => {
      const ts = await page.evaluate(() => window.rigidReport.plots.coordinates.data[0]);
      const shotAt = async (time) => {
        await page.evaluate((x) => window.rigidReport.setTime(x), time);
        assert.equal(await page.evaluate(() => window.rigidReport.time()), time);
        // the view renders on the next animation frame
        await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
        // the canvas's own pixels (it keeps its drawing buffer): a screenshot of the page would
        // composite the whole document, seconds for a humanoid's typeset equations
        const url = await page.evaluate(() => window.rigidReport.view.canvas.toDataURL('image/png'));
        return Buffer.from(url.slice(url.indexOf(',') + 1), 'base64');
      };
      const first = await shotAt(ts[0]);
      const last = await shotAt(ts[ts.length - 1]);
      const firstAgain = await shotAt(ts[0]);
      const stats = await pixelStats(page, first, last);
      t.diagnostic(`first vs last frame: ${JSON.stringify(stats)}`);
      // a blank canvas is one colour; the links and the grid make many and cover > 1 %
      assert.ok(stats.colours > 10 && stats.notBackground > 0.01, `canvas looks blank: ${JSON.stringify(stats)}`);
      assert.ok(stats.changed > c.minChanged, `the links did not move: ${JSON.stringify(stats)}`);
      // the same time drawn twice: the same picture (the renderer is deterministic), so the
      // difference above is the motion
      const again = await pixelStats(page, first, firstAgain);
      assert.equal(again.changed, 0, `t = ${ts[0]} drawn twice differs: ${JSON.stringify(again)}`);
      writeFileSync(screenshotPath(`${c.name}-3d-first.png`), first);
      writeFileSync(screenshotPath(`${c.name}-3d-last.png`), last);
    });

    test('long equation blocks start collapsed, say what they hold, and typeset when opened', async () => {
      // what the blocks hold, from `rigid eom`'s JSON rather than from the page's LaTeX
      const eom = JSON.parse(execFileSync(rigidExe, ['eom', c.model, ...c.eomArgs, '--format', 'json'],
        { encoding: 'utf8', maxBuffer: 256 << 20 }));
      const n = eom.intermediates.length;
      const [rows, cols] = [eom.mass_matrix.text.length, eom.mass_matrix.text[0].length];
      assert.ok(n > 0, 'a tree derived by its recursions has intermediates');
      // each intermediate's definition is its row's only "=", so the typeset "=" count them
      assert.ok(eom.intermediates.every((i) => !i.latex.includes('=')));
      const blocks = () => page.evaluate(() => [...document.querySelectorAll('.equations details')].map((d) => ({
        summary: d.querySelector('summary').textContent,
        open: d.open,
        pieces: d.querySelectorAll('.formula').length,
        typeset: d.querySelectorAll('.formula > .katex-display').length,
        pending: d.querySelectorAll('.pending').length,
        failed: [...d.querySelectorAll('.note, .katex-error')].map((e) => e.textContent),
        // KaTeX sets a relation as <span class="mrel">
        equals: [...d.querySelectorAll('.mrel')].filter((e) => e.textContent === '=').length,
      })));
      const before = await blocks();
      const where = before.find((b) => b.summary.startsWith('where'));
      const mass = before.find((b) => b.summary.startsWith('M(q)'));
      assert.ok(where, `no collapsed "where" block: ${JSON.stringify(before.map((b) => b.summary))}`);
      assert.ok(mass, `no collapsed mass matrix block: ${JSON.stringify(before.map((b) => b.summary))}`);
      assert.ok(where.summary.endsWith(`— ${n.toLocaleString('en-US')} intermediates`), where.summary);
      assert.ok(mass.summary.includes(`— ${rows} × ${cols} mass matrix`), mass.summary);
      // collapsed: nothing typeset until opened
      for (const b of before) {
        assert.equal(b.open, false, b.summary);
        assert.equal(b.typeset, 0, b.summary);
      }

      await page.evaluate(async (source) => {
        const re = new RegExp(source);
        for (const d of document.querySelectorAll('.equations details')) {
          if (re.test(d.querySelector('summary').textContent)) d.open = true;
        }
        await window.rigidReport.equationsTypeset();
      }, c.open.source);
      const after = await blocks();
      const opened = after.filter((b) => c.open.test(b.summary));
      assert.ok(opened.length >= 1);
      for (const b of opened) {
        assert.equal(b.open, true, b.summary);
        assert.ok(b.pieces >= 1, b.summary);
        assert.equal(b.typeset, b.pieces, `${b.summary}: ${b.typeset} of ${b.pieces} pieces typeset`);
        assert.equal(b.pending, 0, b.summary);
        assert.deepEqual(b.failed, [], b.summary);
        if (b.summary.startsWith('where')) assert.equal(b.equals, n, 'one "=" per intermediate');
        if (b.summary.startsWith('M(q)')) assert.equal(b.equals, 2, 'M = … and f = …');
        if (b.summary.startsWith('equations of motion')) assert.equal(b.equals, c.dof, 'one equation per coordinate');
      }
      for (const b of after.filter((x) => !c.open.test(x.summary))) assert.equal(b.typeset, 0, b.summary);
      assert.deepEqual(problems, []);
    });
  });
}
