// The animation's state: current frame, play/pause and speed. Playback advances by real time (frames.time_s)
// with requestAnimationFrame and stops the loop when paused, so an idle page costs nothing.

export function createPlayer(frames) {
  const n = frames.count;
  const time = frames.time_s;
  const frameListeners = new Set();
  const stateListeners = new Set();
  let frame = 0;
  let playing = false;
  let speed = 1;
  let clock = n ? time[0] : 0; // playback time, s (between frame times while playing)
  let lastTs = null;
  let raf = 0;

  const firstFrameOfLine = new Map();
  frames.line.forEach((l, i) => {
    if (l && !firstFrameOfLine.has(l)) firstFrameOfLine.set(l, i);
  });

  /** Index of the last frame with time <= t (0 when t is before the first frame). */
  function frameAtTime(t) {
    let lo = 0;
    let hi = n - 1;
    if (n === 0 || !(t > time[0])) return 0;
    if (t >= time[hi]) return hi;
    while (hi - lo > 1) {
      const mid = (lo + hi) >> 1;
      if (time[mid] <= t) lo = mid;
      else hi = mid;
    }
    return lo;
  }

  function emitFrame() {
    for (const f of frameListeners) f(frame);
  }
  function emitState() {
    for (const f of stateListeners) f({ playing, speed });
  }

  function setFrame(i, keepClock = false) {
    if (n === 0) return;
    const j = Math.max(0, Math.min(n - 1, Math.round(Number(i) || 0)));
    if (!keepClock) clock = time[j];
    if (j === frame) return;
    frame = j;
    emitFrame();
  }

  function tick(ts) {
    raf = 0;
    if (!playing) return;
    if (lastTs != null) clock += (Math.min(250, ts - lastTs) / 1000) * speed;
    lastTs = ts;
    if (clock >= time[n - 1]) {
      setFrame(n - 1);
      pause();
      return;
    }
    const i = frameAtTime(clock);
    if (i !== frame) setFrame(i, true);
    raf = requestAnimationFrame(tick);
  }

  function play() {
    if (n < 2 || playing) return;
    if (frame >= n - 1) setFrame(0);
    playing = true;
    lastTs = null;
    raf = requestAnimationFrame(tick);
    emitState();
  }

  function pause() {
    if (!playing) return;
    playing = false;
    if (raf) cancelAnimationFrame(raf);
    raf = 0;
    emitState();
  }

  return {
    count: n,
    get frame() {
      return frame;
    },
    get playing() {
      return playing;
    },
    get speed() {
      return speed;
    },
    time: (i = frame) => (n ? time[i] : 0),
    line: (i = frame) => (n ? frames.line[i] || 0 : 0),
    setFrame,
    frameAtTime,
    /** Moves to the frame nearest to time t (s). */
    seekTime(t) {
      if (n === 0) return;
      const i = frameAtTime(t);
      const j = i + 1 < n && Math.abs(time[i + 1] - t) < Math.abs(time[i] - t) ? i + 1 : i;
      setFrame(j);
    },
    /** First frame of program line `line`, or -1. */
    frameOfLine: (line) => firstFrameOfLine.get(Number(line)) ?? -1,
    play,
    pause,
    toggle: () => (playing ? pause() : play()),
    setSpeed(s) {
      speed = Number(s) > 0 ? Number(s) : 1;
      emitState();
    },
    onFrame: (f) => frameListeners.add(f),
    onState: (f) => stateListeners.add(f),
    /** Tells every listener about the current frame again (initial display). */
    refresh: emitFrame,
  };
}
