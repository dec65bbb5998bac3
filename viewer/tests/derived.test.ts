import { describe, expect, it } from 'vitest';
import { decodeReport } from '../src/data';
import { angularMomentumWorld, bodyVectors, comTrack, lSource, magnitudes3, samplesNote, vectorMaxima } from '../src/derived';
import { formatTick, plotDefs, toPlotValues } from '../src/plotdata';
import { normalizeQ, rotate } from '../src/quat';
import type { Body, Meta } from '../src/types';
import { AXIS, COM_WORLD, MOMENTS, syntheticReport, W } from './synthetic.mjs';

const close = (a: ArrayLike<number>, b: ArrayLike<number>, tol: number) => {
  for (let i = 0; i < b.length; i++) expect(Math.abs(a[i] - b[i])).toBeLessThan(tol);
};

describe('derived quantities', () => {
  it('computes L = R U diag(Λ) ω_p in the world', () => {
    const body: Body = {
      name: 'b',
      kind: 'body',
      mesh: null,
      box: null,
      com: [0, 0, 0],
      // Columns: principal axis 1 = y, 2 = z, 3 = x.
      principal_axes: [
        [0, 0, 1],
        [1, 0, 0],
        [0, 1, 0],
      ],
      principal_moments: [1, 2, 3],
      size: 1,
    };
    // Identity orientation, spin about principal axis 2 (= z) at 5 rad/s: L = 2 * 5 z.
    close(angularMomentumWorld(body, [1, 0, 0, 0], [0, 5, 0]), [0, 0, 10], 1e-12);
    // Rotated 90 degrees about x: z goes to -y.
    const q = normalizeQ([1, 1, 0, 0]);
    close(angularMomentumWorld(body, q, [0, 5, 0]), rotate(q, [0, 0, 10]), 1e-12);
    close(angularMomentumWorld(body, q, [0, 5, 0]), [0, -10, 0], 1e-12);
  });

  it("draws each body's own L about its centre of mass, a lone one too", () => {
    // A lone body whose system L (about the world origin) is an orbit's m r × v, 1e13 along z: the
    // arrow must still be the body's own L = I₂ ω n, not that.
    const lone = syntheticReport({ T: 5, particle: false }) as Record<string, any>;
    const orbit = new Float64Array(5 * 3).map((_, i) => (i % 3 === 2 ? 2.3e13 : 0));
    lone.system.angular_momentum.base64 = Buffer.from(orbit.buffer).toString('base64');
    const one = decodeReport(lone);
    close(one.system.angular_momentum!.subarray(0, 3), [0, 0, 2.3e13], 1);
    expect(lSource(one, 0)).toBe('principal');
    const two = decodeReport(syntheticReport({ T: 5 }));
    expect(lSource(two, 0)).toBe('principal');
    expect(lSource(two, 1)).toBeNull();
    // Both agree with the closed form L = I2 w n for the spinning handle.
    for (const r of [one, two]) {
      const v = bodyVectors(r, 0, { i: 2, s: 0.3 });
      close(v.L!, AXIS.map((a: number) => MOMENTS[1] * W * a), 1e-6);
      close(v.omega!, AXIS.map((a: number) => W * a), 1e-6);
    }
    expect(bodyVectors(two, 1, { i: 0, s: 0 })).toEqual({ omega: null, L: null });
  });

  it('derives L from ω in the world when the principal rates are absent', () => {
    const j = syntheticReport({ T: 5 }) as Record<string, any>;
    delete j.series.omega_principal;
    const r = decodeReport(j);
    expect(lSource(r, 0)).toBe('world');
    close(bodyVectors(r, 0, { i: 2, s: 0.3 }).L!, AXIS.map((a: number) => MOMENTS[1] * W * a), 1e-6);
  });

  it('derives ω from the principal rates when omega_world is absent', () => {
    const j = syntheticReport({ T: 5 }) as Record<string, any>;
    delete j.series.omega_world;
    const v = bodyVectors(decodeReport(j), 0, { i: 1, s: 0 });
    close(v.omega!, AXIS.map((a: number) => W * a), 1e-6);
  });

  it('puts the centre of mass where the closed form has it', () => {
    const r = decodeReport(syntheticReport({ T: 9, particle: false }));
    const track = comTrack(r, 0);
    for (let i = 0; i < 9; i++) close(track.subarray(3 * i, 3 * i + 3), COM_WORLD, 1e-6);
    const max = vectorMaxima(r, 0);
    expect(max.omega).toBeCloseTo(W, 5);
  });

  it('takes |L| per sample, NaN staying NaN', () => {
    const m = magnitudes3([3, 4, 0, NaN, 0, 0]);
    expect(m[0]).toBe(5);
    expect(Number.isNaN(m[1])).toBe(true);
  });

  it('says when the samples were thinned', () => {
    const meta = { samples_total: 100000, samples_shown: 5000 } as Meta;
    expect(samplesNote(meta)).toBe('showing 5,000 of 100,000 samples');
    expect(samplesNote({ ...meta, samples_shown: 100000 })).toBeNull();
  });
});

describe('plot data', () => {
  it('turns NaN and infinities into gaps (null) for uPlot', () => {
    expect(toPlotValues(new Float64Array([1, NaN, Infinity, -2]))).toEqual([1, null, null, -2]);
  });

  it('shows the five plots when every series is there, with T points each', () => {
    const r = decodeReport(syntheticReport({ T: 7 }));
    const defs = plotDefs(r, 0);
    expect(defs.map((d) => d.id)).toEqual(['energy', 'energy_drift', 'angular_momentum', 'omega_world', 'omega_principal']);
    for (const d of defs) for (const s of d.series) expect(s.values.length).toBe(7);
    expect(defs[1].series[0].values[0]).toBeNull(); // the NaN first drift
    expect(defs[2].series.map((s) => s.scale)).toEqual(['y', 'y2']);
  });

  it('leaves out the plots whose series are absent', () => {
    const j = syntheticReport({ T: 7 }) as Record<string, any>;
    j.system = { total_energy: j.system.total_energy, angular_momentum_drift: j.system.angular_momentum_drift };
    delete j.series.omega_principal;
    const defs = plotDefs(decodeReport(j), 0);
    expect(defs.map((d) => d.id)).toEqual(['energy', 'angular_momentum', 'omega_world']);
    expect(defs[1].series.map((s) => s.scale)).toEqual(['y']);
  });

  it('picks the selected body for the ω plots', () => {
    const r = decodeReport(syntheticReport({ T: 7 }));
    const w1 = plotDefs(r, 1).find((d) => d.id === 'omega_principal')!;
    expect(w1.title).toContain('bob');
    expect(w1.series[1].values.every((v) => v === 0)).toBe(true);
  });

  it('formats ticks readably', () => {
    expect(formatTick(0.5, 0.5)).toBe('0.5');
    expect(formatTick(0.25, 0.25)).toBe('0.25');
    expect(formatTick(2, 2)).toBe('2');
    expect(formatTick(1.5e-12, 5e-13)).toBe('1.5e-12');
    expect(formatTick(0, 1e-12)).toBe('0');
  });
});
