// Designer benchmark: in the real browser, the time from a property change on a
// 1024x768 image chain to the updated preview on screen, over 50 changes, next to the executor's
// own run time for the same change (the `finished` events' last_ms of the blocks that re-ran).
// Usage: node bench/designer_preview.mjs   (IMAGENETS_BIN: the built `imagenets`)
import fs from 'node:fs';
import path from 'node:path';
import { launchBrowser, openDesigner, run, startDesigner, tempDir, until, LONG } from '../web/test/harness.mjs';
import { select, setProperty, stats, watch } from '../web/test/actions.mjs';

const changes = 50;
const dir = tempDir('bench');
const image = path.join(dir, 'plasma.png');
const made = run('convert', ['-seed', '7', '-size', '1024x768', 'plasma:', image]);
if (made.code !== 0) throw new Error(made.out);
const net = path.join(dir, 'chain.yaml');
fs.writeFileSync(net, `doc: 1024x768 image chain for the Designer benchmark
blocks:
  source: {type: imagenets/ImageFileSource, properties: {path: ${image}}}
  gray: {type: imagenets/Grayscale}
  blur: {type: imagenets/GaussianBlur, properties: {kernel_size: 5}}
  threshold: {type: imagenets/Threshold, properties: {threshold: 100}}
links:
  - source.image -> gray.image
  - gray.image -> blur.image
  - blur.image -> threshold.image
`);

const designer = await startDesigner({ net });
const browser = await launchBrowser();
try {
  // When each binary frame (port data) reaches the page, to split the time into the server's part
  // (up to the frame's arrival) and the page's (decoding and drawing the preview).
  const page = await openDesigner(browser, designer.url, (p) => p.evaluateOnNewDocument(() => {
    window.benchFrames = [];
    const Native = window.WebSocket;
    window.WebSocket = class extends Native {
      constructor(...args) {
        super(...args);
        this.addEventListener('message', (m) => { if (typeof m.data !== 'string') window.benchFrames.push(performance.now()); });
      }
    };
  }));
  await page.waitForSelector('.react-flow__node[data-id="threshold"]', { timeout: LONG });
  await page.click('[data-testid="run"]');
  await until('the chain ran', async () => (await stats(page, 'threshold')).runs >= 1);
  await watch(page, 'threshold.image');
  await select(page, 'threshold');
  // A second listener on the server's pushes, as another tab would be, for the executor's times;
  // and the moment the user's Enter went down.
  await page.evaluate((url) => new Promise((resolve) => {
    window.benchEvents = [];
    const ws = new WebSocket(url);
    ws.onmessage = (m) => {
      if (typeof m.data !== 'string') return;
      const e = JSON.parse(m.data);
      if (e.op === 'event') window.benchEvents.push({ ...e, time: performance.now() });
    };
    ws.onopen = resolve;
    document.addEventListener('keydown', (e) => { if (e.key === 'Enter') window.benchStart = performance.now(); }, true);
  }), designer.url.replace('http', 'ws') + 'ws');

  const latency = [], executor = [], frame = [];
  for (let i = 0; i < changes; ++i) {
    const shownBefore = await page.evaluate(() => (window.designerShown || []).length);
    await page.evaluate(() => { window.benchEvents.length = 0; });
    await setProperty(page, 'threshold', 100 + (i % 2 ? 20 : 40) + i);
    const r = await until('the updated preview', () => page.evaluate((n) => {
      const shown = window.designerShown.slice(n).find((s) => s.port === 'threshold.image' && s.time > window.benchStart);
      const done = window.benchEvents.some((e) => e.kind === 'run_finished');
      if (!shown || !done) return null;
      const ran = window.benchEvents.filter((e) => e.kind === 'finished' && e.stats);
      const arrived = window.benchFrames.filter((t) => t > window.benchStart && t <= shown.time);
      return { latency: shown.time - window.benchStart, executor: ran.reduce((s, e) => s + e.stats.last_ms, 0),
        frame: arrived.length ? arrived[arrived.length - 1] - window.benchStart : NaN };
    }, shownBefore));
    latency.push(r.latency);
    executor.push(r.executor);
    frame.push(r.frame);
  }
  const stat = (xs) => {
    const s = [...xs].sort((a, b) => a - b);
    return { median: s[Math.floor(s.length / 2)], p95: s[Math.min(s.length - 1, Math.ceil(0.95 * s.length) - 1)] };
  };
  const l = stat(latency), e = stat(executor), f = stat(frame);
  console.log(`designer preview, 1024x768 chain (threshold change -> preview on screen), ${changes} changes:`);
  console.log(`  browser: median ${l.median.toFixed(1)} ms, p95 ${l.p95.toFixed(1)} ms`);
  console.log(`    of which until the preview's frame reached the page: median ${f.median.toFixed(1)} ms, p95 ${f.p95.toFixed(1)} ms`);
  console.log(`  executor run of the same change: median ${e.median.toFixed(1)} ms, p95 ${e.p95.toFixed(1)} ms`);
  console.log(`  designer adds: median ${(l.median - e.median).toFixed(1)} ms (target < 30 ms)`);
} finally {
  await browser.close();
  await designer.stop();
}
