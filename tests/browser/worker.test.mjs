// The worker and its client in headless Chromium: progress with a growing proxy count,
// a result, and a cancel mid-run followed by a run that works.
import assert from 'node:assert/strict';
import { after, before, test } from 'node:test';
import { guardNetwork, launchBrowser, startSite } from './support.mjs';

let site, browser, page;
const offsite = [];
before(async () => {
  site = await startSite();
  browser = await launchBrowser();
  page = await browser.newPage();
  guardNetwork(page, site.url, offsite);
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  await page.goto(`${site.url}/test/worker-page.html`);
  await page.waitForFunction(() => window.ready);
  assert.deepEqual(errors, []);
});
after(async () => {
  await browser?.close();
  site?.server.close();
  assert.deepEqual(offsite, [], 'requests left localhost');
});

test('the worker runs fandisk with growing progress and a result', async () => {
  const outcome = await page.evaluate(async () => {
    const client = new window.VqsaClient();
    const bytes = await (await fetch('/meshes/fandisk.off')).arrayBuffer();
    const mesh = await client.load(bytes, 'fandisk.off');
    const counts = [];
    let labelsOk = true;
    const result = await client.run({ proxies: 22 }, {
      onProgress: (p) => {
        counts.push(p.proxies);
        labelsOk &&= p.labels instanceof Int32Array && p.labels.length === mesh.triangles.length / 3;
      },
    });
    // The GLB is built when asked for, from the result the worker keeps.
    const glb = await client.glb();
    client.terminate();
    return { counts, labelsOk, faces: mesh.info.faces, proxies: result.proxies.length, glbInResult: 'glb' in result,
      glbMagic: new TextDecoder().decode(glb.subarray(0, 4)), glb: glb.length, report: JSON.parse(result.report) };
  });
  assert.equal(outcome.faces, 12946);
  assert.ok(outcome.counts.length >= 5, `only ${outcome.counts.length} progress events`);
  // Validity splits may overshoot the target for a while; merges bring the count back.
  assert.ok(outcome.counts.at(-1) > outcome.counts[0], 'the proxy count grows');
  assert.ok(outcome.labelsOk);
  assert.equal(outcome.proxies, 22);
  assert.equal(outcome.report.stop_reason, 'proxies');
  assert.equal(outcome.glbInResult, false);
  assert.equal(outcome.glbMagic, 'glTF');
  assert.ok(outcome.glb > 1000);
});

test('cancelling mid-run, then running again, works', async () => {
  const outcome = await page.evaluate(async () => {
    const client = new window.VqsaClient();
    await client.loadExample('turned_part');
    let events = 0;
    const first = client.run({ proxies: 60 }, { onProgress: () => { if (++events === 3) client.cancel(); } });
    const cancelled = await first.then(() => 'finished', (e) => e.name);
    const again = await client.run({ proxies: 6 });
    const bad = await client.load(new Uint8Array([1, 2, 3]), 'junk.stl').then(() => 'loaded', (e) => e.message);
    const afterBad = await client.loadExample('capsule').then((m) => m.info.faces);
    client.terminate();
    return { cancelled, events, proxies: again.proxies.length, bad, afterBad };
  });
  assert.equal(outcome.cancelled, 'AbortError');
  assert.ok(outcome.events >= 3);
  assert.equal(outcome.proxies, 6);
  assert.match(outcome.bad, /junk\.stl: too short for a binary STL/);
  assert.ok(outcome.afterBad > 0);
});

test('a mesh beyond the browser\'s memory fails with a clear message, and the next run works', async () => {
  const outcome = await page.evaluate(async () => {
    const client = new window.VqsaClient();
    // Reading it fits; its model (adjacency, moments) or the run does not.
    const failure = await client.loadExample('turned_part:20000000').then(() => client.run({ proxies: 50 }))
      .then(() => 'finished', (e) => e.message);
    await client.loadExample('capsule');
    const next = await client.run({ proxies: 3 });
    client.terminate();
    return { failure, proxies: next.proxies.length };
  });
  assert.match(outcome.failure, /out of memory: the mesh is too large for this browser/);
  assert.equal(outcome.proxies, 3);
});

test('a cancel is acknowledged within 100 ms in every stage of a 100K-face run', async (t) => {
  const latencies = await page.evaluate(async () => {
    const client = new window.VqsaClient();
    await client.loadExample('flange:100000');
    const out = {};
    // A busy machine can delay one message: a stage gets two more tries (a stage stepped in
    // too large pieces fails all three).
    for (const stage of ['lloyd', 'smooth', 'refit', 'project', 'measure']) {
      for (let attempt = 0; attempt < 3 && !(out[stage]?.ms <= 100); ++attempt) {
        let sent = null;
        const run = client.run({ proxies: 7 }, {
          onProgress: (p) => {
            if (sent === null && p.stage === stage) {
              sent = performance.now();
              client.cancel();
            }
          },
        });
        const outcome = await run.then(() => 'finished', (e) => e.name);
        const ms = sent === null ? null : performance.now() - sent;
        if (!out[stage] || (ms !== null && ms < (out[stage].ms ?? Infinity))) out[stage] = { outcome, ms };
      }
    }
    client.terminate();
    return out;
  });
  t.diagnostic(`cancel latency in Chromium (ms): ${Object.entries(latencies).map(([s, l]) => `${s} ${l.ms?.toFixed(0)}`).join(', ')}`);
  for (const [stage, { outcome, ms }] of Object.entries(latencies)) {
    assert.equal(outcome, 'AbortError', `${stage}: ${outcome}`);
    assert.ok(ms <= 100, `${stage}: cancel took ${ms?.toFixed(0)} ms`);
  }
});
