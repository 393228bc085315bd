// The module worker that owns the WASM instance. Protocol (every request carries an id):
//   in:  {type:'load', id, bytes, name} | {type:'example', id, name} | {type:'run', id, options}
//        | {type:'edit', id, edit} (docs/EDITS.md) | {type:'undo', id} | {type:'redo', id}
//        | {type:'glb', id, colours: 'region' | 'type'} (of the last result) | {type:'cancel'}
//   out: {type:'loaded', id, info, positions, triangles, sourceFaces}
//        {type:'progress', id, stage, phase, proxies, iteration, rms, settledProxies, settledRms,
//          fraction, labels}
//          (each new stage and operation, else ≤ 25 per second)
//        {type:'result', id, ..., history: {canUndo, canRedo}}
//          (after a run, an edit, an undo or a redo)  {type:'glb', id, glb}
//        {type:'cancelled', id}  {type:'error', id, message, fatal}
import createVqsaModule from './vqsa.mjs';

const PROGRESS_INTERVAL_MS = 40;
const SLICE_MS = 16;

const ready = createVqsaModule();
let session = null;
let cancelRequested = false;

// Lets queued messages (a cancel) in between slices of work, without setTimeout's clamping.
const channel = new MessageChannel();
const pending = [];
channel.port1.onmessage = () => pending.shift()?.();
const yieldToEvents = () => new Promise((resolve) => { pending.push(resolve); channel.port2.postMessage(0); });

function post(message, transfer = []) {
  self.postMessage(message, transfer);
}

function loaded(id, info) {
  const positions = session.positions(), triangles = session.triangles(), sourceFaces = session.sourceFaces();
  post({ type: 'loaded', id, info, positions, triangles, sourceFaces }, [positions.buffer, triangles.buffer, sourceFaces.buffer]);
}

function progress(id) {
  const p = session.progress();
  const labels = session.faceLabels();
  post({ type: 'progress', id, ...p, labels }, [labels.buffer]);
  return p;
}

// Steps the run or edit the session has started to its end, then posts the result.
async function drive(id) {
  cancelRequested = false;
  let lastPost = 0, lastStage = '', lastOperation = '';
  for (let more = true; more;) {
    more = session.stepFor(SLICE_MS);
    const p = session.progress();
    const now = performance.now();
    // A new stage and every operation (insert, split, merge, teleport) show: a slice ends
    // right after one, and on a small mesh every slice does, so the plot gets each count the
    // run passes through. Lloyd iterations, an edit's steps and progress within a stage are
    // throttled.
    const operation = p.stage === 'lloyd' && p.phase !== 'lloyd' ? `${p.phase} ${p.proxies} ${p.iteration}` : '';
    if (more && ((operation && operation !== lastOperation) || p.stage !== lastStage || now - lastPost >= PROGRESS_INTERVAL_MS)) {
      progress(id);
      lastPost = now;
    }
    lastStage = p.stage;
    lastOperation = operation;
    await yieldToEvents();
    if (cancelRequested && more) {
      session.cancel();
      post({ type: 'cancelled', id });
      return;
    }
  }
  postResult(id);
}

function postResult(id) {
  const faceLabels = session.faceLabels(), lloydFaceLabels = session.lloydFaceLabels();
  // No GLB here: it is built when asked for (a download), not after every run (on 1.5M faces
  // it is 67 MB and 1.8 s).
  const projected = session.projected(), vertexErrors = session.vertexErrors();
  post({
    type: 'result', id,
    progress: session.progress(),
    report: session.report(),
    proxies: JSON.parse(session.proxies()),
    history: session.history(),
    faceLabels, lloydFaceLabels, projected, vertexErrors,
  }, [faceLabels.buffer, lloydFaceLabels.buffer, projected.buffer, vertexErrors.buffer]);
}

// Requests run one after another (a load arriving during a run waits for it to end), but
// a cancel acts at once: the running loop sees the flag at its next slice.
let queue = Promise.resolve();
self.onmessage = ({ data }) => {
  if (data.type === 'cancel') {
    cancelRequested = true;
    return;
  }
  queue = queue.then(() => handle(data));
};

async function handle(data) {
  try {
    const vqsa = await ready;
    session ??= new vqsa.Session();
    if (data.type === 'load') loaded(data.id, session.load(new Uint8Array(data.bytes), data.name));
    else if (data.type === 'example') loaded(data.id, session.loadExample(data.name));
    else if (data.type === 'run') {
      session.start(data.options ?? {});
      await drive(data.id);
    } else if (data.type === 'edit') {
      session.edit(JSON.stringify(data.edit ?? {}));
      await drive(data.id);
    } else if (data.type === 'undo' || data.type === 'redo') {
      if (!session[data.type]()) throw new Error(`nothing to ${data.type}`);
      postResult(data.id);
    }
    else if (data.type === 'glb') {
      const glb = session.glb(String(data.colours ?? 'region'));
      post({ type: 'glb', id: data.id, glb }, [glb.buffer]);
    }
    else throw new Error(`unknown request '${data.type}'`);
  } catch (e) {
    // A RuntimeError (a trap, memory exhausted mid-way) leaves the instance unusable.
    const fatal = e instanceof WebAssembly.RuntimeError || !(e instanceof Error);
    const message = e instanceof WebAssembly.RuntimeError ? `the computation failed (${e.message}); the engine restarts`
      : e instanceof Error ? e.message : String(e);
    post({ type: 'error', id: data.id, message, fatal });
  }
}
