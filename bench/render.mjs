// Renders the partitions of vqsa GLB files to PNG (two opposite views, one colour per
// region, boundaries drawn): `node bench/render.mjs OUT_DIR FILE.glb[=Title] ...`.
// Uses the test setup: Debian's Chromium through playwright-core, served on localhost.
import { mkdirSync } from 'node:fs';
import { basename, join, resolve } from 'node:path';
import { launchBrowser } from '../tests/browser/support.mjs';
import { startServer } from '../scripts/serve.mjs';
import { root } from '../tests/node/support.mjs';

const [out, ...inputs] = process.argv.slice(2);
if (!out || inputs.length === 0) {
  console.error('usage: node bench/render.mjs OUT_DIR FILE.glb[=Title] ...');
  process.exit(2);
}
mkdirSync(out, { recursive: true });
const files = inputs.map((arg) => {
  const [file, title] = arg.split('=');
  return { file: resolve(file), title: title ?? basename(file, '.glb') };
});
const mounts = { '/': join(root, 'bench'), '/node/': join(root, 'node_modules') };
files.forEach((f, i) => { mounts[`/input${i}/`] = join(f.file, '..'); });
const server = await startServer({ mounts });
const browser = await launchBrowser();
try {
  const page = await browser.newPage({ viewport: { width: 1160, height: 480 } });
  page.on('pageerror', (e) => console.error(e.message));
  await page.goto(`http://127.0.0.1:${server.address().port}/render.html`);
  await page.waitForFunction(() => window.ready);
  for (const [i, { file, title }] of files.entries()) {
    await page.evaluate(([url, t]) => window.render(url, t), [`/input${i}/${basename(file)}`, title]);
    const png = join(out, `${basename(file, '.glb')}.png`);
    await page.locator('#frame').screenshot({ path: png });
    console.log(png);
  }
} finally {
  await browser.close();
  server.close();
}
