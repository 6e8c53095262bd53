// Synthetic report data for developing the page: the ch5 test hexapod (base joints on a 400 mm circle at z 0,
// platform joints merged in pairs on a 200 mm circle, tool point 150 mm above the platform) milling a
// pocket around z 700. Follows docs/report-data.md. Deterministic (seeded noise).
//
//   import { makeSampleData } from './sample-data.mjs';
//   makeSampleData({ chartPoints: 4000, frames: 600, variant: 'hexapod' | 'planar' | 'minimal' })

const PROGRAM = `(pocket.ngc - a rectangular pocket 60 x 40 mm, 6 mm deep, wall corner radius 8 mm)
G21 G90 G17 G94        (mm, absolute coordinates, XY plane, feed per minute)
G0 Z10                 (safe height first)
G0 X-10 Y0             (above the start of the ramp)
M3 S10000              (spindle on, clockwise)
G0 Z1
(--- level 1: Z-3, counter-clockwise ---)
G1 X10 Z-3 F600        (ramp)
G1 X-10 F1000          (centre slot)
G1 X0 Y-9              (onto the roughing contour)
G1 X16 Y-9
G3 X19 Y-6 I0 J3
G1 Y6
G3 X16 Y9 I-3 J0
G1 X-16
G3 X-19 Y6 I0 J-3
G1 Y-6
G3 X-16 Y-9 I3 J0
G1 X0
G1 Y-15 F800           (onto the finishing contour)
G1 X22
G3 X25 Y-12 I0 J3
G1 Y12
G3 X22 Y15 I-3 J0
G1 X-22
G3 X-25 Y12 I0 J-3
G1 Y-12
G3 X-22 Y-15 I3 J0
G1 X0
(--- level 2: Z-6, clockwise ---)
G1 X-10 Y0 F1000
G1 X10 Z-6 F600
G1 X-10 F1000
G1 X0 Y-9
G1 X-16
G2 X-19 Y-6 I0 J3
G1 Y6
G2 X-16 Y9 I3 J0
G1 X16
G2 X19 Y6 I0 J-3
G1 Y-6
G2 X16 Y-9 I-3 J0
G1 X0
G1 Y-15 F800
G1 X-22
G2 X-25 Y-12 I0 J3
G1 Y12
G2 X-22 Y15 I3 J0
G1 X22
G2 X25 Y12 I0 J-3
G1 Y-12
G2 X22 Y-15 I-3 J0
G1 X0
G1 Y-12                (leave the wall before lifting)
G0 Z10                 (retract)
M5                     (spindle off)
G0 X0 Y0
M2                     (end of program)`;

function rng(seed) {
  let s = seed >>> 0;
  return () => {
    s = (s * 1664525 + 1013904223) >>> 0;
    return s / 4294967296;
  };
}

const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const add = (a, b) => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
const mul = (a, k) => [a[0] * k, a[1] * k, a[2] * k];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const norm = (a) => Math.hypot(a[0], a[1], a[2]);
const r3 = (v) => Math.round(v * 1000) / 1000;
const r3v = (p) => [r3(p[0]), r3(p[1]), r3(p[2])];

/** Parses the little G-code subset above into motion segments ({line, rapid, feed, points[]}). */
function parseProgram(text) {
  const lines = text.split('\n');
  const segs = [];
  const src = {};
  let pos = [0, 0, 10];
  let feed = 600;
  let mode = 0;
  lines.forEach((raw, k) => {
    const n = k + 1;
    src[n] = raw.trimEnd();
    const code = raw.replace(/\(.*?\)/g, '').trim().toUpperCase();
    if (!code) return;
    const words = {};
    for (const m of code.matchAll(/([A-Z])(-?[\d.]+)/g)) {
      const v = parseFloat(m[2]);
      if (m[1] === 'G' && [0, 1, 2, 3].includes(v)) mode = v;
      else words[m[1]] = v;
    }
    if (words.F) feed = words.F;
    if (!('X' in words || 'Y' in words || 'Z' in words)) return;
    const to = [words.X ?? pos[0], words.Y ?? pos[1], words.Z ?? pos[2]];
    const pts = [pos];
    if (mode === 2 || mode === 3) {
      const c = [pos[0] + (words.I ?? 0), pos[1] + (words.J ?? 0)];
      const r = Math.hypot(pos[0] - c[0], pos[1] - c[1]);
      let a0 = Math.atan2(pos[1] - c[1], pos[0] - c[0]);
      let a1 = Math.atan2(to[1] - c[1], to[0] - c[0]);
      if (mode === 3 && a1 <= a0) a1 += 2 * Math.PI;
      if (mode === 2 && a1 >= a0) a1 -= 2 * Math.PI;
      const steps = Math.max(4, Math.ceil(Math.abs(a1 - a0) / (Math.PI / 36)));
      for (let i = 1; i <= steps; i++) {
        const a = a0 + ((a1 - a0) * i) / steps;
        pts.push([c[0] + r * Math.cos(a), c[1] + r * Math.sin(a), pos[2] + ((to[2] - pos[2]) * i) / steps]);
      }
      pts[pts.length - 1] = to;
    } else {
      pts.push(to);
    }
    for (let i = 1; i < pts.length; i++) {
      const L = norm(sub(pts[i], pts[i - 1]));
      if (L > 1e-9) segs.push({ line: n, rapid: mode === 0, feed: mode === 0 ? 6000 : feed, a: pts[i - 1], b: pts[i], len: L });
    }
    pos = to;
  });
  return { segs, src };
}

/** Junction-speed planner with constant acceleration; returns a dense time sampling of the tool path. */
function plan(segs, accel, dt) {
  const n = segs.length;
  const vmax = segs.map((s) => s.feed / 60);
  const dir = segs.map((s) => mul(sub(s.b, s.a), 1 / s.len));
  const vj = new Array(n + 1).fill(0);
  for (let i = 1; i < n; i++) {
    const c = dot(dir[i - 1], dir[i]);
    const same = segs[i - 1].rapid === segs[i].rapid;
    vj[i] = same && c > 0.5 ? Math.min(vmax[i - 1], vmax[i]) * Math.pow(c, 6) : 0;
  }
  for (let i = 0; i < n; i++) vj[i + 1] = Math.min(vj[i + 1], Math.sqrt(vj[i] ** 2 + 2 * accel * segs[i].len));
  for (let i = n - 1; i >= 0; i--) vj[i] = Math.min(vj[i], Math.sqrt(vj[i + 1] ** 2 + 2 * accel * segs[i].len));
  // Per segment trapezoid (v0 -> vp -> v1).
  const prof = segs.map((s, i) => {
    const v0 = vj[i], v1 = vj[i + 1];
    let vp = Math.min(vmax[i], Math.sqrt((2 * accel * s.len + v0 * v0 + v1 * v1) / 2));
    const ta = (vp - v0) / accel, tc0 = (vp - v1) / accel;
    const da = (vp * vp - v0 * v0) / (2 * accel), dd = (vp * vp - v1 * v1) / (2 * accel);
    const tcr = Math.max(0, (s.len - da - dd) / vp);
    return { v0, v1, vp, ta, td: tc0, tc: tcr, da, T: ta + tcr + tc0 };
  });
  const samples = [];
  let t0 = 0;
  let t = 0;
  for (let i = 0; i < n; i++) {
    const p = prof[i], s = segs[i];
    while (t <= t0 + p.T) {
      const u = t - t0;
      let d, v;
      if (u < p.ta) { v = p.v0 + accel * u; d = p.v0 * u + 0.5 * accel * u * u; }
      else if (u < p.ta + p.tc) { v = p.vp; d = p.da + p.vp * (u - p.ta); }
      else { const w = u - p.ta - p.tc; v = p.vp - accel * w; d = p.da + p.vp * p.tc + p.vp * w - 0.5 * accel * w * w; }
      d = Math.min(s.len, Math.max(0, d));
      samples.push({ t, line: s.line, rapid: s.rapid, feed: s.feed / 60, v, pos: add(s.a, mul(dir[i], d)) });
      t += dt;
    }
    t0 += p.T;
  }
  return samples;
}

/** Gaussian elimination for a small dense system (A x = b). */
function solve(A, b) {
  const n = b.length;
  const M = A.map((row, i) => [...row, b[i]]);
  for (let c = 0; c < n; c++) {
    let p = c;
    for (let r = c + 1; r < n; r++) if (Math.abs(M[r][c]) > Math.abs(M[p][c])) p = r;
    [M[c], M[p]] = [M[p], M[c]];
    for (let r = c + 1; r < n; r++) {
      const f = M[r][c] / M[c][c];
      for (let k = c; k <= n; k++) M[r][k] -= f * M[c][k];
    }
  }
  const x = new Array(n).fill(0);
  for (let r = n - 1; r >= 0; r--) {
    let s = M[r][n];
    for (let k = r + 1; k < n; k++) s -= M[r][k] * x[k];
    x[r] = s / M[r][r];
  }
  return x;
}

function machineFor(variant) {
  if (variant === 'planar') {
    const base = [[300, 0, 0], [-150, 259.8, 0], [-150, -259.8, 0]];
    const plat = [[60, 0, 0], [-30, 52, 0], [-30, -52, 0]];
    return { name: '3-RPR planar test machine', type: 'planar3', file: 'examples/machines/planar3.yaml', base, plat, toolOffset: [0, 0, 0], origin: [0, 0, 0], planar: true, qmin: 150, qmax: 420 };
  }
  const base = [0, 60, 120, 180, 240, 300].map((d) => [400 * Math.cos((d * Math.PI) / 180), 400 * Math.sin((d * Math.PI) / 180), 0]);
  const pj = [30, 30, 150, 150, 270, 270].map((d) => [200 * Math.cos((d * Math.PI) / 180), 200 * Math.sin((d * Math.PI) / 180), 0]);
  return { name: 'ch5 test hexapod', type: 'hexapod', file: 'examples/machines/hexapod_ch5.yaml', base, plat: pj, toolOffset: [0, 0, 150], origin: [0, 0, 700], planar: false, qmin: 350, qmax: 900 };
}

export function makeSampleData({ chartPoints = 4000, frames: frameCount = 600, variant = 'hexapod' } = {}) {
  const rand = rng(42);
  const M = machineFor(variant);
  const { segs, src } = parseProgram(PROGRAM);
  if (M.planar) for (const s of segs) { s.a = [s.a[0] * 2, s.a[1] * 2, 0]; s.b = [s.b[0] * 2, s.b[1] * 2, 0]; s.len = norm(sub(s.b, s.a)); }
  const live = segs.filter((s) => s.len > 1e-9);
  const dt = 0.002;
  const S = plan(live, 1000, dt);
  const n = S.length;
  const ns = M.base.length;
  const vlim = 100, alim = 2000;
  // Kinematics along the dense sampling.
  const q = [], tool = [], sPath = [], err = [];
  let sAcc = 0;
  for (let k = 0; k < n; k++) {
    const tp = add(S[k].pos, M.origin);
    // A small programmed tilt so the platform visibly moves in orientation (hexapod only).
    tool.push(tp);
    if (k > 0) sAcc += norm(sub(tp, tool[k - 1]));
    sPath.push(sAcc);
    const P = sub(tp, M.toolOffset);
    q.push(M.base.map((b, i) => norm(sub(add(P, M.plat[i]), b))));
  }
  const qd = q.map((row, k) => row.map((v, i) => (q[Math.min(n - 1, k + 1)][i] - q[Math.max(0, k - 1)][i]) / (dt * (k === 0 || k === n - 1 ? 1 : 2))));
  const qdd = qd.map((row, k) => row.map((v, i) => (qd[Math.min(n - 1, k + 1)][i] - qd[Math.max(0, k - 1)][i]) / (dt * (k === 0 || k === n - 1 ? 1 : 2))));
  // Statics: platform + spindle 40 kg, strut forces from J^T f = w (hexapod); simple projection (planar).
  const mass = 40;
  const forces = [];
  const energy = [];
  let eAcc = 0;
  for (let k = 0; k < n; k++) {
    const P = sub(tool[k], M.toolOffset);
    const a = k > 0 && k < n - 1 ? mul(sub(add(tool[k + 1], tool[k - 1]), mul(tool[k], 2)), 1 / (dt * dt * 1000)) : [0, 0, 0];
    const w = [mass * a[0], mass * a[1], mass * (a[2] + 9.81)];
    let f;
    if (!M.planar) {
      const cols = M.base.map((b, i) => {
        const u = sub(add(P, M.plat[i]), b);
        const un = mul(u, 1 / norm(u));
        return [...un, ...mul(cross(M.plat[i], un), 0.001)];
      });
      const A = [0, 1, 2, 3, 4, 5].map((r) => cols.map((c) => c[r]));
      f = solve(A, [...w, 0, 0, 0]);
    } else {
      f = M.base.map((b, i) => { const u = sub(add(P, M.plat[i]), b); return (mass * dot(a, u)) / norm(u) / 3 + 5 * Math.sin(k * 0.001 + i); });
    }
    forces.push(f);
    if (k > 0) eAcc += f.reduce((acc, fi, i) => acc + Math.abs(fi * qd[k][i] * 0.001) * dt, 0);
    energy.push(eAcc);
    const acc = norm(a) * 1000;
    err.push(S[k].rapid ? null : 1.2e-3 * Math.min(1, acc / 1000) + 2.5e-4 * (S[k].v / 16) + 5e-5 * rand());
  }
  // Decimation indices: min and max of q1 per bucket (two per bucket), in time order.
  const buckets = Math.max(1, Math.floor(chartPoints / 2));
  const idx = [];
  for (let b = 0; b < buckets; b++) {
    const lo = Math.floor((b * n) / buckets), hi = Math.max(lo + 1, Math.floor(((b + 1) * n) / buckets));
    let imin = lo, imax = lo;
    for (let k = lo; k < hi; k++) { if (qd[k][0] < qd[imin][0]) imin = k; if (qd[k][0] > qd[imax][0]) imax = k; }
    if (imin === imax) idx.push(imin, Math.min(hi - 1, imin + 1));
    else idx.push(Math.min(imin, imax), Math.max(imin, imax));
  }
  const pick = (f) => idx.map(f);
  const time = pick((k) => r3(S[k].t * 1000) / 1000);
  const sx = pick((k) => r3(sPath[k]));
  const names = M.base.map((_, i) => `q${i + 1}`);
  // Series named as pkm names them: the quantity per drive (q, v, a, F) with the chart's unit.
  const qSeries = (arr, symbol, unit, digits = 4) => names.map((nm, i) => ({ name: `${symbol}${i + 1} [${unit}]`, values: pick((k) => Number(arr[k][i].toFixed(digits))) }));
  const charts = [
    { id: 'actuator_positions', title: 'Actuator positions', y_label: 'position', y_unit: 'mm', x: { time_s: time }, series: qSeries(q, 'q', 'mm'), limits: [{ label: `max ${M.qmax} mm`, value: M.qmax }, { label: `min ${M.qmin} mm`, value: M.qmin }] },
    { id: 'actuator_speeds', title: 'Actuator speeds', y_label: 'speed', y_unit: 'mm/s', x: { time_s: time }, series: qSeries(qd, 'v', 'mm/s', 3), limits: [{ label: `max ${vlim} mm/s`, value: vlim }, { label: `min -${vlim} mm/s`, value: -vlim }] },
    { id: 'actuator_accels', title: 'Actuator accelerations', y_label: 'acceleration', y_unit: 'mm/s²', x: { time_s: time }, series: qSeries(qdd, 'a', 'mm/s²', 1), limits: [{ label: `max ${alim} mm/s²`, value: alim }, { label: `min -${alim} mm/s²`, value: -alim }] },
    { id: 'path_speed', title: 'Path speed', y_label: 'speed', y_unit: 'mm/s', x: { time_s: time, s_mm: sx }, series: [
      { name: 'path speed [mm/s]', values: pick((k) => r3(S[k].v)) },
      { name: 'programmed feed [mm/s]', values: pick((k) => r3(S[k].feed)), dash: true },
    ] },
    { id: 'contour_error', title: 'Contour error', y_label: 'error', y_unit: 'mm', x: { time_s: time, s_mm: sx }, series: [{ name: 'contour error [mm]', values: pick((k) => (err[k] == null ? null : Number(err[k].toPrecision(4)))) }], limits: [{ label: 'tolerance 0.01 mm', value: 0.01 }] },
    { id: 'strut_forces', title: 'Strut forces', y_label: 'force', y_unit: 'N', x: { time_s: time }, series: qSeries(forces, 'F', 'N', 2) },
    { id: 'energy', title: 'Energy', y_label: 'energy', y_unit: 'J', x: { time_s: time, s_mm: sx }, series: [{ name: 'actuator work [J]', values: pick((k) => Number(energy[k].toFixed(4))) }] },
  ];
  // Frames: uniformly in time.
  const T = S[n - 1].t;
  const fr = { time_s: [], line: [], tool: [], tool_axis: [], struts: [], strut_closeness: [] };
  for (let j = 0; j < frameCount; j++) {
    const k = Math.min(n - 1, Math.round(((j / (frameCount - 1)) * T) / dt));
    const P = sub(tool[k], M.toolOffset);
    fr.time_s.push(r3(S[k].t * 1000) / 1000);
    fr.line.push(S[k].line);
    fr.tool.push(r3v(tool[k]));
    fr.tool_axis.push([0, 0, 1]);
    fr.struts.push(M.base.map((b, i) => [r3v(b), r3v(add(P, M.plat[i]))]));
    const mid = (M.qmin + M.qmax) / 2, half = (M.qmax - M.qmin) / 2;
    fr.strut_closeness.push(q[k].map((qi, i) => {
      const c = Math.max(Math.abs(qi - mid) / half, Math.abs(qd[k][i]) / vlim, Math.abs(qdd[k][i]) / alim);
      return Math.round(Math.min(1, c) * 1000) / 1000;
    }));
  }
  // Executed path: the tool path with the (tiny) contour error applied sideways.
  const exe = [], exeErr = [];
  const ePts = Math.min(2000, n);
  for (let j = 0; j < ePts; j++) {
    const k = Math.round((j / (ePts - 1)) * (n - 1));
    const d = k > 0 ? sub(tool[k], tool[k - 1]) : [1, 0, 0];
    const side = cross(d, [0, 0, 1]);
    const sn = norm(side) || 1;
    const e = err[k] ?? 0;
    exe.push(r3v(add(tool[k], mul(side, e / sn))));
    exeErr.push(Number(e.toPrecision(3)));
  }
  const prog = [];
  for (const s of live) { if (!prog.length) prog.push(r3v(add(s.a, M.origin))); prog.push(r3v(add(s.b, M.origin))); }
  // Peaks for the table and the limits entry.
  let vmaxAbs = 0, vk = 0, vi = 0, amaxAbs = 0, ak = 0, emax = 0, ek = 0;
  for (let k = 0; k < n; k++) {
    for (let i = 0; i < ns; i++) {
      if (Math.abs(qd[k][i]) > vmaxAbs) { vmaxAbs = Math.abs(qd[k][i]); vk = k; vi = i; }
      if (Math.abs(qdd[k][i]) > amaxAbs) { amaxAbs = Math.abs(qdd[k][i]); ak = k; }
    }
    if (err[k] != null && err[k] > emax) { emax = err[k]; ek = k; }
  }
  let qLo = Infinity, qHi = -Infinity;
  for (const row of q) for (const v of row) { if (v < qLo) qLo = v; if (v > qHi) qHi = v; }
  const usedLines = new Set(fr.line);
  for (const s of live) usedLines.add(s.line);
  const lines = {};
  for (const l of [...usedLines].sort((a, b) => a - b)) if (l > 0) lines[String(l)] = src[l];
  const progFile = M.planar ? 'examples/programs/planar_circle.ngc' : 'examples/programs/pocket.ngc';
  const summary = {
    command: 'plan', machine: M.file, program: progFile, duration_s: Number(T.toFixed(3)), path_length_mm: Number(sAcc.toFixed(3)),
    max_actuator_speed_mm_s: Number(vmaxAbs.toFixed(3)), max_actuator_accel_mm_s2: Number(amaxAbs.toFixed(1)), max_contour_error_mm: Number(emax.toPrecision(3)),
    segments: live.length, samples: n, limits: { min: M.qmin, max: M.qmax, speed: vlim, accel: alim }, ok: true,
  };
  return {
    format: 'pkm-report-1',
    kind: 'plan',
    title: `${progFile.split('/').pop()} on ${M.name}`,
    generated_by: 'pkm 0.1 (sample data)',
    machine: { file: M.file, name: M.name, type: M.type, actuator_unit: 'mm', actuator_names: names, limits: { min: M.qmin, max: M.qmax, speed: vlim, accel: alim } },
    program: { file: progFile, lines },
    table: [
      { label: 'Duration', value: `${T.toFixed(2)} s` },
      { label: 'Path length', value: `${sAcc.toFixed(1)} mm` },
      { label: 'Program lines', value: `${Object.keys(lines).length} with motion` },
      { label: 'Max path error', value: `${emax.toPrecision(2)} mm`, line: S[ek].line },
      { label: 'Max actuator speed', value: `${vmaxAbs.toFixed(1)} mm/s (q${vi + 1})`, line: S[vk].line },
      { label: 'Max actuator accel', value: `${amaxAbs.toFixed(0)} mm/s²`, line: S[ak].line },
      { label: 'Actuator range used', value: `${qLo.toFixed(1)} … ${qHi.toFixed(1)} mm` },
      { label: 'Machine file', value: M.file },
      { label: 'Program file', value: progFile },
    ],
    limits_reached: [
      { what: `actuator ${vi + 1} speed ${vmaxAbs.toFixed(1)} mm/s (limit ${vlim} mm/s)`, line: S[vk].line, time_s: Number(S[vk].t.toFixed(3)), severity: vmaxAbs > vlim ? 'exceeded' : 'reached' },
    ],
    summary,
    charts,
    scene: {
      base_polygon: M.base.map(r3v),
      programmed_path: prog,
      executed_path: exe,
      executed_error_mm: exeErr,
      error_scale_mm: 0.002,
      frames: fr,
    },
  };
}

/** A degenerate report: no struts, no base, one chart without s_mm, few frames (robustness check). */
export function makeMinimalData() {
  const d = makeSampleData({ chartPoints: 200, frames: 20 });
  d.scene.base_polygon = [];
  d.scene.frames.struts = d.scene.frames.struts.map(() => []);
  d.scene.frames.strut_closeness = d.scene.frames.strut_closeness.map(() => []);
  d.charts = d.charts.slice(3, 4);
  d.limits_reached = [];
  return d;
}
