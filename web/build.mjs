// Builds the report page's script bundle and style sheet for pkm's single-file HTML report.
//   node web/build.mjs --out DIR     ->  DIR/report.bundle.js, DIR/report.css
// Works from any working directory. Fails (exit 1) if the bundle or the CSS could end the <script>/<style>
// element they are inlined into.
import { build } from 'esbuild';
import { readFileSync, writeFileSync, mkdirSync } from 'node:fs';
import { dirname, resolve, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));

function parseArgs(argv) {
  const args = { out: null, sourcemap: false };
  for (let i = 0; i < argv.length; i++) {
    if (argv[i] === '--out') args.out = argv[++i];
    else if (argv[i].startsWith('--out=')) args.out = argv[i].slice(6);
    else if (argv[i] === '--help' || argv[i] === '-h') args.help = true;
    else throw new Error(`unknown argument: ${argv[i]}`);
  }
  return args;
}

async function main() {
  const args = parseArgs(process.argv.slice(2));
  if (args.help || !args.out) {
    console.log('usage: node web/build.mjs --out DIR');
    process.exit(args.help ? 0 : 2);
  }
  const outDir = resolve(process.cwd(), args.out);
  mkdirSync(outDir, { recursive: true });

  const result = await build({
    absWorkingDir: here,
    entryPoints: [join(here, 'src/main.js')],
    bundle: true,
    format: 'iife',
    minify: true,
    treeShaking: true,
    target: 'es2020',
    platform: 'browser',
    legalComments: 'none',
    charset: 'ascii',
    write: false,
    logLevel: 'warning',
    define: { 'process.env.NODE_ENV': '"production"' },
  });
  let js = result.outputFiles[0].text;
  // A literal "</script" (any case) would end the inline <script> element early.
  if (/<\/script/i.test(js)) {
    // esbuild keeps string contents; escape the slash inside string literals is not safe to do blindly, so fail.
    throw new Error('bundle contains "</script" - it cannot be inlined into the HTML report');
  }
  if (/<!--/.test(js)) throw new Error('bundle contains "<!--" - it cannot be inlined safely into the HTML report');

  const ownCss = readFileSync(join(here, 'src/report.css'), 'utf8');
  const uplotCss = readFileSync(join(here, 'node_modules/uplot/dist/uPlot.min.css'), 'utf8');
  const css = `${uplotCss.trim()}\n${minifyCss(ownCss)}\n`;
  if (/<\/style/i.test(css)) throw new Error('CSS contains "</style" - it cannot be inlined into the HTML report');

  writeFileSync(join(outDir, 'report.bundle.js'), js);
  writeFileSync(join(outDir, 'report.css'), css);
  const kb = (n) => `${(n / 1024).toFixed(1)} KB`;
  console.log(`report.bundle.js ${kb(Buffer.byteLength(js))}, report.css ${kb(Buffer.byteLength(css))} -> ${outDir}`);
  if (Buffer.byteLength(js) > 700 * 1024) throw new Error('bundle is larger than 700 KB');
}

/** Removes comments and redundant white space (the CSS is ours and simple: no strings with braces). */
function minifyCss(s) {
  return s
    .replace(/\/\*[\s\S]*?\*\//g, '')
    .replace(/\s+/g, ' ')
    .replace(/\s*([{};,>])\s*/g, '$1')
    .replace(/;}/g, '}')
    .trim();
}

main().catch((e) => {
  console.error(`build.mjs: ${e.message}`);
  process.exit(1);
});
