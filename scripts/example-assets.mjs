// Writes the example meshes that come from npm packages into the site: the Stanford
// bunny of the `bunny` package as dist/examples/bunny.off.
import { mkdirSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { join } from 'node:path';

const out = process.argv[2];
const bunny = createRequire(import.meta.url)('bunny');
const lines = ['OFF', `${bunny.positions.length} ${bunny.cells.length} 0`];
for (const p of bunny.positions) lines.push(p.join(' '));
for (const c of bunny.cells) lines.push(`3 ${c.join(' ')}`);
mkdirSync(out, { recursive: true });
writeFileSync(join(out, 'bunny.off'), lines.join('\n') + '\n');
