// What a user does on the Designer page, with the mouse and keyboard (puppeteer-core).
import { LONG, until } from './harness.mjs';

export const nodeSel = (name) => `.react-flow__node[data-id="${name}"]`;
const handleSel = (key, side) => {
  const dot = key.lastIndexOf('.');
  return `.react-flow__handle.${side}[data-nodeid="${key.slice(0, dot)}"][data-handleid="${key.slice(dot + 1)}"]`;
};

async function centre(page, selector) {
  const element = await page.waitForSelector(selector, { visible: true, timeout: LONG });
  // Scrolls lists (the block browser) but never the canvas, whose content it would shift.
  await element.evaluate((e) => { if (!e.closest('.react-flow')) e.scrollIntoView({ block: 'nearest' }); });
  const box = await element.boundingBox();
  return { x: box.x + box.width / 2, y: box.y + box.height / 2 };
}

export async function blockNames(page) {
  return page.$$eval('.react-flow__node', (nodes) => nodes.map((n) => n.dataset.id));
}

// Drags a block from the browser onto the canvas at page coordinates; returns its new name.
export async function dragBlockIn(page, type, x, y) {
  const before = new Set(await blockNames(page));
  await dragBlock(page, type, x, y);
  return newBlock(page, before, type);
}

export async function newBlock(page, before, what) {
  return until(`block ${what} on the canvas`, async () => (await blockNames(page)).find((n) => !before.has(n)));
}

export async function dragBlock(page, type, x, y) {
  const from = await centre(page, `.block-entry[data-type="${type}"] .entry-name`);
  await page.mouse.move(from.x, from.y);
  await page.mouse.down();
  await page.mouse.move(from.x + 40, from.y + 10, { steps: 4 });
  await page.mouse.move(x, y, { steps: 10 });
  await page.mouse.up();
}

// Drags from an output handle to an input handle ("block.port" each).
export async function connect(page, from, to) {
  const a = await centre(page, handleSel(from, 'source'));
  const b = await centre(page, handleSel(to, 'target'));
  await page.mouse.move(a.x, a.y);
  await page.mouse.down();
  await page.mouse.move((a.x + b.x) / 2, (a.y + b.y) / 2 + 20, { steps: 6 });
  await page.mouse.move(b.x, b.y, { steps: 6 });
  await page.mouse.up();
}

// Links as a user does: drag, then see the link drawn before going on; a drag that missed (the
// canvas still settling after an edit moved a handle) is made again, as a user would.
export async function link(page, from, to) {
  const linked = async () => (await linkIds(page)).includes(`${from}->${to}`);
  for (let attempt = 1; attempt < 3; ++attempt) {
    await connect(page, from, to);
    try {
      await until(`the link ${from} -> ${to}`, linked, 10000);
      return;
    } catch {
      // dragged again below
    }
  }
  await connect(page, from, to);
  await until(`the link ${from} -> ${to}`, linked);
}

// The links' edges (a feedback's dashed edge, `feedback:BLOCK`, is no link).
export async function linkIds(page) {
  return page.$$eval('.react-flow__edge', (edges) => edges.map((e) => e.dataset.id).filter((id) => !id.startsWith('feedback:')).sort());
}

export async function select(page, name) {
  const p = await centre(page, `${nodeSel(name)} .block-name`);
  await page.mouse.click(p.x, p.y);
  await page.waitForSelector(`.properties-panel[data-block="${name}"]`, { timeout: LONG });
}

export async function setProperty(page, property, text) {
  const field = await page.waitForSelector(`[data-testid="property-${property}"]`, { visible: true, timeout: LONG });
  await field.click({ clickCount: 3 });
  await page.keyboard.press('End');
  await page.keyboard.down('Shift');
  await page.keyboard.press('Home');
  await page.keyboard.up('Shift');
  await page.keyboard.type(String(text));
  await page.keyboard.press('Enter');
}

export async function stats(page, name) {
  return page.$eval(nodeSel(name), (n) => ({
    status: n.querySelector('.status-word').textContent,
    runs: Number(n.querySelector('.stats').dataset.runs),
    cpuMs: Number(n.querySelector('.cpu').dataset.ms),
    message: n.querySelector('.block-message')?.textContent || '',
  }));
}

export async function allStats(page) {
  const out = {};
  for (const name of await blockNames(page)) out[name] = await stats(page, name);
  return out;
}

export async function message(page) {
  return page.$eval('[data-testid="message"]', (m) => ({ text: m.textContent, error: m.classList.contains('error') }));
}

// A node beyond the canvas's edge (the fit keeps text readable, so a wide net is wider than the
// canvas) lies under a side panel: the canvas is zoomed out until the target is what the mouse hits.
export async function click(page, selector) {
  let p = await centre(page, selector);
  for (let i = 0; i < 6 && !(await hits(page, selector, p)); ++i) {
    const out = await centre(page, '.react-flow__controls-zoomout');
    await page.mouse.click(out.x, out.y);
    await new Promise((r) => setTimeout(r, 100));
    p = await centre(page, selector);
  }
  await page.mouse.click(p.x, p.y);
}

async function hits(page, selector, p) {
  return page.evaluate(({ selector, x, y }) => {
    const target = document.querySelector(selector), hit = document.elementFromPoint(x, y);
    return !target || !target.closest('.react-flow__node') || (hit !== null && target.contains(hit));
  }, { selector, x: p.x, y: p.y });
}

// Turns the preview box of an output on; resolves when it shows a value. A node can change size
// while the mouse moves to its button (a run's stats or a new port re-lay it out), so the click is
// checked by the button's state and given again if it landed elsewhere.
export async function watch(page, port) {
  const button = `button.watch[data-port="${port}"]`;
  await until(`the preview of ${port} switched on`, async () => {
    if (await page.$(`${button}.on`)) return true;
    await click(page, button);
    return page.waitForSelector(`${button}.on`, { timeout: 2000 }).then(() => true, () => false);
  });
  await page.waitForSelector(`.preview[data-port="${port}"] [data-revision]`, { timeout: LONG });
}

// Opens a net file through the Open dialog; resolves when the title names it.
export async function openFile(page, file) {
  await click(page, '[data-testid="open"]');
  const field = await page.waitForSelector('[data-testid="file-path"]', { timeout: LONG });
  await field.evaluate((i) => i.select());
  await page.keyboard.type(file);
  await click(page, '[data-testid="file-ok"]');
  const name = file.split('/').pop();
  await until(`${name} open`, async () => (await page.$eval('[data-testid="file-name"]', (e) => e.textContent)).startsWith(name));
}

// Shift + drag a box around every block on the canvas, as a user selects them all.
export async function boxSelectAll(page) {
  const boxes = await page.$$eval('.react-flow__node', (ns) => ns.map((n) => {
    const r = n.getBoundingClientRect();
    return [r.left, r.top, r.right, r.bottom];
  }));
  const [x0, y0] = [Math.min(...boxes.map((b) => b[0])) - 12, Math.min(...boxes.map((b) => b[1])) - 12];
  const [x1, y1] = [Math.max(...boxes.map((b) => b[2])) + 12, Math.max(...boxes.map((b) => b[3])) + 12];
  await page.keyboard.down('Shift');
  await page.mouse.move(x0, y0);
  await page.mouse.down();
  await page.mouse.move((x0 + x1) / 2, (y0 + y1) / 2, { steps: 5 });
  await page.mouse.move(x1, y1, { steps: 5 });
  await page.mouse.up();
  await page.keyboard.up('Shift');
  await until('every block selected', async () => (await page.$$('.react-flow__node:not(.selected)')).length === 0);
}

// The canvas's zoom (1 = 100 %).
export async function zoom(page) {
  return page.$eval('.react-flow__viewport', (v) => new DOMMatrix(getComputedStyle(v).transform).a);
}

// Drags with the mouse from one page point to another.
export async function drag(page, from, to) {
  await page.mouse.move(from.x, from.y);
  await page.mouse.down();
  await page.mouse.move((from.x + to.x) / 2, (from.y + to.y) / 2 + 10, { steps: 6 });
  await page.mouse.move(to.x, to.y, { steps: 6 });
  await page.mouse.up();
}

export async function centreOf(page, selector) {
  return centre(page, selector);
}
