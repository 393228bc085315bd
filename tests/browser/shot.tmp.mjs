import { launchBrowser, startSite } from './support.mjs';
const site = await startSite();
const browser = await launchBrowser();
const errors = [];
for (const [path, w, h, name] of [['index.html', 1400, 900, 'app'], ['embed.html', 1280, 900, 'embed'], ['index.html', 390, 844, 'narrow']]) {
  const page = await browser.newPage({ viewport: { width: w, height: h } });
  page.on('console', (m) => m.type() === 'error' && errors.push(m.text()));
  page.on('pageerror', (e) => errors.push(e.message));
  await page.goto(`${site.url}/${path}`);
  await page.waitForFunction(() => document.querySelector('.vqsa-viewer')?.dataset.state === 'done', null, { timeout: 60000 }).catch(() => {});
  await page.waitForTimeout(500);
  await page.screenshot({ path: `/tmp/${name}.png`, fullPage: name !== 'app' });
  console.log(name, await page.evaluate(() => document.querySelector('.vqsa-viewer').dataset.state));
}
console.log(errors);
await browser.close();
site.server.close();
