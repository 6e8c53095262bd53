// The calibration plots (docs/calibration.md, `calibration` of a `pkm calibrate identify` report): every
// residual of the identification before (the drawing) and after (the identified model) as magnitudes on a log
// axis over the measurements (uPlot), and the parameter table: drawing, identified value, change, standard
// deviation and whether the measurements could identify it. The residuals are over the measurements, not over
// time, so they stand apart from the time charts.
import uPlot from 'uplot';
import { h } from './dom.js';
import { seriesColor } from './colors.js';
import { fmtNum } from './format.js';
import { AXIS, axisLabel, card, legendOptions } from './plot-style.js';
import { registerPlot } from './plot-registry.js';
import { painted } from './pixels.js';

const PLOT_HEIGHT = 260;
// Below this a residual is drawn at it: a log axis has no zero, and 1 nm is below anything measured.
const FLOOR_MM = 1e-6;

const arr = (v) => (Array.isArray(v) ? v : []);
const num = (v) => (v == null || v === '' ? NaN : Number(v));

/** The `calibration` object, or null when absent or malformed. */
export function normalizeCalibration(raw) {
  if (!raw || typeof raw !== 'object') return null;
  const r = raw.residuals && typeof raw.residuals === 'object' ? raw.residuals : {};
  const labels = arr(r.labels).map(String);
  const before = arr(r.before_mm).map(num);
  const after = arr(r.after_mm).map(num);
  const residuals = labels.length && before.length === labels.length && after.length === labels.length ? { labels, before, after } : null;
  const parameters = arr(raw.parameters)
    .filter((p) => p && typeof p === 'object')
    .map((p) => ({
      name: String(p.name ?? ''),
      unit: String(p.unit ?? ''),
      nominal: num(p.nominal),
      identified: num(p.identified),
      change: num(p.change),
      sigma: num(p.sigma),
      identifiable: !!p.identifiable,
    }));
  if (!residuals && !parameters.length) return null;
  return { status: String(raw.status ?? ''), residuals, parameters };
}

function residualChart(res, body) {
  const x = res.labels.map((_, i) => i + 1);
  const mag = (v) => (Number.isFinite(v) ? Math.max(FLOOR_MM, Math.abs(v)) : null);
  const opts = {
    width: Math.max(200, body.clientWidth),
    height: PLOT_HEIGHT,
    scales: { x: { time: false }, y: { distr: 3 } },
    axes: [
      // The residuals in residuals.csv's order: a number, no physical unit.
      { ...AXIS, label: axisLabel('measured quantity', 'index'), size: 30, labelGap: 0 },
      { ...AXIS, label: axisLabel('|residual|', 'mm'), size: 62, gap: 4, values: (u, splits) => splits.map((v) => fmtNum(v, 2)) },
    ],
    series: [
      { label: 'measurement', value: (u, v) => (v == null ? '—' : res.labels[v - 1] ?? String(v)) },
      ...['before (drawing) [mm]', 'after (identified) [mm]'].map((label, i) => ({
        label,
        stroke: seriesColor(i),
        width: 0,
        points: { show: true, size: 4, fill: seriesColor(i) },
        value: (u, v) => (v == null ? '—' : fmtNum(v)),
      })),
    ],
    cursor: { drag: { x: true, y: false }, points: { size: 6 } },
    legend: legendOptions(),
  };
  return new uPlot(opts, [x, res.before.map(mag), res.after.map(mag)], body);
}

function parameterTable(parameters) {
  const cell = { whiteSpace: 'nowrap' };
  const head = h('tr', null, ['parameter', 'unit', 'drawing', 'identified', 'change', 'σ', 'identifiable'].map((t) => h('th', null, t)));
  const rows = parameters.map((p) =>
    h(
      'tr',
      { class: p.identifiable ? '' : 'not-identifiable' },
      h('th', null, p.name),
      h('td', { style: cell }, p.unit),
      h('td', { class: 'val', style: cell }, fmtNum(p.nominal, 9)),
      h('td', { class: 'val', style: cell }, fmtNum(p.identified, 9)),
      h('td', { class: 'val', style: cell }, fmtNum(p.change, 4)),
      h('td', { class: 'val', style: cell }, fmtNum(p.sigma, 3)),
      h('td', { style: cell }, p.identifiable ? 'yes' : 'no'),
    ),
  );
  return h('table', { class: 'summary-table calibration-parameters' }, h('thead', null, head), h('tbody', null, rows));
}

export function createCalibrationPlots(data) {
  const cal = normalizeCalibration(data.calibration);
  let chart = null;
  let chartBody = null;
  const cards = [];
  if (cal && cal.residuals) {
    chartBody = h('div', { class: 'chart-body', style: { minHeight: `${PLOT_HEIGHT + 26}px` } });
    cards.push(card('chart-calibration-residuals', 'Residuals before and after', `residuals.csv · ${cal.residuals.labels.length} measured quantities · log scale`, chartBody, { wide: true }));
  }
  if (cal && cal.parameters.length) {
    const identifiable = cal.parameters.filter((p) => p.identifiable).length;
    const body = h('div', { class: 'chart-body', style: { overflowX: 'auto' } }, parameterTable(cal.parameters));
    cards.push(card('calibration-parameters', 'Parameters', `parameters.csv · ${identifiable} of ${cal.parameters.length} identifiable · ${cal.status}`, body, { wide: true }));
  }
  const element = cards.length
    ? h('section', { class: 'charts-section', id: 'calibration-plots' }, h('div', { class: 'section-head' }, h('h2', null, 'Calibration')), h('div', { class: 'charts' }, cards))
    : null;
  const ro = new ResizeObserver(() => {
    if (!chart) return;
    const w = Math.max(200, Math.floor(chartBody.clientWidth));
    if (w !== chart.width) chart.setSize({ width: w, height: PLOT_HEIGHT });
  });
  return {
    element,
    /** Draws the chart (call once the section is in the document). */
    start() {
      if (!chartBody) return;
      chart = residualChart(cal.residuals, chartBody);
      registerPlot('chart-calibration-residuals', chart);
      ro.observe(chartBody);
    },
    /** For the browser test: {residuals, parameters, drawn} or null without calibration data. */
    state() {
      if (!cal) return null;
      const drawn = !!chart && painted(chart.ctx.canvas);
      return { residuals: cal.residuals ? cal.residuals.labels.length : 0, parameters: cal.parameters.length, drawn };
    },
  };
}
