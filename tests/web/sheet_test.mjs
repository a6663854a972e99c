#!/usr/bin/env node
// Headless-browser test of an installation sheet written by
// `certipose-export PLAN.json --format sheet`:
//
//   node tests/web/sheet_test.mjs SHEET.html PLAN.csv [SCREENSHOT.png]
//
// PLAN.csv is `certipose-export PLAN.json --format csv` of the same plan. Opens SHEET.html from
// file:// in Debian's Chromium (CHROMIUM=/path for another) through playwright-core and checks that
//   1. the page logs no console error or warning, throws nothing and requests nothing but file:
//      and data: URLs;
//   2. it has one page (section.page) per CSV row, and every number on a page (a cell with a
//      data-field) is, as text, the CSV's cell of that column for that camera;
//   3. each page's view is laid out (a non-empty SVG box) and draws facets, and nothing on a page
//      (header, view, table, footer) reaches past its bottom edge;
//   4. printed to PDF (A4 landscape, the sheet's @page), it is one sheet of paper per camera.
// With SCREENSHOT.png it writes a picture of the first page. Prints "sheet_test: N passed, M
// failed" and exits 1 on any failure (2 on bad usage).

import { existsSync, readFileSync } from 'node:fs';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

import { launchChromium } from './chromium.mjs';


const [fileArg, csvArg, screenshotArg] = process.argv.slice(2);
if (!fileArg || !csvArg || process.argv.length > 5) {
  console.error('usage: node tests/web/sheet_test.mjs SHEET.html PLAN.csv [SCREENSHOT.png]');
  process.exit(2);
}
for (const f of [fileArg, csvArg]) {
  if (!existsSync(f)) {
    console.error(`sheet_test: no such file: ${f}`);
    process.exit(2);
  }
}

let passed = 0;
let failed = 0;
const check = (ok, what) => {
  if (ok) { passed++; console.log(`  ok   ${what}`); } else { failed++; console.log(`  FAIL ${what}`); }
};

const lines = readFileSync(csvArg, 'utf8').trim().split('\n');
const header = lines[0].split(',');
const rows = lines.slice(1).map((l) => Object.fromEntries(l.split(',').map((v, i) => [header[i], v])));

const browser = await launchChromium('sheet_test');
let exitCode = 0;
try {
  const page = await browser.newPage({ viewport: { width: 1280, height: 900 }, deviceScaleFactor: 1 });
  const problems = [];
  page.on('console', (m) => { if (m.type() === 'error' || m.type() === 'warning') problems.push(`console.${m.type()}: ${m.text()}`); });
  page.on('pageerror', (e) => problems.push(`uncaught: ${e.message}`));
  page.on('request', (r) => {
    const u = r.url();
    if (!u.startsWith('file:') && !u.startsWith('data:')) problems.push(`request to ${u}`);
  });
  await page.goto(pathToFileURL(path.resolve(fileArg)).href, { waitUntil: 'load' });

  const pages = await page.evaluate(() => [...document.querySelectorAll('section.page')].map((s) => {
    const svg = s.querySelector('svg.view');
    const box = svg ? svg.getBoundingClientRect() : { width: 0, height: 0 };
    // Nothing may fall off the sheet: the page hides what overflows it.
    const bottom = s.getBoundingClientRect().bottom;
    const parts = [...s.querySelectorAll('header, table, footer, svg')];
    return {
      clipped: parts.filter((e) => e.getBoundingClientRect().bottom > bottom + 0.5).map((e) => e.tagName.toLowerCase()),
      camera: s.dataset.camera,
      fields: Object.fromEntries([...s.querySelectorAll('[data-field]')].map((td) => [td.dataset.field, td.textContent])),
      svgWidth: box.width,
      svgHeight: box.height,
      polygons: svg ? svg.querySelectorAll('polygon').length : 0,
    };
  }));
  check(pages.length === rows.length && rows.length > 0, `one page per camera (${pages.length} pages, ${rows.length} CSV rows)`);
  for (const row of rows) {
    const p = pages.find((x) => x.camera === row.camera);
    if (!p) { check(false, `camera ${row.camera} has a page`); continue; }
    const names = Object.keys(p.fields);
    const wrong = names.filter((n) => !(n in row) || row[n] !== p.fields[n]);
    check(names.length >= 20 && wrong.length === 0,
      `camera ${row.camera}: ${names.length} numbers equal the CSV's${wrong.length ? ` (differ: ${wrong.map((n) => `${n} ${p.fields[n]} vs ${row[n]}`).join('; ')})` : ''}`);
    check(p.clipped.length === 0, `camera ${row.camera}: everything fits on the sheet${p.clipped.length ? ` (cut off: ${p.clipped.join(', ')})` : ''}`);
    check(p.svgWidth > 100 && p.svgHeight > 100 && p.polygons > 10,
      `camera ${row.camera}: the view is laid out (${Math.round(p.svgWidth)} x ${Math.round(p.svgHeight)} px) and draws ${p.polygons} facets`);
  }

  const pdf = await page.pdf({ preferCSSPageSize: true, printBackground: true });
  const sheets = (pdf.toString('latin1').match(/\/Type\s*\/Page(?![a-zA-Z])/g) || []).length;
  check(sheets === rows.length, `printed, it is one sheet per camera (${sheets} PDF pages)`);

  if (screenshotArg) {
    await page.locator('section.page').first().screenshot({ path: path.resolve(screenshotArg) });
    console.log(`sheet_test: screenshot written to ${path.resolve(screenshotArg)}`);
  }
  check(problems.length === 0, `no console problem, error or foreign request${problems.length ? `: ${problems.join('; ')}` : ''}`);
} catch (e) {
  console.log(`  FAIL ${e.message}`);
  failed++;
} finally {
  await browser.close();
}
console.log(`sheet_test: ${passed} passed, ${failed} failed`);
if (failed) exitCode = 1;
process.exit(exitCode);
