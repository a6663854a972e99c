#!/usr/bin/env node
// Headless-browser test of a page written by `certipose-export PLAN.json --format html`:
//
//   node tests/web/viewer_test.mjs FILE.html [SCREENSHOT.png]
//
// Opens FILE.html from file:// in Debian's Chromium (the `chromium` package; another binary with
// CHROMIUM=/path) through playwright-core, waits for window.certipose.ready and checks that
//   1. the page logs no console error or warning, throws no uncaught error and requests nothing
//      but file: and data: URLs (the page must be self-contained);
//   2. WebGL drew something: enough canvas pixels differ from the background colour;
//   3. picking works: it clicks on the centroids of (up to 3) visible facets that some camera
//      certifies and checks that #pick names each facet's cameras as listed in the scene JSON's
//      facet_cameras (if a click lands on another facet, it checks that facet's entry instead, but
//      at least one click must hit the facet it aimed at);
//   4. clicking a camera in the side panel selects it;
//   5. the summary counts the uncovered facets by the plan's reasons (a picked uncovered facet says why).
// It prints "viewer_test: N passed, M failed" and exits 1 on any failure (2 on bad usage), with
// the reason. Run `npm ci` in web/ first: playwright-core is resolved from web/node_modules.
//
// WebGL headless: Chromium has no GPU here; --use-angle=swiftshader with --enable-unsafe-swiftshader
// (playwright adds the latter itself too) gives WebGL 2 on ANGLE over SwiftShader's Vulkan.

import { existsSync } from 'node:fs';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

import { drawnPixels, launchChromium, MIN_DRAWN_FRACTION } from './chromium.mjs';


const READY_TIMEOUT_MS = Number(process.env.CERTIPOSE_READY_TIMEOUT_MS || 120000);
const VIEWPORT = { width: 1280, height: 800 };

const [fileArg, screenshotArg] = process.argv.slice(2);
if (!fileArg || process.argv.length > 4) {
  console.error('usage: node tests/web/viewer_test.mjs FILE.html [SCREENSHOT.png]');
  process.exit(2);
}
const file = path.resolve(fileArg);
if (!existsSync(file)) {
  console.error(`viewer_test: no such file: ${file}`);
  process.exit(2);
}

const started = Date.now();
const elapsed = () => `${((Date.now() - started) / 1000).toFixed(1)} s`;
let passed = 0;
let failed = 0;
const pass = (what) => { passed++; console.log(`  ok   ${what}`); };
const failCheck = (what) => { failed++; console.log(`  FAIL ${what}`); };

function withTimeout(promise, ms, what) {
  let timer;
  return Promise.race([
    promise.finally(() => clearTimeout(timer)),
    new Promise((_, reject) => { timer = setTimeout(() => reject(new Error(`${what}: timed out after ${ms} ms`)), ms); }),
  ]);
}

const consoleProblems = [];
const pageErrors = [];
const foreignRequests = [];
const ignoredMessages = [];

const browser = await launchChromium('viewer_test', ['--use-angle=swiftshader', '--enable-unsafe-swiftshader']);
let exitCode = 0;
try {
  const page = await browser.newPage({ viewport: VIEWPORT, deviceScaleFactor: 1 });
  page.on('console', (m) => {
    if (m.type() !== 'error' && m.type() !== 'warning') return;
    // Chromium's own note when its software compositor reads a WebGL canvas back (ANGLE on Vulkan;
    // --use-angle=swiftshader avoids it): the browser's, not the page's.
    if (m.type() === 'warning' && /GL Driver Message \(OpenGL, Performance, .*GPU stall due to ReadPixels/.test(m.text())) {
      ignoredMessages.push(m.text());
      return;
    }
    consoleProblems.push(`console.${m.type()}: ${m.text()}`);
  });
  page.on('pageerror', (e) => pageErrors.push(`uncaught: ${e.message}`));
  page.on('crash', () => pageErrors.push('the page crashed'));
  page.on('request', (r) => {
    const u = r.url();
    if (!u.startsWith('file:') && !u.startsWith('data:') && !u.startsWith('blob:')) foreignRequests.push(u);
  });

  console.log(`viewer_test: opening ${pathToFileURL(file).href}`);
  await page.goto(pathToFileURL(file).href, { waitUntil: 'load', timeout: READY_TIMEOUT_MS });

  const hasApi = await page.evaluate(() => typeof window.certipose === 'object' && window.certipose !== null);
  if (!hasApi) throw new Error('the page defines no window.certipose (is the viewer bundle inlined?)');
  try {
    await withTimeout(page.evaluate(() => window.certipose.ready.then(() => true)), READY_TIMEOUT_MS, 'certipose.ready');
  } catch (e) {
    const message = await page.evaluate(() => document.getElementById('message')?.textContent || '').catch(() => '');
    throw new Error(`certipose.ready did not resolve: ${e.message.split('\n')[0]}${message ? ` (the page says: ${message})` : ''}`);
  }
  pass(`certipose.ready resolved after ${elapsed()}`);

  // What the scene JSON says, read in the page as the viewer reads it.
  const scene = await page.evaluate(() => {
    const s = JSON.parse(document.getElementById('certipose-scene').textContent);
    return {
      facetCameras: s.facet_cameras,
      cameras: (s.cameras || []).map((c, i) => ({ index: Number.isInteger(c.index) ? c.index : i, name: c.name })),
      facetCount: window.certipose.facetCount,
      background: window.certipose.background,
      uncovered: s.uncovered && typeof s.uncovered === 'object' ? s.uncovered : {},
      summary: document.getElementById('summary').textContent,
    };
  });
  const reasonOf = new Map();
  for (const [reason, facets] of Object.entries(scene.uncovered)) for (const f of facets) reasonOf.set(f, reason);
  const nameOf = new Map(scene.cameras.map((c) => [c.index, typeof c.name === 'string' ? c.name : `camera ${c.index}`]));
  const expectedText = (f) => {
    const ks = scene.facetCameras[f] || [];
    if (ks.length) return `facet ${f}: ${ks.map((k) => nameOf.get(k) ?? `camera ${k}`).join(', ')}`;
    return `facet ${f}: no camera certifies it${reasonOf.has(f) ? ` (${reasonOf.get(f)})` : ''}`;
  };
  // The summary counts the uncovered facets by the plan's reasons.
  const reasons = Object.entries(scene.uncovered);
  if (reasons.every(([reason, facets]) => scene.summary.includes(`${facets.length} ${reason}`))) {
    pass(`the summary names the uncovered facets' reasons (${reasons.length} reason${reasons.length === 1 ? '' : 's'})`);
  } else {
    failCheck(`the summary does not count the uncovered facets by reason: ${scene.summary}`);
  }
  if (!Array.isArray(scene.facetCameras) || scene.facetCameras.length !== scene.facetCount) {
    failCheck(`facet_cameras has ${scene.facetCameras?.length} entries but the part has ${scene.facetCount} facets`);
  } else {
    pass(`the part has ${scene.facetCount} facets, one facet_cameras entry each`);
  }

  // 2. Something was drawn: count canvas pixels that differ from the background colour.
  const drawn = await drawnPixels(page);
  const fraction = drawn.differing / Math.max(1, drawn.total);
  const drawnWhat = `${drawn.differing} of ${drawn.total} canvas pixels (${(100 * fraction).toFixed(1)}%, ${drawn.width}x${drawn.height}) differ from the background ${scene.background}`;
  if (fraction >= MIN_DRAWN_FRACTION) pass(drawnWhat);
  else failCheck(`${drawnWhat}: expected at least ${100 * MIN_DRAWN_FRACTION}%; did WebGL draw?`);

  // 3. Picking: up to PICKS visible facets that some camera certify (at most 400 candidates tried,
  // spread over all). Each click must name a facet with that facet's cameras; a click may land on
  // another facet than the one aimed at (an edge, a sliver), but at least one must hit its target.
  const PICKS = 3;
  const targets = await page.evaluate(({ facetCameras, wanted }) => {
    const certified = [];
    facetCameras.forEach((ks, f) => { if (Array.isArray(ks) && ks.length) certified.push(f); });
    const step = Math.max(1, Math.floor(certified.length / 400));
    const visible = [];
    for (let i = 0; i < certified.length && visible.length < 10 * wanted; i += step) {
      const p = window.certipose.facetScreenPosition(certified[i]);
      if (p) visible.push({ facet: certified[i], ...p });
    }
    // Facets with different camera lists first, so that the texts to check differ.
    const seen = new Set();
    const distinct = visible.filter((t) => {
      const key = JSON.stringify(facetCameras[t.facet]);
      if (seen.has(key)) return false;
      seen.add(key);
      return true;
    });
    const found = [...distinct, ...visible.filter((t) => !distinct.includes(t))].slice(0, wanted);
    return { found, certified: certified.length };
  }, { facetCameras: scene.facetCameras, wanted: PICKS });
  if (targets.found.length === 0) {
    failCheck(targets.certified
      ? `none of the ${targets.certified} certified facets tried is visible in the initial view`
      : 'no facet is certified by any camera: nothing to pick');
  } else {
    let exactHits = 0;
    let pickFailures = 0;
    const lines = [];
    for (const target of targets.found) {
      const clientX = target.clientX ?? target.x;
      const clientY = target.clientY ?? target.y;
      await page.$eval('#pick', (el) => { el.textContent = ''; });
      await page.mouse.click(clientX, clientY);
      let text = '';
      try {
        await page.waitForFunction(() => /^facet \d+: /.test(document.getElementById('pick')?.textContent || ''), null, { timeout: 10000 });
      } catch { /* reported below */ }
      text = await page.$eval('#pick', (el) => el.textContent).catch(() => '(no #pick)');
      const m = /^facet (\d+): /.exec(text);
      const where = `click at (${clientX.toFixed(1)}, ${clientY.toFixed(1)}) on facet ${target.facet}'s centroid`;
      if (!m) {
        pickFailures++;
        lines.push(`${where}: #pick says "${text}", expected "${expectedText(target.facet)}"`);
        continue;
      }
      const hit = Number(m[1]);
      const note = hit === target.facet ? '' : ` (the click hit facet ${hit}, not ${target.facet})`;
      if (hit === target.facet) exactHits++;
      if (hit >= scene.facetCount) {
        pickFailures++;
        lines.push(`${where}: #pick names facet ${hit}, but the part has ${scene.facetCount}`);
      } else if (text !== expectedText(hit)) {
        pickFailures++;
        lines.push(`${where}: #pick says "${text}", expected "${expectedText(hit)}"${note}`);
      } else {
        lines.push(`${where}: #pick says "${text}"${note}`);
      }
    }
    const detail = lines.join('\n       ');
    if (pickFailures > 0) failCheck(`picking:\n       ${detail}`);
    else if (exactHits === 0) failCheck(`picking: no click hit the facet it aimed at:\n       ${detail}`);
    else pass(`picking (${exactHits} of ${targets.found.length} clicks hit the facet aimed at):\n       ${detail}`);
  }

  // 4. The camera panel: clicking the first camera selects it.
  const firstCamera = page.locator('#cameras li').first();
  if ((await page.locator('#cameras li').count()) !== scene.cameras.length) {
    failCheck(`the side panel lists ${await page.locator('#cameras li').count()} cameras, the scene ${scene.cameras.length}`);
  } else if (scene.cameras.length === 0) {
    pass('no cameras to list');
  } else {
    await firstCamera.click();
    await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
    const selected = await firstCamera.evaluate((el) => el.classList.contains('selected'));
    if (selected) pass(`clicking "${await firstCamera.locator('.name').textContent()}" in the panel selects it`);
    else failCheck('clicking the first camera in the panel did not select it');
    if (screenshotArg) {
      // Leave the screenshot showing the whole plan, not one camera's selection.
      await firstCamera.click();
      await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
    }
  }

  if (screenshotArg) {
    await page.screenshot({ path: path.resolve(screenshotArg) });
    console.log(`viewer_test: screenshot written to ${path.resolve(screenshotArg)}`);
  }

  // 1. No errors, no warnings, no requests leaving the page (checked last: it covers everything above).
  const problems = [...pageErrors, ...consoleProblems];
  if (ignoredMessages.length) console.log(`  note ignored ${ignoredMessages.length} "GPU stall due to ReadPixels" warning(s) of Chromium's software GL`);
  if (problems.length === 0) pass('no console error or warning, no uncaught error');
  else failCheck(`the page reported problems:\n       ${problems.join('\n       ')}`);
  if (foreignRequests.length === 0) pass('no request other than file: and data: URLs');
  else failCheck(`the page requested: ${foreignRequests.join(', ')}`);
} catch (e) {
  failCheck(e.message);
  for (const p of [...pageErrors, ...consoleProblems]) console.log(`       ${p.split('\n')[0]}`);
} finally {
  await browser.close();
}

console.log(`viewer_test: done in ${elapsed()}`);
console.log(`viewer_test: ${passed} passed, ${failed} failed`);
if (failed > 0) exitCode = 1;
process.exit(exitCode);
