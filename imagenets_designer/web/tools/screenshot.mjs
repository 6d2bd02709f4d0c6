// Screenshots for the README: the Designer on the paper's Fig. 3.3 net (robust marker detection:
// preview boxes and the feedback trace) and the 3D dialog on the stereo point cloud.
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

try {
  const fig = await designerOn('robust_marker_detection.yaml');
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
  await click(fig.page, '.react-flow__node[data-id="threshold"] .block-name');
  await new Promise((r) => setTimeout(r, 500)); // the fit-view animation
  await fig.page.screenshot({ path: path.join(out, 'designer.png') });
  await fig.designer.stop();

  const cloud = await designerOn('stereo_point_cloud.yaml');
  const port = await cloud.page.evaluate(() => {
    const h = [...document.querySelectorAll('.react-flow__handle.source')]
      .find((x) => x.closest('.port').title.startsWith('sensor_msgs/PointCloud2'));
    return `${h.dataset.nodeid}.${h.dataset.handleid}`;
  });
  await runAll(cloud.page, [port.split('.')[0]]);
  await click(cloud.page, `button.open-data[data-port="${port}"]`);
  await cloud.page.waitForSelector('[data-testid="data-dialog"] canvas[data-testid="scene3d"]', { timeout: LONG });
  await new Promise((r) => setTimeout(r, 500)); // a few rendered frames
  const dialog = await cloud.page.$('[data-testid="data-dialog"]');
  await dialog.screenshot({ path: path.join(out, 'designer_3d.png') });
  await cloud.designer.stop();
  console.log(`wrote ${path.join(out, 'designer.png')} and ${path.join(out, 'designer_3d.png')}`);
} finally {
  await browser.close();
}
