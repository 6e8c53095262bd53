// Reads the report's JSON (docs/report-data.md) from the page and fills in what is optional, so the rest of the
// page can rely on every field being there with the right type.

const arr = (v) => (Array.isArray(v) ? v : []);
const obj = (v) => (v && typeof v === 'object' && !Array.isArray(v) ? v : {});

/** The Bode data (`frequency_response`), or null when absent or malformed. */
function normalizeResponse(raw) {
  const r = obj(raw);
  const f = arr(r.frequency_Hz).map(Number);
  if (!f.length) return null;
  const entries = arr(r.entries)
    .map(obj)
    .map((e, k) => ({ name: String(e.name ?? `entry ${k + 1}`), magnitude_um_N: arr(e.magnitude_um_N), phase_deg: arr(e.phase_deg) }))
    .filter((e) => e.magnitude_um_N.length === f.length && e.phase_deg.length === f.length);
  return entries.length ? { file: String(r.file ?? ''), frequency_Hz: f, entries } : null;
}

/** The stiffness map (`stiffness_map`), or null when absent or malformed; null cells become NaN. */
function normalizeMap(raw) {
  const m = obj(raw);
  const x = arr(m.x).map(Number);
  const y = arr(m.y).map(Number);
  const values = arr(m.values).map(arr);
  if (!x.length || !y.length || values.length !== y.length || values.some((row) => row.length !== x.length)) return null;
  return {
    file: String(m.file ?? ''),
    x_label: String(m.x_label ?? 'x'),
    y_label: String(m.y_label ?? 'y'),
    value_label: String(m.value_label ?? ''),
    value_unit: String(m.value_unit ?? ''),
    x,
    y,
    values: values.map((row) => row.map((v) => (v == null ? NaN : Number(v)))),
  };
}

/** The workspace map (`workspace_map`, docs/workspace.md), or null when absent or malformed; null cells become NaN. */
function normalizeWorkspace(raw) {
  const m = obj(raw);
  const x = arr(m.x).map(Number);
  const y = arr(m.y).map(Number);
  const slices = arr(m.slices).map(Number);
  const depth = slices.length || 1;
  const fits = (values) =>
    values.length === depth && values.every((s) => arr(s).length === y.length && arr(s).every((row) => arr(row).length === x.length));
  const layers = arr(m.layers)
    .map(obj)
    .filter((l) => fits(arr(l.values)))
    .map((l) => ({
      id: String(l.id ?? ''),
      label: String(l.label ?? l.id ?? ''),
      unit: String(l.unit ?? ''),
      categorical: !!l.categorical,
      hot: l.hot === 'low' ? 'low' : 'high',
      values: arr(l.values).map((s) => arr(s).map((row) => arr(row).map((v) => (v == null ? NaN : Number(v))))),
    }));
  if (!x.length || !y.length || !layers.length) return null;
  return {
    file: String(m.file ?? ''),
    x_label: String(m.x_label ?? 'x'),
    y_label: String(m.y_label ?? 'y'),
    slice_label: String(m.slice_label ?? ''),
    x,
    y,
    slices,
    status_names: arr(m.status_names).map(String),
    layers,
  };
}

export function readData(doc = document) {
  const el = doc.getElementById('pkm-report-data');
  if (!el) throw new Error('no report data in this page (script#pkm-report-data is missing)');
  return normalize(JSON.parse(el.textContent || '{}'));
}

export function normalize(raw) {
  const d = obj(raw);
  const machine = obj(d.machine);
  const program = obj(d.program);
  const scene = obj(d.scene);
  const frames = obj(scene.frames);
  const time = arr(frames.time_s).map(Number);
  const n = time.length;
  const perFrame = (v, fill) => {
    const a = arr(v);
    return a.length >= n ? a : a.concat(Array.from({ length: n - a.length }, () => fill));
  };
  const charts = arr(d.charts)
    .map((c, i) => {
      c = obj(c);
      const x = obj(c.x);
      const t = arr(x.time_s);
      const s = Array.isArray(x.s_mm) && x.s_mm.length === t.length && t.length > 0 ? x.s_mm : null;
      return {
        id: String(c.id ?? `chart${i}`),
        title: String(c.title ?? c.id ?? `Chart ${i + 1}`),
        y_label: c.y_label == null ? '' : String(c.y_label),
        y_unit: c.y_unit == null ? '' : String(c.y_unit),
        x: { time_s: t, s_mm: s },
        series: arr(c.series)
          .map((sr, k) => ({
            name: String(obj(sr).name ?? `series ${k + 1}`),
            values: arr(obj(sr).values),
            dash: !!obj(sr).dash,
          }))
          .filter((sr) => sr.values.length === t.length),
        limits: arr(c.limits)
          .map(obj)
          .filter((l) => Number.isFinite(l.value))
          .map((l) => ({ label: String(l.label ?? l.value), value: l.value })),
      };
    })
    .filter((c) => c.x.time_s.length > 0);
  return {
    format: d.format,
    kind: d.kind ?? '',
    title: String(d.title ?? 'pkm report'),
    generated_by: d.generated_by ?? '',
    machine: {
      file: machine.file ?? '',
      name: machine.name ?? '',
      type: machine.type ?? '',
      actuator_unit: machine.actuator_unit ?? '',
      actuator_names: arr(machine.actuator_names),
      limits: obj(machine.limits),
    },
    program: { file: program.file ?? '', lines: obj(program.lines), subroutine_lines: obj(program.subroutine_lines) },
    table: arr(d.table).map(obj),
    limits_reached: arr(d.limits_reached).map(obj),
    warnings: arr(d.warnings).map(obj),
    summary: d.summary,
    charts,
    frequency_response: normalizeResponse(d.frequency_response),
    stiffness_map: normalizeMap(d.stiffness_map),
    workspace_map: normalizeWorkspace(d.workspace_map),
    calibration: d.calibration ?? null,
    servo: d.servo ?? null,
    scene: {
      base_polygon: arr(scene.base_polygon),
      programmed_path: arr(scene.programmed_path),
      executed_path: arr(scene.executed_path),
      executed_error_mm: arr(scene.executed_error_mm),
      error_scale_mm: Number(scene.error_scale_mm) > 0 ? Number(scene.error_scale_mm) : 0,
      // Drive forces per frame (plans with --dynamics): only when every frame has them, so that the page
      // either offers force colouring throughout or not at all.
      drive_force_scale: Number(scene.drive_force_scale) > 0 ? Number(scene.drive_force_scale) : 0,
      drive_force_unit: String(scene.drive_force_unit ?? 'N'),
      frames: {
        count: n,
        // "time" (a run: the frames are moments) or "pose" (calibration: measured poses, a slide show).
        axis: frames.axis === 'pose' ? 'pose' : 'time',
        time_s: time,
        line: perFrame(frames.line, 0).map((v) => Number(v) || 0),
        tool: perFrame(frames.tool, null),
        tool_axis: perFrame(frames.tool_axis, null),
        struts: perFrame(frames.struts, []).map(arr),
        strut_closeness: perFrame(frames.strut_closeness, []).map(arr),
        drive_force: n > 0 && arr(frames.drive_force).length === n ? arr(frames.drive_force).map(arr) : null,
      },
    },
  };
}

/** Source text of a program line ("" when unknown). */
export function lineText(data, line) {
  const t = data.program.lines[String(line)];
  return t == null ? '' : String(t).trim();
}

/** Where the moves a program line executes were written, when elsewhere (a subroutine call): "file:line"s. */
export function lineCalls(data, line) {
  return arr(data.program.subroutine_lines[String(line)]).map(String);
}

/** "line 12: o<drill_hole> call [0] → drill_hole.ngc:2, drill_hole.ngc:3", as much as is known. */
export function lineDescription(data, line) {
  const src = lineText(data, line);
  const calls = lineCalls(data, line);
  let text = src ? `line ${line}: ${src}` : `line ${line}`;
  if (calls.length) text += ` \u2192 ${calls.join(', ')}`;
  return text;
}
