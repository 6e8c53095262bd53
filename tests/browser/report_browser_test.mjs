// The HTML report in a real browser. For shipped examples of every kind of report (plan, interpolate, optimize,
// stiffness, workspace, servo, calibration) it runs pkm with --report, opens each page in Debian's headless
// Chromium (playwright-core from web/), and checks:
//   - that every page is readable (readability_checks.mjs): colour keys that match the curves, units on every
//     axis and colour bar, maps to scale with the unreachable cells masked, controls only where they act, a
//     verdict that is the worst of its items, no large blank areas;
//   - no console error or warning, no page error, no network request (the page is self-contained);
//   - pkmReport.ready comes, the 3-D canvas and every plot canvas have drawn pixels;
//   - scrubbing (the range input, as a user drags it) moves the animation, and #current-line shows the program
//     line that the run's own file (path.csv / contour.csv) gives for that moment, with its source text;
//   - play advances the animation and pause stops it;
//   - a program that calls a subroutine has, for the calling line, where the moves it executes were written
//     (summary.json's subroutine_lines): in #current-line and beside the line's links;
//   - a plan with --dynamics --elastic has its force, power, energy and dynamic-error plots, and the
//     #strut-colour switch colours the struts by drive force (redder the harder a drive pushes, bluer the harder
//     it pulls), following the animation; reports without drive forces have no such switch;
//   - a run directory with bode.csv and stiffness_map.csv (pkm compliance --bode / --map) gets the Bode plot and
//     the stiffness map, drawn, with the files' frequencies and cells; reports without them have neither;
//   - a `pkm workspace` report has its heat map, drawn for every layer with the colour each cell's value
//     should get, with workspace.csv's cells and statuses, and a 3-D grid's slices can be stepped through.
//   - `pkm servo --report` on a plan has the following-error and contour-error plots with servo.csv's drives and
//     ticks, and a Bode plot per loop (magnitude and phase) for every drive with servo_bode.csv's frequencies,
//     its sampled series ending at the Nyquist frequency; reports without a servo run have none of them;
//   - a `pkm calibrate identify --report` page has its residual chart, drawn, and the parameter table with
//     residuals.csv's and parameters.csv's rows, and its measured poses can be scrubbed through.
// Usage: node tests/browser/report_browser_test.mjs --pkm build/pkm --out build/browser-test
//                                                   [--screenshots docs/images] [--chromium /usr/bin/chromium]
import { execFileSync } from 'node:child_process';
import { existsSync, mkdirSync, readFileSync, rmSync } from 'node:fs';
import { createRequire } from 'node:module';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { checkControls, checkLayout, checkMaps, checkPlots, checkServoWarnings, checkVerdict } from './readability_checks.mjs';

const root = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const require = createRequire(join(root, 'web/package.json'));
const { chromium } = require('playwright-core');
const { CHROMIUM_ARGS } = await import(pathToFileURL(join(root, 'web/dev/chromium.mjs')).href);

function parseArgs(argv) {
  const a = { pkm: join(root, 'build/pkm'), out: join(root, 'build/browser-test'), screenshots: null,
              chromium: process.env.CHROMIUM || '/usr/bin/chromium' };
  for (let i = 0; i < argv.length; i++) {
    const key = argv[i].replace(/^--/, '');
    if (!(key in a)) throw new Error(`unknown argument ${argv[i]}`);
    a[key] = resolve(argv[++i]);
  }
  return a;
}

/** Rows of a CSV file as objects of numbers (empty fields: NaN). */
function readCsv(file) {
  const [header, ...rows] = readFileSync(file, 'utf8').trim().split('\n');
  const names = header.split(',');
  return rows.map((row) => Object.fromEntries(row.split(',').map((v, k) => [names[k], v === '' ? NaN : Number(v)])));
}

/** The program line the run's file gives at time t: the row with that time (frames are rows of the file). */
function lineAt(rows, t) {
  let best = rows[0];
  for (const r of rows) if (Math.abs(r.time_s - t) < Math.abs(best.time_s - t)) best = r;
  if (Math.abs(best.time_s - t) > 1e-6) throw new Error(`no row at t = ${t} (nearest ${best.time_s})`);
  return best.line;
}

const args = parseArgs(process.argv.slice(2));
if (!existsSync(args.pkm)) throw new Error(`no pkm binary at ${args.pkm}: build it first (make build)`);
if (!existsSync(args.chromium)) throw new Error(`no Chromium at ${args.chromium}: scripts/install-deps.sh --with-browser`);
rmSync(args.out, { recursive: true, force: true });
mkdirSync(args.out, { recursive: true });

const cases = [
  { name: 'plan-pocket', command: 'plan', program: 'examples/programs/pocket.ngc', machine: 'examples/machines/hexapod_ch5.yaml',
    rows: 'path.csv', extra: [], verdict: 'ok' },
  // A subroutine called in a loop: the calling line names where the drilling moves were written.
  { name: 'plan-bolt-circle', command: 'plan', program: 'examples/programs/bolt_circle.ngc',
    machine: 'examples/machines/hexapod_ch5.yaml', rows: 'path.csv', extra: [], subroutines: true },
  { name: 'interpolate-ch5-line', command: 'interpolate', program: 'examples/programs/ch5_line.ngc',
    machine: 'examples/machines/hexapod_ch5.yaml', rows: 'contour.csv', extra: ['--method', 'carrier-corrected'] },
  // The naive registers exceed ρ_max on this line: a limit exceeded, the verdict red.
  { name: 'interpolate-ch5-line-exceeded', command: 'interpolate', program: 'examples/programs/ch5_line.ngc',
    machine: 'examples/machines/hexapod_ch5.yaml', rows: 'contour.csv', extra: ['--method', 'carrier', '--rho-max', '0.001'],
    verdict: 'exceeded' },
  // planar3.yaml has no actuator limits: the machine file's warnings make the verdict amber.
  { name: 'plan-planar-circle', command: 'plan', program: 'examples/programs/planar_circle.ngc',
    machine: 'examples/machines/planar3.yaml', rows: 'path.csv', extra: [], verdict: 'warning' },
  { name: 'plan-circle-stiffness', command: 'plan', program: 'examples/programs/circle.ngc',
    machine: 'examples/machines/hexapod_ch5.yaml', rows: 'path.csv', extra: [], stiffness: true },
  // pkm stiffness: the deflection under a cutting load at the program's points (time at the programmed feeds).
  { name: 'stiffness-ch5-circle', command: 'stiffness', program: 'examples/programs/circle.ngc',
    machine: 'examples/machines/hexapod_ch5.yaml', rows: 'points.csv', extra: ['--load', 'tangential=500'],
    strutForces: true },
  { name: 'plan-helix-dynamics', command: 'plan', program: 'examples/programs/helix.ngc',
    machine: 'examples/machines/hexapod_ch5.yaml', rows: 'path.csv', extra: ['--dynamics', '--elastic'], dynamics: true },
  // optimize writes a program, not a run directory: its frames' lines are checked against the report's own data.
  { name: 'optimize-planar-circle', command: 'optimize', program: 'examples/programs/planar_circle.ngc',
    machine: 'examples/machines/planar3.yaml', rows: null,
    extra: ['--law', 'increment', '--step-mm', '0.6981'] },
  // pkm workspace: a map, not a run; one frame (the machine at the grid's centre), nothing to scrub or play.
  { name: 'workspace-ch5-xz', command: 'workspace', machine: 'examples/machines/hexapod_ch5.yaml', rows: null,
    extra: ['--plane', 'xz', '--range-mm', '400', '--step-mm', '40', '--stiffness'], workspace: true },
  { name: 'workspace-triglide-3d', command: 'workspace', machine: 'examples/machines/triglide.yaml', rows: null,
    extra: ['--grid3d', '--range-mm', '400', '--step-mm', '40'], workspace: true },
  // pkm plan, then pkm servo --report on its directory: the plan's page with the servo plots.
  { name: 'servo-ch5-line', command: 'plan', program: 'examples/programs/ch5_line.ngc',
    machine: 'examples/machines/hexapod_ch5.yaml', rows: 'path.csv', extra: [], servo: true, verdict: 'warning' },
  // pkm calibrate identify: the measured poses one second apart (too slow to see play advance), lines of the
  // measurement file.
  { name: 'calibrate-ch5-tracker', command: 'calibrate', machine: 'examples/machines/hexapod_ch5.yaml', rows: null,
    measurements: 'examples/calibration/hexapod_ch5_tracker.csv', extra: [], calibration: true },
];

/** '#rrggbb' → redness r − b in 0..1 units: rises monotonically from full tension to full compression. */
function redness(hex) {
  return (parseInt(hex.slice(1, 3), 16) - parseInt(hex.slice(5, 7), 16)) / 255;
}

/**
 * The struts' colours against the frame's drive forces: wherever two drives' forces differ by more than 5 % of
 * the scale the larger force is the redder strut, and a strut pushing (pulling) with more than 10 % of the
 * scale is red (blue).
 */
function checkColoursFollowForces(colours, forces, scale, where, fail) {
  if (colours.length !== forces.length) return fail(`${where}: ${colours.length} strut colours for ${forces.length} drives`);
  let compared = 0;
  for (let a = 0; a < forces.length; a++) {
    if (forces[a] > 0.1 * scale && !(redness(colours[a]) > 0)) fail(`${where}: drive ${a + 1} pushes ${forces[a]} but is ${colours[a]}`);
    if (forces[a] < -0.1 * scale && !(redness(colours[a]) < 0)) fail(`${where}: drive ${a + 1} pulls ${forces[a]} but is ${colours[a]}`);
    for (let b = 0; b < forces.length; b++) {
      if (forces[a] - forces[b] > 0.05 * scale) {
        compared++;
        if (!(redness(colours[a]) > redness(colours[b])))
          fail(`${where}: drive ${a + 1} (${forces[a]}) is not redder than drive ${b + 1} (${forces[b]}): ${colours[a]} vs ${colours[b]}`);
      }
    }
  }
  return compared;
}

/** Writes the stiffness plots' files into a run's directory and the run's report again (as `pkm report`). */
function addStiffnessFiles(c, dir, page_file) {
  const machine = join(root, c.machine);
  execFileSync(args.pkm, ['compliance', '--machine', machine, '--pose', '0,0,700,0,0,0', '--bode', join(dir, 'bode.csv'),
                          '--points', '120'], { stdio: 'pipe' });
  execFileSync(args.pkm, ['compliance', '--machine', machine, '--map', '--plane', 'xz', '--range-mm', '400', '--step-mm', '40',
                          '--out', join(dir, 'stiffness_map.csv')], { stdio: 'pipe' });
  execFileSync(args.pkm, ['report', dir, '--out', page_file], { stdio: 'pipe' });
}

/** The Bode plot and the stiffness map are there, drawn, with the files' frequencies and cells. */
async function checkStiffnessPlots(page, data, dir, fail) {
  const plots = await page.evaluate(() => window.pkmReport.stiffnessPlots());
  const bode = readCsv(join(dir, 'bode.csv'));
  const map = readCsv(join(dir, 'stiffness_map.csv'));
  if (!data.frequency_response || data.frequency_response.frequency_Hz.length !== bode.length)
    fail(`frequency_response has ${data.frequency_response?.frequency_Hz.length} frequencies, bode.csv ${bode.length}`);
  if (plots.bode.length !== 2 || !plots.bode.every((b) => b.drawn)) fail(`Bode plots ${JSON.stringify(plots.bode)}`);
  if (!plots.map || !plots.map.drawn) fail(`stiffness map ${JSON.stringify(plots.map)}`);
  else if (plots.map.cells !== map.length) fail(`the stiffness map has ${plots.map.cells} cells, stiffness_map.csv ${map.length} rows`);
  // Some cells are beyond the drives' range: null in the data, grey on the page.
  const empty = data.stiffness_map.values.flat().filter((v) => v === null).length;
  const outside = map.filter((r) => !(r.lowest_stiffness_N_um > 0)).length;
  if (empty !== outside || outside === 0) fail(`${empty} empty cells in the data, ${outside} rows without a value`);
}

/** Runs `pkm workspace` for a case (its own command line: no program, no animation to scrub). */
function runWorkspace(c, dir, page_file) {
  execFileSync(args.pkm, ['workspace', '--machine', join(root, c.machine), '--out', dir, '--report', page_file, ...c.extra],
               { stdio: 'pipe' });
}

/** The workspace heat map: drawn for every layer, each cell in the colour of its value, workspace.csv's cells. */
async function checkWorkspaceMap(page, data, dir, fail) {
  const state = await page.evaluate(() => window.pkmReport.workspaceMap());
  if (!state || !state.drawn) return fail(`workspace map ${JSON.stringify(state)}`);
  const header = readFileSync(join(dir, 'workspace.csv'), 'utf8').split('\n')[0].split(',');
  const statusColumn = header.indexOf('status');
  const rows = readFileSync(join(dir, 'workspace.csv'), 'utf8').trim().split('\n').slice(1).map((r) => r.split(','));
  const map = data.workspace_map;
  const slices = map.slices.length || 1;
  if (state.cells * slices !== rows.length) fail(`the map shows ${state.cells} × ${slices} cells, workspace.csv has ${rows.length} rows`);
  for (const id of ['status', 'delta_rho', 'condition_number', 'S_x', 'S_y', 'S_z']) {
    if (!state.layers.includes(id)) fail(`no ${id} layer (layers: ${state.layers.join(', ')})`);
  }
  // Statuses: the data's are the file's, cell by cell (x fastest, then y, then the slices).
  const statusLayer = map.layers.find((l) => l.id === 'status');
  const counts = {};
  rows.forEach((r, k) => {
    const i = k % map.x.length;
    const j = Math.floor(k / map.x.length) % map.y.length;
    const s = Math.floor(k / (map.x.length * map.y.length));
    const shown = map.status_names[statusLayer.values[s][j][i]];
    if (shown !== r[statusColumn]) fail(`cell ${k}: the map says ${shown}, workspace.csv ${r[statusColumn]}`);
    counts[r[statusColumn]] = (counts[r[statusColumn]] ?? 0) + 1;
  });
  if (!counts.ok || !counts.actuator_range) fail(`the case should have ok and actuator_range cells: ${JSON.stringify(counts)}`);
  // Every layer draws, and a sample of cells has the colour of its value.
  for (const id of state.layers) {
    if ((await page.evaluate((l) => window.pkmReport.setWorkspaceLayer(l), id)) !== id) fail(`cannot show layer ${id}`);
    const shown = await page.evaluate(() => window.pkmReport.workspaceMap());
    if (shown.layer !== id || !shown.drawn) fail(`layer ${id}: ${JSON.stringify(shown)}`);
    for (const [i, j] of [[0, 0], [Math.floor(map.x.length / 2), Math.floor(map.y.length / 2)], [map.x.length - 1, map.y.length - 1], [1, map.y.length - 2]]) {
      const c = await page.evaluate(([a, b]) => window.pkmReport.workspaceCellColour(a, b), [i, j]);
      if (!c || c.drawn !== c.expected) fail(`layer ${id}, cell [${i}, ${j}]: drawn ${c?.drawn}, its value's colour ${c?.expected}`);
    }
  }
  if (slices > 1) {
    const last = await page.evaluate((k) => window.pkmReport.setWorkspaceSlice(k), slices - 1);
    const shown = await page.evaluate(() => window.pkmReport.workspaceMap());
    if (last !== slices - 1 || shown.slice !== slices - 1 || !shown.drawn) fail(`slice ${slices - 1}: ${JSON.stringify(shown)}`);
  }
  await page.evaluate(() => window.pkmReport.setWorkspaceLayer('status'));
}

/** The points a chart keeps of `rows` samples (src/report/decimator.hpp, 2000 buckets of two points). */
function decimatedPoints(rows, buckets = 2000) {
  if (rows <= 2 * buckets) return rows;
  const size = Math.ceil(rows / buckets);
  return 2 * Math.ceil(rows / size);
}

// The series of each Bode plot (web/src/servo.js): servo_bode.csv's columns.
const SERVO_BODE_SERIES = {
  'speed magnitude': ['speed_open_db', 'speed_open_sampled_db', 'speed_closed_db'],
  'speed phase': ['speed_open_deg', 'speed_open_sampled_deg'],
  'position magnitude': ['position_open_db', 'position_open_sampled_db', 'position_closed_db', 'position_closed_sampled_db'],
  'position phase': ['position_open_deg', 'position_open_sampled_deg'],
};

/**
 * The servo plots: the following error with a series per drive and the contour error, servo.csv's ticks, drawn;
 * for the first and the last drive the four Bode plots with servo_bode.csv's frequencies and the non-empty
 * values of each column (the sampled ones end at the Nyquist frequency); the table's contour error row.
 */
async function checkServoPlots(page, data, dir, fail) {
  const state = await page.evaluate(() => window.pkmReport.servoPlots());
  if (!state) return fail('no servo plots');
  const ticks = readCsv(join(dir, 'servo.csv'));
  const drives = Object.keys(ticks[0]).filter((k) => /^e\d+_(mm|deg)$/.test(k)).length;
  const summary = JSON.parse(readFileSync(join(dir, 'servo_summary.json'), 'utf8'));
  if (drives !== 6 || summary.drives.length !== drives) fail(`servo.csv has ${drives} drives, the summary ${summary.drives.length}`);
  for (const [id, series] of [['servo_following_error', drives], ['servo_contour_error', 1]]) {
    const chart = state.charts.find((ch) => ch.id === id);
    if (!chart) { fail(`no ${id} plot`); continue; }
    if (chart.series !== series || chart.legend !== series) fail(`${id}: ${chart.series} series in the data, ${chart.legend} drawn, servo.csv has ${series}`);
    if (chart.points !== decimatedPoints(ticks.length)) fail(`${id}: ${chart.points} points for ${ticks.length} ticks`);
    if (!chart.drawn) fail(`${id} is not drawn`);
  }
  if (Math.abs(data.servo.nyquist_hz - 0.5 / summary.loop_period_s) > 1e-6) fail(`nyquist_hz ${data.servo.nyquist_hz}`);
  const bode = readCsv(join(dir, 'servo_bode.csv'));
  if (state.drives !== drives) fail(`the Bode plots offer ${state.drives} drives`);
  for (const drive of [1, drives]) {
    if ((await page.evaluate((d) => window.pkmReport.setServoDrive(d), drive)) !== drive) fail(`cannot show drive ${drive}`);
    const shown = await page.evaluate(() => window.pkmReport.servoPlots());
    const rows = bode.filter((r) => r.drive === drive);
    if (shown.drive !== drive || shown.bode.length !== 4) fail(`drive ${drive}: ${JSON.stringify(shown.bode)}`);
    for (const plot of shown.bode) {
      const columns = SERVO_BODE_SERIES[`${plot.loop} ${plot.which}`];
      const where = `drive ${drive}, ${plot.loop} loop ${plot.which}`;
      if (!columns || plot.series !== columns.length) { fail(`${where}: ${plot.series} series`); continue; }
      if (!plot.drawn) fail(`${where}: not drawn`);
      if (plot.points !== rows.length) fail(`${where}: ${plot.points} frequencies, servo_bode.csv has ${rows.length}`);
      columns.forEach((column, k) => {
        const given = rows.filter((r) => Number.isFinite(r[column])).length;
        if (plot.values[k] !== given) fail(`${where}: ${column} has ${plot.values[k]} values, servo_bode.csv ${given}`);
        if (column.includes('sampled') && !(given > 0 && given < rows.length)) fail(`${where}: ${column} should end at the Nyquist frequency`);
      });
    }
    const sampledEnd = Math.max(...rows.filter((r) => Number.isFinite(r.speed_open_sampled_db)).map((r) => r.frequency_hz));
    if (!(sampledEnd <= data.servo.nyquist_hz)) fail(`drive ${drive}: sampled values up to ${sampledEnd} Hz, beyond Nyquist ${data.servo.nyquist_hz} Hz`);
  }
  const row = data.table.find((r) => r.label === 'Max contour error (servo)');
  if (!row || row.line !== summary.max_contour_line) fail(`the table's contour error row ${JSON.stringify(row)}, the summary's line ${summary.max_contour_line}`);
  const shownRow = await page.evaluate(() => [...document.querySelectorAll('#summary-table th')].some((th) => th.textContent === 'Max contour error (servo)'));
  if (!shownRow) fail('the summary table does not show the contour error');
  await page.evaluate(() => window.pkmReport.setServoDrive(1));
}

/** Rows of a CSV that pkm wrote with text fields (no quoting needed): the data rows, comments skipped. */
function csvRowCount(file) {
  return readFileSync(file, 'utf8').split('\n').filter((l) => l.trim() && !l.startsWith('#')).length - 1;
}

/** The calibration page: the residual chart drawn with residuals.csv's rows, the parameter table parameters.csv's. */
async function checkCalibrationPlots(page, data, dir, fail) {
  const state = await page.evaluate(() => window.pkmReport.calibrationPlots());
  if (!state) return fail('no calibration plots');
  const residuals = csvRowCount(join(dir, 'residuals.csv'));
  const parameters = csvRowCount(join(dir, 'parameters.csv'));
  if (state.residuals !== residuals) fail(`the residual chart has ${state.residuals} residuals, residuals.csv ${residuals}`);
  if (state.parameters !== parameters) fail(`the parameter table has ${state.parameters} parameters, parameters.csv ${parameters}`);
  if (!state.drawn) fail('the residual chart is not drawn');
  const tableRows = await page.evaluate(() => document.querySelectorAll('#calibration-parameters tbody tr').length);
  if (tableRows !== parameters) fail(`the parameter table shows ${tableRows} rows for ${parameters} parameters`);
  if (data.kind !== 'calibration' || data.charts.length) fail(`kind ${data.kind}, ${data.charts.length} time plots`);
}

/**
 * The calling lines of a program with subroutines: the report names where their moves were written, and
 * #current-line shows it on a frame of such a line ("line 19: o<drill_hole> call … → bolt_circle.ngc:11").
 */
async function checkSubroutineLines(page, data, dir, fail) {
  const summary = JSON.parse(readFileSync(join(dir, 'summary.json'), 'utf8'));
  const called = Object.entries(data.program.subroutine_lines ?? {});
  if (!called.length) return fail(`no subroutine_lines in the report (summary: ${JSON.stringify(summary.subroutine_lines)})`);
  const frameLines = data.scene.frames.line;
  const entry = called.find(([line]) => frameLines.includes(Number(line)));
  if (!entry) return fail(`no frame on a calling line (${called.map(([l]) => l).join(', ')})`);
  const [line, places] = entry;
  if (JSON.stringify(summary.subroutine_lines?.[line]) !== JSON.stringify(places))
    fail(`line ${line}: the report says ${JSON.stringify(places)}, summary.json ${JSON.stringify(summary.subroutine_lines?.[line])}`);
  const text = await page.evaluate((i) => {
    window.pkmReport.setFrame(i);
    return document.getElementById('current-line').textContent;
  }, frameLines.indexOf(Number(line)));
  if (!text.startsWith(`line ${line}: `) || !text.includes(`\u2192 ${places[0]}`)) fail(`#current-line "${text}" does not name ${places[0]}`);
}

/** The dynamics plots are there and the struts can be coloured by drive force, in step with the animation. */
async function checkForceColouring(page, data, fail) {
  const ids = data.charts.map((ch) => ch.id);
  for (const id of ['drive_forces', 'drive_forces_static', 'drive_forces_dynamic', 'drive_power', 'drive_energy', 'dynamic_error'])
    if (!ids.includes(id)) fail(`no ${id} plot (plots: ${ids.join(', ')})`);
  if (!(await page.evaluate(() => document.querySelector('#chart-drive_forces canvas') !== null))) fail('the drive force plot has no canvas');
  const frames = data.scene.frames;
  const scale = data.scene.drive_force_scale;
  if (!Array.isArray(frames.drive_force) || frames.drive_force.length !== frames.time_s.length) return fail('frames lack drive_force');
  if (!(scale > 0)) return fail(`drive_force_scale ${scale}`);

  const k0 = Math.floor(0.2 * (frames.time_s.length - 1));
  await page.evaluate((i) => window.pkmReport.setFrame(i), k0);
  const before = await page.evaluate(() => ({ mode: window.pkmReport.strutColoring(), colours: window.pkmReport.strutColors() }));
  if (before.mode !== 'limits') fail(`strut colouring starts as ${before.mode}, not limits`);
  await page.click('#strut-colour');
  const after = await page.evaluate(() => ({
    mode: window.pkmReport.strutColoring(),
    colours: window.pkmReport.strutColors(),
    legend: getComputedStyle(document.getElementById('legend-strut-force')).display !== 'none',
    limitsLegend: getComputedStyle(document.getElementById('legend-strut-limits')).display !== 'none',
  }));
  if (after.mode !== 'force') fail(`clicking #strut-colour gave ${after.mode}, not force`);
  if (!after.legend || after.limitsLegend) fail('the legend does not show the force scale alone');
  if (after.colours.join() === before.colours.join()) fail('force colouring did not change the strut colours');
  let compared = checkColoursFollowForces(after.colours, frames.drive_force[k0], scale, `frame ${k0}`, fail);
  if (!(await page.evaluate(() => window.pkmReport.canvasHasPixels()))) fail('the 3-D canvas is empty with force colouring');

  // The frame of the largest force of the run, and the colours after playing: they follow the animation.
  let peakFrame = 0;
  frames.drive_force.forEach((f, i) => { if (Math.max(...f.map(Math.abs)) > Math.max(...frames.drive_force[peakFrame].map(Math.abs))) peakFrame = i; });
  const atPeak = await page.evaluate((i) => { window.pkmReport.setFrame(i); return window.pkmReport.strutColors(); }, peakFrame);
  compared += checkColoursFollowForces(atPeak, frames.drive_force[peakFrame], scale, `frame ${peakFrame}`, fail);
  if (atPeak.join() === after.colours.join()) fail(`the strut colours at frames ${k0} and ${peakFrame} are the same`);
  await page.click('#play');
  await page.waitForTimeout(500);
  await page.click('#play');
  const played = await page.evaluate(() => ({ frame: window.pkmReport.currentFrame(), colours: window.pkmReport.strutColors() }));
  compared += checkColoursFollowForces(played.colours, frames.drive_force[played.frame], scale, `played frame ${played.frame}`, fail);
  if (compared === 0) fail('no two drives differed enough to compare their colours');

  await page.click('#strut-colour');
  await page.evaluate((i) => window.pkmReport.setFrame(i), k0);
  const back = await page.evaluate(() => ({ mode: window.pkmReport.strutColoring(), colours: window.pkmReport.strutColors() }));
  if (back.mode !== 'limits' || back.colours.join() !== before.colours.join()) fail('switching back does not restore the limit colours');
  // Screenshots show the force colouring.
  await page.evaluate(() => window.pkmReport.setStrutColoring('force'));
}

const failures = [];
const browser = await chromium.launch({ executablePath: args.chromium, headless: true, args: CHROMIUM_ARGS });
try {
  for (const c of cases) {
    const dir = join(args.out, c.name);
    const page_file = join(dir, 'report.html');
    mkdirSync(dir, { recursive: true });
    const out = c.command === 'optimize' ? join(dir, 'optimized.ngc') : dir;
    if (c.workspace) runWorkspace(c, dir, page_file);
    else if (c.servo) {
      execFileSync(args.pkm, ['plan', join(root, c.program), '--machine', join(root, c.machine), '--tables', 'csv', '--out', dir],
                   { stdio: 'pipe' });
      execFileSync(args.pkm, ['servo', dir, '--machine', join(root, c.machine), '--report', page_file], { stdio: 'pipe' });
    } else if (c.calibration) {
      execFileSync(args.pkm, ['calibrate', 'identify', '--machine', join(root, c.machine), '--measurements', join(root, c.measurements),
                              '--out', join(dir, 'calibrated.yaml'), '--dir', dir, '--report', page_file], { stdio: 'pipe', cwd: root });
    } else execFileSync(args.pkm, [c.command, join(root, c.program), '--machine', join(root, c.machine), '--out', out,
                                 '--report', page_file, ...(c.command === 'plan' ? ['--tables', 'csv'] : []), ...c.extra],
                        { stdio: 'pipe' });
    if (c.stiffness) addStiffnessFiles(c, dir, page_file);
    const rows = c.rows ? readCsv(join(dir, c.rows)) : null;
    const fail = (what) => failures.push(`${c.name}: ${what}`);

    const page = await browser.newPage({ viewport: { width: 1400, height: 900 } });
    page.on('console', (m) => { if (m.type() === 'error' || m.type() === 'warning') fail(`console ${m.type()}: ${m.text()}`); });
    page.on('pageerror', (e) => fail(`page error: ${e.message}`));
    page.on('request', (r) => { if (!/^(file|data|blob):/.test(r.url())) fail(`network request ${r.url()}`); });
    await page.goto(pathToFileURL(page_file).href, { waitUntil: 'load' });
    await page.waitForFunction(() => window.pkmReport && window.pkmReport.ready === true, null, { timeout: 30000 });
    await page.waitForFunction(() => window.pkmReport.builtCharts() === window.pkmReport.chartCount, null, { timeout: 30000 });

    const data = await page.evaluate(() => JSON.parse(document.getElementById('pkm-report-data').textContent));
    if (!(await page.evaluate(() => window.pkmReport.canvasHasPixels()))) fail('the 3-D canvas is empty');
    // Every plot drew something besides its background: some pixel of its canvas is not transparent/white.
    const plots = await page.evaluate(() => [...document.querySelectorAll('#charts canvas')].map((canvas) => {
      const { width, height } = canvas;
      const pixels = canvas.getContext('2d').getImageData(0, 0, width, height).data;
      let inked = 0;
      for (let i = 0; i < pixels.length; i += 4) {
        if (pixels[i + 3] > 0 && (pixels[i] < 240 || pixels[i + 1] < 240 || pixels[i + 2] < 240)) inked++;
      }
      return inked;
    }));
    if (plots.length < data.charts.length) fail(`${plots.length} plot canvases for ${data.charts.length} charts`);
    plots.forEach((inked, k) => { if (inked < 50) fail(`plot ${k} has only ${inked} drawn pixels`); });
    const described = await checkPlots(page, data, fail);
    await checkMaps(page, data, fail);
    await checkControls(page, data, fail);
    await checkVerdict(page, data, fail);
    if (c.verdict) {
      const level = await page.evaluate(() => window.pkmReport.verdict().shown.level);
      if (level !== c.verdict) fail(`the verdict is ${level}, the case's is ${c.verdict}`);
    }
    await checkLayout(page, fail);
    if (c.servo) checkServoWarnings(data, dir, fail);

    const frames = data.scene.frames;
    if (c.workspace) {
      await checkWorkspaceMap(page, data, dir, fail);
      if (data.charts.length || data.stiffness_map) fail('a workspace report has time plots or a stiffness map');
      if (args.screenshots) await page.screenshot({ path: join(args.screenshots, `report-${c.name}.png`), fullPage: true });
      await page.close();
      console.log(`${c.name}: workspace map and ${described} plots checked`);
      continue;
    }
    if (data.workspace_map || (await page.evaluate(() => document.getElementById('workspace-map') !== null)))
      fail('a report of a run has a workspace map');
    // Scrub as a user does: move the range input and let it fire its input event.
    for (const fraction of [0.3, 0.75]) {
      const k = Math.floor(fraction * (frames.time_s.length - 1));
      const shown = await page.evaluate((i) => {
        const scrub = document.getElementById('scrub');
        scrub.value = String(i);
        scrub.dispatchEvent(new Event('input', { bubbles: true }));
        return { frame: window.pkmReport.currentFrame(), text: document.getElementById('current-line').textContent };
      }, k);
      const expected = rows ? lineAt(rows, frames.time_s[k]) : frames.line[k];
      if (shown.frame !== k) fail(`scrubbed to ${k}, the animation is at frame ${shown.frame}`);
      if (!shown.text.startsWith(`line ${expected}`)) fail(`at frame ${k} #current-line says "${shown.text}", ${c.rows ?? 'the data'} says line ${expected}`);
      const source = data.program.lines[String(expected)];
      if (source && !shown.text.includes(source.trim().slice(0, 20))) fail(`#current-line "${shown.text}" lacks the source text "${source}"`);
      if (!(await page.evaluate(() => window.pkmReport.canvasHasPixels()))) fail(`the 3-D canvas is empty at frame ${k}`);
    }
    if (c.calibration) {
      await checkCalibrationPlots(page, data, dir, fail);
      if (args.screenshots) await page.screenshot({ path: join(args.screenshots, `report-${c.name}.png`), fullPage: true });
      await page.close();
      console.log(`${c.name}: ${frames.time_s.length} poses, ${described} plots, calibration plots checked`);
      continue;
    }
    if (data.calibration || (await page.evaluate(() => window.pkmReport.calibrationPlots() !== null)))
      fail('a report of a run has calibration plots');
    // Play moves the animation on; pause holds it.
    await page.evaluate(() => window.pkmReport.setFrame(0));
    await page.click('#play');
    await page.waitForTimeout(700);
    await page.click('#play');
    const played = await page.evaluate(() => window.pkmReport.currentFrame());
    await page.waitForTimeout(300);
    const held = await page.evaluate(() => window.pkmReport.currentFrame());
    if (!(played > 0)) fail('play did not advance the animation');
    if (held !== played) fail(`pause did not hold the animation (${played} → ${held})`);

    if (c.stiffness) await checkStiffnessPlots(page, data, dir, fail);
    else if (data.frequency_response || data.stiffness_map || (await page.evaluate(() => document.getElementById('stiffness-plots') !== null)))
      fail('a report without bode.csv or stiffness_map.csv has stiffness plots');

    if (c.servo) await checkServoPlots(page, data, dir, fail);
    else if (data.servo || (await page.evaluate(() => window.pkmReport.servoPlots() !== null || document.getElementById('servo-plots') !== null)))
      fail('a report without a servo run has servo plots');

    if (c.subroutines) await checkSubroutineLines(page, data, dir, fail);
    else if (data.program.subroutine_lines) fail('a program without subroutine calls has subroutine_lines');

    if (c.dynamics) await checkForceColouring(page, data, fail);
    else if (c.strutForces) {
      // pkm stiffness: the struts' tensions colour the struts, as a plan's drive forces do.
      if ((await page.evaluate(() => window.pkmReport.strutColoring())) !== 'limits') fail('the strut tensions cannot colour the struts');
    } else if (await page.evaluate(() => document.getElementById('strut-colour') !== null || window.pkmReport.strutColoring() !== null))
      fail('a report without drive forces offers force colouring');

    if (args.screenshots) {
      mkdirSync(args.screenshots, { recursive: true });
      await page.evaluate((i) => window.pkmReport.setFrame(i), Math.floor(frames.time_s.length / 3));
      await page.screenshot({ path: join(args.screenshots, `report-${c.name}.png`), fullPage: true });
    }
    await page.close();
    console.log(`${c.name}: ${frames.time_s.length} frames, ${described} plots checked`);
  }
} finally {
  await browser.close();
}
if (failures.length) {
  for (const f of failures) console.error(`FAIL: ${f}`);
  process.exit(1);
}
console.log('report browser test: OK');
