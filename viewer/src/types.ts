// The decoded report: what src/data.ts makes of the JSON the C++ CLI embeds (README.md "Data
// contract"). Every array is a typed array, flat and row-major, so the views and plots index it
// without copying.

export type Vec3 = [number, number, number];
/** Quaternion with w FIRST, as tumble writes it: [w, x, y, z]. */
export type QuatWXYZ = [number, number, number, number];
export type Mat3 = [Vec3, Vec3, Vec3];

export interface Meta {
  tumble_version: string;
  scene_path: string;
  scene_text: string;
  integrator: string;
  formulation: string;
  timestep: number;
  duration: number;
  wall_time_s: number | null;
  samples_total: number;
  samples_shown: number;
  warnings: string[];
}

export interface Mesh {
  /** V*3 vertex coordinates in the body's reference frame, m. */
  positions: Float32Array;
  /** F*3 vertex indices. */
  indices: Uint32Array;
}

export interface Body {
  name: string;
  kind: 'body' | 'particle';
  /** Shared by every body of the same surface (the report's "meshes", one object each). */
  mesh: Mesh | null;
  /**
   * The edges of the box the body is drawn as (no surface of its own: the box of its principal
   * moments): its mesh is then the unit cube, scaled by these along the principal axes and centred
   * at the centre of mass. null: the mesh is in the reference frame as it is.
   */
  box: Vec3 | null;
  com: Vec3;
  /** Row-major U; its COLUMNS are the principal axes in the reference frame. */
  principal_axes: Mat3;
  principal_moments: Vec3;
  size: number;
}

export interface Spring {
  a: number;
  b: number | null;
  point_a: Vec3;
  point_b: Vec3;
}

export interface Series {
  /** T*N*3, world, m: the origin of each body's reference frame. */
  position: Float32Array | Float64Array;
  /** T*N*4, [w,x,y,z]: rotates the reference frame to the world. */
  quaternion: Float32Array | Float64Array;
  omega_world?: Float32Array | Float64Array;
  omega_principal?: Float32Array | Float64Array;
}

export interface SystemSeries {
  kinetic_energy?: Float64Array | Float32Array;
  potential_energy?: Float64Array | Float32Array;
  total_energy?: Float64Array | Float32Array;
  energy_drift?: Float64Array | Float32Array;
  /** T*3, world, about the origin. */
  angular_momentum?: Float64Array | Float32Array;
  angular_momentum_drift?: Float64Array | Float32Array;
}

export interface TumbleEvent {
  name: string;
  t: number;
  body: number | null;
}

export interface Report {
  meta: Meta;
  /** T sample times, s (non-decreasing). */
  t: Float64Array | Float32Array;
  bodies: Body[];
  springs: Spring[];
  series: Series;
  system: SystemSeries;
  events: TumbleEvent[];
}
