#!/usr/bin/env node
// Validates a glTF binary with the Khronos glTF validator:
//
//   node tests/web/validate_glb.mjs FILE.glb
//
// Exits 0 when the report has no error (printing the number of warnings, infos and hints, and
// the messages of the warnings), 1 when it has errors (printing each), 2 on bad usage or an
// unreadable file. Run `npm ci` in web/ first: the validator is resolved from web/node_modules.

import { readFile } from 'node:fs/promises';
import { createRequire } from 'node:module';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const requireFromWeb = createRequire(path.join(here, '..', '..', 'web', 'package.json'));

function die(code, message) {
  console.error(`validate_glb: ${message}`);
  process.exit(code);
}

const file = process.argv[2];
if (!file || process.argv.length > 3) die(2, 'usage: node tests/web/validate_glb.mjs FILE.glb');

let validator;
try {
  validator = requireFromWeb('gltf-validator');
} catch (e) {
  die(2, `cannot load gltf-validator (run \`npm ci\` in web/): ${e.message}`);
}

let bytes;
try {
  bytes = new Uint8Array(await readFile(file));
} catch (e) {
  die(2, `cannot read ${file}: ${e.message}`);
}

let report;
try {
  report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 1000,
    // The .glb is self-contained: any external URI is itself a problem, so refuse to load it.
    externalResourceFunction: (uri) => Promise.reject(new Error(`external resource ${uri} is not allowed`)),
  });
} catch (e) {
  die(1, `${file}: the validator failed: ${e && e.message ? e.message : e}`);
}

const issues = report.issues;
const label = ['error', 'warning', 'info', 'hint'];
const show = (severity) => {
  for (const m of issues.messages.filter((x) => x.severity === severity)) {
    const where = m.pointer !== undefined ? m.pointer : m.offset !== undefined ? `byte ${m.offset}` : '';
    console.log(`  ${label[severity]} ${m.code}${where ? ` at ${where}` : ''}: ${m.message}`);
  }
};
const summary = `${issues.numErrors} error(s), ${issues.numWarnings} warning(s), ${issues.numInfos} info(s), ${issues.numHints} hint(s)`;
const info = report.info || {};
const contents = info.drawCallCount !== undefined
  ? ` [${info.drawCallCount} draw call(s), ${info.totalVertexCount} vertices, ${info.totalTriangleCount} triangles]` : '';
if (issues.truncated) console.log('validate_glb: the validator stopped after too many issues; the counts are a lower bound');
if (issues.numErrors > 0) {
  console.log(`validate_glb: ${file}: INVALID: ${summary}`);
  show(0);
  show(1);
  process.exit(1);
}
console.log(`validate_glb: ${file}: valid (${report.validatorVersion}): ${summary}${contents}`);
show(1);
