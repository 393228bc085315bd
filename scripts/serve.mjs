// A small static server for the built site (dist/): `npm run serve` (PORT overrides 8080).
// The browser tests reuse startServer() with extra folders mounted.
import { createReadStream, statSync } from 'node:fs';
import { createServer } from 'node:http';
import { dirname, extname, join, normalize, resolve, sep } from 'node:path';
import { fileURLToPath } from 'node:url';

const types = {
  '.html': 'text/html; charset=utf-8', '.js': 'text/javascript', '.mjs': 'text/javascript',
  '.css': 'text/css', '.json': 'application/json', '.wasm': 'application/wasm', '.svg': 'image/svg+xml',
  '.png': 'image/png', '.glb': 'model/gltf-binary', '.ico': 'image/x-icon',
};

// mounts: {'/': folder, '/meshes/': folder, ...}; the longest matching prefix wins.
export function startServer({ port = 0, host = '127.0.0.1', mounts }) {
  const prefixes = Object.keys(mounts).sort((a, b) => b.length - a.length);
  const server = createServer((request, response) => {
    const path = decodeURIComponent(new URL(request.url, 'http://localhost').pathname);
    const prefix = prefixes.find((p) => path.startsWith(p));
    const root = prefix && resolve(mounts[prefix]);
    let file = root && normalize(join(root, path.slice(prefix.length)));
    if (!file || (file !== root && !file.startsWith(root + sep))) return send(response, 403, 'forbidden');
    try {
      if (statSync(file).isDirectory()) file = join(file, 'index.html');
      const size = statSync(file).size;
      response.writeHead(200, { 'Content-Type': types[extname(file)] ?? 'application/octet-stream', 'Content-Length': size,
        'Cache-Control': 'no-cache' });
      createReadStream(file).pipe(response);
    } catch {
      send(response, 404, 'not found');
    }
  });
  return new Promise((resolveListen) => server.listen(port, host, () => resolveListen(server)));
}

function send(response, status, text) {
  response.writeHead(status, { 'Content-Type': 'text/plain' });
  response.end(text);
}

if (process.argv[1] && resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
  const dist = join(dirname(fileURLToPath(import.meta.url)), '..', 'dist');
  try {
    statSync(join(dist, 'index.html'));
  } catch {
    console.error('dist/ is not built: run npm run build (or npm start)');
    process.exit(1);
  }
  const port = Number(process.env.PORT ?? 8080);
  const server = await startServer({ port, host: process.env.HOST ?? '127.0.0.1', mounts: { '/': dist } });
  console.log(`vqsa is served at http://localhost:${server.address().port}/`);
}
