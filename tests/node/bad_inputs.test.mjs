// The bad-input corpus through the WASM API: the same outcomes as natively, and a
// session that stays usable after every failure; options out of range are refused.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { test } from 'node:test';
import { loadVqsa } from '../../wasm/node/load.mjs';
import { root, validateGlb } from './support.mjs';

const corpus = join(root, 'tests', 'bad_inputs');
const expected = JSON.parse(readFileSync(join(corpus, 'expected.json'), 'utf8'));
const vqsa = await loadVqsa();

// Runs an approximation to the end; returns its proxies.
function approximate(session, options) {
  session.start(options);
  while (session.stepFor(100)) {}
  return JSON.parse(session.proxies());
}

const finite = (value) => (typeof value === 'number' ? Number.isFinite(value)
  : value && typeof value === 'object' ? Object.values(value).every(finite) : true);

test('every corpus file fails with its message or runs to finite results', async () => {
  const session = new vqsa.Session();
  for (const [name, want] of Object.entries(expected)) {
    const bytes = readFileSync(join(corpus, name));
    if (want.error !== undefined) {
      assert.throws(() => session.load(bytes, name), (e) => e instanceof Error && e.message.startsWith(`${name}: `) &&
        e.message.toLowerCase().includes(want.error), name);
      continue;
    }
    const info = session.load(bytes, name);
    assert.equal(info.facesUsed, want.faces_used, name);
    session.start({ proxies: want.request });
    while (session.stepFor(100)) {}
    const report = JSON.parse(session.report());
    assert.equal(report.proxies.length, want.proxies, name);
    assert.ok(finite(report), `${name}: a non-finite number in the report`);
    await validateGlb(session.glb('region').slice(), name);
  }
  session.delete();
});

test('options out of range are refused with a message', () => {
  const session = new vqsa.Session();
  session.loadExample('capsule');
  assert.throws(() => session.start({ proxies: 0 }), /proxies must be an integer between 1 and 1000000 or 'auto', not 0/);
  assert.throws(() => session.start({ tolerance: -1 }), /tolerance/);
  assert.throws(() => session.start({ proxies: 1e6 }), /exceeds the number of faces/);
  assert.throws(() => session.start({ proxies: 1e7 }), /between 1 and 1000000/);
  assert.throws(() => session.start({ proxies: 2.5 }), /integer/);
  assert.throws(() => session.start({ proxies: 'three' }), /proxies must be an integer/);
  assert.throws(() => session.start({ smooth: 'maybe' }), /smooth must be true or false/);
  assert.throws(() => session.start({ proxies: 3, rings: 0 }), /rings/);
  assert.equal(approximate(session, { proxies: 3 }).length, 3);
  session.delete();
});

test('a mesh too large for the 4 GB of wasm32 fails with a clear message, and the session goes on', () => {
  const session = new vqsa.Session();
  assert.throws(() => {
    session.loadExample('turned_part:20000000');
    session.start({ proxies: 50 });
    while (session.stepFor(1000)) {}
  }, /out of memory: the mesh is too large for this browser/);
  session.loadExample('capsule');
  assert.equal(approximate(session, { proxies: 3 }).length, 3);
  session.delete();
});

test('100 runs in one instance do not grow its memory', () => {
  const session = new vqsa.Session();
  const run = () => {
    session.loadExample('capsule');
    approximate(session, { proxies: 4 });
    session.glb('region');
    session.labels();
  };
  for (let i = 0; i < 5; ++i) run();  // the allocator settles
  const before = vqsa.HEAP8.buffer.byteLength;
  for (let i = 0; i < 100; ++i) run();
  assert.equal(vqsa.HEAP8.buffer.byteLength, before, 'the WASM heap grew over 100 runs');
  session.delete();
});
