// WASM/native speed of the Lloyd stage on fandisk/22 and bunny_closed/28 (issue 5), and
// the size of the module. One run each; the first WASM run of a process ("cold") pays
// for V8's tiered compilation, so it is reported apart. Usage: node bench/wasm_bench.mjs [MESH_DIR]
import { execFileSync } from 'node:child_process';
import { readFileSync, statSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { performance } from 'node:perf_hooks';
import { fileURLToPath } from 'node:url';
import { gzipSync } from 'node:zlib';
import { defaultBuildDir, loadVqsa } from '../wasm/node/load.mjs';

const root = join(dirname(fileURLToPath(import.meta.url)), '..');
const meshes = process.argv[2] ?? join(root, '..', 'shared', 'meshes');
const vqsa = await loadVqsa();

function wasmLloyd(file, proxies) {
  const session = new vqsa.Session();
  session.load(readFileSync(join(meshes, file)), file);
  const t0 = performance.now();
  session.start({ proxies, smooth: false, refit: false, project: false });
  while (session.stepFor(1000)) {}
  const seconds = (performance.now() - t0) / 1000;
  session.delete();
  return seconds;
}

const native = execFileSync(join(root, 'build', 'native', 'bench', 'vqsa_bench'), [meshes, '1'], { encoding: 'utf8' });
const nativeSeconds = Object.fromEntries(native.trim().split('\n').slice(1).map((l) => {
  const c = l.trim().split(/\s+/);
  return [c[0], Number(c[3])];
}));

const cold = wasmLloyd('fandisk.off', 22);
console.log('| mesh | proxies | native s | WASM s | WASM/native |');
console.log('|---|---:|---:|---:|---:|');
console.log(`| fandisk.off (cold: first call) | 22 | ${nativeSeconds['fandisk.off'].toFixed(3)} | ${cold.toFixed(3)} | ${(cold / nativeSeconds['fandisk.off']).toFixed(2)} |`);
for (const [file, proxies] of [['fandisk.off', 22], ['bunny_closed.off', 28]]) {
  const w = wasmLloyd(file, proxies), n = nativeSeconds[file];
  console.log(`| ${file} | ${proxies} | ${n.toFixed(3)} | ${w.toFixed(3)} | ${(w / n).toFixed(2)} |`);
}
const wasm = readFileSync(join(defaultBuildDir, 'vqsa.wasm'));
console.log(`\nvqsa.wasm: ${(statSync(join(defaultBuildDir, 'vqsa.wasm')).size / 1024).toFixed(0)} KiB raw, ` +
  `${(gzipSync(wasm, { level: 9 }).length / 1024).toFixed(0)} KiB gzipped`);
