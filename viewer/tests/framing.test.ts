import { describe, expect, it } from 'vitest';
import { decodeReport } from '../src/data';
import { comTrack } from '../src/derived';
import { defaultFollow, FOLLOW_ALL, FREE_CAMERA, runFraming, sizesOf, sphereNow } from '../src/framing';
import type { Report } from '../src/types';
import { syntheticReport } from './synthetic.mjs';

/** The synthetic T-handle and its particle, the particle carried away along x at `speed` per unit time. */
function drifting(speed: number): Report {
  const r = decodeReport(syntheticReport({ T: 41, duration: 10 }));
  const N = r.bodies.length;
  for (let i = 0; i < r.t.length; i++) r.series.position[(i * N + 1) * 3] += speed * r.t[i];
  return r;
}

describe('camera framing', () => {
  it('follows a lone body from the start', () => {
    expect(defaultFollow(decodeReport(syntheticReport({ T: 5, particle: false })))).toBe(0);
  });

  it('frames several bodies on their start while they stay there, else keeps all in view', () => {
    expect(defaultFollow(decodeReport(syntheticReport({ T: 41 })))).toBe(FREE_CAMERA);
    expect(defaultFollow(drifting(0))).toBe(FREE_CAMERA);
    // 10 units a second for 10 s: far beyond the start's sphere (the T-handle and its anchor, a few units).
    expect(defaultFollow(drifting(10))).toBe(FOLLOW_ALL);
  });

  it('holds every body (its centre of mass ± size) over the whole run', () => {
    const r = drifting(10);
    const { start, run, runBox } = runFraming(r);
    const size = sizesOf(r);
    for (let b = 0; b < r.bodies.length; b++) {
      const track = comTrack(r, b);
      for (let i = 0; i < track.length; i += 3) {
        const c = track.subarray(i, i + 3);
        const d = Math.hypot(c[0] - run.center[0], c[1] - run.center[1], c[2] - run.center[2]);
        // The sphere around the box holds the box (rounding of the hypot aside), the box each body.
        expect(d + size[b]).toBeLessThanOrEqual(run.radius * (1 + 1e-12));
        for (let k = 0; k < 3; k++) {
          expect(c[k] - size[b]).toBeGreaterThanOrEqual(runBox!.lo[k]);
          expect(c[k] + size[b]).toBeLessThanOrEqual(runBox!.hi[k]);
        }
      }
    }
    expect(start.radius).toBeLessThan(run.radius / 10);
  });

  it('frames the bodies now, skipping one that blew up, and nothing when none is finite', () => {
    const size = Float64Array.from([1, 2]);
    const s = sphereNow([0, 0, 0, 10, 0, 0], size)!;
    // The box x ∈ [-1, 12] (body 0 of size 1, body 1 at 10 of size 2), y, z ∈ [-2, 2]: its centre and half-diagonal.
    expect(s.center).toEqual([5.5, 0, 0]);
    expect(s.radius).toBeCloseTo(Math.hypot(13, 4, 4) / 2, 12);
    expect(sphereNow([0, 0, 0, NaN, 0, 0], size)!.center).toEqual([0, 0, 0]);
    expect(sphereNow([NaN, 0, 0, Infinity, 0, 0], size)).toBeNull();
  });
});
