// What makes every report page readable, checked on each page of report_browser_test.mjs:
//   - every plot has a colour key: its legend lists exactly its series, by name, each with a swatch in the
//     colour of its curve, and no swatch is grey; the time plots' series are the data's, named by quantity
//     with the chart's unit ("P1 [N]");
//   - every axis and every colour bar has a unit in brackets;
//   - maps are drawn to scale (the plot's width over height is the grid's x extent over its y extent, within
//     2 %) and the cells where the machine cannot stand, or that have no value, are masked;
//   - the transport bar (Play, scrub) is there only with frames to animate, the x-axis switch only with plots
//     over path length;
//   - the verdict is the worst of the limits and warnings: amber with a warning, never a green "No limit
//     reached" beside one;
//   - no large blank area: no empty section, the summary and the 3-D view one height, every row of plots as
//     wide as its grid, a map's card no wider than the map and its side column.
import { readFileSync } from 'node:fs';
import { join } from 'node:path';

const UNIT = /\[[^\]]+\]/;
const LEVELS = ['ok', 'warning', 'reached', 'exceeded'];

/** A colour is grey (or black/white) when its channels hardly differ. */
function isGrey(hex) {
  if (!/^#[0-9a-f]{6}$/i.test(hex)) return true;
  const c = [1, 3, 5].map((k) => parseInt(hex.slice(k, k + 2), 16));
  return Math.max(...c) - Math.min(...c) < 40;
}

/** Legends, swatches, series names and axis units of every plot. */
export async function checkPlots(page, data, fail) {
  const plots = await page.evaluate(() => window.pkmReport.plots());
  for (const chart of data.charts) {
    const plot = plots.find((p) => p.id === `chart-${chart.id}`);
    if (!plot) { fail(`no plot for chart ${chart.id}`); continue; }
    const names = chart.series.map((s) => s.name);
    if (JSON.stringify(plot.series.map((s) => s.name)) !== JSON.stringify(names))
      fail(`${chart.id}: the plot draws ${JSON.stringify(plot.series.map((s) => s.name))}, the data has ${JSON.stringify(names)}`);
    for (const name of names) {
      if (chart.y_unit && !name.endsWith(`[${chart.y_unit}]`)) fail(`${chart.id}: series "${name}" is not named with the unit [${chart.y_unit}]`);
      if (/^q\d+( \[|$)/.test(name) && chart.id !== 'actuator_positions') fail(`${chart.id}: series "${name}" is named as a drive position`);
    }
  }
  for (const plot of plots) {
    const where = plot.id;
    if (new Set(plot.series.map((s) => s.name)).size !== plot.series.length) fail(`${where}: two series have one name`);
    if (plot.legend.length !== plot.series.length) fail(`${where}: ${plot.legend.length} legend entries for ${plot.series.length} series`);
    plot.series.forEach((s, k) => {
      const entry = plot.legend[k];
      if (!entry) return;
      if (entry.label !== s.name) fail(`${where}: legend entry ${k + 1} "${entry.label}", the series "${s.name}"`);
      if (entry.swatch !== s.stroke) fail(`${where}: "${s.name}" has the swatch ${entry.swatch || 'none'}, its curve ${s.stroke}`);
      if (isGrey(entry.swatch)) fail(`${where}: "${s.name}" has a grey swatch ${entry.swatch}`);
    });
    plot.axes.forEach((label, k) => { if (!UNIT.test(label)) fail(`${where}: axis ${k} "${label}" has no unit [...]`); });
  }
  return plots.length;
}

/** The cells of the grid's x and y extent (cell centres, evenly spaced) as the map should be drawn. */
function extentRatio(xs, ys) {
  const span = (v) => (v.length > 1 ? ((v[v.length - 1] - v[0]) * v.length) / (v.length - 1) : 1);
  return span(xs) / span(ys);
}

function checkGeometry(where, geometry, xs, ys, fail) {
  if (!geometry) return fail(`${where}: no geometry`);
  for (const label of [geometry.xLabel, geometry.yLabel]) if (!UNIT.test(label)) fail(`${where}: axis "${label}" has no unit`);
  if (!geometry.toScale) return fail(`${where}: an ${geometry.xLabel} × ${geometry.yLabel} map is not drawn to scale`);
  const drawn = geometry.plot.width / geometry.plot.height;
  const expected = extentRatio(xs, ys);
  if (Math.abs(drawn / expected - 1) > 0.02) fail(`${where}: drawn ${drawn.toFixed(3)}:1, the grid is ${expected.toFixed(3)}:1`);
}

/**
 * Every workspace layer: its colour bar's unit, and each cell of the slice shown in the colour the map gives
 * it: the mask where the machine cannot stand (a quantity layer), the value's colour elsewhere.
 */
async function checkWorkspaceLayers(page, data, fail) {
  const map = data.workspace_map;
  for (const layer of map.layers) {
    await page.evaluate((id) => window.pkmReport.setWorkspaceLayer(id), layer.id);
    const state = await page.evaluate(() => window.pkmReport.workspaceMap());
    checkGeometry(`workspace ${layer.id}`, state.geometry, map.x, map.y, fail);
    if (!layer.categorical && !UNIT.test(state.colourBar ?? '')) fail(`workspace ${layer.id}: colour bar "${state.colourBar}" has no unit`);
    const cells = await page.evaluate(([nx, ny]) => {
      const out = [];
      for (let j = 0; j < ny; j++) for (let i = 0; i < nx; i++) out.push({ i, j, ...window.pkmReport.workspaceCellColour(i, j) });
      return out;
    }, [map.x.length, map.y.length]);
    let masked = 0;
    for (const c of cells) {
      if (c.drawn !== c.expected) { fail(`workspace ${layer.id} [${c.i}, ${c.j}]: drawn ${c.drawn}, should be ${c.expected}`); break; }
      if (layer.categorical) continue;
      if (!c.reachable && c.drawn !== state.maskColour) { fail(`workspace ${layer.id} [${c.i}, ${c.j}]: not reachable but ${c.drawn}, not masked`); break; }
      if (!c.reachable) masked++;
    }
    if (!layer.categorical && cells.some((c) => !c.reachable) && masked === 0) fail(`workspace ${layer.id}: no cell masked`);
  }
  await page.evaluate(() => window.pkmReport.setWorkspaceLayer('status'));
}

/** The maps: drawn to scale with units, unreachable cells masked, the status shown first. */
export async function checkMaps(page, data, fail) {
  if (data.workspace_map) {
    const first = await page.evaluate(() => window.pkmReport.workspaceMap());
    if (first.layer !== 'status') fail(`the workspace map opens on ${first.layer}, not on the reachable region (status)`);
    await checkWorkspaceLayers(page, data, fail);
  }
  if (data.stiffness_map) {
    const { map } = await page.evaluate(() => window.pkmReport.stiffnessPlots());
    const m = data.stiffness_map;
    checkGeometry('stiffness map', map.geometry, m.x, m.y, fail);
    if (!UNIT.test(map.colourBar)) fail(`stiffness map: colour bar "${map.colourBar}" has no unit`);
    const wrong = await page.evaluate(([values, mask]) => {
      for (let j = 0; j < values.length; j++) {
        for (let i = 0; i < values[j].length; i++) {
          const c = window.pkmReport.stiffnessMapCellColour(i, j);
          if (c.drawn !== c.expected || (values[j][i] === null && c.drawn !== mask)) return { i, j, ...c };
        }
      }
      return null;
    }, [m.values, map.maskColour]);
    if (wrong) fail(`stiffness map [${wrong.i}, ${wrong.j}]: drawn ${wrong.drawn}, should be ${wrong.expected}`);
  }
}

/** Play and scrub only with frames to animate; the x-axis switch only with plots over path length. */
export async function checkControls(page, data, fail) {
  const t = await page.evaluate(() => ({
    ...window.pkmReport.transport(),
    play: !!document.getElementById('play'),
    scrub: !!document.getElementById('scrub'),
    toggle: !!document.getElementById('x-axis-toggle'),
  }));
  const animated = data.scene.frames.time_s.length >= 2;
  if (t.shown !== animated || t.play !== animated || t.scrub !== animated)
    fail(`${data.scene.frames.time_s.length} frames, but the transport bar ${t.shown ? 'is' : 'is not'} shown (play ${t.play}, scrub ${t.scrub})`);
  const overPath = data.charts.some((c) => Array.isArray(c.x.s_mm) && c.x.s_mm.length > 0);
  if (t.toggle !== overPath) fail(`the x-axis switch is ${t.toggle ? 'shown' : 'absent'} with${overPath ? '' : 'out'} plots over path length`);
  if (data.kind === 'calibration' && t.axis !== 'pose') fail(`a calibration's frames are ${t.axis}, not poses`);
}

/** The verdict is the worst of the items, and a warning is never shown as green. */
export async function checkVerdict(page, data, fail) {
  const v = await page.evaluate(() => window.pkmReport.verdict());
  const severities = [...(data.limits_reached ?? []).map((l) => (l.severity === 'exceeded' ? 'exceeded' : 'reached')), ...(data.warnings ?? []).map(() => 'warning')];
  const worst = severities.reduce((a, s) => (LEVELS.indexOf(s) > LEVELS.indexOf(a) ? s : a), 'ok');
  if (!v.shown) return fail('no verdict shown');
  if (v.shown.level !== worst) fail(`the verdict is ${v.shown.level}, the worst of its items ${worst}`);
  // The verdict's colour (its border): green, amber (red above green well above blue) or red (green ≈ blue).
  const [r, g, b] = (v.shown.colour.match(/\d+/g) ?? []).map(Number);
  const hue = g > r && g > b ? 'green' : r > g && g - b > 50 ? 'amber' : r > 1.8 * g && Math.abs(g - b) < 30 ? 'red' : 'other';
  const wanted = { ok: 'green', warning: 'amber', reached: 'amber', exceeded: 'red' }[worst];
  if (hue !== wanted) fail(`a verdict of ${worst} is drawn ${hue} (${v.shown.colour}), not ${wanted}`);
  if (worst !== 'ok' && /no limit reached/i.test(v.shown.text)) fail(`"${v.shown.text}" beside ${severities.length} items`);
}

/** A servo run whose drives reach the coupling ratio limit makes the servo report's verdict a warning. */
export function checkServoWarnings(data, dir, fail) {
  const summary = JSON.parse(readFileSync(join(dir, 'servo_summary.json'), 'utf8'));
  const limit = summary.coupling_ratio_limit ?? 0.3;
  const coupled = summary.drives.filter((d) => d.max_coupling_ratio >= limit).length;
  const warned = (data.warnings ?? []).some((w) => /coupling ratio/.test(w.what));
  if ((coupled > 0) !== warned) fail(`${coupled} drives at coupling ratio ≥ ${limit}, ${warned ? 'a' : 'no'} coupling warning`);
  if (coupled === 0) fail('the servo case should have drives at the coupling ratio limit (docs/servo.md: 7.6)');
}

/** No empty section, no empty column beside the summary, no half-empty row of plots, no map card wider than its map. */
export async function checkLayout(page, fail) {
  const l = await page.evaluate(() => window.pkmReport.layout());
  if (l.emptySections.length) fail(`empty sections: ${l.emptySections.join(', ')}`);
  if (Math.abs(l.summaryHeight - l.sceneHeight) > 2) fail(`the summary is ${l.summaryHeight} px high, the 3-D view ${l.sceneHeight} px`);
  for (const g of l.grids) {
    g.rows.forEach((w, k) => { if (Math.abs(w - g.width) > 2) fail(`${g.id}: row ${k + 1} of plots is ${w.toFixed(0)} px of ${g.width.toFixed(0)}`); });
  }
  // The card's padding, border and the gap between map and side column.
  for (const m of l.maps) if (m.width > m.content + 40) fail(`${m.id}: a ${m.width.toFixed(0)} px card around ${m.content.toFixed(0)} px of map and legend`);
}
