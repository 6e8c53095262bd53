// What every uPlot plot of the page shares: fonts, axis style, axis labels with their unit in brackets, the
// card a plot sits in, log-axis ticks, and a legend whose swatch is the curve's own colour (the page's CSS
// leaves uPlot's marker border out, so the swatch is its fill).
import { h } from './dom.js';
import { fmtNum } from './format.js';

export const FONT = '11px system-ui, -apple-system, "Segoe UI", Roboto, sans-serif';
export const LABEL_FONT = '600 11px system-ui, -apple-system, "Segoe UI", Roboto, sans-serif';
export const AXIS = {
  stroke: '#56616b',
  grid: { stroke: '#e7ebee', width: 1 },
  ticks: { stroke: '#cfd6dc', width: 1, size: 4 },
  font: FONT,
  labelFont: LABEL_FONT,
  labelSize: 16,
};

/** "[mm]"; "[–]" for a quantity without a unit (a ratio, a count), so that no axis is left without one. */
export function unitText(unit) {
  return `[${unit ? unit : '–'}]`;
}

/** "position [mm]": an axis or colour bar label, the quantity and its unit. */
export function axisLabel(label, unit) {
  return `${label} ${unitText(unit)}`.trim();
}

/** "x_mm" → {name: "x", unit: "mm"}: pkm's CSV columns carry their unit after the last underscore. */
export function columnParts(column) {
  const m = /^(.*)_(mm|deg|rad|s|Hz|N|N_um|um|W|J)$/.exec(String(column));
  if (!m) return { name: String(column), unit: '' };
  return { name: m[1], unit: m[2].replace('N_um', 'N/µm').replace('um', 'µm') };
}

/** "x [mm]" from the column "x_mm". */
export function columnLabel(column) {
  const { name, unit } = columnParts(column);
  return axisLabel(name, unit);
}

/** Tick labels of a log axis: 1, 2, 5 × powers of ten, others blank. */
export function logTicks(u, splits) {
  return splits.map((v) => {
    if (!(v > 0)) return '';
    const m = v / 10 ** Math.floor(Math.log10(v) + 1e-9);
    return Math.abs(m - 1) < 1e-6 || Math.abs(m - 2) < 1e-6 || Math.abs(m - 5) < 1e-6 ? fmtNum(v, 3) : '';
  });
}

/** The legend of a plot: live values, and each series' swatch filled with its stroke colour. */
export function legendOptions() {
  return {
    live: true,
    markers: { width: 0, fill: (u, i) => u.series[i].stroke(u, i) },
  };
}

/** A plot's card: title, subtitle and body. */
export function card(id, title, sub, body, { wide = false } = {}) {
  return h(
    'article',
    // Over measurements or parameters rather than time: the section's whole width.
    { class: 'chart-card', id, dataset: { chartId: id }, style: wide ? { gridColumn: '1 / -1' } : {} },
    h('header', { class: 'chart-head' }, h('h3', null, title), h('span', { class: 'chart-sub' }, sub)),
    body,
  );
}
