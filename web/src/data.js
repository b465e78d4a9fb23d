// Decoding of the report's JSON (schema version 1): "f32:BASE64" and "u32:BASE64" arrays are
// little-endian float32 / uint32; plain arrays are kept as they are.
const kLittleEndian = new Uint8Array(new Uint32Array([1]).buffer)[0] === 1;

export function decodeArray(v) {
  if (v === null || v === undefined) return null;
  if (Array.isArray(v)) return v;
  if (typeof v !== 'string') throw new Error(`expected an array or "f32:"/"u32:" string, got ${typeof v}`);
  const colon = v.indexOf(':');
  const tag = v.slice(0, colon);
  if (tag !== 'f32' && tag !== 'u32') throw new Error(`unknown array encoding "${tag}"`);
  const bin = atob(v.slice(colon + 1));
  const n = bin.length / 4;
  if (!Number.isInteger(n)) throw new Error(`${tag} array of ${bin.length} bytes (not a multiple of 4)`);
  const bytes = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i += 1) bytes[i] = bin.charCodeAt(i);
  // the data are little-endian: on a little-endian machine (every browser's in practice) the
  // bytes are the array; otherwise each value is read through a DataView
  if (kLittleEndian) return tag === 'f32' ? new Float32Array(bytes.buffer) : new Uint32Array(bytes.buffer);
  const dv = new DataView(bytes.buffer);
  const out = tag === 'f32' ? new Float32Array(n) : new Uint32Array(n);
  for (let i = 0; i < n; i += 1) out[i] = tag === 'f32' ? dv.getFloat32(4 * i, true) : dv.getUint32(4 * i, true);
  return out;
}

export function readReport(text) {
  if (!text) throw new Error('rigid report: no #rigid-report-data element');
  const r = JSON.parse(text);
  if (r.rigid_report !== 1) throw new Error(`rigid report: schema version ${r.rigid_report}, expected 1`);
  return r;
}
