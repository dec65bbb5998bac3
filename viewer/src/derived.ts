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
 * Where the L arrow of a body comes from: always the body's own L about its centre of mass,
 * R U diag(Λ) ω_p (docs/report.md), from its principal rates, or from ω in the world when the report
 * has only that. Never the system's L about the world origin, which holds m r × v of the orbit (a lone
 * satellite's is 1e13 along the orbit normal); the plots show that one, labelled as the system's.
 * Particles spin about nothing: no arrow.
 */
export type LSource = 'principal' | 'world' | null;

export function lSource(r: Report, body: number): LSource {
  const b = r.bodies[body];
  if (b.kind !== 'body') return null;
  if (r.series.omega_principal) return 'principal';
  if (r.series.omega_world) return 'world';
  return null;
}

/** L = R U diag(Λ) ω_p in the world, from the orientation q and principal rates ω_p. */
export function angularMomentumWorld(b: Body, q: QuatWXYZ, omegaPrincipal: Vec3): Vec3 {
  const m = b.principal_moments;
  const lPrincipal: Vec3 = [m[0] * omegaPrincipal[0], m[1] * omegaPrincipal[1], m[2] * omegaPrincipal[2]];
  return rotate(q, matVec(b.principal_axes, lPrincipal));
}

/** The principal rates from ω in the world: ω_p = Uᵀ Rᵀ ω (when the report has no omega_principal). */
export function omegaPrincipalFromWorld(b: Body, q: QuatWXYZ, omegaWorld: Vec3): Vec3 {
  const v = rotate([q[0], -q[1], -q[2], -q[3]], omegaWorld);
  const U = b.principal_axes;
  return [
    U[0][0] * v[0] + U[1][0] * v[1] + U[2][0] * v[2],
    U[0][1] * v[0] + U[1][1] * v[1] + U[2][1] * v[2],
    U[0][2] * v[0] + U[1][2] * v[1] + U[2][2] * v[2],
  ];
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
  if (src === 'principal' && wp) {
    L = angularMomentumWorld(b, rot, wp);
  } else if (src === 'world' && omega) {
    L = angularMomentumWorld(b, rot, omegaPrincipalFromWorld(b, rot, omega));
  }
  return { omega, L };
}

/**
 * The largest |ω| and |L| of a body over the run. Arrows are drawn at a fixed scale per body (the
 * largest value maps to a fixed length), so a change of magnitude shows as a change of length.
 * Rotations keep lengths, so |ω| = |ω_p| and |L| = |Λ ω_p|: no orientation is needed, but to find ω_p
 * from ω in the world when the report has only that.
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
  if (src === 'world' && ww) {
    // |L| = |Λ ω_p| with ω_p = Uᵀ Rᵀ ω: the orientation is needed here.
    const quat = r.series.quaternion;
    for (let i = 0; i < T; i++) {
      const a = (i * N + body) * 3;
      const q = quat.subarray((i * N + body) * 4, (i * N + body) * 4 + 4);
      const w = omegaPrincipalFromWorld(b, [q[0], q[1], q[2], q[3]], [ww[a], ww[a + 1], ww[a + 2]]);
      const v = Math.hypot(m1 * w[0], m2 * w[1], m3 * w[2]);
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
