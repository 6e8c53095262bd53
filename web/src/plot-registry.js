// Every uPlot plot the page draws, by id, so that one hook can describe them all: the series each draws (name
// and stroke colour), what its legend shows (label and swatch colour) and its axis labels. A plot that is
// rebuilt (the x-axis switch) replaces its entry.

const plots = new Map();

/** Records plot `u` under `id` (the card's id). */
export function registerPlot(id, u) {
  plots.set(id, u);
}

/** Forgets the plot `u` of `id` (when it is destroyed). */
export function unregisterPlot(id, u) {
  if (plots.get(id) === u) plots.delete(id);
}

/** '#rrggbb' of a CSS colour as the browser computes it ('' when none). */
function hexOf(css) {
  const m = /rgba?\((\d+),\s*(\d+),\s*(\d+)(?:,\s*([\d.]+))?\)/.exec(css || '');
  if (!m || m[4] === '0') return '';
  return `#${[m[1], m[2], m[3]].map((c) => Number(c).toString(16).padStart(2, '0')).join('')}`;
}

/** A stroke option as '#rrggbb' (the plots give hex colours). */
function strokeHex(u, i) {
  const s = u.series[i].stroke(u, i);
  return typeof s === 'string' ? s.toLowerCase() : '';
}

/** The legend rows of a plot, the x series' row left out. */
function legendRows(u) {
  const rows = [...u.root.querySelectorAll('.u-legend tr.u-series')];
  // uPlot's live inline legend starts with the x value's row.
  return rows.length === u.series.length ? rows.slice(1) : rows;
}

/** For the browser test: every plot's series, legend entries and axis labels. */
export function describePlots() {
  return [...plots.entries()].map(([id, u]) => ({
    id,
    series: u.series.slice(1).map((s, k) => ({ name: String(s.label), stroke: strokeHex(u, k + 1) })),
    legend: legendRows(u).map((row) => ({
      label: row.querySelector('.u-label')?.textContent ?? '',
      swatch: hexOf(getComputedStyle(row.querySelector('.u-marker')).backgroundColor),
    })),
    axes: u.axes.map((a) => String(a.label ?? '')),
  }));
}
