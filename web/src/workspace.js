// The workspace map of a `pkm workspace` run (docs/workspace.md, report data `workspace_map`): one heat map,
// one layer at a time, chosen by buttons: the status as categories (where the machine can stand and which
// limit stops it elsewhere), the other layers (δρ, S_x, S_y, S_z, the condition number, the optional stiffness,
// natural frequency and error after calibration) on a colour scale over the whole layer, grey where a cell
// has no value. A 3-D grid is shown one slice at a time, chosen by a slider. A canvas, one cell per grid point.
import { h } from './dom.js';
import { errorRgb, ERROR_GRADIENT } from './colors.js';
import { fmtNum } from './format.js';
import { labelMapAxes, startMapCanvas } from './stiffness.js';

const MAP_HEIGHT = 360;
const NONE_COLOR = '#d5d9dd';
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

/** The finite values' range of a layer over all its slices (null when it has none). */
function layerRange(layer) {
  let lo = Infinity;
  let hi = -Infinity;
  for (const slice of layer.values) {
    for (const row of slice) {
      for (const v of row) {
        if (!Number.isFinite(v)) continue;
        lo = Math.min(lo, v);
        hi = Math.max(hi, v);
      }
    }
  }
  return Number.isFinite(lo) ? [lo, hi] : null;
}

/** 0 … 1 along the colour scale; a log scale where the layer spans more than a factor of 10 (condition numbers). */
function scaleOf(layer, range) {
  if (!range) return () => 0;
  const [lo, hi] = range;
  const log = lo > 0 && hi / lo > 10;
  const t = log ? (v) => Math.log(v / lo) / Math.log(hi / lo) : (v) => (hi > lo ? (v - lo) / (hi - lo) : 0);
  // The hot (red) end is the bad end: high δρ and condition number, low stiffness and frequency.
  return layer.hot === 'low' ? (v) => 1 - t(v) : t;
}

function hexOf(rgb) {
  return `#${rgb.map((c) => Math.round(c * 255).toString(16).padStart(2, '0')).join('')}`;
}

export function createWorkspaceMap(data) {
  const map = data.workspace_map;
  if (!map) return { element: null, start() {}, state: () => null, setLayer: () => null, setSlice: () => null, cellColour: () => null };
  const nx = map.x.length;
  const ny = map.y.length;
  const slices = map.slices.length ? map.slices.length : 1;
  const ranges = map.layers.map(layerRange);
  let layerIndex = Math.max(0, map.layers.findIndex((l) => l.id === 'delta_rho'));
  if (!map.layers[layerIndex]) layerIndex = 0;
  // The slice through the grid's centre first.
  let slice = Math.floor((slices - 1) / 2);
  let layout = null;
  let drawn = false;

  const canvas = h('canvas', { class: 'workspace-map-canvas' });
  const legend = h('div', { class: 'workspace-map-legend' });
  const readout = h('div', { class: 'stiffness-map-readout' }, 'hover a cell for its values');
  const buttons = map.layers.map((layer, k) =>
    h('button', { class: 'btn workspace-layer', type: 'button', dataset: { layer: layer.id }, onclick: () => select(k) }, layer.label),
  );
  const sliceLabel = h('span', { class: 'workspace-slice-label' });
  const sliceInput = map.slices.length
    ? h('input', { id: 'workspace-slice', type: 'range', min: '0', max: String(slices - 1), step: '1', value: String(slice), oninput: (e) => choose(Number(e.target.value)) })
    : null;
  const body = h('div', { class: 'chart-body' }, canvas, legend, readout);
  const controls = h('div', { class: 'workspace-controls' }, buttons, sliceInput ? h('span', { class: 'workspace-slice' }, sliceInput, sliceLabel) : null);
  const element = h(
    'section',
    { class: 'charts-section', id: 'workspace-map' },
    h('div', { class: 'section-head' }, h('h2', null, 'Workspace map'), h('span', { class: 'hint' }, `${map.file} · ${nx} × ${ny}${map.slices.length ? ` × ${slices}` : ''} cells shown`)),
    h('article', { class: 'chart-card' }, controls, body),
  );

  function colourOf(layer, range, v, rgb) {
    if (layer.categorical) return Number.isInteger(v) ? STATUS_COLORS[map.status_names[v]] ?? NONE_COLOR : NONE_COLOR;
    if (!Number.isFinite(v) || !range) return NONE_COLOR;
    errorRgb(scaleOf(layer, range)(v), rgb);
    return hexOf(rgb);
  }

  function drawLegend(layer, range) {
    legend.textContent = '';
    if (layer.categorical) {
      const counts = new Map();
      for (const row of layer.values[slice]) for (const v of row) if (Number.isInteger(v)) counts.set(v, (counts.get(v) ?? 0) + 1);
      map.status_names.forEach((name, k) => {
        if (!counts.has(k)) return;
        legend.appendChild(h('span', { class: 'workspace-key', dataset: { status: name } },
          h('span', { class: 'workspace-swatch', style: { background: STATUS_COLORS[name] ?? NONE_COLOR } }), `${name.replace('_', ' ')} ${counts.get(k)}`));
      });
      return;
    }
    const unit = layer.unit ? ` ${layer.unit}` : '';
    const low = range ? `${fmtNum(range[0])}${unit}` : '—';
    const high = range ? `${fmtNum(range[1])}${unit}` : '—';
    const reversed = layer.hot === 'low';
    legend.append(
      h('span', null, reversed ? high : low),
      h('span', { class: 'workspace-ramp', style: { background: ERROR_GRADIENT } }),
      h('span', null, reversed ? low : high),
      h('span', { class: 'stiffness-map-none' }, 'no value'),
    );
  }

  function draw() {
    const layer = map.layers[layerIndex];
    const range = ranges[layerIndex];
    const width = Math.max(200, Math.floor(body.clientWidth));
    const { ctx, pad, plotW, plotH, pr } = startMapCanvas(canvas, width, MAP_HEIGHT, 60, CONTEXT);
    const cellW = plotW / nx;
    const cellH = plotH / ny;
    const rgb = [0, 0, 0];
    const values = layer.values[slice];
    for (let j = 0; j < ny; j++) {
      for (let i = 0; i < nx; i++) {
        ctx.fillStyle = colourOf(layer, range, values[j][i], rgb);
        // Row 0 is the lowest value of the second axis: drawn at the bottom.
        ctx.fillRect(pad.left + i * cellW, pad.top + (ny - 1 - j) * cellH, Math.ceil(cellW), Math.ceil(cellH));
      }
    }
    labelMapAxes(ctx, map, pad, plotW, plotH, cellW, cellH);
    layout = { pad, cellW, cellH, pr };
    drawLegend(layer, range);
    buttons.forEach((b, k) => b.classList.toggle('active', k === layerIndex));
    if (sliceInput) sliceLabel.textContent = `${map.slice_label} ${fmtNum(map.slices[slice], 5)}`;
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
    if (sliceInput) sliceInput.value = String(k);
    draw();
    return slice;
  }

  /** The cell [i, j] under a mouse position, or null. */
  function cellAt(x, y) {
    if (!layout) return null;
    const i = Math.floor((x - layout.pad.left) / layout.cellW);
    const j = ny - 1 - Math.floor((y - layout.pad.top) / layout.cellH);
    return i >= 0 && i < nx && j >= 0 && j < ny ? [i, j] : null;
  }

  canvas.addEventListener('mousemove', (e) => {
    const r = canvas.getBoundingClientRect();
    const cell = cellAt(e.clientX - r.left, e.clientY - r.top);
    if (!cell) return;
    const [i, j] = cell;
    const parts = map.layers.map((layer) => {
      const v = layer.values[slice][j][i];
      if (layer.categorical) return Number.isInteger(v) ? map.status_names[v] : 'no cell';
      return `${layer.id} ${Number.isFinite(v) ? fmtNum(v) : '—'}${layer.unit && Number.isFinite(v) ? ` ${layer.unit}` : ''}`;
    });
    const where = `${map.x_label} ${fmtNum(map.x[i], 5)}, ${map.y_label} ${fmtNum(map.y[j], 5)}`;
    readout.textContent = `${where}: ${parts.join(' · ')}`;
  });

  const ro = new ResizeObserver(() => {
    if (drawn) draw();
  });

  return {
    element,
    /** Draws the map (call once the section is in the document). */
    start() {
      draw();
      ro.observe(body);
    },
    setLayer: (id) => select(map.layers.findIndex((l) => l.id === id)),
    setSlice: choose,
    /** For the browser test: the layers, the one shown, whether the canvas has pixels, the cells shown. */
    state() {
      const px = canvas.width && canvas.height ? canvas.getContext('2d', CONTEXT).getImageData(0, 0, canvas.width, canvas.height).data : [];
      let painted = false;
      for (let k = 3; k < px.length && !painted; k += 4) painted = px[k] !== 0;
      return { layers: map.layers.map((l) => l.id), layer: map.layers[layerIndex].id, slice, slices, cells: nx * ny, drawn: drawn && painted };
    },
    /** The colour drawn at the centre of cell [i, j] of the slice shown ('#rrggbb'), and the colour it should have. */
    cellColour(i, j) {
      if (!layout || !(i >= 0 && i < nx && j >= 0 && j < ny)) return null;
      const x = Math.round((layout.pad.left + (i + 0.5) * layout.cellW) * layout.pr);
      const y = Math.round((layout.pad.top + (ny - 1 - j + 0.5) * layout.cellH) * layout.pr);
      const p = canvas.getContext('2d', CONTEXT).getImageData(x, y, 1, 1).data;
      const layer = map.layers[layerIndex];
      const expected = colourOf(layer, ranges[layerIndex], layer.values[slice][j][i], [0, 0, 0]);
      return { drawn: hexOf([p[0] / 255, p[1] / 255, p[2] / 255]), expected };
    },
  };
}
