// A heat map on a canvas, one cell per grid point, shared by the workspace and the stiffness maps. Where both
// axes are lengths in one unit (a section x–z in mm) the map is drawn to scale, one millimetre as long across
// as up, so that the reachable region has its true shape; otherwise it fills the space it gets. Axes carry
// nice ticks in the grid's own units and their labels with the unit ("x [mm]").
import { columnLabel, columnParts, FONT, LABEL_FONT } from './plot-style.js';

const PAD = { left: 66, right: 14, top: 10, bottom: 40 };
const TICK_SPACING_PX = 70;

/** The cells' outer edges along an axis of cell centres (uniform spacing; one cell: ±0.5). */
export function cellEdges(values) {
  const n = values.length;
  if (n < 2) return [values[0] - 0.5, values[0] + 0.5];
  const step = (values[n - 1] - values[0]) / (n - 1);
  return [values[0] - step / 2, values[n - 1] + step / 2];
}

/**
 * Ticks 1, 2 or 5 × 10^k apart, about `count` of them within [lo, hi], as [value, label]: every label with the
 * decimals the step needs, so that a column of them reads alike ("300", "1100", not "300.0", "1100").
 */
function niceTicks(lo, hi, count) {
  const raw = (hi - lo) / Math.max(1, count);
  if (!(raw > 0)) return [[lo, String(lo)]];
  const p = 10 ** Math.floor(Math.log10(raw));
  const step = [1, 2, 5, 10].map((m) => m * p).find((s) => s >= raw) ?? 10 * p;
  const decimals = Math.max(0, -Math.floor(Math.log10(step) + 1e-9));
  const ticks = [];
  for (let k = Math.ceil(lo / step); k * step <= hi + step * 1e-9; k++) {
    const text = (k * step).toFixed(decimals);
    ticks.push([k * step, /^-0(\.0*)?$/.test(text) ? text.slice(1) : text]);
  }
  return ticks;
}

/**
 * The plot area for a map of `xs` × `ys` cells within `maxWidth` × `maxHeight` CSS pixels: to scale where the
 * axes' units are the same length unit.
 */
export function mapLayout(xs, ys, xColumn, yColumn, maxWidth, maxHeight) {
  const ex = cellEdges(xs);
  const ey = cellEdges(ys);
  const ux = columnParts(xColumn).unit;
  const toScale = ux !== '' && ux === columnParts(yColumn).unit && ux !== 'deg' && ux !== 'rad';
  const room = { w: Math.max(60, maxWidth - PAD.left - PAD.right), h: Math.max(60, maxHeight - PAD.top - PAD.bottom) };
  let plotW = room.w;
  let plotH = room.h;
  if (toScale) {
    const aspect = (ex[1] - ex[0]) / (ey[1] - ey[0]);
    plotW = Math.min(room.w, room.h * aspect);
    plotH = plotW / aspect;
  }
  return {
    pad: PAD,
    plotW,
    plotH,
    width: Math.ceil(plotW + PAD.left + PAD.right),
    height: Math.ceil(plotH + PAD.top + PAD.bottom),
    cellW: plotW / xs.length,
    cellH: plotH / ys.length,
    extent: { x: ex, y: ey },
    toScale,
  };
}

/** Sizes the canvas to the layout at the device's pixel ratio and clears it; gives its 2-D context. */
function startCanvas(canvas, layout, contextOptions) {
  const pr = window.devicePixelRatio || 1;
  canvas.width = Math.round(layout.width * pr);
  canvas.height = Math.round(layout.height * pr);
  canvas.style.width = `${layout.width}px`;
  canvas.style.height = `${layout.height}px`;
  const ctx = canvas.getContext('2d', contextOptions);
  ctx.setTransform(pr, 0, 0, pr, 0, 0);
  ctx.clearRect(0, 0, layout.width, layout.height);
  return { ctx, pr };
}

/** Ticks, numbers and the axes' labels with their units. */
function drawAxes(ctx, layout, xColumn, yColumn) {
  const { pad, plotW, plotH, extent } = layout;
  const px = (v) => pad.left + ((v - extent.x[0]) / (extent.x[1] - extent.x[0])) * plotW;
  const py = (v) => pad.top + plotH - ((v - extent.y[0]) / (extent.y[1] - extent.y[0])) * plotH;
  ctx.fillStyle = '#56616b';
  ctx.strokeStyle = '#9aa5af';
  ctx.lineWidth = 1;
  ctx.font = FONT;
  ctx.textAlign = 'center';
  ctx.textBaseline = 'top';
  for (const [v, text] of niceTicks(extent.x[0], extent.x[1], plotW / TICK_SPACING_PX)) {
    const x = Math.round(px(v)) + 0.5;
    ctx.beginPath();
    ctx.moveTo(x, pad.top + plotH);
    ctx.lineTo(x, pad.top + plotH + 4);
    ctx.stroke();
    ctx.fillText(text, x, pad.top + plotH + 6);
  }
  ctx.textAlign = 'right';
  ctx.textBaseline = 'middle';
  for (const [v, text] of niceTicks(extent.y[0], extent.y[1], plotH / TICK_SPACING_PX)) {
    const y = Math.round(py(v)) + 0.5;
    ctx.beginPath();
    ctx.moveTo(pad.left - 4, y);
    ctx.lineTo(pad.left, y);
    ctx.stroke();
    ctx.fillText(text, pad.left - 6, y);
  }
  ctx.font = LABEL_FONT;
  ctx.textAlign = 'center';
  ctx.textBaseline = 'alphabetic';
  ctx.fillText(columnLabel(xColumn), pad.left + plotW / 2, pad.top + plotH + 34);
  ctx.save();
  ctx.translate(14, pad.top + plotH / 2);
  ctx.rotate(-Math.PI / 2);
  ctx.fillText(columnLabel(yColumn), 0, 0);
  ctx.restore();
}

/**
 * A heat map over cell centres `xs` (columns) and `ys` (rows) of CSV columns `xColumn`, `yColumn`. draw()
 * paints each cell in colourAt(i, j) within the room given; cellAt() finds the cell under a mouse position.
 */
export function createHeatMap(canvas, { xs, ys, xColumn, yColumn, contextOptions }) {
  let layout = null;
  let pr = 1;
  return {
    draw(colourAt, maxWidth, maxHeight) {
      layout = mapLayout(xs, ys, xColumn, yColumn, maxWidth, maxHeight);
      const started = startCanvas(canvas, layout, contextOptions);
      pr = started.pr;
      const { ctx } = started;
      const { pad, cellW, cellH } = layout;
      for (let j = 0; j < ys.length; j++) {
        for (let i = 0; i < xs.length; i++) {
          ctx.fillStyle = colourAt(i, j);
          // Row 0 is the lowest value of the second axis: drawn at the bottom. Cells overlap by a fraction of a
          // pixel so that no seam shows between them.
          const x = pad.left + i * cellW;
          const y = pad.top + (ys.length - 1 - j) * cellH;
          ctx.fillRect(x, y, cellW + 0.5, cellH + 0.5);
        }
      }
      // The overlap may not spill beyond the plot's edge.
      ctx.clearRect(pad.left + layout.plotW, pad.top, 1, layout.plotH + 1);
      ctx.clearRect(pad.left, pad.top + layout.plotH, layout.plotW + 1, 1);
      drawAxes(ctx, layout, xColumn, yColumn);
      return layout;
    },
    /** The cell [i, j] under a mouse position in CSS pixels, or null. */
    cellAt(x, y) {
      if (!layout) return null;
      const i = Math.floor((x - layout.pad.left) / layout.cellW);
      const j = ys.length - 1 - Math.floor((y - layout.pad.top) / layout.cellH);
      return i >= 0 && i < xs.length && j >= 0 && j < ys.length ? [i, j] : null;
    },
    /** The device pixel at the centre of cell [i, j]. */
    cellCentre(i, j) {
      if (!layout) return null;
      return [
        Math.round((layout.pad.left + (i + 0.5) * layout.cellW) * pr),
        Math.round((layout.pad.top + (ys.length - 1 - j + 0.5) * layout.cellH) * pr),
      ];
    },
    /** For the browser test: the plot area in CSS pixels, the grid's extent and whether it is to scale. */
    geometry() {
      if (!layout) return null;
      return { plot: { width: layout.plotW, height: layout.plotH }, extent: layout.extent, toScale: layout.toScale, xLabel: columnLabel(xColumn), yLabel: columnLabel(yColumn) };
    },
  };
}
