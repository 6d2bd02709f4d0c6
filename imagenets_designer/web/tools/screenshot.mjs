// Screenshots for the README: the Designer on the paper's Fig. 3.3 net (robust marker detection:
// preview boxes and the feedback trace), that net's feedback edge close up, and the 3D view of the
// paper's Fig. 3.2 scene (scene_3d.yaml: a point cloud, a frame and an object, labelled).
// Usage: node screenshot.mjs OUT_DIR   (IMAGENETS_BIN: the built `imagenets`)
import path from 'node:path';
import { copyConfig, launchBrowser, openDesigner, startDesigner, tempDir, until, LONG } from '../test/harness.mjs';
import { click, stats, watch } from '../test/actions.mjs';

const out = path.resolve(process.argv[2] || 'docs');
const config = copyConfig(tempDir('shot'));
const browser = await launchBrowser();

async function designerOn(net) {
  const designer = await startDesigner({ net: path.join(config, 'nets', net) });
  const page = await openDesigner(browser, designer.url);
  await page.waitForSelector('.react-flow__node', { timeout: LONG });
  return { designer, page };
}

async function runAll(page, blocks) {
  await click(page, '[data-testid="run"]');
  await until('the net ran', async () => {
    for (const b of blocks) if ((await stats(page, b)).runs < 1) return false;
    return true;
  });
}

const settle = () => new Promise((r) => setTimeout(r, 500)); // the viewport and a few rendered frames

try {
  const fig = await designerOn('robust_marker_detection.yaml');
  // A 1920x1080 screen: the whole net at a readable zoom, the feedback's score port in view.
  await fig.page.setViewport({ width: 1920, height: 1080 });
  await runAll(fig.page, ['source', 'gray', 'threshold', 'detector']);
  for (const port of ['source.image', 'gray.image', 'threshold.image', 'threshold.feedback_trace', 'detector.confidence', 'detector.pose']) {
    await watch(fig.page, port);
  }
  // The previews made the nodes tall: lay the net out again until no two nodes overlap.
  await click(fig.page, '[data-testid="layout"]');
  await until('nodes apart', () => fig.page.evaluate(() => {
    const boxes = [...document.querySelectorAll('.react-flow__node')].map((n) => n.getBoundingClientRect());
    return boxes.every((a, i) => boxes.every((b, j) => i === j || a.right <= b.left || b.right <= a.left
      || a.bottom <= b.top || b.bottom <= a.top));
  }));
  await click(fig.page, '[data-testid="fit-view"]');
  await settle();
  await click(fig.page, '.react-flow__node[data-id="threshold"] .block-name');
  await settle();
  await fig.page.screenshot({ path: path.join(out, 'designer.png') });

  // The feedback edge: from the detector's confidence (the score) back to the threshold block.
  const clip = await fig.page.evaluate(() => {
    const parts = ['.react-flow__node[data-id="threshold"]', '.react-flow__node[data-id="detector"]',
      '.feedback-edge-label[data-block="threshold"]', '.react-flow__edge[data-id="feedback:threshold"]']
      .map((s) => document.querySelector(s).getBoundingClientRect());
    const canvas = document.querySelector('.canvas').getBoundingClientRect();
    const x = Math.max(canvas.left, Math.min(...parts.map((r) => r.left)) - 30);
    const y = Math.max(canvas.top, Math.min(...parts.map((r) => r.top)) - 30);
    const right = Math.min(canvas.right, Math.max(...parts.map((r) => r.right)) + 30);
    const bottom = Math.min(canvas.bottom, Math.max(...parts.map((r) => r.bottom)) + 30);
    return { x, y, width: right - x, height: bottom - y };
  });
  await fig.page.screenshot({ path: path.join(out, 'designer_feedback.png'), clip });
  await fig.designer.stop();

  const scene = await designerOn('scene_3d.yaml');
  await runAll(scene.page, ['scene']);
  await click(scene.page, 'button.open-data[data-port="scene.markers"]');
  await scene.page.waitForSelector('[data-testid="data-dialog"] canvas[data-testid="scene3d"]', { timeout: LONG });
  await settle();
  const window = await scene.page.$('[data-testid="data-dialog"]');
  await window.screenshot({ path: path.join(out, 'designer_3d.png') });
  await scene.designer.stop();
  console.log(`wrote designer.png, designer_feedback.png and designer_3d.png in ${out}`);
} finally {
  await browser.close();
}
