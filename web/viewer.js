// The vqsa viewer: load a mesh, watch proxies being inserted and boundaries smoothed,
// inspect the quadrics, download the GLB. Everything runs in the page's own worker;
// meshes never leave the browser.
//
//   import { createViewer } from './viewer.js';
//   const viewer = createViewer(element, { proxies: 20, example: 'turned_part' });
//   viewer.addEventListener('result', (e) => console.log(e.detail.report));
//   await viewer.load(file);        // File/Blob/URL string/ArrayBuffer (+ name)
//   await viewer.run({ proxies: 12 });  // or 'auto'
//
// The root element carries data-state (idle | loading | running | done | error) and
// data-proxies; events: state, loaded, progress, result, error (detail: the data).
import * as THREE from './vendor/three/three.module.js';
import { OrbitControls } from './vendor/three/addons/controls/OrbitControls.js';
import GUI from './vendor/three/addons/libs/lil-gui.module.min.js';
import { VqsaClient } from './vqsa-client.js';

const VIEWS = {
  'Input mesh': 'input',
  'Partition before smoothing': 'lloyd',
  'Partition': 'smoothed',
  'Projected mesh': 'projected',
  'Error heat map': 'error',
};
const COLOURINGS = { 'By region': 'region', 'By quadric type': 'type' };
const NEUTRAL = [0.72, 0.74, 0.78];
const MAX_FILE_BYTES = 1.5 * 1024 ** 3;

let stylesheetAdded = false;
function addStylesheet() {
  if (stylesheetAdded) return;
  stylesheetAdded = true;
  const link = document.createElement('link');
  link.rel = 'stylesheet';
  link.href = new URL('./viewer.css', import.meta.url).href;
  document.head.append(link);
}

function element(tag, attributes = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attributes)) {
    if (k === 'text') e.textContent = v;
    else if (k.startsWith('data')) e.setAttribute(k.replace(/[A-Z]/g, (c) => `-${c.toLowerCase()}`), v);
    else e[k] = v;
  }
  e.append(...children);
  return e;
}

// A distinct colour per region: golden-ratio hues, alternating lightness.
function regionColour(id) {
  const c = new THREE.Color().setHSL((id * 0.6180339887) % 1, 0.55, id % 2 ? 0.52 : 0.64, THREE.SRGBColorSpace);
  return [c.r, c.g, c.b];
}

// Blue → cyan → yellow → red, t in [0, 1].
function heat(t) {
  const stops = [[0.15, 0.25, 0.8], [0.1, 0.75, 0.85], [0.95, 0.85, 0.2], [0.85, 0.1, 0.1]];
  const x = Math.min(Math.max(t, 0), 1) * (stops.length - 1), i = Math.min(Math.floor(x), stops.length - 2), f = x - i;
  return stops[i].map((v, k) => v + f * (stops[i + 1][k] - v));
}

// `digits` significant digits whatever the model's size (an r of 0.00123 is not
// "0.001"), exponents only far from 1, no "-0".
const format = (x, digits = 4) => {
  if (!Number.isFinite(x)) return String(x);
  const a = Math.abs(x);
  const text = a !== 0 && (a >= 1e5 || a < 1e-3) ? x.toExponential(digits - 1) : x.toPrecision(digits);
  return Number(text) === 0 ? '0' : text;
};
// Components below the last printed digit of the vector's largest are 0: a normal's
// rounding noise (2.6e-7) is not a direction.
const vector = (v, digits = 4) => {
  const largest = Math.max(...v.map(Math.abs));
  return `(${v.map((x) => (Math.abs(x) < 0.5 * 10 ** -digits * largest ? '0' : format(x, digits))).join(', ')})`;
};
const degrees = (radians) => `${((radians * 180) / Math.PI).toFixed(2)}°`;
// The terms of f = C0 + C1 x + … + C9 z², in the report's order.
const TERMS = ['', 'x', 'y', 'z', 'x²', 'xy', 'xz', 'y²', 'yz', 'z²'];
const polynomial = (c) => c.map((v, i) => [v, i]).filter(([v]) => v !== 0)
  .map(([v, i], k) => `${k === 0 ? (v < 0 ? '−' : '') : v < 0 ? ' − ' : ' + '}${format(Math.abs(v))}${TERMS[i] && ' ' + TERMS[i]}`)
  .join('') || '0';

function keyParams(p) {
  const q = p.params ?? {};
  switch (p.type) {
    case 'plane': return `n ${vector(q.normal, 3)}`;
    case 'sphere': return `r ${format(q.radius)}`;
    case 'cylinder': return `r ${format(q.radius)}`;
    case 'cone': return degrees(q.half_angle);
    default: return q.semi_axes ? `a ${vector(q.semi_axes, 3)}` : '';
  }
}

export function createViewer(root, options = {}) {
  addStylesheet();
  const api = new EventTarget();
  const settings = {
    proxies: options.proxies === 'auto' ? 20 : options.proxies ?? 20,
    // Grow until more proxies no longer pay: the default for files the user brings.
    automatic: options.proxies === 'auto',
    useTolerance: options.tolerance !== undefined,
    tolerance: options.tolerance ?? 0.002,
    rings: options.rings ?? 1,
    lambda: options.lambda ?? 1,
    seed: options.seed ?? 1,
    smooth: options.smooth ?? true,
    refit: options.refit ?? true,
    view: 'Partition',
    colouring: 'By region',
    wireframe: false,
  };

  // ---- DOM -------------------------------------------------------------------------
  root.classList.add('vqsa-viewer');
  root.dataset.state = 'idle';
  root.dataset.proxies = '0';
  const fileInput = element('input', { type: 'file', accept: '.off,.obj,.ply,.stl,.gltf,.glb', hidden: true });
  const openButton = element('button', { text: 'Open…', title: 'Open a mesh (or drop one anywhere)' });
  const examples = element('select', { title: 'Examples', ariaLabel: 'Examples' }, element('option', { text: 'Examples…', value: '' }));
  const runButton = element('button', { text: 'Run', className: 'vqsa-primary' });
  const cancelButton = element('button', { text: 'Cancel', disabled: true });
  const glbButton = element('button', { text: 'GLB', title: 'Download the result as binary glTF', disabled: true, dataTestid: 'download-glb' });
  const reportButton = element('button', { text: 'Report', title: 'Download the JSON report', disabled: true, dataTestid: 'download-report' });
  const title = element('span', { className: 'vqsa-title', text: 'vqsa' });
  const meshName = element('span', { className: 'vqsa-mesh-name' });
  const toolbar = element('div', { className: 'vqsa-toolbar' }, title, meshName, openButton, examples, runButton, cancelButton,
    element('span', { className: 'vqsa-spacer' }), glbButton, reportButton, fileInput);

  const canvasHost = element('div', { className: 'vqsa-canvas' });
  const status = element('div', { className: 'vqsa-status' });
  const bar = element('div', { className: 'vqsa-bar' });
  const progress = element('div', { className: 'vqsa-progress' }, element('div', { className: 'vqsa-track' }, bar), status);
  const errorBox = element('div', { className: 'vqsa-error', hidden: true, dataTestid: 'error', role: 'alert' });
  const legend = element('div', { className: 'vqsa-legend' });
  const dropHint = element('div', { className: 'vqsa-drop', text: 'Drop a mesh to approximate it' });
  const stage = element('div', { className: 'vqsa-stage' }, canvasHost, progress, errorBox, legend, dropHint);

  const plot = element('canvas', { className: 'vqsa-plot', width: 320, height: 120 });
  const guiHost = element('div', { className: 'vqsa-gui' });
  const detail = element('div', { className: 'vqsa-detail' });
  const table = element('table', { className: 'vqsa-table' });
  const tableHost = element('div', { className: 'vqsa-table-host' }, table);
  const side = element('div', { className: 'vqsa-side' }, guiHost,
    element('div', { className: 'vqsa-caption', text: 'RMS error against proxy count' }), plot,
    element('div', { className: 'vqsa-caption', text: 'Proxies' }), tableHost, detail);
  root.replaceChildren(toolbar, element('div', { className: 'vqsa-body' }, stage, side));

  // ---- Three.js ----------------------------------------------------------------------
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
  canvasHost.append(renderer.domElement);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xf4f5f7);
  const camera = new THREE.PerspectiveCamera(40, 1, 0.01, 100);
  const controls = new OrbitControls(camera, renderer.domElement);
  controls.enableDamping = true;
  scene.add(new THREE.HemisphereLight(0xffffff, 0x8090a0, 1.6));
  const sun = new THREE.DirectionalLight(0xffffff, 1.6);
  sun.position.set(1, 2, 1.5);
  camera.add(sun);
  scene.add(camera);
  const material = new THREE.MeshStandardMaterial({ vertexColors: true, roughness: 0.75, metalness: 0, side: THREE.DoubleSide,
    flatShading: true, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1 });
  const wireMaterial = new THREE.MeshBasicMaterial({ color: 0x20242c, wireframe: true, transparent: true, opacity: 0.25 });
  const surface = new THREE.Mesh(new THREE.BufferGeometry(), material);
  const wire = new THREE.Mesh(surface.geometry, wireMaterial);
  wire.visible = false;
  const model = new THREE.Group();
  model.add(surface, wire);
  scene.add(model);

  const resize = () => {
    const w = canvasHost.clientWidth || 1, h = canvasHost.clientHeight || 1;
    renderer.setSize(w, h, false);
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
    requestRender();
  };
  const observer = new ResizeObserver(resize);
  observer.observe(canvasHost);
  let alive = true;
  // Render on demand: one frame per change (a camera move, new colours or geometry), and
  // more only while the controls' damping is still moving the camera. An idle page draws
  // nothing.
  let frameRequested = false;
  function requestRender() {
    if (frameRequested || !alive) return;
    frameRequested = true;
    requestAnimationFrame(() => {
      frameRequested = false;
      if (!alive) return;
      if (controls.update()) requestRender();
      renderer.render(scene, camera);
    });
  }
  controls.addEventListener('change', requestRender);

  // ---- state -------------------------------------------------------------------------
  let client = new VqsaClient();
  let mesh = null;            // {positions, triangles, sourceFaces, info, name}
  let live = null;            // labels during a run
  let result = null;          // the last result
  let legendColours = {};
  let highlighted = -1;
  let history = [];           // [proxies, rms] during the run
  let busy = false;

  function setState(state) {
    root.dataset.state = state;
    runButton.disabled = !mesh || state === 'running' || state === 'loading';
    cancelButton.disabled = state !== 'running';
    // After a failed load the result shown is still the worker's: it stays downloadable.
    glbButton.disabled = reportButton.disabled = !(result && (state === 'done' || state === 'error'));
    api.dispatchEvent(new CustomEvent('state', { detail: state }));
  }

  function showError(message) {
    errorBox.textContent = message;
    errorBox.hidden = false;
    setState('error');
    api.dispatchEvent(new CustomEvent('error', { detail: message }));
  }

  function clearError() {
    errorBox.hidden = true;
    errorBox.textContent = '';
  }

  // The bar over a whole run: the Lloyd stage to 70 %, then the post-processing stages in
  // equal shares, each by its own fraction done (progress events carry both).
  const POST_STAGES = ['smooth', 'refit', 'project', 'measure'];
  function runFraction(p) {
    if (p.stage === 'lloyd') return p.fraction > 0 ? 0.7 * p.fraction : null;  // automatic count: unknown
    const index = POST_STAGES.indexOf(p.stage);
    return index < 0 ? 1 : 0.7 + 0.3 * (index + p.fraction) / POST_STAGES.length;
  }

  function setStatus(text, fraction = null) {
    status.textContent = text;
    bar.style.width = fraction === null ? '0' : `${Math.round(100 * Math.min(Math.max(fraction, 0), 1))}%`;
    bar.classList.toggle('vqsa-indeterminate', fraction === null && root.dataset.state === 'running');
  }

  // ---- geometry and colours -------------------------------------------------------------
  function buildGeometry(positions) {
    const t = mesh.triangles, n = t.length / 3;
    const xyz = new Float32Array(9 * n);
    for (let f = 0; f < n; ++f)
      for (let k = 0; k < 3; ++k) {
        const v = t[3 * f + k];
        xyz.set(positions.subarray(3 * v, 3 * v + 3), 9 * f + 3 * k);
      }
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(xyz, 3));
    geometry.setAttribute('color', new THREE.BufferAttribute(new Float32Array(9 * n), 3));
    geometry.computeVertexNormals();
    geometry.computeBoundingSphere();
    return geometry;
  }

  function useGeometry(geometry) {
    surface.geometry.dispose();
    surface.geometry = wire.geometry = geometry;
    requestRender();
  }

  function frame() {
    const sphere = surface.geometry.boundingSphere;
    const distance = sphere.radius / Math.sin((camera.fov * Math.PI) / 360) * 1.15;
    controls.target.copy(sphere.center);
    camera.position.copy(sphere.center).add(new THREE.Vector3(0.55, 0.45, 0.75).normalize().multiplyScalar(distance));
    camera.near = distance / 100;
    camera.far = distance * 10;
    camera.updateProjectionMatrix();
    requestRender();
  }

  function proxyType(region) {
    return result?.proxies?.[region]?.type;
  }

  function faceColour(region) {
    if (region < 0) return NEUTRAL;
    let c = settings.colouring === 'By quadric type' && proxyType(region) ? legendColours[proxyType(region)] ?? NEUTRAL
      : regionColour(region);
    if (region === highlighted) c = c.map((v) => v + (1 - v) * 0.55);
    return c;
  }

  function paint() {
    if (!mesh) return;
    const colour = surface.geometry.getAttribute('color');
    const array = colour.array, n = mesh.triangles.length / 3;
    const view = VIEWS[settings.view];
    const labels = live ?? (result && (view === 'lloyd' ? result.lloydFaceLabels : result.faceLabels));
    if (view === 'error' && result?.vertexErrors?.length && !live) {
      const errors = result.vertexErrors, t = mesh.triangles;
      const scale = heatScale();
      for (let f = 0; f < n; ++f)
        for (let k = 0; k < 3; ++k) array.set(heat(errors[t[3 * f + k]] / scale), 9 * f + 3 * k);
    } else {
      for (let f = 0; f < n; ++f) {
        const c = view === 'input' || !labels ? NEUTRAL : faceColour(labels[f]);
        array.set(c, 9 * f);
        array.set(c, 9 * f + 3);
        array.set(c, 9 * f + 6);
      }
    }
    colour.needsUpdate = true;
    drawLegend();
    requestRender();
  }

  function heatScale() {
    const e = result.vertexErrors;
    let max = 0;
    for (let i = 0; i < e.length; ++i) max = Math.max(max, e[i]);
    return max > 0 ? max : 1;
  }

  function showView() {
    if (!mesh) return;
    const view = VIEWS[settings.view];
    const projected = (view === 'projected' || view === 'error') && result?.projected?.length && !live;
    const wanted = projected ? 'projected' : 'input';
    if (surface.userData.kind !== wanted) {
      useGeometry(buildGeometry(projected ? result.projected : mesh.positions));
      surface.userData.kind = wanted;
    }
    paint();
  }

  function drawLegend() {
    legend.replaceChildren();
    const view = VIEWS[settings.view];
    if (view === 'error' && result?.vertexErrors?.length && !live) {
      const ramp = element('div', { className: 'vqsa-ramp' });
      ramp.style.background = `linear-gradient(to right, ${[0, 1 / 3, 2 / 3, 1].map((t) =>
        `rgb(${heat(t).map((v) => Math.round(255 * Math.pow(v, 1 / 2.2))).join(',')})`).join(',')})`;
      legend.append(element('div', { text: 'distance to the input / bbox diagonal' }), ramp,
        element('div', { className: 'vqsa-ramp-labels' }, element('span', { text: '0' }), element('span', { text: format(heatScale()) })));
      return;
    }
    if (settings.colouring !== 'By quadric type' || !result) return;
    const types = [...new Set(result.proxies.map((p) => p.type))];
    for (const type of types) {
      const swatch = element('span', { className: 'vqsa-swatch' });
      swatch.style.background = `rgb(${legendColours[type].map((v) => Math.round(255 * Math.pow(v, 1 / 2.2))).join(',')})`;
      legend.append(element('div', { className: 'vqsa-legend-row' }, swatch, element('span', { text: type.replaceAll('_', ' ') })));
    }
  }

  // ---- plot, table, detail -------------------------------------------------------------
  function drawPlot() {
    const g = plot.getContext('2d'), w = plot.width, h = plot.height, pad = 26;
    g.clearRect(0, 0, w, h);
    g.fillStyle = '#fff';
    g.fillRect(0, 0, w, h);
    g.strokeStyle = '#ccd';
    g.strokeRect(pad, 6, w - pad - 6, h - pad);
    const points = history.filter(([, rms]) => rms > 0);
    if (points.length < 2) return;
    const maxN = Math.max(...points.map(([n]) => n)), logs = points.map(([, r]) => Math.log10(r));
    const lo = Math.floor(Math.min(...logs)), hi = Math.ceil(Math.max(...logs)) + (Math.min(...logs) === Math.max(...logs) ? 1 : 0);
    const x = (n) => pad + ((n - 1) / Math.max(1, maxN - 1)) * (w - pad - 8);
    const y = (r) => 6 + ((hi - Math.log10(r)) / (hi - lo)) * (h - pad - 2);
    g.fillStyle = '#556';
    g.font = '10px sans-serif';
    for (let e = lo; e <= hi; ++e) g.fillText(`1e${e}`, 0, y(10 ** e) + 3);
    g.fillText('proxies', w / 2 - 15, h - 4);
    g.fillText(String(maxN), w - 22, h - 14);
    g.strokeStyle = '#2864c8';
    g.lineWidth = 1.5;
    g.beginPath();
    points.forEach(([n, r], i) => (i ? g.lineTo(x(n), y(r)) : g.moveTo(x(n), y(r))));
    g.stroke();
  }

  function fillTable() {
    table.replaceChildren(element('tr', {}, ...['#', 'type', 'parameters', 'area %', 'RMS'].map((t) => element('th', { text: t }))));
    if (!result) return;
    const total = result.proxies.reduce((s, p) => s + p.area, 0);
    for (const p of result.proxies) {
      const swatch = element('span', { className: 'vqsa-swatch' });
      const c = settings.colouring === 'By quadric type' ? legendColours[p.type] : regionColour(p.id);
      swatch.style.background = `rgb(${c.map((v) => Math.round(255 * Math.pow(v, 1 / 2.2))).join(',')})`;
      const row = element('tr', { dataRegion: p.id },
        element('td', {}, swatch, String(p.id)), element('td', { text: p.type.replaceAll('_', ' ') }),
        element('td', { text: keyParams(p) }), element('td', { text: ((100 * p.area) / total).toFixed(1) }),
        element('td', { text: format(p.metrics?.rms ?? p.rms_error) }));
      row.addEventListener('mouseenter', () => highlight(p.id));
      row.addEventListener('click', () => highlight(p.id, true));
      table.append(row);
    }
  }

  let pinned = false;
  function highlight(region, pin = false) {
    if (pinned && !pin) return;
    if (pin) pinned = region >= 0 && !(pinned && highlighted === region);
    if (highlighted === region && !pin) return;
    highlighted = region;
    for (const row of table.querySelectorAll('tr[data-region]')) row.classList.toggle('vqsa-selected', Number(row.dataset.region) === region);
    const p = result?.proxies?.[region];
    detail.replaceChildren();
    if (p) {
      const lines = [`region ${p.id}: ${p.type.replaceAll('_', ' ')}${p.special_fit ? ' (refitted)' : ''}`,
        `${p.faces} faces, RMS ${format(p.metrics?.rms ?? 0)} of the diagonal`,
        // How clear the type choice was: the chosen type's fit to the region's vertices
        // against the best fit of another type.
        ...(p.runner_up ? [`type fit RMS ${format(p.type_rms)}; runner-up ${p.runner_up.type.replaceAll('_', ' ')}, RMS ${format(p.runner_up.rms)}`] : []),
        ...Object.entries(p.params).map(([k, v]) => `${k.replaceAll('_', ' ')}: ${k === 'half_angle' ? degrees(v)
          : Array.isArray(v[0]) ? v.map((row) => vector(row)).join(' ') : Array.isArray(v) ? vector(v) : format(v)}`),
        `f = ${polynomial(p.coefficients)}`];
      detail.append(...lines.map((l) => element('div', { text: l })));
    }
    paint();
  }

  // ---- picking -----------------------------------------------------------------------
  const raycaster = new THREE.Raycaster(), pointer = new THREE.Vector2();
  function pick(event) {
    if (!result || live || !mesh) return -1;
    const rect = renderer.domElement.getBoundingClientRect();
    pointer.set(((event.clientX - rect.left) / rect.width) * 2 - 1, -((event.clientY - rect.top) / rect.height) * 2 + 1);
    raycaster.setFromCamera(pointer, camera);
    const hit = raycaster.intersectObject(surface)[0];
    const labels = VIEWS[settings.view] === 'lloyd' ? result.lloydFaceLabels : result.faceLabels;
    return hit ? labels[hit.faceIndex] : -1;
  }
  let pointerDown = null;
  renderer.domElement.addEventListener('pointerdown', (e) => { pointerDown = [e.clientX, e.clientY]; });
  renderer.domElement.addEventListener('pointerup', (e) => {
    if (pointerDown && Math.hypot(e.clientX - pointerDown[0], e.clientY - pointerDown[1]) < 4) highlight(pick(e), true);
  });
  renderer.domElement.addEventListener('pointermove', (e) => {
    if (e.buttons === 0 && result && !live) highlight(pick(e));
  });

  // ---- controls ----------------------------------------------------------------------
  const gui = new GUI({ container: guiHost, title: 'Approximation' });
  // A file the user brings runs with the automatic count until they choose a count.
  let countChosen = false;
  gui.add(settings, 'automatic').name('automatic count').onChange(() => { countChosen = true; });
  gui.add(settings, 'proxies', 1, 200, 1).name('proxies').onChange(() => {
    countChosen = true;
    settings.automatic = false;
    gui.controllersRecursive().forEach((c) => c.updateDisplay());
  });
  gui.add(settings, 'useTolerance').name('stop on tolerance').onChange(() => syncControls());
  const toleranceControl = gui.add(settings, 'tolerance', 1e-4, 0.05, 1e-4).name('tolerance (RMS)');
  // The tolerance only matters when the run stops on it.
  function syncControls() {
    toleranceControl.enable(settings.useTolerance);
  }
  syncControls();
  gui.add(settings, 'rings', 1, 5, 1).name('smoothing rings');
  gui.add(settings, 'lambda', 0, 20, 0.1).name('smoothing λ');
  gui.add(settings, 'seed', 0, 1000, 1).name('seed');
  gui.add(settings, 'smooth').name('smooth boundaries');
  gui.add(settings, 'refit').name('choose types');
  const display = gui.addFolder('Display');
  display.add(settings, 'view', Object.keys(VIEWS)).name('view').onChange(showView);
  display.add(settings, 'colouring', Object.keys(COLOURINGS)).name('colour').onChange(() => { paint(); fillTable(); });
  display.add(settings, 'wireframe').name('wireframe').onChange((v) => { wire.visible = v; requestRender(); });

  function forgetResult() {
    result = null;
    history = [];
    highlighted = -1;
    pinned = false;
    fillTable();
    detail.replaceChildren();
  }

  // ---- loading -----------------------------------------------------------------------
  async function receiveMesh(loaded, name) {
    mesh = { ...loaded, name };
    legendColours = loaded.legend;
    if (examples.options.length === 1)
      for (const e of [...loaded.examples, 'bunny']) examples.append(element('option', { value: e, text: e.replaceAll('_', ' ') }));
    forgetResult();
    live = null;
    drawPlot();
    surface.userData.kind = 'input';
    useGeometry(buildGeometry(mesh.positions));
    frame();
    paint();
    meshName.textContent = `${name} · ${loaded.info.faces.toLocaleString()} faces`;
    setStatus(`${name}: ${loaded.info.faces.toLocaleString()} faces, ${loaded.info.vertices.toLocaleString()} vertices`);
    api.dispatchEvent(new CustomEvent('loaded', { detail: loaded.info }));
  }

  // Every load or run supersedes the one before: a superseded one changes nothing
  // when its answer (or its cancellation) finally arrives.
  let generation = 0;
  async function guarded(work) {
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
        showError(e.message);
      }
      showView();
      return null;
    } finally {
      if (current()) busy = false;
    }
  }

  async function load(source, name) {
    // A file that fails to load changes nothing: the worker keeps the mesh and result shown,
    // and so does the page (its status line and downloads too), under the error.
    const shown = { text: status.textContent, width: bar.style.width };
    return guarded(async (current) => {
      try {
        return await loadNow(source, name, current);
      } catch (e) {
        if (current()) status.textContent = shown.text, bar.style.width = shown.width;
        throw e;
      }
    });
  }

  async function loadNow(source, name, current) {
    clearError();
    setState('loading');
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
    const loaded = await client.load(bytes, fileName);
    if (!current()) return null;
    await receiveMesh(loaded, fileName);
    setState('idle');
    return mesh.info;
  }

  async function loadExample(name) {
    if (name === 'bunny') return load(new URL('./examples/bunny.off', import.meta.url).href, 'bunny.off');
    return guarded(async (current) => {
      clearError();
      setState('loading');
      const loaded = await client.loadExample(name);
      if (!current()) return null;
      await receiveMesh(loaded, name);
      setState('idle');
      return mesh.info;
    });
  }

  async function run(overrides = {}) {
    // proxies: a count, or 'auto' for the automatic count.
    const { proxies, ...rest } = overrides;
    if (proxies !== undefined) {
      settings.automatic = proxies === 'auto';
      if (proxies !== 'auto') settings.proxies = proxies;
    }
    Object.assign(settings, rest);
    gui.controllersRecursive().forEach((c) => c.updateDisplay());
    syncControls();
    return guarded(async (current) => {
      if (!mesh) throw new Error('open a mesh first');
      clearError();
      forgetResult();
      setState('running');
      const target = settings.useTolerance || settings.automatic ? 0 : settings.proxies;
      const runOptions = { proxies: target || 'auto', rings: settings.rings, lambda: settings.lambda, seed: settings.seed,
        smooth: settings.smooth, refit: settings.refit };
      if (settings.useTolerance) runOptions.tolerance = settings.tolerance;
      surface.userData.kind = null;
      live = new Int32Array(mesh.triangles.length / 3).fill(-1);
      showView();
      const done = await client.run(runOptions, {
        onProgress: (p) => {
          if (!current()) return;
          live = p.labels;
          root.dataset.proxies = String(p.proxies);
          if (p.stage === 'lloyd') history.push([p.proxies, p.rms]);
          setStatus(p.stage === 'lloyd'
            ? `${p.phase} · ${p.proxies} proxies · iteration ${p.iteration} · RMS ${format(p.rms)}`
            : `${p.stage} ${Math.round(100 * p.fraction)} % · ${p.proxies} proxies`, runFraction(p));
          paint();
          drawPlot();
          api.dispatchEvent(new CustomEvent('progress', { detail: p }));
        },
      });
      if (!current()) return null;
      live = null;
      result = done;
      result.reportObject = JSON.parse(done.report);
      root.dataset.proxies = String(done.proxies.length);
      const metrics = result.reportObject.metrics;
      setStatus(`${done.proxies.length} proxies · RMS ${format(result.reportObject.rms_error_relative)} of the size` +
        (metrics ? ` · projected ${format(metrics.rms)} of the diagonal` : ''), 1);
      history.push([done.proxies.length, result.reportObject.rms_error_relative]);
      drawPlot();
      fillTable();
      showView();
      setState('done');
      api.dispatchEvent(new CustomEvent('result', { detail: result.reportObject }));
      return result.reportObject;
    });
  }

  function cancel() {
    client.cancel();
  }

  function download(bytes, name, type) {
    const url = URL.createObjectURL(new Blob([bytes], { type }));
    const a = element('a', { href: url, download: name });
    document.body.append(a);
    a.click();
    a.remove();
    setTimeout(() => URL.revokeObjectURL(url), 1000);
  }
  const baseName = () => (mesh?.name ?? 'mesh').replace(/\.[^.]*$/, '');

  openButton.addEventListener('click', () => fileInput.click());
  fileInput.addEventListener('change', () => {
    if (fileInput.files[0]) load(fileInput.files[0]).then(() => root.dataset.state !== 'error' && run(countChosen ? {} : { automatic: true }));
    fileInput.value = '';
  });
  function chooseExample() {
    const name = examples.value;
    examples.value = '';
    if (name) loadExample(name).then(() => root.dataset.state !== 'error' && run());
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
  glbButton.addEventListener('click', () => download(result.glb, `${baseName()}.vqsa.glb`, 'model/gltf-binary'));
  reportButton.addEventListener('click', () => download(result.report, `${baseName()}.vqsa.json`, 'application/json'));

  // Drops anywhere on the page (the app) or on the viewer (embedded).
  const dropTarget = options.dropTarget ?? root;
  const onDragOver = (e) => {
    if (![...(e.dataTransfer?.types ?? [])].includes('Files')) return;
    e.preventDefault();
    root.classList.add('vqsa-dragging');
  };
  const onDragLeave = (e) => {
    if (e.target === dropTarget || !dropTarget.contains(e.relatedTarget)) root.classList.remove('vqsa-dragging');
  };
  const onDrop = (e) => {
    root.classList.remove('vqsa-dragging');
    const file = e.dataTransfer?.files?.[0];
    if (!file) return;
    e.preventDefault();
    load(file).then(() => root.dataset.state !== 'error' && run(countChosen ? {} : { automatic: true }));
  };
  dropTarget.addEventListener('dragover', onDragOver);
  dropTarget.addEventListener('dragleave', onDragLeave);
  dropTarget.addEventListener('drop', onDrop);

  drawPlot();
  fillTable();
  setState('idle');

  Object.assign(api, {
    element: root,
    load, loadExample, run, cancel,
    get state() { return root.dataset.state; },
    get result() { return result?.reportObject ?? null; },
    destroy() {
      alive = false;
      observer.disconnect();
      controls.dispose();
      renderer.dispose();
      gui.destroy();
      client.terminate();
      dropTarget.removeEventListener('dragover', onDragOver);
      dropTarget.removeEventListener('dragleave', onDragLeave);
      dropTarget.removeEventListener('drop', onDrop);
      root.replaceChildren();
    },
  });

  if (options.src) load(options.src).then(() => root.dataset.state !== 'error' && run());
  else if (options.example) loadExample(options.example).then(() => root.dataset.state !== 'error' && run());
  return api;
}
