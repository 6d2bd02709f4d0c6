// The Designer in a real browser, as docs/designer.md describes it: Debian's chromium, driven by puppeteer-core,
// on the real `imagenets designer`. Everything is done as a user does it, with mouse and keyboard;
// counts and states are the server's (shown on the nodes), and the saved file is checked by the
// engine itself (`imagenets validate`, `imagenets run`).
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { LONG, copyConfig, launchBrowser, openDesigner, run, startDesigner, tempDir, until, imagenets } from './harness.mjs';
import {
  allStats, blockNames, click, connect, dragBlock, link, dragBlockIn, newBlock, linkIds, message, nodeSel, select, setProperty, stats, watch,
} from './actions.mjs';

let browser;
before(async () => { browser = await launchBrowser(); });
after(async () => { await browser?.close(); });

// A gradient with one known pixel: (5, 7) = rgb(200, 100, 50).
function makeImage(dir) {
  const file = path.join(dir, 'gradient.png');
  const made = run('convert', ['-size', '64x48', 'gradient:black-white', '-rotate', '90', '-fill', 'rgb(200,100,50)',
    '-draw', 'point 5,7', `PNG24:${file}`]);
  assert.equal(made.code, 0, made.out);
  return file;
}

// Moves the mouse onto image pixel (x, y) in the data dialog; returns the readout text.
async function readPixel(page, x, y) {
  const canvas = await page.waitForSelector('.image-canvas[data-scale]', { timeout: LONG });
  const box = await canvas.boundingBox();
  const view = await canvas.evaluate((c) => ({ scale: Number(c.dataset.scale), x: Number(c.dataset.offsetX), y: Number(c.dataset.offsetY) }));
  await page.mouse.move(box.x + view.x + (x + 0.5) * view.scale, box.y + view.y + (y + 0.5) * view.scale);
  return until(`the readout of pixel ${x},${y}`, () => page.$eval('[data-testid="pixel-readout"]', (r) => r.textContent)
    .then((t) => (t.includes(`x=${x} y=${y}`) ? t : null)));
}

async function closeDialog(page) {
  await page.keyboard.press('Escape');
  await until('the dialog to close', async () => !(await page.$('.modal')));
}

async function untilStats(page, what, check) {
  return until(what, async () => {
    const s = await allStats(page);
    return check(s) ? s : null;
  });
}

test('a user draws, runs, inspects, undoes and saves a net', { timeout: 600000 }, async (t) => {
  const dir = tempDir('draw');
  const image = makeImage(dir);
  const config = copyConfig(dir);
  const designer = await startDesigner({ roots: [dir] });
  t.after(() => designer.stop());
  const page = await openDesigner(browser, designer.url);
  // The steps build on each other: after a failed one the rest are skipped, not timed out.
  let failed = false;
  const step = (name, fn) => t.test(name, async (s) => {
    if (failed) { s.skip('an earlier step failed'); return; }
    try { await fn(); } catch (e) {
      failed = true;
      const shot = path.join(dir, 'failed-step.png');
      await page.screenshot({ path: shot }).catch(() => {});
      throw new Error(`${e.message}\n(page at the failure: ${shot}; message: ${JSON.stringify(await message(page).catch(() => null))}; console: ${page.logs.slice(-10).join(' | ')})`, { cause: e });
    }
  });
  const canvas = await (await page.$('.canvas')).boundingBox();
  let source, gray, threshold, quality, executor;
  const at = (fx, fy) => [canvas.x + fx * canvas.width, canvas.y + fy * canvas.height];

  await step('finds Grayscale by search and by output type', async () => {
    await page.type('[data-testid="block-search"]', 'grayscale');
    await until('only matching entries', async () => {
      const types = await page.$$eval('.block-entry', (es) => es.map((e) => e.dataset.type));
      return types.includes('imagenets/Grayscale') && !types.includes('imagenets/Threshold');
    });
    await page.$eval('[data-testid="block-search"]', (i) => i.select());
    await page.keyboard.press('Backspace');
    await page.select('[data-testid="filter-output"]', 'sensor_msgs/Image');
    await page.select('[data-testid="filter-input"]', 'sensor_msgs/Image');
    const types = await page.$$eval('.block-entry', (es) => es.map((e) => e.dataset.type));
    assert.ok(types.includes('imagenets/Grayscale'), types.join());
    assert.ok(!types.includes('imagenets/ImageFileSource'), 'a block without an image input is filtered out');
    assert.ok(!types.includes('imagenets/SegmentationQuality'), 'a block without an image output is filtered out');
    await page.select('[data-testid="filter-output"]', '');
    await page.select('[data-testid="filter-input"]', '');
  });

  await step('drags ImageFileSource, Grayscale, Threshold, SegmentationQuality in and links them', async () => {
    source = await dragBlockIn(page, 'imagenets/ImageFileSource', ...at(0.12, 0.3));
    gray = await dragBlockIn(page, 'imagenets/Grayscale', ...at(0.4, 0.3));
    threshold = await dragBlockIn(page, 'imagenets/Threshold', ...at(0.68, 0.2));
    quality = await dragBlockIn(page, 'imagenets/SegmentationQuality', ...at(0.68, 0.55));
    await select(page, source);
    await setProperty(page, 'path', image);
    await until('the path set', async () => (await page.$eval('[data-testid="yaml"]', (y) => y.value)).includes('gradient.png'));
    await link(page, `${source}.image`, `${gray}.image`);
    await link(page, `${gray}.image`, `${threshold}.image`);
    await link(page, `${gray}.image`, `${quality}.gray`);
    await link(page, `${threshold}.image`, `${quality}.binary`);
    await until('four links', async () => (await linkIds(page)).length === 4);
    assert.deepEqual(await linkIds(page), [
      `${gray}.image->${quality}.gray`, `${gray}.image->${threshold}.image`,
      `${source}.image->${gray}.image`, `${threshold}.image->${quality}.binary`].sort());
  });

  await step('a link between different types is refused with the engine\'s reason', async () => {
    const [x, y] = at(0.3, 0.75);
    await page.mouse.click(...at(0.3, 0.9)); // clears the selection
    await page.mouse.click(x, y, { clickCount: 2 });
    await page.waitForSelector('[data-testid="block-search-popup"] input', { timeout: LONG });
    await page.keyboard.type('CameraInfoFile');
    await page.keyboard.press('Enter');
    const camera = await until('the camera block', async () => (await blockNames(page)).find((n) => ![source, gray, threshold, quality].includes(n)));
    await connect(page, `${camera}.camera_info`, `${threshold}.image`);
    const m = await until('the refusal', async () => { const s = await message(page); return s.error && s.text ? s : null; });
    assert.match(m.text, /sensor_msgs\/CameraInfo/);
    assert.match(m.text, /sensor_msgs\/Image/);
    assert.equal((await linkIds(page)).length, 4);
    await select(page, camera);
    await page.keyboard.press('Delete');
    await until('the camera block removed', async () => !(await blockNames(page)).includes(camera));
  });

  await step('Ctrl+Enter runs the net; a property change re-runs only the block and its downstream', async () => {
    await page.mouse.click(...at(0.3, 0.9));
    await page.keyboard.down('Control');
    await page.keyboard.press('Enter');
    await page.keyboard.up('Control');
    const once = await untilStats(page, 'every block ok once', (s) => [source, gray, threshold, quality].every((n) => s[n].status === 'ok' && s[n].runs === 1));
    // The footer shows what the run cost the block's thread beside its wall time.
    assert.ok(once[gray].cpuMs > 0, `gray's CPU time ${once[gray].cpuMs}`);
    assert.match(await page.$eval(`${nodeSel(gray)} .cpu`, (e) => e.textContent), /^CPU \d+\.\d+ \/ \d+\.\d+ ms$/);
    await select(page, threshold);
    await setProperty(page, 'threshold', 100);
    const s = await untilStats(page, 'threshold and quality re-run', (x) => x[threshold].runs === 2 && x[quality].runs === 2);
    assert.equal(s[source].runs, 1);
    assert.equal(s[gray].runs, 1);
  });

  await step('an invalid property value is refused with the engine\'s error', async () => {
    await setProperty(page, 'threshold', 999);
    const error = await page.waitForSelector('[data-testid="property-error"]', { timeout: LONG });
    const text = await error.evaluate((e) => e.textContent);
    assert.match(text, /threshold/);
    assert.match(text, /999/);
  });

  await step('runs one block', async () => {
    await select(page, gray);
    await click(page, '[data-testid="run-block"]');
    await untilStats(page, 'gray ran once more', (s) => s[gray].runs === 2);
    assert.equal((await stats(page, source)).runs, 1);
  });

  await step('the data dialog reads known pixels', async () => {
    await click(page, `button.open-data[data-port="${source}.image"]`);
    const colour = await readPixel(page, 5, 7);
    assert.match(colour, /bgr8|rgb8/);
    assert.match(colour, colour.includes('bgr8') ? /value=50, 100, 200/ : /value=200, 100, 50/);
    await closeDialog(page);
    await click(page, `button.open-data[data-port="${gray}.image"]`);
    const g = await readPixel(page, 5, 7);
    assert.match(g, /mono8/);
    assert.match(g, /value=124\b/); // 0.299*200 + 0.587*100 + 0.114*50
    await closeDialog(page);
  });

  await step('feedback on the threshold shows the trace plot', async () => {
    await select(page, threshold);
    const property = '.property[data-property="threshold"]';
    await click(page, `${property} [data-testid="feedback-on"]`);
    for (const [key, value] of [['from', 40], ['to', 200], ['step', 10]]) {
      await page.$eval(`${property} [data-testid="feedback-${key}"]`, (i) => i.select());
      await page.type(`${property} [data-testid="feedback-${key}"]`, String(value));
    }
    assert.equal(await page.$eval(`${property} [data-testid="feedback-score"]`, (s) => s.value), `${quality}.score`);
    await click(page, `${property} [data-testid="feedback-apply"]`);
    await page.waitForSelector(`button.watch[data-port="${threshold}.feedback_trace"]`, { timeout: LONG });
    const runs = (await stats(page, threshold)).runs;
    await click(page, '[data-testid="run"]');
    await untilStats(page, 'the feedback run done', (s) => s[threshold].runs > runs && s[threshold].status === 'ok');
    await until('the run reported', async () => /^ran /.test((await message(page)).text));
    await watch(page, `${threshold}.feedback_trace`);
    const dots = await page.$$eval(`${nodeSel(threshold)} [data-testid="trace-plot"] .plot-dot`, (d) => d.length);
    assert.equal(dots, 17); // 40, 50, ..., 200
    assert.ok(await page.$(`${nodeSel(threshold)} .plot-chosen`), 'the chosen value is marked');
  });

  await step('opens a sub-net', async () => {
    // An Executor cannot exist without its net: dropping one asks for the file.
    const before = new Set(await blockNames(page));
    await dragBlock(page, 'imagenets/Executor', ...at(0.4, 0.7));
    const field = await page.waitForSelector('[data-testid="file-path"]', { timeout: LONG });
    await field.evaluate((i) => i.select());
    await page.keyboard.type(path.join(config, 'nets/segmentation_subnet.yaml'));
    await click(page, '[data-testid="file-ok"]');
    executor = await newBlock(page, before, 'imagenets/Executor');
    await page.waitForSelector(`${nodeSel(executor)} [data-handleid="image"]`, { timeout: LONG });
    await link(page, `${source}.image`, `${executor}.image`);
    await until('five links', async () => (await linkIds(page)).length === 5);
    await click(page, `${nodeSel(executor)} button[title="open the sub-net"]`);
    await page.waitForSelector('[data-testid="subnet-view"] .react-flow__node', { timeout: LONG });
    const inner = await page.$$eval('[data-testid="subnet-view"] .react-flow__node', (ns) => ns.map((n) => n.dataset.id).sort());
    assert.deepEqual(inner, ['binary', 'blur', 'gray', 'image', 'threshold']);
    await closeDialog(page);
  });

  await step('undo and redo', async () => {
    const links = await linkIds(page);
    await page.mouse.click(...at(0.3, 0.9));
    await page.keyboard.down('Control');
    await page.keyboard.press('z');
    await page.keyboard.up('Control');
    await until('the last link undone', async () => (await linkIds(page)).length === links.length - 1);
    await click(page, '[data-testid="redo"]');
    await until('the link redone', async () => (await linkIds(page)).length === links.length);
    assert.deepEqual(await linkIds(page), links);
  });

  await step('copy and paste keep the links inside the selection; undo removes the pasted blocks', async () => {
    const blocks = await blockNames(page);
    const links = await linkIds(page);
    await select(page, gray);
    await page.keyboard.down('Control');
    await click(page, `${nodeSel(threshold)} .block-name`);
    await page.keyboard.up('Control');
    await until('two selected', async () => (await page.$$('.react-flow__node.selected')).length === 2);
    await page.mouse.move(...at(0.5, 0.95));
    await page.keyboard.down('Control');
    await page.keyboard.press('c');
    await page.keyboard.press('v');
    await page.keyboard.up('Control');
    await until('two pasted blocks', async () => (await blockNames(page)).length === blocks.length + 2);
    const pasted = (await blockNames(page)).filter((n) => !blocks.includes(n));
    await until('one pasted link', async () => (await linkIds(page)).length === links.length + 1);
    const added = (await linkIds(page)).filter((l) => !links.includes(l));
    assert.equal(added.length, 1);
    assert.ok(pasted.some((n) => added[0].startsWith(`${n}.image->`)) && pasted.some((n) => added[0].endsWith(`${n}.image`)), added[0]);
    await page.mouse.click(...at(0.3, 0.9));
    await page.keyboard.down('Control');
    await page.keyboard.press('z');
    await page.keyboard.up('Control');
    await until('the paste undone', async () => (await blockNames(page)).length === blocks.length);
    assert.deepEqual(await linkIds(page), links);
  });

  await step('a link dropped on empty canvas offers only blocks taking its type', async () => {
    const from = await (await page.waitForSelector(`.react-flow__handle.source[data-nodeid="${gray}"][data-handleid="image"]`)).boundingBox();
    const [x, y] = at(0.25, 0.08); // empty canvas
    await page.mouse.move(from.x + from.width / 2, from.y + from.height / 2);
    await page.mouse.down();
    await page.mouse.move(x, y, { steps: 10 });
    await page.mouse.up();
    await page.waitForSelector('[data-testid="block-search-popup"] .search-result', { timeout: LONG });
    const offered = await page.$$eval('[data-testid="block-search-popup"] .search-result', (rs) => rs.map((r) => r.dataset.type).sort());
    const listed = run(imagenets, ['blocks', '--input-type', 'sensor_msgs/Image']);
    assert.equal(listed.code, 0, listed.out);
    const expected = [...listed.out.matchAll(/^ {2}(\S+) - /gm)].map((m) => m[1]).sort();
    assert.ok(expected.includes('imagenets/Threshold') && !expected.includes('imagenets/ImageFileSource'), listed.out);
    assert.deepEqual(offered, expected);
    // Picking one adds it already linked.
    const links = await linkIds(page);
    const before = new Set(await blockNames(page));
    await page.keyboard.type('GaussianBlur');
    await page.keyboard.press('Enter');
    const blur = await newBlock(page, before, 'imagenets/GaussianBlur');
    await until('the new block linked', async () => (await linkIds(page)).includes(`${gray}.image->${blur}.image`));
    await select(page, blur);
    await page.keyboard.press('Delete');
    await until('the blur removed with its link', async () => (await linkIds(page)).length === links.length);
  });

  await step('saves; the engine loads and runs the saved net as drawn', async () => {
    const file = path.join(dir, 'drawn.yaml');
    await click(page, '[data-testid="save-as"]');
    const field = await page.waitForSelector('[data-testid="file-path"]', { timeout: LONG });
    await field.evaluate((i) => i.select());
    await page.keyboard.type(file);
    await click(page, '[data-testid="file-ok"]');
    await until('the file written', () => fs.existsSync(file));
    await until('the title shows the file', async () => (await page.$eval('[data-testid="file-name"]', (e) => e.textContent)) === 'drawn.yaml');
    const validate = run(imagenets, ['validate', file]);
    assert.equal(validate.code, 0, validate.out);
    assert.match(validate.out, /^OK /);
    const ran = run(imagenets, ['run', file]);
    assert.equal(ran.code, 0, ran.out);
    const text = fs.readFileSync(file, 'utf8');
    for (const l of await linkIds(page)) assert.ok(text.includes(l.replace('->', ' -> ')), `${l} in\n${text}`);
    for (const n of [source, gray, threshold, quality, executor]) assert.match(ran.out, new RegExp(`\\b${n}\\s+ok\\b`));
    assert.match(text, /threshold: 100/);
    assert.match(text, /feedback:/);
    assert.match(text, new RegExp(`score: ${quality}\\.score`));
  });
  await step('opens the sub-net\'s own file for editing', async () => {
    await click(page, `${nodeSel(executor)} button[title="open the sub-net"]`);
    await click(page, '[data-testid="subnet-edit"]');
    await until('the inner net open', async () =>
      (await page.$eval('[data-testid="file-name"]', (e) => e.textContent)) === 'segmentation_subnet.yaml');
    assert.deepEqual((await blockNames(page)).sort(), ['binary', 'blur', 'gray', 'image', 'threshold']);
  });
  assert.deepEqual(page.errors, []);
});

test('the 3D view draws the stereo point cloud', { timeout: 300000 }, async (t) => {
  const dir = tempDir('3d');
  const config = copyConfig(dir);
  const designer = await startDesigner({ net: path.join(config, 'nets/stereo_point_cloud.yaml') });
  t.after(() => designer.stop());
  const page = await openDesigner(browser, designer.url);
  await page.waitForSelector('.react-flow__node', { timeout: LONG });
  const cloudPort = await until('a PointCloud2 output', () => page.evaluate(() => {
    const handle = [...document.querySelectorAll('.react-flow__handle.source')]
      .find((h) => h.closest('.port').title.startsWith('sensor_msgs/PointCloud2'));
    return handle && `${handle.dataset.nodeid}.${handle.dataset.handleid}`;
  }));
  await click(page, '[data-testid="run"]');
  await until('the cloud block ran', async () => (await stats(page, cloudPort.split('.')[0])).runs >= 1);
  await click(page, `button.open-data[data-port="${cloudPort}"]`);
  const drawn = await until('a drawn 3D canvas', () => page.evaluate(() => {
    const c = document.querySelector('[data-testid="data-dialog"] canvas[data-testid="scene3d"]');
    if (!c) return null;
    const copy = document.createElement('canvas');
    copy.width = c.width;
    copy.height = c.height;
    const g = copy.getContext('2d');
    g.drawImage(c, 0, 0);
    const pixels = g.getImageData(0, 0, c.width, c.height).data;
    let differing = 0;
    for (let i = 0; i < pixels.length; i += 4) {
      // The clear colour is #101418; the axes helper alone is a few hundred pixels.
      if (Math.abs(pixels[i] - 0x10) + Math.abs(pixels[i + 1] - 0x14) + Math.abs(pixels[i + 2] - 0x18) > 30) ++differing;
    }
    return differing > 5000 ? differing : null;
  }));
  assert.ok(drawn > 5000, `${drawn} pixels differ from the background`);
  await closeDialog(page);
  // The disparity (32FC1) in the image dialog: a float within the searched range at the centre.
  await click(page, 'button.open-data[data-port="disparity.disparity"]');
  const canvas = await page.waitForSelector('.image-canvas[data-scale]', { timeout: LONG });
  const size = await page.$eval('[data-testid="pixel-readout"]', (r) => r.textContent.match(/^(\d+)x(\d+) (\S+)/).slice(1));
  assert.equal(size[2], '32FC1');
  const readout = await readPixel(page, Math.floor(Number(size[0]) / 2), Math.floor(Number(size[1]) / 2));
  const value = Number(readout.match(/value=(-?[\d.]+)/)[1]);
  assert.ok(value > 0 && value <= 64, readout);
  assert.ok(canvas);
  assert.deepEqual(page.errors, []);
});

test('files: open, the YAML pane, export; a second tab sees the same net', { timeout: 300000 }, async (t) => {
  const dir = tempDir('files');
  const config = copyConfig(dir);
  const designer = await startDesigner({ roots: [dir] });
  t.after(() => designer.stop());
  const page = await openDesigner(browser, designer.url);

  // Open through the file dialog.
  await click(page, '[data-testid="open"]');
  const field = await page.waitForSelector('[data-testid="file-path"]', { timeout: LONG });
  await field.evaluate((i) => i.select());
  await page.keyboard.type(path.join(config, 'nets/threshold_demo.yaml'));
  await click(page, '[data-testid="file-ok"]');
  await until('the opened net', async () => (await blockNames(page)).sort().join() === 'blur,gray,source,threshold');
  assert.equal(await page.$eval('[data-testid="file-name"]', (e) => e.textContent), 'threshold_demo.yaml');

  // A bad edit in the YAML pane: refused with the line, which is selected; nothing changes.
  const yaml = await page.$eval('[data-testid="yaml"]', (y) => y.value);
  const badLine = yaml.split('\n').indexOf('  blur:') + 1; // the engine names the block's line
  await page.$eval('[data-testid="yaml"]', (y) => { y.focus(); y.setSelectionRange(0, 0); });
  const edit = async (text) => {
    await page.$eval('[data-testid="yaml"]', (y) => y.select());
    await page.keyboard.press('Backspace');
    // Typing the whole file is slow; paste-like input through the editor's own change event.
    await page.$eval('[data-testid="yaml"]', (y, value) => {
      const setter = Object.getOwnPropertyDescriptor(HTMLTextAreaElement.prototype, 'value').set;
      setter.call(y, value);
      y.dispatchEvent(new Event('input', { bubbles: true }));
    }, text);
    await click(page, '[data-testid="yaml-apply"]');
  };
  await edit(yaml.replace('type: imagenets/GaussianBlur', 'type: imagenets/NoSuchBlock'));
  const error = await (await page.waitForSelector('[data-testid="yaml-error"]', { timeout: LONG })).evaluate((e) => e.textContent);
  assert.match(error, /NoSuchBlock/);
  assert.match(error, new RegExp(`:${badLine}:`));
  const selectedLine = await page.$eval('[data-testid="yaml"]', (y) => y.value.slice(0, y.selectionStart).split('\n').length);
  assert.equal(selectedLine, badLine);
  assert.deepEqual((await blockNames(page)).sort(), ['blur', 'gray', 'source', 'threshold']);

  // A good edit replaces the net; a second tab shows the same.
  const second = await openDesigner(browser, designer.url);
  await edit(yaml.replace('threshold: 60', 'threshold: 77').replace('  blur:\n', '  smooth:\n').replace(/blur\./g, 'smooth.'));
  await until('the edited net', async () => (await blockNames(page)).includes('smooth'));
  await until('the edited net in the second tab', async () => (await blockNames(second)).sort().join() === 'gray,smooth,source,threshold');
  assert.match(await second.$eval('[data-testid="yaml"]', (y) => y.value), /threshold: 77/);
  // ... and an edit in the second tab shows in the first.
  await select(second, 'smooth');
  await setProperty(second, 'kernel_size', 7);
  await until('the property in the first tab', async () => /kernel_size: 7/.test(await page.$eval('[data-testid="yaml"]', (y) => y.value)));

  // Exports.
  await click(page, '[data-testid="export-launch"]');
  const launch = await (await page.waitForSelector('[data-testid="export-dialog"] .export-text', { timeout: LONG })).evaluate((e) => e.textContent);
  assert.match(launch, /<launch>/);
  assert.match(launch, /nodelet/);
  assert.match(launch, /smooth/);
  await page.keyboard.press('Escape');
  await click(page, '[data-testid="export-svg"]');
  await page.waitForSelector('[data-testid="export-dialog"] .export-svg svg', { timeout: LONG });
  const svgText = await page.$eval('[data-testid="export-dialog"] .export-svg svg', (s) => s.textContent);
  for (const name of ['source', 'gray', 'smooth', 'threshold']) assert.match(svgText, new RegExp(name));
  assert.deepEqual([...page.errors, ...second.errors], []);
});

test('a running block is highlighted and a long run can be cancelled', { timeout: 300000 }, async (t) => {
  const dir = tempDir('cancel');
  const image = path.join(dir, 'big.png');
  const made = run('convert', ['-size', '1024x768', 'gradient:black-white', image]);
  assert.equal(made.code, 0, made.out);
  const net = path.join(dir, 'sweep.yaml');
  // A feedback sweep over every threshold, one candidate at a time: long enough to be seen running.
  fs.writeFileSync(net, `blocks:
  source: {type: imagenets/ImageFileSource, properties: {path: ${image}}}
  gray: {type: imagenets/Grayscale}
  threshold:
    type: imagenets/Threshold
    feedback: {property: threshold, from: 0, to: 255, step: 1, score: quality.score, goal: maximize, parallel: false}
  quality: {type: imagenets/SegmentationQuality}
links:
  - source.image -> gray.image
  - gray.image -> threshold.image
  - gray.image -> quality.gray
  - threshold.image -> quality.binary
`);
  const designer = await startDesigner({ net });
  t.after(() => designer.stop());
  const page = await openDesigner(browser, designer.url);
  await page.waitForSelector(nodeSel('threshold'), { timeout: LONG });
  // Should a run end before the click lands (a fast machine), the user runs it again.
  await until('a cancelled run', async () => {
    await click(page, '[data-testid="run-all"]');
    await page.waitForSelector('.block-node.running', { timeout: LONG });
    await click(page, '[data-testid="cancel"]').catch(() => {});
    const m = await until('the run to end', async () => {
      const s = await message(page);
      return /^ran \d+/.test(s.text) ? s.text : null;
    });
    return m.includes('cancelled');
  }, 240000);
  await until('no block highlighted', async () => !(await page.$('.block-node.running')));
  assert.deepEqual(page.errors, []);
});
