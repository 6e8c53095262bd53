// The 3-D view's panel: the canvas container (#scene), view buttons, the strut colouring switch (limits or
// drive force, only for runs with drive forces) and the colour legend. Falls back to a message when WebGL
// cannot be started.
import { h } from './dom.js';
import { CLOSENESS_GRADIENT, ERROR_GRADIENT, FORCE_GRADIENT } from './colors.js';
import { fmtNum } from './format.js';
import { createSceneView } from './scene.js';

/** True when every frame has the drive forces (a plan with --dynamics). */
export function hasDriveForces(data) {
  return Array.isArray(data.scene.frames.drive_force) && data.scene.frames.struts.some((s) => s.length > 0);
}

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
    hasStruts
      ? h('div', { class: 'lg-row', id: 'legend-strut-limits' }, h('span', { class: 'lg-name' }, 'strut'), ramp(CLOSENESS_GRADIENT, 'far', 'at limit'))
      : null,
    hasDriveForces(data) ? forceLegend(sd, ramp) : null,
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

/** The force scale's legend: tension (the drive pulls) to compression (it pushes) at ± the run's peak |force|. */
function forceLegend(sd, ramp) {
  const peak = `${fmtNum(sd.drive_force_scale, 4)} ${sd.drive_force_unit}`;
  return h(
    'div',
    { class: 'lg-row', id: 'legend-strut-force', style: { display: 'none' } },
    h('span', { class: 'lg-name' }, 'force'),
    ramp(FORCE_GRADIENT, `−${peak} tension`, `+${peak} compression`),
  );
}

/** The switch between strut colours by closeness to the limits and by drive force. */
function coloringToggle(getView) {
  const toggle = h(
    'button',
    {
      id: 'strut-colour',
      class: 'seg-toggle',
      type: 'button',
      title: 'colour the struts by closeness to their limits or by drive force',
      'aria-pressed': 'false',
      dataset: { mode: 'limits' },
      onclick: () => set(toggle.dataset.mode === 'force' ? 'limits' : 'force'),
    },
    h('span', { class: 'seg-label' }, 'struts:'),
    h('span', { class: 'seg on', dataset: { mode: 'limits' } }, 'limits'),
    h('span', { class: 'seg', dataset: { mode: 'force' } }, 'force'),
  );
  function set(mode) {
    const view = getView();
    const shown = view ? view.setStrutColoring(mode) : 'limits';
    toggle.dataset.mode = shown;
    toggle.setAttribute('aria-pressed', String(shown === 'force'));
    toggle.querySelectorAll('.seg').forEach((el) => el.classList.toggle('on', el.dataset.mode === shown));
    const panel = toggle.closest('.scene');
    const limitsRow = panel && panel.querySelector('#legend-strut-limits');
    const forceRow = panel && panel.querySelector('#legend-strut-force');
    if (limitsRow) limitsRow.style.display = shown === 'force' ? 'none' : '';
    if (forceRow) forceRow.style.display = shown === 'force' ? '' : 'none';
    if (view) view.render();
    return shown;
  }
  return { element: toggle, set };
}

export function createScenePanel(data) {
  const container = h('div', { id: 'scene', class: 'scene' });
  const panel = h('section', { class: 'scene-panel' }, container);
  let view = null;
  let coloring = null;
  const api = {
    element: panel,
    view: () => view,
    /** Strut colouring: 'limits' or 'force'; null when the run has no drive forces (no switch). */
    setStrutColoring: (mode) => (coloring ? coloring.set(mode) : null),
    strutColoring: () => (coloring && view ? view.strutColoring() : null),
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
      if (hasDriveForces(data)) {
        coloring = coloringToggle(() => view);
        bar.prepend(coloring.element);
      }
      container.appendChild(bar);
      container.appendChild(legend(data));
      return true;
    },
  };
  return api;
}
