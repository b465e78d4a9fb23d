// Recording the 3D view's animation for slides: a "record" control beside the player that
// steps the page's time by (1/fps) × speed per frame, renders, and captures that frame, from the
// current time to the end (or for a chosen span of simulated time). Where the page may use
// WebCodecs (a secure context: https or a file), each frame is encoded (vp9, else vp8) with its
// own time, k/fps, and the frames are written as one WebM here (webmFile): the video plays at
// the chosen rate however slowly the machine rendered it. Elsewhere, MediaRecorder and
// canvas.captureStream make the WebM (or MP4 where only that is recorded), and the wall clock
// stamps each frame (held for 1/fps: a machine that cannot keep up makes a video that plays
// slower, never one with other frames); without either, PNG images in one uncompressed .tar.
import { el, saveDataUrl } from './format.js';

const kRates = [10, 24, 25, 30, 50, 60];
// after the last frame: the most to wait for the encoder, and (where its frames cannot be
// counted: MP4) how long it must have written nothing
const kDrainMs = 60000;
const kQuietMs = 3000;
// the most frames one recording makes (10 min at 30 fps): PNG frames are held in memory
const kMaxFrames = 18000;

/** True where the page may encode frames itself (WebCodecs: a secure context, https or a file). */
export function hasEncoder() {
  return typeof window.VideoEncoder === 'function' && typeof window.VideoFrame === 'function';
}

// the codecs tried for an encoded WebM, in order: WebCodecs' codec string, Matroska's CodecID
const kEncoderCodecs = [{ codec: 'vp09.00.10.08', id: 'V_VP9', name: 'vp9' }, { codec: 'vp8', id: 'V_VP8', name: 'vp8' }];

/** The first of kEncoderCodecs VideoEncoder supports for a width × height view at `rate`, or null. */
async function encoderCodec(width, height, rate) {
  for (const c of kEncoderCodecs) {
    const config = { codec: c.codec, width, height, bitrate: 8e6, framerate: rate, latencyMode: 'quality' };
    try {
      if ((await VideoEncoder.isConfigSupported(config)).supported) return { ...c, config };
    } catch {
      // a codec string this browser does not parse: the next
    }
  }
  return null;
}

/**
 * A WebM file (EBML, RFC 8794; Matroska's elements, RFC 9559; WebM's subset) of one video track:
 * `codecId` (V_VP9, V_VP8), width × height pixels, `frames` = [{ms, key, data: Uint8Array}] in
 * order with their times in ms (TimecodeScale 1 ms) and `durationMs`. A cluster starts at each
 * key frame (and before a frame 30 s after its cluster's start: a block's time is 16 bits), each
 * frame one SimpleBlock. Sizes are known, so every element states its own.
 */
export function webmFile({ codecId, width, height, rate, frames, durationMs }) {
  const bytesOf = (v, n) => {
    const out = new Uint8Array(n);
    for (let i = n - 1; i >= 0; i -= 1) {
      out[i] = v % 256;
      v = Math.floor(v / 256);
    }
    return out;
  };
  const concat = (parts) => {
    const out = new Uint8Array(parts.reduce((s, p) => s + p.length, 0));
    let at = 0;
    for (const p of parts) {
      out.set(p, at);
      at += p.length;
    }
    return out;
  };
  // an element ID as written (its length marker included), then the size as a variable-size
  // integer of the fewest bytes (all ones is reserved for "unknown"), then the payload
  const element = (id, payload) => {
    const idLength = id > 0xffffff ? 4 : id > 0xffff ? 3 : id > 0xff ? 2 : 1;
    let n = 1;
    while (payload.length >= 2 ** (7 * n) - 1) n += 1;
    const size = bytesOf(payload.length, n);
    size[0] |= 0x80 >> (n - 1);
    return concat([bytesOf(id, idLength), size, payload]);
  };
  const uint = (id, v) => {
    let n = 1;
    while (v >= 2 ** (8 * n)) n += 1;
    return element(id, bytesOf(v, n));
  };
  const text = (id, s) => element(id, ascii(s));
  const float = (id, v) => {
    const b = new Uint8Array(8);
    new DataView(b.buffer).setFloat64(0, v);
    return element(id, b);
  };
  const header = element(0x1a45dfa3, concat([
    uint(0x4286, 1), uint(0x42f7, 1), uint(0x42f2, 4), uint(0x42f3, 8), text(0x4282, 'webm'), uint(0x4287, 4), uint(0x4285, 2),
  ]));
  const info = element(0x1549a966, concat([uint(0x2ad7b1, 1e6), float(0x4489, durationMs), text(0x4d80, 'rigid'), text(0x5741, 'rigid')]));
  const tracks = element(0x1654ae6b, element(0xae, concat([
    uint(0xd7, 1), uint(0x73c5, 1), uint(0x83, 1), uint(0x9c, 0), text(0x86, codecId), uint(0x23e383, Math.round(1e9 / rate)),
    element(0xe0, concat([uint(0xb0, width), uint(0xba, height)])),
  ])));
  const clusters = [];
  let cluster = null;
  const close = () => {
    if (cluster) clusters.push(element(0x1f43b675, concat([uint(0xe7, cluster.ms), ...cluster.blocks])));
  };
  for (const f of frames) {
    if (!cluster || f.key || f.ms - cluster.ms > 30000) {
      close();
      cluster = { ms: f.ms, blocks: [] };
    }
    // track 1, the time relative to the cluster's (signed 16 bits), flags (0x80: a key frame)
    const head = new Uint8Array(4);
    head[0] = 0x81;
    new DataView(head.buffer).setInt16(1, f.ms - cluster.ms);
    head[3] = f.key ? 0x80 : 0;
    cluster.blocks.push(element(0xa3, concat([head, f.data])));
  }
  close();
  return concat([header, element(0x18538067, concat([info, tracks, ...clusters]))]);
}

/**
 * Encodes `count` frames with WebCodecs: frameAt(k) draws frame k on `canvas`, which is
 * encoded with the time k/rate (a key frame every two seconds); `shouldStop()` ends early and
 * `onFrame(k)` follows the progress. Returns {bytes (a WebM), frames, codec}, or null where no
 * codec of kEncoderCodecs is supported for this view.
 */
async function encodeWebm({ canvas, rate, count, frameAt, shouldStop, onFrame }) {
  const { width, height } = canvas;
  const codec = await encoderCodec(width, height, rate);
  if (!codec) return null;
  const chunks = [];
  let failure = null;
  const encoder = new VideoEncoder({
    output: (chunk) => {
      const data = new Uint8Array(chunk.byteLength);
      chunk.copyTo(data);
      chunks.push({ us: chunk.timestamp, key: chunk.type === 'key', data });
    },
    error: (e) => { failure = e; },
  });
  encoder.configure(codec.config);
  const keyEvery = 2 * rate;
  let done = 0;
  for (let k = 0; k < count && !shouldStop() && !failure; k += 1) {
    frameAt(k);
    const frame = new VideoFrame(canvas, { timestamp: Math.round((k * 1e6) / rate), duration: Math.round(1e6 / rate) });
    encoder.encode(frame, { keyFrame: k % keyEvery === 0 });
    frame.close();
    done = k + 1;
    onFrame(done);
    // a few frames in the encoder at most (each holds a copy of the view), and the page
    // answers between frames (the stop button)
    do await pause(0); while (encoder.encodeQueueSize > 2 && !failure);
  }
  await encoder.flush().catch((e) => { failure = failure ?? e; });
  encoder.close();
  if (failure) throw new Error(`the video encoder failed: ${failure.message ?? failure}`);
  chunks.sort((a, b) => a.us - b.us);
  const frames = chunks.map((c) => ({ ms: Math.round(c.us / 1000), key: c.key, data: c.data }));
  const bytes = webmFile({ codecId: codec.id, width, height, rate, frames, durationMs: (done * 1000) / rate });
  return { bytes, frames: frames.length, codec: codec.name };
}

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
 * Returns {record(): Promise of {name, size, frames, codec} once the file is offered, type (the
 * MediaRecorder type, or null), encoder (true where frames are encoded with their own times)}.
 */
export function buildRecorder({ canvas, render, player, name, bar }) {
  const type = videoType();
  const encoder = hasEncoder();
  // what MediaRecorder writes
  const recorderExt = type?.startsWith('video/mp4') ? 'mp4' : 'webm';
  const videoName = encoder ? 'WebM (exact frame times)'
    : type === null ? null : `${recorderExt === 'mp4' ? 'MP4' : 'WebM'} (${/codecs=(\w+)/.exec(type)?.[1] ?? 'default codec'})`;
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
    ...(videoName === null ? [] : [el('option', { value: 'video', text: videoName })]),
    el('option', { value: 'png', text: framesName }));
  const note = el('span', { class: 'record-note', text: videoName === null ? 'this browser has neither WebCodecs nor MediaRecorder: PNG frames only' : '' });
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
    const video = videoName !== null && format.value === 'video';
    let ext = video ? 'webm' : 'tar';
    let blob;
    let codec = null;
    // WebCodecs: each frame encoded with its own time, the WebM written here
    const encoded = video && encoder
      ? await encodeWebm({ canvas, rate, count, frameAt, shouldStop: () => stop, onFrame: (k) => { done = k; progress(); } })
      : null;
    if (video && encoder && encoded === null && type === null) {
      throw new Error(`no video codec (vp9, vp8) encodes a ${canvas.width} × ${canvas.height} view here: choose PNG frames`);
    }
    if (encoded) {
      blob = new Blob([encoded.bytes], { type: 'video/webm' });
      written = encoded.frames;
      codec = encoded.codec;
    } else if (video) {
      ext = recorderExt;
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
      const inFile = async () => (recorderExt === 'webm' ? webmFrames(new Uint8Array(await new Blob(chunks).arrayBuffer())) : null);
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
      codec = /codecs=(\w+)/.exec(type)?.[1] ?? null;
      if (recorderExt === 'webm') {
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
    note.textContent = `saved ${file} (${written ?? done} frames at ${rate} fps${codec ? `, ${codec}` : ''}${lost}, ${megabytes(blob.size)})`;
    return { name: file, size: blob.size, frames: written ?? done, codec };
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
  return { record: run, type, encoder };
}
