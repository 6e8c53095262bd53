// window.pkmReport: the hooks the browser test uses.
import { describePlots } from './plot-registry.js';
import { verdictOf } from './verdict.js';

/** The page's layout as the test checks it for blank areas: the top panels' heights and each grid's rows. */
function layout() {
  const box = (el) => (el ? el.getBoundingClientRect() : null);
  const grids = [...document.querySelectorAll('.charts')].map((grid) => {
    const g = box(grid);
    // A map's card is as wide as its map (drawn to scale), not as its row.
    const cards = [...grid.children].filter((c) => !c.classList.contains('map-card')).map(box).filter((r) => r.width > 0);
    // Per row (cards of one top): from the first card's left to the last card's right.
    const rows = new Map();
    for (const r of cards) {
      const key = Math.round(r.top);
      const row = rows.get(key) ?? { left: r.left, right: r.right };
      rows.set(key, { left: Math.min(row.left, r.left), right: Math.max(row.right, r.right) });
    }
    return { id: grid.closest('section')?.id || grid.id, width: g.width, rows: [...rows.values()].map((r) => r.right - r.left), cards: cards.length };
  });
  const maps = [...document.querySelectorAll('.map-card')].map((card) => {
    const parts = [...card.querySelectorAll('.map-plot, .map-side')].map(box);
    return { id: card.id, width: box(card).width, content: parts.reduce((w, r) => w + r.width, 0) };
  });
  return {
    summaryHeight: box(document.querySelector('.summary-panel'))?.height ?? 0,
    sceneHeight: box(document.querySelector('.scene-panel'))?.height ?? 0,
    emptySections: [...document.querySelectorAll('main section')].filter((s) => s.getBoundingClientRect().height < 2).map((s) => s.id || s.className),
    grids,
    maps,
  };
}

export function installHooks({ data, player, sceneView, charts, transport, scenePanel, stiffness, workspace, calibration, servo }) {
  const hooks = {
    ready: false,
    frameCount: player.count,
    chartCount: charts.count,
    /** Moves the animation to frame i and updates slider, 3-D view and #current-line synchronously. */
    setFrame(i) {
      player.setFrame(i);
      transport.showFrame(player.frame);
      const v = sceneView();
      if (v) {
        v.setFrame(player.frame);
        v.render();
      }
      return player.frame;
    },
    currentFrame: () => player.frame,
    currentLine: () => player.line(),
    canvasHasPixels: () => {
      const v = sceneView();
      return v ? v.hasPixels() : false;
    },
    /** 'limits' or 'force'; null without drive forces (the switch is absent) or without WebGL. */
    strutColoring: () => scenePanel.strutColoring(),
    /** Switches the strut colours as the #strut-colour switch does; returns the mode shown (null: none). */
    setStrutColoring: (mode) => scenePanel.setStrutColoring(mode),
    /** The struts' colours in the 3-D view now ('#rrggbb'). */
    strutColors: () => {
      const v = sceneView();
      return v ? v.strutColors() : [];
    },
    builtCharts: () => charts.builtCount,
    chartScales: () => charts.debugScales(),
    /** The stiffness plots: {bode: [{which, drawn}], map: {drawn, cells} | null}; drawn = has pixels. */
    stiffnessPlots: () => stiffness.state(),
    /** The workspace map: {layers, layer, slice, slices, cells, drawn} | null; drawn = has pixels. */
    workspaceMap: () => workspace.state(),
    /** Shows a layer of the workspace map (its id, e.g. 'status', 'delta_rho'); returns the id, null if none. */
    setWorkspaceLayer: (id) => workspace.setLayer(id),
    /** Shows slice k of a 3-D workspace map; returns k, null if out of range. */
    setWorkspaceSlice: (k) => workspace.setSlice(k),
    /** {drawn, expected}: the colour at the centre of cell [i, j] of the workspace map and the one it should have. */
    workspaceCellColour: (i, j) => workspace.cellColour(i, j),
    /** The calibration plots: {residuals, parameters, drawn} | null; drawn = the residual chart has pixels. */
    calibrationPlots: () => calibration.state(),
    /**
     * The servo plots (plans after `pkm servo`): {drive, drives, bode: [{loop, which, series, points, values,
     * drawn}], charts: [{id, series, legend, points, drawn}]} | null; drawn = has pixels.
     */
    servoPlots: () => servo.state(),
    /** Shows the loops of drive d (1-based); returns d, null if there is no such drive. */
    setServoDrive: (d) => servo.setDrive(d),
    /** Every uPlot plot: {id, series: [{name, stroke}], legend: [{label, swatch}], axes: [label]}. */
    plots: () => describePlots(),
    /** The verdict as computed from the data and as shown: {level, items, shown: {level, text}}. */
    verdict: () => {
      const v = verdictOf(data);
      const el = document.getElementById('verdict');
      return { level: v.level, items: v.items.map((i) => i.severity), shown: el ? { level: el.dataset.level, text: el.textContent, colour: getComputedStyle(el).borderLeftColor } : null };
    },
    /** Whether the transport bar is there, and what its frames are ('time' | 'pose'). */
    transport: () => ({ shown: !!transport.element && document.body.contains(transport.element), axis: data.scene.frames.axis, frames: player.count }),
    /** The stiffness map's point [i, j]: {drawn, expected, value} ('#rrggbb'), null without a map. */
    stiffnessMapCellColour: (i, j) => stiffness.mapCellColour(i, j),
    /** Sizes of the page's parts, for blank areas: {summaryHeight, sceneHeight, emptySections, grids, maps}. */
    layout,
  };
  window.pkmReport = hooks;
  return hooks;
}
