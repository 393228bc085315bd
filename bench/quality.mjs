// Projected-surface error at the paper's proxy counts, smoothing on and off, against
// the planar VSA figures measured on this machine (issue 3). Prints a Markdown table.
// Usage: node bench/quality.mjs [MESH_DIR]   (after a native build)
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = join(dirname(fileURLToPath(import.meta.url)), '..');
const meshes = process.argv[2] ?? join(root, '..', 'shared', 'meshes');
const cli = join(root, 'build', 'native', 'wasm', 'vqsa');
// Planar VSA (CGAL, L21, 20 iterations), symmetric RMS / bbox diagonal, from the issue.
const cases = [
  ['fandisk.off', 22, 1.27e-2],
  ['bunny_closed.off', 28, 9.9e-3],
  ['mask.off', 6, 1.2e-2],
  ['homer.obj', 61, 8.7e-3],
  ['joint.off', 30, 8.8e-3],
  ['rocker_arm.obj', 20, 1.7e-2],
  ['chess_pawn.stl', 12, 4.4e-2],
];

const work = mkdtempSync(join(tmpdir(), 'vqsa-quality-'));
const run = (file, proxies, extra) => {
  const report = join(work, 'report.json');
  execFileSync(cli, [join(meshes, file), '--proxies', String(proxies), '--quiet', '--report', report, ...extra]);
  return JSON.parse(readFileSync(report, 'utf8'));
};
const e = (x) => x.toExponential(2);

console.log('| mesh | faces | proxies | planar VSA | target (≤ planar/5) | vqsa smoothed | hausdorff | vqsa unsmoothed | met | Lloyd s | post s | types |');
console.log('|---|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|---|');
for (const [file, proxies, planar] of cases) {
  const on = run(file, proxies, []);
  const off = run(file, proxies, ['--no-smooth']);
  const target = file === 'fandisk.off' ? 1.0e-3 : planar / 5;
  const types = {};
  for (const p of on.proxies) types[p.type] = (types[p.type] ?? 0) + 1;
  const typeList = Object.entries(types).map(([t, n]) => `${n} ${t}`).join(', ');
  console.log(`| ${file} | ${on.input.faces} | ${proxies} | ${e(planar)} | ${e(target)} | ${e(on.metrics.rms)} | ` +
    `${e(on.metrics.hausdorff)} | ${e(off.metrics.rms)} | ${on.metrics.rms <= target ? 'yes' : 'no'} | ` +
    `${on.timing_s.lloyd.toFixed(3)} | ${on.timing_s.postprocess.toFixed(3)} | ${typeList} |`);
}
rmSync(work, { recursive: true, force: true });
