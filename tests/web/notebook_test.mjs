#!/usr/bin/env node
// A notebook cell's output, rendered as Jupyter renders it: the HTML a certipose.Plan returns
// from _repr_html_, inside an output area, opened in headless Chromium (chromium.mjs).
//
//   node tests/web/notebook_test.mjs CELL.html CAMERAS [SCREENSHOT.png]
//
// CELL.html is a page whose output area holds that HTML (tests/python/test_notebook.py writes
// it). Checks that
//   1. the cameras' table has CAMERAS rows and its header names the units (mm, cm²);
//   2. the inline viewer (an iframe) resolves window.certipose.ready and WebGL drew something;
//   3. neither the page nor the viewer logs a console error or requests anything from outside.
// Prints "notebook_test: N passed, M failed"; exits 1 on a failure, 2 on bad usage.

import { existsSync } from 'node:fs';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

import { drawnPixels, launchChromium, MIN_DRAWN_FRACTION } from './chromium.mjs';

const READY_TIMEOUT_MS = Number(process.env.CERTIPOSE_READY_TIMEOUT_MS || 120000);
const [fileArg, camerasArg, screenshotArg] = process.argv.slice(2);
if (!fileArg || !camerasArg || process.argv.length > 5) {
  console.error('usage: node tests/web/notebook_test.mjs CELL.html CAMERAS [SCREENSHOT.png]');
  process.exit(2);
}
const file = path.resolve(fileArg);
if (!existsSync(file)) {
  console.error(`notebook_test: no such file: ${file}`);
  process.exit(2);
}
const cameras = Number(camerasArg);

let passed = 0;
let failed = 0;
const check = (ok, what) => {
  if (ok) passed++; else failed++;
  console.log(`  ${ok ? 'ok  ' : 'FAIL'} ${what}`);
};

const problems = [];
const browser = await launchChromium('notebook_test', ['--use-angle=swiftshader', '--enable-unsafe-swiftshader']);
try {
  const page = await browser.newPage({ viewport: { width: 1100, height: 900 }, deviceScaleFactor: 1 });
  page.on('console', (m) => {
    if (m.type() === 'error' || (m.type() === 'warning' && !/GPU stall due to ReadPixels/.test(m.text()))) {
      problems.push(`console.${m.type()}: ${m.text()}`);
    }
  });
  page.on('pageerror', (e) => problems.push(`uncaught: ${e.message}`));
  page.on('request', (r) => {
    const u = r.url();
    if (!/^(file|data|blob|about):/.test(u)) problems.push(`request to ${u}`);
  });
  await page.goto(pathToFileURL(file).href, { waitUntil: 'load', timeout: READY_TIMEOUT_MS });

  const table = await page.evaluate(() => {
    const t = document.querySelector('.output_area .certipose table');
    if (!t) return null;
    return { rows: t.querySelectorAll('tr').length - 1, head: t.querySelector('tr').textContent };
  });
  check(table !== null && table.rows === cameras, `the cameras' table has ${cameras} rows (${table ? table.rows : 'no table'})`);
  check(table !== null && /x mm/.test(table.head) && /area cm²/.test(table.head), 'its header names the units');

  const frameElement = await page.$('.output_area iframe.certipose-viewer');
  check(frameElement !== null, 'the output holds the inline viewer');
  if (frameElement) {
    const frame = await frameElement.contentFrame();
    const ready = await Promise.race([
      frame.evaluate(() => window.certipose.ready.then(() => true)),
      new Promise((resolve) => setTimeout(() => resolve(false), READY_TIMEOUT_MS)),
    ]).catch((e) => { problems.push(`viewer: ${e.message.split('\n')[0]}`); return false; });
    check(ready, 'the inline viewer is ready');
    if (ready) {
      // WebGL drew, as viewer_test.mjs checks it.
      const px = await drawnPixels(frame);
      const drawn = px.differing / Math.max(1, px.total);
      check(drawn > MIN_DRAWN_FRACTION, `the viewer drew the part (${(100 * drawn).toFixed(1)} % of its canvas)`);
    }
  }
  check(problems.length === 0, `no console problem or outside request${problems.length ? ': ' + problems.join('; ') : ''}`);
  if (screenshotArg) await page.screenshot({ path: screenshotArg, fullPage: true });
} finally {
  await browser.close();
}
console.log(`notebook_test: ${passed} passed, ${failed} failed`);
process.exit(failed ? 1 : 0);
