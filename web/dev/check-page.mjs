// Opens a report page in headless Chromium and checks it:
//   node web/dev/check-page.mjs FILE.html [--screenshot OUT.png] [--chromium PATH] [--timeout MS]
// Fails (exit 1) on any console error/warning or page error, when pkmReport.ready does not come, when the
// WebGL canvas is empty, or when scrubbing does not show a program line.
import { chromium } from 'playwright-core';
import { existsSync } from 'node:fs';
import { resolve } from 'node:path';
import { pathToFileURL } from 'node:url';

// The flags (SwiftShader WebGL, no --disable-gpu) are shared with tests/browser/ in chromium.mjs.
import { CHROMIUM_ARGS } from './chromium.mjs';

function parseArgs(argv) {
  const a = { file: null, screenshot: null, chromium: process.env.CHROMIUM || '/usr/bin/chromium', timeout: 20000, width: 1400, height: 900 };
  for (let i = 0; i < argv.length; i++) {
    const x = argv[i];
    if (x === '--screenshot') a.screenshot = argv[++i];
    else if (x === '--chromium') a.chromium = argv[++i];
    else if (x === '--timeout') a.timeout = Number(argv[++i]);
    else if (x === '--size') [a.width, a.height] = argv[++i].split('x').map(Number);
    else if (!a.file) a.file = x;
    else throw new Error(`unexpected argument: ${x}`);
  }
  if (!a.file) throw new Error('usage: node web/dev/check-page.mjs FILE.html [--screenshot OUT.png] [--chromium PATH] [--size WxH]');
  return a;
}

async function main() {
  const args = parseArgs(process.argv.slice(2));
  const file = resolve(args.file);
  if (!existsSync(file)) throw new Error(`no such file: ${file}`);
  if (!existsSync(args.chromium)) throw new Error(`no Chromium at ${args.chromium} (apt-get install chromium, or --chromium PATH)`);

  const failures = [];
  const browser = await chromium.launch({ executablePath: args.chromium, headless: true, args: CHROMIUM_ARGS });
  try {
    const page = await browser.newPage({ viewport: { width: args.width, height: args.height } });
    const messages = [];
    page.on('console', (m) => {
      messages.push(`${m.type()}: ${m.text()}`);
      if (m.type() === 'error' || m.type() === 'warning') failures.push(`console ${m.type()}: ${m.text()}`);
    });
    page.on('pageerror', (e) => failures.push(`page error: ${e.message}`));
    page.on('requestfailed', (r) => failures.push(`request failed: ${r.url()}`));
    page.on('request', (r) => {
      const u = r.url();
      if (!u.startsWith('file:') && !u.startsWith('data:') && !u.startsWith('blob:')) failures.push(`network request: ${u}`);
    });

    await page.goto(pathToFileURL(file).href, { waitUntil: 'load', timeout: args.timeout });
    await page.waitForFunction(() => window.pkmReport && window.pkmReport.ready === true, null, { timeout: args.timeout, polling: 20 });
    const timing = await page.evaluate(() => {
      const nav = performance.getEntriesByType('navigation')[0];
      return { ready: performance.now(), domContentLoaded: nav ? nav.domContentLoadedEventEnd : null, load: nav ? nav.loadEventEnd : null };
    });
    // performance.now() is measured from navigation start; `ready` was read right after the flag became true
    // (polling every 20 ms), so this is at most ~20 ms late. The page also records its own time below.
    const own = await page.evaluate(() => window.pkmReport.readyAt ?? null);
    const readyMs = own ?? timing.ready;
    console.log(`time to ready: ${readyMs.toFixed(0)} ms (DOMContentLoaded ${timing.domContentLoaded?.toFixed(0)} ms)`);

    const info = await page.evaluate(() => ({
      frames: window.pkmReport.frameCount,
      charts: window.pkmReport.chartCount,
      built: window.pkmReport.builtCharts ? window.pkmReport.builtCharts() : null,
      pixels: window.pkmReport.canvasHasPixels(),
    }));
    console.log(`frames ${info.frames}, charts ${info.charts} (${info.built} built at ready)`);
    if (!info.pixels) failures.push('the 3-D canvas has no pixels other than the background');
    else console.log('3-D canvas: has pixels');

    if (info.frames > 0) {
      const mid = Math.floor(info.frames / 2);
      const r = await page.evaluate((i) => {
        window.pkmReport.setFrame(i);
        return {
          frame: window.pkmReport.currentFrame(),
          line: window.pkmReport.currentLine(),
          text: document.getElementById('current-line').textContent,
          slider: Number(document.getElementById('scrub').value),
          time: document.getElementById('current-time').textContent,
        };
      }, mid);
      console.log(`frame ${r.frame} (t = ${r.time} s): ${r.text}`);
      if (r.frame !== mid || r.slider !== mid) failures.push(`setFrame(${mid}) left frame ${r.frame}, slider ${r.slider}`);
      if (r.line > 0 && !r.text.startsWith(`line ${r.line}`)) failures.push(`#current-line "${r.text}" does not show line ${r.line}`);
      if (!(await page.evaluate(() => window.pkmReport.canvasHasPixels()))) failures.push('the 3-D canvas is empty after setFrame');
    }

    if (args.screenshot) {
      // Let the idle-time chart building finish so the whole page is drawn.
      await page.waitForFunction(() => !window.pkmReport.builtCharts || window.pkmReport.builtCharts() === window.pkmReport.chartCount, null, { timeout: args.timeout });
      await page.screenshot({ path: resolve(args.screenshot), fullPage: true });
      console.log(`screenshot: ${resolve(args.screenshot)}`);
    }
    if (process.env.PKM_CHECK_VERBOSE) for (const m of messages) console.log(`  console ${m}`);
  } finally {
    await browser.close();
  }
  if (failures.length) {
    for (const f of failures) console.error(`FAIL: ${f}`);
    process.exit(1);
  }
  console.log('OK');
}

main().catch((e) => {
  console.error(`check-page: ${e.message}`);
  process.exit(1);
});
