// Two or more WebAssembly modules of whitted in one page of headless Chromium, in interleaved
// rounds: is one module faster than another in the page itself, without native in the loop?
//   node bench/page-ab.mjs [--rounds N] [--size WxH] [--scene FILE] A.wasm B.wasm ...
// For each sampling mode (centre, corners, adaptive at threshold 0.3 and K = 2) it prints each
// module's median time of a whole `render` call and, against the first module, the median of
// the rounds' ratios with their range; the rays are checked equal across modules.
import { readFileSync } from 'node:fs';
import { join } from 'node:path';

const { ROOT, launch } = await import('../tests/browser/support.mjs');
const { loadModules, callModule } = await import('./page-module.mjs');

const args = process.argv.slice(2);
let rounds = 15;
let size = '640x480';
let scenePath = join(ROOT, 'bench', 'scenes', 'whitted.json');
const modules = [];
for (let k = 0; k < args.length; k++) {
  if (args[k] === '--rounds') rounds = Number(args[++k]);
  else if (args[k] === '--size') size = args[++k];
  else if (args[k] === '--scene') scenePath = args[++k];
  else modules.push(args[k]);
}
if (modules.length < 2) {
  console.error('usage: node bench/page-ab.mjs [--rounds N] [--size WxH] [--scene FILE] A.wasm B.wasm ...');
  process.exit(2);
}
const [w, h] = size.split('x').map(Number);
const text = readFileSync(scenePath, 'utf8');
const modes = [
  ['center', {}],
  ['corners', { aa: 'corners' }],
  ['adaptive', { aa: 'adaptive', threshold: 0.3, max_level: 2 }],
];

const browser = await launch();
const page = await browser.newPage();
await loadModules(page, modules.map((m) => readFileSync(m)));

const median = (xs) => [...xs].sort((a, b) => a - b)[xs.length >> 1];
console.log(`${scenePath}, ${size}, ${rounds} rounds, ${await browser.version()}`);
modules.forEach((m, i) => console.log(`module ${i}: ${m} (${readFileSync(m).length} bytes)`));
console.log(`| mode | ${modules.map((_, i) => `module ${i} (ms)`).join(' | ')} | ${modules.slice(1).map((_, i) => `${i + 1} / 0`).join(' | ')} |`);
console.log(`|---|${modules.map(() => '---:').join('|')}|${modules.slice(1).map(() => '---:').join('|')}|`);
for (const [name, options] of modes) {
  const request = { op: 'render', scene: text, options: { ...options, size: [w, h] } };
  const times = modules.map(() => []);
  for (let i = 0; i < modules.length; i++) await callModule(page, i, request); // a first, cold call
  for (let k = 0; k < rounds; k++) {
    // The order turns each round, so that neither module always runs first.
    const order = modules.map((_, i) => (i + k) % modules.length);
    let rays = null;
    for (const i of order) {
      const { ms, answer } = await callModule(page, i, request);
      const r = answer.rays;
      if (rays !== null && JSON.stringify(rays) !== JSON.stringify(r)) throw new Error(`${name}: module ${i} traced other rays`);
      rays = r;
      times[i].push(ms);
    }
  }
  const ratios = times.slice(1).map((t) => t.map((ms, k) => ms / times[0][k]));
  console.log(`| ${name} | ${times.map((t) => median(t).toFixed(1)).join(' | ')} | ${ratios
    .map((r) => `${median(r).toFixed(3)} (${Math.min(...r).toFixed(2)}–${Math.max(...r).toFixed(2)})`)
    .join(' | ')} |`);
}
await browser.close();
