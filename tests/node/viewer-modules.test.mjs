// The viewer's DOM-free modules (dist/ui/, as the site serves them) on every quadric type
// the core can emit: a colour of its own, a name, and parameters that print (a type the
// legend did not know once crashed the type colouring).
import assert from 'node:assert/strict';
import { join } from 'node:path';
import { test } from 'node:test';
import { pathToFileURL } from 'node:url';
import { root } from './support.mjs';

const load = (path) => import(pathToFileURL(join(root, 'dist', path)).href);

test('every type the core can emit has a colour, a name and printable parameters', async () => {
  const { palette } = await load('vqsa-schema.js');
  const { NEUTRAL, css, regionColour, typeColour } = await load('ui/colours.js');
  const { keyParameters, parameterLines, typeName } = await load('ui/format.js');
  const types = Object.keys(palette.types);
  for (const t of ['plane', 'sphere', 'cylinder', 'cone', 'ellipsoid', 'hyperboloid_one_sheet', 'hyperboloid_two_sheets',
    'elliptic_paraboloid', 'hyperbolic_paraboloid', 'elliptic_cylinder', 'hyperbolic_cylinder', 'parabolic_cylinder',
    'elliptic_cone', 'intersecting_planes', 'parallel_planes', 'empty'])
    assert.ok(types.includes(t), `the palette lacks ${t}`);
  assert.equal(new Set(types.map((t) => css(typeColour(t)))).size, types.length, 'two types share a colour');
  for (const type of types) {
    assert.notDeepEqual(typeColour(type), NEUTRAL);
    assert.doesNotMatch(typeName(type), /_/);
    for (const params of [{}, { normal: [0, 0, 1], radius: 2, half_angle: 0.5, semi_axes: [1, 2, 3], center: [0, 0, 0] }]) {
      assert.equal(typeof keyParameters({ type, params }), 'string');
      assert.ok(parameterLines({ type, params }).every((l) => !/undefined|NaN/.test(l)));
    }
  }
  // Region colours: the GLB's palette, repeating after its length.
  assert.deepEqual(regionColour(3), palette.regions[3]);
  assert.deepEqual(regionColour(palette.regions.length + 3), palette.regions[3]);
});
