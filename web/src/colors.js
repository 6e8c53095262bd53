// Colour maps: series palette, strut closeness (green-yellow-red), path error (blue-red), drive force
// (diverging: tension blue, no force grey, compression red).

/**
 * Distinct series colours (Tableau 10, reordered so the first few differ most), without its grey: grey is the
 * page's colour for what has no value, and a grey curve reads as a reference line.
 */
export const SERIES_COLORS = [
  '#1f77b4', '#d62728', '#2ca02c', '#ff7f0e', '#9467bd', '#17becf',
  '#8c564b', '#e377c2', '#bcbd22', '#393b79',
];

export function seriesColor(i) {
  return SERIES_COLORS[i % SERIES_COLORS.length];
}

const CLOSENESS_STOPS = [
  [0, [0.18, 0.65, 0.27]],
  [0.5, [0.96, 0.77, 0.1]],
  [1, [0.84, 0.12, 0.1]],
];

const ERROR_STOPS = [
  [0, [0.16, 0.42, 0.86]],
  [0.5, [0.6, 0.36, 0.72]],
  [1, [0.86, 0.13, 0.12]],
];

// Grey at zero force, so that a strut that carries little stays neutral whichever way it is loaded.
const FORCE_STOPS = [
  [0, [0.13, 0.36, 0.8]],
  [0.5, [0.78, 0.8, 0.82]],
  [1, [0.82, 0.14, 0.1]],
];

function ramp(stops, t, out) {
  const x = !(t > 0) ? 0 : t > 1 ? 1 : t;
  let i = 1;
  while (i < stops.length - 1 && x > stops[i][0]) i++;
  const [t0, c0] = stops[i - 1];
  const [t1, c1] = stops[i];
  const f = (x - t0) / (t1 - t0 || 1);
  out[0] = c0[0] + (c1[0] - c0[0]) * f;
  out[1] = c0[1] + (c1[1] - c0[1]) * f;
  out[2] = c0[2] + (c1[2] - c0[2]) * f;
  return out;
}

/** sRGB [r,g,b] in 0..1 for strut closeness 0 (far from limits) .. 1 (at a limit). */
export function closenessRgb(t, out = [0, 0, 0]) {
  return ramp(CLOSENESS_STOPS, t, out);
}

/** sRGB [r,g,b] in 0..1 for a path error fraction 0 .. 1 (of the error scale). */
export function errorRgb(t, out = [0, 0, 0]) {
  return ramp(ERROR_STOPS, t, out);
}

/**
 * sRGB [r,g,b] in 0..1 for a drive force as a fraction of the scale, −1 (tension: the drive pulls) .. 0 ..
 * +1 (compression: the drive pushes, pkm's positive force); beyond ±1 the ends.
 */
export function forceRgb(f, out = [0, 0, 0]) {
  return ramp(FORCE_STOPS, Number.isFinite(f) ? (f + 1) / 2 : 0.5, out);
}

function cssGradient(stops) {
  const parts = stops.map(([t, c]) => `rgb(${c.map((v) => Math.round(v * 255)).join(',')}) ${t * 100}%`);
  return `linear-gradient(to right, ${parts.join(', ')})`;
}

export const CLOSENESS_GRADIENT = cssGradient(CLOSENESS_STOPS);
export const ERROR_GRADIENT = cssGradient(ERROR_STOPS);
export const FORCE_GRADIENT = cssGradient(FORCE_STOPS);
