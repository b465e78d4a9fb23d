// Bundles the report page: `node web/build.mjs OUTDIR` writes OUTDIR/report.js (one minified
// IIFE with three, uPlot and KaTeX inlined) and OUTDIR/report.css (uPlot's and KaTeX's CSS plus
// ours, KaTeX's fonts inlined as woff2 data: URLs). The page loads nothing at run time.
// Exits non-zero on any error.
import * as esbuild from 'esbuild';
import { mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const modules = join(here, 'node_modules');

// KaTeX's stylesheet names three formats per font (woff2, woff, ttf). Every browser that runs
// the page reads woff2, so only those are kept and inlined; the others would triple the size.
function katexCss() {
  const dist = join(modules, 'katex', 'dist');
  const css = readFileSync(join(dist, 'katex.css'), 'utf8');
  let fonts = 0;
  const out = css.replace(/src:\s*([^;}]*)/g, (_, list) => {
    const woff2 = /url\((fonts\/[^)]+\.woff2)\)\s*format\("woff2"\)/.exec(list);
    if (!woff2) throw new Error(`katex.css: a @font-face without a woff2 source: ${list}`);
    const data = readFileSync(join(dist, woff2[1])).toString('base64');
    fonts += 1;
    return `src:url(data:font/woff2;base64,${data}) format("woff2")`;
  });
  if (fonts === 0) throw new Error('katex.css: no @font-face found (KaTeX changed its layout?)');
  if (/url\((?!data:)/.test(out)) throw new Error('katex.css: a url() left that is not a data: URL');
  return out;
}

async function main() {
  const outArg = process.argv[2];
  if (!outArg) throw new Error('usage: node build.mjs OUTDIR');
  const outDir = resolve(outArg);
  mkdirSync(outDir, { recursive: true });

  const js = await esbuild.build({
    entryPoints: [join(here, 'src', 'main.js')],
    bundle: true,
    format: 'iife',
    minify: true,
    target: ['es2020'],
    legalComments: 'none',
    write: false,
    logLevel: 'warning',
    // ASCII only (the default, said here because it matters): every other character is
    // escaped, so the bundle embeds in a C++ raw string with no bidirectional control character
    // (GCC's -Werror=bidi-chars) or carriage return, and reads the same in any encoding
    charset: 'ascii',
  });
  let code = js.outputFiles[0].text;
  // esbuild escapes non-ASCII characters in strings but keeps them in regular expression
  // literals (KaTeX has /[\u00ee…]/): each UTF-16 unit written as \uXXXX means the same there,
  // in strings and in identifiers
  code = code.replace(/[^\x00-\x7e]/g, (c) => `\\u${c.charCodeAt(0).toString(16).padStart(4, '0')}`);
  code = code.replace(/<\/(script)/gi, '<\\/$1');

  const css = [
    readFileSync(join(modules, 'uplot', 'dist', 'uPlot.min.css'), 'utf8'),
    katexCss(),
    readFileSync(join(here, 'src', 'report.css'), 'utf8'),
  ].join('\n');
  const cssMin = await esbuild.transform(css, { loader: 'css', minify: true, legalComments: 'none', charset: 'ascii' });
  const cssText = cssMin.code.replace(/<\/(style)/gi, '<\\/$1');
  // the page is one inline <script> and one <style>: neither may hold the text that closes it
  for (const [name, text] of [['report.js', code], ['report.css', cssText]]) {
    const bad = /[^\x20-\x7e\n\t]/.exec(text);
    if (bad) throw new Error(`${name}: character U+${bad[0].codePointAt(0).toString(16)} at ${bad.index}; the bundle must be printable ASCII`);
  }

  writeFileSync(join(outDir, 'report.js'), code);
  writeFileSync(join(outDir, 'report.css'), cssText);
  console.log(`build.mjs: ${join(outDir, 'report.js')} (${code.length} B), ` +
              `${join(outDir, 'report.css')} (${cssText.length} B)`);
}

main().catch((e) => {
  console.error(`build.mjs: error: ${e.message}`);
  process.exit(1);
});
