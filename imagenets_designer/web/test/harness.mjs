// Starts the real `imagenets designer` and Debian's chromium for the browser tests and benchmark.
import { spawn, execFileSync } from 'node:child_process';
import fs from 'node:fs';
import http from 'node:http';
import net from 'node:net';
import os from 'node:os';
import path from 'node:path';
import { createRequire } from 'node:module';

const require = createRequire(import.meta.url);
const puppeteer = require('puppeteer-core');

export const source = process.env.IMAGENETS_SOURCE || path.resolve(new URL('../../..', import.meta.url).pathname);
export const imagenets = process.env.IMAGENETS_BIN || path.join(source, 'devel/bin/imagenets');
const chromium = process.env.CHROMIUM || '/usr/bin/chromium';

// Generous: the machine may be busy with builds of other work.
export const LONG = Number(process.env.LONG || 60000);

export function tempDir(prefix) {
  return fs.mkdtempSync(path.join(os.tmpdir(), `designer-${prefix}-`));
}

// A copy of config/ (nets refer to ../images, ../cameras, ../markers) in a temp folder.
export function copyConfig(dir) {
  fs.cpSync(path.join(source, 'config'), path.join(dir, 'config'), { recursive: true });
  return path.join(dir, 'config');
}

async function freePort() {
  return new Promise((resolve, reject) => {
    const server = net.createServer();
    server.on('error', reject);
    server.listen(0, '127.0.0.1', () => {
      const { port } = server.address();
      server.close(() => resolve(port));
    });
  });
}

function get(url) {
  return new Promise((resolve) => {
    http.get(url, (res) => { res.resume(); resolve(res.statusCode); }).on('error', () => resolve(0));
  });
}

export async function until(what, check, timeout = LONG) {
  const start = Date.now();
  for (;;) {
    const value = await check();
    if (value) return value;
    if (Date.now() - start > timeout) throw new Error(`timed out after ${timeout} ms waiting for ${what}`);
    await new Promise((r) => setTimeout(r, 100));
  }
}

// `imagenets designer [net] --port P --root DIR...`; resolves when the page is served.
export async function startDesigner({ net, roots = [] } = {}) {
  const port = await freePort();
  const args = ['designer', ...(net ? [net] : []), '--port', String(port), ...roots.flatMap((r) => ['--root', r])];
  const proc = spawn(imagenets, args, { stdio: ['ignore', 'pipe', 'pipe'] });
  let output = '';
  proc.stdout.on('data', (d) => { output += d; });
  proc.stderr.on('data', (d) => { output += d; });
  let exited = null;
  proc.on('exit', (code) => { exited = code; });
  const url = `http://127.0.0.1:${port}/`;
  await until(`the designer on ${url}`, async () => {
    if (exited !== null) throw new Error(`imagenets designer exited with ${exited}:\n${output}`);
    return (await get(url)) === 200;
  });
  return {
    url,
    output: () => output,
    stop: () => new Promise((resolve) => {
      if (exited !== null) { resolve(); return; }
      proc.on('exit', () => resolve());
      proc.kill('SIGINT');
      setTimeout(() => { if (exited === null) proc.kill('SIGKILL'); }, 10000).unref();
    }),
  };
}

// The Designer on a copy of config/nets/NET (stopped when test `t` ends), and a page on it.
export async function designerOnNetCopy(t, browser, prefix, net) {
  const config = copyConfig(tempDir(prefix));
  const designer = await startDesigner({ net: path.join(config, 'nets', net) });
  t.after(() => designer.stop());
  return { config, designer, page: await openDesigner(browser, designer.url) };
}

export async function launchBrowser() {
  return puppeteer.launch({
    executablePath: chromium,
    headless: true,
    // WebGL in headless chromium without a GPU: SwiftShader through ANGLE.
    args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--window-size=1600,1000'],
    protocolTimeout: 180000,
  });
}

// A page on the designer that fails the test on any page error; resolves once the net is shown.
export async function openDesigner(browser, url, beforeLoad = async () => {}, viewport = { width: 1600, height: 1000 }) {
  const page = await browser.newPage();
  await beforeLoad(page);
  await page.setViewport(viewport);
  page.errors = [];
  page.logs = [];
  page.on('pageerror', (e) => page.errors.push(e.message));
  page.on('console', (m) => { if (m.type() === 'warn' || m.type() === 'error') page.logs.push(`${m.type()}: ${m.text()}`); });
  await page.goto(url);
  await page.waitForSelector('.designer', { timeout: LONG });
  return page;
}

export function run(cmd, args) {
  try {
    return { code: 0, out: execFileSync(cmd, args, { encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] }) };
  } catch (e) {
    return { code: e.status, out: `${e.stdout}${e.stderr}` };
  }
}
