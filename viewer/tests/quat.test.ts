import * as THREE from 'three';
import { describe, expect, it } from 'vitest';
import { axisAngle, multiply, normalizeQ, quatDistance, rotate, slerp, wxyzToXyzw, xyzwToWxyz } from '../src/quat';
import type { QuatWXYZ, Vec3 } from '../src/types';

const close = (a: ArrayLike<number>, b: ArrayLike<number>, tol = 1e-12) => {
  expect(a.length).toBe(b.length);
  for (let i = 0; i < a.length; i++) expect(Math.abs(a[i] - b[i])).toBeLessThan(tol);
};

describe('w-first quaternions and three.js', () => {
  it('moves w from first to last and back', () => {
    expect(wxyzToXyzw([1, 2, 3, 4])).toEqual([2, 3, 4, 1]);
    expect(xyzwToWxyz([2, 3, 4, 1])).toEqual([1, 2, 3, 4]);
  });

  it('gives three.js the same rotation tumble means', () => {
    // 90 degrees about z, w first: x-axis -> y-axis.
    const q: QuatWXYZ = [Math.SQRT1_2, 0, 0, Math.SQRT1_2];
    const tq = new THREE.Quaternion().fromArray(wxyzToXyzw(q));
    const v = new THREE.Vector3(1, 0, 0).applyQuaternion(tq);
    close(v.toArray(), [0, 1, 0]);
    close(rotate(q, [1, 0, 0]), [0, 1, 0]);
    close(xyzwToWxyz(tq.toArray()), q);
  });

  it('rotates like three.js for an arbitrary rotation', () => {
    const q = normalizeQ([0.3, -0.5, 0.7, 0.2]);
    const v: Vec3 = [0.4, -1.2, 2.5];
    const tv = new THREE.Vector3(...v).applyQuaternion(new THREE.Quaternion().fromArray(wxyzToXyzw(q)));
    close(rotate(q, v), tv.toArray());
  });

  it('composes like three.js multiply', () => {
    const a = normalizeQ([0.3, -0.5, 0.7, 0.2]);
    const b = normalizeQ([-0.1, 0.9, 0.2, 0.4]);
    const tab = new THREE.Quaternion().fromArray(wxyzToXyzw(a)).multiply(new THREE.Quaternion().fromArray(wxyzToXyzw(b)));
    close(multiply(a, b), xyzwToWxyz(tab.toArray()));
  });
});

describe('slerp', () => {
  const a = axisAngle([0, 0, 1], 0.2);
  const b = axisAngle([0, 0, 1], 1.0);

  it('is exact at the ends', () => {
    close(slerp(a, b, 0), a);
    close(slerp(a, b, 1), b);
  });

  it('rotates at a constant rate about a fixed axis', () => {
    for (const s of [0.1, 0.25, 0.5, 0.9]) close(slerp(a, b, s), axisAngle([0, 0, 1], 0.2 + 0.8 * s));
  });

  it('takes the short way when the samples have opposite signs', () => {
    const negB = b.map((x) => -x) as QuatWXYZ;
    const mid = slerp(a, negB, 0.5);
    expect(quatDistance(mid, axisAngle([0, 0, 1], 0.6))).toBeLessThan(1e-12);
  });

  it('matches three.js slerp', () => {
    const p = normalizeQ([0.3, -0.5, 0.7, 0.2]);
    const q = normalizeQ([-0.1, 0.9, 0.2, 0.4]);
    const tq = new THREE.Quaternion().fromArray(wxyzToXyzw(p)).slerp(new THREE.Quaternion().fromArray(wxyzToXyzw(q)), 0.3);
    expect(quatDistance(slerp(p, q, 0.3), xyzwToWxyz(tq.toArray()))).toBeLessThan(1e-12);
  });

  it('handles nearly equal quaternions without dividing by zero', () => {
    const c = axisAngle([1, 0, 0], 1e-9);
    const r = slerp([1, 0, 0, 0], c, 0.5);
    expect(r.every(Number.isFinite)).toBe(true);
    close(r, axisAngle([1, 0, 0], 5e-10));
  });

  it('normalises (float32 data are slightly off unit length)', () => {
    expect(Math.hypot(...normalizeQ([2, 0, 0, 0]))).toBeCloseTo(1, 15);
    expect(normalizeQ([0, 0, 0, 0])).toEqual([1, 0, 0, 0]);
  });
});
