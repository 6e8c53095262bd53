// The 3-D view's panel: the canvas container (#scene), view buttons and the colour legend. Falls back to a
// message when WebGL cannot be started.
import { h } from './dom.js';
import { CLOSENESS_GRADIENT, ERROR_GRADIENT } from './colors.js';
import { createSceneView } from './scene.js';

function legend(data) {
  const sd = data.scene;
  const hasStruts = sd.frames.struts.some((s) => s.length > 0);
  const errs = sd.executed_error_mm.filter(Number.isFinite);
  const scale = sd.error_scale_mm > 0 ? sd.error_scale_mm : errs.length ? Math.max(...errs) : 0;
  const ramp = (grad, lo, hi) =>
    h('span', { class: 'ramp' }, h('span', { class: 'ramp-lo' }, lo), h('span', { class: 'ramp-bar', style: { background: grad } }), h('span', { class: 'ramp-hi' }, hi));
  return h(
    'div',
    { class: 'scene-legend' },
    hasStruts ? h('div', { class: 'lg-row' }, h('span', { class: 'lg-name' }, 'strut'), ramp(CLOSENESS_GRADIENT, 'far', 'at limit')) : null,
    sd.executed_path.length >= 2
      ? h('div', { class: 'lg-row' }, h('span', { class: 'lg-name' }, 'error'), ramp(ERROR_GRADIENT, '0', scale > 0 ? `${Number(scale.toPrecision(3))} mm` : '—'))
      : null,
    h(
      'div',
      { class: 'lg-row lg-keys' },
      sd.programmed_path.length >= 2 ? h('span', null, h('i', { class: 'sw line prog' }), 'programmed') : null,
      sd.frames.tool.some((p) => Array.isArray(p)) ? h('span', null, h('i', { class: 'sw dot tool' }), 'tool') : null,
      h('span', { class: 'axes-key' }, h('b', { class: 'ax x' }, 'x'), h('b', { class: 'ax y' }, 'y'), h('b', { class: 'ax z' }, 'z')),
    ),
  );
}

export function createScenePanel(data) {
  const container = h('div', { id: 'scene', class: 'scene' });
  const panel = h('section', { class: 'scene-panel' }, container);
  let view = null;
  const api = {
    element: panel,
    view: () => view,
    /** Starts WebGL (the panel must be in the document). Returns false when it is not available. */
    start() {
      try {
        view = createSceneView(container, data);
      } catch (e) {
        container.appendChild(h('div', { class: 'scene-error' }, '3-D view unavailable: WebGL could not be started in this browser.'));
        view = null;
        return false;
      }
      const buttons = [
        ['iso', 'Fit', 'fit the whole machine'],
        ['path', 'Path', 'zoom to the tool path'],
        ['top', 'Top', 'view from above'],
        ['front', 'Front', 'view from the front'],
      ];
      const bar = h(
        'div',
        { class: 'view-buttons' },
        buttons.map(([k, label, title]) =>
          h('button', { type: 'button', class: 'btn small', title, dataset: { view: k }, onclick: () => view.setView(k) }, label),
        ),
      );
      container.appendChild(bar);
      container.appendChild(legend(data));
      return true;
    },
  };
  return api;
}
