// The three.js view: each body's mesh (or a sphere for a particle) posed by the report, its principal
// axes through the centre of mass, its ω and L arrows, an optional trail of the centre of mass,
// springs, a ground grid and an orbit camera that can follow a body.
//
// A crowd (more than CROWD bodies: a debris field of 10⁵) is drawn as one instanced mesh per surface,
// a draw call each rather than three per body; axes, arrows and the trail are then drawn for the
// followed body only. Bodies of one surface share one geometry either way.
//
// tumble's world is z-up (gravity along -z in the examples), so the camera's up is +z and the grid
// lies in the xy-plane. Rendering happens only when something changed (time, camera, size): a
// software-rendered WebGL (no GPU) would otherwise burn a core redrawing a still picture.

import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { COLORS, bodyColor } from './colors';
import { bodyVectors, comTrack, principalAxes, toWorld, vectorMaxima } from './derived';
import { FOLLOW_ALL, FRAME_MARGIN, type Framing, sizesOf, sphereNow } from './framing';
import { norm, wxyzToXyzw, xyzwToWxyz } from './quat';
import { lerpRow, quatAtSegment, type Segment } from './timeline';
import type { Body, Mesh, QuatWXYZ, Report, Vec3 } from './types';

import { CROWD } from './bodypicker';

interface BodyView {
  /** Posed by the report: position = origin of the reference frame, quaternion = R. */
  group: THREE.Group;
  omegaArrow: THREE.ArrowHelper | null;
  LArrow: THREE.ArrowHelper | null;
  /** The centre of mass's path, made when trails are first shown (a pass over every sample). */
  trail: THREE.Line | null;
  color: THREE.Color;
  /** Length scales of the arrows: the largest |ω| (|L|) of the run is drawn `arrowLength` long. */
  omegaScale: number;
  LScale: number;
  head: number;
}

/** Arrows and axes drawn on top of the meshes: they sit inside the body, where they belong. */
function overlayMaterial<T extends THREE.Material>(m: T): T {
  m.depthTest = false;
  m.transparent = true;
  return m;
}

function makeArrow(color: string): THREE.ArrowHelper {
  const a = new THREE.ArrowHelper(new THREE.Vector3(0, 0, 1), new THREE.Vector3(), 1, color);
  overlayMaterial(a.line.material as THREE.Material);
  overlayMaterial(a.cone.material as THREE.Material);
  a.renderOrder = 10;
  a.line.renderOrder = 10;
  a.cone.renderOrder = 10;
  return a;
}

/** Points `a` along v from `origin`, |v| * scale long; the head is `head` long (less on short arrows). */
function setArrow(a: THREE.ArrowHelper, origin: Vec3, v: Vec3 | null, scale: number, head: number): void {
  const n = v ? norm(v) : 0;
  const length = n * scale;
  if (!v || !(length > 1e-9) || !Number.isFinite(length)) {
    a.visible = false;
    return;
  }
  a.visible = true;
  a.position.set(origin[0], origin[1], origin[2]);
  a.setDirection(new THREE.Vector3(v[0] / n, v[1] / n, v[2] / n));
  const h = Math.min(head, length * 0.5);
  a.setLength(length, h, h * 0.5);
}

/** A round number (1, 2 or 5 times a power of ten) at or above x: grid cells of readable size. */
export function niceCeil(x: number): number {
  if (!(x > 0)) return 1;
  const p = Math.pow(10, Math.floor(Math.log10(x)));
  for (const m of [1, 2, 5, 10]) if (m * p >= x) return m * p;
  return 10 * p;
}

/** Names of WebGL implementations that rasterise on the CPU. */
const SOFTWARE_GL = /swiftshader|llvmpipe|softpipe|software|basic render/i;

/**
 * A renderer with antialiasing on a GPU and without it where WebGL runs in software (SwiftShader on
 * a machine without a GPU, as in CI): there multisampling costs more than the rest of the frame.
 * The probe context is kept in the software case, so asking costs nothing there.
 *
 * preserveDrawingBuffer: the browser tests and screenshots read the canvas back after the frame was
 * shown; its cost is small.
 */
function createRenderer(): THREE.WebGLRenderer {
  const canvas = document.createElement('canvas');
  const attributes = { antialias: false, alpha: false, depth: true, stencil: false, preserveDrawingBuffer: true };
  const gl = canvas.getContext('webgl2', attributes) as WebGL2RenderingContext | null;
  if (!gl) throw new Error('this browser has no WebGL 2');
  let name = String(gl.getParameter(gl.RENDERER));
  if (!SOFTWARE_GL.test(name)) {
    // Chrome masks RENDERER ("WebKit WebGL"); the unmasked name needs the extension (which Firefox
    // deprecates, hence asked only when the plain name says nothing).
    const info = gl.getExtension('WEBGL_debug_renderer_info');
    if (info) name = String(gl.getParameter(info.UNMASKED_RENDERER_WEBGL));
  }
  if (SOFTWARE_GL.test(name)) return new THREE.WebGLRenderer({ canvas, context: gl, ...attributes });
  gl.getExtension('WEBGL_lose_context')?.loseContext();
  return new THREE.WebGLRenderer({ ...attributes, antialias: true });
}

export class Scene3D {
  readonly renderer: THREE.WebGLRenderer;
  readonly camera: THREE.PerspectiveCamera;
  readonly controls: OrbitControls;
  private scene = new THREE.Scene();
  /** Each body's objects; in a crowd only the followed body's (the others are instances). */
  private views: (BodyView | null)[] = [];
  private geometries = new Map<Mesh | 'sphere', THREE.BufferGeometry>();
  private readonly crowd: boolean;
  /** A crowd's instance of each body, and its pose as last drawn (x, then q as w, x, y, z). */
  private crowdSlots: { mesh: THREE.InstancedMesh; index: number; local: THREE.Matrix4 }[] = [];
  private crowdPoses = new Float64Array(0);
  private crowdMeshes: THREE.InstancedMesh[] = [];
  private springs: THREE.LineSegments | null = null;
  private dirty = true;
  private followIndex = -1;
  private trails = false;
  private followPoint = new THREE.Vector3();
  private lastSegment: Segment = { i: 0, s: 0 };
  private resizeObserver: ResizeObserver;
  /** Radius of the bodies at the start: the unit for default sizes. */
  readonly radius: number;
  /** Each body's size and centre of mass as last drawn (3 per body), for keeping all of them in view. */
  private readonly sizes: Float64Array;
  private coms: Float64Array;
  /** Whether update() has posed the bodies yet. */
  private posed = false;

  constructor(
    private container: HTMLElement,
    private report: Report,
    framing: Framing,
  ) {
    this.renderer = createRenderer();
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
    this.renderer.setClearColor(COLORS.background);
    container.appendChild(this.renderer.domElement);

    const N = report.bodies.length;
    // The view is framed on the bodies as they are at the start; the far plane and the grid cover the
    // whole run (following moves the camera, never its near and far planes).
    const { start, run } = framing;
    const sphere = new THREE.Sphere(new THREE.Vector3(...start.center), start.radius);
    const allSphere = new THREE.Sphere(new THREE.Vector3(...run.center), run.radius);
    this.radius = Math.max(sphere.radius, 1e-3);
    this.sizes = sizesOf(report);
    this.coms = new Float64Array(3 * N);

    this.camera = new THREE.PerspectiveCamera(40, 1, this.radius * 0.01, 1);
    this.camera.up.set(0, 0, 1);
    const dist = this.distanceToShow(this.radius);
    const dir = new THREE.Vector3(1, -1.6, 0.9).normalize();
    this.camera.position.copy(sphere.center).addScaledVector(dir, dist);
    // Far enough for the camera that keeps every body in view (FOLLOW_ALL) over the whole run.
    this.camera.far = (this.distanceToShow(allSphere.radius) + dist + allSphere.radius + allSphere.center.distanceTo(sphere.center)) * 20;
    this.camera.updateProjectionMatrix();

    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.target.copy(sphere.center);
    this.controls.update();
    this.controls.addEventListener('change', () => (this.dirty = true));

    this.addLights();
    this.addGrid(framing.runBox, sphere);
    this.crowd = N > CROWD;
    if (this.crowd) {
      this.views = new Array<BodyView | null>(N).fill(null);
      this.makeCrowd();
    } else {
      for (let b = 0; b < N; b++) this.views.push(this.makeBody(b));
    }
    this.makeSprings();

    this.resizeObserver = new ResizeObserver(() => this.resize());
    this.resizeObserver.observe(container);
    this.resize();
  }

  private addLights(): void {
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x404050, 1.6));
    // The key light rides with the camera so the side the user looks at is always lit.
    const key = new THREE.DirectionalLight(0xffffff, 1.8);
    key.position.set(0.5, 1, 1);
    this.camera.add(key);
    this.scene.add(this.camera);
  }

  private addGrid(run: Framing['runBox'], start: THREE.Sphere): void {
    const lo = run?.lo ?? start.center.clone().subScalar(start.radius).toArray();
    const hi = run?.hi ?? start.center.clone().addScalar(start.radius).toArray();
    const extent = Math.max(hi[0] - lo[0], hi[1] - lo[1], start.radius * 4);
    const cell = niceCeil(extent / 12);
    const divisions = 24;
    const grid = new THREE.GridHelper(cell * divisions, divisions, 0x5a6270, 0x3a404a);
    grid.rotation.x = Math.PI / 2; // GridHelper lies in xz (y-up); tumble's ground is the xy-plane
    // Centred under the run, just below the lowest point any body reaches.
    const cx = Math.round((lo[0] + hi[0]) / 2 / cell) * cell;
    const cy = Math.round((lo[1] + hi[1]) / 2 / cell) * cell;
    grid.position.set(cx, cy, lo[2] - start.radius * 0.05);
    this.scene.add(grid);
  }

  /** One geometry per surface (bodies of one mesh file share it; so do all boxes and all spheres). */
  private geometryOf(body: Body): THREE.BufferGeometry {
    const key = body.mesh ?? 'sphere';
    let g = this.geometries.get(key);
    if (!g) {
      if (body.mesh) {
        g = new THREE.BufferGeometry();
        g.setAttribute('position', new THREE.BufferAttribute(body.mesh.positions, 3));
        g.setIndex(new THREE.BufferAttribute(body.mesh.indices, 1));
      } else {
        g = new THREE.SphereGeometry(1, 20, 14); // scaled per body (localMatrix)
      }
      this.geometries.set(key, g);
    }
    return g;
  }

  /**
   * Where the body's geometry sits in its reference frame: the mesh as it is; a box's unit cube
   * scaled by its edges along the principal axes (the columns of U) at the centre of mass; a sphere
   * (particles, bodies without a surface) at the centre of mass.
   */
  private localMatrix(body: Body): THREE.Matrix4 {
    const m = new THREE.Matrix4();
    if (body.mesh && !body.box) return m;
    const [c, U] = [body.com, body.principal_axes];
    if (body.mesh && body.box) {
      const [a, b, d] = body.box;
      return m.set(
        U[0][0] * a, U[0][1] * b, U[0][2] * d, c[0],
        U[1][0] * a, U[1][1] * b, U[1][2] * d, c[1],
        U[2][0] * a, U[2][1] * b, U[2][2] * d, c[2],
        0, 0, 0, 1,
      );
    }
    const size = body.size > 0 ? body.size : this.radius * 0.3;
    const r = body.kind === 'particle' ? size * 0.5 : size * 0.6;
    return m.makeScale(r, r, r).setPosition(c[0], c[1], c[2]);
  }

  /** Lambert, not a PBR material: flat faces show the shape as well, and its shader compiles and runs
   * several times faster where WebGL is rendered in software (SwiftShader, no GPU). */
  private static material(color: THREE.Color): THREE.MeshLambertMaterial {
    return new THREE.MeshLambertMaterial({ color, flatShading: true, side: THREE.DoubleSide });
  }

  /**
   * The crowd's instanced meshes, one per surface; instance k of a surface is body crowdBodies[k],
   * posed by update() as pose × localMatrix.
   */
  private makeCrowd(): void {
    const N = this.report.bodies.length;
    const groups = new Map<THREE.BufferGeometry, number[]>();
    for (let b = 0; b < N; b++) {
      const g = this.geometryOf(this.report.bodies[b]);
      const list = groups.get(g);
      if (list) list.push(b);
      else groups.set(g, [b]);
    }
    this.crowdPoses = new Float64Array(N * 7);
    for (const [geometry, bodies] of groups) {
      const mesh = new THREE.InstancedMesh(geometry, Scene3D.material(new THREE.Color(0xffffff)), bodies.length);
      mesh.frustumCulled = false; // the instances move; their bounds are not the geometry's
      bodies.forEach((b, k) => {
        mesh.setColorAt(k, new THREE.Color(bodyColor(b)));
        this.crowdSlots[b] = { mesh, index: k, local: this.localMatrix(this.report.bodies[b]) };
      });
      this.scene.add(mesh);
      this.crowdMeshes.push(mesh);
    }
  }

  /** A body's own objects: its mesh (unless drawn as an instance), principal axes and arrows. */
  private makeBody(b: number, withMesh = true): BodyView {
    const body = this.report.bodies[b];
    const color = new THREE.Color(bodyColor(b));
    const group = new THREE.Group();
    group.name = body.name;
    const size = body.size > 0 ? body.size : this.radius * 0.3;

    if (withMesh) {
      const mesh = new THREE.Mesh(this.geometryOf(body), Scene3D.material(color));
      mesh.matrixAutoUpdate = false;
      mesh.matrix.copy(this.localMatrix(body));
      group.add(mesh);
    }
    if (body.kind === 'body') {
      // The principal axes: three short lines through the centre of mass, in the reference frame, so
      // the group's pose carries them along.
      const axes = principalAxes(body);
      const pts: number[] = [];
      const cols: number[] = [];
      const half = size * 0.9;
      axes.forEach((a, k) => {
        const c = new THREE.Color(COLORS.axes[k]);
        for (const sgn of [-1, 1]) {
          pts.push(body.com[0] + sgn * half * a[0], body.com[1] + sgn * half * a[1], body.com[2] + sgn * half * a[2]);
          cols.push(c.r, c.g, c.b);
        }
      });
      const g = new THREE.BufferGeometry();
      g.setAttribute('position', new THREE.Float32BufferAttribute(pts, 3));
      g.setAttribute('color', new THREE.Float32BufferAttribute(cols, 3));
      const lines = new THREE.LineSegments(g, overlayMaterial(new THREE.LineBasicMaterial({ vertexColors: true })));
      lines.renderOrder = 5;
      group.add(lines);
    }
    this.scene.add(group);

    const max = vectorMaxima(this.report, b);
    // ω a little longer than L: about a principal axis the two are parallel, and the longer ω then
    // still shows past the tip of L (drawn over it).
    const arrowLength = size * 1.5;
    let omegaArrow: THREE.ArrowHelper | null = null;
    let LArrow: THREE.ArrowHelper | null = null;
    if (max.omega > 0) {
      omegaArrow = makeArrow(COLORS.omega);
      this.scene.add(omegaArrow);
    }
    if (max.L > 0) {
      LArrow = makeArrow(COLORS.L);
      LArrow.renderOrder = LArrow.line.renderOrder = LArrow.cone.renderOrder = 11;
      this.scene.add(LArrow);
    }

    return {
      group,
      omegaArrow,
      LArrow,
      trail: null,
      color,
      omegaScale: max.omega > 0 ? (arrowLength * 1.3) / max.omega : 0,
      LScale: max.L > 0 ? arrowLength / max.L : 0,
      head: arrowLength * 0.16,
    };
  }

  private makeSprings(): void {
    const S = this.report.springs.length;
    if (S === 0) return;
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(new Float32Array(S * 6), 3));
    this.springs = new THREE.LineSegments(g, new THREE.LineBasicMaterial({ color: 0xd0d4dc }));
    this.springs.frustumCulled = false;
    this.scene.add(this.springs);
  }

  /** Poses everything for the time at `seg` (sample i, fraction s towards i + 1). */
  update(seg: Segment): void {
    this.lastSegment = seg;
    const r = this.report;
    const N = r.bodies.length;
    const poses: { x: Vec3; q: QuatWXYZ }[] = [];
    const pose = new THREE.Matrix4(), quaternion = new THREE.Quaternion(), position = new THREE.Vector3();
    const one = new THREE.Vector3(1, 1, 1);
    for (let b = 0; b < N; b++) {
      const x = lerpRow(r.series.position, N, b, 3, seg, [0, 0, 0]) as Vec3;
      const q = quatAtSegment(r.series.quaternion, N, b, seg);
      poses.push({ x, q });
      const com = toWorld(x, q, r.bodies[b].com);
      this.coms.set(com, 3 * b);
      const slot = this.crowdSlots[b];
      if (slot) {
        this.crowdPoses.set([x[0], x[1], x[2], q[0], q[1], q[2], q[3]], 7 * b);
        pose.compose(position.set(x[0], x[1], x[2]), quaternion.set(q[1], q[2], q[3], q[0]), one);
        slot.mesh.setMatrixAt(slot.index, pose.multiply(slot.local));
      }
      const v = this.views[b];
      if (!v) continue;
      v.group.position.set(x[0], x[1], x[2]);
      v.group.quaternion.fromArray(wxyzToXyzw(q));
      const vec = bodyVectors(r, b, seg, q);
      if (v.omegaArrow) setArrow(v.omegaArrow, com, vec.omega, v.omegaScale, v.head);
      if (v.LArrow) setArrow(v.LArrow, com, vec.L, v.LScale, v.head);
      v.trail?.geometry.setDrawRange(0, seg.i + 1);
    }
    for (const mesh of this.crowdMeshes) mesh.instanceMatrix.needsUpdate = true;
    if (this.springs) {
      const attr = this.springs.geometry.getAttribute('position') as THREE.BufferAttribute;
      r.springs.forEach((s, k) => {
        const pa = toWorld(poses[s.a].x, poses[s.a].q, s.point_a);
        const pb = s.b === null ? s.point_b : toWorld(poses[s.b].x, poses[s.b].q, s.point_b);
        attr.setXYZ(2 * k, pa[0], pa[1], pa[2]);
        attr.setXYZ(2 * k + 1, pb[0], pb[1], pb[2]);
      });
      attr.needsUpdate = true;
    }
    this.posed = true;
    this.applyFollow();
    this.dirty = true;
  }

  /**
   * Moves the camera with what it follows: the followed body's centre of mass stays the orbit target;
   * or (FOLLOW_ALL) the centre of the bodies now does, and the camera backs off when they spread
   * beyond its view (it never closes in by itself: the user's zoom stays).
   */
  private applyFollow(): void {
    if (this.followIndex === FOLLOW_ALL) {
      const now = sphereNow(this.coms, this.sizes);
      if (!now) return;
      const center = new THREE.Vector3(...now.center);
      this.camera.position.add(center.clone().sub(this.controls.target));
      this.controls.target.copy(center);
      const away = this.camera.position.clone().sub(center);
      const needed = this.distanceToShow(now.radius);
      if (away.length() < needed) this.camera.position.copy(center).addScaledVector(away.normalize(), needed);
      this.controls.update();
      return;
    }
    if (this.followIndex < 0) return;
    const p = this.comOf(this.followIndex);
    const delta = p.clone().sub(this.followPoint);
    this.followPoint.copy(p);
    this.camera.position.add(delta);
    this.controls.target.add(delta);
    this.controls.update();
  }

  /** How far from a sphere's centre the camera shows all of it, with the default margin. */
  private distanceToShow(radius: number): number {
    // The narrower of the two angles of view: the vertical one, or the horizontal one of a tall view.
    const halfVertical = THREE.MathUtils.degToRad(this.camera.fov) / 2;
    const half = Math.atan(Math.tan(halfVertical) * Math.min(1, this.camera.aspect));
    return (radius / Math.sin(half)) * FRAME_MARGIN;
  }

  private comOf(b: number): THREE.Vector3 {
    const [x, q] = this.poseOf(b);
    const com = this.report.bodies[b].com;
    return new THREE.Vector3(com[0], com[1], com[2]).applyQuaternion(q).add(x);
  }

  /** The body's pose as last drawn. */
  private poseOf(b: number): [THREE.Vector3, THREE.Quaternion] {
    const v = this.views[b];
    if (v) return [v.group.position.clone(), v.group.quaternion.clone()];
    const p = this.crowdPoses.subarray(7 * b, 7 * b + 7);
    return [new THREE.Vector3(p[0], p[1], p[2]), new THREE.Quaternion(p[4], p[5], p[6], p[3])];
  }

  /** Follow body `b` (its centre of mass becomes the orbit target), all of them (FOLLOW_ALL), or none. */
  setFollow(b: number): void {
    // In a crowd the followed body alone gets its axes, arrows (and trail).
    if (this.crowd && this.followIndex !== b && this.followIndex >= 0) this.dropView(this.followIndex);
    this.followIndex = b;
    if (b === FOLLOW_ALL && this.posed) {
      this.applyFollow();
      this.dirty = true;
    }
    if (b < 0) return;
    if (this.crowd && !this.views[b]) {
      this.views[b] = this.makeBody(b, false);
      this.setTrails(this.trails);
      this.update(this.lastSegment);
    }
    const p = this.comOf(b);
    const delta = p.clone().sub(this.controls.target);
    this.camera.position.add(delta);
    this.controls.target.copy(p);
    this.followPoint.copy(p);
    this.controls.update();
    this.dirty = true;
  }

  /** Removes a body's own objects (a crowd's body no longer followed). */
  private dropView(b: number): void {
    const v = this.views[b];
    if (!v) return;
    for (const o of [v.group, v.omegaArrow, v.LArrow, v.trail]) if (o) this.scene.remove(o);
    this.views[b] = null;
  }

  setTrails(on: boolean): void {
    this.trails = on;
    this.views.forEach((v, b) => {
      if (!v) return;
      if (on && !v.trail) {
        const g = new THREE.BufferGeometry();
        g.setAttribute('position', new THREE.BufferAttribute(comTrack(this.report, b), 3));
        g.setDrawRange(0, this.lastSegment.i + 1);
        v.trail = new THREE.Line(g, new THREE.LineBasicMaterial({ color: v.color, transparent: true, opacity: 0.7 }));
        v.trail.frustumCulled = false;
        this.scene.add(v.trail);
      }
      if (v.trail) v.trail.visible = on;
    });
    this.dirty = true;
  }

  /** The orientation as drawn, read back from the three.js object: [w, x, y, z]. */
  bodyQuaternion(b: number): QuatWXYZ {
    return xyzwToWxyz(this.poseOf(b)[1].toArray());
  }

  /** Where body b's centre of mass is drawn, in normalised device coordinates (x, y in [-1, 1] and z < 1
   * when in view), with the camera as it is now (following a body moves it at each frame). */
  bodyOnScreen(b: number): Vec3 {
    this.camera.updateMatrixWorld();
    const p = this.comOf(b).project(this.camera);
    return [p.x, p.y, p.z];
  }

  private resize(): void {
    const w = Math.max(1, this.container.clientWidth);
    const h = Math.max(1, this.container.clientHeight);
    // The observer also reports the first, unchanged size: no redraw for that.
    const size = this.renderer.getSize(new THREE.Vector2());
    if (size.x === w && size.y === h) return;
    this.renderer.setSize(w, h);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.dirty = true;
  }

  /** Draws if anything changed since the last frame. */
  render(force = false): void {
    if (!this.dirty && !force) return;
    this.dirty = false;
    this.renderer.render(this.scene, this.camera);
  }
}
