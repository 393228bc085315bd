// The WASM build under node: same labels and coefficients as the native build, C++ errors
// as JS Errors, and a module that stays usable after them.
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { test } from 'node:test';
import { loadVqsa } from '../../wasm/node/load.mjs';
import { meshes, readGlb, root, runNativeCli, triangleRegions, validateGlb } from './support.mjs';

const work = mkdtempSync(join(tmpdir(), 'vqsa-wasm-'));
test.after(() => rmSync(work, { recursive: true, force: true }));
const vqsa = await loadVqsa();

function wasmRun(session, options) {
  session.start(options);
  while (session.stepFor(100)) {}
  return JSON.parse(session.report());
}

function assertSameResult(wasm, native) {
  assert.deepEqual(wasm.labels, native.labels);
  assert.deepEqual(wasm.labels_lloyd, native.labels_lloyd);
  assert.equal(wasm.proxies.length, native.proxies.length);
  wasm.proxies.forEach((p, i) => {
    assert.equal(p.type, native.proxies[i].type);
    p.coefficients.forEach((c, k) => {
      const n = native.proxies[i].coefficients[k];
      assert.ok(Math.abs(c - n) <= 1e-9 * Math.max(1e-3, Math.abs(n)), `proxy ${i} C${k}: ${c} vs ${n}`);
    });
  });
  // Relative to the size; exact fits (a capsule) leave rounding, where the two libms differ.
  assert.ok(Math.abs(wasm.metrics.rms - native.metrics.rms) <= 1e-9 * native.metrics.rms + 1e-14,
    `RMS ${wasm.metrics.rms} vs ${native.metrics.rms}`);
}

// turned_part:20000 differed while the examples used libm's sin and cos (examples/portable_math.h).
// Automatic: the axle's and casting's finishes merge pieces of surfaces in batches.
for (const [input, proxies] of [['fandisk.off', 22], ['example:capsule', 3], ['example:turned_part:20000', 11],
  ['example:axle:20000', 'auto'], ['casting.off', 'auto']]) {
  test(`${input}: WASM gives the native build's labels and coefficients`, () => {
    const json = join(work, 'native.json');
    const path = input.startsWith('example:') ? input : join(meshes, input);
    runNativeCli([path, '--proxies', String(proxies), '--seed', '7', '--quiet', '--report', json]);
    const native = JSON.parse(readFileSync(json, 'utf8'));

    const session = new vqsa.Session();
    if (input.startsWith('example:')) session.loadExample(input.slice(8));
    else session.load(readFileSync(path), input);
    const wasm = wasmRun(session, { proxies, seed: 7 });
    session.delete();
    assertSameResult(wasm, native);
  });
}

test('edits: WASM gives the native build\'s labels; undo and redo step through the results', () => {
  const edits = [{ op: 'merge', regions: [0, 4] }, { op: 'split', region: 0 }, { op: 'lock', region: 2 },
    { op: 'set_type', region: 3, type: 'quadric' }, { op: 'add_seed', face: 100 }];
  const file = join(work, 'edits.json'), plain = join(work, 'plain.json'), json = join(work, 'edited.json');
  writeFileSync(file, JSON.stringify(edits));
  runNativeCli(['example:box_boss_hole', '--quiet', '--report', plain]);
  runNativeCli(['example:box_boss_hole', '--quiet', '--edits', file, '--report', json]);
  const native = JSON.parse(readFileSync(json, 'utf8'));
  assert.deepEqual(native.edits, edits);
  assert.equal(native.proxies[2].locked, true);
  assert.equal(native.proxies[3].imposed_type, 'quadric');

  const session = new vqsa.Session();
  session.loadExample('box_boss_hole');
  wasmRun(session, {});
  for (const e of edits) {
    session.edit(JSON.stringify(e));
    while (session.stepFor(100)) {}
  }
  const wasm = JSON.parse(session.report());
  assertSameResult(wasm, native);
  assert.deepEqual(wasm.edits, edits);
  assert.throws(() => session.edit(JSON.stringify({ op: 'split', region: 2 })), /region 2 is locked/);
  assert.throws(() => session.edit('{"op": "merge"}'), /merge needs "regions"/);
  for (let i = 0; i < edits.length; ++i) assert.equal(session.undo(), true);
  assert.equal(session.undo(), false);
  assert.deepEqual(session.history(), { canUndo: false, canRedo: true });
  assert.deepEqual(JSON.parse(session.report()).labels, JSON.parse(readFileSync(plain, 'utf8')).labels);
  for (let i = 0; i < edits.length; ++i) assert.equal(session.redo(), true);
  assert.deepEqual(JSON.parse(session.report()).labels, native.labels);
  session.delete();
});

test('bad input rejects with the C++ message and the session stays usable', () => {
  const session = new vqsa.Session();
  const cases = [
    [new Uint8Array([0x7f, 0x45, 0x4c, 0x46, 1, 2, 3, 0, 0, 9]), 'garbage.off', /garbage\.off: line 1: not an OFF file/],
    [new Uint8Array(0), 'empty.stl', /empty\.stl: the file is empty/],
    [new TextEncoder().encode('1 2 3'), 'mesh.xyz', /mesh\.xyz: unknown format '\.xyz'/],
    [new TextEncoder().encode('OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n'), 'nan.off', /not a finite number/],
  ];
  for (const [bytes, name, message] of cases) {
    assert.throws(() => session.load(bytes, name), (e) => e instanceof Error && message.test(e.message));
    const mesh = session.loadExample('closed_cylinder');  // usable right after
    assert.equal(mesh.faces > 0, true);
  }
  assert.throws(() => session.start({ proxies: -1 }), /proxies/);
  assert.throws(() => session.start({ proxies: 3, bogus: 1 }), /unknown option 'bogus'/);
  assert.throws(() => new vqsa.Session().stepFor(10), /start an approximation first/);
  const result = wasmRun(session, { proxies: 3 });
  assert.equal(result.proxies.length, 3);
  assert.equal(result.proxies.filter((p) => p.type === 'plane').length, 2);
  session.delete();
});

test('npm run cli:wasm writes what npm run cli writes', async () => {
  const outputs = (dir) => ({ report: join(dir, 'r.json'), labels: join(dir, 'l.txt'), projected: join(dir, 'p.off'), glb: join(dir, 'o.glb') });
  const n = outputs(mkdtempSync(join(work, 'n'))), w = outputs(mkdtempSync(join(work, 'w')));
  const args = (o) => [join(meshes, 'csg.off'), '--proxies', '10', '--quiet', '--report', o.report, '--labels', o.labels,
    '--projected', o.projected, '-o', o.glb];
  runNativeCli(args(n));
  execFileSync(process.execPath, [join(root, 'build', 'wasm', 'wasm', 'vqsa-cli.js'), ...args(w)], { stdio: 'ignore' });
  assert.equal(readFileSync(w.labels, 'utf8'), readFileSync(n.labels, 'utf8'));
  assertSameResult(JSON.parse(readFileSync(w.report, 'utf8')), JSON.parse(readFileSync(n.report, 'utf8')));
  const tokens = (f) => readFileSync(f, 'utf8').split(/\s+/).filter(Boolean);
  const pn = tokens(n.projected), pw = tokens(w.projected);
  assert.equal(pw.length, pn.length);
  pw.forEach((t, i) => {
    const a = Number(t), b = Number(pn[i]);
    if (Number.isNaN(b)) assert.equal(t, pn[i]);
    else assert.ok(Math.abs(a - b) <= 1e-9 * Math.max(1, Math.abs(b)), `value ${i}: ${t} vs ${pn[i]}`);
  });
  // The GLB validates and carries the same regions as the native one.
  await validateGlb(new Uint8Array(readFileSync(w.glb)), 'cli:wasm GLB');
  const regions = async (f) => triangleRegions((await readGlb(f)).scene.getObjectByName('input'));
  assert.deepEqual(await regions(w.glb), await regions(n.glb));
});
