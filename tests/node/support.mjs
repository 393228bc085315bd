// Shared helpers of the node tests: paths, the native CLI, GLB parsing with Three.js.
import { execFileSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import assert from 'node:assert/strict';
import validator from 'gltf-validator';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';

export const root = join(dirname(fileURLToPath(import.meta.url)), '..', '..');
export const meshes = join(root, '..', 'shared', 'meshes');
export const nativeBuild = join(root, 'build', 'native');

export function runNativeCli(args) {
  return execFileSync(join(nativeBuild, 'wasm', 'vqsa'), args, { encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] });
}

export function parseGlb(bytes) {
  const buffer = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
  return new Promise((resolve, reject) => new GLTFLoader().parse(buffer, '', resolve, reject));
}

export function readGlb(path) {
  return parseGlb(new Uint8Array(readFileSync(path)));
}

// Region of every triangle of a Three.js mesh, through its _FEATURE_ID_0 attribute.
export function triangleRegions(mesh) {
  const ids = mesh.geometry.getAttribute('_feature_id_0');
  const index = mesh.geometry.index;
  const regions = [];
  for (let t = 0; t < index.count / 3; ++t) regions.push(ids.getX(index.getX(3 * t)));
  return regions;
}

// The Khronos validator finds no error in the GLB's bytes.
export async function validateGlb(bytes, what) {
  const report = await validator.validateBytes(bytes, { maxIssues: 100 });
  const errors = report.issues.messages.filter((m) => m.severity === 0);
  assert.equal(report.issues.numErrors, 0, `${what}: ${JSON.stringify(errors, null, 1)}`);
}
