// Shared helpers of the node tests: paths, the native CLI, GLB parsing with Three.js, the
// app's worker in a thread.
import { execFileSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { Worker } from 'node:worker_threads';
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

// The app's worker (dist/worker.js, from `npm run build`) in a node worker thread
// (worker-thread.mjs), driven by its message protocol.
export function startWorker() {
  const dist = join(root, 'dist');
  const thread = new Worker(join(root, 'tests', 'node', 'worker-thread.mjs'), {
    workerData: { url: pathToFileURL(join(dist, 'worker.js')).href },
    execArgv: ['--no-warnings'],  // dist/ has no package.json saying its .js files are modules
  });
  const waiting = new Map();
  let nextId = 0;
  const worker = {
    onProgress: null,
    request(message) {
      const id = ++nextId;
      return new Promise((resolve) => {
        waiting.set(id, resolve);
        thread.postMessage({ ...message, id });
      });
    },
    cancel: () => thread.postMessage({ type: 'cancel' }),
    terminate: () => thread.terminate(),
  };
  thread.on('message', (m) => (m.type === 'progress' ? worker.onProgress?.(m) : waiting.get(m.id)?.(m)));
  return worker;
}

// Milliseconds from a cancel, sent at the first progress event of each stage, to the
// worker's `cancelled` (null for a stage the run never reported).
export async function cancelLatencies(worker, options, stages = ['lloyd', 'smooth', 'refit', 'project', 'measure']) {
  const latencies = {};
  for (const stage of stages) {
    let sent = null;
    worker.onProgress = (p) => {
      if (sent === null && p.stage === stage) {
        sent = performance.now();
        worker.cancel();
      }
    };
    const reply = await worker.request({ type: 'run', options });
    assert.equal(reply.type, sent === null ? 'result' : 'cancelled', `${stage}: ${reply.type} ${reply.message ?? ''}`);
    latencies[stage] = sent === null ? null : performance.now() - sent;
  }
  worker.onProgress = null;
  return latencies;
}
