import { describe, expect, it } from 'vitest';
import { base64ToBytes, bytesToBase64 } from '../src/base64';
import { DataError, decodeArray, decodeReport, readEmbedded } from '../src/data';
import { escapeForScript, injectReport, PLACEHOLDER } from '../scripts/inject.mjs';
import { syntheticReport } from './synthetic.mjs';

function enc(dtype: 'f32' | 'f64' | 'u32', shape: number[], a: Float32Array | Float64Array | Uint32Array) {
  return { dtype, shape, base64: bytesToBase64(new Uint8Array(a.buffer, a.byteOffset, a.byteLength)) };
}

describe('base64', () => {
  it('round-trips bytes of every value', () => {
    const bytes = new Uint8Array(256 * 3 + 1).map((_, i) => i % 256);
    expect(Array.from(base64ToBytes(bytesToBase64(bytes)))).toEqual(Array.from(bytes));
    expect(bytesToBase64(new Uint8Array(0))).toBe('');
  });

  it('matches node Buffer encoding', () => {
    const a = new Float64Array([1.5, -2, Math.PI]);
    const b = new Uint8Array(a.buffer);
    expect(bytesToBase64(b)).toBe(Buffer.from(b).toString('base64'));
  });

  it('rejects what is not base64', () => {
    expect(() => base64ToBytes('***')).toThrow(/base64/);
  });
});

describe('decodeArray', () => {
  it('round-trips f32, f64 and u32 typed arrays', () => {
    const f32 = new Float32Array([0, 1.25, -3.5e-7, 1e30]);
    const f64 = new Float64Array([Math.PI, -0, 1e-300, Number.MAX_VALUE]);
    const u32 = new Uint32Array([0, 1, 4294967295]);
    const d1 = decodeArray(enc('f32', [2, 2], f32), 'x');
    expect(d1.data).toBeInstanceOf(Float32Array);
    expect(Array.from(d1.data)).toEqual(Array.from(f32));
    expect(d1.shape).toEqual([2, 2]);
    expect(Array.from(decodeArray(enc('f64', [4], f64), 'x').data)).toEqual(Array.from(f64));
    const d3 = decodeArray(enc('u32', [3], u32), 'x').data;
    expect(d3).toBeInstanceOf(Uint32Array);
    expect(Array.from(d3)).toEqual([0, 1, 4294967295]);
  });

  it('keeps NaN bits and infinities of the raw bytes', () => {
    const a = new Float64Array([NaN, Infinity, -Infinity, 1]);
    const d = decodeArray(enc('f64', [4], a), 'x').data;
    expect(Number.isNaN(d[0])).toBe(true);
    expect(d[1]).toBe(Infinity);
    expect(d[2]).toBe(-Infinity);
  });

  it('reads plain JSON arrays with null as NaN', () => {
    const d = decodeArray([[1, null], [3, 4]], 'x');
    expect(d.shape).toEqual([2, 2]);
    expect(Number.isNaN(d.data[1])).toBe(true);
    expect(d.data[3]).toBe(4);
    expect(() => decodeArray([1, 'a'], 'x')).toThrow(DataError);
    expect(() => decodeArray([[1, 2], [3]], 'x')).toThrow(/ragged/);
  });

  it('rejects an unknown dtype', () => {
    expect(() => decodeArray({ dtype: 'f16', shape: [1], base64: 'AAA=' }, 'series.position')).toThrow(
      /series\.position: unknown dtype "f16"/,
    );
  });

  it('rejects a byte length that does not match the shape', () => {
    const a = new Float32Array(5);
    expect(() => decodeArray(enc('f32', [6], a), 't')).toThrow(/t: 20 bytes, but shape \[6\] of f32 needs 24/);
    // The same bytes read as f64 of the same count: 8 bytes each.
    expect(() => decodeArray(enc('f64', [5], a), 't')).toThrow(/needs 40/);
  });

  it('rejects a malformed shape or base64', () => {
    expect(() => decodeArray({ dtype: 'f32', shape: [-1], base64: '' }, 'x')).toThrow(/shape/);
    expect(() => decodeArray({ dtype: 'f32', shape: [1.5], base64: '' }, 'x')).toThrow(/shape/);
    expect(() => decodeArray({ dtype: 'f32', shape: [1], base64: '!!!!' }, 'x')).toThrow(/base64/);
    expect(() => decodeArray('nope', 'x')).toThrow(/encoded array/);
  });
});

describe('decodeReport', () => {
  it('decodes the synthetic report', () => {
    const r = decodeReport(syntheticReport({ T: 11 }));
    expect(r.t.length).toBe(11);
    expect(r.bodies.map((b) => b.kind)).toEqual(['body', 'particle']);
    expect(r.bodies[0].mesh!.indices.length).toBe(72);
    expect(r.series.quaternion.length).toBe(11 * 2 * 4);
    expect(r.system.angular_momentum!.length).toBe(33);
    // The synthetic drift starts with NaN: kept as NaN, not dropped or zeroed.
    expect(Number.isNaN(r.system.energy_drift![0])).toBe(true);
    expect(r.events.length).toBe(3);
    expect(r.meta.samples_shown).toBe(11);
  });

  it('accepts flat shapes as well as (T, N, w)', () => {
    const j = syntheticReport({ T: 5, particle: false });
    j.series.position.shape = [15];
    expect(decodeReport(j).series.position.length).toBe(15);
  });

  it('names the field whose shape does not fit T and N', () => {
    const j = syntheticReport({ T: 5, particle: false });
    j.series.omega_world.shape = [5, 3, 1];
    expect(() => decodeReport(j)).toThrow(/series\.omega_world: shape \[5,3,1\] does not match \(T=5, N=1, 3\)/);
  });

  it('rejects a series whose length disagrees with t', () => {
    const j = syntheticReport({ T: 5, particle: false });
    const other = syntheticReport({ T: 6, particle: false });
    j.series.quaternion = other.series.quaternion;
    expect(() => decodeReport(j)).toThrow(/series\.quaternion: shape \[6,1,4\] does not match \(T=5, N=1, 4\)/);
    j.series.quaternion = syntheticReport({ T: 5, particle: false }).series.quaternion;
    j.system.angular_momentum = other.system.angular_momentum;
    expect(() => decodeReport(j)).toThrow(/system\.angular_momentum/);
  });

  it('requires t, position and quaternion; everything else may be absent', () => {
    const j = syntheticReport({ T: 5, particle: false }) as Record<string, any>;
    for (const k of ['omega_world', 'omega_principal']) delete j.series[k];
    j.system = {};
    delete j.events;
    delete j.springs;
    const r = decodeReport(j);
    expect(r.series.omega_world).toBeUndefined();
    expect(r.system.total_energy).toBeUndefined();
    expect(r.events).toEqual([]);
    delete j.series.quaternion;
    expect(() => decodeReport(j)).toThrow(/series\.quaternion: missing/);
    const k = syntheticReport({ T: 5 }) as Record<string, any>;
    delete k.t;
    expect(() => decodeReport(k)).toThrow(/^t: missing/);
  });

  it('checks format, version, times, indices', () => {
    const base = () => syntheticReport({ T: 5 }) as Record<string, any>;
    expect(() => decodeReport({ ...base(), format: 'x' })).toThrow(/format/);
    expect(() => decodeReport({ ...base(), version: 2 })).toThrow(/version/);
    const j = base();
    j.t = enc('f64', [5], new Float64Array([0, 1, 0.5, 2, 3]));
    expect(() => decodeReport(j)).toThrow(/times decrease at sample 2/);
    const s = base();
    s.springs[0].a = 7;
    expect(() => decodeReport(s)).toThrow(/springs\[0\]\.a/);
    const m = base();
    m.bodies[0].mesh.indices = enc('u32', [1, 3], new Uint32Array([0, 1, 99]));
    expect(() => decodeReport(m)).toThrow(/index 99/);
    const k = base();
    k.bodies[1].kind = 'rock';
    expect(() => decodeReport(k)).toThrow(/bodies\[1\]\.kind/);
  });

  it('reads null numbers in meta as NaN / null', () => {
    const j = syntheticReport({ T: 5 }) as Record<string, any>;
    j.meta.wall_time_s = null;
    j.meta.timestep = null;
    const r = decodeReport(j);
    expect(r.meta.wall_time_s).toBeNull();
    expect(Number.isNaN(r.meta.timestep)).toBe(true);
  });

  it('reads down-sampled counts', () => {
    const r = decodeReport(syntheticReport({ T: 7, samplesTotal: 70001 }));
    expect(r.meta.samples_shown).toBe(7);
    expect(r.meta.samples_total).toBe(70001);
  });
});

describe('readEmbedded', () => {
  it('recognises the raw template', () => {
    expect(readEmbedded(PLACEHOLDER)).toEqual({ kind: 'template' });
    expect(readEmbedded(`\n  ${PLACEHOLDER} \n`)).toEqual({ kind: 'template' });
  });

  it('reports bad JSON and bad data as errors, not exceptions', () => {
    const bad = readEmbedded('{"format": ');
    expect(bad.kind).toBe('error');
    expect((bad as { message: string }).message).toMatch(/not valid JSON/);
    const wrong = readEmbedded('{"format":"tumble-report","version":1,"t":[0,1]}');
    expect(wrong).toEqual({ kind: 'error', message: 'bodies: expected a non-empty list' });
    expect(readEmbedded(null).kind).toBe('error');
  });

  it('reads what injectReport wrote, even with </script> and <!-- in strings', () => {
    const j = syntheticReport({ T: 3 });
    j.meta.scene_text = 'a </script> b <!-- <script> c \\</ d $& $1';
    const template = `<html><script id="tumble-data" type="application/json">${PLACEHOLDER}</script></html>`;
    const html = injectReport(template, JSON.stringify(j));
    expect(html.toLowerCase().indexOf('</script>')).toBe(html.length - '</script></html>'.length);
    expect(html).not.toContain('<!--');
    const text = html.slice(html.indexOf('>', html.indexOf('<script')) + 1, html.lastIndexOf('</script>'));
    const r = readEmbedded(text);
    expect(r.kind).toBe('report');
    expect((r as { report: { meta: { scene_text: string } } }).report.meta.scene_text).toBe(j.meta.scene_text);
  });

  it('escapes only what can end the script element', () => {
    expect(escapeForScript('{"a":"</x>"}')).toBe('{"a":"<\\/x>"}');
    expect(JSON.parse(escapeForScript('"<!--</"'))).toBe('<!--</');
    expect(() => injectReport('no placeholder', '{}')).toThrow(/exactly once/);
  });
});
