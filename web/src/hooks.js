// window.pkmReport: the hooks the browser test uses.

export function installHooks({ player, sceneView, charts, transport, scenePanel, stiffness, workspace, calibration, servo }) {
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
  };
  window.pkmReport = hooks;
  return hooks;
}
