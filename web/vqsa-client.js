// A promise-based client for the vqsa worker. The page never blocks: meshes are parsed
// and approximated in a module worker that owns the WASM instance.
//
//   const client = new VqsaClient();
//   const mesh = await client.load(file);               // File, Blob, ArrayBuffer or Uint8Array (+ name)
//   const result = await client.run({ proxies: 20 }, { onProgress: (p) => draw(p.labels) });
//   client.cancel();                                     // the pending run() rejects with an AbortError
//   const edited = await client.edit({ op: 'split', region: 3 });  // docs/EDITS.md; undo(), redo()
//
// load() resolves to {info, positions: Float32Array, triangles: Uint32Array, sourceFaces};
// progress events carry {stage, phase, proxies, iteration, rms, settledProxies, settledRms,
// fraction, labels: Int32Array per triangle}; run() resolves to {report (JSON text), proxies, faceLabels, lloydFaceLabels,
// projected, vertexErrors, progress, history: {canUndo, canRedo}}, and so do
// edit(), undo() and redo(). Options: the option schema's camelCase
// names (vqsa-schema.js, as the CLI's flags). Errors carry `fatal` when the engine itself
// failed (it restarts).
// `fatal`: the engine itself failed (and restarts), not the request.
function engineError(message, fatal) {
  return Object.assign(new Error(message), { fatal });
}

export class VqsaClient {
  #workerUrl;
  #worker = null;
  #requests = new Map();
  #nextId = 1;

  constructor({ workerUrl = new URL('./worker.js', import.meta.url) } = {}) {
    this.#workerUrl = workerUrl;
    this.#start();
  }

  async load(source, name = source?.name) {
    if (!name) throw new Error('load() needs a file name (its extension picks the format)');
    const bytes = source instanceof Blob ? await source.arrayBuffer()
      : source instanceof ArrayBuffer ? source.slice(0) : new Uint8Array(source).slice().buffer;
    return this.#request({ type: 'load', name, bytes }, [bytes]);
  }

  loadExample(name) {
    return this.#request({ type: 'example', name });
  }

  run(options = {}, { onProgress } = {}) {
    return this.#request({ type: 'run', options }, [], onProgress);
  }

  // Edits the last result (an object as docs/EDITS.md describes) and resolves to the new one.
  edit(edit, { onProgress } = {}) {
    return this.#request({ type: 'edit', edit }, [], onProgress);
  }

  undo() {
    return this.#request({ type: 'undo' });
  }

  redo() {
    return this.#request({ type: 'redo' });
  }

  // The last result's GLB, its regions coloured each its own ('region') or by quadric type
  // ('type'); resolves to a Uint8Array.
  async glb(colours = 'region') {
    return (await this.#request({ type: 'glb', colours })).glb;
  }

  cancel() {
    this.#worker?.postMessage({ type: 'cancel' });
  }

  terminate() {
    this.#worker?.terminate();
    this.#worker = null;
    this.#failAll(engineError('the client was terminated', true));
  }

  #start() {
    this.#worker = new Worker(this.#workerUrl, { type: 'module' });
    this.#worker.onmessage = ({ data }) => this.#receive(data);
    this.#worker.onerror = (event) => {
      event.preventDefault?.();
      this.#restart(engineError(`the engine could not start: ${event.message ?? 'worker error'}`, true));
    };
  }

  #restart(error) {
    this.#worker?.terminate();
    this.#failAll(error);
    this.#start();
  }

  #failAll(error) {
    for (const { reject } of this.#requests.values()) reject(error);
    this.#requests.clear();
  }

  #request(message, transfer = [], onProgress = null) {
    const id = this.#nextId++;
    return new Promise((resolve, reject) => {
      this.#requests.set(id, { resolve, reject, onProgress });
      this.#worker.postMessage({ ...message, id }, transfer);
    });
  }

  #receive(data) {
    const request = this.#requests.get(data.id);
    if (!request) return;
    switch (data.type) {
      case 'progress':
        request.onProgress?.(data);
        return;
      case 'loaded':
      case 'result':
      case 'glb':
        this.#requests.delete(data.id);
        request.resolve(data);
        return;
      case 'cancelled': {
        this.#requests.delete(data.id);
        const error = new Error('cancelled');
        error.name = 'AbortError';
        request.reject(error);
        return;
      }
      case 'error': {
        this.#requests.delete(data.id);
        const error = engineError(data.message, data.fatal);
        if (data.fatal) this.#restart(error);
        request.reject(error);
      }
    }
  }
}
