// `npm run bench:edit`: how long each edit takes on 100K-face parts, natively (the CLI's
// --edits, the report's timing_s.edits) and in the app's worker (WASM in a node worker
// thread: request to result, the result's arrays and GLB included). Writes section 6 of
// bench/RESULTS.md.
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { performance } from 'node:perf_hooks';
import { fileURLToPath } from 'node:url';
import { startWorker } from '../tests/node/support.mjs';

const root = join(dirname(fileURLToPath(import.meta.url)), '..');
const native = join(root, 'build', 'native', 'wasm', 'vqsa');
const RUNS = Number(process.env.VQSA_BENCH_RUNS ?? 3);
const work = mkdtempSync(join(tmpdir(), 'vqsa-edits-'));
const median = (values) => [...values].sort((a, b) => a - b)[Math.floor(values.length / 2)];
const cases = [['flange:100000', 7], ['turned_part:100000', 50]];

// The edits: a split at the worst face of the largest region, the new region merged back,
// a general quadric imposed on the second largest, a seed in the third largest, a lock.
function editsFor(report) {
  const bySize = report.proxies.map((p) => p.id).sort((a, b) => report.proxies[b].faces - report.proxies[a].faces);
  const [first, second, third] = bySize;
  const n = report.proxies.length;
  return [
    { op: 'split', region: first },
    { op: 'merge', regions: [first, n] },
    { op: 'set_type', region: second, type: 'quadric' },
    { op: 'add_seed', face: report.labels.findIndex((l) => l === third) },
    { op: 'lock', region: third },
  ];
}

const rows = [];
const worker = startWorker();
for (const [example, proxies] of cases) {
  console.error(`edits: ${example}/${proxies}`);
  const plain = join(work, 'plain.json'), edited = join(work, 'edited.json'), file = join(work, 'edits.json');
  execFileSync(native, [`example:${example}`, '--proxies', String(proxies), '--quiet', '--report', plain]);
  const before = JSON.parse(readFileSync(plain, 'utf8'));
  const edits = editsFor(before);
  writeFileSync(file, JSON.stringify(edits));
  const nativeRuns = Array.from({ length: RUNS }, () => {
    execFileSync(native, [`example:${example}`, '--proxies', String(proxies), '--quiet', '--edits', file, '--report', edited]);
    return JSON.parse(readFileSync(edited, 'utf8')).timing_s.edits;
  });
  await worker.request({ type: 'example', name: example });
  const workerRuns = [];
  for (let run = 0; run < RUNS; ++run) {
    // The worker's result is the native one (same labels), so the same edits apply.
    await worker.request({ type: 'run', options: { proxies } });
    const seconds = [];
    for (const request of [...edits.map((edit) => ({ type: 'edit', edit })), { type: 'undo' }, { type: 'redo' }]) {
      const start = performance.now();
      const reply = await worker.request(request);
      if (reply.type !== 'result') throw new Error(`${JSON.stringify(request)}: ${reply.message}`);
      seconds.push((performance.now() - start) / 1000);
    }
    workerRuns.push(seconds);
  }
  const ops = [...edits.map((e) => e.op), 'undo', 'redo'];
  ops.forEach((op, i) => rows.push({
    mesh: `${example}/${proxies}`, faces: before.input.faces, op,
    native: i < edits.length ? median(nativeRuns.map((r) => r[i])) : null, worker: median(workerRuns.map((r) => r[i])),
  }));
}
worker.terminate();

const f = (x) => (x === null ? '—' : x.toFixed(3));
const slowest = Math.max(...rows.map((r) => Math.max(r.native ?? 0, r.worker)));
const section = ['## 6. Edits', '',
  `Written by \`npm run bench:edit\` on ${new Date().toISOString().slice(0, 10)}; medians of ${RUNS}. Each edit on the result of a run:`,
  'native, the seconds the CLI reports for it (`npm run cli -- example:flange:100000 --proxies 7 --edits e.json --report r.json`,',
  '`timing_s.edits`: the local Lloyd and the post-processing of the regions it touches, projection and measurement of the whole',
  'mesh); worker, from the request to the result in the app\'s worker under node (WASM; the result\'s arrays and its GLB included).', '',
  'The edits: a split of the largest region at its worst face, the new region merged back, a general quadric imposed on',
  'the second largest, a seed in the third largest, a lock; then, in the worker, an undo and a redo.', '',
  '| mesh | faces | edit | native s | worker (WASM) s |', '| --- | --- | --- | --- | --- |',
  ...rows.map((r) => `| ${r.mesh} | ${r.faces} | \`${r.op}\` | ${f(r.native)} | ${f(r.worker)} |`), '',
  `Target: every edit of a 100K-face mesh under 1 s: ${slowest < 1 ? 'met' : 'missed'} (slowest ${slowest.toFixed(2)} s).`, ''];
const path = join(root, 'bench', 'RESULTS.md');
const previous = readFileSync(path, 'utf8');
const start = previous.indexOf('\n## 6. Edits');
const end = start < 0 ? -1 : previous.indexOf('\n## ', start + 1);
const text = start < 0 ? `${previous.trimEnd()}\n\n${section.join('\n')}`
  : `${previous.slice(0, start)}\n${section.join('\n')}${end < 0 ? '' : previous.slice(end)}`;
writeFileSync(path, text.endsWith('\n') ? text : `${text}\n`);
rmSync(work, { recursive: true, force: true });
console.log(section.join('\n'));
