// Quaternion and small-vector maths on plain arrays, free of three.js so the unit tests check it in
// node. tumble writes quaternions w FIRST ([w, x, y, z]); three.js stores them x, y, z, w. Every
// conversion between the two goes through wxyzToXyzw/xyzwToWxyz, so the order is decided once.

import type { Mat3, QuatWXYZ, Vec3 } from './types';

/** [w, x, y, z] (tumble) -> [x, y, z, w] (three.js Quaternion.fromArray). */
export function wxyzToXyzw(q: ArrayLike<number>): [number, number, number, number] {
  return [q[1], q[2], q[3], q[0]];
}

/** [x, y, z, w] (three.js Quaternion.toArray) -> [w, x, y, z] (tumble). */
export function xyzwToWxyz(q: ArrayLike<number>): QuatWXYZ {
  return [q[3], q[0], q[1], q[2]];
}

export function normalizeQ(q: QuatWXYZ): QuatWXYZ {
  const n = Math.hypot(q[0], q[1], q[2], q[3]);
  if (!(n > 0)) return [1, 0, 0, 0];
  return [q[0] / n, q[1] / n, q[2] / n, q[3] / n];
}

/**
 * Spherical interpolation between unit quaternions a (s = 0) and b (s = 1) along the shorter arc:
 * q and -q are the same rotation, so b is negated when the two point into opposite hemispheres,
 * otherwise playback would swing the long way round between two close samples.
 */
export function slerp(a: QuatWXYZ, b: QuatWXYZ, s: number): QuatWXYZ {
  let [bw, bx, by, bz] = b;
  let cos = a[0] * bw + a[1] * bx + a[2] * by + a[3] * bz;
  if (cos < 0) {
    cos = -cos;
    bw = -bw;
    bx = -bx;
    by = -by;
    bz = -bz;
  }
  let ka: number;
  let kb: number;
  if (cos > 0.9999995) {
    // Nearly equal: sin(theta) ~ 0 would divide by ~0; a normalised lerp is exact to rounding here.
    ka = 1 - s;
    kb = s;
  } else {
    const theta = Math.acos(Math.min(1, cos));
    const sin = Math.sin(theta);
    ka = Math.sin((1 - s) * theta) / sin;
    kb = Math.sin(s * theta) / sin;
  }
  return normalizeQ([
    ka * a[0] + kb * bw,
    ka * a[1] + kb * bx,
    ka * a[2] + kb * by,
    ka * a[3] + kb * bz,
  ]);
}

/** v rotated by the unit quaternion q = [w, x, y, z] (R v). */
export function rotate(q: QuatWXYZ, v: Vec3): Vec3 {
  const [w, x, y, z] = q;
  // t = 2 (q_vec x v); v' = v + w t + q_vec x t: the standard two-cross-product form.
  const tx = 2 * (y * v[2] - z * v[1]);
  const ty = 2 * (z * v[0] - x * v[2]);
  const tz = 2 * (x * v[1] - y * v[0]);
  return [
    v[0] + w * tx + (y * tz - z * ty),
    v[1] + w * ty + (z * tx - x * tz),
    v[2] + w * tz + (x * ty - y * tx),
  ];
}

/** q1 * q2 (apply q2, then q1). */
export function multiply(a: QuatWXYZ, b: QuatWXYZ): QuatWXYZ {
  return [
    a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
    a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
    a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
    a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
  ];
}

/** Rotation by `angle` (rad) about the unit axis `axis`. */
export function axisAngle(axis: Vec3, angle: number): QuatWXYZ {
  const s = Math.sin(angle / 2);
  return [Math.cos(angle / 2), axis[0] * s, axis[1] * s, axis[2] * s];
}

/** The same rotation up to the sign of q: |<a, b>| = 1 for unit quaternions. */
export function quatDistance(a: ArrayLike<number>, b: ArrayLike<number>): number {
  const dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
  return 1 - Math.min(1, Math.abs(dot));
}

/** Column j of the row-major matrix m: for U, the j-th principal axis in the reference frame. */
export function column(m: Mat3, j: number): Vec3 {
  return [m[0][j], m[1][j], m[2][j]];
}

/** m v for a row-major m. */
export function matVec(m: Mat3, v: Vec3): Vec3 {
  return [
    m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2],
    m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
    m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2],
  ];
}

export function norm(v: ArrayLike<number>): number {
  return Math.hypot(v[0], v[1], v[2]);
}
