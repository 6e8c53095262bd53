// The page header (title, machine, program) and the summary: pkm's table, the limits reached and the raw
// summary JSON (collapsed).
import { h } from './dom.js';
import { fmtTime } from './format.js';
import { lineCalls, lineDescription } from './data.js';
import { verdictOf } from './verdict.js';

export function renderHeader(data) {
  const m = data.machine;
  const p = data.program;
  const meta = [];
  if (m.name || m.file) {
    meta.push(
      h('span', { class: 'meta-item' }, h('span', { class: 'meta-key' }, 'machine'), ' ',
        h('strong', null, m.name || m.file), m.type ? h('span', { class: 'tag' }, m.type) : null,
        m.name && m.file ? h('code', { class: 'file' }, m.file) : null),
    );
  }
  if (p.file) meta.push(h('span', { class: 'meta-item' }, h('span', { class: 'meta-key' }, 'program'), ' ', h('code', { class: 'file' }, p.file)));
  if (data.kind) meta.push(h('span', { class: 'meta-item' }, h('span', { class: 'meta-key' }, 'run'), ' ', h('span', { class: 'tag kind' }, data.kind)));
  return h(
    'header',
    { class: 'page-header' },
    h('div', { class: 'brand' }, 'pkm report'),
    h('h1', null, data.title),
    h('div', { class: 'meta' }, meta),
  );
}

/** Text with line-break opportunities after path separators (long file names wrap at a "/"). */
function breakable(text) {
  const parts = text.split(/(?<=[/\\])/);
  return parts.flatMap((p, i) => (i < parts.length - 1 ? [p, h('wbr')] : [p]));
}

/** A "line N" link (disabled when no frame shows that line). */
export function lineLink(line, frameOf, onLine) {
  const f = frameOf(line);
  if (f < 0) return h('span', { class: 'line-ref off', title: 'no animation frame on this line' }, `line ${line}`);
  return h(
    'a',
    {
      href: `#line-${line}`,
      class: 'line-ref',
      title: 'show this line in the 3-D view',
      dataset: { line: String(line) },
      onclick: (e) => {
        e.preventDefault();
        onLine(line);
      },
    },
    `line ${line}`,
  );
}

/**
 * A program line's link, followed by where the moves it executes were written when that is elsewhere (a
 * subroutine call): the calling line alone does not say which lines moved the tool.
 */
function lineRef(data, line, frameOf, onLine) {
  const link = lineLink(line, frameOf, onLine);
  const calls = lineCalls(data, line);
  if (!calls.length) return link;
  return h(
    'span',
    { class: 'line-with-calls', title: lineDescription(data, line) },
    link,
    h('span', { class: 'line-calls' }, `\u2192 ${calls.join(', ')}`),
  );
}

export function renderSummary(data, { frameOf, onLine, onTime }) {
  const rows = data.table.map((r) =>
    h(
      'tr',
      null,
      h('th', { scope: 'row' }, r.label ?? ''),
      h('td', { class: 'val' }, breakable(String(r.value ?? ''))),
      h('td', { class: 'ref' }, Number(r.line) > 0 ? lineRef(data, Number(r.line), frameOf, onLine) : null),
    ),
  );
  const table = h('table', { id: 'summary-table', class: 'summary-table' }, h('tbody', null, rows));

  const verdict = renderVerdict(data, frameOf, onLine, onTime);
  const details =
    data.summary !== undefined && data.summary !== null
      ? h('details', { class: 'raw-summary' }, h('summary', null, 'summary.json'), h('pre', null, JSON.stringify(data.summary, null, 2)))
      : null;

  // The verdict first: whether anything needs a look is the first thing the page must say.
  return h('div', { class: 'summary' }, verdict, table, details);
}

/** One limit or warning: its severity, what, and where (program line, time). */
function verdictItem(data, item, frameOf, onLine, onTime) {
  const t = Number(item.time_s);
  return h(
    'li',
    { class: `limit ${item.severity}` },
    h('span', { class: `badge ${item.severity}` }, item.severity),
    h('span', { class: 'what' }, item.what ?? ''),
    h(
      'span',
      { class: 'where' },
      Number(item.line) > 0 ? lineRef(data, Number(item.line), frameOf, onLine) : null,
      Number.isFinite(t)
        ? h('a', { href: '#', class: 'time-ref', title: 'show this moment', onclick: (e) => { e.preventDefault(); onTime(t); } }, `${fmtTime(t)} s`)
        : null,
    ),
  );
}

/** The verdict: the worst of the limits reached and the warnings, coloured by it, with each item below. */
function renderVerdict(data, frameOf, onLine, onTime) {
  const v = verdictOf(data);
  return h(
    'div',
    { class: `limits verdict ${v.level}`, id: 'verdict', dataset: { level: v.level } },
    h('h2', null, h('span', { class: 'verdict-text' }, v.text), v.items.length ? h('span', { class: 'count' }, String(v.items.length)) : null),
    v.items.length ? h('ul', null, v.items.map((item) => verdictItem(data, item, frameOf, onLine, onTime))) : null,
  );
}
