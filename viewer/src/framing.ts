// What the camera frames: the bodies at the start, over the whole run, or now; and which body (or
// all of them) the camera follows when the page opens. Plain numbers, so the unit tests check them
// without WebGL; scene3d.ts turns them into a camera.

import { comTrack } from './derived';
import type { Report, Vec3 } from './types';

/** A sphere that holds what is to be seen. */
export interface Sphere {
  center: Vec3;
  radius: number;
}

/** The camera's choice in the "follow" control besides a body's index: no body, or all of them. */
export const FREE_CAMERA = -1;
export const FOLLOW_ALL = -2;

/** Grows an axis-aligned box [lo, hi] by the cube of half-side h about p; NaN is skipped. */
function grow(lo: number[], hi: number[], p: ArrayLike<number>, h: number): void {
  // NaN fails every comparison: a sample that blew up does not stretch the view to infinity.
  if (!(Number.isFinite(p[0]) && Number.isFinite(p[1]) && Number.isFinite(p[2]))) return;
  for (let k = 0; k < 3; k++) {
    if (p[k] - h < lo[k]) lo[k] = p[k] - h;
    if (p[k] + h > hi[k]) hi[k] = p[k] + h;
  }
}

/** The sphere around the box [lo, hi]; `fallback` when the box is empty. */
function sphereOf(lo: number[], hi: number[], fallback: Sphere): Sphere {
  if (!(lo[0] <= hi[0] && lo[1] <= hi[1] && lo[2] <= hi[2])) return fallback;
  const center: Vec3 = [(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2];
  return { center, radius: Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) / 2 };
}

/** The default view shows the start sphere's radius times this (scene3d.ts), at the narrower angle of view. */
export const FRAME_MARGIN = 1.15;

const UNIT: Sphere = { center: [0, 0, 0], radius: Math.sqrt(3) };

/** Each body's size: every point drawn of it is within this of its centre of mass. */
export function sizesOf(r: Report): Float64Array {
  return Float64Array.from(r.bodies, (b) => Math.max(b.size, 0));
}

/** Where the bodies are: at the start (their centres of mass ± size), and over the whole run. */
export interface Framing {
  start: Sphere;
  run: Sphere;
  /** The box of the whole run (the grid lies under it); null when no sample is finite. */
  runBox: { lo: Vec3; hi: Vec3 } | null;
}

export function runFraming(r: Report): Framing {
  const size = sizesOf(r);
  const startLo = [Infinity, Infinity, Infinity], startHi = [-Infinity, -Infinity, -Infinity];
  const runLo = [Infinity, Infinity, Infinity], runHi = [-Infinity, -Infinity, -Infinity];
  for (let b = 0; b < r.bodies.length; b++) {
    const track = comTrack(r, b);
    grow(startLo, startHi, track, size[b]);
    for (let i = 0; i < track.length; i += 3) grow(runLo, runHi, track.subarray(i, i + 3), size[b]);
  }
  const start = sphereOf(startLo, startHi, UNIT);
  const run = sphereOf(runLo, runHi, start);
  const runBox = run === start ? null : { lo: runLo as Vec3, hi: runHi as Vec3 };
  return { start, run, runBox };
}

/** The bodies now, from their centres of mass (3 numbers each) and sizes; null when none is finite. */
export function sphereNow(com: ArrayLike<number>, size: Float64Array): Sphere | null {
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  const p = [0, 0, 0];
  for (let b = 0; b < size.length; b++) {
    p[0] = com[3 * b];
    p[1] = com[3 * b + 1];
    p[2] = com[3 * b + 2];
    grow(lo, hi, p, size[b]);
  }
  const s = sphereOf(lo, hi, UNIT);
  return s === UNIT ? null : s;
}

/** Whether `outer`, grown by `margin`, holds `inner`. */
function holds(outer: Sphere, inner: Sphere, margin: number): boolean {
  const d = Math.hypot(outer.center[0] - inner.center[0], outer.center[1] - inner.center[1], outer.center[2] - inner.center[2]);
  return d + inner.radius <= outer.radius * margin;
}

/**
 * What the camera follows when the page opens: a lone body (a thrown box leaves a view framed on its
 * start within a second, an orbiting satellite at once); all the bodies when, together, they leave
 * the view of their start (the camera keeps all of them in view); else nothing (the view framed on
 * the start holds the whole run). The "follow" control switches.
 */
export function defaultFollow(r: Report, framing = runFraming(r)): number {
  if (r.bodies.length === 1 && r.bodies[0].kind === 'body') return 0;
  return holds(framing.start, framing.run, FRAME_MARGIN) ? FREE_CAMERA : FOLLOW_ALL;
}
