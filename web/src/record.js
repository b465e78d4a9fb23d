// Recording the 3D view's animation for slides: a "record" control beside the player that
// steps the page's time by (1/fps) × speed per frame, renders, and captures that frame, from the
// current time to the end (or for a chosen span of simulated time). Where the browser has
// MediaRecorder and canvas.captureStream, the frames become one WebM (vp9 or vp8, or MP4 where
// only that is recorded); elsewhere they are PNG images packed in one uncompressed .tar (ustar).
// The frames are the same on a slow machine: the recorder's clock, not the wall clock, sets
// the time of each. (In a video the wall clock still stamps each frame: a machine that cannot
// render at the chosen rate makes a video that plays slower, never one with other frames.)
import { el, saveDataUrl } from './format.js';

const kRates = [10, 24, 25, 30, 50, 60];
// after the last frame: the most to wait for the encoder, and (where its frames cannot be
// counted: MP4) how long it must have written nothing
const kDrainMs = 60000;
const kQuietMs = 3000;
// the most frames one recording makes (10 min at 30 fps): PNG frames are held in memory
const kMaxFrames = 18000;

/** The first recording type MediaRecorder says it supports, or null (none, or no MediaRecorder). */
export function videoType() {
  if (typeof window.MediaRecorder !== 'function' || typeof MediaRecorder.isTypeSupported !== 'function') return null;
  if (typeof HTMLCanvasElement.prototype.captureStream !== 'function') return null;
  const types = ['video/webm;codecs=vp9', 'video/webm;codecs=vp8', 'video/webm', 'video/mp4;codecs=avc1', 'video/mp4'];
  return types.find((t) => MediaRecorder.isTypeSupported(t)) ?? null;
}

/**
 * The number of whole frames (SimpleBlocks, BlockGroups) in the start of a WebM file (EBML, RFC
 * 8794; Matroska's element IDs, RFC 9559). Segment, Cluster and BlockGroup are entered (a
 * recorder writes Segments and Clusters of unknown size); other elements are skipped by their
 * size. An element cut off by the end is not counted.
 */
export function webmFrames(b) {
  const kEnter = new Set([0x18538067, 0x1f43b675]);
  const vint = (at, keepMarker) => {
    if (at >= b.length) return null;
    let len = 1;
    while (len <= 8 && !(b[at] & (0x80 >> (len - 1)))) len += 1;
    if (len > 8 || at + len > b.length) return null;
    let v = keepMarker ? b[at] : b[at] & ((0x80 >> (len - 1)) - 1);
    for (let i = 1; i < len; i += 1) v = v * 256 + b[at + i];
    return { v, len };
  };
  let frames = 0;
  let at = 0;
  for (;;) {
    const id = vint(at, true);
    const size = id && vint(at + id.len, false);
    if (!size) return frames;
    const body = at + id.len + size.len;
    if (kEnter.has(id.v)) {
      at = body;
      continue;
    }
    if (body + size.v > b.length) return frames;
    if (id.v === 0xa3 || id.v === 0xa0) frames += 1;
    at = body + size.v;
  }
}

const ascii = (s) => Uint8Array.from(s, (c) => c.charCodeAt(0) & 0x7f);

/**
 * An uncompressed tar archive (POSIX ustar, IEEE 1003.1-1988 / POSIX.1-2001 "pax" base format)
 * of `entries` = [{name, bytes: Uint8Array}]: per file a 512-byte header and the data padded
 * to 512 bytes, then two zero blocks. Names are ASCII of at most 100 bytes.
 */
export function tarArchive(entries, mtime = Math.floor(Date.now() / 1000)) {
  const size = entries.reduce((s, e) => s + 512 + Math.ceil(e.bytes.length / 512) * 512, 1024);
  const out = new Uint8Array(size);
  let at = 0;
  const octal = (v, width) => `${v.toString(8).padStart(width - 1, '0')}\0`;
  for (const e of entries) {
    if (e.name.length > 100) throw new Error(`tar: name longer than 100 bytes: ${e.name}`);
    const h = out.subarray(at, at + 512);
    const put = (offset, text) => h.set(ascii(text), offset);
    put(0, e.name);
    put(100, octal(0o644, 8)); // mode
    put(108, octal(0, 8)); // uid
    put(116, octal(0, 8)); // gid
    put(124, octal(e.bytes.length, 12)); // size
    put(136, octal(mtime, 12)); // mtime
    put(148, '        '); // the checksum counts its own field as 8 spaces
    put(156, '0'); // a regular file
    put(257, 'ustar\0'); // magic
    put(263, '00'); // version
    put(265, 'rigid'); // uname
    put(297, 'rigid'); // gname
    let sum = 0;
    for (const b of h) sum += b;
    put(148, `${sum.toString(8).padStart(6, '0')}\0 `);
    out.set(e.bytes, at + 512);
    at += 512 + Math.ceil(e.bytes.length / 512) * 512;
  }
  return out;
}

// a time in a file name: at most 3 decimals, no trailing zeros
const stamp = (t) => String(Number(t.toFixed(3)));

const megabytes = (n) => `${(n / 1048576).toFixed(n < 10485760 ? 2 : 1)} MB`;

const pause = (ms) => new Promise((r) => setTimeout(r, Math.max(0, ms)));

function save(blob, name) {
  const url = URL.createObjectURL(blob);
  saveDataUrl(url, name);
  // the download has its own copy well before this
  setTimeout(() => URL.revokeObjectURL(url), 60000);
}

/**
 * The control, in a row after `bar` (the player's row): `canvas` is the 3D view's canvas (drawn
 * with preserveDrawingBuffer), `render()` draws the current frame at once, `name` the scene's.
 * Returns {record(): Promise of {name, size, frames} once the file is offered, type (the video
 * type, or null where there is none: PNG frames only)}.
 */
export function buildRecorder({ canvas, render, player, name, bar }) {
  const type = videoType();
  const videoExt = type?.startsWith('video/mp4') ? 'mp4' : 'webm';
  const videoName = type === null ? null : `${videoExt === 'mp4' ? 'MP4' : 'WebM'} (${/codecs=(\w+)/.exec(type)?.[1] ?? 'default codec'})`;
  const framesName = 'PNG frames (.tar)';
  const button = el('button', {
    type: 'button', class: 'record',
    title: 'record the 3D view from the current time to the end (or for the span) at the player’s speed',
    text: '● record',
  });
  const fps = el('select', { class: 'record-fps', title: 'frames per second of the recording', 'aria-label': 'recording frame rate' },
    ...kRates.map((r) => {
      const o = el('option', { value: String(r), text: `${r} fps` });
      if (r === 30) o.selected = true;
      return o;
    }));
  const span = el('input', {
    type: 'number', class: 'record-span', min: '0', step: 'any', placeholder: 'to end',
    title: 'simulated seconds to record from the current time (empty: to the end)', 'aria-label': 'recording span (s)',
  });
  span.style.width = '5.5em';
  // the format: the video where the browser records one, else PNG frames (said in the note)
  const format = el('select', { class: 'record-format', title: 'what the recording is saved as', 'aria-label': 'recording format' },
    ...(type === null ? [] : [el('option', { value: 'video', text: videoName })]),
    el('option', { value: 'png', text: framesName }));
  const note = el('span', { class: 'record-note', text: type === null ? 'this browser has no MediaRecorder: PNG frames only' : '' });
  note.style.fontSize = '0.8rem';
  // a row of its own under the player's
  const row = el('div', { class: 'player record-row' }, button, format, fps,
    el('label', { title: span.title }, 'span ', span, ' s'), note);
  button.style.whiteSpace = 'nowrap';
  bar.after(row);

  let busy = null;
  let stop = false;

  const record = async () => {
    player.pause();
    const ts = player.ts;
    const tEnd = ts[ts.length - 1];
    if (player.index >= ts.length - 1) player.setIndex(0);
    const t0 = player.time();
    const rate = Number(fps.value);
    const asked = span.value === '' ? Infinity : Number(span.value);
    const length = Math.max(0, Math.min(Number.isFinite(asked) ? asked : Infinity, tEnd - t0));
    const dt = player.speed / rate;
    // frames at t0, t0 + dt, …, never past the end; one at least
    const count = Math.floor(length / dt + 1e-9) + 1;
    if (count > kMaxFrames) {
      throw new Error(`${count} frames is more than ${kMaxFrames}: choose a shorter span, a lower rate or a higher speed`);
    }
    const frameAt = (k) => {
      player.setTime(t0 + k * dt);
      render();
    };
    let done = 0;
    let written = null;
    const progress = () => { note.textContent = `recording frame ${done}/${count}… (click to stop)`; };
    const video = type !== null && format.value === 'video';
    const ext = video ? videoExt : 'tar';
    let blob;
    if (video) {
      // captureStream(0) with requestFrame: exactly one video frame per rendered frame; without
      // requestFrame, the canvas is sampled at the rate
      let stream = canvas.captureStream(0);
      let track = stream.getVideoTracks()[0];
      if (typeof track.requestFrame !== 'function') {
        track.stop();
        stream = canvas.captureStream(rate);
        track = null;
      }
      const chunks = [];
      let lastData = performance.now();
      const recorder = new MediaRecorder(stream, { mimeType: type, videoBitsPerSecond: 8e6 });
      recorder.ondataavailable = (e) => {
        if (e.data.size > 0) {
          chunks.push(e.data);
          lastData = performance.now();
        }
      };
      const stopped = new Promise((r) => { recorder.onstop = r; });
      // data every 100 ms: how the encoder's progress is seen
      recorder.start(100);
      const start = performance.now();
      for (let k = 0; k < count && !stop; k += 1) {
        frameAt(k);
        if (track) track.requestFrame();
        done = k + 1;
        progress();
        // each frame held for 1/fps of wall time (the video's own clock)
        await pause(start + (k + 1) * (1000 / rate) - performance.now());
      }
      // the encoder runs behind the frames (a second or more for a large view in software), and
      // a stop drops what it has not written: stopped once a WebM holds every frame sent but the
      // last (which the muxer keeps until the next frame or the stop, and the stop writes), or
      // once nothing was written for kQuietMs (an MP4, whose frames are not counted here; an
      // encoder that keeps more), at most kDrainMs after the last frame
      const last = performance.now();
      const inFile = async () => (videoExt === 'webm' ? webmFrames(new Uint8Array(await new Blob(chunks).arrayBuffer())) : null);
      for (;;) {
        const n = await inFile();
        note.textContent = `encoding the last frames… (${n ?? '?'} of ${done} written)`;
        const now = performance.now();
        if ((n !== null && n >= done - 1) || now - Math.max(last, lastData) >= kQuietMs) break;
        if (now - last >= kDrainMs) break;
        await pause(n === null ? 100 : 250);
      }
      recorder.stop();
      await stopped;
      for (const t of stream.getTracks()) t.stop();
      blob = new Blob(chunks, { type: type.split(';')[0] });
      if (videoExt === 'webm') {
        // what the file holds (a frame the encoder dropped is not in it)
        written = webmFrames(new Uint8Array(await blob.arrayBuffer()));
      }
    } else {
      const entries = [];
      const dir = `${name}_${stamp(t0)}s`;
      for (let k = 0; k < count && !stop; k += 1) {
        frameAt(k);
        const png = await new Promise((r) => canvas.toBlob(r, 'image/png'));
        entries.push({ name: `${dir}/frame_${String(k).padStart(5, '0')}.png`, bytes: new Uint8Array(await png.arrayBuffer()) });
        done = k + 1;
        progress();
        // let the page answer (the stop button) between frames
        await pause(0);
      }
      blob = new Blob([tarArchive(entries)], { type: 'application/x-tar' });
    }
    const t1 = t0 + Math.max(0, done - 1) * dt;
    const file = `${name}_${stamp(t0)}-${stamp(t1)}s.${ext}`;
    save(blob, file);
    const lost = written !== null && written < done ? `; ${done - written} dropped by the encoder` : '';
    note.textContent = `saved ${file} (${written ?? done} frames at ${rate} fps${lost}, ${megabytes(blob.size)})`;
    return { name: file, size: blob.size, frames: written ?? done };
  };

  const run = () => {
    if (busy) return busy;
    stop = false;
    button.textContent = '■ stop';
    busy = record().finally(() => {
      busy = null;
      button.textContent = '● record';
    });
    return busy;
  };
  button.addEventListener('click', () => {
    if (busy) stop = true;
    else run().catch((e) => { note.textContent = `recording failed: ${e.message}`; });
  });
  return { record: run, type };
}
