// The stiffness plots (docs/report-data.md: `frequency_response`, `stiffness_map`): the tool's dynamic
// compliance as a Bode plot (magnitude on log-log axes, phase on a log frequency axis; uPlot) and the lowest
// stiffness over a plane of poses as a heat map drawn to scale (heat-map.js), the points without a value masked.
// Both are over their own axes, not over the run's time, so they stand apart from the time charts.
import uPlot from 'uplot';
import { h } from './dom.js';
import { seriesColor, errorRgb, ERROR_GRADIENT } from './colors.js';
import { fmtNum } from './format.js';
import { AXIS, axisLabel, card, columnLabel, legendOptions, logTicks } from './plot-style.js';
import { registerPlot } from './plot-registry.js';
import { createHeatMap } from './heat-map.js';
import { colourBar, MASK_COLOR } from './colour-bar.js';
import { painted } from './pixels.js';

const PLOT_HEIGHT = 230;
const SIDE_WIDTH = 240;
// The browser test reads the map's cells back: a canvas read often is kept in memory, where that is cheap.
const CONTEXT = { willReadFrequently: true };

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
      { ...AXIS, values: logTicks, label: axisLabel('frequency', 'Hz'), size: 30, labelGap: 0 },
      { ...AXIS, values: magnitude ? logTicks : undefined, label: magnitude ? axisLabel('compliance', unit) : axisLabel('phase', unit), size: 56, gap: 4 },
    ],
    series: [
      { label: 'frequency', value: (u, v) => (v == null ? '—' : `${fmtNum(v, 4)} Hz`) },
      ...response.entries.map((e, i) => ({
        // The entry (xx, yy, zz, tool axis) with the plot's unit, as every series of the page is named.
        label: `${e.name} [${unit}]`,
        stroke: seriesColor(i),
        width: 1.25,
        points: { show: false },
        value: (u, v) => (v == null ? '—' : fmtNum(v)),
      })),
    ],
    cursor: { drag: { x: false, y: false }, points: { size: 6 } },
    legend: legendOptions(),
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

/** The colour of a stiffness: weak (low) is hot, on a log scale (a map spans a factor of several). */
function stiffnessColour(v, range, rgb) {
  if (!Number.isFinite(v) || !range) return MASK_COLOR;
  const t = range[1] > range[0] && range[0] > 0 ? Math.log(range[1] / v) / Math.log(range[1] / range[0]) : 0;
  errorRgb(t, rgb);
  return hexOf(rgb.map((c) => c * 255));
}

/** '#rrggbb' of channels 0 … 255. */
function hexOf(rgb) {
  return `#${rgb.map((c) => Math.round(c).toString(16).padStart(2, '0')).join('')}`;
}

/** The map's card: the canvas, and beside it the colour bar and the hovered point's value. */
function stiffnessMapView(map) {
  const range = mapRange(map);
  const canvas = h('canvas', { class: 'stiffness-map-canvas' });
  const heat = createHeatMap(canvas, { xs: map.x, ys: map.y, xColumn: map.x_label, yColumn: map.y_label, contextOptions: CONTEXT });
  const readout = h('div', { class: 'map-readout' }, 'hover a point for its value');
  const bar = colourBar({ label: map.value_label, unit: map.value_unit, range, gradient: ERROR_GRADIENT, reversed: true, log: true, masked: 'no value: masked' });
  const side = h('div', { class: 'map-side', style: { width: `${SIDE_WIDTH}px` } }, bar, readout);
  const element = card('chart-stiffness-map', 'Lowest stiffness over the workspace', map.file, h('div', { class: 'map-row' }, h('div', { class: 'map-plot' }, canvas), side));
  element.classList.add('map-card');
  canvas.addEventListener('mousemove', (e) => {
    const r = canvas.getBoundingClientRect();
    const cell = heat.cellAt(e.clientX - r.left, e.clientY - r.top);
    if (!cell) return;
    const [i, j] = cell;
    const v = map.values[j][i];
    const value = Number.isFinite(v) ? `${fmtNum(v)} ${map.value_unit}` : 'no value';
    readout.textContent = `${columnLabel(map.x_label)} ${fmtNum(map.x[i], 5)}, ${columnLabel(map.y_label)} ${fmtNum(map.y[j], 5)}: ${value}`;
  });
  const view = { element, canvas, heat, drawn: false };
  view.draw = (roomWidth) => {
    const rgb = [0, 0, 0];
    const tall = Math.max(320, Math.min(700, 0.75 * (window.innerHeight || 800)));
    heat.draw((i, j) => stiffnessColour(map.values[j][i], range, rgb), Math.max(240, roomWidth - SIDE_WIDTH - 40), tall);
    view.drawn = true;
  };
  view.barTitle = () => bar.querySelector('.colour-bar-title').textContent;
  /** The colour drawn at the centre of point [i, j] and the one its value should have ('#rrggbb'). */
  view.cellColour = (i, j) => {
    const at = i >= 0 && i < map.x.length && j >= 0 && j < map.y.length ? heat.cellCentre(i, j) : null;
    if (!at) return null;
    const p = canvas.getContext('2d', CONTEXT).getImageData(at[0], at[1], 1, 1).data;
    const expected = stiffnessColour(map.values[j][i], range, [0, 0, 0]);
    return { drawn: hexOf([p[0], p[1], p[2]]), expected, value: Number.isFinite(map.values[j][i]) };
  };
  return view;
}

export function createStiffnessPlots(data) {
  const response = data.frequency_response;
  const map = data.stiffness_map;
  const bode = [];
  const cards = [];
  if (response) {
    for (const which of ['magnitude', 'phase']) {
      const body = h('div', { class: 'chart-body', style: { minHeight: `${PLOT_HEIGHT + 26}px` } });
      const title = which === 'magnitude' ? 'Dynamic compliance: magnitude' : 'Dynamic compliance: phase';
      const id = `chart-bode-${which}`;
      cards.push(card(id, title, `${response.file} · ${response.entries.length} entries`, body));
      bode.push({ id, which, body, u: null });
    }
  }
  const mapView = map ? stiffnessMapView(map) : null;
  if (mapView) cards.push(mapView.element);
  const grid = h('div', { class: 'charts' }, cards);
  const element = cards.length
    ? h('section', { class: 'charts-section', id: 'stiffness-plots' }, h('div', { class: 'section-head' }, h('h2', null, 'Stiffness')), grid)
    : null;

  let width = 0;
  const ro = new ResizeObserver(() => {
    for (const b of bode) {
      if (!b.u) continue;
      const w = Math.max(200, Math.floor(b.body.clientWidth));
      if (w !== b.u.width) b.u.setSize({ width: w, height: PLOT_HEIGHT });
    }
    if (mapView && mapView.drawn && grid.clientWidth !== width) mapView.draw(grid.clientWidth);
    width = grid.clientWidth;
  });

  return {
    element,
    /** Draws the plots (call once the section is in the document). */
    start() {
      if (!element) return;
      for (const b of bode) {
        b.u = bodeChart(response, b.body, b.which);
        registerPlot(b.id, b.u);
      }
      if (mapView) mapView.draw(grid.clientWidth);
      for (const b of bode) ro.observe(b.body);
      ro.observe(grid);
    },
    /** For the browser test: the map's point [i, j] as drawn and as its value's colour; null without a map. */
    mapCellColour: (i, j) => (mapView ? mapView.cellColour(i, j) : null),
    /** For the browser test: which plots there are and whether their canvases have pixels. */
    state() {
      return {
        bode: bode.map((b) => ({ which: b.which, drawn: !!b.u && painted(b.u.ctx.canvas) })),
        map: mapView
          ? { drawn: mapView.drawn && painted(mapView.canvas), cells: map.x.length * map.y.length, geometry: mapView.heat.geometry(), colourBar: mapView.barTitle(), maskColour: MASK_COLOR }
          : null,
      };
    },
  };
}
