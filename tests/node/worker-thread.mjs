// Runs the app's web worker (dist/worker.js) in a node worker thread, so tests and the
// benchmark can time it without a browser: `self` stands for the worker global.
import { readFile } from 'node:fs/promises';
import { createRequire } from 'node:module';
import { dirname } from 'node:path';
import { fileURLToPath } from 'node:url';
import { parentPort, workerData } from 'node:worker_threads';

// What the module's node code path expects (as wasm/node/load.mjs gives it).
globalThis.require ??= createRequire(import.meta.url);
globalThis.__dirname ??= dirname(fileURLToPath(workerData.url));

// Node's fetch has no file: scheme; the module fetches its .wasm next to itself.
const networkFetch = globalThis.fetch;
globalThis.fetch = async (url, init) => {
  const href = String(url);
  if (!href.startsWith('file:')) return networkFetch(url, init);
  return new Response(await readFile(new URL(href)), { headers: { 'content-type': 'application/wasm' } });
};
// Node delivers a port's queued messages before another port's, so a worker yielding
// through its own MessageChannel would never see the parent's (a cancel): in a thread, a
// yield is a setImmediate, which lets them in as a browser's task queue does.
globalThis.MessageChannel = class {
  constructor() {
    this.port1 = { onmessage: null };
    this.port2 = { postMessage: (data) => setImmediate(() => this.port1.onmessage?.({ data })) };
  }
};
globalThis.self = {
  postMessage: (message, transfer) => parentPort.postMessage(message, transfer),
  set onmessage(handler) { parentPort.on('message', (data) => handler({ data })); },
};
await import(workerData.url);
