// The run page's pictures of the motion for slides: the "record" control makes a WebM of the 3D
// view for a span of simulated time (WebCodecs: each frame at its own time k/fps, however slowly
// the page renders; else MediaRecorder), or, in a browser with neither, a .tar of PNG frames,
// one per 1/fps × speed of simulated time, each the frame of its own time; the PNG button saves
// the view at the canvas's size.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { after, before, describe, test } from 'node:test';
import { launch, openPage, pixelStats, screenshotPath, writeReport } from './support.mjs';

const kPng = [0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a];

let browser;
let dir;
before(async () => {
  browser = await launch();
  // a swinging rod, 1 rad amplitude, period 1.75 s: every 0.1 s the rod is drawn elsewhere
  dir = writeReport('examples/physical_pendulum.toml');
});
after(async () => { await browser?.close(); });

async function download(page, button) {
  const [d] = await Promise.all([page.waitForEvent('download', { timeout: 60000 }), button.click()]);
  return { name: d.suggestedFilename(), bytes: readFileSync(await d.path()) };
}

// A PNG's width and height from its IHDR chunk (bytes 16–23, big-endian; PNG spec §11.2.2).
const pngSize = (b) => [b.readUInt32BE(16), b.readUInt32BE(20)];

// The files of a ustar archive: [{name, bytes}], each header's checksum verified (the unsigned
// sum of the header's bytes with its checksum field read as 8 spaces, POSIX.1 ustar).
function untar(buf) {
  const files = [];
  let at = 0;
  while (at + 512 <= buf.length) {
    const h = buf.subarray(at, at + 512);
    if (h.every((b) => b === 0)) break;
    const field = (o, n) => h.subarray(o, o + n).toString('latin1').replace(/\0.*$/s, '');
    assert.equal(field(257, 6), 'ustar');
    let sum = 0;
    for (let i = 0; i < 512; i += 1) sum += i >= 148 && i < 156 ? 0x20 : h[i];
    assert.equal(parseInt(field(148, 8).trim(), 8), sum, 'header checksum');
    const size = parseInt(field(124, 12), 8);
    files.push({ name: field(0, 100), bytes: buf.subarray(at + 512, at + 512 + size) });
    at += 512 + Math.ceil(size / 512) * 512;
  }
  // the end: two zero blocks
  assert.ok(at + 1024 <= buf.length && buf.subarray(at, at + 1024).every((b) => b === 0), 'two zero blocks at the end');
  return files;
}

// The video track of a WebM (EBML, RFC 8794; Matroska elements, RFC 9559): its codec, pixel
// size and the number of frames (SimpleBlocks and BlockGroups); the time of each SimpleBlock (its
// cluster's Timecode plus its own signed 16-bit offset, in TimecodeScale units: ms) and whether
// it is a key frame; the Info's Duration. Segment, Info, Cluster, Tracks, TrackEntry and Video
// are entered (MediaRecorder writes Segments and Clusters of unknown size, so they are read as a
// flat sequence); every other element is skipped by its size.
function webmTrack(buf) {
  const kEnter = new Set([0x18538067, 0x1549a966, 0x1f43b675, 0x1654ae6b, 0xae, 0xe0]);
  const vint = (at, keepMarker) => {
    const first = buf[at];
    let len = 1;
    while (len <= 8 && !(first & (0x80 >> (len - 1)))) len += 1;
    assert.ok(len <= 8, `a variable-size integer at ${at}`);
    let v = keepMarker ? first : first & ((0x80 >> (len - 1)) - 1);
    let allOnes = v === (0x80 >> (len - 1)) - 1;
    for (let i = 1; i < len; i += 1) {
      v = v * 256 + buf[at + i];
      allOnes = allOnes && buf[at + i] === 0xff;
    }
    return { v, len, unknown: !keepMarker && allOnes };
  };
  const out = { codec: null, width: null, height: null, frames: 0, times: [], keys: [], duration: null, scale: 1e6 };
  let cluster = 0;
  let at = 0;
  while (at < buf.length) {
    const id = vint(at, true);
    const size = vint(at + id.len, false);
    const body = at + id.len + size.len;
    if (kEnter.has(id.v)) { at = body; continue; }
    assert.ok(!size.unknown, `element ${id.v.toString(16)} of unknown size`);
    const data = buf.subarray(body, body + size.v);
    if (id.v === 0x86) out.codec = data.toString('latin1');
    else if (id.v === 0xb0) out.width = data.readUIntBE(0, data.length);
    else if (id.v === 0xba) out.height = data.readUIntBE(0, data.length);
    else if (id.v === 0xe7) cluster = data.readUIntBE(0, data.length);
    else if (id.v === 0x2ad7b1) out.scale = data.readUIntBE(0, data.length);
    else if (id.v === 0x4489) out.duration = data.length === 8 ? data.readDoubleBE(0) : data.readFloatBE(0);
    if (id.v === 0xa3) {
      // track number (a 1-byte vint here), time offset, flags
      out.times.push(cluster + data.readInt16BE(1));
      out.keys.push((data[3] & 0x80) !== 0);
    }
    if (id.v === 0xa3 || id.v === 0xa0) out.frames += 1;
    at = body + size.v;
  }
  return out;
}

// 0.5 s of simulated time at 10 fps and speed ×1: the frames of t = 0, 0.1, …, 0.5
async function setUpSpan(page) {
  await page.locator('.player select[aria-label=speed]').selectOption('1');
  await page.locator('.record-row select.record-fps').selectOption('10');
  await page.locator('.record-row input.record-span').fill('0.5');
  await page.evaluate(() => window.rigidReport.setTime(0));
}

describe('recording the 3D view', () => {
  test('with WebCodecs: a WebM of the span, named for it, each frame at k/fps however slow the page', async () => {
    const { page, problems } = await openPage(browser, join(dir, 'report.html'));
    try {
      assert.equal(await page.evaluate(() => window.rigidReport.view.recorder.encoder), true);
      assert.deepEqual(await page.locator('.record-row select.record-format option').allTextContents(), ['WebM (exact frame times)', 'PNG frames (.tar)']);
      await setUpSpan(page);
      // the page made 20 times slower (Chrome's CPU throttling): rendering and encoding take far
      // longer than 1/10 s a frame, which a wall-clocked video would stretch
      const cdp = await page.context().newCDPSession(page);
      await cdp.send('Emulation.setCPUThrottlingRate', { rate: 20 });
      const started = Date.now();
      const video = await download(page, page.locator('.record-row button.record'));
      const seconds = (Date.now() - started) / 1000;
      await cdp.send('Emulation.setCPUThrottlingRate', { rate: 1 });
      assert.equal(video.name, 'physical_pendulum_0-0.5s.webm');
      assert.deepEqual([...video.bytes.subarray(0, 4)], [0x1a, 0x45, 0xdf, 0xa3]);
      assert.ok(video.bytes.subarray(0, 64).includes(Buffer.from('webm')), 'DocType webm');
      const size = await page.evaluate(() => [window.rigidReport.view.canvas.width, window.rigidReport.view.canvas.height]);
      const track = webmTrack(video.bytes);
      assert.ok(['V_VP9', 'V_VP8'].includes(track.codec), track.codec);
      assert.deepEqual([track.width, track.height, track.frames], [...size, 6]);
      // frame k at k/10 s exactly (ms), the first a key frame, the file 0.6 s long
      assert.equal(track.scale, 1e6);
      assert.deepEqual(track.times, [0, 100, 200, 300, 400, 500], `recorded in ${seconds} s`);
      assert.equal(track.keys[0], true);
      assert.equal(track.duration, 600);
      assert.match(await page.locator('.record-row .record-note').textContent(), /saved physical_pendulum_0-0\.5s\.webm \(6 frames at 10 fps, vp[89], /);
      assert.ok(Math.abs((await page.evaluate(() => window.rigidReport.time())) - 0.5) < 1e-9);
      assert.deepEqual(problems, []);
    } finally {
      await page.close();
    }
  });

  test('with MediaRecorder (no WebCodecs): a WebM of the span, named for it', async () => {
    const { page, problems } = await openPage(browser, join(dir, 'report.html'), undefined, () => { delete window.VideoEncoder; });
    try {
      assert.equal(await page.evaluate(() => window.rigidReport.view.recorder.encoder), false);
      const type = await page.evaluate(() => window.rigidReport.view.recorder.type);
      assert.match(type, /^video\/webm;codecs=vp[89]$/);
      await setUpSpan(page);
      const video = await download(page, page.locator('.record-row button.record'));
      assert.equal(video.name, 'physical_pendulum_0-0.5s.webm');
      // EBML's magic number, the first bytes of every Matroska/WebM file (RFC 8794 §8)
      assert.deepEqual([...video.bytes.subarray(0, 4)], [0x1a, 0x45, 0xdf, 0xa3]);
      // "webm" as the EBML DocType, within the header
      assert.ok(video.bytes.subarray(0, 64).includes(Buffer.from('webm')), 'DocType webm');
      // six frames of an 1200 × 560-pixel view at 8 Mbit/s: far more than a header's few hundred bytes
      assert.ok(video.bytes.length > 2000, `${video.bytes.length} bytes`);
      // one video frame per recorded frame, at the canvas's size
      const size = await page.evaluate(() => [window.rigidReport.view.canvas.width, window.rigidReport.view.canvas.height]);
      const track = webmTrack(video.bytes);
      assert.deepEqual([track.codec, track.width, track.height, track.frames], [type.endsWith('vp9') ? 'V_VP9' : 'V_VP8', size[0], size[1], 6]);
      // the page stopped at the span's end and says what it saved
      assert.ok(Math.abs((await page.evaluate(() => window.rigidReport.time())) - 0.5) < 1e-9);
      assert.match(await page.locator('.record-row .record-note').textContent(), /saved physical_pendulum_0-0\.5s\.webm \(6 frames at 10 fps, vp[89]/);
      // PNG frames chosen where there is a video too: the same span as a .tar of 6 frames
      assert.deepEqual(await page.locator('.record-row select.record-format option').allTextContents(), [`WebM (${type.slice(-3)})`, 'PNG frames (.tar)']);
      await page.locator('.record-row select.record-format').selectOption('png');
      await setUpSpan(page);
      const tar = await download(page, page.locator('.record-row button.record'));
      assert.equal(tar.name, 'physical_pendulum_0-0.5s.tar');
      assert.equal(untar(tar.bytes).filter((f) => f.bytes.subarray(0, 8).equals(Buffer.from(kPng))).length, 6);
      await page.locator('.stage').screenshot({ path: screenshotPath('record_controls.png') });
      assert.deepEqual(problems, []);
    } finally {
      await page.close();
    }
  });

  test('with neither: a .tar of one distinct PNG per frame, the view at its own time', async () => {
    const page = await browser.newPage({ viewport: { width: 1200, height: 900 } });
    try {
      await page.addInitScript(() => { delete window.MediaRecorder; delete window.VideoEncoder; });
      const errors = [];
      page.on('pageerror', (e) => errors.push(e.message));
      await page.goto(`file://${join(dir, 'report.html')}`);
      await page.evaluate(() => window.rigidReport.ready);
      assert.equal(await page.evaluate(() => window.rigidReport.view.recorder.type), null);
      assert.match(await page.locator('.record-row .record-note').textContent(), /neither WebCodecs nor MediaRecorder: PNG frames only/);
      assert.deepEqual(await page.locator('.record-row select.record-format option').allTextContents(), ['PNG frames (.tar)']);
      await setUpSpan(page);
      const tar = await download(page, page.locator('.record-row button.record'));
      assert.equal(tar.name, 'physical_pendulum_0-0.5s.tar');
      const files = untar(tar.bytes);
      assert.deepEqual(files.map((f) => f.name), [0, 1, 2, 3, 4, 5].map((k) => `physical_pendulum_0s/frame_0000${k}.png`));
      const size = await page.evaluate(() => [window.rigidReport.view.canvas.width, window.rigidReport.view.canvas.height]);
      for (const f of files) {
        assert.deepEqual([...f.bytes.subarray(0, 8)], kPng);
        assert.deepEqual(pngSize(f.bytes), size);
      }
      // each frame differs from the one before it (the rod has moved), and frame k is the
      // view at t = 0.1 k: the same pixels as the canvas rendered at that time, within the
      // PNG round trip (lossless: no pixel differs)
      for (let k = 1; k < files.length; k += 1) {
        const stats = await pixelStats(page, Buffer.from(files[k].bytes), Buffer.from(files[k - 1].bytes));
        assert.ok(stats.changed > 0.001, `frame ${k} vs ${k - 1}: ${JSON.stringify(stats)}`);
      }
      for (const k of [0, 3]) {
        const now = Buffer.from(await page.evaluate(async (t) => {
          window.rigidReport.setTime(t);
          window.rigidReport.view.render();
          const b = await new Promise((r) => window.rigidReport.view.canvas.toBlob(r, 'image/png'));
          return [...new Uint8Array(await b.arrayBuffer())];
        }, 0.1 * k));
        const stats = await pixelStats(page, now, Buffer.from(files[k].bytes));
        assert.equal(stats.changed, 0, `frame ${k} is the view at t = ${0.1 * k}`);
      }
      assert.deepEqual(errors, []);
    } finally {
      await page.close();
    }
  });

  test('the PNG button saves the 3D view at the canvas size', async () => {
    const { page, problems } = await openPage(browser, join(dir, 'report.html'));
    try {
      await page.evaluate(() => window.rigidReport.setTime(1));
      const png = await download(page, page.locator('.toggles button.download'));
      assert.equal(png.name, 'physical_pendulum-view.png');
      assert.deepEqual([...png.bytes.subarray(0, 8)], kPng);
      const size = await page.evaluate(() => [window.rigidReport.view.canvas.width, window.rigidReport.view.canvas.height]);
      assert.deepEqual(pngSize(png.bytes), size);
      const stats = await pixelStats(page, png.bytes);
      assert.ok(stats.notBackground > 0.01 && stats.colours > 4, JSON.stringify(stats));
      assert.deepEqual(problems, []);
    } finally {
      await page.close();
    }
  });
});
