#!/usr/bin/env node
// Loads a plan's glTF binary with three.js's GLTFLoader (a loader that is not ours) and checks
// that a render or CAD tool can look through each camera:
//
//   node tests/web/load_glb.mjs FILE.glb PLAN.csv
//
// For every row of PLAN.csv (certipose-export --format csv of the same plan), the scene must
// hold one perspective camera on the node "camera k view" whose world position is the row's nominal position
// and whose view direction (three.js cameras look down their −z) is the row's optical axis, the
// third column of its rotation r00…r22 — both after the scene's z-up → y-up turn. Numbers in the
// file are single precision and the CSV's are rounded to 0.1 mm, hence the tolerances below.
// Prints "load_glb: N passed, M failed" and exits 1 on any failure, 2 on bad usage. Run `npm ci`
// in web/ first: three is resolved from web/node_modules.

import { readFile } from 'node:fs/promises';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const web = path.join(here, '..', '..', 'web', 'node_modules', 'three');

const [glbArg, csvArg] = process.argv.slice(2);
if (!glbArg || !csvArg || process.argv.length > 4) {
  console.error('usage: node tests/web/load_glb.mjs FILE.glb PLAN.csv');
  process.exit(2);
}
let THREE, GLTFLoader;
try {
  THREE = await import(pathToFileURL(path.join(web, 'build', 'three.module.js')).href);
  ({ GLTFLoader } = await import(pathToFileURL(path.join(web, 'examples', 'jsm', 'loaders', 'GLTFLoader.js')).href));
} catch (e) {
  console.error(`load_glb: cannot load three.js (run \`npm ci\` in web/): ${e.message}`);
  process.exit(2);
}
let bytes, csv;
try {
  bytes = await readFile(glbArg);
  csv = await readFile(csvArg, 'utf8');
} catch (e) {
  console.error(`load_glb: ${e.message}`);
  process.exit(2);
}

let passed = 0;
let failed = 0;
const check = (ok, what) => {
  if (ok) passed++;
  else failed++;
  console.log(`  ${ok ? 'ok  ' : 'FAIL'} ${what}`);
};

const lines = csv.trim().split('\n');
const header = lines[0].split(',');
const rows = lines.slice(1).map((l) => {
  const cells = l.split(',');
  return Object.fromEntries(header.map((h, i) => [h, Number(cells[i])]));
});

const buffer = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
const gltf = await new GLTFLoader().parseAsync(buffer, '');
gltf.scene.updateMatrixWorld(true);
check(gltf.cameras.length === rows.length, `${gltf.cameras.length} glTF cameras for ${rows.length} plan cameras`);

// The scene's root turns the part frame (z up) to glTF's y up: −90° about x.
const toScene = new THREE.Matrix4().makeRotationX(-Math.PI / 2);
for (const row of rows) {
  const k = row.camera;
  // The loader names a camera after its node (keeping the original in userData.name).
  const cam = gltf.cameras.find((c) => (c.userData.name || c.name) === `camera ${k} view`);
  if (!cam) {
    check(false, `camera ${k}: no glTF camera of that name`);
    continue;
  }
  check(cam.isPerspectiveCamera === true, `camera ${k}: a perspective camera`);
  const at = new THREE.Vector3();
  cam.getWorldPosition(at);
  const want = new THREE.Vector3(row.x_mm / 1000, row.y_mm / 1000, row.z_mm / 1000).applyMatrix4(toScene);
  const off = at.distanceTo(want);
  check(off < 2e-4, `camera ${k}: at the nominal position (off by ${(off * 1000).toFixed(3)} mm)`);
  const looks = new THREE.Vector3();
  cam.getWorldDirection(looks);
  const axis = new THREE.Vector3(row.r02, row.r12, row.r22).applyMatrix4(toScene).normalize();
  const angle = looks.angleTo(axis);
  check(angle < 1e-5, `camera ${k}: looks along the optical axis (off by ${angle.toExponential(2)} rad)`);
  check(cam.fov > 1 && cam.fov < 179, `camera ${k}: a field of view of ${cam.fov.toFixed(2)}°`);
}
console.log(`load_glb: ${passed} passed, ${failed} failed`);
process.exit(failed ? 1 : 0);
