// Number formatting for legends, the time display and labels.

/** A compact number with about `digits` significant digits; exponent form for very small/large values. */
export function fmtNum(v, digits = 4) {
  if (v == null || Number.isNaN(v)) return '—';
  if (!Number.isFinite(v)) return v > 0 ? '∞' : '-∞';
  const a = Math.abs(v);
  if (a === 0) return '0';
  if (a >= 1e6 || a < 1e-3) return v.toExponential(Math.max(0, digits - 2)).replace('e+', 'e');
  const decimals = Math.max(0, digits - 1 - Math.floor(Math.log10(a)));
  return v.toFixed(Math.min(decimals, 6));
}

/** Seconds with millisecond resolution: "12.345". */
export function fmtTime(t) {
  return t == null || !Number.isFinite(t) ? '—' : t.toFixed(3);
}

export function withUnit(v, unit, digits) {
  const s = fmtNum(v, digits);
  return v == null || !unit ? s : `${s} ${unit}`;
}
