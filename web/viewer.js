// The vqsa viewer: load a mesh, watch proxies being inserted and boundaries smoothed,
// inspect the quadrics, download the GLB. Everything runs in the page's own worker;
// meshes never leave the browser.
//
//   import { createViewer } from './viewer.js';
//   const viewer = createViewer(element, { example: 'turned_part', proxies: 20 });
//   viewer.addEventListener('result', (e) => console.log(e.detail));
//   await viewer.load(file);              // File/Blob/URL string/ArrayBuffer (+ name); null if it failed
//   await viewer.run({ proxies: 12 });    // any option of the schema (camelCase), proxies may be 'auto'
//
// The viewer lives in the element's shadow root (its styles stay inside). The element
// carries data-state (idle | loading | running | done | error) and data-proxies; events:
// state, loaded, progress, result, edit (detail: {edits, history: {canUndo, canRedo}}), error (detail:
// {type: 'load' | 'run' | 'edit' | 'engine', message}).
//
// Edits of the result (docs/EDITS.md; faces in the file's order, as the report's labels):
//   await viewer.split(3); await viewer.merge(2, 5); await viewer.setType(1, 'cone');
//   await viewer.lock(4); await viewer.addSeed(812); await viewer.undo(); await viewer.redo();
import { NEUTRAL, css, heat, regionColour, typeColour } from './ui/colours.js';
import { createControls } from './ui/controls.js';
import { element } from './ui/dom.js';
import { attachDropZone } from './ui/drop-zone.js';
import { createEditBar } from './ui/edit-bar.js';
import { describeEdit, format, typeName } from './ui/format.js';
import { createInspector } from './ui/inspector.js';
import { drawPlot } from './ui/plot.js';
import { createScene } from './ui/scene.js';
import { createTimeline, frameOf } from './ui/timeline.js';
import { VqsaClient } from './vqsa-client.js';
import { examples as exampleNames, options as schema } from './vqsa-schema.js';

const VIEWS = {
  input: 'Input mesh',
  lloyd: 'Partition before smoothing',
  smoothed: 'Partition',
  projected: 'Projected mesh',
  error: 'Error heat map',
};
const DISPLAY_FIELDS = [
  { name: 'view', kind: 'choice', choices: Object.keys(VIEWS), labels: VIEWS },
  { name: 'colouring', label: 'colour', kind: 'choice', choices: ['region', 'type'],
    labels: { region: 'By region', type: 'By quadric type' } },
  { name: 'heat', label: 'heat scale', kind: 'choice', choices: ['linear', 'log'],
    labels: { linear: 'linear', log: 'logarithmic (3 decades)' } },
  { name: 'wireframe', kind: 'boolean' },
  { name: 'up', label: 'up axis', kind: 'choice', choices: ['y', 'z'], labels: { y: 'Y up', z: 'Z up' } },
  // 0 is off: the cut's height along the up axis, as a fraction of the model's.
  { name: 'section', label: 'section', kind: 'number', min: 0.01, max: 1, typicalWhenOn: 0.5, slider: true,
    help: 'cut the model across the up axis at this fraction of its height' },
];
const STANDARD_VIEWS = { iso: 'Iso', front: 'Front', top: 'Top', side: 'Side' };
// The regions out of focus fade towards this grey while one is in focus (a lighter focus
// alone was invisible on the back of the model).
const FADED = [0.86, 0.87, 0.89];
// The approximation's settings: the core's option schema, under its camelCase names.
const OPTION_FIELDS = schema.map((o) => ({ ...o, name: o.js, label: o.name.replaceAll('-', ' ') }));
const MAX_FILE_BYTES = 1.5 * 1024 ** 3;
// The heat map's red: this quantile of the vertices' errors (the maximum would leave
// almost every vertex blue).
const HEAT_QUANTILE = 0.98;
const HEAT_DECADES = 3;  // the logarithmic heat scale's range below its top
// The bar over a whole run: the Lloyd stage to 70 %, then the post-processing stages in
// equal shares, each by its own fraction done.
const POST_STAGES = ['smooth', 'refit', 'project', 'measure'];
function runFraction(p) {
  if (p.stage === 'lloyd') return p.fraction > 0 ? 0.7 * p.fraction : null;  // automatic count: unknown
  const index = POST_STAGES.indexOf(p.stage);
  return index < 0 ? 1 : 0.7 + (0.3 * (index + p.fraction)) / POST_STAGES.length;
}

export function createViewer(host, options = {}) {
  const api = new EventTarget();
  const settings = Object.fromEntries(OPTION_FIELDS.map((f) => [f.name, f.default]));
  for (const f of OPTION_FIELDS) if (options[f.name] !== undefined) settings[f.name] = options[f.name];
  const display = { view: 'smoothed', colouring: 'region', heat: 'linear', wireframe: false, up: 'y', section: 0 };
  // A file the user brings runs with the automatic count until a count is chosen (in the
  // panel, or by the embedding page).
  let countChosen = options.proxies !== undefined;

  // ---- DOM -------------------------------------------------------------------------
  host.classList.add('vqsa-viewer');
  host.dataset.state = 'idle';
  host.dataset.proxies = '0';
  const shadow = host.shadowRoot ?? host.attachShadow({ mode: 'open' });
  const stylesheet = element('link', { rel: 'stylesheet', href: new URL('./viewer.css', import.meta.url).href });
  const fileInput = element('input', { type: 'file', accept: '.off,.obj,.ply,.stl,.gltf,.glb', hidden: true });
  const openButton = element('button', { textContent: 'Open…', title: 'Open a mesh (or drop one on the view)' });
  const examples = element('select', { title: 'Examples', ariaLabel: 'Examples' },
    element('option', { textContent: 'Examples…', value: '' }),
    ...[...exampleNames, 'bunny'].map((e) => element('option', { value: e, textContent: typeName(e) })));
  const runButton = element('button', { textContent: 'Run', className: 'vqsa-primary' });
  const cancelButton = element('button', { textContent: 'Cancel', disabled: true });
  const glbButton = element('button', { textContent: 'GLB', title: 'Download the result as binary glTF', disabled: true,
    dataset: { testid: 'download-glb' } });
  const reportButton = element('button', { textContent: 'Report', title: 'Download the JSON report', disabled: true,
    dataset: { testid: 'download-report' } });
  const pngButton = element('button', { textContent: 'PNG', title: 'Download the view as a PNG picture', disabled: true,
    dataset: { testid: 'download-png' } });
  const meshName = element('span', { className: 'vqsa-mesh-name' });
  const toolbar = element('div', { className: 'vqsa-toolbar' },
    element('span', { className: 'vqsa-title', textContent: 'vqsa', title: 'variational quadric shape approximation' }),
    element('span', { className: 'vqsa-tagline', textContent: 'the quadric surfaces of a mesh' }),
    meshName, openButton, examples, runButton, cancelButton, element('span', { className: 'vqsa-spacer' }),
    pngButton, glbButton, reportButton, fileInput);

  const canvasHost = element('div', { className: 'vqsa-canvas' });
  const status = element('div', { className: 'vqsa-status' });
  const bar = element('div', { className: 'vqsa-bar' });
  const progress = element('div', { className: 'vqsa-progress' }, element('div', { className: 'vqsa-track' }, bar), status);
  const errorBox = element('div', { className: 'vqsa-error', hidden: true, role: 'alert', dataset: { testid: 'error' } });
  const legend = element('div', { className: 'vqsa-legend' });
  const dropHint = element('div', { className: 'vqsa-drop', textContent: 'Drop a mesh to approximate it' });
  const hint = element('div', { className: 'vqsa-hint', textContent: 'Drop an OBJ, STL, PLY, OFF or glTF file to approximate it' });
  const views = element('div', { className: 'vqsa-views' }, ...Object.entries(STANDARD_VIEWS).map(([name, label]) => {
    const button = element('button', { textContent: label, title: `${label} view` });
    button.addEventListener('click', () => scene.view(name));
    return button;
  }));
  const fit = element('button', { textContent: 'Fit', title: 'Frame the whole model' });
  fit.addEventListener('click', () => scene.frame());
  views.append(fit);
  const timeline = createTimeline((frame) => showFrame(frame));
  const stage = element('div', { className: 'vqsa-stage' }, canvasHost, progress, errorBox, legend, views, hint, timeline.element, dropHint);

  const plot = element('canvas', { className: 'vqsa-plot', width: 320, height: 120 });
  const inspector = createInspector({
    focus: (region, pin) => focus(region, pin),
    visibility: () => applyVisibility(),
    frame: (region) => {
      const labels = shownLabels();
      scene.frame(labels ? (f) => labels[f] === region : null);
    },
    merge: (region) => {
      if (pinned && region !== focused && result && !result.proxies[focused]?.locked) act('merge', focused, region);
    },
  });
  const approximation = createControls('Approximation', OPTION_FIELDS, settings, (name) => {
    if (name === 'proxies') countChosen = true;
  });
  const displayControls = createControls('Display', DISPLAY_FIELDS, display, (name, value) => {
    if (name === 'view') showView();
    else if (name === 'colouring') paint(), fillTable();
    else if (name === 'heat') paint();
    else if (name === 'up') scene.setUp(value);
    else if (name === 'section') scene.setSection(value > 0 ? value : null);
    else scene.setWireframe(value);
  });
  const editBar = createEditBar((kind, ...args) => act(kind, ...args));
  const editList = element('ol', { className: 'vqsa-edit-list', dataset: { testid: 'edits' } });
  const side = element('div', { className: 'vqsa-side' }, approximation.element, displayControls.element,
    element('div', { className: 'vqsa-caption', textContent: 'RMS error against proxy count' }), plot,
    element('div', { className: 'vqsa-caption', textContent: 'Proxies' }),
    element('div', { className: 'vqsa-table-host' }, inspector.table),
    element('div', { className: 'vqsa-caption', textContent: 'Edit the pinned region' }), editBar.element, inspector.detail,
    element('div', { className: 'vqsa-caption', textContent: 'Edits' }), editList);
  shadow.replaceChildren(stylesheet, toolbar, element('div', { className: 'vqsa-body' }, stage, side));
  const scene = createScene(canvasHost);

  // ---- state -------------------------------------------------------------------------
  const client = new VqsaClient();
  let mesh = null;            // {positions, triangles, sourceFaces, info, name}
  let live = null;            // labels during a run
  let result = null;          // the last result
  let focused = -1, pinned = false;
  let growth = [];            // [proxies, rms] of the partitions the run settled on
  let ending = null;          // [proxies, rms] of the run's result
  let scrubbed = null;        // the timeline's frame shown instead of the result
  let busy = false;

  function setState(state) {
    host.dataset.state = state;
    runButton.disabled = !mesh || state === 'running' || state === 'loading';
    cancelButton.disabled = state !== 'running';
    // After a failed load the result shown is still the worker's: it stays downloadable.
    glbButton.disabled = reportButton.disabled = !(result && (state === 'done' || state === 'error'));
    pngButton.disabled = !mesh || state === 'loading';
    host.classList.toggle('vqsa-empty', !mesh);
    updateEditBar();
    api.dispatchEvent(new CustomEvent('state', { detail: state }));
  }

  function showError(type, message) {
    errorBox.textContent = message;
    errorBox.hidden = false;
    setState('error');
    api.dispatchEvent(new CustomEvent('error', { detail: { type, message } }));
  }

  function clearError() {
    errorBox.hidden = true;
    errorBox.textContent = '';
  }

  function setStatus(text, fraction = null) {
    status.textContent = text;
    bar.style.width = fraction === null ? '0' : `${Math.round(100 * Math.min(Math.max(fraction, 0), 1))}%`;
    bar.classList.toggle('vqsa-indeterminate', fraction === null && host.dataset.state === 'running');
  }

  // ---- colours -------------------------------------------------------------------------
  const showsHeat = () => display.view === 'error' && result?.vertexErrors?.length && !live && !scrubbed;
  // The labels on show: a timeline frame, the run's progress, or the result.
  const shownLabels = () => scrubbed?.labels ?? live ?? (result && (display.view === 'lloyd' ? result.lloydFaceLabels : result.faceLabels));

  function faceColour(region) {
    if (region < 0) return NEUTRAL;
    const type = result?.proxies?.[region]?.type;
    const c = display.colouring === 'type' && type && !scrubbed ? typeColour(type) : regionColour(region);
    return focused >= 0 && region !== focused ? c.map((v, k) => v + (FADED[k] - v) * 0.75) : c;
  }

  function paint() {
    if (!mesh) return;
    const array = scene.colours(), n = mesh.triangles.length / 3;
    const labels = shownLabels();
    if (showsHeat()) {
      const errors = result.vertexErrors, t = mesh.triangles;
      for (let f = 0; f < n; ++f)
        for (let k = 0; k < 3; ++k) array.set(heat(heatPosition(errors[t[3 * f + k]])), 9 * f + 3 * k);
    } else {
      // One colour per region, not one per face (a hover repaints every face).
      const byRegion = [];
      for (let f = 0; f < n; ++f) {
        const c = display.view === 'input' || !labels ? NEUTRAL : (byRegion[labels[f] + 1] ??= faceColour(labels[f]));
        array.set(c, 9 * f);
        array.set(c, 9 * f + 3);
        array.set(c, 9 * f + 6);
      }
    }
    scene.coloursChanged();
    drawLegend();
  }

  let heatScaleOf = null;
  function heatScale() {
    if (heatScaleOf?.result !== result) {
      const sorted = Float32Array.from(result.vertexErrors).sort();
      const value = sorted[Math.min(sorted.length - 1, Math.floor(HEAT_QUANTILE * sorted.length))];
      heatScaleOf = { result, value: value > 0 ? value : sorted[sorted.length - 1] || 1 };
    }
    return heatScaleOf.value;
  }

  // Where an error lies on the colour bar, in [0, 1].
  function heatPosition(error) {
    const top = heatScale();
    if (display.heat !== 'log') return error / top;
    return error > 0 ? 1 + Math.log10(error / top) / HEAT_DECADES : 0;
  }

  function showView() {
    if (!mesh) return;
    const projected = (display.view === 'projected' || display.view === 'error') && result?.projected?.length && !live;
    const wanted = projected ? 'projected' : 'input';
    if (shownGeometry !== wanted) {
      scene.setGeometry(projected ? result.projected : mesh.positions, mesh.triangles);
      shownGeometry = wanted;
      applyVisibility();
    }
    paint();
  }

  // Faces of hidden regions are not drawn (the inspector's visibility and isolate).
  function applyVisibility() {
    const hidden = inspector.hidden, labels = shownLabels();
    if (!hidden.size || !labels || live) return scene.setVisibleFaces(null);
    const faces = [];
    for (let f = 0; f < labels.length; ++f) if (!hidden.has(labels[f])) faces.push(f);
    scene.setVisibleFaces(faces);
  }
  let shownGeometry = null;

  function drawLegend() {
    legend.replaceChildren();
    if (showsHeat()) {
      const ramp = element('div', { className: 'vqsa-ramp' });
      ramp.style.background = `linear-gradient(to right, ${[0, 1 / 3, 2 / 3, 1].map((t) => css(heat(t))).join(',')})`;
      // Relative to the diagonal, and in the model's own units.
      const top = heatScale(), diagonal = mesh.info.bboxDiagonal;
      const bottom = display.heat === 'log' ? `≤ ${format(top / 10 ** HEAT_DECADES, 2)}` : '0';
      legend.append(element('div', { textContent: 'distance to the input / bbox diagonal' }), ramp,
        element('div', { className: 'vqsa-ramp-labels' }, element('span', { textContent: bottom }),
          element('span', { textContent: `≥ ${format(top, 3)}` })),
        element('div', { className: 'vqsa-ramp-units', textContent: `${format(top, 3)} of the diagonal = ${format(top * diagonal, 3)} model units` }));
      return;
    }
    if (display.colouring !== 'type' || !result) return;
    for (const type of new Set(result.proxies.map((p) => p.type))) {
      const swatch = element('span', { className: 'vqsa-swatch' });
      swatch.style.background = css(typeColour(type));
      legend.append(element('div', { className: 'vqsa-legend-row' }, swatch, element('span', { textContent: typeName(type) })));
    }
  }

  // ---- inspector and picking -----------------------------------------------------------
  function fillTable() {
    inspector.fill(result?.proxies, (p) => (display.colouring === 'type' ? typeColour(p.type) : regionColour(p.id)));
  }

  // The pointer's region is in focus until a click pins one (a second click unpins it).
  function focus(region, pin = false) {
    if (pinned && !pin) return;
    if (pin) pinned = region >= 0 && !(pinned && focused === region);
    if (focused === region && !pin) return;
    focused = region;
    inspector.show(result?.proxies?.[region]);
    updateEditBar();
    paint();
  }

  // The face under the pointer (-1: none, or nothing to pick).
  function faceAt(event) {
    if (!result || live || scrubbed || !mesh) return -1;
    return scene.pick(event);
  }
  let pointerDown = null, hovered = -1;
  scene.canvas.addEventListener('pointerdown', (e) => { pointerDown = [e.clientX, e.clientY]; });
  scene.canvas.addEventListener('pointerup', (e) => {
    if (!pointerDown || Math.hypot(e.clientX - pointerDown[0], e.clientY - pointerDown[1]) >= 4) return;
    const face = faceAt(e), region = face < 0 ? -1 : shownLabels()[face];
    if (editBar.picked(face, region)) return;
    if (e.shiftKey && pinned && region >= 0 && region !== focused && !result.proxies[focused]?.locked) act('merge', focused, region);
    else focus(region, true);
  });
  scene.canvas.addEventListener('pointermove', (e) => {
    if (e.buttons !== 0 || !result || live) return;
    const face = faceAt(e);
    hovered = face < 0 ? -1 : shownLabels()[face];
    focus(hovered);
  });
  scene.canvas.addEventListener('pointerleave', () => { hovered = -1; });
  host.addEventListener('keydown', (e) => {
    if (e.defaultPrevented || e.composedPath()[0]?.closest?.('input, select, textarea')) return;
    if (editBar.key(e, hovered)) e.preventDefault();
  });
  // Escape drops a pending pick before it unpins the region (the inspector's Escape).
  host.addEventListener('keydown', (e) => {
    if (e.key !== 'Escape' || !editBar.pending) return;
    editBar.key(e, hovered);
    e.preventDefault();
    e.stopPropagation();
  }, true);

  // ---- edits ---------------------------------------------------------------------------
  // The edit bar follows the region pinned in the view or the inspector.
  function updateEditBar() {
    const editable = Boolean(result) && host.dataset.state === 'done' && !scrubbed;
    editBar.update(pinned ? result?.proxies?.[focused] ?? null : null, result?.history, editable);
  }

  // What the edit bar (or a key, or a shift-click) asked for; faces are the view's
  // triangles, the engine's are the file's.
  function act(kind, ...args) {
    const fileFace = (face) => mesh.sourceFaces[face];
    if (kind === 'pick') scene.canvas.style.cursor = args[0] ? 'crosshair' : '';
    else if (kind === 'split') split(args[0], args[1] === undefined ? undefined : fileFace(args[1]));
    else if (kind === 'merge') merge(args[0], args[1]);
    else if (kind === 'type') setType(args[0], args[1]);
    else if (kind === 'lock') (args[1] ? lock : unlock)(args[0]);
    else if (kind === 'seed') addSeed(fileFace(args[0]));
    else if (kind === 'undo') undo();
    else if (kind === 'redo') redo();
  }

  // Runs an edit (or an undo or redo) in the worker and shows its result; `pin`: the region
  // to keep in focus after it (from the new result).
  function editing(request, pin) {
    return guarded('edit', async (current) => {
      if (!result) throw new Error('run an approximation first');
      const onRow = shadow.activeElement?.matches('tr');  // keys go on from the pinned row
      const kept = pinned ? focused : -1;  // undo and redo keep the region pinned
      clearError();
      setState('running');
      const done = await request((p) => {
        if (!current()) return;
        setStatus(p.stage === 'lloyd' ? `${p.phase} · iteration ${p.iteration}` : `${p.stage} ${Math.round(100 * p.fraction)} %`,
          runFraction(p));
      });
      if (!current()) return null;
      showResult(done, { edited: true });
      const region = pin ? pin(done) : kept;
      focused = -1, pinned = false;
      if (region >= 0 && region < done.proxies.length) focus(region, true);
      if (onRow && pinned) inspector.focusRow(focused);
      updateEditBar();
      const edits = result.reportObject.edits;
      api.dispatchEvent(new CustomEvent('edit', { detail: { edits, history: done.history } }));
      return result.reportObject;
    });
  }
  const edit = (op, pin) => editing((onProgress) => client.edit(op, { onProgress }), pin);
  const split = (region, face) => edit({ op: 'split', region, ...(face === undefined ? {} : { face }) }, (r) => r.proxies.length - 1);
  const merge = (a, b) => edit({ op: 'merge', regions: [a, b] }, () => (a > b ? a - 1 : a));
  const setType = (region, type) => edit({ op: 'set_type', region, type }, () => region);
  const lock = (region) => edit({ op: 'lock', region }, () => region);
  const unlock = (region) => edit({ op: 'unlock', region }, () => region);
  const addSeed = (face) => edit({ op: 'add_seed', face }, (r) => r.proxies.length - 1);
  const undo = () => editing(() => client.undo());
  const redo = () => editing(() => client.redo());

  function showEdits() {
    const edits = result?.reportObject?.edits ?? [];
    editList.replaceChildren(...edits.map((e) => element('li', { textContent: describeEdit(e) })));
    if (!edits.length) editList.append(element('li', { className: 'vqsa-none', textContent: 'none: pick a region to edit it' }));
  }

  function forgetResult() {
    result = null;
    showEdits();
    growth = [];
    ending = null;
    scrubbed = null;
    timeline.clear();
    focused = -1;
    pinned = false;
    fillTable();
    inspector.show(null);
  }

  // ---- loading and running ---------------------------------------------------------------
  function receiveMesh(loaded, name) {
    mesh = { ...loaded, name };
    forgetResult();
    live = null;
    drawPlot(plot, growth);
    shownGeometry = null;
    showView();
    scene.frame();
    meshName.textContent = `${name} · ${loaded.info.faces.toLocaleString()} faces`;
    setStatus(`${name}: ${loaded.info.faces.toLocaleString()} faces, ${loaded.info.vertices.toLocaleString()} vertices`);
    api.dispatchEvent(new CustomEvent('loaded', { detail: loaded.info }));
  }

  // Every load or run supersedes the one before: a superseded one changes nothing when its
  // answer (or its cancellation) finally arrives. `type` names what failed in error events.
  let generation = 0;
  async function guarded(type, work) {
    const mine = ++generation;
    const current = () => mine === generation;
    if (busy) {
      client.cancel();
      await new Promise((r) => setTimeout(r, 0));
    }
    busy = true;
    try {
      return await work(current);
    } catch (e) {
      if (!current()) return null;
      live = null;
      if (e.name === 'AbortError') {
        setState(result ? 'done' : 'idle');
        setStatus('cancelled');
      } else {
        showError(e.fatal ? 'engine' : type, e.message);
      }
      showView();
      return null;
    } finally {
      if (current()) busy = false;
    }
  }

  // A file that fails to load changes nothing: the worker keeps the mesh and result shown,
  // and so does the page (its status line and downloads too), under the error.
  function loading(work) {
    const shown = { text: status.textContent, width: bar.style.width };
    return guarded('load', async (current) => {
      clearError();
      setState('loading');
      try {
        const loaded = await work();
        if (!current()) return null;
        receiveMesh(loaded.mesh, loaded.name);
        setState('idle');
        return mesh.info;
      } catch (e) {
        if (current()) status.textContent = shown.text, bar.style.width = shown.width;
        throw e;
      }
    });
  }

  function load(source, name) {
    return loading(async () => {
      let bytes = source, fileName = name;
      if (typeof source === 'string') {
        const url = new URL(source, document.baseURI);
        fileName ??= decodeURIComponent(url.pathname.split('/').pop());
        setStatus(`downloading ${fileName}…`);
        const response = await fetch(url);
        if (!response.ok) throw new Error(`${fileName}: could not fetch it (${response.status})`);
        bytes = await response.arrayBuffer();
      } else if (source instanceof Blob) {
        fileName ??= source.name;
        if (source.size > MAX_FILE_BYTES) throw new Error(`${fileName}: ${(source.size / 1024 ** 3).toFixed(1)} GB is more than this browser can hold`);
        bytes = await source.arrayBuffer();
      }
      setStatus(`reading ${fileName}…`);
      return { mesh: await client.load(bytes, fileName), name: fileName };
    });
  }

  function loadExample(name) {
    if (name === 'bunny') return load(new URL('./examples/bunny.off', import.meta.url).href, 'bunny.off');
    return loading(async () => ({ mesh: await client.loadExample(name), name }));
  }

  function showProgress(p) {
    live = p.labels;
    timeline.record(frameOf(p));
    host.dataset.proxies = String(p.proxies);
    // The curve: each partition Lloyd settled on (the error right after an operation has not
    // settled yet).
    if (p.settledProxies > 0) growth.push([p.settledProxies, p.settledRms]);
    setStatus(p.stage === 'lloyd'
      ? `${p.phase} · ${p.proxies} proxies · iteration ${p.iteration} · RMS ${format(p.rms)}`
      : `${p.stage} ${Math.round(100 * p.fraction)} % · ${p.proxies} proxies`, runFraction(p));
    // Recolouring a large mesh takes longer than the worker takes to post: only the newest
    // labels are painted, once per frame, and the ones in between are dropped (the
    // timeline keeps them), so the picture never lags the run.
    if (!paintQueued) {
      paintQueued = true;
      requestAnimationFrame(() => {
        paintQueued = false;
        if (live) paint(), drawPlot(plot, growth);
      });
    }
    api.dispatchEvent(new CustomEvent('progress', { detail: p }));
  }
  let paintQueued = false;

  // Why a run ended, where the count alone does not say it (the report's stop_reason).
  function stopped(report, asked) {
    const cap = report.options['max-iterations'];
    switch (report.stop_reason) {
      case 'fitted': return asked === 'auto' ? 'automatic: every region fitted' : '';
      case 'no_gain': return 'automatic: more proxies stopped paying';
      case 'tolerance': return 'tolerance reached';
      case 'max_iterations': return `stopped at the ${cap}-iteration cap`;
      case 'exhausted': return 'no face left to seed';
      default: return '';
    }
  }

  function summary() {
    const report = result.reportObject, metrics = report.metrics, asked = report.options.proxies;
    // Fewer than asked: say why (the surfaces ran out; the rest would have been slivers).
    const count = typeof asked === 'number' && result.proxies.length < asked && report.stop_reason === 'fitted'
      ? `${result.proxies.length} proxies (every surface found before ${asked})` : `${result.proxies.length} proxies`;
    const why = stopped(report, asked);
    const edits = report.edits.length ? ` · ${report.edits.length} edit${report.edits.length > 1 ? 's' : ''}` : '';
    return `${count} · RMS ${format(report.rms_error_relative)} of the size` +
      (metrics ? ` · projected ${format(metrics.rms)} of the diagonal` : '') + (why ? ` · ${why}` : '') + edits;
  }

  // A run's result, or an edited one (`edited`: the run's timeline and plot stay).
  function showResult(done, { edited = false } = {}) {
    live = null;
    result = done;
    result.reportObject = JSON.parse(done.report);
    host.dataset.proxies = String(done.proxies.length);
    setStatus(summary(), 1);
    const rms = result.reportObject.rms_error_relative;
    if (!edited) {
      ending = [done.proxies.length, rms];
      timeline.record({ labels: done.faceLabels, proxies: done.proxies.length, rms, at: ending });
      timeline.finish();
    }
    // An edited result is marked on the run's curve.
    drawPlot(plot, growth, ending, edited ? [done.proxies.length, rms] : null);
    fillTable();
    showEdits();
    showView();
    setState('done');
    api.dispatchEvent(new CustomEvent('result', { detail: result.reportObject }));
  }

  // A recorded state of the run (null: the result), from the timeline.
  function showFrame(frame) {
    scrubbed = frame;
    if (frame) {
      const where = frame.stage === 'lloyd' ? `${frame.phase} · iteration ${frame.iteration}` : frame.stage;
      setStatus(`replay: ${where} · ${frame.proxies} proxies · RMS ${format(frame.rms)}`, null);
    } else {
      setStatus(summary(), 1);
    }
    host.dataset.frame = frame ? String(timeline.frames.indexOf(frame)) : '';
    updateEditBar();
    showView();
    applyVisibility();
    const edited = result?.reportObject?.edits?.length ? [result.proxies.length, result.reportObject.rms_error_relative] : null;
    drawPlot(plot, growth, ending, frame ? frame.at : edited);
  }

  // `overrides`: options of the schema by their camelCase names; they stay set.
  function run(overrides = {}) {
    for (const [name, value] of Object.entries(overrides)) {
      if (!(name in settings)) throw new Error(`unknown option '${name}'`);
      settings[name] = value;
    }
    approximation.update();
    return guarded('run', async (current) => {
      if (!mesh) throw new Error('open a mesh first');
      clearError();
      forgetResult();
      setState('running');
      shownGeometry = null;
      live = new Int32Array(mesh.triangles.length / 3).fill(-1);
      showView();
      const done = await client.run({ ...settings }, { onProgress: (p) => current() && showProgress(p) });
      if (!current()) return null;
      showResult(done);
      return result.reportObject;
    });
  }

  function cancel() {
    client.cancel();
  }

  function download(bytes, name, type) {
    const url = URL.createObjectURL(new Blob([bytes], { type }));
    const a = element('a', { href: url, download: name });
    shadow.append(a);
    a.click();
    a.remove();
    setTimeout(() => URL.revokeObjectURL(url), 1000);
  }
  const baseName = () => (mesh?.name ?? 'mesh').replace(/\.[^.]*$/, '');

  // A mesh the user brings (a file, an example) runs with the automatic count unless a
  // count was chosen; nothing runs after a failed load.
  const runBrought = (info) => info && run(countChosen ? {} : { proxies: 'auto' });
  openButton.addEventListener('click', () => fileInput.click());
  fileInput.addEventListener('change', () => {
    if (fileInput.files[0]) load(fileInput.files[0]).then(runBrought);
    fileInput.value = '';
  });
  function chooseExample() {
    const name = examples.value;
    examples.value = '';
    if (name) loadExample(name).then(runBrought);
  }
  // With its list closed, a select changes value (and fires change) at every arrow key: a
  // choice made by keys loads on Enter, and leaving the select drops it; a click loads at once.
  let browsingByKeys = false;
  examples.addEventListener('keydown', (e) => {
    if (e.key === 'Enter' && browsingByKeys) {
      browsingByKeys = false;
      chooseExample();
    } else if (!e.altKey && /^(Arrow|Home$|End$|Page)/.test(e.key)) {
      browsingByKeys = true;
    }
  });
  examples.addEventListener('change', () => browsingByKeys || chooseExample());
  examples.addEventListener('blur', () => {
    if (browsingByKeys) examples.value = '';
    browsingByKeys = false;
  });
  runButton.addEventListener('click', () => run());
  cancelButton.addEventListener('click', cancel);
  // The GLB in the colours on screen, built by the worker (which keeps the result) when asked.
  glbButton.addEventListener('click', async () => {
    try {
      const bytes = await client.glb(display.colouring);
      download(bytes, `${baseName()}.vqsa.glb`, 'model/gltf-binary');
    } catch (e) {
      showError(e.fatal ? 'engine' : 'run', e.message);
    }
  });
  reportButton.addEventListener('click', () => download(result.report, `${baseName()}.vqsa.json`, 'application/json'));
  pngButton.addEventListener('click', async () => download(await scene.screenshot(), `${baseName()}.vqsa.png`, 'image/png'));
  const detachDropZone = attachDropZone(options.dropTarget ?? host, host, (file) => load(file).then(runBrought));

  drawPlot(plot, growth);
  fillTable();
  showEdits();
  setState('idle');

  // Accessors stay accessors (Object.assign would copy their values once).
  Object.defineProperties(api, Object.getOwnPropertyDescriptors({
    element: host,
    load, loadExample, run, cancel, split, merge, setType, lock, unlock, addSeed, undo, redo,
    get state() { return host.dataset.state; },
    get result() { return result?.reportObject ?? null; },
    get settings() { return { ...settings }; },
    destroy() {
      timeline.clear();
      scene.destroy();
      client.terminate();
      detachDropZone();
      shadow.replaceChildren();
    },
  }));

  const initial = options.src ? load(options.src) : options.example ? loadExample(options.example) : null;
  initial?.then((info) => info && run());
  return api;
}
