import { describe, expect, it } from 'vitest';
import { axisAngle, quatDistance } from '../src/quat';
import { lerpRow, quatAtSegment, Timeline } from '../src/timeline';

describe('Timeline.locate', () => {
  const tl = new Timeline([0, 0.5, 1, 2, 4]);

  it('finds the sample and the fraction to the next', () => {
    expect(tl.locate(0)).toEqual({ i: 0, s: 0 });
    expect(tl.locate(0.25)).toEqual({ i: 0, s: 0.5 });
    expect(tl.locate(1)).toEqual({ i: 2, s: 0 });
    expect(tl.locate(3)).toEqual({ i: 3, s: 0.5 });
    // Backwards after the hint moved forward: still right.
    expect(tl.locate(0.75)).toEqual({ i: 1, s: 0.5 });
  });

  it('clamps outside the run', () => {
    expect(tl.locate(-1)).toEqual({ i: 0, s: 0 });
    expect(tl.locate(10)).toEqual({ i: 4, s: 0 });
    expect(tl.locate(NaN)).toEqual({ i: 0, s: 0 });
  });

  it('agrees with a linear scan on many random times', () => {
    const t = Array.from({ length: 1000 }, (_, i) => i * 0.01 + (i % 7) * 1e-4);
    const tl2 = new Timeline(t);
    for (let k = 0; k < 2000; k++) {
      const x = Math.random() * 10.5 - 0.2;
      let expected = 0;
      while (expected < t.length - 1 && t[expected + 1] <= x) expected++;
      expect(tl2.locate(x).i).toBe(expected);
    }
  });

  it('steps to the next and previous samples', () => {
    expect(tl.nextIndex(0)).toBe(1);
    expect(tl.nextIndex(0.7)).toBe(2);
    expect(tl.nextIndex(4)).toBe(4);
    expect(tl.prevIndex(1)).toBe(1);
    expect(tl.prevIndex(0.7)).toBe(1);
    expect(tl.prevIndex(0)).toBe(0);
    expect(tl.prevIndex(4)).toBe(3);
  });

  it('has one sample only', () => {
    const one = new Timeline([2]);
    expect(one.locate(5)).toEqual({ i: 0, s: 0 });
    expect(one.nextIndex(2)).toBe(0);
    expect(one.prevIndex(2)).toBe(0);
  });
});

describe('interpolation', () => {
  it('interpolates a (T, N, 3) row of one body linearly', () => {
    // T = 2, N = 2: body 1 goes from (10, 20, 30) to (20, 40, 60).
    const data = [0, 0, 0, 10, 20, 30, 1, 1, 1, 20, 40, 60];
    expect(lerpRow(data, 2, 1, 3, { i: 0, s: 0.5 }, [])).toEqual([15, 30, 45]);
    expect(lerpRow(data, 2, 0, 3, { i: 1, s: 0 }, [])).toEqual([1, 1, 1]);
  });

  it('slerps the orientation between samples, w first', () => {
    const q0 = axisAngle([0, 1, 0], 0.1);
    const q1 = axisAngle([0, 1, 0], 0.5).map((x) => -x); // the other sign of the same rotation
    const data = new Float64Array([...q0, ...q1]);
    const q = quatAtSegment(data, 1, 0, { i: 0, s: 0.25 });
    expect(quatDistance(q, axisAngle([0, 1, 0], 0.2))).toBeLessThan(1e-12);
  });
});
