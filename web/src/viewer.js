// certipose camera-plan viewer.
//
// Bundled by web/build.mjs into one IIFE that certipose-export inlines into the page
// (web/src/viewer.html). It reads the scene JSON from <script id="certipose-scene">, decodes the
// glTF binary in it, renders the part (triangle i = facet i, coloured by camera), each camera's
// frustum and position-tolerance box, lists the cameras, and lets one pick facets.
//
// For tests it exposes window.certipose = { ready, facetScreenPosition(f), facetCount, ... }.
//
// The part's coordinates are metres in the part frame, Z up. The glTF file may hold them as they are
// or under a root node that turns them into glTF's Y-up convention: the viewer reads the part
// node's world rotation and takes the part frame's +Z, so turned, as the view's up direction.

import {
  BufferAttribute,
  BufferGeometry,
  Box3,
  Color,
  DirectionalLight,
  DoubleSide,
  Float32BufferAttribute,
  HemisphereLight,
  LineBasicMaterial,
  LineLoop,
  LineSegments,
  MeshStandardMaterial,
  PerspectiveCamera,
  SRGBColorSpace,
  Quaternion,
  Raycaster,
  Scene,
  Sphere,
  Vector2,
  Vector3,
  WebGLRenderer,
  WireframeGeometry,
} from 'three';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';

const BACKGROUND = '#f4f5f7';           // canvas clear colour (sRGB); exposed to tests
const UNCOVERED_GREY = new Color(0x9a9ea6);
const PICK_COLOUR = new Color(0xffd400);
const PICK_OUTLINE = 0xd4145a;
const DIM_MIX = 0.78;                   // how far non-selected facets fade toward the background
const MAX_EDGE_FACETS = 20000;          // draw facet edges by default up to this many facets
const FALLBACK_PALETTE = [0xe6194b, 0x3cb44b, 0x4363d8, 0xf58231, 0x911eb4, 0x42d4f4, 0xf032e6,
  0xbfef45, 0x469990, 0x9a6324, 0x800000, 0x808000, 0x000075];

let resolveReady;
let rejectReady;
const ready = new Promise((resolve, reject) => { resolveReady = resolve; rejectReady = reject; });
// A failure is reported on the page and through `ready`; keep an unobserved rejection quiet.
ready.catch(() => {});

const api = {
  ready,
  facetCount: 0,
  background: BACKGROUND,
  facetScreenPosition: () => null,
  selectCamera: () => {},
  pickFacet: () => {},
};
window.certipose = api;

function showMessage(text) {
  const el = document.getElementById('message');
  if (el) el.textContent = text;
}

function readScene() {
  const el = document.getElementById('certipose-scene');
  if (!el) throw new Error('no <script id="certipose-scene"> in the page');
  let scene;
  try {
    scene = JSON.parse(el.textContent);
  } catch (e) {
    throw new Error(`the scene JSON does not parse (${e.message}); was the template filled in?`);
  }
  if (!scene || typeof scene.glb !== 'string') throw new Error('the scene JSON has no "glb" string');
  return scene;
}

function base64ToArrayBuffer(text) {
  const clean = text.replace(/\s+/g, '');
  if (typeof Uint8Array.fromBase64 === 'function') return Uint8Array.fromBase64(clean).buffer;
  const binary = atob(clean);
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; i++) bytes[i] = binary.charCodeAt(i);
  return bytes.buffer;
}

function formatNumber(v) {
  return Number.isFinite(v) ? v.toFixed(3) : String(v);
}

// Finds the glTF nodes by their original names (GLTFLoader keeps them in userData.name; node.name
// itself is sanitised, spaces becoming underscores).
function findNodes(root) {
  let part = null;
  const cameraLines = new Map(); // k -> { frustum: Object3D[], tolerance: Object3D[] }
  root.traverse((obj) => {
    const name = obj.userData && obj.userData.name;
    if (typeof name !== 'string') return;
    if (name === 'part' && !part) part = obj;
    const m = /^camera (\d+) (frustum|tolerance|cone)$/.exec(name);
    if (m) {
      const k = Number(m[1]);
      if (!cameraLines.has(k)) cameraLines.set(k, { frustum: [], tolerance: [] });
      // The axis cone is part of the camera's tolerance: it fades and shows with the box.
      cameraLines.get(k)[m[2] === 'cone' ? 'tolerance' : m[2]].push(obj);
    }
  });
  let partMesh = null;
  if (part) {
    part.traverse((obj) => { if (!partMesh && obj.isMesh) partMesh = obj; });
  }
  return { partMesh, cameraLines };
}

function lineObjects(list) {
  const out = [];
  for (const node of list) node.traverse((obj) => { if (obj.isLine) out.push(obj); });
  return out;
}

async function main() {
  const sceneData = readScene();
  const title = typeof sceneData.title === 'string' && sceneData.title ? sceneData.title : 'certipose camera plan';
  document.getElementById('title').textContent = title;

  const cameras = Array.isArray(sceneData.cameras) ? sceneData.cameras : [];
  const facetCameras = Array.isArray(sceneData.facet_cameras) ? sceneData.facet_cameras : [];
  // Why an uncovered facet is uncovered (PLAN.json's reasons), for the picker and the summary.
  const whyUncovered = new Map();
  const reasonCounts = [];
  if (sceneData.uncovered && typeof sceneData.uncovered === 'object') {
    for (const [reason, facets] of Object.entries(sceneData.uncovered)) {
      if (!Array.isArray(facets)) continue;
      for (const f of facets) whyUncovered.set(f, reason);
      reasonCounts.push(`${facets.length} ${reason}`);
    }
  }
  const cameraByIndex = new Map();
  cameras.forEach((c, i) => cameraByIndex.set(Number.isInteger(c.index) ? c.index : i, c));
  // A camera's "colour" in the scene JSON: [r, g, b], sRGB, 0-255 (or 0-1).
  const jsonColour = (k) => {
    const c = cameraByIndex.get(k);
    const rgb = c && (c.colour || c.color);
    if (!Array.isArray(rgb) || rgb.length < 3 || !rgb.slice(0, 3).every(Number.isFinite)) return null;
    const scale = rgb.slice(0, 3).some((x) => x > 1) ? 1 / 255 : 1;
    return new Color().setRGB(rgb[0] * scale, rgb[1] * scale, rgb[2] * scale, SRGBColorSpace);
  };
  const paletteColour = (k) => jsonColour(k) || new Color(FALLBACK_PALETTE[k % FALLBACK_PALETTE.length]);
  const cameraName = (k) => {
    const c = cameraByIndex.get(k);
    return c && typeof c.name === 'string' ? c.name : `camera ${k}`;
  };

  // --- three.js set-up -----------------------------------------------------------------------
  const view = document.getElementById('view');
  const renderer = new WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setClearColor(new Color(BACKGROUND), 1);
  view.prepend(renderer.domElement);

  const scene = new Scene();
  const camera = new PerspectiveCamera(40, 1, 0.001, 100);
  scene.add(camera);
  scene.add(new HemisphereLight(0xffffff, 0x767b85, 1.9));
  const headLight = new DirectionalLight(0xffffff, 1.6);
  headLight.position.set(0.4, 0.6, 1); // relative to the viewpoint, slightly above and right
  camera.add(headLight);
  camera.add(headLight.target);
  headLight.target.position.set(0, 0, -1);

  const gltf = await new GLTFLoader().parseAsync(base64ToArrayBuffer(sceneData.glb), '');
  const root = gltf.scene;
  scene.add(root);
  root.updateMatrixWorld(true);

  const { partMesh, cameraLines } = findNodes(root);
  // The part frame's axes start at its origin, often inside the part: draw them over it.
  root.traverse((obj) => {
    const name = obj.userData && obj.userData.name;
    if (typeof name !== 'string' || !/^axis [xyz]$/.test(name)) return;
    obj.traverse((o) => {
      if (!o.isLine) return;
      o.material = o.material.clone();
      o.material.depthTest = false;
      o.renderOrder = 5;
    });
  });
  if (!partMesh) throw new Error('the glTF scene has no mesh node named "part"');
  // The part frame in world coordinates: its +Z is up, whatever the glTF root does (see above).
  const partRotation = new Quaternion();
  partMesh.matrixWorld.decompose(new Vector3(), partRotation, new Vector3());
  camera.up.set(0, 0, 1).applyQuaternion(partRotation).normalize();

  // --- the part: per-facet colours we can change ---------------------------------------------
  let geometry = partMesh.geometry;
  if (geometry.index) geometry = geometry.toNonIndexed(); // the exporter writes none; be lenient
  const position = geometry.getAttribute('position');
  const facetCount = Math.floor(position.count / 3);
  api.facetCount = facetCount;

  const baseColours = new Float32Array(facetCount * 9);
  const sourceColour = geometry.getAttribute('color');
  for (let v = 0; v < facetCount * 3; v++) {
    if (sourceColour) {
      baseColours[3 * v] = sourceColour.getX(v);
      baseColours[3 * v + 1] = sourceColour.getY(v);
      baseColours[3 * v + 2] = sourceColour.getZ(v);
    } else {
      const f = Math.floor(v / 3);
      const ks = facetCameras[f] || [];
      const c = ks.length ? paletteColour(ks[0]) : UNCOVERED_GREY;
      baseColours[3 * v] = c.r; baseColours[3 * v + 1] = c.g; baseColours[3 * v + 2] = c.b;
    }
  }
  const colourAttr = new BufferAttribute(new Float32Array(baseColours), 3);
  geometry.setAttribute('color', colourAttr);
  if (!geometry.getAttribute('normal')) geometry.computeVertexNormals();
  partMesh.geometry = geometry;
  partMesh.material = new MeshStandardMaterial({
    vertexColors: true, metalness: 0, roughness: 0.85, flatShading: true, side: DoubleSide,
    polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1,
  });

  const edges = new LineSegments(new WireframeGeometry(geometry),
    new LineBasicMaterial({ color: 0x1d2330, transparent: true, opacity: 0.18 }));
  edges.visible = facetCount <= MAX_EDGE_FACETS;
  partMesh.add(edges);

  // The picked facet's outline, drawn over everything.
  const outlineGeometry = new BufferGeometry();
  outlineGeometry.setAttribute('position', new Float32BufferAttribute(new Float32Array(9), 3));
  const outline = new LineLoop(outlineGeometry,
    new LineBasicMaterial({ color: PICK_OUTLINE, depthTest: false, transparent: true }));
  outline.renderOrder = 10;
  outline.visible = false;
  partMesh.add(outline);

  // --- cameras ---------------------------------------------------------------------------------
  const cameraIndices = new Set([...cameraByIndex.keys(), ...cameraLines.keys()]);
  for (const ks of facetCameras) for (const k of Array.isArray(ks) ? ks : []) if (Number.isInteger(k)) cameraIndices.add(k);
  const sortedCameras = [...cameraIndices].sort((a, b) => a - b);
  const facetsOf = new Map(sortedCameras.map((k) => [k, new Set()]));
  for (const k of sortedCameras) {
    const c = cameraByIndex.get(k);
    if (c && Array.isArray(c.facets)) for (const f of c.facets) facetsOf.get(k).add(f);
  }
  facetCameras.forEach((ks, f) => {
    for (const k of Array.isArray(ks) ? ks : []) if (facetsOf.has(k)) facetsOf.get(k).add(f);
  });

  // Per camera: its line objects (own material, so they can be dimmed) and a display colour.
  const linesOf = new Map();
  const colourOf = new Map();
  for (const k of sortedCameras) {
    const group = cameraLines.get(k) || { frustum: [], tolerance: [] };
    const lines = lineObjects([...group.frustum, ...group.tolerance]);
    for (const l of lines) {
      l.material = l.material.clone();
      l.material.transparent = true;
      l.userData.baseOpacity = l.material.opacity;
    }
    linesOf.set(k, lines);
    // The camera's colour as drawn: a facet only it certifies, else its frustum's colour, else the
    // scene JSON's, else a palette's.
    let colour = null;
    const only = facetCameras.findIndex((ks) => Array.isArray(ks) && ks.length === 1 && ks[0] === k);
    if (only >= 0 && only < facetCount) {
      colour = new Color(baseColours[9 * only], baseColours[9 * only + 1], baseColours[9 * only + 2]);
    } else if (lines.length && lines[0].material.color) {
      colour = lines[0].material.color.clone();
    } else {
      colour = paletteColour(k);
    }
    colourOf.set(k, colour);
  }

  // --- state and colouring ---------------------------------------------------------------------
  let selectedCamera = null;
  let pickedFacet = null;
  const background = new Color(BACKGROUND);

  function recolour() {
    const out = colourAttr.array;
    out.set(baseColours);
    if (selectedCamera !== null) {
      // The selected camera's facets in its colour (a facet that several cameras certify has only
      // one of their colours in the file), every other facet faded toward the background.
      const keep = facetsOf.get(selectedCamera) || new Set();
      const mine = colourOf.get(selectedCamera);
      for (let f = 0; f < facetCount; f++) {
        if (keep.has(f)) {
          for (let i = 9 * f; i < 9 * f + 9; i += 3) { out[i] = mine.r; out[i + 1] = mine.g; out[i + 2] = mine.b; }
          continue;
        }
        for (let i = 9 * f; i < 9 * f + 9; i += 3) {
          out[i] += (background.r - out[i]) * DIM_MIX;
          out[i + 1] += (background.g - out[i + 1]) * DIM_MIX;
          out[i + 2] += (background.b - out[i + 2]) * DIM_MIX;
        }
      }
    }
    if (pickedFacet !== null) {
      for (let i = 9 * pickedFacet; i < 9 * pickedFacet + 9; i += 3) {
        out[i] = PICK_COLOUR.r; out[i + 1] = PICK_COLOUR.g; out[i + 2] = PICK_COLOUR.b;
      }
    }
    colourAttr.needsUpdate = true;
    for (const [k, lines] of linesOf) {
      for (const l of lines) {
        l.material.opacity = selectedCamera === null || selectedCamera === k
          ? l.userData.baseOpacity : 0.2 * l.userData.baseOpacity;
      }
    }
    requestRender();
  }

  // --- side panel ------------------------------------------------------------------------------
  const list = document.getElementById('cameras');
  const items = new Map();
  for (const k of sortedCameras) {
    const c = cameraByIndex.get(k);
    const li = document.createElement('li');
    li.tabIndex = 0;
    li.dataset.camera = String(k);
    const swatch = document.createElement('span');
    swatch.className = 'swatch';
    swatch.style.background = `#${colourOf.get(k).getHexString()}`;
    const text = document.createElement('div');
    const name = document.createElement('div');
    name.className = 'name';
    name.textContent = cameraName(k);
    const detail = document.createElement('div');
    detail.className = 'detail';
    const n = facetsOf.get(k).size;
    let d = `${n} facet${n === 1 ? '' : 's'}`;
    if (c && Array.isArray(c.position)) d += ` · at (${c.position.map(formatNumber).join(', ')}) m`;
    const t = c && c.tolerance;
    if (t && Array.isArray(t.half_mm)) {
      d += ` · ±(${t.half_mm.map((v) => v.toFixed(1)).join(', ')}) mm, axis within ${Number(t.cone_deg).toFixed(2)}°,`
        + ` roll ±${Number(t.roll_deg).toFixed(2)}°`;
    }
    detail.textContent = d;
    text.append(name, detail);
    li.append(swatch, text);
    const toggle = () => selectCamera(selectedCamera === k ? null : k);
    li.addEventListener('click', toggle);
    li.addEventListener('keydown', (e) => { if (e.key === 'Enter' || e.key === ' ') { e.preventDefault(); toggle(); } });
    list.append(li);
    items.set(k, li);
  }
  const covered = facetCameras.filter((ks) => Array.isArray(ks) && ks.length > 0).length;
  document.getElementById('summary').textContent =
    `${facetCount} facets, ${covered} certified by some camera; ${sortedCameras.length} camera${sortedCameras.length === 1 ? '' : 's'}`
    + (reasonCounts.length ? `. Uncovered: ${reasonCounts.join(', ')}` : '');

  function selectCamera(k) {
    selectedCamera = k === null || k === undefined || !facetsOf.has(k) ? null : k;
    for (const [j, li] of items) li.classList.toggle('selected', j === selectedCamera);
    recolour();
  }

  const pickDiv = document.getElementById('pick');
  function pickFacet(f) {
    if (f === null || f === undefined || !(f >= 0 && f < facetCount)) {
      pickedFacet = null;
      outline.visible = false;
      pickDiv.textContent = 'no facet under the pointer';
      recolour();
      return;
    }
    pickedFacet = f;
    const ks = Array.isArray(facetCameras[f]) ? facetCameras[f] : [];
    pickDiv.textContent = ks.length
      ? `facet ${f}: ${ks.map(cameraName).join(', ')}`
      : `facet ${f}: no camera certifies it${whyUncovered.has(f) ? ` (${whyUncovered.get(f)})` : ''}`;
    const p = outlineGeometry.getAttribute('position');
    for (let i = 0; i < 3; i++) p.setXYZ(i, position.getX(3 * f + i), position.getY(3 * f + i), position.getZ(3 * f + i));
    p.needsUpdate = true;
    outlineGeometry.computeBoundingSphere();
    outline.visible = true;
    recolour();
  }

  // --- view fitting ----------------------------------------------------------------------------
  const controls = new OrbitControls(camera, renderer.domElement);
  controls.enableDamping = false;
  controls.screenSpacePanning = true;

  // Bounding boxes in world coordinates: the part's triangles, and everything the glTF file holds
  // (the part, the frustums and the tolerance boxes; not the viewer's own overlays).
  const partBox = () => {
    if (!geometry.boundingBox) geometry.computeBoundingBox();
    return geometry.boundingBox.clone().applyMatrix4(partMesh.matrixWorld);
  };
  const allBox = () => {
    const box = partBox();
    for (const lines of linesOf.values()) for (const l of lines) box.union(new Box3().setFromObject(l));
    return box;
  };

  function fitTo(box) {
    root.updateMatrixWorld(true);
    if (box.isEmpty()) return;
    const sphere = box.getBoundingSphere(new Sphere());
    const radius = Math.max(sphere.radius, 1e-6);
    const fov = (camera.fov * Math.PI) / 180;
    const fitFov = camera.aspect < 1 ? 2 * Math.atan(Math.tan(fov / 2) * camera.aspect) : fov;
    const distance = (radius / Math.sin(fitFov / 2)) * 1.05;
    // From the front right, above (in the part frame).
    const direction = new Vector3(0.9, -1.3, 0.8).applyQuaternion(partRotation).normalize();
    controls.target.copy(sphere.center);
    camera.position.copy(sphere.center).addScaledVector(direction, distance);
    const all = allBox().getBoundingSphere(new Sphere());
    const far = (distance + all.radius + all.center.distanceTo(sphere.center)) * 4;
    camera.near = far / 20000;
    camera.far = far;
    controls.maxDistance = far / 2;
    camera.updateProjectionMatrix();
    controls.update();
    requestRender();
  }

  // --- rendering on demand ---------------------------------------------------------------------
  let framePending = false;
  let firstFrame = true;
  function renderNow() {
    framePending = false;
    renderer.render(scene, camera);
    if (firstFrame) {
      firstFrame = false;
      requestAnimationFrame(() => resolveReady());
    }
  }
  function requestRender() {
    if (framePending) return;
    framePending = true;
    requestAnimationFrame(renderNow);
  }
  function resize() {
    const w = Math.max(1, view.clientWidth);
    const h = Math.max(1, view.clientHeight);
    renderer.setSize(w, h, false);
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
    requestRender();
  }
  controls.addEventListener('change', requestRender);
  new ResizeObserver(resize).observe(view);
  resize();
  root.updateMatrixWorld(true);
  fitTo(partBox());

  // --- buttons: fit part / fit all / facet edges -------------------------------------------------
  const help = document.getElementById('help');
  const bar = document.createElement('div');
  bar.style.cssText = 'display:flex;gap:6px;flex-wrap:wrap;margin-bottom:6px';
  const button = (label, onClick) => {
    const b = document.createElement('button');
    b.type = 'button';
    b.textContent = label;
    b.addEventListener('click', onClick);
    bar.append(b);
    return b;
  };
  button('fit part', () => fitTo(partBox()));
  button('fit all', () => fitTo(allBox()));
  const edgeButton = button(edges.visible ? 'hide facet edges' : 'show facet edges', () => {
    edges.visible = !edges.visible;
    edgeButton.textContent = edges.visible ? 'hide facet edges' : 'show facet edges';
    requestRender();
  });
  help.prepend(bar);

  // --- picking -----------------------------------------------------------------------------------
  const raycaster = new Raycaster();
  const ndc = new Vector2();
  let down = null;
  renderer.domElement.addEventListener('pointerdown', (e) => {
    down = e.button === 0 ? { x: e.clientX, y: e.clientY } : null;
  });
  renderer.domElement.addEventListener('pointerup', (e) => {
    if (!down || e.button !== 0) return;
    const moved = Math.hypot(e.clientX - down.x, e.clientY - down.y);
    down = null;
    if (moved > 4) return; // that was an orbit drag, not a click
    const rect = renderer.domElement.getBoundingClientRect();
    ndc.set(((e.clientX - rect.left) / rect.width) * 2 - 1, -((e.clientY - rect.top) / rect.height) * 2 + 1);
    raycaster.setFromCamera(ndc, camera);
    const hit = raycaster.intersectObject(partMesh, false)[0];
    pickFacet(hit && hit.faceIndex !== undefined && hit.faceIndex !== null ? hit.faceIndex : null);
  });

  // --- the test interface ------------------------------------------------------------------------
  const a = new Vector3();
  const b = new Vector3();
  const c = new Vector3();
  api.facetScreenPosition = (f) => {
    if (!Number.isInteger(f) || f < 0 || f >= facetCount) return null;
    camera.updateMatrixWorld();
    partMesh.updateMatrixWorld();
    a.fromBufferAttribute(position, 3 * f).applyMatrix4(partMesh.matrixWorld);
    b.fromBufferAttribute(position, 3 * f + 1).applyMatrix4(partMesh.matrixWorld);
    c.fromBufferAttribute(position, 3 * f + 2).applyMatrix4(partMesh.matrixWorld);
    const centroid = a.clone().add(b).add(c).divideScalar(3);
    const projected = centroid.clone().project(camera);
    if (Math.abs(projected.x) > 1 || Math.abs(projected.y) > 1 || projected.z < -1 || projected.z > 1) return null;
    // Visible only if the first thing the ray toward the centroid meets is this facet.
    const toCentroid = centroid.clone().sub(camera.position);
    const distance = toCentroid.length();
    raycaster.set(camera.position, toCentroid.normalize());
    raycaster.near = 0;
    raycaster.far = Infinity;
    const hit = raycaster.intersectObject(partMesh, false)[0];
    if (!hit || (hit.faceIndex !== f && hit.distance < distance * (1 - 1e-6))) return null;
    const rect = renderer.domElement.getBoundingClientRect();
    const x = ((projected.x + 1) / 2) * rect.width;
    const y = ((1 - projected.y) / 2) * rect.height;
    return { x, y, clientX: rect.left + x, clientY: rect.top + y };
  };
  api.selectCamera = selectCamera;
  api.pickFacet = pickFacet;
  api.cameras = sortedCameras.map((k) => ({ index: k, name: cameraName(k), facets: [...facetsOf.get(k)] }));

  recolour();
}

main().catch((error) => {
  showMessage(`The camera plan could not be shown: ${error.message}`);
  console.error('certipose viewer:', error);
  rejectReady(error);
});
