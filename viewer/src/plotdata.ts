// What each plot shows, as plain data: its title, its series and their values, or nothing when the
// report lacks the series it needs (the plot is then left out). Kept apart from plots.ts (uPlot and
// the DOM) so the unit tests check the selection and the NaN handling in node.

import { COLORS } from './colors';
import { magnitudes3 } from './derived';
import type { Report } from './types';

export interface SeriesDef {
  label: string;
  color: string;
  /** 'y' (left axis) or 'y2' (right axis). */
  scale: 'y' | 'y2';
  values: PlotValues;
}

export interface PlotDef {
  id: 'energy' | 'energy_drift' | 'angular_momentum' | 'omega_world' | 'omega_principal';
  title: string;
  yLabel: string;
  y2Label?: string;
  /** Shows the selected body (and changes with the body select). */
  perBody: boolean;
  series: SeriesDef[];
}

/**
 * uPlot draws null as a gap but chokes on NaN (its min/max and paths go NaN): a series with any NaN
 * (JSON null or NaN bits in the base64) becomes an array with null there. A series without is
 * passed as a typed array, uncopied: uPlot reads those directly, and a long run has 1e5+ values.
 */
export type PlotValues = (number | null)[] | Float64Array | Float32Array;

export function toPlotValues(a: Float64Array | Float32Array): PlotValues {
  let finite = true;
  for (let i = 0; i < a.length; i++) {
    if (!Number.isFinite(a[i])) {
      finite = false;
      break;
    }
  }
  if (finite) return a;
  const out = new Array<number | null>(a.length);
  for (let i = 0; i < a.length; i++) {
    const v = a[i];
    out[i] = Number.isFinite(v) ? v : null;
  }
  return out;
}

/** Component k of body b's row in a (T, N, 3) series. */
function component(data: Float64Array | Float32Array, T: number, N: number, b: number, k: number): PlotValues {
  const out = new Float64Array(T);
  for (let i = 0; i < T; i++) out[i] = data[(i * N + b) * 3 + k];
  return toPlotValues(out);
}

/** The plots this report can show, in their fixed order; `body` selects the per-body ones. */
export function plotDefs(r: Report, body: number): PlotDef[] {
  const T = r.t.length;
  const N = r.bodies.length;
  const s = r.system;
  const defs: PlotDef[] = [];

  const energy: SeriesDef[] = [];
  if (s.kinetic_energy) energy.push({ label: 'kinetic', color: '#ffb74d', scale: 'y', values: toPlotValues(s.kinetic_energy) });
  if (s.potential_energy) energy.push({ label: 'potential', color: '#4dd0e1', scale: 'y', values: toPlotValues(s.potential_energy) });
  if (s.total_energy) energy.push({ label: 'total', color: '#eceff1', scale: 'y', values: toPlotValues(s.total_energy) });
  if (energy.length) defs.push({ id: 'energy', title: 'Energy', yLabel: 'J', perBody: false, series: energy });

  if (s.energy_drift) {
    defs.push({
      id: 'energy_drift',
      title: 'Relative energy drift',
      yLabel: '(E − E₀)/|E₀|',
      perBody: false,
      series: [{ label: 'energy drift', color: '#ffd54f', scale: 'y', values: toPlotValues(s.energy_drift) }],
    });
  }

  const L: SeriesDef[] = [];
  if (s.angular_momentum) L.push({ label: '|L|', color: COLORS.L, scale: 'y', values: toPlotValues(magnitudes3(s.angular_momentum)) });
  if (s.angular_momentum_drift) {
    L.push({
      label: '|L| drift',
      color: '#b0bec5',
      // Alone it takes the left axis; beside |L| the right one (its values are ~1e-12, |L|'s ~1).
      scale: L.length ? 'y2' : 'y',
      values: toPlotValues(s.angular_momentum_drift),
    });
  }
  if (L.length) {
    defs.push({
      id: 'angular_momentum',
      title: 'Angular momentum (system, about the origin)',
      yLabel: L[0].scale === 'y' && L[0].label === '|L|' ? 'kg m²/s' : 'drift',
      y2Label: L.length > 1 ? 'drift' : undefined,
      perBody: false,
      series: L,
    });
  }

  const name = r.bodies[body]?.name ?? '';
  // ω of the chosen body, in world axes and in its principal axes: one plot each, from one description.
  const omegas = [
    { id: 'omega_world', axes: 'world axes', labels: ['x', 'y', 'z'], data: r.series.omega_world },
    { id: 'omega_principal', axes: 'principal axes', labels: ['1', '2', '3'], data: r.series.omega_principal },
  ] as const;
  for (const o of omegas) {
    const w = o.data;
    if (!w) continue;
    defs.push({
      id: o.id,
      title: `ω in ${o.axes} — ${name}`,
      yLabel: 'rad/s',
      perBody: true,
      series: o.labels.map((a, k) => ({ label: `ω${a}`, color: COLORS.axes[k], scale: 'y' as const, values: component(w, T, N, body, k) })),
    });
  }
  return defs;
}

/** Axis tick text: as many decimals as the tick step has; exponential for tiny drifts (1e-12) and huge values. */
export function formatTick(v: number, step: number): string {
  if (v === 0) return '0';
  const a = Math.abs(step) || Math.abs(v);
  if (a < 1e-3 || Math.abs(v) >= 1e6) {
    // Enough significant digits to tell neighbouring ticks apart (1.5e-12 next to 2.0e-12).
    const digits = Math.max(0, Math.min(4, Math.ceil(Math.log10(Math.abs(v) / a) - 1e-9)));
    return v.toExponential(digits);
  }
  const text = String(Number(a.toPrecision(6)));
  const dot = text.indexOf('.');
  return v.toFixed(dot < 0 ? 0 : Math.min(8, text.length - dot - 1));
}
