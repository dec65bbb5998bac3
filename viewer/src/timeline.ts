// Finding where a playback time falls among the samples and interpolating the body state there.
// Samples may be unevenly spaced (an adaptive integrator, a down-sampled long run), so the lookup is a
// binary search; playback asks for nearby times frame after frame, so the last answer is tried first.

import { normalizeQ, slerp } from './quat';
import type { QuatWXYZ, Vec3 } from './types';

/** Sample i and the fraction s in [0, 1] of the way to sample i + 1 at time `time`. */
export interface Segment {
  i: number;
  s: number;
}

export class Timeline {
  private hint = 0;

  constructor(readonly t: ArrayLike<number>) {}

  get start(): number {
    return this.t[0];
  }

  get end(): number {
    return this.t[this.t.length - 1];
  }

  get count(): number {
    return this.t.length;
  }

  /** The segment holding `time`, clamped to the first and last sample. */
  locate(time: number): Segment {
    const t = this.t;
    const n = t.length;
    if (n === 1 || !(time > t[0])) return { i: 0, s: 0 };
    if (time >= t[n - 1]) return { i: n - 1, s: 0 };
    let i = this.hint;
    if (!(i < n - 1 && t[i] <= time && time < t[i + 1])) {
      // Largest i with t[i] <= time: t[lo] <= time < t[hi] throughout.
      let lo = 0;
      let hi = n - 1;
      while (hi - lo > 1) {
        const mid = (lo + hi) >> 1;
        if (t[mid] <= time) lo = mid;
        else hi = mid;
      }
      i = lo;
    }
    this.hint = i;
    const dt = t[i + 1] - t[i];
    return { i, s: dt > 0 ? (time - t[i]) / dt : 0 };
  }

  /** The first sample after `time` (or the last): from between two samples, the later of them. */
  nextIndex(time: number): number {
    if (time < this.t[0]) return 0;
    return Math.min(this.t.length - 1, this.locate(time).i + 1);
  }

  /**
   * The last sample before `time` (or the first): from between two samples, the earlier of them.
   * A tolerance of 1e-9 of the interval keeps a time a rounding error past a sample "at" it, so
   * stepping back from there does not stay on the same sample.
   */
  prevIndex(time: number): number {
    const { i, s } = this.locate(time);
    if (s > 1e-9) return i;
    return Math.max(0, i - 1);
  }
}

/** Linear interpolation of `width` components of row (i, body) and (i + 1, body) of a (T, N, width) series. */
export function lerpRow(
  data: ArrayLike<number>,
  N: number,
  body: number,
  width: number,
  seg: Segment,
  out: number[],
): number[] {
  const a = (seg.i * N + body) * width;
  if (seg.s === 0) {
    for (let k = 0; k < width; k++) out[k] = data[a + k];
    return out;
  }
  const b = a + N * width;
  for (let k = 0; k < width; k++) out[k] = data[a + k] + (data[b + k] - data[a + k]) * seg.s;
  return out;
}

/** Row (i, body) of a (T, N, 3) series. */
export function vecAt(data: ArrayLike<number>, N: number, body: number, i: number): Vec3 {
  const a = (i * N + body) * 3;
  return [data[a], data[a + 1], data[a + 2]];
}

/** The orientation of `body` at sample i, normalised (data may be float32, off unit by ~1e-7). */
export function quatAt(q: ArrayLike<number>, N: number, body: number, i: number): QuatWXYZ {
  const a = (i * N + body) * 4;
  return normalizeQ([q[a], q[a + 1], q[a + 2], q[a + 3]]);
}

/** Orientation at a segment: slerp between the two samples (exactly sample i when s = 0). */
export function quatAtSegment(q: ArrayLike<number>, N: number, body: number, seg: Segment): QuatWXYZ {
  const a = quatAt(q, N, body, seg.i);
  if (seg.s === 0) return a;
  return slerp(a, quatAt(q, N, body, seg.i + 1), seg.s);
}
