// The workspace map of a `pkm workspace` run (docs/workspace.md, report data `workspace_map`): one heat map,
// one layer at a time, chosen by buttons beside it: the status as categories (where the machine can stand and
// which limit stops it elsewhere), the other layers (δρ, S_x, S_y, S_z, the condition number, the optional
// stiffness, natural frequency and error after calibration) on a colour scale over the reachable cells, every
// other cell masked. A 3-D grid is shown one slice at a time, chosen by a slider. Drawn to scale (heat-map.js).
import { h } from './dom.js';
import { errorRgb, ERROR_GRADIENT } from './colors.js';
import { fmtNum } from './format.js';
import { createHeatMap } from './heat-map.js';
import { colourBar, MASK_COLOR } from './colour-bar.js';
import { columnLabel } from './plot-style.js';

const SIDE_WIDTH = 270;
// The browser test reads cells back (cellColour): a canvas read often is kept in memory, where that is cheap.
const CONTEXT = { willReadFrequently: true };
/** The status categories' colours: green where the machine can stand, a colour per limit elsewhere. */
export const STATUS_COLORS = {
  ok: '#2ca02c',
  unreachable: '#d5d9dd',
  actuator_range: '#ff7f0e',
  joint_angle: '#9467bd',
  singular: '#d62728',
  conditioning: '#8c564b',
};

/** 0 … 1 along the colour scale; a log scale where the layer spans more than a factor of 10 (condition numbers). */
function scaleOf(layer, range) {
  if (!range) return () => 0;
  const [lo, hi] = range;
  const t = isLog(range) ? (v) => Math.log(v / lo) / Math.log(hi / lo) : (v) => (hi > lo ? (v - lo) / (hi - lo) : 0);
  // The hot (red) end is the bad end: high δρ and condition number, low stiffness and frequency.
  return layer.hot === 'low' ? (v) => 1 - t(v) : t;
}

function isLog(range) {
  return !!range && range[0] > 0 && range[1] / range[0] > 10;
}

function hexOf(rgb) {
  return `#${rgb.map((c) => Math.round(c * 255).toString(16).padStart(2, '0')).join('')}`;
}

/** The finite values' range of a layer over the cells where the machine can stand (null when none has one). */
function reachableRange(layer, reachable) {
  let lo = Infinity;
  let hi = -Infinity;
  layer.values.forEach((slice, s) =>
    slice.forEach((row, j) =>
      row.forEach((v, i) => {
        if (!Number.isFinite(v) || !reachable(s, j, i)) return;
        lo = Math.min(lo, v);
        hi = Math.max(hi, v);
      }),
    ),
  );
  return Number.isFinite(lo) ? [lo, hi] : null;
}

const NONE = { element: null, start() {}, state: () => null, setLayer: () => null, setSlice: () => null, cellColour: () => null };

/** What the drawing needs of the data: the cells where the machine can stand and each layer's range there. */
function workspaceModel(map) {
  const status = map.layers.find((l) => l.categorical);
  const okIndex = map.status_names.indexOf('ok');
  // Without a status layer every cell with a value counts as reachable.
  const reachable = status ? (s, j, i) => status.values[s][j][i] === okIndex : () => true;
  return { status, reachable, ranges: map.layers.map((l) => (l.categorical ? null : reachableRange(l, reachable))) };
}

/** The colour of cell [i, j] of slice s in layer k ('#rrggbb'). */
function colourOf(map, model, k, s, j, i, rgb) {
  const layer = map.layers[k];
  const v = layer.values[s][j][i];
  if (layer.categorical) return Number.isInteger(v) ? STATUS_COLORS[map.status_names[v]] ?? MASK_COLOR : MASK_COLOR;
  // Outside the reachable region a value (where the file has one) is not the machine's: masked, not scaled.
  if (!Number.isFinite(v) || !model.reachable(s, j, i) || !model.ranges[k]) return MASK_COLOR;
  errorRgb(scaleOf(layer, model.ranges[k])(v), rgb);
  return hexOf(rgb);
}

/** The legend of a layer: its colour bar, or the status categories with their cells in the slice. */
function fillLegend(legend, map, layer, range, slice) {
  legend.textContent = '';
  if (!layer.categorical) {
    legend.appendChild(colourBar({ label: layer.label, unit: layer.unit, range, gradient: ERROR_GRADIENT, reversed: layer.hot === 'low', log: isLog(range), masked: 'not reachable: masked' }));
    return;
  }
  const counts = new Map();
  for (const row of layer.values[slice]) for (const v of row) if (Number.isInteger(v)) counts.set(v, (counts.get(v) ?? 0) + 1);
  legend.appendChild(h('div', { class: 'colour-bar-title' }, 'status (cells)'));
  map.status_names.forEach((name, k) => {
    if (!counts.has(k)) return;
    legend.appendChild(h('span', { class: 'workspace-key', dataset: { status: name } },
      h('span', { class: 'workspace-swatch', style: { background: STATUS_COLORS[name] ?? MASK_COLOR } }), `${name.replace('_', ' ')} ${counts.get(k)}`));
  });
}

/** "x [mm] -40, z [mm] 500: ok · delta_rho 1.2 · …" of cell [i, j] of a slice. */
function cellText(map, slice, i, j) {
  const parts = map.layers.map((layer) => {
    const v = layer.values[slice][j][i];
    if (layer.categorical) return Number.isInteger(v) ? map.status_names[v] : 'no cell';
    return `${layer.id} ${Number.isFinite(v) ? fmtNum(v) : '—'}${layer.unit && Number.isFinite(v) ? ` ${layer.unit}` : ''}`;
  });
  return `${columnLabel(map.x_label)} ${fmtNum(map.x[i], 5)}, ${columnLabel(map.y_label)} ${fmtNum(map.y[j], 5)}: ${parts.join(' · ')}`;
}

/** The section: the map's card with the canvas and, beside it, the layer buttons, slice slider, legend, readout. */
function workspaceDom(map, slices, slice, { onLayer, onSlice }) {
  const canvas = h('canvas', { class: 'workspace-map-canvas' });
  const legend = h('div', { class: 'workspace-map-legend' });
  const readout = h('div', { class: 'map-readout' }, 'hover a cell for its values');
  const buttons = map.layers.map((layer, k) =>
    h('button', { class: 'btn workspace-layer', type: 'button', dataset: { layer: layer.id }, onclick: () => onLayer(k) }, layer.label),
  );
  const sliceLabel = h('span', { class: 'workspace-slice-label' });
  const sliceInput = map.slices.length
    ? h('input', { id: 'workspace-slice', type: 'range', min: '0', max: String(slices - 1), step: '1', value: String(slice), oninput: (e) => onSlice(Number(e.target.value)) })
    : null;
  const side = h(
    'div',
    { class: 'map-side', style: { width: `${SIDE_WIDTH}px` } },
    h('div', { class: 'workspace-controls' }, buttons),
    sliceInput ? h('label', { class: 'workspace-slice' }, sliceInput, sliceLabel) : null,
    legend,
    readout,
  );
  const cells = `${map.x.length} × ${map.y.length}${map.slices.length ? ` × ${slices}` : ''} cells shown`;
  const element = h(
    'section',
    { class: 'charts-section', id: 'workspace-map' },
    h('div', { class: 'section-head' }, h('h2', null, 'Workspace map'), h('span', { class: 'hint' }, `${map.file} · ${cells}`)),
    h('article', { class: 'chart-card map-card', id: 'chart-workspace-map' }, h('div', { class: 'map-row' }, h('div', { class: 'map-plot' }, canvas), side)),
  );
  return { element, canvas, legend, readout, buttons, sliceInput, sliceLabel };
}

export function createWorkspaceMap(data) {
  const map = data.workspace_map;
  if (!map) return NONE;
  const nx = map.x.length;
  const ny = map.y.length;
  const slices = map.slices.length ? map.slices.length : 1;
  const model = workspaceModel(map);
  // The status first: where the machine can stand at all, and which limit stops it elsewhere, is what an
  // engineer asks of a workspace before any figure inside it; the quantity layers only mean something there.
  let layerIndex = Math.max(0, map.layers.indexOf(model.status));
  // The slice through the grid's centre (the working height the grid was centred on) first.
  let slice = Math.floor((slices - 1) / 2);
  let drawn = false;
  const dom = workspaceDom(map, slices, slice, { onLayer: (k) => select(k), onSlice: (k) => choose(k) });
  const heat = createHeatMap(dom.canvas, { xs: map.x, ys: map.y, xColumn: map.x_label, yColumn: map.y_label, contextOptions: CONTEXT });

  function draw() {
    const rgb = [0, 0, 0];
    const room = Math.max(240, dom.element.clientWidth - SIDE_WIDTH - 40);
    const tall = Math.max(320, Math.min(760, 0.8 * (window.innerHeight || 800)));
    heat.draw((i, j) => colourOf(map, model, layerIndex, slice, j, i, rgb), room, tall);
    fillLegend(dom.legend, map, map.layers[layerIndex], model.ranges[layerIndex], slice);
    dom.buttons.forEach((b, k) => b.classList.toggle('active', k === layerIndex));
    if (dom.sliceInput) dom.sliceLabel.textContent = `${columnLabel(map.slice_label)} ${fmtNum(map.slices[slice], 5)}`;
    drawn = true;
  }

  function select(k) {
    if (k < 0 || k >= map.layers.length) return null;
    layerIndex = k;
    draw();
    return map.layers[k].id;
  }

  function choose(k) {
    if (!(k >= 0 && k < slices)) return null;
    slice = k;
    if (dom.sliceInput) dom.sliceInput.value = String(k);
    draw();
    return slice;
  }

  dom.canvas.addEventListener('mousemove', (e) => {
    const r = dom.canvas.getBoundingClientRect();
    const cell = heat.cellAt(e.clientX - r.left, e.clientY - r.top);
    if (cell) dom.readout.textContent = cellText(map, slice, cell[0], cell[1]);
  });

  let width = 0;
  const ro = new ResizeObserver(() => {
    if (drawn && dom.element.clientWidth !== width) draw();
    width = dom.element.clientWidth;
  });
  const context = () => dom.canvas.getContext('2d', CONTEXT);

  return {
    element: dom.element,
    /** Draws the map (call once the section is in the document). */
    start() {
      draw();
      width = dom.element.clientWidth;
      ro.observe(dom.element);
    },
    setLayer: (id) => select(map.layers.findIndex((l) => l.id === id)),
    setSlice: choose,
    /**
     * For the browser test: the layers, the one shown, the slice, whether the canvas has pixels, the cells,
     * the plot's geometry, the colour bar's title (null for the status) and the colour of masked cells.
     */
    state() {
      const c = dom.canvas;
      const px = c.width && c.height ? context().getImageData(0, 0, c.width, c.height).data : [];
      let painted = false;
      for (let k = 3; k < px.length && !painted; k += 4) painted = px[k] !== 0;
      const bar = dom.legend.querySelector('.colour-bar .colour-bar-title');
      const layers = map.layers.map((l) => l.id);
      return { layers, layer: layers[layerIndex], slice, slices, cells: nx * ny, drawn: drawn && painted, geometry: heat.geometry(), colourBar: bar ? bar.textContent : null, maskColour: MASK_COLOR };
    },
    /**
     * The colour drawn at the centre of cell [i, j] of the slice shown ('#rrggbb'), the colour it should have,
     * and whether the machine can stand there.
     */
    cellColour(i, j) {
      const at = i >= 0 && i < nx && j >= 0 && j < ny ? heat.cellCentre(i, j) : null;
      if (!at) return null;
      const p = context().getImageData(at[0], at[1], 1, 1).data;
      const expected = colourOf(map, model, layerIndex, slice, j, i, [0, 0, 0]);
      return { drawn: hexOf([p[0] / 255, p[1] / 255, p[2] / 255]), expected, reachable: model.reachable(slice, j, i) };
    },
  };
}
