// A synthetic report whose every value is known in closed form, for the browser tests and for
// trying the viewer without the C++ CLI: a T-handle-like body (a bar on a stem) in steady rotation
// about its intermediate principal axis, optionally with a particle bobbing on a spring.
//
// Steady rotation at rate w about a principal axis fixed in space, n = R0 U e2, is exact for a free
// rigid body: R(t) = exp(w t [n]x) R0, ω_world = w n, ω_principal = w e2, L = I2 w n. Slerp between
// two samples of a rotation about a fixed axis at a constant rate is exactly that rotation, so
// the orientation drawn at ANY time must equal the closed form (to float32 rounding).

export const W = 3.0; // rad/s
const DENSITY = 2700; // kg/m^3

function normalize(v) {
  const n = Math.hypot(...v);
  return v.map((x) => x / n);
}
function qmul(a, b) {
  return [
    a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
    a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
    a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
    a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
  ];
}
function axisAngle(n, angle) {
  const s = Math.sin(angle / 2);
  return [Math.cos(angle / 2), n[0] * s, n[1] * s, n[2] * s];
}
function rotate(q, v) {
  const [w, x, y, z] = q;
  const tx = 2 * (y * v[2] - z * v[1]);
  const ty = 2 * (z * v[0] - x * v[2]);
  const tz = 2 * (x * v[1] - y * v[0]);
  return [v[0] + w * tx + (y * tz - z * ty), v[1] + w * ty + (z * tx - x * tz), v[2] + w * tz + (x * ty - y * tx)];
}

/** Box [x0,x1]x[y0,y1]x[z0,z1] as 8 vertices and 12 outward triangles, appended to pos/idx. */
function box(pos, idx, [x0, y0, z0], [x1, y1, z1]) {
  const base = pos.length / 3;
  for (const z of [z0, z1]) for (const y of [y0, y1]) for (const x of [x0, x1]) pos.push(x, y, z);
  const quads = [
    [0, 2, 3, 1], [4, 5, 7, 6], // -z, +z
    [0, 1, 5, 4], [2, 6, 7, 3], // -y, +y
    [0, 4, 6, 2], [1, 3, 7, 5], // -x, +x
  ];
  for (const [a, b, c, d] of quads) idx.push(base + a, base + b, base + c, base + a, base + c, base + d);
}

/** Mass properties of the two boxes: mass, centre of mass, inertia about the com (diagonal). */
function massProperties(boxes) {
  let m = 0;
  const c = [0, 0, 0];
  for (const [lo, hi] of boxes) {
    const d = [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
    const mi = DENSITY * d[0] * d[1] * d[2];
    m += mi;
    for (let k = 0; k < 3; k++) c[k] += (mi * (lo[k] + hi[k])) / 2;
  }
  for (let k = 0; k < 3; k++) c[k] /= m;
  const I = [0, 0, 0];
  for (const [lo, hi] of boxes) {
    const d = [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
    const mi = DENSITY * d[0] * d[1] * d[2];
    const r = [0, 1, 2].map((k) => (lo[k] + hi[k]) / 2 - c[k]);
    I[0] += (mi * (d[1] ** 2 + d[2] ** 2)) / 12 + mi * (r[1] ** 2 + r[2] ** 2);
    I[1] += (mi * (d[0] ** 2 + d[2] ** 2)) / 12 + mi * (r[0] ** 2 + r[2] ** 2);
    I[2] += (mi * (d[0] ** 2 + d[1] ** 2)) / 12 + mi * (r[0] ** 2 + r[1] ** 2);
  }
  return { m, c, I };
}

// A bar 0.10 x 0.02 x 0.02 m along x on top of a 0.06 m stem along z; origin at the stem's foot.
const BOXES = [
  [[-0.05, -0.01, 0.06], [0.05, 0.01, 0.08]],
  [[-0.01, -0.01, 0.0], [0.01, 0.01, 0.06]],
];
const MP = massProperties(BOXES);
// Principal axes (columns of U), moments ascending: x (smallest), z (intermediate), -y (largest),
// a proper rotation (det +1) that is not the identity, so a row/column mix-up would show.
export const U = [
  [1, 0, 0],
  [0, 0, -1],
  [0, 1, 0],
];
export const MOMENTS = [MP.I[0], MP.I[2], MP.I[1]];
export const COM_REF = MP.c;
export const COM_WORLD = [0.02, -0.01, 0.1];
export const Q0 = axisAngle(normalize([1, 2, 3]), 0.7);
/** The spin axis in the world: R0 U e2 (U's second column, rotated). */
export const AXIS = rotate(Q0, [U[0][1], U[1][1], U[2][1]]);

/** The closed-form orientation [w, x, y, z] at time t. */
export function expectedQuaternion(t) {
  return qmul(axisAngle(AXIS, W * t), Q0);
}

const PARTICLE_MASS = 0.01;
const ANCHOR = [0.15, 0, 0.2];
function particlePosition(t) {
  return [ANCHOR[0], ANCHOR[1], ANCHOR[2] - 0.06 - 0.02 * Math.cos(2 * t)];
}
function particleVelocity(t) {
  return [0, 0, 0.04 * Math.sin(2 * t)];
}

function encode(dtype, shape, values) {
  const Arr = { f32: Float32Array, f64: Float64Array, u32: Uint32Array }[dtype];
  const a = values instanceof Arr ? values : Arr.from(values);
  return { dtype, shape, base64: Buffer.from(a.buffer, a.byteOffset, a.byteLength).toString('base64') };
}

/**
 * The report JSON (an object). T samples over `duration` seconds; `particle` adds a particle on a
 * spring to a world anchor; `samplesTotal` pretends the CLI thinned a longer run.
 */
export function syntheticReport({ T = 501, duration = 10, particle = true, samplesTotal = T, events = true } = {}) {
  const N = particle ? 2 : 1;
  const t = new Float64Array(T);
  const position = new Float32Array(T * N * 3);
  const quaternion = new Float32Array(T * N * 4);
  const omegaWorld = new Float32Array(T * N * 3);
  const omegaPrincipal = new Float32Array(T * N * 3);
  const ke = new Float64Array(T);
  const pe = new Float64Array(T);
  const te = new Float64Array(T);
  const drift = new Float64Array(T);
  const L = new Float64Array(T * 3);
  const Ldrift = new Float64Array(T);
  const I2 = MOMENTS[1];
  const Lbody = AXIS.map((a) => I2 * W * a);
  for (let i = 0; i < T; i++) {
    const ti = (duration * i) / Math.max(1, T - 1);
    t[i] = ti;
    const q = expectedQuaternion(ti);
    const rc = rotate(q, COM_REF);
    const o = i * N;
    for (let k = 0; k < 3; k++) position[o * 3 + k] = COM_WORLD[k] - rc[k];
    quaternion.set(q, o * 4);
    for (let k = 0; k < 3; k++) omegaWorld[o * 3 + k] = W * AXIS[k];
    omegaPrincipal.set([0, W, 0], o * 3);
    let kinetic = 0.5 * I2 * W * W;
    let potential = 0;
    const Li = [...Lbody];
    if (particle) {
      const p = particlePosition(ti);
      const v = particleVelocity(ti);
      position.set(p, (o + 1) * 3);
      quaternion.set([1, 0, 0, 0], (o + 1) * 4);
      kinetic += 0.5 * PARTICLE_MASS * v[2] ** 2;
      potential = 0.5 * PARTICLE_MASS * 4 * (0.02 * Math.cos(2 * t[i])) ** 2; // k = m ω², ω = 2
      Li[0] += PARTICLE_MASS * (p[1] * v[2] - p[2] * v[1]);
      Li[1] += PARTICLE_MASS * (p[2] * v[0] - p[0] * v[2]);
      Li[2] += PARTICLE_MASS * (p[0] * v[1] - p[1] * v[0]);
    }
    ke[i] = kinetic;
    pe[i] = potential;
    te[i] = kinetic + potential;
    // A small made-up drift; its first value NaN, as a relative drift of an E0 = 0 run would be.
    drift[i] = i === 0 ? NaN : 1e-12 * Math.sin(ti);
    L.set(Li, i * 3);
    Ldrift[i] = 1e-13 * ti;
  }
  const pos = [];
  const idx = [];
  for (const [lo, hi] of BOXES) box(pos, idx, lo, hi);
  const bodies = [
    {
      name: 'handle',
      kind: 'body',
      mesh: { positions: encode('f32', [pos.length / 3, 3], pos), indices: encode('u32', [idx.length / 3, 3], idx) },
      com: COM_REF,
      principal_axes: U,
      principal_moments: MOMENTS,
      size: 0.06,
    },
  ];
  if (particle) {
    bodies.push({
      name: 'bob',
      kind: 'particle',
      mesh: null,
      com: [0, 0, 0],
      principal_axes: [[1, 0, 0], [0, 1, 0], [0, 0, 1]],
      principal_moments: [0, 0, 0],
      size: 0.012,
    });
  }
  const halfTurn = Math.PI / W;
  return {
    format: 'tumble-report',
    version: 1,
    meta: {
      tumble_version: '0.0.0-synthetic',
      scene_path: 'synthetic/t_handle_steady.toml',
      scene_text: '# synthetic: steady rotation about the intermediate axis\n[simulation]\nduration = 10.0\n# a string that must not close the script element: </script><!-- <script>\n',
      integrator: 'exact',
      formulation: 'body',
      timestep: 1e-3,
      duration,
      wall_time_s: 0.0123,
      samples_total: samplesTotal,
      samples_shown: T,
      warnings: particle ? ['synthetic data: energy drift is made up (1e-12 sin t)'] : [],
    },
    t: encode('f64', [T], t),
    bodies,
    springs: particle ? [{ a: 1, b: null, point_a: [0, 0, 0], point_b: ANCHOR }] : [],
    series: {
      position: encode('f32', [T, N, 3], position),
      quaternion: encode('f32', [T, N, 4], quaternion),
      omega_world: encode('f32', [T, N, 3], omegaWorld),
      omega_principal: encode('f32', [T, N, 3], omegaPrincipal),
    },
    system: {
      kinetic_energy: encode('f64', [T], ke),
      potential_energy: encode('f64', [T], pe),
      total_energy: encode('f64', [T], te),
      energy_drift: encode('f64', [T], drift),
      angular_momentum: encode('f64', [T, 3], L),
      angular_momentum_drift: encode('f64', [T], Ldrift),
    },
    events: events
      ? [
          { name: 'half turn', t: halfTurn, body: 0 },
          { name: 'full turn', t: 2 * halfTurn, body: 0 },
          ...(particle ? [{ name: 'bob lowest', t: Math.PI / 2, body: 1 }] : []),
        ]
      : [],
  };
}

/** The stored (float32) quaternion of body b at sample i, as the report holds it. */
export function storedQuaternion(report, i, b = 0) {
  const N = report.bodies.length;
  const bytes = Buffer.from(report.series.quaternion.base64, 'base64');
  const q = new Float32Array(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength));
  return Array.from(q.subarray((i * N + b) * 4, (i * N + b) * 4 + 4));
}

/** The stored sample times. */
export function storedTimes(report) {
  const b = Buffer.from(report.t.base64, 'base64');
  return new Float64Array(b.buffer.slice(b.byteOffset, b.byteOffset + b.byteLength));
}
