// Designer benchmark: in the real browser, the time from a property change on a
// 1024x768 image chain to the updated preview on screen, over 50 changes, next to the executor's
// own run time for the same change (the `finished` events' last_ms of the blocks that re-ran).
// Then drags the threshold slider over its range: previews shown per second while dragging.
// Prints where the time goes (the page's side of the WebSocket, step by step) and SUMMARY rows.
// Usage: node bench/designer_preview.mjs   (IMAGENETS_BIN: the built `imagenets`)
import fs from 'node:fs';
import os from 'node:os';
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
  // A timeline of the page's side of the WebSocket (each request sent, each message handled,
  // binary frames as port data) and of the main thread's long tasks, to split the latency into the
  // server's part (up to the frame's arrival) and the page's (decoding and drawing the preview).
  const page = await openDesigner(browser, designer.url, (p) => p.evaluateOnNewDocument(() => {
    window.benchFrames = [];
    window.benchTimeline = [];
    window.benchLongTasks = [];
    new PerformanceObserver((list) => {
      for (const e of list.getEntries()) window.benchLongTasks.push({ start: e.startTime, ms: e.duration });
    }).observe({ entryTypes: ['longtask'] });
    const Native = window.WebSocket;
    window.WebSocket = class extends Native {
      constructor(...args) {
        super(...args);
        this.benchOwn = (window.benchSockets = (window.benchSockets || 0) + 1) === 1;  // the page's socket, not ours
        if (!this.benchOwn) return;
        this.addEventListener('message', (m) => {
          const time = performance.now();
          if (typeof m.data !== 'string') {
            window.benchFrames.push(time);
            window.benchTimeline.push({ what: 'frame', time, bytes: m.data.byteLength });
          } else {
            const e = JSON.parse(m.data);
            window.benchTimeline.push({ what: e.op === 'event' ? `event ${e.kind}` : e.op, time, bytes: m.data.length });
          }
        });
      }
      send(data) {
        if (!this.benchOwn) { super.send(data); return; }
        const time = performance.now();
        let what = 'send';
        try { what = `send ${JSON.parse(data).op}`; } catch (e) { /* not JSON */ }
        window.benchTimeline.push({ what, time, bytes: data.length });
        super.send(data);
      }
    };
  }));
  // When the browser's network stack received each frame (DevTools protocol), before the page's
  // main thread handled it: the gap is time the page was busy or its task waited to run.
  const cdp = await page.target().createCDPSession();
  await cdp.send('Network.enable');
  const network = [];
  cdp.on('Network.webSocketFrameReceived', (e) => network.push({ what: 'received', at: e.timestamp * 1000, opcode: e.response.opcode, data: e.response.payloadData.slice(0, 200) }));
  cdp.on('Network.webSocketFrameSent', (e) => network.push({ what: 'sent', at: e.timestamp * 1000, data: e.response.payloadData.slice(0, 200) }));
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

  const latency = [], executor = [], frame = [], samples = [];
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
      const t0 = window.benchStart;
      const timeline = window.benchTimeline.filter((e) => e.time > t0 && e.time <= shown.time)
        .map((e) => ({ ...e, time: e.time - t0 }));
      const longTasks = window.benchLongTasks.filter((e) => e.start + e.ms > t0 && e.start <= shown.time)
        .map((e) => ({ start: e.start - t0, ms: e.ms }));
      return { latency: shown.time - t0, executor: ran.reduce((s, e) => s + e.stats.last_ms, 0),
        frame: arrived.length ? arrived[arrived.length - 1] - t0 : NaN, timeline, longTasks };
    }, shownBefore));
    latency.push(r.latency);
    executor.push(r.executor);
    frame.push(r.frame);
    samples.push(r);
    r.network = network.splice(0);
  }
  const stat = (xs) => {
    const s = [...xs].sort((a, b) => a - b);
    return { median: s[Math.floor(s.length / 2)], p95: s[Math.min(s.length - 1, Math.ceil(0.95 * s.length) - 1)] };
  };
  const l = stat(latency), e = stat(executor), f = stat(frame);
  const load = os.loadavg()[0].toFixed(1);
  console.log(`designer preview, 1024x768 chain (threshold change -> preview on screen), ${changes} changes, load average ${load}:`);
  console.log(`  browser (Enter in the property field -> preview drawn): median ${l.median.toFixed(1)} ms, p95 ${l.p95.toFixed(1)} ms`);
  console.log(`    of which until the preview's frame reached the page: median ${f.median.toFixed(1)} ms, p95 ${f.p95.toFixed(1)} ms`);
  console.log(`  executor run of the same change (blocks' own time): median ${e.median.toFixed(1)} ms, p95 ${e.p95.toFixed(1)} ms`);
  const above = { median: l.median - e.median, p95: l.p95 - e.p95 };
  console.log(`  designer adds: median ${above.median.toFixed(1)} ms (target <= 16 ms), p95 ${above.p95.toFixed(1)} ms (target <= 33 ms)`);
  printSummary('Designer: change -> preview shown, above executor, median ms', above.median, NaN, '<= 16 ms', above.median <= 16);
  printSummary('Designer: change -> preview shown, above executor, p95 ms', above.p95, NaN, '<= 33 ms', above.p95 <= 33);
  printBreakdown(samples, stat);
  await dragSlider(page);
} finally {
  await browser.close();
  await designer.stop();
}

// Where the time goes: the median moment of each step after Enter, and the change of median
// latency with its messages and the main thread's long tasks.
function printBreakdown(samples, stat) {
  const at = (what) => stat(samples.map((s) => s.timeline.find((e) => e.what === what)?.time ?? NaN).filter(Number.isFinite));
  console.log('  steps after Enter (median ms): ' + ['send set_property', 'event run_finished', 'frame', 'reply', 'net']
    .map((w) => `${w} ${at(w).median?.toFixed(1)}`).join(', ') + `, shown ${stat(samples.map((s) => s.latency)).median.toFixed(1)}`);
  const long = stat(samples.map((s) => s.longTasks.reduce((a, t) => a + t.ms, 0)));
  console.log(`  main thread in long tasks (>50 ms) between Enter and shown: median ${long.median.toFixed(1)} ms`);
  // The network stack's clock: its set_property "sent" is the page's send.
  for (const s of samples) {
    const sent = s.network.find((n) => n.what === 'sent' && n.data.includes('set_property'));
    const send = s.timeline.find((e) => e.what === 'send set_property');
    if (!sent || !send) continue;
    const offset = sent.at - send.time;
    s.received = s.network.filter((n) => n.what === 'received').map((n) => ({ ...n, at: n.at - offset }));
  }
  const firstIn = stat(samples.filter((s) => s.received?.length).map((s) => s.received[0].at));
  const frameIn = stat(samples.filter((s) => s.received?.length).map((s) => s.received.find((n) => n.opcode === 2)?.at ?? NaN).filter(Number.isFinite));
  console.log(`  network stack received (median ms after Enter): first message ${firstIn.median?.toFixed(1)}, frame ${frameIn.median?.toFixed(1)}`);
  const typical = [...samples].sort((a, b) => a.latency - b.latency)[Math.floor(samples.length / 2)];
  console.log('  the median change: ' + typical.timeline.map((e) => `${e.what}@${e.time.toFixed(1)}`).join(' ') +
    ` shown@${typical.latency.toFixed(1)}` + ` | network: ${(typical.received || []).map((n) => `${n.opcode === 2 ? 'frame' : n.data.slice(0, 30)}@${n.at.toFixed(1)}`).join(' ')}` + (typical.longTasks.length ? ` long tasks ${typical.longTasks.map((t) => `${t.start.toFixed(0)}+${t.ms.toFixed(0)}`).join(' ')}` : ''));
}

// Drags the threshold slider from end to end over about 2 s (a move every 16 ms, as a display
// frame), then lets go: how many previews the page showed while dragging, and how many changes it
// sent (one in flight at a time, the newest value next).
async function dragSlider(page) {
  const slider = await page.waitForSelector('[data-testid="slider-threshold"]', { visible: true, timeout: LONG });
  const box = await slider.boundingBox();
  const y = box.y + box.height / 2;
  await page.mouse.move(box.x + 1, y);
  const start = await page.evaluate(() => ({ time: performance.now(), shown: window.designerShown.length, sent: window.benchTimeline.length }));
  await page.mouse.down();
  const moves = 120;
  for (let k = 1; k <= moves; ++k) {
    await page.mouse.move(box.x + 1 + ((box.width - 2) * k) / moves, y);
    await new Promise((r) => setTimeout(r, 16));
  }
  await page.mouse.up();
  const end = await page.evaluate(() => performance.now());
  const last = await page.$eval('[data-testid="slider-threshold"]', (s) => s.value);
  // The last value reaches the net and its preview is shown.
  await until('the dragged value in the net', async () => (await page.$eval('[data-testid="property-threshold"]', (f) => f.value)) === last);
  const r = await until('the last preview', () => page.evaluate((start, end) => {
    const shown = window.designerShown.slice(start.shown).filter((s) => s.port === 'threshold.image');
    const sent = window.benchTimeline.slice(start.sent).filter((e) => e.what === 'send set_property').length;
    const during = shown.filter((s) => s.time <= end).length;
    return shown.length ? { during, sent, last: shown[shown.length - 1].time - end, seconds: (end - start.time) / 1000 } : null;
  }, start, end));
  await new Promise((resolve) => setTimeout(resolve, 500));
  const after = await page.evaluate((start) => window.designerShown.slice(start.shown).filter((s) => s.port === 'threshold.image').length, start);
  console.log(`  slider dragged over its range (${moves} moves in ${r.seconds.toFixed(2)} s): ${(r.during / r.seconds).toFixed(1)} ` +
    `previews shown per second while dragging (${r.during} previews, ${r.sent} changes sent, ${after - r.during} after letting go)`);
  printSummary('Designer: previews/s while dragging the threshold slider', r.during / r.seconds, NaN, '', false);
}

// One row of the summary table of `make bench` (as imagenets/bench_summary.h prints it).
function printSummary(figure, ours, baseline, target, met) {
  const number = (v) => (Number.isFinite(v) ? String(Number(v.toPrecision(4))) : '-');
  const ratio = Number.isFinite(ours) && Number.isFinite(baseline) && baseline !== 0 ? ours / baseline : NaN;
  console.log(['SUMMARY', figure, number(ours), number(baseline), number(ratio), target || '-', target ? (met ? 'yes' : 'no') : '-'].join('\t'));
}
