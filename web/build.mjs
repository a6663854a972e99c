#!/usr/bin/env node
// Builds the certipose camera-plan viewer:
//
//   node web/build.mjs OUT_DIR
//
// writes
//   OUT_DIR/viewer.bundle.js  web/src/viewer.js with three.js, GLTFLoader and OrbitControls, as one
//                             minified IIFE (no imports, no network access at run time);
//   OUT_DIR/viewer.html       a copy of the template web/src/viewer.html.
//
// certipose-export makes a self-contained page from these two files by replacing, in ONE pass over
// the template (so that nothing it inserts is searched for placeholders again), each of these
// placeholders, each of which occurs exactly once in the template (checked below):
//
//   @CERTIPOSE_TITLE@          inside <title>: the plan's title, HTML-escaped (& < > ").
//   @CERTIPOSE_SCENE_JSON@     inside <script type="application/json" id="certipose-scene">: the
//                              scene JSON {"glb": base64, "cameras": [...], "facet_cameras": [...],
//                              "title": ...}. Whatever a script element's type, the HTML parser
//                              ends it at the first "</script" and treats "<!--" specially (after
//                              "<!--<script" the real "</script>" no longer ends the element), so
//                              the C++ side escapes "<" in the JSON text: "</" as "<\/" at the
//                              least, better every "<" as \u003c; JSON.parse undoes either.
//   /*@CERTIPOSE_VIEWER_JS@*/  inside a classic <script> at the end of <body>: the contents of
//                              viewer.bundle.js, verbatim.
//
// This script guarantees that the bundle is ASCII (esbuild escapes every other character) and
// contains neither "</script" nor "<!--" (in any letter case) nor any placeholder nor the closing
// sequence of cmake/embed_viewer.cmake's raw string literals. "</script" is rewritten as
// "<\/script" (esbuild already writes it so in string literals; the rewrite is harmless in regular
// expressions and template literals too); anything else fails the build.

import { build } from 'esbuild';
import { copyFile, mkdir, readFile, writeFile } from 'node:fs/promises';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const PLACEHOLDERS = ['@CERTIPOSE_TITLE@', '@CERTIPOSE_SCENE_JSON@', '/*@CERTIPOSE_VIEWER_JS@*/'];

function fail(message) {
  console.error(`build.mjs: ${message}`);
  process.exit(1);
}

function count(haystack, needle) {
  let n = 0;
  for (let i = haystack.indexOf(needle); i >= 0; i = haystack.indexOf(needle, i + needle.length)) n++;
  return n;
}

const outDir = process.argv[2];
if (!outDir || process.argv.length > 3) fail('usage: node web/build.mjs OUT_DIR');
await mkdir(outDir, { recursive: true });

const template = await readFile(path.join(here, 'src', 'viewer.html'), 'utf8');
for (const p of PLACEHOLDERS) {
  const n = count(template, p);
  if (n !== 1) fail(`the template must contain ${p} exactly once (found ${n})`);
}

const result = await build({
  entryPoints: [path.join(here, 'src', 'viewer.js')],
  absWorkingDir: here,
  bundle: true,
  format: 'iife',
  minify: true,
  target: ['es2022'],
  platform: 'browser',
  charset: 'ascii', // non-ASCII characters as escapes: safe to embed in any C++ string literal
  legalComments: 'eof', // keeps three.js's MIT licence notice
  write: false,
  logLevel: 'warning',
});
if (result.outputFiles.length !== 1) fail(`esbuild wrote ${result.outputFiles.length} files, expected 1`);

let js = result.outputFiles[0].text.replace(/<\/(script)/gi, '<\\/$1');
if (/<\/script/i.test(js)) fail('the bundle still contains "</script"');
if (js.includes('<!--')) fail('the bundle contains "<!--", which would derail the inline <script>');
if (/[^\x00-\x7f]/.test(js)) fail('the bundle contains non-ASCII characters');
// cmake/embed_viewer.cmake embeds the bundle as C++ raw string literals R"certipose_viewer(...)certipose_viewer".
if (js.includes(')certipose_viewer"')) fail('the bundle contains the raw string literal\'s closing sequence');
for (const p of [...PLACEHOLDERS, '@CERTIPOSE_']) {
  if (js.includes(p)) fail(`the bundle contains the placeholder text ${p}`);
}

const bundlePath = path.join(outDir, 'viewer.bundle.js');
await writeFile(bundlePath, js);
await copyFile(path.join(here, 'src', 'viewer.html'), path.join(outDir, 'viewer.html'));
console.log(`build.mjs: wrote ${bundlePath} (${Buffer.byteLength(js)} bytes) and ${path.join(outDir, 'viewer.html')}`);
