// Quantities the report does not store but the pictures need: each body's centre of mass in the
// world, its angular momentum vector, the scale of the arrows, the magnitude of the system's L.
// Pure functions of the decoded report, so the unit tests check them without a browser.

import { column, matVec, rotate } from './quat';
import { quatAtSegment, lerpRow, type Segment } from './timeline';
import type { Body, Meta, QuatWXYZ, Report, Vec3 } from './types';

/** World position of a point given in the body's reference frame: x + R p. */
export function toWorld(position: Vec3, q: QuatWXYZ, p: Vec3): Vec3 {
  const r = rotate(q, p);
  return [position[0] + r[0], position[1] + r[1], position[2] + r[2]];
}

/**
 * The centre-of-mass track of one body, T*3 floats (world), for its trail and the camera bounds.
 * Written out without temporaries: it runs over every sample (1e5 and more) before the first frame.
 */
export function comTrack(r: Report, body: number): Float32Array {
  const T = r.t.length;
  const N = r.bodies.length;
  const [cx, cy, cz] = r.bodies[body].com;
  const pos = r.series.position;
  const quat = r.series.quaternion;
  const out = new Float32Array(T * 3);
  for (let i = 0; i < T; i++) {
    const a = (i * N + body) * 4;
    let w = quat[a];
    let x = quat[a + 1];
    let y = quat[a + 2];
    let z = quat[a + 3];
    const n = Math.hypot(w, x, y, z) || 1;
    w /= n;
    x /= n;
    y /= n;
    z /= n;
    // R c by the two-cross-product form (quat.ts rotate).
    const tx = 2 * (y * cz - z * cy);
    const ty = 2 * (z * cx - x * cz);
    const tz = 2 * (x * cy - y * cx);
    const p = (i * N + body) * 3;
    out[i * 3] = pos[p] + cx + w * tx + (y * tz - z * ty);
    out[i * 3 + 1] = pos[p + 1] + cy + w * ty + (z * tx - x * tz);
    out[i * 3 + 2] = pos[p + 2] + cz + w * tz + (x * ty - y * tx);
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
 * Rotations keep lengths, so |ω| = |ω_p| and |L| = |Λ ω_p|: no orientation is needed here.
 */
export function vectorMaxima(r: Report, body: number): { omega: number; L: number } {
  const b = r.bodies[body];
  if (b.kind !== 'body') return { omega: 0, L: 0 };
  const T = r.t.length;
  const N = r.bodies.length;
  const [m1, m2, m3] = b.principal_moments;
  const wp = r.series.omega_principal;
  const ww = r.series.omega_world ?? wp;
  let omega = 0;
  if (ww) {
    for (let i = 0; i < T; i++) {
      const a = (i * N + body) * 3;
      const v = Math.hypot(ww[a], ww[a + 1], ww[a + 2]);
      if (v > omega) omega = v;
    }
  }
  let L = 0;
  const src = lSource(r, body);
  if (src === 'system') {
    const l = r.system.angular_momentum!;
    for (let i = 0; i < T; i++) {
      const v = Math.hypot(l[3 * i], l[3 * i + 1], l[3 * i + 2]);
      if (v > L) L = v;
    }
  } else if (src === 'principal' && wp) {
    for (let i = 0; i < T; i++) {
      const a = (i * N + body) * 3;
      const v = Math.hypot(m1 * wp[a], m2 * wp[a + 1], m3 * wp[a + 2]);
      if (v > L) L = v;
    }
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
