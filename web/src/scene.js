// The 3-D view (three.js): base outline, struts coloured by closeness to their limits or (runs with drive
// forces) by force, platform polygon, tool, programmed path (grey) and executed path (coloured by error).
// Renders on demand only.
import {
  AxesHelper,
  Box3,
  BufferGeometry,
  Color,
  CylinderGeometry,
  DirectionalLight,
  DoubleSide,
  DynamicDrawUsage,
  Float32BufferAttribute,
  GridHelper,
  HemisphereLight,
  InstancedMesh,
  Line,
  LineBasicMaterial,
  LineLoop,
  Matrix4,
  Mesh,
  MeshBasicMaterial,
  MeshLambertMaterial,
  PerspectiveCamera,
  Quaternion,
  Scene,
  SphereGeometry,
  SRGBColorSpace,
  Vector3,
  WebGLRenderer,
} from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { closenessRgb, errorRgb, forceRgb } from './colors.js';

export const BACKGROUND = '#f4f6f8';
const NEUTRAL_STRUT = '#8a97a3';

const isPoint = (p) => Array.isArray(p) && p.length >= 2 && Number.isFinite(p[0]) && Number.isFinite(p[1]);
const vec = (p, out = new Vector3()) => out.set(p[0], p[1], Number.isFinite(p[2]) ? p[2] : 0);

/** Nice grid step (1, 2 or 5 times a power of ten) giving at most ~20 cells over `extent`. */
function niceStep(extent) {
  const raw = extent / 16;
  const p = Math.pow(10, Math.floor(Math.log10(raw)));
  for (const m of [1, 2, 5, 10]) if (m * p >= raw) return m * p;
  return 10 * p;
}

function srgbColor(rgb, out = new Color()) {
  return out.setRGB(rgb[0], rgb[1], rgb[2], SRGBColorSpace);
}

/** Positions (and optional per-vertex colours) of a static polyline. */
function polylineGeometry(points, colors) {
  const pos = [];
  const col = [];
  const c = new Color();
  points.forEach((p, i) => {
    if (!isPoint(p)) return;
    pos.push(p[0], p[1], Number.isFinite(p[2]) ? p[2] : 0);
    if (colors) {
      srgbColor(colors(i), c);
      col.push(c.r, c.g, c.b);
    }
  });
  const g = new BufferGeometry();
  g.setAttribute('position', new Float32BufferAttribute(pos, 3));
  if (colors) g.setAttribute('color', new Float32BufferAttribute(col, 3));
  return g;
}

/** A dynamic closed polygon: a line loop and a translucent fan fill around its centroid (up to `max` corners). */
function makePolygon(max, lineColor, fillColor, fillOpacity) {
  const linePos = new Float32BufferAttribute(new Float32Array(max * 3), 3).setUsage(DynamicDrawUsage);
  const lineGeo = new BufferGeometry().setAttribute('position', linePos);
  const line = new LineLoop(lineGeo, new LineBasicMaterial({ color: lineColor }));
  const fillPos = new Float32BufferAttribute(new Float32Array(max * 9), 3).setUsage(DynamicDrawUsage);
  const fillGeo = new BufferGeometry().setAttribute('position', fillPos);
  const fill = new Mesh(
    fillGeo,
    new MeshBasicMaterial({ color: fillColor, transparent: true, opacity: fillOpacity, side: DoubleSide, depthWrite: false }),
  );
  line.frustumCulled = false;
  fill.frustumCulled = false;
  const c = new Vector3();
  return {
    objects: [fill, line],
    /** points: array of [x,y,z] (invalid ones skipped). */
    set(points) {
      const pts = points.filter(isPoint).slice(0, max);
      const m = pts.length;
      c.set(0, 0, 0);
      pts.forEach((p, i) => {
        linePos.setXYZ(i, p[0], p[1], p[2] || 0);
        c.x += p[0] / m;
        c.y += p[1] / m;
        c.z += (p[2] || 0) / m;
      });
      for (let i = 0; i < m && m >= 3; i++) {
        const a = pts[i];
        const b = pts[(i + 1) % m];
        fillPos.setXYZ(3 * i, c.x, c.y, c.z);
        fillPos.setXYZ(3 * i + 1, a[0], a[1], a[2] || 0);
        fillPos.setXYZ(3 * i + 2, b[0], b[1], b[2] || 0);
      }
      lineGeo.setDrawRange(0, m >= 2 ? m : 0);
      fillGeo.setDrawRange(0, m >= 3 ? 3 * m : 0);
      linePos.needsUpdate = true;
      fillPos.needsUpdate = true;
      return m ? c : null;
    },
  };
}

export function createSceneView(container, data) {
  const { scene: sd } = data;
  const frames = sd.frames;
  const n = frames.count;

  const renderer = new WebGLRenderer({ antialias: true, preserveDrawingBuffer: true, powerPreference: 'low-power' });
  renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
  renderer.setClearColor(new Color(BACKGROUND), 1);
  const canvas = renderer.domElement;
  canvas.className = 'scene-canvas';
  container.appendChild(canvas);

  const scene = new Scene();
  const camera = new PerspectiveCamera(35, 1, 1, 1e5);
  camera.up.set(0, 0, 1);

  // ---- bounds of everything that is ever drawn
  const box = new Box3();
  const v = new Vector3();
  const addPts = (pts) => {
    for (const p of pts) if (isPoint(p)) box.expandByPoint(vec(p, v));
  };
  addPts(sd.base_polygon);
  addPts(sd.programmed_path);
  addPts(sd.executed_path);
  addPts(frames.tool);
  for (const fs of frames.struts) for (const s of fs) if (Array.isArray(s)) addPts(s);
  if (box.isEmpty()) box.set(new Vector3(-100, -100, 0), new Vector3(100, 100, 0));
  const size = box.getSize(new Vector3());
  const center = box.getCenter(new Vector3());
  const radius = Math.max(1e-3, size.length() / 2);
  const planar = size.z <= 1e-6 * Math.max(size.x, size.y, 1e-9) && Math.abs(box.max.z) < 1e-9 * radius + 1e-9;

  // Points the camera fits to (subsampled): the whole machine, and the tool path alone.
  const sample = (pts, max) => {
    const out = [];
    const stepK = Math.max(1, Math.ceil(pts.length / max));
    for (let k = 0; k < pts.length; k += stepK) if (isPoint(pts[k])) out.push(vec(pts[k]));
    return out;
  };
  const pathPts = [...sample(sd.programmed_path, 800), ...sample(sd.executed_path, 800), ...sample(frames.tool, 400)];
  const machinePts = [...sample(sd.base_polygon, 1000), ...pathPts];
  const fstep = Math.max(1, Math.ceil(n / 60));
  for (let i = 0; i < n; i += fstep) for (const st of frames.struts[i]) if (Array.isArray(st)) machinePts.push(...sample(st, 2));
  if (!machinePts.length) machinePts.push(box.min.clone(), box.max.clone());

  // ---- lights
  scene.add(new HemisphereLight(0xffffff, 0x9aa6b2, 2.2));
  const sun = new DirectionalLight(0xffffff, 1.6);
  sun.position.set(0.6, -1, 1.4).multiplyScalar(radius * 4).add(center);
  sun.target.position.copy(center);
  scene.add(sun, sun.target);

  // ---- grid and axes on the base plane (z = 0)
  const extent = 2.3 * Math.max(Math.abs(box.min.x), Math.abs(box.max.x), Math.abs(box.min.y), Math.abs(box.max.y), radius * 0.25);
  const step = niceStep(extent);
  const cells = Math.max(2, Math.ceil(extent / step / 2) * 2);
  const grid = new GridHelper(cells * step, cells, 0xb9c2cb, 0xdde2e7);
  grid.rotation.x = Math.PI / 2;
  const gridZ = Math.min(0, box.min.z) - radius * 2e-3;
  grid.position.set(0, 0, gridZ);
  scene.add(grid);
  const axes = new AxesHelper(step * 1.5);
  axes.position.set(0, 0, gridZ + radius * 1e-3);
  scene.add(axes);

  // ---- static geometry: base outline, programmed and executed paths
  const rStrut = radius * 0.0075;
  if (sd.base_polygon.filter(isPoint).length >= 2) {
    const base = makePolygon(sd.base_polygon.length, 0x37474f, 0x90a4ae, 0.18);
    base.set(sd.base_polygon);
    scene.add(...base.objects);
  }
  if (sd.programmed_path.length >= 2) {
    scene.add(new Line(polylineGeometry(sd.programmed_path), new LineBasicMaterial({ color: 0x9aa0a6 })));
  }
  if (sd.executed_path.length >= 2) {
    const errs = sd.executed_error_mm;
    let scale = sd.error_scale_mm;
    if (!(scale > 0)) scale = Math.max(...errs.filter(Number.isFinite), 0) || 1;
    const tmp = [0, 0, 0];
    const geo = polylineGeometry(sd.executed_path, (i) => errorRgb(Number.isFinite(errs[i]) ? errs[i] / scale : 0, tmp));
    scene.add(new Line(geo, new LineBasicMaterial({ vertexColors: true })));
  }

  // ---- moving parts: struts (instanced cylinders), joints, platform polygon, tool
  const maxStruts = frames.struts.reduce((m, s) => Math.max(m, s.length), 0);
  let struts = null;
  let joints = null;
  let platform = null;
  if (maxStruts > 0) {
    struts = new InstancedMesh(new CylinderGeometry(rStrut, rStrut, 1, 10, 1), new MeshLambertMaterial({ color: 0xffffff }), maxStruts);
    struts.frustumCulled = false;
    struts.instanceMatrix.setUsage(DynamicDrawUsage);
    joints = new InstancedMesh(new SphereGeometry(rStrut * 1.9, 14, 10), new MeshLambertMaterial({ color: 0xffffff }), 2 * maxStruts);
    // Coloured per instance like the struts, so both share one shader program (faster first render).
    const jc = new Color(0x546e7a);
    for (let k = 0; k < 2 * maxStruts; k++) joints.setColorAt(k, jc);
    joints.frustumCulled = false;
    joints.instanceMatrix.setUsage(DynamicDrawUsage);
    platform = makePolygon(maxStruts, 0x1e4f8a, 0x5b8fd1, 0.28);
    scene.add(struts, joints, ...platform.objects);
  }
  const hasTool = frames.tool.some(isPoint);
  const toolBody = new Mesh(new CylinderGeometry(rStrut * 0.7, rStrut * 0.7, 1, 12, 1), new MeshLambertMaterial({ color: 0x455a64 }));
  const toolTip = new Mesh(new SphereGeometry(rStrut * 2.2, 16, 12), new MeshLambertMaterial({ color: 0xff6d00 }));
  toolBody.visible = toolTip.visible = false;
  scene.add(toolBody, toolTip);

  const m4 = new Matrix4();
  const q = new Quaternion();
  const Y = new Vector3(0, 1, 0);
  const a = new Vector3();
  const b = new Vector3();
  const d = new Vector3();
  const sc = new Vector3();
  const col = new Color();
  const neutral = new Color(NEUTRAL_STRUT);
  const rgb = [0, 0, 0];
  const zero = new Matrix4().makeScale(0, 0, 0);
  // What the strut colours show: 'limits' (closeness) or 'force' (only when every frame has drive forces).
  const forces = frames.drive_force;
  const forceScale = sd.drive_force_scale > 0 ? sd.drive_force_scale : 1;
  let coloring = 'limits';
  let current = 0;

  /** Places a unit cylinder (along y, centred) between a and b. */
  function segmentMatrix(pa, pb, out) {
    d.subVectors(pb, pa);
    const len = d.length();
    if (!(len > 0)) return out.copy(zero);
    q.setFromUnitVectors(Y, d.multiplyScalar(1 / len));
    return out.compose(a.addVectors(pa, pb).multiplyScalar(0.5), q, sc.set(1, len, 1));
  }

  function setFrame(i) {
    if (n === 0) return;
    const fs = frames.struts[i] || [];
    const cl = frames.strut_closeness[i] || [];
    const fr = coloring === 'force' && forces ? forces[i] || [] : null;
    current = i;
    let centroid = null;
    if (struts) {
      const ends = [];
      for (let k = 0; k < maxStruts; k++) {
        const s = fs[k];
        if (!Array.isArray(s) || !isPoint(s[0]) || !isPoint(s[1])) {
          struts.setMatrixAt(k, zero);
          joints.setMatrixAt(2 * k, zero);
          joints.setMatrixAt(2 * k + 1, zero);
          struts.setColorAt(k, neutral);
          continue;
        }
        const pa = vec(s[0], new Vector3());
        const pb = vec(s[1], new Vector3());
        ends.push(s[1]);
        // segmentMatrix clobbers `a`, so compute into a fresh matrix each time.
        struts.setMatrixAt(k, segmentMatrix(pa, pb, m4));
        joints.setMatrixAt(2 * k, m4.makeTranslation(pa.x, pa.y, pa.z));
        joints.setMatrixAt(2 * k + 1, m4.makeTranslation(pb.x, pb.y, pb.z));
        if (fr) {
          // Scaled to the run's peak |force|, so the colours compare across the whole animation.
          const f = fr[k];
          struts.setColorAt(k, Number.isFinite(f) ? srgbColor(forceRgb(f / forceScale, rgb), col) : neutral);
        } else {
          const c = cl[k];
          struts.setColorAt(k, Number.isFinite(c) ? srgbColor(closenessRgb(c, rgb), col) : neutral);
        }
      }
      struts.instanceMatrix.needsUpdate = true;
      joints.instanceMatrix.needsUpdate = true;
      if (struts.instanceColor) struts.instanceColor.needsUpdate = true;
      centroid = platform.set(ends);
    }
    const tp = frames.tool[i];
    if (hasTool && isPoint(tp)) {
      const tip = vec(tp, new Vector3());
      const ax = frames.tool_axis[i];
      const axis = isPoint(ax) ? vec(ax, new Vector3()).normalize() : new Vector3(0, 0, 1);
      if (!(axis.lengthSq() > 0)) axis.set(0, 0, 1);
      // The tool body reaches from the tip towards the platform (or a short way along the axis without one).
      let len = radius * 0.12;
      if (centroid) {
        const along = b.subVectors(centroid, tip).dot(axis);
        if (Math.abs(along) > radius * 0.02) {
          len = Math.min(Math.abs(along), radius * 0.6);
          if (along < 0) axis.negate();
        }
      }
      const top = new Vector3().copy(tip).addScaledVector(axis, len);
      segmentMatrix(tip, top, toolBody.matrix);
      toolBody.matrixAutoUpdate = false;
      toolBody.matrixWorldNeedsUpdate = true;
      toolTip.position.copy(tip);
      toolBody.visible = toolTip.visible = true;
    } else {
      toolBody.visible = toolTip.visible = false;
    }
  }

  // ---- camera, controls and views
  const controls = new OrbitControls(camera, canvas);
  controls.enableDamping = false;
  controls.screenSpacePanning = true;
  let dirty = true;
  let pending = 0;
  let rendered = false;
  const renderListeners = [];

  /** Looks at `pts` from direction dir, as close as the points allow (with a small margin). */
  function fit(pts, dir) {
    if (!pts.length) pts = machinePts;
    const fitBox = new Box3().setFromPoints(pts);
    const c = fitBox.getCenter(new Vector3());
    const r = Math.max(1e-3, fitBox.getSize(new Vector3()).length() / 2, radius * 1e-3);
    const back = dir.clone().normalize();
    // The camera's axes for this direction, as lookAt builds them with z up.
    const right = new Vector3().crossVectors(camera.up, back);
    if (right.lengthSq() < 1e-12) right.set(1, 0, 0);
    right.normalize();
    const upv = new Vector3().crossVectors(back, right).normalize();
    const tv = Math.tan((camera.fov * Math.PI) / 360);
    const th = tv * camera.aspect;
    // Centre the view on the points' projected extent, then find the nearest distance that shows them all.
    let x0 = Infinity, x1 = -Infinity, y0 = Infinity, y1 = -Infinity;
    const p = new Vector3();
    for (const q of pts) {
      p.subVectors(q, c);
      const x = p.dot(right);
      const y = p.dot(upv);
      x0 = Math.min(x0, x); x1 = Math.max(x1, x);
      y0 = Math.min(y0, y); y1 = Math.max(y1, y);
    }
    c.addScaledVector(right, (x0 + x1) / 2).addScaledVector(upv, (y0 + y1) / 2);
    let dist = 0;
    for (const q of pts) {
      p.subVectors(q, c);
      const z = p.dot(back);
      dist = Math.max(dist, z + Math.abs(p.dot(right)) / th, z + Math.abs(p.dot(upv)) / tv);
    }
    dist = Math.max(dist * 1.08, r * 0.2);
    camera.position.copy(c).addScaledVector(back, dist);
    camera.near = Math.max(dist - r * 4, dist / 1000, 1e-3);
    camera.far = dist + r * 8 + radius * 4;
    camera.updateProjectionMatrix();
    controls.target.copy(c);
    controls.update();
    invalidate();
  }

  const VIEWS = {
    iso: () => fit(machinePts, planar ? new Vector3(0.15, -0.55, 1) : new Vector3(1, -1.55, 0.85)),
    top: () => fit(machinePts, new Vector3(0, -1e-3, 1)),
    front: () => fit(machinePts, planar ? new Vector3(0, -1, 0.35) : new Vector3(0, -1, 0.08)),
    path: () => fit(pathPts, planar ? new Vector3(0.15, -0.55, 1) : new Vector3(1, -1.3, 1.1)),
  };
  let view = 'iso';

  function resize() {
    const w = Math.max(1, container.clientWidth);
    const h = Math.max(1, container.clientHeight);
    const cur = renderer.getSize(new Vector3());
    if (cur.x === w && cur.y === h) return false;
    renderer.setSize(w, h, false);
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
    return true;
  }

  function render() {
    if (pending) cancelAnimationFrame(pending);
    pending = 0;
    dirty = false;
    if (toolTip.visible) {
      // The tip marker keeps a modest size on screen when zoomed in on the path.
      const dist = camera.position.distanceTo(toolTip.position);
      toolTip.scale.setScalar(Math.min(1, (dist * 0.011) / (rStrut * 2.2)));
    }
    renderer.render(scene, camera);
    if (!rendered) {
      rendered = true;
      renderListeners.forEach((f) => f());
    }
  }

  function invalidate() {
    dirty = true;
    if (!pending) pending = requestAnimationFrame(() => {
      pending = 0;
      if (dirty) render();
    });
  }

  controls.addEventListener('change', invalidate);
  let userMoved = false; // once the user has orbited, a resize keeps their view
  controls.addEventListener('start', () => (userMoved = true));
  resize();
  VIEWS.iso();
  if (n > 0) setFrame(0);
  const ro = new ResizeObserver(() => {
    if (resize()) {
      if (!userMoved) VIEWS[view]();
      render();
    }
  });
  ro.observe(container);

  // The clear colour as it ends up in the canvas (sRGB bytes).
  const bgRgb = [1, 3, 5].map((k) => parseInt(BACKGROUND.slice(k, k + 2), 16));

  return {
    planar,
    setFrame(i) {
      setFrame(i);
      invalidate();
    },
    render,
    invalidate,
    /** 'limits' or 'force' (force only where the run has drive forces); recolours the current frame. */
    setStrutColoring(mode) {
      const next = mode === 'force' && forces ? 'force' : 'limits';
      if (next === coloring) return coloring;
      coloring = next;
      setFrame(current);
      invalidate();
      return coloring;
    },
    strutColoring: () => coloring,
    /** The struts' colours now, as '#rrggbb' in sRGB (for tests). */
    strutColors() {
      if (!struts) return [];
      const out = [];
      for (let k = 0; k < maxStruts; k++) {
        struts.getColorAt(k, col);
        out.push(`#${col.getHexString()}`);
      }
      return out;
    },
    setView(name) {
      if (!VIEWS[name]) return;
      view = name;
      userMoved = false;
      VIEWS[name]();
    },
    onFirstRender(f) {
      if (rendered) f();
      else renderListeners.push(f);
    },
    get rendered() {
      return rendered;
    },
    /** True when the drawn image has pixels that differ from the background (reads the WebGL canvas). */
    hasPixels() {
      if (dirty) render();
      // Copy through a 2-D canvas: gl.readPixels would make Chromium warn about a GPU stall.
      const w = canvas.width;
      const h = canvas.height;
      if (!w || !h) return false;
      const c2 = document.createElement('canvas');
      c2.width = w;
      c2.height = h;
      const ctx = c2.getContext('2d', { willReadFrequently: true });
      ctx.drawImage(canvas, 0, 0);
      const buf = ctx.getImageData(0, 0, w, h).data;
      let differ = 0;
      for (let k = 0; k < buf.length; k += 4) {
        if (Math.abs(buf[k] - bgRgb[0]) > 6 || Math.abs(buf[k + 1] - bgRgb[1]) > 6 || Math.abs(buf[k + 2] - bgRgb[2]) > 6) {
          if (++differ > 50) return true;
        }
      }
      return false;
    },
  };
}
