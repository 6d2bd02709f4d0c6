// The Designer in a real browser, as docs/designer.md describes it: Debian's chromium, driven by puppeteer-core,
// on the real `imagenets designer`. Everything is done as a user does it, with mouse and keyboard;
// counts and states are the server's (shown on the nodes), and the saved file is checked by the
// engine itself (`imagenets validate`, `imagenets run`).
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { LONG, copyConfig, designerOnNetCopy, launchBrowser, openDesigner, run, startDesigner, tempDir, until, imagenets } from './harness.mjs';
import {
  allStats, blockNames, boxSelectAll, centreOf, click, connect, drag, dragBlock, link, dragBlockIn, newBlock, linkIds, message, nodeSel,
  openFile, select, setProperty, stats, watch, zoom,
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
  // Measured again on each try: the data window lays its canvas out anew once it has shown a frame.
  return until(`the readout of pixel ${x},${y}`, async () => {
    const canvas = await page.waitForSelector('.image-canvas[data-scale]', { timeout: LONG });
    const box = await canvas.boundingBox();
    const view = await canvas.evaluate((c) => ({ scale: Number(c.dataset.scale), x: Number(c.dataset.offsetX), y: Number(c.dataset.offsetY) }));
    // Mouse events land on whole CSS pixels: the first one inside the image pixel (the window
    // shows an image below 100 %, where a pixel's middle may round into its neighbour).
    const at = (start, i) => {
      const lo = start + i * view.scale, hi = lo + view.scale;
      const c = Math.round(lo + view.scale / 2);
      return c >= lo && c < hi ? c : Math.ceil(lo);
    };
    await page.mouse.move(at(box.x + view.x, x), at(box.y + view.y, y));
    const t = await page.$eval('[data-testid="pixel-readout"]', (r) => r.textContent);
    return t.includes(`x=${x} y=${y}`) ? t : null;
  });
}

// Closes the dialog or the data window (Escape, as a user does).
async function closeDialog(page) {
  // Escape in a property field belongs to the field (the data window stays open), as for a user.
  await page.evaluate(() => document.activeElement && document.activeElement.blur());
  await page.keyboard.press('Escape');
  await until('the dialog to close', async () => !(await page.$('.modal, .floating-window')));
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

  await step('lists the blocks by category, A-Z, input type and output type', async () => {
    const groups = () => page.$$eval('.block-list .category', (cs) => cs.map((c) => ({
      name: c.dataset.group, types: [...c.querySelectorAll('.block-entry')].map((e) => e.dataset.type) })));
    const byCategory = await groups();
    assert.ok(byCategory.some((g) => g.name === 'preprocessing' && g.types.includes('imagenets/Grayscale')), JSON.stringify(byCategory));
    await page.select('[data-testid="browser-sort"]', 'name');
    const byName = await groups();
    const all = byName.flatMap((g) => g.types).map((t) => t.replace(/^imagenets\//, ''));
    assert.deepEqual(all, [...all].sort((a, b) => a.localeCompare(b, 'en', { sensitivity: 'base' })));
    assert.equal(new Set(all).size, all.length, 'each block once');
    for (const g of byName) assert.ok(g.types.every((t) => t.replace(/^imagenets\//, '')[0].toUpperCase() === g.name), g.name);
    await page.select('[data-testid="browser-sort"]', 'input');
    const byInput = await groups();
    const names = byInput.map((g) => g.name);
    assert.equal(names.at(-1), 'no inputs');
    assert.deepEqual(names.slice(0, -1), [...names.slice(0, -1)].sort());
    const imageTakers = byInput.find((g) => g.name === 'sensor_msgs/Image').types;
    assert.ok(imageTakers.includes('imagenets/Grayscale') && imageTakers.includes('imagenets/Threshold'), imageTakers.join());
    assert.ok(byInput.find((g) => g.name === 'no inputs').types.includes('imagenets/ImageFileSource'));
    // A block with inputs of two types is under both (SegmentationQuality: gray and binary images
    // are one type, the detector takes an image and camera info).
    assert.ok(byInput.find((g) => g.name === 'sensor_msgs/CameraInfo').types.includes('imagenets/SquareMarkerDetector'));
    await page.select('[data-testid="browser-sort"]', 'output');
    const byOutput = await groups();
    assert.ok(byOutput.find((g) => g.name === 'std_msgs/Float64').types.includes('imagenets/SegmentationQuality'));
    assert.ok(!byOutput.find((g) => g.name === 'std_msgs/Float64').types.includes('imagenets/Grayscale'));
    await page.select('[data-testid="browser-sort"]', 'category');
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
    // The whole reason, beside the input where the link was dropped.
    const popup = await page.waitForSelector('[data-testid="link-refusal"]', { visible: true, timeout: LONG });
    const text = await popup.evaluate((e) => e.textContent);
    assert.match(text, new RegExp(`link ${camera}\\.camera_info -> ${threshold}\\.image: type mismatch: output is sensor_msgs/CameraInfo, input is sensor_msgs/Image`));
    const box = await popup.boundingBox();
    const input = await (await page.$(`.react-flow__handle.target[data-nodeid="${threshold}"][data-handleid="image"]`)).boundingBox();
    const [px, py] = [input.x + input.width / 2, input.y + input.height / 2];
    const dx = Math.min(Math.abs(box.x - px), Math.abs(box.x + box.width - px)), dy = box.y - py;
    assert.ok(dx < 40 && dy >= 0 && dy < 40, `the reason ${dx}, ${dy} px from the drop point`);
    const clipped = await popup.evaluate((e) => e.scrollWidth > e.clientWidth || e.scrollHeight > e.clientHeight);
    assert.ok(!clipped, 'the reason is shown whole');
    await popup.click();
    await until('the reason dismissed', async () => !(await page.$('[data-testid="link-refusal"]')));
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

  await step('runs one block only, or from it on', async () => {
    await select(page, gray);
    const before = await allStats(page);
    assert.match(await page.$eval('[data-testid="run-block-only"]', (b) => b.title), /only.*current|only.*inputs hold now/);
    assert.match(await page.$eval('[data-testid="run-block"]', (b) => b.title), /downstream/);
    await click(page, '[data-testid="run-block-only"]');
    await untilStats(page, 'gray ran once more', (s) => s[gray].runs === before[gray].runs + 1);
    await until('the run reported', async () => /^ran 1,/.test((await message(page)).text));
    let now = await allStats(page);
    for (const n of [source, threshold, quality]) assert.equal(now[n].runs, before[n].runs, n);
    await click(page, '[data-testid="run-block"]');
    now = await untilStats(page, 'gray and its downstream ran', (s) => s[gray].runs === before[gray].runs + 2
      && s[threshold].runs === before[threshold].runs + 1 && s[quality].runs === before[quality].runs + 1);
    assert.equal(now[source].runs, before[source].runs);
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
    // The axes read as what they are: integer thresholds, two different score labels.
    const labels = await page.$$eval(`${nodeSel(threshold)} [data-testid="trace-plot"] .plot-label`,
      (ls) => ls.map((l) => ({ axis: l.classList.contains('x-label') ? 'x' : 'y', text: l.textContent })));
    assert.deepEqual(labels.filter((l) => l.axis === 'x').map((l) => l.text), ['40', '200']);
    const y = labels.filter((l) => l.axis === 'y').map((l) => l.text);
    assert.equal(y.length, 2);
    assert.notEqual(y[0], y[1]);
    // Which score drives the feedback is on the canvas: a dashed edge from it to the block.
    const edge = await page.waitForSelector(`.react-flow__edge[data-id="feedback:${threshold}"]`, { timeout: LONG });
    assert.match(await edge.$eval('path.feedback-edge-path', (p) => getComputedStyle(p).strokeDasharray), /\d/);
    assert.equal(await page.$eval(`.feedback-edge-label[data-block="${threshold}"]`, (l) => l.textContent),
      `feedback: threshold (max ${quality}.score)`);
  });

  await step('opens a sub-net', async () => {
    // An Executor cannot exist without its net: dropping one asks for the file.
    const before = new Set(await blockNames(page));
    await dragBlock(page, 'imagenets/SubNet', ...at(0.4, 0.7));
    const field = await page.waitForSelector('[data-testid="file-path"]', { timeout: LONG });
    await field.evaluate((i) => i.select());
    await page.keyboard.type(path.join(config, 'nets/segmentation_subnet.yaml'));
    await click(page, '[data-testid="file-ok"]');
    executor = await newBlock(page, before, 'imagenets/SubNet');
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
    // Save as lists the folders it may write to, as Open does.
    await page.waitForSelector('[data-testid="file-roots"] .file-root', { timeout: LONG });
    assert.ok((await page.$$eval('.file-root', (rs) => rs.map((r) => r.dataset.root))).includes(fs.realpathSync(dir)));
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
  const { page } = await designerOnNetCopy(t, browser, '3d', 'stereo_point_cloud.yaml');
  await page.waitForSelector('.react-flow__node', { timeout: LONG });
  const cloudPort = await until('a PointCloud2 output', () => page.evaluate(() => {
    const handle = [...document.querySelectorAll('.react-flow__handle.source')]
      .find((h) => h.closest('.port').title.startsWith('sensor_msgs/PointCloud2'));
    return handle && `${handle.dataset.nodeid}.${handle.dataset.handleid}`;
  }));
  await click(page, '[data-testid="run"]');
  await until('the cloud block ran', async () => (await stats(page, cloudPort.split('.')[0])).runs >= 1);
  await click(page, `button.open-data[data-port="${cloudPort}"]`);
  const drawn = await until('a drawn 3D canvas', async () => {
    const s = await scenePixels(page);
    return s && s.differing > 5000 ? s : null;
  });
  assert.ok(drawn.differing > 5000, `${drawn.differing} pixels differ from the background`);
  // The cloud's name and frame are in the view.
  const labels = await page.$$eval('.scene-label', (ls) => ls.map((l) => l.textContent));
  assert.ok(labels.some((l) => l.startsWith(`${cloudPort} (`)), labels.join(' | '));
  assert.ok(labels.includes('left_camera_optical'), labels.join(' | '));
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

// The 3D view's pixels: its background (a corner pixel) and how many pixels differ from it.
async function scenePixels(page) {
  return page.evaluate(() => {
    const c = document.querySelector('[data-testid="data-dialog"] canvas[data-testid="scene3d"]');
    if (!c) return null;
    const copy = document.createElement('canvas');
    copy.width = c.width;
    copy.height = c.height;
    const g = copy.getContext('2d');
    g.drawImage(c, 0, 0);
    const pixels = g.getImageData(0, 0, c.width, c.height).data;
    const background = [pixels[0], pixels[1], pixels[2]];
    let differing = 0;
    for (let i = 0; i < pixels.length; i += 4) {
      if (Math.abs(pixels[i] - background[0]) + Math.abs(pixels[i + 1] - background[1]) + Math.abs(pixels[i + 2] - background[2]) > 30) ++differing;
    }
    return { background, differing };
  });
}

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

test('another net opened shows nothing of the last; an opened net cleared with the mouse takes a new net', { timeout: 300000 }, async (t) => {
  const dir = tempDir('reopen');
  const config = copyConfig(dir);
  const image = makeImage(dir);
  const designer = await startDesigner({ roots: [dir] });
  t.after(() => designer.stop());
  const page = await openDesigner(browser, designer.url);

  // The Open dialog lists the folders it may open from, before anything is refused.
  await click(page, '[data-testid="open"]');
  await page.waitForSelector('[data-testid="file-roots"] .file-root', { timeout: LONG });
  const roots = await page.$$eval('.file-root', (rs) => rs.map((r) => r.dataset.root));
  assert.ok(roots.includes(fs.realpathSync(dir)), roots.join());
  assert.ok(roots.some((r) => r.endsWith('imagenets_blocks/config')), roots.join());
  await closeDialog(page);

  await openFile(page, path.join(config, 'nets/feedback_threshold.yaml'));
  await until('the feedback net', async () => (await blockNames(page)).sort().join() === 'gray,quality,source,threshold');
  await click(page, '[data-testid="run"]');
  await untilStats(page, 'the feedback net ran', (s) => s.threshold.status === 'ok' && s.quality.status === 'ok');
  await watch(page, 'threshold.feedback_trace');
  await watch(page, 'threshold.image');
  await until('the run reported', async () => /^ran 4,/.test((await message(page)).text));
  await click(page, 'button.open-data[data-port="threshold.image"]');
  await page.waitForSelector('.image-canvas[data-scale]', { timeout: LONG });

  // threshold_demo has a `threshold` too: it shows none of the old one's previews, run or data.
  await openFile(page, path.join(config, 'nets/threshold_demo.yaml'));
  await until('the demo net', async () => (await blockNames(page)).sort().join() === 'blur,gray,source,threshold');
  assert.equal(await page.$$eval('.preview', (p) => p.length), 0);
  assert.equal(await page.$$eval('button.watch.on', (b) => b.length), 0);
  assert.equal(await page.$('[data-testid="data-dialog"]'), null);
  assert.equal(await page.$$eval('.block-node .cached', (c) => c.length), 0);
  assert.doesNotMatch((await message(page)).text, /^ran /);
  assert.deepEqual(await stats(page, 'threshold'), { status: 'pending', runs: 0, cpuMs: 0, message: '' });
  assert.ok(!(await page.$('button.watch[data-port="threshold.feedback_trace"]')), 'the demo\'s threshold has no trace port');

  // Every block box-selected and deleted; the emptied net takes new blocks (the Designer names
  // them) without asking for any file, and runs and saves.
  await boxSelectAll(page);
  await page.keyboard.press('Delete');
  await until('an empty canvas', async () => (await blockNames(page)).length === 0);
  const canvas = await (await page.$('.canvas')).boundingBox();
  const source = await dragBlockIn(page, 'imagenets/ImageFileSource', canvas.x + 0.2 * canvas.width, canvas.y + 0.3 * canvas.height);
  assert.equal(source, 'image_file_source');
  const gray = await dragBlockIn(page, 'imagenets/Grayscale', canvas.x + 0.5 * canvas.width, canvas.y + 0.3 * canvas.height);
  assert.equal(gray, 'grayscale');
  assert.equal(await page.$('[data-testid="file-dialog"]'), null, 'no file was asked for');
  assert.equal((await message(page)).error, false, (await message(page)).text);
  await select(page, source);
  await setProperty(page, 'path', image);
  await link(page, `${source}.image`, `${gray}.image`);
  await page.keyboard.down('Control');
  await page.keyboard.press('Enter');
  await page.keyboard.up('Control');
  await untilStats(page, 'the new net ran', (s) => s[source].status === 'ok' && s[gray].status === 'ok');
  await click(page, '[data-testid="save"]');
  const file = path.join(config, 'nets/threshold_demo.yaml');
  await until('the file saved', () => fs.readFileSync(file, 'utf8').includes('grayscale:'));
  const validate = run(imagenets, ['validate', file]);
  assert.equal(validate.code, 0, validate.out);
  assert.deepEqual(page.errors, []);
});

test('feedback is a dashed edge from its score, moved by dragging', { timeout: 300000 }, async (t) => {
  const { page } = await designerOnNetCopy(t, browser, 'feedback', 'feedback_threshold.yaml');
  await page.waitForSelector(nodeSel('threshold'), { timeout: LONG });
  const yaml = () => page.$eval('[data-testid="yaml"]', (y) => y.value);
  const feedbackEdge = '.react-flow__edge[data-id="feedback:threshold"]';
  const label = () => page.$eval('.feedback-edge-label[data-block="threshold"]', (l) => l.textContent);
  await page.waitForSelector(feedbackEdge, { timeout: LONG });
  assert.equal(await label(), 'feedback: threshold (max quality.score)');
  // The label is seen whole: no block covers any corner of it.
  const covered = await page.$eval('.feedback-edge-label[data-block="threshold"]', (l) => {
    const r = l.getBoundingClientRect();
    return [[r.left + 2, r.top + 2], [r.right - 2, r.top + 2], [r.left + 2, r.bottom - 2], [r.right - 2, r.bottom - 2]]
      .map(([x, y]) => document.elementFromPoint(x, y))
      .filter((e) => !e || !l.contains(e)).map((e) => (e ? e.className : 'nothing'));
  });
  assert.deepEqual(covered, []);

  // A second score, and the feedback's score port dragged onto the block's feedback handle.
  const canvas = await (await page.$('.canvas')).boundingBox();
  const second = await dragBlockIn(page, 'imagenets/SegmentationQuality', canvas.x + 0.45 * canvas.width, canvas.y + 0.85 * canvas.height);
  await link(page, 'gray.image', `${second}.gray`);
  await link(page, 'threshold.image', `${second}.binary`);
  const handle = '.react-flow__handle.target[data-nodeid="threshold"][data-handleid="feedback"]';
  await drag(page, await centreOf(page, `.react-flow__handle.source[data-nodeid="${second}"][data-handleid="score"]`), await centreOf(page, handle));
  await until('the feedback scored by the new block', async () => (await yaml()).includes(`score: ${second}.score`));
  await until('the edge from the new score', async () => (await label()) === `feedback: threshold (max ${second}.score)`);

  // The edge's end at the score, dragged back onto the first score port.
  const end = await page.$eval(`${feedbackEdge} .react-flow__edgeupdater-source`, (c) => {
    const r = c.getBoundingClientRect();
    return { x: r.left + r.width / 2, y: r.top + r.height / 2, r: r.width / 2 };
  });
  // Inside the end's grip but beside the port's own handle (which would start a new link).
  await drag(page, { x: end.x + end.r * 0.75, y: end.y }, await centreOf(page, '.react-flow__handle.source[data-nodeid="quality"][data-handleid="score"]'));
  await until('the feedback scored by quality again', async () => (await label()) === 'feedback: threshold (max quality.score)');
  assert.match(await yaml(), /score: quality\.score/);

  // A port that is no score is refused, with the reason where it was dropped.
  await drag(page, await centreOf(page, '.react-flow__handle.source[data-nodeid="gray"][data-handleid="image"]'), await centreOf(page, handle));
  const refusal = await page.waitForSelector('[data-testid="link-refusal"]', { visible: true, timeout: LONG });
  assert.match(await refusal.evaluate((e) => e.textContent), /gray\.image is sensor_msgs\/Image, not std_msgs\/Float64/);
  await refusal.click();

  // The edge selected and deleted is the feedback turned off.
  const onEdge = await page.$eval(`${feedbackEdge} path.feedback-edge-path`, (p) => {
    const m = p.getScreenCTM();
    const q = p.getPointAtLength(p.getTotalLength() * 0.3);
    return { x: m.a * q.x + m.c * q.y + m.e, y: m.b * q.x + m.d * q.y + m.f };
  });
  await page.mouse.click(onEdge.x, onEdge.y);
  await page.waitForSelector(`${feedbackEdge}.selected`, { timeout: LONG });
  await page.keyboard.press('Delete');
  await until('the feedback removed', async () => !(await page.$(feedbackEdge)));
  assert.doesNotMatch(await yaml(), /feedback:/);
  assert.deepEqual(page.errors, []);
});

test('the data window stays open beside the properties, resizes and shows each run', { timeout: 300000 }, async (t) => {
  const { page } = await designerOnNetCopy(t, browser, 'window', 'threshold_demo.yaml');
  await page.waitForSelector(nodeSel('threshold'), { timeout: LONG });
  await click(page, '[data-testid="run"]');
  await untilStats(page, 'the net ran', (s) => s.threshold.status === 'ok');
  await select(page, 'threshold');
  await setProperty(page, 'threshold', 0);
  await untilStats(page, 'threshold 0 applied', (s) => s.threshold.runs === 2);
  await click(page, 'button.open-data[data-port="threshold.image"]');
  const title = () => page.$eval('[data-testid="data-dialog-title"]', (e) => e.textContent);
  const runOf = async () => Number((await title()).match(/run (\d+)/)?.[1] ?? -1);
  await until('the data shown', async () => (await runOf()) >= 0);
  const firstRun = await runOf();
  assert.match(await readPixel(page, 200, 150), /value=255\b/);

  // Moved by its title and resized by its corner; the image area grows with it.
  const win = '[data-testid="data-dialog"]';
  const before = await (await page.$(win)).boundingBox();
  const canvasBefore = await page.$eval('.image-canvas', (c) => c.width);
  const grip = await centreOf(page, '[data-testid="data-dialog-title"] .window-title-text');
  await drag(page, grip, { x: grip.x - 120, y: grip.y + 40 });
  const moved = await (await page.$(win)).boundingBox();
  assert.ok(Math.abs(moved.x - (before.x - 120)) < 3 && Math.abs(moved.y - (before.y + 40)) < 3, JSON.stringify({ before, moved }));
  const corner = await centreOf(page, '[data-testid="data-dialog-resize"]');
  await drag(page, corner, { x: corner.x + 150, y: corner.y + 60 });
  const resized = await (await page.$(win)).boundingBox();
  assert.ok(Math.abs(resized.width - (moved.width + 150)) < 4, JSON.stringify({ moved, resized }));
  assert.ok(await page.$eval('.image-canvas', (c) => c.width) > canvasBefore + 140);

  // With the window open the property is changed, and the window shows the new run's pixels.
  await setProperty(page, 'threshold', 255);
  await until('the next run in the window', async () => (await runOf()) > firstRun);
  assert.match(await readPixel(page, 200, 150), /value=0\b/);
  assert.ok(await page.$(win), 'the window is still open');
  await closeDialog(page);
  assert.deepEqual(page.errors, []);
});

test('a property slider re-runs the net while it is dragged and ends at the value let go', { timeout: 300000 }, async (t) => {
  const { page } = await designerOnNetCopy(t, browser, 'slider', 'threshold_demo.yaml');
  await page.waitForSelector(nodeSel('threshold'), { timeout: LONG });
  await click(page, '[data-testid="run"]');
  await untilStats(page, 'the net ran', (s) => s.threshold.status === 'ok');
  await watch(page, 'threshold.image');
  await select(page, 'threshold');
  const slider = await page.waitForSelector('[data-testid="slider-threshold"]', { visible: true, timeout: LONG });
  const box = await slider.boundingBox();
  const y = box.y + box.height / 2;
  const shownBefore = await page.evaluate(() => (window.designerShown || []).length);
  await page.mouse.move(box.x + 2, y);
  await page.mouse.down();
  // Each step waits for a new preview: the page follows the hand, not only the release.
  for (let k = 1; k <= 3; ++k) {
    const n = await page.evaluate(() => window.designerShown.length);
    await page.mouse.move(box.x + (box.width * k) / 4, y, { steps: 3 });
    await until(`a preview while dragging (step ${k})`, () => page.evaluate((n) =>
      window.designerShown.slice(n).some((s) => s.port === 'threshold.image'), n));
  }
  const runsWhileDragging = (await stats(page, 'threshold')).runs;
  await page.mouse.up();
  const value = await slider.evaluate((s) => s.value);
  await until('the value let go in the net', async () =>
    (await page.$eval('[data-testid="property-threshold"]', (f) => f.value)) === value);
  assert.ok(runsWhileDragging >= 4, `threshold ran ${runsWhileDragging} times by the time the slider was let go`);
  const shown = await page.evaluate((n) => window.designerShown.slice(n).filter((s) => s.port === 'threshold.image').length, shownBefore);
  assert.ok(shown >= 3, `${shown} previews shown while dragging`);
  assert.deepEqual(page.errors, []);
});

test('on a 1366x768 screen a fitted net is readable and the minimap covers no node', { timeout: 300000 }, async (t) => {
  const dir = tempDir('readable');
  const config = copyConfig(dir);
  const designer = await startDesigner({ net: path.join(config, 'nets/robust_marker_detection.yaml') });
  t.after(() => designer.stop());
  const page = await openDesigner(browser, designer.url, async () => {}, { width: 1366, height: 768 });
  await page.waitForSelector(nodeSel('detector'), { timeout: LONG });
  // The fit comes once the nodes are measured: the zoom settles.
  let last = -1;
  const fitted = await until('the fitted zoom', async () => {
    const z = await zoom(page);
    const settled = z === last ? z : null;
    last = z;
    await new Promise((r) => setTimeout(r, 200));
    return settled;
  });
  const smallest = async () => {
    const z = await zoom(page);
    const sizes = await page.$$eval('.block-node .block-name, .block-node .block-type, .block-node .status-word, .block-node .stats, .block-node .port-name',
      (es) => es.map((e) => parseFloat(getComputedStyle(e).fontSize)));
    return Math.min(...sizes) * z;
  };
  assert.ok(await smallest() >= 10, `node text ${await smallest()} px at zoom ${fitted}`);
  // Zoomed out by hand, the fit button brings the text back to a readable size.
  const pane = await (await page.$('.react-flow__pane')).boundingBox();
  await page.mouse.move(pane.x + pane.width / 2, pane.y + pane.height / 2);
  for (let i = 0; i < 5; ++i) await page.mouse.wheel({ deltaY: 300 });
  await until('zoomed out', async () => (await zoom(page)) < 0.6);
  await click(page, '[data-testid="fit-view"]');
  await until('fitted again', async () => (await smallest()) >= 10);

  // No minimap over the nodes on a canvas this small; the user can still ask for it.
  const overlaps = () => page.evaluate(() => {
    const map = document.querySelector('.react-flow__minimap');
    if (!map) return false;
    const m = map.getBoundingClientRect();
    return [...document.querySelectorAll('.react-flow__node')].some((n) => {
      const r = n.getBoundingClientRect();
      return r.left < m.right && m.left < r.right && r.top < m.bottom && m.top < r.bottom;
    });
  });
  assert.equal(await overlaps(), false);
  await click(page, '[data-testid="toggle-minimap"]');
  await page.waitForSelector('.react-flow__minimap', { timeout: LONG });
  await click(page, '[data-testid="toggle-minimap"]');
  await until('the minimap hidden', async () => !(await page.$('.react-flow__minimap')));

  // An optional port reads as its name: a hollow handle and italics, no '?'.
  const hint = await page.$eval(`${nodeSel('detector')} .port.in.optional`, (p) => ({
    name: p.querySelector('.port-name').textContent, background: getComputedStyle(p.querySelector('.react-flow__handle')).backgroundColor,
    style: getComputedStyle(p.querySelector('.port-name')).fontStyle, title: p.title }));
  assert.deepEqual([hint.name, hint.style], ['pose_hint', 'italic']);
  assert.equal(hint.background, 'rgba(0, 0, 0, 0)');
  assert.match(hint.title, /optional/);
  const names = await page.$$eval('.port-name', (ps) => ps.map((p) => p.textContent));
  assert.ok(names.every((n) => !n.includes('?')), names.join());

  // Every toolbar button says what it does, and the icon the browser asks for is there.
  const untitled = await page.$$eval('.toolbar button', (bs) => bs.filter((b) => !b.title).map((b) => b.textContent));
  assert.deepEqual(untitled.filter((t) => /Run/.test(t)), []);
  assert.equal(await page.evaluate(() => fetch('/favicon.ico').then((r) => r.status)), 200);
  assert.ok(await page.$('link[rel="icon"]'));
  assert.deepEqual(page.errors, []);
});

test('the 3D view names the frames and objects of a scene, over a grid and axes in metres', { timeout: 300000 }, async (t) => {
  const { page } = await designerOnNetCopy(t, browser, 'scene', 'scene_3d.yaml');
  await page.waitForSelector(nodeSel('scene'), { timeout: LONG });
  await click(page, '[data-testid="run"]');
  await untilStats(page, 'the scene joined', (s) => s.scene.status === 'ok');
  await click(page, 'button.open-data[data-port="scene.markers"]');
  await until('a drawn scene', async () => ((await scenePixels(page))?.differing ?? 0) > 2000);
  const labels = await page.$$eval('.scene-label', (ls) => ls.map((l) => l.textContent));
  for (const name of ['left_camera_optical', 'board', 'base_link', 'x', 'y', 'z']) assert.ok(labels.includes(name), `${name} in ${labels.join(' | ')}`);
  assert.ok(labels.some((l) => /^[xyz] -?\d+(\.\d+)? c?m$/.test(l)), `distances in metres: ${labels.join(' | ')}`);
  assert.match(await page.$eval('[data-testid="scene-legend"]', (l) => l.textContent), /grid \d+(\.\d+)? c?m squares/);
  // A mid-grey background, so that dark and light points both show; dark and light on demand.
  const grey = (await scenePixels(page)).background;
  assert.ok(grey.every((c) => c > 60 && c < 160), `background ${grey}`);
  await page.select('[data-testid="scene-background"]', 'light');
  await until('a light background', async () => (await scenePixels(page)).background.every((c) => c > 190));
  assert.deepEqual(page.errors, []);
});
