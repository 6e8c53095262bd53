// The colour bar of a heat map: what the colours mean, with the quantity's unit ("δρ [–]"), the values at the
// two ends (the bad end on the right, where the scale runs red), whether the scale is logarithmic, and the
// colour of the masked cells (no value: unreachable, beyond the drives' range).
import { h } from './dom.js';
import { fmtNum } from './format.js';
import { axisLabel } from './plot-style.js';

export const MASK_COLOR = '#eceff1';

/** The colour bar; `range` [lo, hi] or null (no cell has a value); `reversed`: the low end is the hot one. */
export function colourBar({ label, unit, range, gradient, reversed = false, log = false, masked = 'no value' }) {
  const end = (v) => (range ? fmtNum(v) : '—');
  const [left, right] = reversed && range ? [range[1], range[0]] : range ?? [null, null];
  return h(
    'div',
    { class: 'colour-bar' },
    h('div', { class: 'colour-bar-title' }, axisLabel(label, unit), log ? h('span', { class: 'colour-bar-note' }, ' · log scale') : null),
    h(
      'div',
      { class: 'colour-bar-scale' },
      h('span', { class: 'colour-bar-end' }, end(left)),
      h('span', { class: 'colour-bar-ramp', style: { background: gradient } }),
      h('span', { class: 'colour-bar-end' }, end(right)),
    ),
    h('div', { class: 'colour-bar-mask' }, h('span', { class: 'colour-bar-swatch', style: { background: MASK_COLOR } }), masked),
  );
}
