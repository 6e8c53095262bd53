// The servo loops of a plan's report after `pkm servo` (docs/report-data.md: `servo`): a Bode plot per loop, the
// speed and the position loop of one drive at a time (#servo-drive), each as magnitude and phase over a log
// frequency axis (uPlot): the open loop continuous and sampled (the sampled ones end at the Nyquist frequency of
// the loops' period, marked), the closed loop's magnitude dashed; 0 dB and −180° are marked, and the card says
// the margins. The following and contour error over time are ordinary `charts` (servo_following_error,
// servo_contour_error), drawn and zoomed with the other time charts.
import uPlot from 'uplot';
import { h } from './dom.js';
import { seriesColor } from './colors.js';
import { fmtNum } from './format.js';
import { AXIS, axisLabel, card, legendOptions, logTicks } from './plot-style.js';
import { registerPlot } from './plot-registry.js';
import { painted } from './pixels.js';

const PLOT_HEIGHT = 190;
const REF_COLOR = '#7a8691';
// Per loop: [legend, servo_bode.csv column, dashed] of the magnitude and of the phase plot; each series named
// by the loop it is of, with its unit.
const LOOPS = ['speed', 'position'].map((id) => ({
  id,
  mag: [['open loop [dB]', `${id}_open_db`], ['open loop, sampled [dB]', `${id}_open_sampled_db`], ['closed loop [dB]', `${id}_closed_db`, true]].concat(
    id === 'position' ? [['closed loop, sampled [dB]', 'position_closed_sampled_db', true]] : [],
  ),
  phase: [['open loop [°]', `${id}_open_deg`], ['open loop, sampled [°]', `${id}_open_sampled_deg`]],
}));

/** Degrees unwrapped along the frequencies, from within (−360°, 0°]: an open loop's phase lags. */
function unwrap(values) {
  let offset = 0;
  let prev = null;
  return values.map((v) => {
    if (v == null || !Number.isFinite(v)) return null;
    if (prev == null) offset = v > 0 ? -360 : 0;
    else {
      while (v + offset - prev > 180) offset -= 360;
      while (v + offset - prev < -180) offset += 360;
    }
    prev = v + offset;
    return prev;
  });
}

/** The `servo` object, or null when absent or malformed; columns of another length become gaps. */
export function normalizeServo(raw) {
  if (!raw || typeof raw !== 'object' || !Array.isArray(raw.bode)) return null;
  const bode = raw.bode.filter((b) => b && Array.isArray(b.frequency_hz) && b.frequency_hz.length > 1);
  if (!bode.length) return null;
  const summary = raw.summary && typeof raw.summary === 'object' ? raw.summary : {};
  return {
    bode,
    drives: Array.isArray(summary.drives) ? summary.drives : [],
    nyquist: Number(raw.nyquist_hz),
    charts: Array.isArray(raw.charts) ? raw.charts.map(String) : [],
  };
}

function plotData(b, defs, phase) {
  const f = b.frequency_hz;
  const column = (key) => (Array.isArray(b[key]) && b[key].length === f.length ? b[key] : f.map(() => null));
  return [f, ...defs.map(([, key]) => (phase ? unwrap(column(key)) : column(key)))];
}

/** The reference level (0 dB, −180°) across the plot and the Nyquist frequency as a vertical line. */
function drawRefs(level, label, nyquist) {
  return (u) => {
    const { ctx, bbox } = u;
    const pr = uPlot.pxRatio;
    ctx.save();
    ctx.strokeStyle = REF_COLOR;
    ctx.fillStyle = REF_COLOR;
    ctx.lineWidth = pr;
    ctx.setLineDash([6 * pr, 4 * pr]);
    ctx.font = `${11 * pr}px system-ui, sans-serif`;
    const y = Math.round(u.valToPos(level, 'y', true)) + 0.5;
    if (y >= bbox.top && y <= bbox.top + bbox.height) {
      ctx.beginPath();
      ctx.moveTo(bbox.left, y);
      ctx.lineTo(bbox.left + bbox.width, y);
      ctx.stroke();
      ctx.textAlign = 'right';
      ctx.fillText(label, bbox.left + bbox.width - 4 * pr, y - 4 * pr);
    }
    const x = nyquist > 0 ? Math.round(u.valToPos(nyquist, 'x', true)) + 0.5 : NaN;
    if (x >= bbox.left && x <= bbox.left + bbox.width) {
      ctx.beginPath();
      ctx.moveTo(x, bbox.top);
      ctx.lineTo(x, bbox.top + bbox.height);
      ctx.stroke();
      ctx.fillText('Nyquist', x - 4 * pr, bbox.top + 12 * pr);
    }
    ctx.restore();
  };
}

function bodePlot(body, loop, phase, b, nyquist) {
  const defs = phase ? loop.phase : loop.mag;
  const level = phase ? -180 : 0;
  const opts = {
    width: Math.max(200, body.clientWidth),
    height: PLOT_HEIGHT,
    scales: {
      x: { time: false, distr: 3, range: (u, min, max) => [min, max] },
      // The reference level always in view: where the loop crosses it gives the margins.
      y: { range: (u, min, max) => uPlot.rangeNum(Math.min(min ?? level, level), Math.max(max ?? level, level), 0.1, true) },
    },
    axes: [
      { ...AXIS, values: logTicks, label: axisLabel('frequency', 'Hz'), size: 30, labelGap: 0 },
      { ...AXIS, label: phase ? axisLabel('phase', '°') : axisLabel('magnitude', 'dB'), size: 50, gap: 4 },
    ],
    series: [
      { label: 'frequency', value: (u, v) => (v == null ? '—' : `${fmtNum(v, 4)} Hz`) },
      ...defs.map(([label, , dashed], i) => ({
        label,
        stroke: seriesColor(i),
        width: 1.25,
        dash: dashed ? [6, 4] : undefined,
        points: { show: false },
        value: (u, v) => (v == null ? '—' : fmtNum(v)),
      })),
    ],
    cursor: { drag: { x: false, y: false }, points: { size: 6 }, sync: { key: `servo-${loop.id}` } },
    legend: legendOptions(),
    hooks: { draw: [drawRefs(level, phase ? '−180°' : '0 dB', nyquist)] },
  };
  return new uPlot(opts, plotData(b, defs, phase), body);
}

/** "sampled: PM 63.2° at 210 Hz, GM 12.1 dB, overshoot 4.3 % · continuous: PM 65.5°" of a drive's loop. */
function margins(drive, loop) {
  const l = drive && drive[`${loop}_loop`];
  if (!l) return '';
  const s = l.sampled || {};
  const c = l.continuous || {};
  const gm = s.gain_margin_db == null ? '∞' : `${fmtNum(s.gain_margin_db, 3)} dB`;
  return `sampled: PM ${fmtNum(s.phase_margin_deg, 3)}° at ${fmtNum(s.crossover_hz, 3)} Hz, GM ${gm}, overshoot ${fmtNum(s.overshoot_pct, 3)} % · continuous: PM ${fmtNum(c.phase_margin_deg, 3)}°`;
}

export function createServoPlots(data) {
  const servo = normalizeServo(data.servo);
  if (!servo) return { element: null, start() {}, state: () => null, setDrive: () => null };
  let current = 0;
  const plots = [];
  const subs = [];
  const cards = LOOPS.map((loop) => {
    const bodies = [false, true].map((phase) => {
      const body = h('div', { class: 'chart-body', style: { minHeight: `${PLOT_HEIGHT + 26}px` } });
      plots.push({ loop, phase, body, u: null });
      return body;
    });
    const article = card(`chart-servo-bode-${loop.id}`, `${loop.id === 'speed' ? 'Speed' : 'Position'} loop`, '', bodies);
    subs.push({ loop, el: article.querySelector('.chart-sub') });
    return article;
  });
  const select = h(
    'select',
    { id: 'servo-drive', title: 'the drive whose loops are shown', onchange: () => setDrive(servo.bode[Number(select.value)].drive) },
    servo.bode.map((b, k) => h('option', { value: String(k) }, `drive ${b.drive}`)),
  );
  const element = h(
    'section',
    { class: 'charts-section', id: 'servo-plots' },
    h('div', { class: 'section-head' }, h('h2', null, 'Servo loops'), h('label', { class: 'hint' }, 'drive ', select)),
    h('div', { class: 'charts' }, cards),
  );
  const showMargins = () => {
    for (const s of subs) s.el.textContent = margins(servo.drives[current], s.loop.id);
  };

  /** Shows drive `drive` (1-based, as in the data); returns it, null if there is none such. */
  function setDrive(drive) {
    const k = servo.bode.findIndex((b) => b.drive === Number(drive));
    if (k < 0) return null;
    current = k;
    select.value = String(k);
    for (const p of plots) if (p.u) p.u.setData(plotData(servo.bode[k], p.phase ? p.loop.phase : p.loop.mag, p.phase));
    showMargins();
    return servo.bode[k].drive;
  }

  const ro = new ResizeObserver(() => {
    for (const p of plots) {
      if (!p.u) continue;
      const w = Math.max(200, Math.floor(p.body.clientWidth));
      if (w !== p.u.width) p.u.setSize({ width: w, height: PLOT_HEIGHT });
    }
  });

  return {
    element,
    /** Draws the plots (call once the section is in the document). */
    start() {
      for (const p of plots) {
        p.u = bodePlot(p.body, p.loop, p.phase, servo.bode[current], servo.nyquist);
        registerPlot(`chart-servo-bode-${p.loop.id}-${p.phase ? 'phase' : 'magnitude'}`, p.u);
        ro.observe(p.body);
      }
      showMargins();
    },
    setDrive,
    /**
     * For the browser test: the drive shown, the Bode plots (series, points, non-null values per series, drawn)
     * and the servo's time charts (series in the data and in the legend, points, drawn).
     */
    state() {
      return {
        drive: servo.bode[current].drive,
        drives: servo.bode.length,
        bode: plots.map((p) => ({
          loop: p.loop.id,
          which: p.phase ? 'phase' : 'magnitude',
          series: p.u ? p.u.series.length - 1 : 0,
          points: p.u ? p.u.data[0].length : 0,
          values: p.u ? p.u.data.slice(1).map((s) => s.filter((v) => v != null).length) : [],
          drawn: !!p.u && painted(p.u.ctx.canvas),
        })),
        charts: servo.charts.map((id) => {
          const def = data.charts.find((c) => c.id === id);
          const el = document.getElementById(`chart-${id}`);
          return {
            id,
            series: def ? def.series.length : 0,
            legend: el ? Math.max(0, el.querySelectorAll('.u-legend tr.u-series').length - 1) : 0,
            points: def ? def.x.time_s.length : 0,
            drawn: painted(el && el.querySelector('canvas')),
          };
        }),
      };
    },
  };
}
