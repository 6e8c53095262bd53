// Entry point: reads the report data, builds the page and wires the parts together.
import { readData } from './data.js';
import { h } from './dom.js';
import { renderHeader, renderSummary } from './summary.js';
import { createPlayer } from './player.js';
import { createTransport } from './transport.js';
import { createScenePanel } from './scene-panel.js';
import { createCharts } from './charts.js';
import { createStiffnessPlots } from './stiffness.js';
import { createWorkspaceMap } from './workspace.js';
import { createCalibrationPlots } from './calibration.js';
import { createServoPlots } from './servo.js';
import { installHooks } from './hooks.js';

function init() {
  const marks = { start: performance.now() };
  const data = readData();
  marks.data = performance.now();
  if (!document.title) document.title = data.title;

  const player = createPlayer(data.scene.frames);
  const scenePanel = createScenePanel(data);
  const seekLine = (line) => {
    const f = player.frameOfLine(line);
    if (f >= 0) {
      player.pause();
      player.setFrame(f);
    }
  };
  const seekTime = (t) => {
    player.pause();
    player.seekTime(t);
  };
  const charts = createCharts(data, { onSeekTime: seekTime });
  const stiffness = createStiffnessPlots(data);
  const workspace = createWorkspaceMap(data);
  const calibration = createCalibrationPlots(data);
  const servo = createServoPlots(data);
  const transport = createTransport(player, data, [charts.toggle]);
  const summary = renderSummary(data, { frameOf: player.frameOfLine, onLine: seekLine, onTime: seekTime });

  // Without time plots no empty section (and no gap) is left where they would be; without a transport bar the
  // x-axis switch goes to the plots' own heading.
  const chartsSection = data.charts.length
    ? h('section', { class: 'charts-section' }, h('div', { class: 'section-head' }, h('h2', null, 'Plots'),
        h('span', { class: 'hint' }, 'drag to zoom all plots · double-click to reset · click to move the animation'),
        transport.element ? null : charts.toggle), charts.element)
    : null;
  const root = h(
    'div',
    { class: 'pkm-report' },
    renderHeader(data),
    transport.element,
    h('main', null, h('div', { class: 'top-grid' }, h('section', { class: 'panel summary-panel' }, summary), scenePanel.element), chartsSection, servo.element, stiffness.element, workspace.element, calibration.element),
    h('footer', { class: 'page-footer' }, [data.generated_by, data.format].filter(Boolean).join(' · ')),
  );
  document.body.appendChild(root);

  const hooks = installHooks({ data, player, sceneView: scenePanel.view, charts, transport, scenePanel, stiffness, workspace, calibration, servo });
  marks.dom = performance.now();
  const hasScene = scenePanel.start();
  marks.scene = performance.now();
  const view = scenePanel.view();

  player.onFrame((i) => {
    if (view) view.setFrame(i);
    charts.setCursorTime(player.time(i));
  });
  player.refresh();
  transport.showFrame(player.frame);

  charts.start();
  stiffness.start();
  workspace.start();
  calibration.start();
  servo.start();
  marks.charts = performance.now();
  if (hasScene) view.render();
  marks.render = performance.now();
  hooks.marks = marks;
  hooks.readyAt = performance.now();
  hooks.ready = true;
  document.documentElement.dataset.ready = 'true';
  window.dispatchEvent(new Event('pkm-report-ready'));
}

function fail(e) {
  const msg = e && e.message ? e.message : String(e);
  document.body.appendChild(h('div', { class: 'fatal' }, `The report could not be shown: ${msg}`));
  window.pkmReport = { ready: false, error: msg };
  throw e;
}

try {
  init();
} catch (e) {
  fail(e);
}
