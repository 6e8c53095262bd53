// The stiffness plots (docs/report-data.md: `frequency_response`, `stiffness_map`): the tool's dynamic
// compliance as a Bode plot (magnitude on log-log axes, phase on a log frequency axis; uPlot) and the lowest
// stiffness over a plane of poses as a colour map (a canvas, one cell per grid point, grey where the point has
// no value). Both are over their own axes, not over the run's time, so they stand apart from the time charts.
import uPlot from 'uplot';
import { h } from './dom.js';
import { seriesColor, errorRgb } from './colors.js';
import { fmtNum } from './format.js';

const PLOT_HEIGHT = 230;
const MAP_HEIGHT = 320;
const FONT = '11px system-ui, -apple-system, "Segoe UI", Roboto, sans-serif';
const LABEL_FONT = '600 11px system-ui, -apple-system, "Segoe UI", Roboto, sans-serif';
export const AXIS = { stroke: '#56616b', grid: { stroke: '#e7ebee', width: 1 }, ticks: { stroke: '#cfd6dc', width: 1, size: 4 }, font: FONT, labelFont: LABEL_FONT, labelSize: 16 };
const NONE_COLOR = '#d5d9dd';

export function card(id, title, sub, body) {
  return h(
    'article',
    { class: 'chart-card', id, dataset: { chartId: id } },
    h('header', { class: 'chart-head' }, h('h3', null, title), h('span', { class: 'chart-sub' }, sub)),
    body,
  );
}

/** Tick labels of a log axis: 1, 2, 5 × powers of ten, others blank. */
export function logTicks(u, splits) {
  return splits.map((v) => {
    if (!(v > 0)) return '';
    const m = v / 10 ** Math.floor(Math.log10(v) + 1e-9);
    return Math.abs(m - 1) < 1e-6 || Math.abs(m - 2) < 1e-6 || Math.abs(m - 5) < 1e-6 ? fmtNum(v, 3) : '';
  });
}

function bodeChart(response, body, which) {
  const magnitude = which === 'magnitude';
  const unit = magnitude ? 'µm/N' : '°';
  const opts = {
    width: Math.max(200, body.clientWidth),
    height: PLOT_HEIGHT,
    scales: {
      // The sweep's own ends, not the decades around them.
      x: { time: false, distr: 3, range: (u, min, max) => [min, max] },
      y: magnitude ? { distr: 3 } : { range: [-180, 0] },
    },
    axes: [
      { ...AXIS, values: logTicks, label: 'frequency (Hz)', size: 30, labelGap: 0 },
      { ...AXIS, values: magnitude ? logTicks : undefined, label: magnitude ? 'compliance (µm/N)' : 'phase (°)', size: 56, gap: 4 },
    ],
    series: [
      { label: 'frequency', value: (u, v) => (v == null ? '—' : `${fmtNum(v, 4)} Hz`) },
      ...response.entries.map((e, i) => ({
        label: e.name,
        stroke: seriesColor(i),
        width: 1.25,
        points: { show: false },
        value: (u, v) => (v == null ? '—' : `${fmtNum(v)} ${unit}`),
      })),
    ],
    cursor: { drag: { x: false, y: false }, points: { size: 6 } },
    legend: { live: true },
  };
  const values = response.entries.map((e) => (magnitude ? e.magnitude_um_N : e.phase_deg));
  return new uPlot(opts, [response.frequency_Hz, ...values], body);
}

/** The finite values' range of a map, for its colour scale (null when it has none). */
function mapRange(map) {
  let lo = Infinity;
  let hi = -Infinity;
  for (const row of map.values) {
    for (const v of row) {
      if (!Number.isFinite(v)) continue;
      lo = Math.min(lo, v);
      hi = Math.max(hi, v);
    }
  }
  return Number.isFinite(lo) ? [lo, hi] : null;
}

/** The axes of a heat map of cells (first, middle and last value of each axis, and their labels). */
export function labelMapAxes(ctx, map, pad, plotW, plotH, cellW, cellH) {
  const nx = map.x.length;
  const ny = map.y.length;
  ctx.fillStyle = '#56616b';
  ctx.font = FONT;
  ctx.textAlign = 'center';
  ctx.textBaseline = 'top';
  const ticks = (n) => [...new Set([0, Math.floor((n - 1) / 2), n - 1])];
  for (const i of ticks(nx)) ctx.fillText(fmtNum(map.x[i], 4), pad.left + (i + 0.5) * cellW, pad.top + plotH + 4);
  ctx.font = LABEL_FONT;
  ctx.fillText(map.x_label, pad.left + plotW / 2, pad.top + plotH + 18);
  ctx.font = FONT;
  ctx.textAlign = 'right';
  ctx.textBaseline = 'middle';
  for (const j of ticks(ny)) ctx.fillText(fmtNum(map.y[j], 4), pad.left - 6, pad.top + (ny - 1 - j + 0.5) * cellH);
  ctx.save();
  ctx.translate(12, pad.top + plotH / 2);
  ctx.rotate(-Math.PI / 2);
  ctx.textAlign = 'center';
  ctx.font = LABEL_FONT;
  ctx.fillText(map.y_label, 0, 0);
  ctx.restore();
}

/**
 * Sizes a heat map's canvas to `width` × `height` CSS pixels at the device's pixel ratio, clears it, and gives
 * the context and the plot area inside the margins (`padLeft` for the second axis' numbers).
 */
export function startMapCanvas(canvas, width, height, padLeft, contextOptions) {
  const pr = window.devicePixelRatio || 1;
  const pad = { left: padLeft, right: 12, top: 8, bottom: 34 };
  const plotW = Math.max(40, width - pad.left - pad.right);
  const plotH = height - pad.top - pad.bottom;
  canvas.width = Math.round(width * pr);
  canvas.height = Math.round(height * pr);
  canvas.style.width = `${width}px`;
  canvas.style.height = `${height}px`;
  const ctx = canvas.getContext('2d', contextOptions);
  ctx.setTransform(pr, 0, 0, pr, 0, 0);
  ctx.clearRect(0, 0, width, height);
  return { ctx, pad, plotW, plotH, pr };
}

function drawMap(map, canvas, width) {
  const nx = map.x.length;
  const ny = map.y.length;
  const { ctx, pad, plotW, plotH } = startMapCanvas(canvas, width, MAP_HEIGHT, 56);
  const range = mapRange(map);
  const cellW = plotW / nx;
  const cellH = plotH / ny;
  const rgb = [0, 0, 0];
  for (let j = 0; j < ny; j++) {
    for (let i = 0; i < nx; i++) {
      const v = map.values[j][i];
      if (Number.isFinite(v) && range) {
        // Weak (low stiffness) is hot: the path error's colour map, reversed, on a log scale (a map spans a
        // factor of several, most of it near the weak end).
        const t = range[1] > range[0] && range[0] > 0 ? Math.log(range[1] / v) / Math.log(range[1] / range[0]) : 0;
        errorRgb(t, rgb);
        ctx.fillStyle = `rgb(${rgb.map((c) => Math.round(c * 255)).join(',')})`;
      } else {
        ctx.fillStyle = NONE_COLOR;
      }
      // Row 0 is the lowest value of the second axis: drawn at the bottom.
      ctx.fillRect(pad.left + i * cellW, pad.top + (ny - 1 - j) * cellH, Math.ceil(cellW), Math.ceil(cellH));
    }
  }
  labelMapAxes(ctx, map, pad, plotW, plotH, cellW, cellH);
  return { pad, cellW, cellH, nx, ny };
}

/** The cell [i, j] under a mouse position, or null. */
function cellAt(layout, x, y) {
  if (!layout) return null;
  const i = Math.floor((x - layout.pad.left) / layout.cellW);
  const j = layout.ny - 1 - Math.floor((y - layout.pad.top) / layout.cellH);
  return i >= 0 && i < layout.nx && j >= 0 && j < layout.ny ? [i, j] : null;
}

export function createStiffnessPlots(data) {
  const response = data.frequency_response;
  const map = data.stiffness_map;
  const bode = [];
  let mapView = null;
  const cards = [];
  if (response) {
    for (const which of ['magnitude', 'phase']) {
      const body = h('div', { class: 'chart-body', style: { minHeight: `${PLOT_HEIGHT + 26}px` } });
      const title = which === 'magnitude' ? 'Dynamic compliance: magnitude' : 'Dynamic compliance: phase';
      cards.push(card(`chart-bode-${which}`, title, `${response.file} · ${response.entries.length} entries`, body));
      bode.push({ which, body, u: null });
    }
  }
  if (map) {
    const range = mapRange(map);
    const canvas = h('canvas', { class: 'stiffness-map-canvas' });
    const readout = h('div', { class: 'stiffness-map-readout' }, 'hover a cell for its value');
    const legend = h(
      'div',
      { class: 'stiffness-map-legend' },
      h('span', null, range ? `${fmtNum(range[0])} ${map.value_unit}` : '—'),
      h('span', { class: 'stiffness-map-ramp' }),
      h('span', null, range ? `${fmtNum(range[1])} ${map.value_unit}` : '—'),
      h('span', { class: 'stiffness-map-none' }, 'no value'),
    );
    const body = h('div', { class: 'chart-body' }, canvas, legend, readout);
    cards.push(card('chart-stiffness-map', 'Lowest stiffness over the workspace', `${map.file} · ${map.value_label} (${map.value_unit}, log colour scale)`, body));
    mapView = { canvas, body, layout: null, drawn: false };
    canvas.addEventListener('mousemove', (e) => {
      const r = canvas.getBoundingClientRect();
      const cell = cellAt(mapView.layout, e.clientX - r.left, e.clientY - r.top);
      if (!cell) return;
      const [i, j] = cell;
      const v = map.values[j][i];
      const value = Number.isFinite(v) ? `${fmtNum(v)} ${map.value_unit}` : 'no value';
      readout.textContent = `${map.x_label} ${fmtNum(map.x[i], 5)}, ${map.y_label} ${fmtNum(map.y[j], 5)}: ${value}`;
    });
  }
  const element = cards.length
    ? h('section', { class: 'charts-section', id: 'stiffness-plots' }, h('div', { class: 'section-head' }, h('h2', null, 'Stiffness')), h('div', { class: 'charts' }, cards))
    : null;

  const redrawMap = () => {
    mapView.layout = drawMap(map, mapView.canvas, Math.max(200, Math.floor(mapView.body.clientWidth)));
    mapView.drawn = true;
  };

  const ro = new ResizeObserver(() => {
    for (const b of bode) {
      if (!b.u) continue;
      const w = Math.max(200, Math.floor(b.body.clientWidth));
      if (w !== b.u.width) b.u.setSize({ width: w, height: PLOT_HEIGHT });
    }
    if (mapView && mapView.drawn) redrawMap();
  });

  return {
    element,
    /** Draws the plots (call once the section is in the document). */
    start() {
      if (!element) return;
      for (const b of bode) b.u = bodeChart(response, b.body, b.which);
      if (mapView) redrawMap();
      for (const b of bode) ro.observe(b.body);
      if (mapView) ro.observe(mapView.body);
    },
    /** For the browser test: which plots there are and whether their canvases have pixels. */
    state() {
      const painted = (c) => {
        if (!c || !c.width || !c.height) return false;
        const px = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
        for (let k = 3; k < px.length; k += 4) if (px[k] !== 0) return true;
        return false;
      };
      return {
        bode: bode.map((b) => ({ which: b.which, drawn: !!b.u && painted(b.u.ctx.canvas) })),
        map: mapView ? { drawn: mapView.drawn && painted(mapView.canvas), cells: map.x.length * map.y.length } : null,
      };
    },
  };
}
