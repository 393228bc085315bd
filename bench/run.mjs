// `npm run bench`: vqsa (native and WASM) against the planar VSA peer (CGAL) on the shared
// meshes at the paper's proxy counts, error against proxy count, and scaling with face
// count. Writes bench/RESULTS.md, bench/error_vs_proxies.svg and bench/scaling.svg.
// Expects the builds of scripts/bench-all.sh (native, WASM, CGAL peer).
import { execFileSync, spawnSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { cpus, freemem, tmpdir, totalmem } from 'node:os';
import { dirname, join } from 'node:path';
import { performance } from 'node:perf_hooks';
import { fileURLToPath } from 'node:url';
import { loadVqsa } from '../wasm/node/load.mjs';
import { cancelLatencies, startWorker } from '../tests/node/support.mjs';
import { launchBrowser, startSite } from '../tests/browser/support.mjs';

const root = join(dirname(fileURLToPath(import.meta.url)), '..');
const meshes = process.env.VQSA_MESHES ?? join(root, '..', 'shared', 'meshes');
const native = join(root, 'build', 'native', 'wasm', 'vqsa');
const peer = join(root, 'build', 'bench', 'bench', 'planar_vsa');
const wasmCli = join(root, 'build', 'wasm', 'wasm', 'vqsa-cli.js');
const RUNS = Number(process.env.VQSA_BENCH_RUNS ?? 3);
const work = mkdtempSync(join(tmpdir(), 'vqsa-bench-'));

const paperCases = [
  // mesh, proxies, paper Table 1: Lloyd s, post-processing s (Xeon 2.66 GHz, 2006; their own versions of the meshes)
  ['fandisk.off', 22, 11, 0.017],
  ['bunny_closed.off', 28, 103, 0.352],
  ['mask.off', 6, 203, 0.115],
  ['homer.obj', 61, 148, 0.393],
  ['chess_pawn.stl', 12, 15, 0.1],
  ['csg.off', 10, 16, 0.031],
  ['joint.off', 30, null, null],
  ['rocker_arm.obj', 20, null, null],
];
// Projected RMS at the paper's counts in the bench run of 2026-11-21 (9078a1e), when issue 11
// asked to keep within 5 % of it (fandisk's and joint's then partly from plane pairs).
const rmsIssue11 = { 'fandisk.off': 1.57e-4, 'bunny_closed.off': 2.00e-3, 'mask.off': 3.28e-3, 'homer.obj': 7.80e-4,
  'chess_pawn.stl': 1.65e-3, 'csg.off': 5.09e-3, 'joint.off': 1.40e-4, 'rocker_arm.obj': 1.55e-3 };
const curveCounts = [5, 10, 15, 20, 30, 40, 60, 80, 100];
const scalingFaces = [10000, 40000, 160000, 640000, 1500000];

const median = (values) => [...values].sort((a, b) => a - b)[Math.floor(values.length / 2)];
const e = (x, d = 2) => (x === null || x === undefined ? '—' : x.toExponential(d));
const f = (x, d = 3) => (x === null || x === undefined ? '—' : x.toFixed(d));
const log = (...m) => console.error(...m);

function runNative(input, proxies, extra = []) {
  const report = join(work, 'native.json');
  execFileSync(native, [input, '--proxies', String(proxies), '--quiet', '--report', report, ...extra], { stdio: 'ignore' });
  return JSON.parse(readFileSync(report, 'utf8'));
}

function runPeer(file, proxies, runs) {
  return JSON.parse(execFileSync(peer, [join(meshes, file), String(proxies), String(runs)], { encoding: 'utf8' }));
}

// Peak resident memory (KB) and the report of one CLI run, native or WASM.
function measuredRun(command, args) {
  const report = join(work, 'scaling.json');
  const run = spawnSync('/usr/bin/time', ['-f', '%M', ...command, ...args, '--quiet', '--report', report],
    { encoding: 'utf8', stdio: ['ignore', 'ignore', 'pipe'], maxBuffer: 1 << 24 });
  if (run.status !== 0) throw new Error(`${command.join(' ')} ${args.join(' ')} failed: ${run.stderr.slice(-500)}`);
  return { peakKb: Number(run.stderr.trim().split('\n').pop()), report: JSON.parse(readFileSync(report, 'utf8')) };
}

const vqsa = await loadVqsa();
function runWasm(bytes, name, proxies) {
  const session = new vqsa.Session();
  session.load(bytes, name);
  session.start({ proxies });
  while (session.stepFor(1000)) {}
  const { timing_s: timing } = JSON.parse(session.report());
  session.delete();
  return { lloyd: timing.lloyd, post: timing.postprocess };
}
const stages = ['smooth', 'refit', 'project', 'measure'];
const stageMedians = (reports) => Object.fromEntries(stages.map((s) => [s, median(reports.map((x) => x.timing_s[s]))]));

// ---- 1. the paper's meshes at the paper's counts --------------------------------------------
const rows = [];
runWasm(readFileSync(join(meshes, 'fandisk.off')), 'fandisk.off', 22);  // V8 tiers the module up on a first run
for (const [file, proxies, paperLloyd, paperPost] of paperCases) {
  log(`table: ${file}/${proxies}`);
  // Native, WASM and the peer take turns (the load of a shared machine drifts over minutes).
  const bytes = readFileSync(join(meshes, file));
  const reports = [], wasm = [], peers = [];
  for (let i = 0; i < RUNS; ++i) {
    reports.push(runNative(join(meshes, file), proxies));
    wasm.push(runWasm(bytes, file, proxies));
    peers.push(runPeer(file, proxies, 1));
  }
  const planar = { ...peers[0], vsa_s: median(peers.map((p) => p.vsa_s)), meshing_s: median(peers.map((p) => p.meshing_s)) };
  const r = reports[0];
  const types = {};
  for (const p of r.proxies) types[p.type] = (types[p.type] ?? 0) + 1;
  rows.push({
    file, proxies, faces: r.input.faces,
    lloyd: median(reports.map((x) => x.timing_s.lloyd)), post: median(reports.map((x) => x.timing_s.postprocess)),
    total: median(reports.map((x) => x.timing_s.lloyd + x.timing_s.postprocess)),
    wasmLloyd: median(wasm.map((w) => w.lloyd)), wasmTotal: median(wasm.map((w) => w.lloyd + w.post)),
    stages: stageMedians(reports), samples: r.metrics.samples,
    rms: r.metrics.rms, hausdorff: r.metrics.hausdorff, planar, paperLloyd, paperPost,
    types: Object.entries(types).sort((a, b) => b[1] - a[1]).map(([t, n]) => `${n} ${t.replaceAll('_', ' ')}`).join(', '),
  });
}

// ---- 1b. post-processing: CAD-like parts of crank size, WASM cold and warm, cancel ----------
const crankCases = [['example:flange:100000', 7], ['example:flange:100000', 50], ['example:turned_part:100000', 50]];
const crankRows = crankCases.map(([input, proxies]) => {
  log(`post-processing: ${input}/${proxies}`);
  const reports = Array.from({ length: RUNS }, () => runNative(input, proxies));
  return { file: input.slice(8), proxies, faces: reports[0].input.faces, lloyd: median(reports.map((x) => x.timing_s.lloyd)),
    post: median(reports.map((x) => x.timing_s.postprocess)), stages: stageMedians(reports), samples: reports[0].metrics.samples };
});
// Whole pipeline (Lloyd and post-processing, not reading): cold is the first run of a fresh
// process (the CLI's case: V8 compiles functions lazily and runs them unoptimised at first),
// warm a later run in the same process. Native, cold and warm take turns, so that the load of
// a shared machine, which drifts over minutes, weighs on the three alike.
const wasmColdWarm = [['fandisk.off', 22], ['bunny_closed.off', 28]].map(([file, proxies]) => {
  log(`WASM cold/warm: ${file}`);
  const pipeline = (t) => t.lloyd + t.postprocess;
  const bytes = readFileSync(join(meshes, file));
  const native = [], cold = [], warm = [];
  for (let i = 0; i < Math.max(RUNS, 5); ++i) {
    native.push(pipeline(runNative(join(meshes, file), proxies).timing_s));
    cold.push(pipeline(measuredRun([process.execPath, wasmCli], [join(meshes, file), '--proxies', String(proxies)]).report.timing_s));
    const w = runWasm(bytes, file, proxies);
    warm.push(w.lloyd + w.post);
  }
  return { file, proxies, native: median(native), cold: median(cold), warm: median(warm) };
});
log('cancel latency');
const worker = startWorker();
await worker.request({ type: 'example', name: 'flange:100000' });
const cancelRuns = [];
for (let i = 0; i < RUNS; ++i) cancelRuns.push(await cancelLatencies(worker, { proxies: 7 }));
worker.terminate();
const cancelMs = Object.fromEntries(Object.keys(cancelRuns[0]).map((stage) => [stage, median(cancelRuns.map((r) => r[stage]))]));

// ---- 2. error against proxy count -------------------------------------------------------------
const curves = {};
for (const file of ['fandisk.off', 'bunny_closed.off']) {
  curves[file] = { vqsa: [], planar: [] };
  for (const n of curveCounts) {
    log(`curve: ${file}/${n}`);
    curves[file].vqsa.push([n, runNative(join(meshes, file), n).metrics.rms]);
    curves[file].planar.push([n, runPeer(file, n, 1).rms]);
  }
}
const reach = (points, target) => points.find(([, rms]) => rms <= target)?.[0] ?? null;

// ---- 3. scaling -----------------------------------------------------------------------------
const scaling = [];
for (const faces of scalingFaces) {
  log(`scaling: ${faces}`);
  const input = `example:turned_part:${faces}`;
  const runs = faces <= 160000 ? RUNS : 1;
  const n = Array.from({ length: runs }, () => measuredRun([native], [input, '--proxies', '50']));
  const w = Array.from({ length: runs }, () => measuredRun([process.execPath, wasmCli], [input, '--proxies', '50']));
  scaling.push({
    faces: n[0].report.input.faces, runs,
    nativeLloyd: median(n.map((x) => x.report.timing_s.lloyd)), nativeTotal: median(n.map((x) => x.report.timing_s.total)),
    nativeMb: median(n.map((x) => x.peakKb)) / 1024,
    wasmLloyd: median(w.map((x) => x.report.timing_s.lloyd)), wasmTotal: median(w.map((x) => x.report.timing_s.total)),
    wasmMb: median(w.map((x) => x.peakKb)) / 1024,
  });
}
// The largest point in headless Chromium, as the app runs it: the worker builds the part,
// then runs it to its result (Lloyd, post-processing, the result's arrays and report).
log('scaling: 1.5M faces in Chromium');
const site = await startSite();
const browser = await launchBrowser();
const page = await browser.newPage();
page.setDefaultTimeout(300000);
await page.goto(`${site.url}/test/worker-page.html`);
await page.waitForFunction(() => window.ready);
const chromium = await page.evaluate(async (faces) => {
  const client = new window.VqsaClient();
  await client.loadExample(`turned_part:${faces}`);
  const t0 = performance.now();
  const result = await client.run({ proxies: 50 });
  const seconds = (performance.now() - t0) / 1000;
  client.terminate();
  const { timing_s: t } = JSON.parse(result.report);
  return { seconds, lloyd: t.lloyd, post: t.postprocess };
}, scalingFaces.at(-1));
await browser.close();
site.server.close();

// Least-squares slope of log(time) against log(faces).
function exponent(key) {
  const xs = scaling.map((s) => Math.log(s.faces)), ys = scaling.map((s) => Math.log(s[key]));
  const mx = xs.reduce((a, b) => a + b) / xs.length, my = ys.reduce((a, b) => a + b) / ys.length;
  return xs.reduce((a, x, i) => a + (x - mx) * (ys[i] - my), 0) / xs.reduce((a, x) => a + (x - mx) ** 2, 0);
}

// ---- 4. where the Lloyd time goes, on the mesh furthest behind the peer --------------------
let profile = null;
const behind = [...rows].sort((a, b) => b.lloyd / b.planar.vsa_s - a.lloyd / a.planar.vsa_s)[0];
const perfOk = spawnSync('perf', ['stat', '-e', 'task-clock', 'true'], { stdio: 'ignore' }).status === 0;
if (perfOk && behind.lloyd > behind.planar.vsa_s) {
  log(`profile: ${behind.file}`);
  const data = join(work, 'perf.data');
  spawnSync('perf', ['record', '-o', data, '-F', '2000', '-g', native, join(meshes, behind.file), '--proxies', String(behind.proxies),
    '--quiet', '--no-smooth', '--no-refit', '--no-project'], { stdio: 'ignore' });
  const report = spawnSync('perf', ['report', '-i', data, '--no-children', '--stdio', '--percent-limit', '2'], { encoding: 'utf8' }).stdout;
  profile = { mesh: behind, lines: report.split('\n').filter((l) => /^\s+\d+\.\d+%/.test(l)).map((l) => l.trim().replace(/\s+/g, ' ')) };
}

// ---- charts ---------------------------------------------------------------------------------
function chart({ title, xLabel, yLabel, series, logX = false }) {
  const w = 560, h = 340, l = 70, r = 150, t = 34, b = 46;
  const all = series.flatMap((s) => s.points);
  const xs = all.map(([x]) => (logX ? Math.log10(x) : x)), ys = all.map(([, y]) => Math.log10(y));
  const x0 = Math.min(...xs), x1 = Math.max(...xs), y0 = Math.floor(Math.min(...ys)), y1 = Math.ceil(Math.max(...ys));
  const X = (x) => l + ((logX ? Math.log10(x) : x) - x0) / (x1 - x0) * (w - l - r);
  const Y = (y) => t + (y1 - Math.log10(y)) / (y1 - y0) * (h - t - b);
  const parts = [`<svg xmlns="http://www.w3.org/2000/svg" width="${w}" height="${h}" font-family="sans-serif" font-size="12">`,
    `<rect width="${w}" height="${h}" fill="white"/>`, `<text x="${l}" y="20" font-size="14" font-weight="bold">${title}</text>`,
    `<rect x="${l}" y="${t}" width="${w - l - r}" height="${h - t - b}" fill="none" stroke="#999"/>`];
  for (let p = y0; p <= y1; ++p)
    parts.push(`<line x1="${l}" x2="${w - r}" y1="${Y(10 ** p)}" y2="${Y(10 ** p)}" stroke="#eee"/>`,
      `<text x="${l - 6}" y="${Y(10 ** p) + 4}" text-anchor="end">1e${p}</text>`);
  const ticks = [...new Set(all.map(([x]) => x))];
  for (const x of ticks) parts.push(`<text x="${X(x)}" y="${h - b + 16}" text-anchor="middle">${x >= 1e6 ? `${(x / 1e6).toFixed(1)}M` : x >= 1e3 ? `${Math.round(x / 1e3)}K` : x}</text>`);
  parts.push(`<text x="${(l + w - r) / 2}" y="${h - 8}" text-anchor="middle">${xLabel}</text>`,
    `<text x="16" y="${(t + h - b) / 2}" text-anchor="middle" transform="rotate(-90 16 ${(t + h - b) / 2})">${yLabel}</text>`);
  series.forEach((s, i) => {
    parts.push(`<polyline fill="none" stroke="${s.colour}" stroke-width="2" ${s.dashed ? 'stroke-dasharray="6 4"' : ''} points="${s.points.map(([x, y]) => `${X(x)},${Y(y)}`).join(' ')}"/>`);
    for (const [x, y] of s.points) parts.push(`<circle cx="${X(x)}" cy="${Y(y)}" r="3" fill="${s.colour}"/>`);
    parts.push(`<line x1="${w - r + 12}" x2="${w - r + 36}" y1="${t + 14 + 18 * i}" y2="${t + 14 + 18 * i}" stroke="${s.colour}" stroke-width="2" ${s.dashed ? 'stroke-dasharray="6 4"' : ''}/>`,
      `<text x="${w - r + 42}" y="${t + 18 + 18 * i}">${s.name}</text>`);
  });
  parts.push('</svg>');
  return parts.join('\n');
}

writeFileSync(join(root, 'bench', 'error_vs_proxies.svg'), chart({
  title: 'Symmetric RMS error / bbox diagonal against proxy count', xLabel: 'proxies', yLabel: 'RMS / diagonal',
  series: [
    { name: 'vqsa fandisk', colour: '#2864c8', points: curves['fandisk.off'].vqsa },
    { name: 'planar fandisk', colour: '#2864c8', dashed: true, points: curves['fandisk.off'].planar },
    { name: 'vqsa bunny', colour: '#d0561b', points: curves['bunny_closed.off'].vqsa },
    { name: 'planar bunny', colour: '#d0561b', dashed: true, points: curves['bunny_closed.off'].planar },
  ],
}));
writeFileSync(join(root, 'bench', 'scaling.svg'), chart({
  title: 'Time against face count (turned part, 50 proxies)', xLabel: 'faces', yLabel: 'seconds', logX: true,
  series: [
    { name: 'native Lloyd', colour: '#2864c8', points: scaling.map((s) => [s.faces, s.nativeLloyd]) },
    { name: 'native total', colour: '#2864c8', dashed: true, points: scaling.map((s) => [s.faces, s.nativeTotal]) },
    { name: 'WASM Lloyd', colour: '#d0561b', points: scaling.map((s) => [s.faces, s.wasmLloyd]) },
    { name: 'WASM total', colour: '#d0561b', dashed: true, points: scaling.map((s) => [s.faces, s.wasmTotal]) },
  ],
}));

// ---- RESULTS.md -----------------------------------------------------------------------------
const machine = `${cpus().length} × ${cpus()[0].model}, ${(totalmem() / 1024 ** 3).toFixed(0)} GiB (${(freemem() / 1024 ** 3).toFixed(0)} free), node ${process.version}`;
const lines = [];
const row = (cells) => lines.push(`| ${cells.join(' | ')} |`);
lines.push('# vqsa benchmark results', '',
  `Written by \`npm run bench\` on ${new Date().toISOString().slice(0, 10)}, machine: ${machine}.`,
  `Times are medians of ${RUNS} runs (the scaling rows above 160K faces: one run), the compared programs run in turn; errors are deterministic.`,
  'The planar VSA peer is CGAL 5.5 `Variational_shape_approximation` (L21 metric, hierarchical seeding, 20',
  'iterations; Debian libcgal-dev, installed by the benchmark only) through `bench/planar_vsa.cpp`; its output mesh',
  '(anchors and triangles) is measured with vqsa\'s own metric code. Errors: symmetric RMS and Hausdorff distance',
  'between the input and the approximating surface (vqsa: the projected mesh) over the input\'s bounding-box diagonal.', '',
  '## 1. The paper\'s models and proxy counts', '',
  'Reproduce: `npm run bench` (all of this file) — or one row: `npm run cli -- ../shared/meshes/fandisk.off --proxies 22 --report r.json`',
  'and `build/bench/bench/planar_vsa ../shared/meshes/fandisk.off 22 3`.', '');
row(['mesh', 'faces', 'proxies', 'vqsa Lloyd s', 'post s', 'total s', 'WASM Lloyd s', 'WASM/native', 'planar VSA s', 'Lloyd / planar', 'paper Lloyd s (2006)',
  'vqsa RMS', 'vqsa Hausdorff', 'planar RMS', 'planar Hausdorff', 'RMS vqsa / planar', 'types found']);
row(Array(17).fill('---'));
for (const r of rows) {
  row([r.file, r.faces, r.proxies, f(r.lloyd), f(r.post), f(r.total), f(r.wasmLloyd), f(r.wasmLloyd / r.lloyd, 2),
    f(r.planar.vsa_s), f(r.lloyd / r.planar.vsa_s, 2), r.paperLloyd ?? '—', e(r.rms), e(r.hausdorff), e(r.planar.rms),
    e(r.planar.hausdorff), f(r.rms / r.planar.rms, 3), r.types]);
}
const slower = rows.filter((r) => r.lloyd > r.planar.vsa_s);
const errorMisses = rows.filter((r) => r.rms > (r.file === 'fandisk.off' ? 1.0e-3 : r.planar.rms / 5));
const wasmMisses = rows.filter((r) => r.wasmLloyd / r.lloyd > 1.6);
const keptMisses = rows.filter((r) => r.rms > 1.05 * rmsIssue11[r.file]);
const percent = (x) => `${x >= 0 ? '+' : '−'}${f(Math.abs(100 * x), 0)} %`;
lines.push('', '**Targets.**',
  `- Lloyd stage no slower than the planar peer: ${slower.length ? `missed on ${slower.map((r) => `${r.file} (${f(r.lloyd / r.planar.vsa_s, 2)}×)`).join(', ')}` : 'met on every mesh'}.`,
  `- Projected RMS at most one fifth of the peer's (fandisk/22 ≤ 1.0e-3): ${errorMisses.length ? `missed on ${errorMisses.map((r) => `${r.file} (${f(r.rms / r.planar.rms, 2)} of the peer's)`).join(', ')}` : 'met on every mesh'}.`,
  `- WASM/native ≤ 1.6 (warm module): ${wasmMisses.length ? `missed on ${wasmMisses.map((r) => r.file).join(', ')}` : 'met on every mesh'}.`,
  `- Projected RMS within 5 % of its figure when issue 11 was opened (2026-11-21): ${keptMisses.length ? `missed on ${keptMisses.map((r) => `${r.file} (${percent(r.rms / rmsIssue11[r.file] - 1)})`).join(', ')}` : 'met on every mesh'}. ` +
    'Free-form RMS at a count is one draw of Lloyd\'s minima: measured 2026-11-29 over seeds 1–8, homer/61 spans 6.4–8.4e-4 ' +
    '(median 7.5e-4) and rocker_arm/20 1.45–1.70e-3 (seed 1, the table\'s, is the worst of the eight on homer and the third best on rocker_arm); with `--init paper`, 7.13e-4 and 1.69e-3 at every seed.',
  '', 'The paper\'s times are for its own (larger) versions of these models on a 2006 Xeon: a reference, not a comparison.', '');
lines.push('### Post-processing', '',
  'Native, medians; the stages\' seconds, and the samples the measurement chose for a 0.5 % standard error of the RMS',
  '(both surfaces). The flange (planes and cylinders) and the turned part are procedural CAD-like parts at crank size.',
  'Reproduce: `npm run cli -- example:flange:100000 --proxies 7 --report r.json` (`timing_s`, `metrics.samples`).', '');
row(['mesh', 'faces', 'proxies', 'Lloyd s', 'post s', 'post / Lloyd', 'smooth s', 'refit s', 'project s', 'measure s', 'samples']);
row(Array(11).fill('---'));
for (const r of [...rows, ...crankRows])
  row([r.file, r.faces, r.proxies, f(r.lloyd), f(r.post), f(r.post / r.lloyd, 2), ...stages.map((s) => f(r.stages[s])), r.samples]);
const postMisses = [...rows, ...crankRows].filter((r) => r.post > r.lloyd);
lines.push('', `- Post-processing ≤ the Lloyd stage: ${postMisses.length ? `missed on ${postMisses.map((r) => `${r.file}/${r.proxies} (${f(r.post / r.lloyd, 2)}×)`).join(', ')}` : 'met on every mesh'}.`, '');
row(['WASM, whole pipeline', 'native s', 'WASM cold s', 'cold / native', 'WASM warm s', 'warm / native']);
row(Array(6).fill('---'));
for (const w of wasmColdWarm)
  row([`${w.file}/${w.proxies}`, f(w.native), f(w.cold), f(w.cold / w.native, 2), f(w.warm), f(w.warm / w.native, 2)]);
const ratioTarget = (key, limit) => {
  const misses = wasmColdWarm.filter((w) => w[key] / w.native > limit);
  return `${key} ≤ ${limit}: ${misses.length ? `missed on ${misses.map((w) => `${w.file}/${w.proxies} (${f(w[key] / w.native, 3)})`).join(', ')}` : 'met'}`;
};
lines.push('', `Targets: ${ratioTarget('warm', 1.3)}; ${ratioTarget('cold', 1.6)}.`,
  'Cold: `npm run cli:wasm` (a fresh node process per run); warm: the second and later runs of one module (the app\'s worker keeps it). ' +
  `Medians of ${Math.max(RUNS, 5)} rounds, native, cold and warm in turn.`, '',
  `Cancel latency, from the cancel message to the worker's \`cancelled\`, sent at the first progress event of each stage of a`,
  `run on flange:100000/7 (the app's worker in a node worker thread, \`tests/node/worker.test.mjs\`; median of ${RUNS}):`,
  Object.entries(cancelMs).map(([stage, ms]) => `${stage} ${ms === null ? '—' : `${ms.toFixed(0)} ms`}`).join(', ') +
  ` (target ≤ 100 ms: ${Object.values(cancelMs).every((ms) => ms !== null && ms <= 100) ? 'met' : 'missed'}).`, '');
if (profile) {
  lines.push(`**Where the Lloyd time goes** on ${profile.mesh.file}/${profile.mesh.proxies}, the mesh furthest behind the peer ` +
    `(\`perf record\` of \`vqsa ${profile.mesh.file} --proxies ${profile.mesh.proxies} --no-smooth --no-refit --no-project\`, self time ≥ 2 %):`, '', '```',
  ...profile.lines, '```', '',
  'The Lloyd stage grows the partition one batch of proxies at a time and floods the whole mesh at every iteration',
  '(distortion-minimising flooding: a heap ordered by Taubin errors, each face evaluated against every region that reaches',
  'it), so its cost is about (iterations × faces); the peer seeds all proxies hierarchically, then runs 20 iterations.',
  'Flooding (heap and error evaluation) and the per-iteration evaluation of every face against its proxy dominate; the',
  'moment sums and the 9×9 eigenproblems of the fits are a few per cent. Flooding anew only the regions whose faces or',
  'quadric changed, and their neighbours, does not pay: on the free-form meshes every region\'s boundary moves by 1–10 % of',
  'its area at every iteration until the stage stops, so 93–100 % of the faces would be flooded again (40–90 % on fandisk',
  'and joint; measured 2026-11-23). Nor does cutting the growth short: with each Lloyd stage below the count capped at',
  'two iterations (one), bunny/28 took 65 iterations instead of 112, but fandisk/22\'s RMS rose 22 % (46 %) and homer/61',
  'took 128 instead of 114: the partition the growth ends in moves to other minima, as with larger insertion batches',
  '(measured 2026-11-25). Nor do stages local to an operation: at the count, 40–60 % of the iterations follow',
  'splits, merges, teleports and repairs (fandisk/22 51 of 91, bunny/28 67 of 112, homer/61 44 of 114). Flooding',
  'after each of them only the regions it changed and their neighbours (one ring; two) cut bunny/28\'s Lloyd stage 1.28',
  '→ 1.05 s (0.85 s) but left the partitions in worse minima: fandisk/22 RMS +292 % (+44 %), mask/6 +101 % (+26 %),',
  'homer/61 +21 % (+32 %), chess_pawn/12 +295 % (+295 %), rocker_arm/20 +20 % (+11 %), csg/10 −13 % (−13 %): fewer',
  'teleports paid, judged by an energy that could only fall locally (measured 2026-11-25).', '',
  'Per iteration vqsa is now the faster: on homer/61 the peer\'s 0.137 s cover about 50 iterations (five after each',
  'doubling of the count, then 20), 2.7 ms each; vqsa\'s iterations take 1.7 ms, 2.1 ms with the operations between',
  'them, but the stage makes 120. Since 2026-11-28 a face is queued only under a key below every key it had, so the',
  'heap holds 8-byte keys and each face one record (bunny/28 −16 %, fandisk/22 −9 %, homer/61 −8 %, labels identical).',
  'Faces in the order of the file also cost: bunny_closed.off\'s neighbours lie 1 % of the time within 64 faces of each',
  'other in memory (fandisk.off 79 %), and the same bunny with its faces in breadth-first order takes 19 % less per',
  'iteration; the labels would change (ties go by face index), so the model keeps the file\'s order.',
  'Nor do other stage lengths pay, judged over eight seeds (the RMS of one seed is one draw: the Lloyd stage\'s RMS over',
  'seeds 1–8 spans 3.0–4.8e-4 on fandisk/22, 0.98–3.6e-3 on chess_pawn/12, 3.4–5.5e-3 on mask/6, 1.02–1.23e-3 on',
  'homer/61; seed 1, the one the table shows, is the best of the eight on fandisk and chess_pawn and near the worst on',
  'homer). Medians over the eight seeds:',
  'insertion batches of half the count, or doubling as the peer does, saved 3–20 % of the stage on five meshes but',
  'raised mask/6\'s RMS 14–25 % and csg/10\'s 20 % (doubling); one or two iterations after a split or a teleport before',
  'the merge that follows it saved 3–22 % and raised fandisk/22\'s RMS 20 % and chess_pawn/12\'s 84 % (measured',
  '2026-11-28). A teleport as the peer makes it, the cheapest merge made with the insertion and one Lloyd stage',
  'after both instead of one after each, saved 11–34 % of the stage on six meshes but raised fandisk/22\'s RMS 99 %,',
  'chess_pawn/12\'s 84 % and mask/6\'s 41 % (bunny/28 10 %, homer/61 8 %): fewer teleports paid, and the first that',
  'does not ends them (measured 2026-11-28, later).', '');
}
lines.push(
  '## 2. Error against proxy count', '',
  'Reproduce: `npm run bench` (vqsa with default options; the peer as above, one run each).', '',
  '![error against proxy count](error_vs_proxies.svg)', '');
row(['proxies', ...curveCounts]);
row(Array(curveCounts.length + 1).fill('---'));
for (const file of Object.keys(curves)) {
  row([`vqsa ${file}`, ...curves[file].vqsa.map(([, v]) => e(v))]);
  row([`planar ${file}`, ...curves[file].planar.map(([, v]) => e(v))]);
}
lines.push('');
for (const file of Object.keys(curves)) {
  const a = reach(curves[file].vqsa, 2e-3), b = reach(curves[file].planar, 2e-3);
  lines.push(`- ${file}: RMS ≤ 2e-3 needs ${a ?? `more than ${curveCounts.at(-1)}`} proxies with vqsa, ${b ?? `more than ${curveCounts.at(-1)}`} with planar VSA (first count of the list that reaches it).`);
}
lines.push('', '## 3. Scaling', '',
  'A procedural turned part (`example:turned_part:FACES`, planes, cylinders, a cone and a sphere) at growing',
  'resolution, 50 proxies, default options. Reproduce one point: `/usr/bin/time -f %M npm run cli -- example:turned_part:1500000 --proxies 50`',
  'and the same with `npm run cli:wasm` (node 20; a fresh process per run, so WASM includes compiling the module).', '',
  '![time against face count](scaling.svg)', '');
row(['faces', 'runs', 'native Lloyd s', 'native total s', 'native peak MB', 'WASM Lloyd s', 'WASM total s', 'WASM peak MB', 'WASM/native total']);
row(Array(9).fill('---'));
for (const s of scaling)
  row([s.faces, s.runs, f(s.nativeLloyd), f(s.nativeTotal), f(s.nativeMb, 0), f(s.wasmLloyd), f(s.wasmTotal), f(s.wasmMb, 0), f(s.wasmTotal / s.nativeTotal, 2)]);
const big = scaling.at(-1);
lines.push('', `Fitted growth exponents (time ∝ F^k over 10K–1.5M faces): native Lloyd k = ${f(exponent('nativeLloyd'), 2)}, native total k = ${f(exponent('nativeTotal'), 2)}, ` +
  `WASM Lloyd k = ${f(exponent('wasmLloyd'), 2)}, WASM total k = ${f(exponent('wasmTotal'), 2)}. O(F log F) over this range corresponds to k ≈ 1.1.`,
  `1.5M faces to 50 proxies in WASM: ${f(big.wasmTotal, 1)} s in all (${big.wasmTotal < 60 ? 'under' : 'over'} the one-minute target).`,
  `In headless Chromium (the app's worker, one run, from the run request to its result): ${f(chromium.seconds, 1)} s ` +
  `(Lloyd ${f(chromium.lloyd, 1)} s, post-processing ${f(chromium.post, 1)} s; target ≤ 25 s: ${chromium.seconds <= 25 ? 'met' : 'missed'}).`, '');
// Sections 4 and on (CAD extraction, `npm run bench:cad`) are written by hand from their own
// benchmark: kept as they are.
const previous = readFileSync(join(root, 'bench', 'RESULTS.md'), 'utf8');
const kept = previous.indexOf('\n## 4.');
writeFileSync(join(root, 'bench', 'RESULTS.md'), lines.join('\n') + (kept >= 0 ? previous.slice(kept) : ''));
rmSync(work, { recursive: true, force: true });
log('wrote bench/RESULTS.md, bench/error_vs_proxies.svg, bench/scaling.svg');
