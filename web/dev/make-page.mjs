// Assembles a report page the way pkm does, from the built bundle and synthetic data:
//   node web/dev/make-page.mjs --out FILE.html [--big] [--planar] [--minimal] [--dist DIR] [--data FILE.json]
// The bundle and CSS are taken from DIR (default web/dist; run `node web/build.mjs --out web/dist` first).
import { readFileSync, writeFileSync, mkdirSync } from 'node:fs';
import { dirname, resolve, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { makeSampleData, makeMinimalData } from './sample-data.mjs';

const here = dirname(fileURLToPath(import.meta.url));

const args = { out: null, big: false, planar: false, minimal: false, dist: join(here, '..', 'dist'), data: null };
const argv = process.argv.slice(2);
for (let i = 0; i < argv.length; i++) {
  const a = argv[i];
  if (a === '--out') args.out = argv[++i];
  else if (a === '--big') args.big = true;
  else if (a === '--planar') args.planar = true;
  else if (a === '--minimal') args.minimal = true;
  else if (a === '--dist') args.dist = argv[++i];
  else if (a === '--data') args.data = argv[++i];
  else {
    console.error(`unknown argument: ${a}`);
    process.exit(2);
  }
}
if (!args.out) {
  console.error('usage: node web/dev/make-page.mjs --out FILE.html [--big] [--planar] [--minimal] [--dist DIR] [--data FILE.json]');
  process.exit(2);
}

const escapeHtml = (s) => String(s).replace(/[&<>"]/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' })[c]);
// In JSON every "<" may be written as \u003c: then nothing inside can end the <script> element.
const scriptSafeJson = (v) => JSON.stringify(v).replace(/</g, '\\u003c').replace(/\u2028/g, '\\u2028').replace(/\u2029/g, '\\u2029');

let data;
if (args.data) data = JSON.parse(readFileSync(resolve(args.data), 'utf8'));
else if (args.minimal) data = makeMinimalData();
else {
  data = makeSampleData({
    chartPoints: args.big ? 8000 : 4000,
    frames: args.big ? 3000 : 600,
    variant: args.planar ? 'planar' : 'hexapod',
  });
}

const dist = resolve(args.dist);
const js = readFileSync(join(dist, 'report.bundle.js'), 'utf8');
const css = readFileSync(join(dist, 'report.css'), 'utf8');
const html =
  `<!doctype html><html><head><meta charset="utf-8"><title>${escapeHtml(data.title ?? 'pkm report')}</title>` +
  `<style>${css}</style></head>\n<body><script type="application/json" id="pkm-report-data">${scriptSafeJson(data)}</script>` +
  `<script>${js}</script></body></html>\n`;
const out = resolve(args.out);
mkdirSync(dirname(out), { recursive: true });
writeFileSync(out, html);
console.log(`${out}: ${(Buffer.byteLength(html) / 1024 / 1024).toFixed(2)} MB`);
