// How long the HTML report of a 100 000-line program takes to open (goal: under 3 s), for
// docs/PERFORMANCE.md. Generates the program (scripts/gen-long-program.py), plans it with pkm --report, then
// opens the page in headless Chromium several times and prints the time from navigation to pkmReport.ready
// (the 3-D view drawn and the first plots built) and to every plot built, and the page's size.
// Usage: node bench/report_open_time.mjs [--pkm build/pkm] [--out build/report-bench] [--lines 100000] [--runs 5]
import { execFileSync } from 'node:child_process';
import { mkdirSync, statSync } from 'node:fs';
import { createRequire } from 'node:module';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const root = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const require = createRequire(join(root, 'web/package.json'));
const { chromium } = require('playwright-core');
const { CHROMIUM_ARGS } = await import(pathToFileURL(join(root, 'web/dev/chromium.mjs')).href);

const args = { pkm: join(root, 'build/pkm'), out: join(root, 'build/report-bench'), lines: '100000', runs: '5' };
for (let i = 2; i < process.argv.length; i += 2) args[process.argv[i].replace(/^--/, '')] = process.argv[i + 1];
mkdirSync(args.out, { recursive: true });
const program = join(args.out, 'long.ngc');
execFileSync('python3', [join(root, 'scripts/gen-long-program.py'), program, args.lines]);
const page_file = join(args.out, 'report.html');
let started = Date.now();
execFileSync(resolve(args.pkm), ['plan', program, '--machine', join(root, 'examples/machines/hexapod_ch5.yaml'),
                                 '--out', join(args.out, 'run'), '--report', page_file], { stdio: 'inherit' });
console.log(`pkm plan --report: ${((Date.now() - started) / 1000).toFixed(1)} s`);
started = Date.now();
execFileSync(resolve(args.pkm), ['report', join(args.out, 'run'), '--out', join(args.out, 'again.html')]);
console.log(`pkm report (from the run's files): ${((Date.now() - started) / 1000).toFixed(1)} s`);
console.log(`page: ${(statSync(page_file).size / 1e6).toFixed(2)} MB`);

const browser = await chromium.launch({ executablePath: process.env.CHROMIUM || '/usr/bin/chromium', args: CHROMIUM_ARGS });
const ready = [], all = [];
for (let run = 0; run < Number(args.runs); run++) {
  const page = await browser.newPage({ viewport: { width: 1400, height: 900 } });
  await page.goto(pathToFileURL(page_file).href, { waitUntil: 'load', timeout: 60000 });
  await page.waitForFunction(() => window.pkmReport && window.pkmReport.ready, null, { timeout: 60000, polling: 10 });
  ready.push(await page.evaluate(() => window.pkmReport.readyAt ?? performance.now()));
  await page.waitForFunction(() => window.pkmReport.builtCharts() === window.pkmReport.chartCount, null,
                             { timeout: 60000, polling: 10 });
  all.push(await page.evaluate(() => performance.now()));
  await page.close();
}
await browser.close();
const median = (v) => [...v].sort((a, b) => a - b)[Math.floor(v.length / 2)];
console.log(`time to ready: median ${median(ready).toFixed(0)} ms (runs: ${ready.map((t) => t.toFixed(0)).join(', ')})`);
console.log(`time to every plot built: median ${median(all).toFixed(0)} ms (runs: ${all.map((t) => t.toFixed(0)).join(', ')})`);
