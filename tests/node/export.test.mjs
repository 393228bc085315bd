// GLB export: the Khronos validator on every GLB the tests write, and a round trip
// through Three.js's GLTFLoader against the CLI's own report.
import assert from 'node:assert/strict';
import { mkdtempSync, readdirSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { test } from 'node:test';
import { pathToFileURL } from 'node:url';
import { meshes, nativeBuild, readGlb, root, runNativeCli, triangleRegions, validateGlb } from './support.mjs';

const work = mkdtempSync(join(tmpdir(), 'vqsa-export-'));
test.after(() => rmSync(work, { recursive: true, force: true }));

const validate = (path) => validateGlb(new Uint8Array(readFileSync(path)), path);

test('every GLB written by the C++ tests passes the Khronos validator', async () => {
  const dir = join(nativeBuild, 'test-output');
  const files = readdirSync(dir).filter((f) => f.endsWith('.glb'));
  assert.ok(files.length >= 4, `expected the C++ export tests' GLBs in ${dir}`);
  for (const f of files) await validate(join(dir, f));
});

for (const [file, proxies] of [['fandisk.off', 22], ['csg.off', 10]]) {
  test(`${file}: CLI GLB validates and reads back in Three.js like the report, in the app's colours`, async () => {
    const glb = join(work, `${file}.glb`), json = join(work, `${file}.json`);
    runNativeCli([join(meshes, file), '--proxies', String(proxies), '--quiet', '-o', glb, '--report', json]);
    await validate(glb);
    const report = JSON.parse(readFileSync(json, 'utf8'));
    const gltf = await readGlb(glb);

    const run = gltf.scene.userData;
    assert.equal(run.generator, 'vqsa');
    assert.equal(run.stop_reason, report.stop_reason);
    assert.deepEqual(run.metrics, report.metrics);

    // The default scene shows one surface; the projected mesh is the second scene.
    const input = gltf.scene.getObjectByName('input');
    assert.equal(gltf.scene.getObjectByName('projected'), undefined);
    const projected = gltf.scenes[1]?.getObjectByName('projected');
    assert.ok(input && projected);
    const regions = input.userData.regions;
    assert.equal(regions.length, report.proxies.length);
    regions.forEach((r, i) => {
      assert.equal(r.feature_id, i);
      assert.equal(r.type, report.proxies[i].type);
      assert.deepEqual(r.coefficients, report.proxies[i].coefficients);
    });

    // Triangles are the input's faces in order, less the dropped ones.
    const dropped = new Set(run.dropped_faces);
    const kept = report.labels.filter((_, f) => !dropped.has(f));
    assert.deepEqual(triangleRegions(input), kept);
    assert.deepEqual(triangleRegions(projected), kept);

    // One palette: each vertex has its region's colour in the app (dist/vqsa-schema.js),
    // and the legend names every type.
    const { palette } = await import(pathToFileURL(join(root, 'dist', 'vqsa-schema.js')).href);
    const colours = input.geometry.getAttribute('color'), ids = input.geometry.getAttribute('_feature_id_0');
    for (let v = 0; v < colours.count; v += 7) {
      const expected = palette.regions[ids.getX(v) % palette.regions.length];
      [colours.getX(v), colours.getY(v), colours.getZ(v)].forEach((c, k) => assert.ok(Math.abs(c - expected[k]) < 1e-6));
    }
    assert.deepEqual(run.legend, palette.types);
    assert.ok('empty' in run.legend && 'parallel_planes' in run.legend);
  });
}

test('--glb-colours type paints each region in its type\'s legend colour; a bad word is a usage error', async () => {
  const glb = join(work, 'types.glb');
  runNativeCli([join(meshes, 'csg.off'), '--proxies', '10', '--quiet', '-o', glb, '--glb-colours', 'type']);
  await validate(glb);
  const gltf = await readGlb(glb);
  const input = gltf.scene.getObjectByName('input'), regions = input.userData.regions;
  const colours = input.geometry.getAttribute('color'), ids = input.geometry.getAttribute('_feature_id_0');
  for (let v = 0; v < colours.count; v += 5) {
    const expected = gltf.scene.userData.legend[regions[ids.getX(v)].type];
    [colours.getX(v), colours.getY(v), colours.getZ(v)].forEach((c, k) => assert.ok(Math.abs(c - expected[k]) < 1e-6));
  }
  assert.throws(() => runNativeCli([join(meshes, 'csg.off'), '--quiet', '-o', glb, '--glb-colours', 'pink']), /region.*type/s);
});
