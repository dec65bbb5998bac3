// Decodes and validates the report JSON (README.md "Data contract") into typed arrays.
//
// Everything is checked before anything is drawn: a report that does not match the contract shows
// one clear message naming the field (e.g. "series.position: shape [10, 2, 3] does not match
// (T=10, N=1, 3)") instead of a blank page or a half-drawn scene.

import { Base64Error, base64ToBytes } from './base64';
import type {
  Body,
  Mat3,
  Mesh,
  Meta,
  Report,
  Series,
  Spring,
  SystemSeries,
  TumbleEvent,
  Vec3,
} from './types';

export class DataError extends Error {}

export type DType = 'f32' | 'f64' | 'u32';
export type TypedArray = Float32Array | Float64Array | Uint32Array;

const ITEM_SIZE: Record<DType, number> = { f32: 4, f64: 8, u32: 4 };

type Json = unknown;

function isObject(x: Json): x is Record<string, Json> {
  return typeof x === 'object' && x !== null && !Array.isArray(x);
}

function fail(where: string, what: string): never {
  throw new DataError(`${where}: ${what}`);
}

/**
 * One encoded array `{dtype, shape, base64}` to a typed array of that dtype. The byte count must be
 * product(shape) * itemsize exactly: a truncated or padded array is an error, never silently read.
 *
 * A plain JSON array of numbers (nested or flat; null for NaN, since JSON has no NaN) is accepted
 * too and becomes a Float64Array: it costs nothing and lets small hand-written reports work.
 */
export function decodeArray(x: Json, where: string): { data: TypedArray; shape: number[] } {
  if (Array.isArray(x)) return decodePlainArray(x, where);
  if (!isObject(x)) fail(where, 'expected an encoded array {dtype, shape, base64}');
  const dtype = x.dtype;
  if (typeof dtype !== 'string' || !(dtype in ITEM_SIZE)) {
    fail(where, `unknown dtype ${JSON.stringify(dtype)} (expected "f32", "f64" or "u32")`);
  }
  const shape = x.shape;
  if (
    !Array.isArray(shape) ||
    !shape.every((d) => typeof d === 'number' && Number.isInteger(d) && d >= 0)
  ) {
    fail(where, `shape must be a list of non-negative integers, got ${JSON.stringify(shape)}`);
  }
  if (typeof x.base64 !== 'string') fail(where, 'base64 must be a string');
  let bytes: Uint8Array;
  try {
    bytes = base64ToBytes(x.base64);
  } catch (e) {
    if (e instanceof Base64Error) fail(where, e.message);
    throw e;
  }
  const count = (shape as number[]).reduce((a, b) => a * b, 1);
  const size = ITEM_SIZE[dtype as DType];
  if (bytes.byteLength !== count * size) {
    fail(
      where,
      `${bytes.byteLength} bytes, but shape ${JSON.stringify(shape)} of ${dtype} needs ` +
        `${count * size}`,
    );
  }
  // A fresh Uint8Array starts its own buffer at offset 0, so any element type is aligned. The data
  // are little-endian; so is every machine a browser runs on, which the typed-array views assume.
  const buf = bytes.buffer as ArrayBuffer;
  const off = bytes.byteOffset;
  let data: TypedArray;
  if (off % 8 !== 0) {
    const copy = bytes.slice();
    data = makeView(dtype as DType, copy.buffer as ArrayBuffer, 0, count);
  } else {
    data = makeView(dtype as DType, buf, off, count);
  }
  return { data, shape: shape as number[] };
}

function makeView(dtype: DType, buf: ArrayBuffer, off: number, count: number): TypedArray {
  switch (dtype) {
    case 'f32':
      return new Float32Array(buf, off, count);
    case 'f64':
      return new Float64Array(buf, off, count);
    case 'u32':
      return new Uint32Array(buf, off, count);
  }
}

function decodePlainArray(x: Json[], where: string): { data: Float64Array; shape: number[] } {
  const shape: number[] = [];
  let level: Json = x;
  while (Array.isArray(level)) {
    shape.push(level.length);
    level = level[0];
  }
  const flat = (x as unknown[]).flat(Infinity);
  const count = shape.reduce((a, b) => a * b, 1);
  if (flat.length !== count) fail(where, 'nested arrays are ragged');
  const data = new Float64Array(count);
  for (let i = 0; i < count; i++) {
    const v = flat[i];
    if (v === null) data[i] = NaN;
    else if (typeof v === 'number') data[i] = v;
    else fail(where, `element ${i} is ${JSON.stringify(v)}, not a number or null`);
  }
  return { data, shape };
}

/**
 * Checks that `shape` is `expected` (e.g. [T, N, 3]) or its flattened form [T*N*3]: the contract
 * fixes the row-major layout and element count, and both spellings of the shape say the same.
 */
export function checkShape(shape: number[], expected: number[], where: string, names: string): void {
  const same = (a: number[], b: number[]) => a.length === b.length && a.every((v, i) => v === b[i]);
  const flat = [expected.reduce((a, b) => a * b, 1)];
  if (same(shape, expected) || same(shape, flat)) return;
  fail(where, `shape ${JSON.stringify(shape)} does not match (${names})`);
}

function str(x: Json, where: string, fallback?: string): string {
  if (typeof x === 'string') return x;
  if (x === undefined && fallback !== undefined) return fallback;
  fail(where, `expected a string, got ${JSON.stringify(x)}`);
}

/** A number; JSON null stands for NaN (JSON cannot spell NaN), `undefined` takes the fallback. */
function num(x: Json, where: string, fallback?: number): number {
  if (typeof x === 'number') return x;
  if (x === null) return NaN;
  if (x === undefined && fallback !== undefined) return fallback;
  fail(where, `expected a number, got ${JSON.stringify(x)}`);
}

function vec3(x: Json, where: string): Vec3 {
  if (!Array.isArray(x) || x.length !== 3) fail(where, 'expected 3 numbers');
  return [num(x[0], where), num(x[1], where), num(x[2], where)];
}

function mat3(x: Json, where: string): Mat3 {
  if (!Array.isArray(x) || x.length !== 3) fail(where, 'expected a 3x3 matrix (3 rows)');
  return [vec3(x[0], `${where}[0]`), vec3(x[1], `${where}[1]`), vec3(x[2], `${where}[2]`)];
}

function decodeMeta(x: Json, T: number): Meta {
  if (!isObject(x)) fail('meta', 'expected an object');
  const warnings = x.warnings ?? [];
  if (!Array.isArray(warnings)) fail('meta.warnings', 'expected a list of strings');
  const wall = x.wall_time_s;
  return {
    tumble_version: str(x.tumble_version, 'meta.tumble_version', '?'),
    scene_path: str(x.scene_path, 'meta.scene_path', ''),
    scene_text: str(x.scene_text, 'meta.scene_text', ''),
    integrator: str(x.integrator, 'meta.integrator', '?'),
    formulation: str(x.formulation, 'meta.formulation', '?'),
    timestep: num(x.timestep, 'meta.timestep', NaN),
    duration: num(x.duration, 'meta.duration', NaN),
    wall_time_s: wall === null || wall === undefined ? null : num(wall, 'meta.wall_time_s'),
    samples_total: num(x.samples_total, 'meta.samples_total', T),
    samples_shown: num(x.samples_shown, 'meta.samples_shown', T),
    warnings: warnings.map((w, i) => str(w, `meta.warnings[${i}]`)),
  };
}

/** A surface {positions, indices}, its indices checked against its vertices. */
function decodeMesh(x: Json, where: string): Mesh {
  if (!isObject(x)) fail(where, 'expected {positions, indices}');
  const p = decodeArray(x.positions, `${where}.positions`);
  const ix = decodeArray(x.indices, `${where}.indices`);
  if (p.data.length % 3 !== 0) fail(`${where}.positions`, 'length is not a multiple of 3');
  if (ix.data.length % 3 !== 0) fail(`${where}.indices`, 'length is not a multiple of 3');
  const V = p.data.length / 3;
  checkShape(p.shape, [V, 3], `${where}.positions`, 'V, 3');
  checkShape(ix.shape, [ix.data.length / 3, 3], `${where}.indices`, 'F, 3');
  const indices = ix.data instanceof Uint32Array ? ix.data : Uint32Array.from(ix.data);
  for (let k = 0; k < indices.length; k++) {
    if (indices[k] >= V) fail(`${where}.indices`, `index ${indices[k]} at ${k} is past the ${V} vertices`);
  }
  const positions = p.data instanceof Float32Array ? p.data : Float32Array.from(p.data);
  return { positions, indices };
}

/**
 * A body. Its mesh is an index into the report's shared meshes (tumble writes each surface once), or
 * the mesh itself (a report made by hand), or null (a sphere).
 */
function decodeBody(x: Json, i: number, meshes: Mesh[]): Body {
  const where = `bodies[${i}]`;
  if (!isObject(x)) fail(where, 'expected an object');
  const kind = x.kind ?? 'body';
  if (kind !== 'body' && kind !== 'particle') {
    fail(`${where}.kind`, `expected "body" or "particle", got ${JSON.stringify(kind)}`);
  }
  let mesh: Body['mesh'] = null;
  if (typeof x.mesh === 'number') {
    if (!Number.isInteger(x.mesh) || x.mesh < 0 || x.mesh >= meshes.length) {
      fail(`${where}.mesh`, `expected an index into meshes [0, ${meshes.length}), got ${x.mesh}`);
    }
    mesh = meshes[x.mesh];
  } else if (x.mesh !== null && x.mesh !== undefined) {
    mesh = decodeMesh(x.mesh, `${where}.mesh`);
  }
  let box: Vec3 | null = null;
  if (x.box !== null && x.box !== undefined) {
    box = vec3(x.box, `${where}.box`);
    if (!box.every((e) => Number.isFinite(e) && e >= 0)) fail(`${where}.box`, 'expected three edges ≥ 0');
    if (!mesh) fail(`${where}.box`, 'a box scales a mesh: give mesh too');
  }
  return {
    name: str(x.name, `${where}.name`, `body ${i}`),
    kind,
    mesh,
    box,
    com: x.com === undefined ? [0, 0, 0] : vec3(x.com, `${where}.com`),
    principal_axes:
      x.principal_axes === undefined
        ? [
            [1, 0, 0],
            [0, 1, 0],
            [0, 0, 1],
          ]
        : mat3(x.principal_axes, `${where}.principal_axes`),
    principal_moments:
      x.principal_moments === undefined
        ? [0, 0, 0]
        : vec3(x.principal_moments, `${where}.principal_moments`),
    size: num(x.size, `${where}.size`, 0),
  };
}

function decodeSpring(x: Json, i: number, N: number): Spring {
  const where = `springs[${i}]`;
  if (!isObject(x)) fail(where, 'expected an object');
  const index = (v: Json, w: string): number => {
    if (typeof v !== 'number' || !Number.isInteger(v) || v < 0 || v >= N) {
      fail(w, `expected a body index in [0, ${N}), got ${JSON.stringify(v)}`);
    }
    return v;
  };
  return {
    a: index(x.a, `${where}.a`),
    b: x.b === null || x.b === undefined ? null : index(x.b, `${where}.b`),
    point_a: vec3(x.point_a ?? [0, 0, 0], `${where}.point_a`),
    point_b: vec3(x.point_b ?? [0, 0, 0], `${where}.point_b`),
  };
}

/** A per-body series (T, N, width), or undefined when absent and optional. */
function perBody(
  x: Json,
  name: string,
  T: number,
  N: number,
  width: number,
): Float32Array | Float64Array | undefined {
  if (x === undefined || x === null) return undefined;
  const where = `series.${name}`;
  const { data, shape } = decodeArray(x, where);
  checkShape(shape, [T, N, width], where, `T=${T}, N=${N}, ${width}`);
  if (data instanceof Uint32Array) fail(where, 'expected f32 or f64, got u32');
  return data;
}

function systemSeries(x: Json, name: string, T: number, width: number) {
  if (x === undefined || x === null) return undefined;
  const where = `system.${name}`;
  const { data, shape } = decodeArray(x, where);
  checkShape(shape, width === 1 ? [T] : [T, width], where, width === 1 ? `T=${T}` : `T=${T}, 3`);
  // Integer data would be odd but harmless: plots want floats with NaN.
  return data instanceof Uint32Array ? Float64Array.from(data) : data;
}

/** The whole report. Throws DataError with the offending field's path. */
export function decodeReport(x: Json): Report {
  if (!isObject(x)) fail('report', 'expected a JSON object');
  if (x.format !== 'tumble-report') {
    fail('format', `expected "tumble-report", got ${JSON.stringify(x.format)}`);
  }
  if (x.version !== 1) {
    fail('version', `this viewer reads version 1, the report is ${JSON.stringify(x.version)}`);
  }
  if (x.t === undefined) fail('t', 'missing');
  const tDec = decodeArray(x.t, 't');
  if (tDec.shape.length !== 1) fail('t', `expected shape [T], got ${JSON.stringify(tDec.shape)}`);
  const t = tDec.data;
  if (t instanceof Uint32Array) fail('t', 'expected f64 (or f32)');
  const T = t.length;
  if (T === 0) fail('t', 'no samples');
  for (let i = 0; i < T; i++) {
    if (!Number.isFinite(t[i])) fail('t', `sample ${i} is ${t[i]}`);
    if (i > 0 && t[i] < t[i - 1]) fail('t', `times decrease at sample ${i}`);
  }

  const meshesJson = x.meshes ?? [];
  if (!Array.isArray(meshesJson)) fail('meshes', 'expected a list');
  const meshes = meshesJson.map((m, k) => decodeMesh(m, `meshes[${k}]`));
  if (!Array.isArray(x.bodies) || x.bodies.length === 0) fail('bodies', 'expected a non-empty list');
  const bodies = x.bodies.map((b, i) => decodeBody(b, i, meshes));
  const N = bodies.length;

  const springsJson = x.springs ?? [];
  if (!Array.isArray(springsJson)) fail('springs', 'expected a list');
  const springs = springsJson.map((s, i) => decodeSpring(s, i, N));

  if (!isObject(x.series)) fail('series', 'missing (position and quaternion are required)');
  const s = x.series;
  if (s.position === undefined || s.position === null) fail('series.position', 'missing');
  if (s.quaternion === undefined || s.quaternion === null) fail('series.quaternion', 'missing');
  const series: Series = {
    position: perBody(s.position, 'position', T, N, 3)!,
    quaternion: perBody(s.quaternion, 'quaternion', T, N, 4)!,
    omega_world: perBody(s.omega_world, 'omega_world', T, N, 3),
    omega_principal: perBody(s.omega_principal, 'omega_principal', T, N, 3),
  };

  const sysJson = x.system ?? {};
  if (!isObject(sysJson)) fail('system', 'expected an object');
  const system: SystemSeries = {
    kinetic_energy: systemSeries(sysJson.kinetic_energy, 'kinetic_energy', T, 1),
    potential_energy: systemSeries(sysJson.potential_energy, 'potential_energy', T, 1),
    total_energy: systemSeries(sysJson.total_energy, 'total_energy', T, 1),
    energy_drift: systemSeries(sysJson.energy_drift, 'energy_drift', T, 1),
    angular_momentum: systemSeries(sysJson.angular_momentum, 'angular_momentum', T, 3),
    angular_momentum_drift: systemSeries(
      sysJson.angular_momentum_drift,
      'angular_momentum_drift',
      T,
      1,
    ),
  };

  const eventsJson = x.events ?? [];
  if (!Array.isArray(eventsJson)) fail('events', 'expected a list');
  const events: TumbleEvent[] = eventsJson.map((e, i) => {
    const where = `events[${i}]`;
    if (!isObject(e)) fail(where, 'expected an object');
    const body = e.body;
    if (body !== null && body !== undefined && (typeof body !== 'number' || body < 0 || body >= N)) {
      fail(`${where}.body`, `expected a body index or null, got ${JSON.stringify(body)}`);
    }
    return {
      name: str(e.name, `${where}.name`),
      t: num(e.t, `${where}.t`),
      body: typeof body === 'number' ? body : null,
    };
  });

  return { meta: decodeMeta(x.meta ?? {}, T), t, bodies, springs, series, system, events };
}

/** "no data" (the raw template), a decoded report, or the reason it could not be read. */
export type Embedded =
  | { kind: 'template' }
  | { kind: 'report'; report: Report }
  | { kind: 'error'; message: string };

// The placeholder spelled as a pattern, not as the literal: the built file must contain the
// literal exactly once (in the data element), or the C++ side's replacement could hit this code.
const PLACEHOLDER = /^\s*_{2}TUMBLE_DATA_{2}\s*$/;

/** Reads the text of the data element as the C++ side fills it in. */
export function readEmbedded(text: string | null | undefined): Embedded {
  if (text === null || text === undefined) {
    return { kind: 'error', message: 'the data element (script#tumble-data) is missing' };
  }
  if (PLACEHOLDER.test(text)) return { kind: 'template' };
  let json: Json;
  try {
    json = JSON.parse(text);
  } catch (e) {
    return { kind: 'error', message: `the data are not valid JSON: ${(e as Error).message}` };
  }
  try {
    return { kind: 'report', report: decodeReport(json) };
  } catch (e) {
    if (e instanceof DataError) return { kind: 'error', message: e.message };
    throw e;
  }
}
