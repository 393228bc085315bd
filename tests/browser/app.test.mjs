// The app as a user meets it, in headless Chromium: first load, drag-and-drop, bad files,
// cancel, downloads, the embed page, and no request leaving localhost. Every test opens
// its own page.
import assert from 'node:assert/strict';
import { mkdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';
import { after, before, test } from 'node:test';
import { parseGlb, root, validateGlb } from '../node/support.mjs';
import { guardNetwork, launchBrowser, startSite } from './support.mjs';

const shots = join(root, 'build', 'screenshots');
mkdirSync(shots, { recursive: true });
let site, browser;
const offsite = [], consoleErrors = [];

async function openPage(path) {
  const p = await browser.newPage({ viewport: { width: 1280, height: 800 }, acceptDownloads: true });
  guardNetwork(p, site.url, offsite);
  p.on('console', (m) => m.type() === 'error' && consoleErrors.push(`${path}: ${m.text()}`));
  p.on('pageerror', (e) => consoleErrors.push(`${path}: ${e.message}`));
  await p.goto(`${site.url}/${path}`);
  return p;
}

const state = (p) => p.evaluate(() => document.querySelector('.vqsa-viewer').dataset.state);
const waitFor = (p, wanted, timeout = 120000) =>
  p.waitForFunction((s) => s.includes(document.querySelector('.vqsa-viewer')?.dataset.state), wanted, { timeout });

// Drops a file made in the page from bytes the test server serves (or given inline).
async function drop(p, name, { url = null, text = null } = {}) {
  await p.evaluate(async ({ name, url, text }) => {
    const bytes = url ? await (await fetch(url)).arrayBuffer() : new TextEncoder().encode(text);
    const transfer = new DataTransfer();
    transfer.items.add(new File([bytes], name));
    document.body.dispatchEvent(new DragEvent('dragover', { dataTransfer: transfer, bubbles: true, cancelable: true }));
    document.body.dispatchEvent(new DragEvent('drop', { dataTransfer: transfer, bubbles: true, cancelable: true }));
  }, { name, url, text });
}

// Each test has a page of its own (no test depends on another's state): the app, with its
// example approximated.
async function openApp() {
  const p = await openPage('index.html');
  await waitFor(p, ['done']);
  return p;
}

// A small digest of what the canvas shows: distinct colours on a 32×32 thumbnail.
const canvasDigest = (p) => p.evaluate(() => {
  const canvas = document.querySelector('.vqsa-viewer').shadowRoot.querySelector('.vqsa-canvas canvas');
  const g = document.createElement('canvas');
  g.width = 32, g.height = 32;
  const c = g.getContext('2d');
  c.drawImage(canvas, 0, 0, 32, 32);
  return Array.from(c.getImageData(0, 0, 32, 32).data).join(',');
});

// Does `action` and waits for the run it starts to end in one of the `wanted` states. The
// states are recorded as they change: a short run goes from running to done between two
// polls of waitForFunction.
async function runAndWait(p, action, wanted = ['done']) {
  await p.evaluate(() => {
    const host = document.querySelector('.vqsa-viewer');
    window.stateObserver?.disconnect();
    window.seenStates = [];
    window.stateObserver = new MutationObserver((records) => {
      for (const r of records) window.seenStates.push(r.oldValue);
      window.seenStates.push(host.dataset.state);
    });
    window.stateObserver.observe(host, { attributes: true, attributeFilter: ['data-state'], attributeOldValue: true });
  });
  await action();
  await p.waitForFunction((w) => window.seenStates.includes('running') &&
    w.includes(document.querySelector('.vqsa-viewer').dataset.state), wanted, { timeout: 120000 });
}

async function setProxies(p, n) {
  const input = p.locator('[data-option="proxies"] input[type="number"]');
  await input.fill(String(n));
  await input.press('Enter');
}

before(async () => {
  site = await startSite();
  browser = await launchBrowser();
});
after(async () => {
  await browser?.close();
  site?.server.close();
  assert.deepEqual(offsite, [], 'requests left localhost');
});

test('the app opens with an example approximated, no console errors, a drawn canvas', async () => {
  const page = await openApp();
  // The turned part's six surfaces (sphere, two cylinders, cone, two planes): no sliver.
  assert.equal(await page.getAttribute('.vqsa-viewer', 'data-proxies'), '6');
  const colours = await page.evaluate(() => {
    const canvas = document.querySelector('.vqsa-viewer').shadowRoot.querySelector('.vqsa-canvas canvas');
    const g = document.createElement('canvas');
    g.width = 64, g.height = 64;
    const c = g.getContext('2d');
    c.drawImage(canvas, 0, 0, 64, 64);
    const data = c.getImageData(0, 0, 64, 64).data, seen = new Set();
    for (let i = 0; i < data.length; i += 4) seen.add(`${data[i] >> 4},${data[i + 1] >> 4},${data[i + 2] >> 4}`);
    return seen.size;
  });
  assert.ok(colours > 8, `the canvas looks blank (${colours} colours)`);
  await page.screenshot({ path: join(shots, 'app-example.png') });
  assert.deepEqual(consoleErrors, []);
  await page.close();
});

test('an idle page draws nothing; a camera move draws', async () => {
  const page = await openApp();
  const frames = (action) => page.evaluate(async (action) => {
    let n = 0;
    const raf = window.requestAnimationFrame;
    window.requestAnimationFrame = (callback) => (++n, raf(callback));
    if (action) document.querySelector('.vqsa-viewer').shadowRoot.querySelector('.vqsa-canvas canvas').dispatchEvent(new WheelEvent('wheel', { deltaY: 200, bubbles: true }));
    await new Promise((resolve) => setTimeout(resolve, action ? 500 : 2000));
    window.requestAnimationFrame = raf;
    return n;
  }, action);
  await frames(false);  // let the camera's damping come to rest after the first framing
  assert.equal(await frames(false), 0);
  assert.ok(await frames(true) > 0);
  await page.close();
});

test('the inspector prints parameters in the units they mean', async () => {
  const page = await openApp();
  // The example's cone: its half-angle in degrees, the quadric with its terms.
  await page.hover('.vqsa-table tr[data-region]:has-text("cone")');
  const detail = await page.textContent('.vqsa-detail');
  assert.match(detail, /half angle: \d+\.\d\d°/);
  assert.match(detail, /f = −?[0-9.e+-]+( [+−] [0-9.e+-]+ (x|y|z|x²|xy|xz|y²|yz|z²))+/);
  assert.doesNotMatch(detail, /-0\b|\(0\.00, 0\.00, 0\.00\)/);
  await page.mouse.move(0, 0);
  await page.close();
});

test('a dropped 20K-face mesh runs to 20 proxies through the growing counts; the GLB downloads and validates', async () => {
  const page = await openApp();
  await setProxies(page, 20);
  await page.evaluate(() => {
    window.seen = [];
    const viewer = document.querySelector('.vqsa-viewer');
    new MutationObserver(() => viewer.dataset.state === 'running' && window.seen.push(Number(viewer.dataset.proxies)))
      .observe(viewer, { attributes: true, attributeFilter: ['data-proxies'] });
  });
  await drop(page, 'rocker_arm.obj', { url: '/meshes/rocker_arm.obj' });
  await waitFor(page, ['running']);
  await page.screenshot({ path: join(shots, 'app-running.png') });
  await waitFor(page, ['done']);
  const seen = await page.evaluate(() => window.seen);
  assert.ok(new Set(seen).size >= 4 && Math.min(...seen) <= 5, `proxy counts seen while running: ${seen}`);
  assert.equal(await page.getAttribute('.vqsa-viewer', 'data-proxies'), '20');
  await page.screenshot({ path: join(shots, 'app-rocker-arm.png') });

  const [download] = await Promise.all([page.waitForEvent('download'), page.click('[data-testid="download-glb"]')]);
  assert.match(download.suggestedFilename(), /^rocker_arm\.vqsa\.glb$/);
  await validateGlb(new Uint8Array(readFileSync(await download.path())), 'the app\'s GLB');

  const [json] = await Promise.all([page.waitForEvent('download'), page.click('[data-testid="download-report"]')]);
  const parsed = JSON.parse(readFileSync(await json.path(), 'utf8'));
  assert.equal(parsed.proxies.length, 20);
  assert.equal(parsed.labels.length, 20088);
  await page.close();
});

test('views: heat map and types render after a run', async () => {
  const page = await openApp();
  await page.selectOption('[data-option="view"] select', 'Error heat map');
  assert.match(await page.textContent('.vqsa-legend'), /distance to the input.*≥ [0-9.e-]+.* of the diagonal = [0-9.e-]+ model units/);
  const linear = await canvasDigest(page);
  await page.selectOption('[data-option="heat"] select', 'log');
  assert.match(await page.textContent('.vqsa-legend'), /≤ [0-9.e-]+/);
  await page.waitForTimeout(100);
  assert.notEqual(await canvasDigest(page), linear);
  await page.screenshot({ path: join(shots, 'app-heatmap.png') });
  await page.selectOption('[data-option="view"] select', 'Partition');
  await page.selectOption('[data-option="colouring"] select', 'By quadric type');
  assert.match(await page.textContent('.vqsa-legend'), /plane/);
  await page.hover('.vqsa-table tr[data-region]:has-text("sphere")');
  const detail = await page.textContent('.vqsa-detail');
  assert.match(detail, /region \d+: sphere/);
  // The inspector shows how clear the type choice was.
  assert.match(detail, /type fit RMS [0-9.e+-]+; runner-up [a-z ]+, RMS [0-9.e+-]+/);
  // The GLB comes in the colours on screen.
  const [download] = await Promise.all([page.waitForEvent('download'), page.click('[data-testid="download-glb"]')]);
  const gltf = await parseGlb(new Uint8Array(readFileSync(await download.path())));
  const input = gltf.scene.getObjectByName('input'), colours = input.geometry.getAttribute('color');
  const type = input.userData.regions[input.geometry.getAttribute('_feature_id_0').getX(0)].type;
  assert.deepEqual([colours.getX(0), colours.getY(0), colours.getZ(0)].map((c) => c.toFixed(5)),
    gltf.scene.userData.legend[type].map((c) => c.toFixed(5)));
  await page.screenshot({ path: join(shots, 'app-types.png') });
  await page.close();
});

test('garbage and empty files show an error, and a valid file still works', async () => {
  const page = await openApp();
  await drop(page, 'garbage.stl', { text: 'this is not a mesh at all, just some words'.repeat(5) });
  await waitFor(page, ['error']);
  assert.match(await page.textContent('[data-testid="error"]'), /garbage\.stl: /);
  await page.screenshot({ path: join(shots, 'app-error.png') });
  await drop(page, 'empty.off', { text: '' });
  await page.waitForFunction(() => /empty\.off: the file is empty/.test(document.querySelector('.vqsa-viewer').shadowRoot.querySelector('[data-testid="error"]').textContent));
  await setProxies(page, 5);
  await drop(page, 'csg.off', { url: '/meshes/csg.off' });
  await waitFor(page, ['done']);
  assert.equal(await page.isVisible('[data-testid="error"]'), false);
  assert.equal(await page.getAttribute('.vqsa-viewer', 'data-proxies'), '5');
  await page.close();
});

test('cancel mid-run, then run again', async () => {
  const page = await openApp();
  await setProxies(page, 150);
  await drop(page, 'bunny_closed.off', { url: '/meshes/bunny_closed.off' });
  await page.waitForFunction(() => {
    const v = document.querySelector('.vqsa-viewer');
    return v.dataset.state === 'running' && Number(v.dataset.proxies) >= 3;
  }, null, { timeout: 60000 });
  await page.click('button:has-text("Cancel")', { force: true });
  await page.waitForFunction(() => document.querySelector('.vqsa-viewer').dataset.state !== 'running');
  assert.equal(await state(page), 'idle');
  await setProxies(page, 8);
  await page.click('button:has-text("Run")');
  await waitFor(page, ['done']);
  assert.equal(await page.getAttribute('.vqsa-viewer', 'data-proxies'), '8');
  await page.close();
});

test('20 rapid run/cancel cycles leave a consistent, usable app', async () => {
  const page = await openApp();
  await page.click('.vqsa-toolbar select');
  await page.selectOption('.vqsa-toolbar select', 'axle');
  await waitFor(page, ['done']);
  await setProxies(page, 40);
  for (let i = 0; i < 20; ++i) {
    await page.click('button:has-text("Run")');
    await page.waitForTimeout(i % 4 === 0 ? 0 : 30 * (i % 5));
    await page.click('button:has-text("Cancel")', { force: true });
    await page.waitForFunction(() => document.querySelector('.vqsa-viewer').dataset.state !== 'running', null, { timeout: 30000 });
  }
  assert.ok(['idle', 'done'].includes(await state(page)));
  await setProxies(page, 4);  // fewer than the axle's five surfaces: the count is met exactly
  await page.click('button:has-text("Run")');
  await waitFor(page, ['done']);
  assert.equal(await page.getAttribute('.vqsa-viewer', 'data-proxies'), '4');
  assert.equal(await page.isVisible('[data-testid="error"]'), false);
  await page.close();
});

test('the embed page renders and runs', async () => {
  const embed = await openPage('embed.html');
  await waitFor(embed, ['done']);
  await embed.waitForFunction(() => /quadrics/.test(document.getElementById('summary').textContent));
  assert.equal(await embed.getAttribute('vqsa-viewer', 'data-proxies'), '20');
  await embed.screenshot({ path: join(shots, 'embed.png'), fullPage: true });
  // proxies="auto" re-runs with the automatic count.
  const stop = await embed.evaluate(() => new Promise((resolve) => {
    const element = document.querySelector('vqsa-viewer');
    element.viewer.addEventListener('result', (e) => resolve(e.detail.stop_reason), { once: true });
    element.setAttribute('proxies', 'auto');
  }));
  assert.ok(['fitted', 'no_gain'].includes(stop), `stopped: ${stop}`);
  assert.equal(await embed.isChecked('vqsa-viewer [data-option="proxies"] input[type="checkbox"]'), true);
  assert.deepEqual(consoleErrors, []);
  await embed.close();
});

test('<vqsa-viewer>: options as attributes and properties, one run per change, error events, scoped styles', async () => {
  const embed = await openPage('embed.html');
  await waitFor(embed, ['done']);
  const outcome = await embed.evaluate(async () => {
    const element = document.querySelector('vqsa-viewer');
    const events = [];
    for (const type of ['state', 'result', 'error']) element.addEventListener(type, (e) => events.push([type, e.detail]));
    const next = (type) => new Promise((resolve) => element.addEventListener(type, (e) => resolve(e.detail), { once: true }));
    const out = {};
    // Properties reflect to attributes; two changes in one task make one run.
    let result = next('result');
    element.proxies = 6;
    element.maxIterations = 500;
    out.attributes = [element.getAttribute('proxies'), element.getAttribute('max-iterations'), element.rings];
    out.report = await result;
    out.runs = events.filter(([type, detail]) => type === 'state' && detail === 'running').length;
    // An option out of range: an error event of type 'run'.
    let error = next('error');
    element.setAttribute('rings', '0');
    out.runError = await error;
    element.setAttribute('rings', '1');
    await next('result');
    // A boolean attribute: present without a value is true, a word it cannot read an error.
    error = next('error');
    element.setAttribute('smooth', 'flase');
    out.booleanError = await error;
    result = next('result');
    element.setAttribute('smooth', '');
    out.smoothReport = await result;
    // A src that cannot be fetched: type 'load', and nothing runs after it.
    events.length = 0;
    error = next('error');
    element.src = 'examples/missing.off';
    out.loadError = await error;
    await new Promise((resolve) => setTimeout(resolve, 500));
    out.statesAfterFailedLoad = events.filter(([type]) => type === 'state').map(([, state]) => state);
    // The viewer's styles live in its shadow root, not in the page.
    out.pageSheets = [...document.styleSheets].map((s) => s.href).filter(Boolean);
    out.shadowSheets = [...element.shadowRoot.styleSheets].map((s) => s.href.split('/').pop());
    return out;
  });
  assert.deepEqual(outcome.attributes, ['6', '500', 1]);
  assert.equal(outcome.report.proxies.length, 6);
  assert.equal(outcome.report.options['max-iterations'], 500);
  assert.equal(outcome.runs, 1);
  assert.equal(outcome.runError.type, 'run');
  assert.match(outcome.runError.message, /rings/);
  assert.equal(outcome.booleanError.type, 'run');
  assert.match(outcome.booleanError.message, /smooth must be true or false, not "flase"/);
  assert.equal(outcome.smoothReport.options.smooth, true);
  assert.equal(outcome.loadError.type, 'load');
  assert.match(outcome.loadError.message, /missing\.off/);
  assert.deepEqual(outcome.statesAfterFailedLoad, ['loading', 'error']);
  assert.deepEqual(outcome.pageSheets, []);
  assert.deepEqual(outcome.shadowSheets, ['viewer.css']);
  consoleErrors.splice(0, consoleErrors.length, ...consoleErrors.filter((e) => !/missing\.off|404/.test(e)));
  assert.deepEqual(consoleErrors, []);
  await embed.close();
});

test('a dropped CAD mesh runs with the automatic count until a count is chosen', async () => {
  const fresh = await openPage('index.html');
  await waitFor(fresh, ['done']);
  assert.equal(await fresh.getAttribute('.vqsa-viewer', 'data-proxies'), '6');  // the example's surfaces
  await runAndWait(fresh, () => drop(fresh, 'cylinder_capped.off', { url: '/meshes/cylinder_capped.off' }));
  // A capped cylinder is three surfaces: its side and two disks; the status says why it stopped.
  assert.equal(await fresh.getAttribute('.vqsa-viewer', 'data-proxies'), '3');
  assert.equal(await fresh.isChecked('[data-option="proxies"] input[type="checkbox"]'), true);
  assert.match(await fresh.textContent('.vqsa-status'), /^3 proxies · .* · automatic: every region fitted$/);
  await fresh.screenshot({ path: join(shots, 'app-automatic.png') });
  await setProxies(fresh, 2);
  await runAndWait(fresh, () => drop(fresh, 'cylinder_capped.off', { url: '/meshes/cylinder_capped.off' }));
  assert.equal(await fresh.getAttribute('.vqsa-viewer', 'data-proxies'), '2');
  assert.equal(await fresh.isChecked('[data-option="proxies"] input[type="checkbox"]'), false);
  // More than its three surfaces: three regions, and the status says why.
  await setProxies(fresh, 6);
  await runAndWait(fresh, () => fresh.click('button:has-text("Run")'));
  assert.equal(await fresh.getAttribute('.vqsa-viewer', 'data-proxies'), '3');
  assert.match(await fresh.textContent('.vqsa-status'), /^3 proxies \(every surface found before 6\)/);
  // A run the iteration cap ends is unfinished, and says so.
  const cap = fresh.locator('[data-option="maxIterations"] input');
  await cap.fill('2');
  await cap.press('Enter');
  await runAndWait(fresh, () => fresh.click('button:has-text("Run")'));
  assert.match(await fresh.textContent('.vqsa-status'), / · stopped at the 2-iteration cap$/);
  assert.deepEqual(consoleErrors, []);
  await fresh.close();
});

test('the panel is the option schema: the tolerance field is active only while its switch is on', async () => {
  const fresh = await openPage('index.html');
  await waitFor(fresh, ['done']);
  // Every option of the core's schema has its control, under its camelCase name.
  const { options } = await import(pathToFileURL(join(root, 'dist', 'vqsa-schema.js')).href);
  for (const o of options) assert.equal(await fresh.locator(`[data-option="${o.js}"]`).count(), 1, o.js);
  const tolerance = fresh.locator('[data-option="tolerance"] input[type="number"]');
  const on = fresh.locator('[data-option="tolerance"] input[type="checkbox"]');
  assert.equal(await tolerance.isDisabled(), true);
  await on.check();
  assert.equal(await tolerance.isDisabled(), false);
  assert.equal(await tolerance.inputValue(), '0.002');  // the schema's typical value
  await on.uncheck();
  assert.equal(await tolerance.isDisabled(), true);
  await fresh.close();
});

test('arrow keys browse the examples; Enter loads one, leaving the list loads none', async () => {
  const fresh = await openPage('index.html');
  await waitFor(fresh, ['done']);
  const name = () => fresh.textContent('.vqsa-mesh-name');
  const before = await name();
  const examples = fresh.locator('select[aria-label="Examples"]');
  await examples.focus();
  await fresh.keyboard.press('ArrowDown');
  await fresh.keyboard.press('ArrowDown');
  await fresh.waitForTimeout(300);
  assert.equal(await fresh.getAttribute('.vqsa-viewer', 'data-state'), 'done');
  assert.equal(await name(), before);
  await fresh.keyboard.press('Tab');  // leaving drops the choice
  await fresh.waitForTimeout(300);
  assert.equal(await name(), before);
  await examples.focus();
  await fresh.keyboard.press('ArrowDown');  // the list's first example is the one shown
  await fresh.keyboard.press('ArrowDown');
  await fresh.keyboard.press('Enter');
  await waitFor(fresh, ['loading', 'running']);
  await waitFor(fresh, ['done']);
  assert.notEqual(await name(), before);
  assert.deepEqual(consoleErrors, []);
  await fresh.close();
});

test('a file that fails to load leaves the model, status and downloads as they were', async () => {
  const fresh = await openPage('index.html');
  await waitFor(fresh, ['done']);
  const name = await fresh.textContent('.vqsa-mesh-name');
  const status = await fresh.textContent('.vqsa-status');
  await drop(fresh, 'junk.stl', { text: 'not a mesh' });
  await waitFor(fresh, ['error']);
  assert.match(await fresh.textContent('.vqsa-error'), /junk\.stl/);
  assert.equal(await fresh.textContent('.vqsa-mesh-name'), name);
  assert.equal(await fresh.textContent('.vqsa-status'), status);
  assert.equal(await fresh.isEnabled('button:has-text("GLB")'), true);
  assert.equal(await fresh.isEnabled('button:has-text("Run")'), true);
  assert.deepEqual(consoleErrors, []);
  await fresh.close();
});


test('the timeline replays the run: each recorded state, then the result', async () => {
  const page = await openApp();
  const slider = page.locator('.vqsa-timeline input[type="range"]');
  assert.equal(await slider.isVisible(), true);
  const last = Number(await slider.getAttribute('max'));
  assert.ok(last >= 3, `only ${last + 1} states recorded`);
  const result = await canvasDigest(page);
  await slider.fill('0');
  assert.match(await page.textContent('.vqsa-status'), /^replay: .* · 1 proxies/);
  assert.equal(await page.getAttribute('.vqsa-viewer', 'data-frame'), '0');
  await page.waitForTimeout(100);
  assert.notEqual(await canvasDigest(page), result);
  await page.click('button[aria-label="replay the run"]');
  await page.waitForFunction(() => Number(document.querySelector('.vqsa-viewer').dataset.frame) > 0);
  await page.waitForFunction(() => document.querySelector('.vqsa-viewer').dataset.frame === '', null, { timeout: 20000 });
  assert.doesNotMatch(await page.textContent('.vqsa-status'), /replay/);
  await page.close();
});

test('the inspector: keyboard focus, isolate, hide, frame, copyable JSON', async () => {
  const page = await openApp();
  const rows = page.locator('.vqsa-table tr[data-region]');
  const count = await rows.count();
  await rows.first().focus();
  await page.keyboard.press('ArrowDown');
  await page.keyboard.press('Enter');
  assert.match(await page.textContent('.vqsa-detail'), /^region 1:/);
  const before = await canvasDigest(page);
  await page.keyboard.press('i');  // isolate region 1
  const shown = await rows.evaluateAll((r) => r.map((row) => row.querySelector('input').checked));
  assert.deepEqual(shown, Array.from({ length: count }, (_, i) => i === 1));
  await page.waitForTimeout(100);
  assert.notEqual(await canvasDigest(page), before);
  await page.keyboard.press('i');  // again: everything back
  assert.equal((await rows.evaluateAll((r) => r.filter((row) => row.querySelector('input').checked))).length, count);
  await page.keyboard.press('h');
  assert.equal(await rows.nth(1).evaluate((row) => row.classList.contains('vqsa-hidden')), true);
  await page.keyboard.press('f');  // frame it: the camera moves
  await page.waitForTimeout(100);
  assert.ok(await page.isVisible('.vqsa-detail button:has-text("Copy JSON")'));
  await page.close();
});

test('up axis, standard views and the PNG download', async () => {
  const page = await openApp();
  const iso = await canvasDigest(page);
  await page.selectOption('[data-option="up"] select', 'z');
  await page.waitForTimeout(100);
  assert.notEqual(await canvasDigest(page), iso);
  await page.click('.vqsa-views button:has-text("Top")');
  await page.waitForTimeout(100);
  const top = await canvasDigest(page);
  await page.click('.vqsa-views button:has-text("Front")');
  await page.waitForTimeout(100);
  assert.notEqual(await canvasDigest(page), top);
  const [download] = await Promise.all([page.waitForEvent('download'), page.click('[data-testid="download-png"]')]);
  const png = readFileSync(await download.path());
  assert.deepEqual([...png.subarray(0, 8)], [137, 80, 78, 71, 13, 10, 26, 10]);
  assert.ok(png.length > 10000, `a ${png.length}-byte PNG looks blank`);
  await page.close();
});

test('at 390×844 the controls stay reachable and usable', async () => {
  const page = await browser.newPage({ viewport: { width: 390, height: 844 } });
  guardNetwork(page, site.url, offsite);
  await page.goto(`${site.url}/index.html`);
  await waitFor(page, ['done']);
  const box = (selector) => page.locator(selector).first().boundingBox();
  for (const selector of ['button:has-text("Open")', 'button:has-text("Run")', '[data-testid="download-glb"]']) {
    const b = await box(selector);
    assert.ok(b.width >= 30 && b.height >= 20 && b.x >= 0 && b.x + b.width <= 390, `${selector}: ${JSON.stringify(b)}`);
  }
  const canvas = await box('.vqsa-canvas canvas');
  assert.ok(canvas.width >= 380 && canvas.height >= 300, JSON.stringify(canvas));
  const toolbar = await box('.vqsa-toolbar');
  assert.ok(toolbar.height <= 100, `the toolbar takes ${toolbar.height} px`);
  const proxies = page.locator('[data-option="proxies"] input[type="number"]');
  await proxies.scrollIntoViewIfNeeded();
  const field = await proxies.boundingBox();
  assert.ok(field.width >= 80 && field.height >= 20, JSON.stringify(field));
  await page.screenshot({ path: join(shots, 'app-narrow.png'), fullPage: true });
  await page.close();
});

test('a section plane cuts the model along the up axis', async () => {
  const page = await openApp();
  const whole = await canvasDigest(page);
  await page.check('[data-option="section"] input[type="checkbox"]');
  await page.waitForTimeout(100);
  const cut = await canvasDigest(page);
  assert.notEqual(cut, whole);
  await page.locator('[data-option="section"] input[type="range"]').fill('0.2');
  await page.waitForTimeout(100);
  assert.notEqual(await canvasDigest(page), cut);
  await page.uncheck('[data-option="section"] input[type="checkbox"]');
  await page.waitForTimeout(100);
  assert.equal(await canvasDigest(page), whole);
  await page.close();
});

test('edits by clicks and keys: split, merge, retype, undo; the GLB carries the history', async () => {
  const page = await openApp();
  const proxies = () => page.evaluate(() => Number(document.querySelector('.vqsa-viewer').dataset.proxies));
  const edits = () => page.locator('[data-testid="edits"] li:not(.vqsa-none)').allTextContents();
  // Waits for the result of the edit that leaves `count` edits.
  const settled = (count) => page.waitForFunction((k) => {
    const v = document.querySelector('.vqsa-viewer');
    return v.dataset.state === 'done' && v.shadowRoot.querySelectorAll('[data-testid="edits"] li:not(.vqsa-none)').length === k;
  }, count, { timeout: 60000 });
  const rows = page.locator('.vqsa-table tr[data-region]');
  const n = await proxies();

  await rows.nth(0).click();  // pins region 0; S splits it at its worst face
  await page.keyboard.press('s');
  await settled(1);
  assert.equal(await proxies(), n + 1);
  assert.equal(await rows.count(), n + 1);
  assert.deepEqual(await edits(), ['split region 0']);
  assert.match(await page.textContent('.vqsa-detail'), new RegExp(`^region ${n}:`));  // the new region in focus

  await rows.nth(0).click({ modifiers: ['Shift'] });  // merges region 0 into the pinned new one
  await settled(2);
  assert.equal(await proxies(), n);
  assert.deepEqual(await edits(), ['split region 0', `merge region 0 into ${n}`]);

  const pinned = Number((await page.textContent('.vqsa-detail')).match(/^region (\d+):/)[1]);
  await page.selectOption('[data-testid="edit-type"]', 'quadric');
  await settled(3);
  assert.match(await page.textContent('.vqsa-detail'), new RegExp(`^region ${pinned}: .*\\(imposed\\)`));
  assert.match(await rows.nth(pinned).textContent(), /\(imposed\)/);

  await page.click('[data-testid="edit-undo"]');
  await settled(2);
  assert.doesNotMatch(await page.locator('.vqsa-table').textContent(), /imposed/);
  await rows.nth(1).click();
  await page.keyboard.press('Control+z');  // undoes the merge
  await settled(1);
  assert.equal(await proxies(), n + 1);
  assert.deepEqual(await edits(), ['split region 0']);
  assert.equal(await page.isDisabled('[data-testid="edit-redo"]'), false);
  // Shift+S waits for a face; Escape drops the pick and keeps the region pinned.
  await page.keyboard.press('Shift+S');
  assert.equal(await page.isVisible('.vqsa-edit-prompt'), true);
  await page.keyboard.press('Escape');
  assert.equal(await page.isVisible('.vqsa-edit-prompt'), false);
  assert.equal(await page.isDisabled('[data-testid="edit-split"]'), false);

  const [download] = await Promise.all([page.waitForEvent('download'), page.click('[data-testid="download-glb"]')]);
  const bytes = new Uint8Array(readFileSync(await download.path()));
  await validateGlb(bytes, 'edited GLB');
  const gltf = await parseGlb(bytes);
  assert.deepEqual(gltf.scene.userData.edits, [{ op: 'split', region: 0 }]);
  assert.equal(gltf.scene.getObjectByName('input').userData.regions.length, n + 1);
  await page.screenshot({ path: join(shots, 'app-edited.png') });
  await page.close();
});

test('<vqsa-viewer>: edit methods, the edit event, edit errors', async () => {
  const embed = await openPage('embed.html');
  await waitFor(embed, ['done']);
  const outcome = await embed.evaluate(async () => {
    const element = document.querySelector('vqsa-viewer');
    const events = [];
    element.addEventListener('edit', (e) => events.push(e.detail));
    const count = () => element.viewer.result.proxies.length;
    const out = { start: count() };
    out.split = (await element.split(0)).proxies.length;
    out.merged = (await element.merge(0, out.start)).proxies.length;
    out.typed = (await element.setType(0, 'plane')).proxies[0].imposed_type;
    out.locked = (await element.lock(0)).proxies[0].locked;
    const errors = [];
    element.addEventListener('error', (e) => errors.push(e.detail), { once: true });
    out.lockedSplit = await element.split(0);  // null: the error event says why
    out.error = errors[0];
    out.seeded = (await element.addSeed(element.viewer.result.labels.findIndex((l) => l === 1))).proxies.length;
    out.undone = (await element.undo()).edits.length;
    out.redone = (await element.redo()).edits.length;
    out.events = events.map((e) => [e.edits.length, e.history.canUndo, e.history.canRedo]);
    return out;
  });
  const n = outcome.start;
  assert.equal(outcome.split, n + 1);
  assert.equal(outcome.merged, n);
  assert.equal(outcome.typed, 'plane');
  assert.equal(outcome.locked, true);
  assert.equal(outcome.lockedSplit, null);
  assert.equal(outcome.error.type, 'edit');
  assert.match(outcome.error.message, /region 0 is locked/);
  assert.equal(outcome.seeded, n + 1);
  assert.equal(outcome.undone, 4);
  assert.equal(outcome.redone, 5);
  assert.deepEqual(outcome.events, [[1, true, false], [2, true, false], [3, true, false], [4, true, false],
    [5, true, false], [4, true, true], [5, true, false]]);
  await embed.close();
});
