// Loads the WASM build under node: the ES module needs its binary handed in, and the
// `require`/`__dirname` its node code path expects.
import { readFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { dirname, join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

export const defaultBuildDir = join(dirname(fileURLToPath(import.meta.url)), '..', '..', 'build', 'wasm', 'wasm');

export async function loadVqsa(buildDir = defaultBuildDir) {
  globalThis.require ??= createRequire(import.meta.url);
  globalThis.__dirname ??= buildDir;
  const { default: createVqsaModule } = await import(pathToFileURL(join(buildDir, 'vqsa.mjs')).href);
  return createVqsaModule({ wasmBinary: readFileSync(join(buildDir, 'vqsa.wasm')) });
}
