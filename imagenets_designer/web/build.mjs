// Bundles the page into dist/ (no CDN: everything the page needs is in dist/).
import * as esbuild from 'esbuild';
import { copyFileSync, mkdirSync } from 'node:fs';

const here = new URL('.', import.meta.url).pathname;
mkdirSync(`${here}dist`, { recursive: true });
await esbuild.build({
  entryPoints: [`${here}src/main.jsx`],
  bundle: true,
  minify: true,
  format: 'esm',
  target: ['chrome110', 'firefox110'],
  jsx: 'automatic',
  define: { 'process.env.NODE_ENV': '"production"' },
  outdir: `${here}dist`,
  logLevel: 'warning',
});
copyFileSync(`${here}index.html`, `${here}dist/index.html`);
copyFileSync(`${here}favicon.svg`, `${here}dist/favicon.svg`);
