// The headless Chromium of the browser tests (viewer_test.mjs, sheet_test.mjs): Debian's
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
