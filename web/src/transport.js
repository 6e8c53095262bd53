// The animation controls (a bar that stays at the top): play/pause, scrub slider, speed, current time and
// program line. Keyboard: space plays/pauses, arrows step, Home/End jump. Only where there is something to
// animate (two frames or more): a map or a single pose gets no bar, since its controls would do nothing. Frames
// that are measured poses (calibration) are counted as poses, not seconds.
import { h, icon } from './dom.js';
import { fmtTime } from './format.js';
import { lineDescription } from './data.js';

const PLAY = 'M8 5v14l11-7z';
const PAUSE = 'M6 5h4v14H6zm8 0h4v14h-4z';
const SPEEDS = [0.5, 1, 2, 5, 10];

export function createTransport(player, data, extra = []) {
  const n = player.count;
  if (n < 2) return { element: null, showFrame() {} };
  const poses = data.scene.frames.axis === 'pose';
  const tEnd = data.scene.frames.time_s[n - 1];
  const playIcon = icon(PLAY);
  const playLabel = h('span', { class: 'btn-label' }, 'Play');
  const play = h('button', { id: 'play', class: 'btn primary', type: 'button', title: 'play / pause (space)', onclick: () => player.toggle() }, playIcon, playLabel);
  const scrub = h('input', {
    id: 'scrub', type: 'range', min: '0', max: String(n - 1), step: '1', value: '0',
    'aria-label': poses ? 'measured pose' : 'animation frame',
    oninput: () => player.setFrame(Number(scrub.value)),
  });
  const time = h('span', { id: 'current-time', class: 'num' }, '—');
  const total = h('span', { class: 'total num' }, poses ? `/ ${n}` : `/ ${fmtTime(tEnd)} s`);
  const speed = h(
    'select',
    { id: 'speed', title: 'playback speed', onchange: () => player.setSpeed(Number(speed.value)) },
    SPEEDS.map((s) => h('option', { value: String(s), selected: s === 1 }, `${s}\u00d7`)),
  );
  const line = h('div', { id: 'current-line', class: 'current-line', title: '' }, '—');

  const bar = h(
    'div',
    { class: 'transport', role: 'toolbar', 'aria-label': 'animation' },
    play,
    h('div', { class: 'scrub-wrap' }, scrub),
    poses ? h('div', { class: 'time' }, 'pose ', time, ' ', total) : h('div', { class: 'time' }, time, ' s ', total),
    speed,
    line,
    h('div', { class: 'transport-extra' }, extra),
  );

  let shownLine = null;
  function showFrame(i) {
    scrub.value = String(i);
    time.textContent = poses ? String(i + 1) : fmtTime(player.time(i));
    const l = player.line(i);
    if (l !== shownLine) {
      shownLine = l;
      if (l > 0) {
        line.textContent = lineDescription(data, l);
      } else {
        line.textContent = '—';
      }
      line.title = line.textContent;
    }
  }

  player.onFrame(showFrame);
  player.onState(({ playing }) => {
    playIcon.firstChild.setAttribute('d', playing ? PAUSE : PLAY);
    playLabel.textContent = playing ? 'Pause' : 'Play';
    play.classList.toggle('playing', playing);
  });

  document.addEventListener('keydown', (e) => {
    if (e.defaultPrevented || e.ctrlKey || e.metaKey || e.altKey) return;
    const tag = (e.target && e.target.tagName) || '';
    if (/^(INPUT|SELECT|TEXTAREA|BUTTON)$/.test(tag) && !(e.target === scrub && e.key === ' ')) return;
    const f = player.frame;
    if (e.key === ' ') player.toggle();
    else if (e.key === 'ArrowRight') player.setFrame(f + (e.shiftKey ? 10 : 1));
    else if (e.key === 'ArrowLeft') player.setFrame(f - (e.shiftKey ? 10 : 1));
    else if (e.key === 'Home') player.setFrame(0);
    else if (e.key === 'End') player.setFrame(n - 1);
    else return;
    e.preventDefault();
  });

  return { element: bar, showFrame };
}
