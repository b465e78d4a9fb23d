// The size bound of a large run: 10⁵ steps of 10 free bodies sharing a 100 000-triangle mesh
// give a page of at most 10 MB (the mesh stored once, frames decimated, float32) that loads.
import assert from 'node:assert/strict';
import { mkdtempSync, statSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { after, before, test } from 'node:test';
import { ellipsoidStl, launch, openPage, rigidExe, samplePages } from './support.mjs';
import { execFileSync } from 'node:child_process';

let browser;
before(async () => { browser = await launch(); });
after(async () => { await browser?.close(); });

test('10 bodies, 10⁵ steps, a 100k-triangle mesh: a page of at most 10 MB that loads', { skip: samplePages && 'pages assembled by make_sample.py have no meshes' }, async () => {
  const dir = mkdtempSync(join(tmpdir(), 'rigid-browser-size-'));
  assert.equal(ellipsoidStl(join(dir, 'egg.stl'), 250, 201, [0.3, 0.2, 0.12]), 100000);
  let scene = '';
  for (let b = 0; b < 10; b += 1) {
    scene += `[[bodies]]\nname = "egg${b}"\nfree = true\nmesh = "egg.stl"\nmass = 1\n` +
      `initial_position = [${b % 5}, ${Math.floor(b / 5)}, 0]\nangular_velocity = [${0.1 * b}, 1, 0.2]\n\n`;
  }
  // 10⁵ steps of 1 ms, 10⁴ output samples: decimated to the default frame count
  scene += '[simulation]\nt_end = 100.0\ndt = 0.001\noutput_dt = 0.01\n';
  writeFileSync(join(dir, 'eggs.toml'), scene);
  execFileSync(rigidExe, ['run', join(dir, 'eggs.toml'), '--report', '-o', join(dir, 'out')], { stdio: ['ignore', 'ignore', 'inherit'] });
  const html = join(dir, 'out', 'report.html');
  const bytes = statSync(html).size;
  assert.ok(bytes <= 10e6, `report.html is ${bytes} B, more than 10 MB`);
  // a small window: software WebGL draws the 10⁶ triangles faster
  const { page, problems } = await openPage(browser, html, { width: 640, height: 480 });
  const meshes = await page.evaluate(() => JSON.parse(document.getElementById('rigid-report-data').textContent).meshes.length);
  assert.equal(meshes, 1, 'the mesh shared by 10 bodies is stored once');
  assert.deepEqual(problems, []);
  await page.close();
});
