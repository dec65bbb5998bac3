// Quantities the report does not store but the pictures need: each body's centre of mass in the
// world, its angular momentum vector, the scale of the arrows, the magnitude of the system's L.
// Pure functions of the decoded report, so the unit tests check them without a browser.

import { column, matVec, norm, rotate } from './quat';
import { quatAt, quatAtSegment, lerpRow, vecAt, type Segment } from './timeline';
import type { Body, Meta, QuatWXYZ, Report, Vec3 } from './types';

/** World position of a point given in the body's reference frame: x + R p. */
export function toWorld(position: Vec3, q: QuatWXYZ, p: Vec3): Vec3 {
  const r = rotate(q, p);
  return [position[0] + r[0], position[1] + r[1], position[2] + r[2]];
}

/** The centre-of-mass track of one body, T*3 floats (world), for its trail and the camera bounds. */
export function comTrack(r: Report, body: number): Float32Array {
  const T = r.t.length;
  const N = r.bodies.length;
  const com = r.bodies[body].com;
  const out = new Float32Array(T * 3);
  for (let i = 0; i < T; i++) {
    const c = toWorld(vecAt(r.series.position, N, body, i), quatAt(r.series.quaternion, N, body, i), com);
    out[i * 3] = c[0];
    out[i * 3 + 1] = c[1];
    out[i * 3 + 2] = c[2];
  }
  return out;
}

/**
 * Where the L arrow of a body comes from. For a lone body the report's system L (about the world
 * origin) is that body's; with several bodies each one's own L about its centre of mass is
 * R U diag(Λ) ω_p, from its principal rates and moments. Particles spin about nothing: no arrow.
 */
export type LSource = 'system' | 'principal' | null;

export function lSource(r: Report, body: number): LSource {
  const b = r.bodies[body];
  if (b.kind !== 'body') return null;
  if (r.bodies.length === 1 && r.system.angular_momentum) return 'system';
  if (r.series.omega_principal) return 'principal';
  return null;
}

/** L = R U diag(Λ) ω_p in the world, from the orientation q and principal rates ω_p. */
export function angularMomentumWorld(b: Body, q: QuatWXYZ, omegaPrincipal: Vec3): Vec3 {
  const m = b.principal_moments;
  const lPrincipal: Vec3 = [m[0] * omegaPrincipal[0], m[1] * omegaPrincipal[1], m[2] * omegaPrincipal[2]];
  return rotate(q, matVec(b.principal_axes, lPrincipal));
}

/** ω in the world from the principal rates: R U ω_p (when the report has no omega_world). */
export function omegaWorldFromPrincipal(b: Body, q: QuatWXYZ, omegaPrincipal: Vec3): Vec3 {
  return rotate(q, matVec(b.principal_axes, omegaPrincipal));
}

/** The vectors drawn for one body at one instant; null where the report lacks what they need. */
export interface BodyVectors {
  omega: Vec3 | null;
  L: Vec3 | null;
}

const tmp3: number[] = [0, 0, 0];

/** ω and L of `body` at a segment (interpolated between two samples). */
export function bodyVectors(r: Report, body: number, seg: Segment, q?: QuatWXYZ): BodyVectors {
  const N = r.bodies.length;
  const b = r.bodies[body];
  if (b.kind !== 'body') return { omega: null, L: null };
  const rot = q ?? quatAtSegment(r.series.quaternion, N, body, seg);
  let omega: Vec3 | null = null;
  let wp: Vec3 | null = null;
  if (r.series.omega_principal) {
    wp = lerpRow(r.series.omega_principal, N, body, 3, seg, [0, 0, 0]) as Vec3;
  }
  if (r.series.omega_world) {
    omega = lerpRow(r.series.omega_world, N, body, 3, seg, [0, 0, 0]) as Vec3;
  } else if (wp) {
    omega = omegaWorldFromPrincipal(b, rot, wp);
  }
  let L: Vec3 | null = null;
  const src = lSource(r, body);
  if (src === 'system') {
    L = lerpRow(r.system.angular_momentum!, 1, 0, 3, seg, tmp3).slice() as Vec3;
  } else if (src === 'principal' && wp) {
    L = angularMomentumWorld(b, rot, wp);
  }
  return { omega, L };
}

/**
 * The largest |ω| and |L| of a body over the run. Arrows are drawn at a fixed scale per body (the
 * largest value maps to a fixed length), so a change of magnitude shows as a change of length.
 */
export function vectorMaxima(r: Report, body: number): { omega: number; L: number } {
  let omega = 0;
  let L = 0;
  const T = r.t.length;
  for (let i = 0; i < T; i++) {
    const v = bodyVectors(r, body, { i, s: 0 });
    if (v.omega) omega = Math.max(omega, norm(v.omega) || 0);
    if (v.L) L = Math.max(L, norm(v.L) || 0);
  }
  return { omega, L };
}

/** |L| per sample from the system's (T, 3) angular momentum; NaN stays NaN. */
export function magnitudes3(v: ArrayLike<number>): Float64Array {
  const T = Math.floor(v.length / 3);
  const out = new Float64Array(T);
  for (let i = 0; i < T; i++) out[i] = Math.hypot(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
  return out;
}

/** "showing S of T samples" when the CLI thinned the output for the report, else null. */
export function samplesNote(meta: Meta): string | null {
  if (meta.samples_shown < meta.samples_total) {
    return `showing ${meta.samples_shown.toLocaleString('en-US')} of ${meta.samples_total.toLocaleString('en-US')} samples`;
  }
  return null;
}

/** The principal axes of a body in its reference frame (the columns of U). */
export function principalAxes(b: Body): [Vec3, Vec3, Vec3] {
  return [column(b.principal_axes, 0), column(b.principal_axes, 1), column(b.principal_axes, 2)];
}
