// The headless Chromium of the browser tests (viewer_test.mjs, sheet_test.mjs, notebook_test.mjs): Debian's
// `chromium` package (CHROMIUM=/path for another binary), driven by playwright-core from
// web/node_modules (run `npm ci` in web/ first). Browsers cannot be downloaded here, so
// playwright's own are never used.
import { existsSync } from 'node:fs';
import { createRequire } from 'node:module';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const requireFromWeb = createRequire(path.join(here, '..', '..', 'web', 'package.json'));

/// Launches Chromium with `args` (--no-sandbox is always given: the tests run as root). When
/// playwright-core or the browser is missing it says so, as `who`, and exits 2 (bad usage).
export async function launchChromium(who, args = []) {
  let chromium;
  try {
    ({ chromium } = requireFromWeb('playwright-core'));
  } catch (e) {
    console.error(`${who}: cannot load playwright-core (run \`npm ci\` in web/): ${e.message}`);
    process.exit(2);
  }
  const executablePath = process.env.CHROMIUM || '/usr/bin/chromium';
  if (!existsSync(executablePath)) {
    console.error(`${who}: no Chromium at ${executablePath} (apt-get install chromium, or set CHROMIUM)`);
    process.exit(2);
  }
  return chromium.launch({ executablePath, args: ['--no-sandbox', ...args] });
}

/// At least this share of the viewer's canvas must differ from its background for "WebGL drew".
export const MIN_DRAWN_FRACTION = 0.005;

/// How much of the viewer's canvas differs from its background colour (window.certipose.background),
/// in `frame`: a page, or the frame of a viewer embedded in one. The canvas is copied to a 2-D one
/// to read it back: { differing, total, width, height, background }.
export async function drawnPixels(frame) {
  return frame.evaluate(() => {
    const bg = window.certipose.background;
    const gl = document.querySelector('#view canvas');
    const c = document.createElement('canvas');
    c.width = gl.width;
    c.height = gl.height;
    const ctx = c.getContext('2d', { willReadFrequently: true });
    ctx.drawImage(gl, 0, 0);
    const data = ctx.getImageData(0, 0, c.width, c.height).data;
    const want = [1, 3, 5].map((i) => parseInt(bg.slice(i, i + 2), 16));
    let differing = 0;
    for (let i = 0; i < data.length; i += 4) {
      if (Math.abs(data[i] - want[0]) > 6 || Math.abs(data[i + 1] - want[1]) > 6 || Math.abs(data[i + 2] - want[2]) > 6) differing++;
    }
    return { differing, total: c.width * c.height, width: c.width, height: c.height, background: bg };
  });
}
