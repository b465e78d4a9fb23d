// Shared by the browser tests: writing a report page with rigid, launching Debian's chromium
// through playwright-core (no browser download), and reading pixels of screenshots.
import { execFileSync } from 'node:child_process';
import { mkdirSync, mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from '../../web/node_modules/playwright-core/index.mjs';

export const root = fileURLToPath(new URL('../..', import.meta.url));

export const rigidExe = process.env.RIGID_EXE ?? join(root, 'build', 'ci', 'bin', 'rigid');
export const screenshotDir = process.env.RIGID_SCREENSHOT_DIR ?? join(root, 'build', 'ci', 'browser-screenshots');
// RIGID_BROWSER_SAMPLE=1: assemble the page with web/dev/make_sample.py from a plain `rigid run`
// (for a rigid that does not write reports yet); otherwise the page is rigid's own.
export const samplePages = process.env.RIGID_BROWSER_SAMPLE === '1';

let bundleDir = null;

/** Runs `rigid run SCENE --report -o DIR` and returns DIR (with report.html and trajectory.csv). */
export function writeReport(scene, extraArgs = []) {
  const dir = mkdtempSync(join(tmpdir(), 'rigid-browser-'));
  const scenePath = join(root, scene);
  if (!samplePages) {
    execFileSync(rigidExe, ['run', scenePath, '--report', '-o', dir, ...extraArgs], { stdio: ['ignore', 'ignore', 'inherit'] });
    return dir;
  }
  execFileSync(rigidExe, ['run', scenePath, '-o', dir, ...extraArgs], { stdio: ['ignore', 'ignore', 'inherit'] });
  if (!bundleDir) {
    bundleDir = mkdtempSync(join(tmpdir(), 'rigid-bundle-'));
    execFileSync('node', [join(root, 'web', 'build.mjs'), bundleDir], { stdio: ['ignore', 'ignore', 'inherit'] });
  }
  execFileSync('/usr/bin/python3', [join(root, 'web', 'dev', 'make_sample.py'), dir, scenePath, bundleDir, join(dir, 'report.html')],
    { stdio: ['ignore', 'ignore', 'inherit'] });
  return dir;
}

/** trajectory.csv as {columns, rows} of numbers. */
export function readCsv(path) {
  const lines = readFileSync(path, 'utf8').trim().split('\n');
  const columns = lines[0].split(',');
  return { columns, rows: lines.slice(1).map((l) => l.split(',').map(Number)) };
}

export async function launch() {
  return chromium.launch({
    executablePath: process.env.RIGID_CHROMIUM ?? '/usr/bin/chromium',
    // software WebGL: the machines that run the tests have no GPU
    args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
  });
}

/**
 * Opens the page from file:// and records every console error, page error and request whose URL
 * is neither the page itself nor a data: URL (those are aborted: the page must load nothing).
 * `init`, when given, runs in the page before its own scripts (page.addInitScript).
 */
export async function openPage(browser, htmlPath, viewport = { width: 1200, height: 900 }, init = null) {
  const page = await browser.newPage({ viewport });
  if (init) await page.addInitScript(init);
  const problems = [];
  const pageUrl = `file://${htmlPath}`;
  page.on('console', (m) => { if (m.type() === 'error') problems.push(`console error: ${m.text()}`); });
  page.on('pageerror', (e) => problems.push(`page error: ${e.message}`));
  await page.route('**/*', (route) => {
    const url = route.request().url();
    if (url === pageUrl || url.startsWith('data:')) return route.continue();
    problems.push(`request: ${url}`);
    return route.abort();
  });
  page.on('request', (r) => {
    const url = r.url();
    if (url !== pageUrl && !url.startsWith('data:') && !problems.includes(`request: ${url}`)) problems.push(`request: ${url}`);
  });
  await page.goto(pageUrl);
  await page.evaluate(() => window.rigidReport.ready);
  return { page, problems };
}

/**
 * Pixel statistics of a PNG screenshot, decoded by the browser: the share of pixels that differ
 * from the most common colour, and the number of distinct colours (to 4 bits per channel).
 * With `other`, also the share of pixels that differ between the two (any channel by > 8/255).
 */
export async function pixelStats(page, png, other = null) {
  return page.evaluate(async ([a, b]) => {
    const decode = async (b64) => {
      const img = new Image();
      img.src = `data:image/png;base64,${b64}`;
      await img.decode();
      const c = document.createElement('canvas');
      c.width = img.width;
      c.height = img.height;
      const g = c.getContext('2d');
      g.drawImage(img, 0, 0);
      return g.getImageData(0, 0, c.width, c.height).data;
    };
    const pa = await decode(a);
    const n = pa.length / 4;
    const counts = new Map();
    for (let i = 0; i < pa.length; i += 4) {
      const key = ((pa[i] >> 4) << 8) | ((pa[i + 1] >> 4) << 4) | (pa[i + 2] >> 4);
      counts.set(key, (counts.get(key) ?? 0) + 1);
    }
    const top = Math.max(...counts.values());
    const out = { pixels: n, notBackground: 1 - top / n, colours: counts.size };
    if (b) {
      const pb = await decode(b);
      let diff = 0;
      for (let i = 0; i < pa.length; i += 4) {
        if (Math.abs(pa[i] - pb[i]) > 8 || Math.abs(pa[i + 1] - pb[i + 1]) > 8 || Math.abs(pa[i + 2] - pb[i + 2]) > 8) diff += 1;
      }
      out.changed = diff / n;
    }
    return out;
  }, [png.toString('base64'), other ? other.toString('base64') : null]);
}

export function screenshotPath(name) {
  mkdirSync(screenshotDir, { recursive: true });
  return join(screenshotDir, name);
}

// A closed ellipsoid of 2·m·(n−1) triangles (pole fans and quads between the rings), outward
// normals, as binary STL: m = 250, n = 201 gives 100 000.
export function ellipsoidStl(path, m, n, [a, b, c]) {
  const p = (i, j) => {
    const th = (Math.PI * i) / n;
    const ph = (2 * Math.PI * j) / m;
    return [a * Math.sin(th) * Math.cos(ph), b * Math.sin(th) * Math.sin(ph), c * Math.cos(th)];
  };
  const tris = [];
  for (let j = 0; j < m; j += 1) {
    tris.push([[0, 0, c], p(1, j), p(1, j + 1)]);
    tris.push([[0, 0, -c], p(n - 1, j + 1), p(n - 1, j)]);
    for (let i = 1; i < n - 1; i += 1) {
      tris.push([p(i, j), p(i + 1, j), p(i + 1, j + 1)]);
      tris.push([p(i, j), p(i + 1, j + 1), p(i, j + 1)]);
    }
  }
  const buf = Buffer.alloc(84 + 50 * tris.length);
  buf.writeUInt32LE(tris.length, 80);
  tris.forEach((t, k) => {
    const o = 84 + 50 * k;
    // outward: the normal points away from the centre, so (v1 − v0) × (v2 − v0) · v0 > 0
    const u = t[1].map((x, d) => x - t[0][d]);
    const v = t[2].map((x, d) => x - t[0][d]);
    const nrm = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
    const s = nrm[0] * t[0][0] + nrm[1] * t[0][1] + nrm[2] * t[0][2] + nrm[0] * t[1][0] + nrm[1] * t[1][1] + nrm[2] * t[1][2];
    const tt = s < 0 ? [t[0], t[2], t[1]] : t;
    nrm.forEach((x, d) => buf.writeFloatLE(s < 0 ? -x : x, o + 4 * d));
    tt.forEach((vert, q) => vert.forEach((x, d) => buf.writeFloatLE(x, o + 12 + 12 * q + 4 * d)));
  });
  writeFileSync(path, buf);
  return tris.length;
}

