// Headless Debian Chromium driven by playwright-core, against the built site on localhost.
import { join } from 'node:path';
import { chromium } from 'playwright-core';
import { startServer } from '../../scripts/serve.mjs';
import { meshes, root } from '../node/support.mjs';

export async function startSite() {
  const server = await startServer({
    mounts: { '/': join(root, 'dist'), '/test/': join(root, 'tests', 'browser'), '/meshes/': meshes },
  });
  return { server, url: `http://127.0.0.1:${server.address().port}` };
}

export function launchBrowser() {
  return chromium.launch({
    executablePath: '/usr/bin/chromium',
    args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
      '--disable-component-update', '--disable-sync'],
  });
}

// Fails the test on any request that does not go to our server.
export function guardNetwork(page, origin, requests) {
  page.on('request', (r) => {
    const url = r.url();
    if (!url.startsWith(origin) && !url.startsWith('data:') && !url.startsWith('blob:')) requests.push(url);
  });
}
