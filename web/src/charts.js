// One uPlot chart per `charts` entry. Drag-selecting a window zooms every chart to it (as a time window, so
// charts over path length follow too), double-click resets; limits are dashed lines; a vertical line marks
// the animation's current time. Charts are built when they come near the viewport, the rest when idle.
import uPlot from 'uplot';
import { h } from './dom.js';
import { seriesColor } from './colors.js';
import { fmtNum } from './format.js';
import { axisLabel, legendOptions } from './plot-style.js';
import { registerPlot, unregisterPlot } from './plot-registry.js';

const PLOT_HEIGHT = 230;
const AXIS = { values: tickValues, stroke: '#56616b', grid: { stroke: '#e7ebee', width: 1 }, ticks: { stroke: '#cfd6dc', width: 1, size: 4 } };
const FONT = '11px system-ui, -apple-system, "Segoe UI", Roboto, sans-serif';
const LABEL_FONT = '600 11px system-ui, -apple-system, "Segoe UI", Roboto, sans-serif';
const LIMIT_COLOR = '#c62828';

/** y for x by linear interpolation over the non-decreasing xs (clamped at the ends). */
function interp(xs, ys, x) {
  const n = xs.length;
  if (n === 0) return x;
  if (!(x > xs[0])) return ys[0];
  if (x >= xs[n - 1]) return ys[n - 1];
  let lo = 0;
  let hi = n - 1;
  while (hi - lo > 1) {
    const mid = (lo + hi) >> 1;
    if (xs[mid] <= x) lo = mid;
    else hi = mid;
  }
  const dx = xs[hi] - xs[lo];
  return dx > 0 ? ys[lo] + ((ys[hi] - ys[lo]) * (x - xs[lo])) / dx : ys[lo];
}

/** Decimals that show every tick of increment `incr` exactly. */
function decimalsFor(incr) {
  if (!(incr > 0)) return 0;
  let d = Math.max(0, -Math.floor(Math.log10(incr) + 1e-9));
  while (d < 10 && Math.abs(incr * 10 ** d - Math.round(incr * 10 ** d)) > 1e-6) d++;
  return d;
}

/** Tick labels: plain numbers with the decimals the tick step needs (no grouping, no "-0"). */
function tickValues(u, splits, axisIdx, space, incr) {
  const d = decimalsFor(incr);
  return splits.map((v) => {
    if (v == null) return '';
    const a = Math.abs(v);
    if (a !== 0 && (a >= 1e7 || d > 7)) return v.toExponential(2).replace('e+', 'e');
    const t = v.toFixed(d);
    return /^-0(\.0*)?$/.test(t) ? t.slice(1) : t;
  });
}

/** Index of the value in non-decreasing xs nearest to x. */
function nearestIndex(xs, x) {
  const n = xs.length;
  if (n === 0) return null;
  let lo = 0;
  let hi = n - 1;
  if (!(x > xs[0])) return 0;
  if (x >= xs[hi]) return hi;
  while (hi - lo > 1) {
    const mid = (lo + hi) >> 1;
    if (xs[mid] <= x) lo = mid;
    else hi = mid;
  }
  return x - xs[lo] <= xs[hi] - x ? lo : hi;
}

/** Auto-sizes an axis to its longest tick label. */
function axisSize(self, values, axisIdx, cycleNum) {
  const axis = self.axes[axisIdx];
  if (cycleNum > 1) return axis._size;
  let size = axis.ticks.size + axis.gap;
  const longest = (values || []).reduce((acc, s) => (s != null && String(s).length > acc.length ? String(s) : acc), '');
  if (longest) {
    self.ctx.font = axis.font[0];
    size += self.ctx.measureText(longest).width / uPlot.pxRatio;
  }
  return Math.ceil(size) + 2;
}

/** y range: the data plus the limits that are near it (farther ones are shown as off-scale labels). */
function yRange(limits) {
  return (u, min, max) => {
    if (min == null || max == null || !Number.isFinite(min) || !Number.isFinite(max)) return [0, 1];
    let lo = min;
    let hi = max;
    const span = max - min || Math.abs(max) || 1;
    for (const l of limits) {
      if (l.value >= min - 0.6 * span && l.value <= max + 0.6 * span) {
        lo = Math.min(lo, l.value);
        hi = Math.max(hi, l.value);
      }
    }
    return uPlot.rangeNum(lo, hi, 0.08, true);
  };
}

function drawLimits(limits) {
  return (u) => {
    if (!limits.length) return;
    const { ctx, bbox } = u;
    const pr = uPlot.pxRatio;
    const right = bbox.left + bbox.width - 4 * pr;
    const top = bbox.top;
    const bottom = bbox.top + bbox.height;
    let above = 0;
    let below = 0;
    ctx.save();
    ctx.font = `${11 * pr}px system-ui, -apple-system, "Segoe UI", Roboto, sans-serif`;
    ctx.textAlign = 'right';
    ctx.lineJoin = 'round';
    for (const l of limits) {
      const y = u.valToPos(l.value, 'y', true);
      let text = l.label;
      let ty;
      if (y >= top - 0.5 && y <= bottom + 0.5) {
        ctx.strokeStyle = LIMIT_COLOR;
        ctx.lineWidth = pr;
        ctx.setLineDash([6 * pr, 4 * pr]);
        ctx.beginPath();
        ctx.moveTo(bbox.left, Math.round(y) + 0.5);
        ctx.lineTo(bbox.left + bbox.width, Math.round(y) + 0.5);
        ctx.stroke();
        ctx.setLineDash([]);
        ty = y - top < 14 * pr ? y + 12 * pr : y - 4 * pr;
        ctx.globalAlpha = 1;
      } else if (y < top) {
        text += ' \u2191';
        ty = top + (12 + 13 * above++) * pr;
        ctx.globalAlpha = 0.75;
      } else {
        text += ' \u2193';
        ty = bottom - (5 + 13 * below++) * pr;
        ctx.globalAlpha = 0.75;
      }
      ctx.lineWidth = 3 * pr;
      ctx.strokeStyle = 'rgba(255,255,255,0.9)';
      ctx.strokeText(text, right, ty);
      ctx.fillStyle = LIMIT_COLOR;
      ctx.fillText(text, right, ty);
    }
    ctx.restore();
  };
}

/** A chart's card: title, subtitle (quantity with unit, series count) and the body uPlot draws into. */
function chartItem(def) {
  const sub = `${axisLabel(def.y_label, def.y_unit)} · ${def.series.length} series`;
  const body = h('div', { class: 'chart-body', style: { minHeight: `${PLOT_HEIGHT + 26}px` } });
  const card = h(
    'article',
    { class: 'chart-card', id: `chart-${def.id}`, dataset: { chartId: def.id } },
    h('header', { class: 'chart-head' }, h('h3', null, def.title), h('span', { class: 'chart-sub' }, sub)),
    body,
  );
  return { def, card, body, u: null, mode: 'time', cursorEl: null, toTime: (x) => x, fromTime: (t) => t };
}

/**
 * uPlot's options of a chart over time or, with `useS`, over path length: axes labelled with their units, each
 * series by its name in its palette colour, drag to zoom (`on.zoomTo`), the limits, the animation's cursor.
 */
function chartOptions(item, useS, on) {
  const { def } = item;
  const unit = def.y_unit;
  return {
    width: Math.max(200, item.body.clientWidth),
    height: PLOT_HEIGHT,
    scales: { x: { time: false }, y: { range: yRange(def.limits) } },
    axes: [
      { ...AXIS, font: FONT, labelFont: LABEL_FONT, label: useS ? axisLabel('path length', 'mm') : axisLabel('time', 's'), labelSize: 16, size: 30, labelGap: 0 },
      { ...AXIS, font: FONT, labelFont: LABEL_FONT, label: axisLabel(def.y_label, unit), labelSize: 16, size: axisSize, gap: 4 },
    ],
    series: [
      {
        label: useS ? 'path length' : 'time',
        value: (u, v) => (v == null ? '—' : useS ? `${fmtNum(v, 5)} mm` : `${v.toFixed(3)} s`),
      },
      ...def.series.map((sr, i) => ({
        label: sr.name,
        stroke: seriesColor(i),
        width: 1.25,
        dash: sr.dash ? [6, 4] : undefined,
        points: { show: false },
        // A name with its unit ("P1 [N]") needs none after the value.
        value: (u, v) => (v == null ? '—' : unit && !sr.name.includes('[') ? `${fmtNum(v)} ${unit}` : fmtNum(v)),
      })),
    ],
    cursor: {
      drag: { x: true, y: false, setScale: false },
      points: { size: 6 },
      bind: {
        dblclick: () => (e) => {
          if (e.button === 0) on.zoomTo(null);
          return null;
        },
      },
    },
    legend: legendOptions(),
    hooks: {
      setSelect: [
        (u) => {
          const w = u.select.width;
          if (w < 3) return;
          const a = item.toTime(u.posToVal(u.select.left, 'x'));
          const b = item.toTime(u.posToVal(u.select.left + w, 'x'));
          u.setSelect({ left: 0, top: 0, width: 0, height: 0 }, false);
          on.zoomTo([Math.min(a, b), Math.max(a, b)]);
        },
      ],
      draw: [drawLimits(def.limits)],
      setScale: [(u, key) => key === 'x' && on.placeCursor(item)],
      setSize: [() => on.placeCursor(item)],
      setCursor: [() => on.showAnimLegend(item)],
    },
  };
}

/** The x-axis switch (time | path length). */
function xAxisToggle(onclick) {
  return h(
    'button',
    { id: 'x-axis-toggle', class: 'seg-toggle', type: 'button', title: 'x axis of the charts over the path: time or path length', 'aria-pressed': 'false', onclick },
    h('span', { class: 'seg-label' }, 'x:'),
    h('span', { class: 'seg on', dataset: { mode: 'time' } }, 'time'),
    h('span', { class: 'seg', dataset: { mode: 's' } }, 'path length'),
  );
}

/**
 * Builds the charts on screen now, the others when they come near the viewport or when the page is idle, so that
 * the page is ready before every chart exists; resizes the built ones with their card.
 */
function lazyBuilder(items, build) {
  const idle = window.requestIdleCallback ? (f) => window.requestIdleCallback(f, { timeout: 400 }) : (f) => setTimeout(f, 60);
  const ro = new ResizeObserver((entries) => {
    for (const e of entries) {
      const item = items.find((it) => it.body === e.target);
      if (!item || !item.u) continue;
      const w = Math.max(200, Math.floor(item.body.clientWidth));
      if (w !== item.u.width) item.u.setSize({ width: w, height: PLOT_HEIGHT });
    }
  });
  return function start() {
    const vh = window.innerHeight || document.documentElement.clientHeight;
    for (const item of items) {
      const r = item.card.getBoundingClientRect();
      if (!item.u && r.bottom >= -120 && r.top <= vh + 120) build(item);
    }
    items.forEach((it) => ro.observe(it.body));
    if ('IntersectionObserver' in window) {
      const io = new IntersectionObserver(
        (entries) => {
          for (const e of entries) {
            if (!e.isIntersecting) continue;
            const item = items.find((it) => it.card === e.target);
            if (item) build(item);
            io.unobserve(e.target);
          }
        },
        { rootMargin: '300px 0px' },
      );
      items.forEach((it) => !it.u && io.observe(it.card));
    }
    const next = () => {
      const item = items.find((it) => !it.u);
      if (!item) return;
      build(item);
      idle(next);
    };
    idle(next);
  };
}

/** Sets a built chart's x range to the zoom's time window (or to all its data), in its own x units. */
function applyZoom(item, state) {
  if (!item.u) return;
  const xs = item.u.data[0];
  let [a, b] = state.zoom ? [item.fromTime(state.zoom[0]), item.fromTime(state.zoom[1])] : [xs[0], xs[xs.length - 1]];
  if (state.zoom && !(b > a)) {
    const eps = Math.max(Math.abs(a) * 1e-6, 1e-9);
    a -= eps;
    b += eps;
  }
  item.u.setScale('x', { min: a, max: b });
}

/** Moves a chart's line of the animation's time (hidden when that time is off the chart). */
function placeCursorOf(item, state) {
  const u = item.u;
  if (!u || !item.cursorEl) return;
  const left = state.cursorT == null ? NaN : u.valToPos(item.fromTime(state.cursorT), 'x');
  const shown = left >= 0 && left <= u.bbox.width / uPlot.pxRatio;
  item.cursorEl.style.display = shown ? '' : 'none';
  if (shown) item.cursorEl.style.transform = `translateX(${Math.round(left)}px)`;
}

/** When the mouse is not over a chart, its legend shows the values at the animation's time. */
function showAnimLegendOf(item, state) {
  const u = item.u;
  if (!u || state.cursorT == null || (u.cursor.left != null && u.cursor.left >= 0)) return;
  u.setLegend({ idx: nearestIndex(u.data[0], item.fromTime(state.cursorT)) }, false);
}

export function createCharts(data, { onSeekTime } = {}) {
  const state = { xMode: 'time', zoom: null, cursorT: null };
  const section = h('section', { id: 'charts', class: 'charts' });
  const items = data.charts.map(chartItem);
  items.forEach((item) => section.appendChild(item.card));

  const zoomTo = (range) => {
    state.zoom = range && range[1] > range[0] ? range : null;
    items.forEach((item) => applyZoom(item, state));
  };
  const placeCursor = (item) => placeCursorOf(item, state);
  const showAnimLegend = (item) => showAnimLegendOf(item, state);

  function build(item) {
    if (item.u) return;
    const useS = state.xMode === 's' && !!item.def.x.s_mm;
    const t = item.def.x.time_s;
    const s = item.def.x.s_mm;
    item.mode = useS ? 's' : 'time';
    item.toTime = useS ? (x) => interp(s, t, x) : (x) => x;
    item.fromTime = useS ? (x) => interp(t, s, x) : (x) => x;
    const opts = chartOptions(item, useS, { zoomTo, placeCursor, showAnimLegend });
    item.u = new uPlot(opts, [useS ? s : t, ...item.def.series.map((sr) => sr.values)], item.body);
    registerPlot(item.card.id, item.u);
    item.body.style.minHeight = '';
    item.cursorEl = h('div', { class: 'chart-cursor' });
    item.u.over.appendChild(item.cursorEl);
    item.u.over.addEventListener('click', () => {
      const left = item.u.cursor.left;
      if (onSeekTime && left != null && left >= 0) onSeekTime(item.toTime(item.u.posToVal(left, 'x')));
    });
    if (state.zoom) applyZoom(item, state);
    placeCursor(item);
    showAnimLegend(item);
  }

  function destroy(item) {
    if (!item.u) return;
    item.body.style.minHeight = `${item.body.offsetHeight}px`;
    unregisterPlot(item.card.id, item.u);
    item.u.destroy();
    item.u = null;
    item.cursorEl = null;
  }

  // The switch only where some chart has path length: elsewhere it would do nothing.
  const toggle = data.charts.some((c) => c.x.s_mm) ? xAxisToggle(() => setXMode(state.xMode === 'time' ? 's' : 'time')) : null;

  function setXMode(mode) {
    mode = mode === 's' ? 's' : 'time';
    if (mode === state.xMode || !toggle) return;
    state.xMode = mode;
    toggle.setAttribute('aria-pressed', String(mode === 's'));
    toggle.querySelectorAll('.seg').forEach((el) => el.classList.toggle('on', el.dataset.mode === mode));
    for (const item of items) {
      if (!item.def.x.s_mm || !item.u) continue;
      destroy(item);
      build(item);
    }
  }

  return {
    element: section,
    toggle,
    /** Builds the charts now on screen (call once the section is in the document). */
    start: lazyBuilder(items, build),
    /** Moves the current-time line of every chart. */
    setCursorTime(t) {
      state.cursorT = Number.isFinite(t) ? t : null;
      for (const item of items) {
        placeCursor(item);
        showAnimLegend(item);
      }
    },
    setXMode,
    zoomTo,
    get count() {
      return items.length;
    },
    /** x range of every built chart (for tests): [id, mode, min, max]. */
    debugScales: () => items.filter((it) => it.u).map((it) => [it.def.id, it.mode, +it.u.scales.x.min.toFixed(3), +it.u.scales.x.max.toFixed(3)]),
    get builtCount() {
      return items.filter((it) => it.u).length;
    },
  };
}
