#!/usr/bin/env node
// `npm run cli:wasm -- INPUT [flags]`: the native CLI's flags and outputs, computed by
// the WASM build under node.
import { readFileSync, writeFileSync } from 'node:fs';
import { basename } from 'node:path';
import { performance } from 'node:perf_hooks';
import { loadVqsa } from './load.mjs';

const usage = `usage: vqsa-wasm INPUT [--proxies N] [--tolerance T] [--max-iterations K] [--seed S]
                 [--rings K] [--lambda L] [--no-smooth] [--no-refit] [--no-project]
                 [--report FILE.json] [--labels FILE.txt] [--projected FILE] [-o FILE.glb] [--quiet]
  INPUT is .off .obj .ply .stl .gltf .glb, or example:NAME`;

class UsageError extends Error {}

function parse(argv) {
  const a = { options: {}, quiet: false };
  let proxiesGiven = false;
  for (let i = 0; i < argv.length; ++i) {
    const arg = argv[i];
    const value = () => {
      if (i + 1 >= argv.length) throw new UsageError(`${arg} needs a value`);
      return argv[++i];
    };
    const number = (integer) => {
      const text = value();
      const v = Number(text);
      if (text.trim() === '' || !Number.isFinite(v) || (integer && !Number.isInteger(v)))
        throw new UsageError(`${arg} expects ${integer ? 'an integer' : 'a number'}, not '${text}'`);
      return v;
    };
    switch (arg) {
      case '--proxies': a.options.proxies = number(true); proxiesGiven = true;
        if (a.options.proxies < 1 || a.options.proxies > 1e6) throw new UsageError('--proxies must be between 1 and 1000000');
        break;
      case '--tolerance': a.options.tolerance = number(false);
        if (!(a.options.tolerance > 0 && a.options.tolerance < 1)) throw new UsageError('--tolerance must be in (0, 1)');
        break;
      case '--max-iterations': a.options.maxIterations = number(true);
        if (a.options.maxIterations < 1) throw new UsageError('--max-iterations must be at least 1');
        break;
      case '--seed': a.options.seed = number(true);
        if (a.options.seed < 0) throw new UsageError('--seed must be non-negative');
        break;
      case '--rings': a.options.rings = number(true);
        if (a.options.rings < 1 || a.options.rings > 100) throw new UsageError('--rings must be between 1 and 100');
        break;
      case '--lambda': a.options.lambda = number(false);
        if (!(a.options.lambda >= 0)) throw new UsageError('--lambda must be a non-negative number');
        break;
      case '--no-smooth': a.options.smooth = false; break;
      case '--no-refit': a.options.refit = false; break;
      case '--no-project': a.options.project = false; break;
      case '--report': a.report = value(); break;
      case '--labels': a.labels = value(); break;
      case '--projected': a.projected = value(); break;
      case '-o': case '--output': a.glb = value(); break;
      case '--quiet': a.quiet = true; break;
      case '--help': case '-h': console.log(usage); process.exit(0);
      default:
        if (arg.startsWith('-')) throw new UsageError(`unknown option ${arg}`);
        if (a.input) throw new UsageError(`more than one input: ${a.input} and ${arg}`);
        a.input = arg;
    }
  }
  if (!a.input) throw new UsageError('no input file');
  a.defaultProxies = !proxiesGiven && a.options.tolerance === undefined;
  return a;
}

let args;
try {
  args = parse(process.argv.slice(2));
} catch (e) {
  if (!(e instanceof UsageError)) throw e;
  console.error(`vqsa-wasm: ${e.message}\n${usage}`);
  process.exit(2);
}

try {
  const vqsa = await loadVqsa();
  const session = new vqsa.Session();
  const t0 = performance.now();
  let info;
  if (args.input.startsWith('example:')) {
    info = session.loadExample(args.input.slice('example:'.length));
  } else {
    let bytes;
    try {
      bytes = readFileSync(args.input);
    } catch {
      throw new Error(`${args.input}: cannot open the file`);
    }
    info = session.load(bytes, args.input);
  }
  if (args.defaultProxies) args.options.proxies = Math.min(20, info.facesUsed);
  const t1 = performance.now();
  session.start(args.options);
  let lloydEnd = 0, lastPhase = '';
  for (let more = true; more;) {
    more = session.stepFor(50);
    const p = session.progress();
    if (!lloydEnd && p.lloydDone) lloydEnd = performance.now();
    if (!args.quiet && p.phase !== lastPhase && !['lloyd', 'smooth'].includes(p.phase))
      console.error(`${p.phase.padEnd(10)} proxies ${String(p.proxies).padStart(4)}  iteration ${String(p.iteration).padStart(5)}  rms ${p.rms.toExponential(3)}`);
    lastPhase = p.phase;
  }
  const t3 = performance.now();
  lloydEnd ||= t3;
  const s = (a, b) => (b - a) / 1000;
  const report = JSON.parse(session.report(s(t0, t1), s(t1, lloydEnd), s(lloydEnd, t3), s(t0, t3)));
  if (args.report) writeFileSync(args.report, JSON.stringify(report, null, 1) + '\n');
  if (args.labels) writeFileSync(args.labels, report.labels.join('\n') + '\n');
  if (args.glb) writeFileSync(args.glb, session.glb());
  if (args.projected) writeFileSync(args.projected, session.projectedFile(args.projected));
  console.log(`${args.input}: ${report.input.faces} faces, ${report.input.components} components -> ${report.proxies.length} proxies (stopped: ${report.stop_reason}) in ${report.iterations} Lloyd iterations`);
  console.log(`rms error ${report.rms_error.toExponential(4)} (${report.rms_error_relative.toExponential(4)} of the longest side), load ${s(t0, t1).toFixed(3)} s, Lloyd ${s(t1, lloydEnd).toFixed(3)} s, post-processing ${s(lloydEnd, t3).toFixed(3)} s`);
  if (report.metrics) console.log(`projected surface vs input: rms ${report.metrics.rms.toExponential(4)}, hausdorff ${report.metrics.hausdorff.toExponential(4)} (of the bounding-box diagonal)`);
  for (const p of report.proxies)
    console.log(`  ${String(p.id).padStart(3)} ${p.type.padEnd(24)} faces ${String(p.faces).padStart(6)}  rms ${p.rms_error.toExponential(3)}`);
} catch (e) {
  console.error(`vqsa-wasm: ${e.message}`);
  process.exit(1);
}
