// The course's budgets in headless Chromium (issue 24, item 6), run by hand after ./run.sh and
// ./test.sh (which installs playwright-core):
//   node bench/browser.mjs            (the site in out/; WHITTED_SITE=DIR for another)
// It prints one line per budget with the measurement and the goal. Not a test: numbers of this
// machine, never compared in CI.
//   interactive  from navigation to the first view rendered and traced (and to all views), the
//                page opened from disk
//   click        a click on whitted.json's pixel with the deepest ray tree → figure + narration
//                on screen (median of CLICKS, in the page's own clock)
//   render       a 320×240 render of whitted.json in the page's worker vs `whitted render
//                --threads 1` (the median of RUNS each)
//   size         the module, raw and gzipped
//   long task    the longest main-thread task seen (longtask entries are tasks over 50 ms)
//
//   node bench/browser.mjs --module [SCENE] [WxH] [ROUNDS]
// measures the module alone, without the site (web/build.sh and cargo build --release first):
// the same render (default bench/scenes/whitted.json, 640x480) in each sampling mode, by
// target/wasm/whitted_web.wasm (or WHITTED_WASM) in a blank Chromium page and by `whitted render --threads 1`, in
// interleaved rounds (default 9), the ratio page / native of each round's pair and its median.
// The page's time is the whole `render` call (the scene parsed, the structure built, the image
// traced and turned into RGBA8, the answer written); the native time is the binary's own
// load + build + trace seconds (its PNG is not timed). Both check the same rays.
import { execFileSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { gzipSync } from 'node:zlib';
import { join, resolve } from 'node:path';

process.env.WHITTED_SITE ??= resolve('out');
process.env.WHITTED_BIN ??= resolve('target/release/whitted');
const { ROOT, SITE, BIN, launch, open, settled } = await import('../tests/browser/support.mjs');
const { loadModules, callModule } = await import('./page-module.mjs');

const CLICKS = 21;
const RUNS = 5;
const median = (xs) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];
const report = (name, value, goal) => console.log(`${name.padEnd(12)} ${value.padEnd(44)} goal ${goal}`);

if (process.argv[2] === '--module') {
  await moduleAgainstNative(process.argv.slice(3));
  process.exit(0);
}

/** `--module`: the module's render in a blank page against the native binary on one thread. */
async function moduleAgainstNative([scenePath = join(ROOT, 'bench', 'scenes', 'whitted.json'), size = '640x480', rounds = '9']) {
  const [w, h] = size.split('x').map(Number);
  const text = readFileSync(scenePath, 'utf8');
  const wasm = readFileSync(process.env.WHITTED_WASM ?? join(ROOT, 'target', 'wasm', 'whitted_web.wasm'));
  const modes = [
    ['center', {}, []],
    ['corners', { aa: 'corners' }, ['--aa', 'corners']],
    ['adaptive', { aa: 'adaptive', threshold: 0.3, max_level: 2 }, ['--aa', 'adaptive', '--threshold', '0.3', '--max-level', '2']],
  ];
  const browser = await launch();
  const page = await browser.newPage();
  await loadModules(page, [wasm]);
  console.log(`${scenePath}, ${size}, ${rounds} rounds; page = the module in ${await browser.version()}, native = ${BIN} --threads 1`);
  console.log('| mode | page (ms) | native (ms) | page / native, median of rounds (range) |');
  console.log('|---|---:|---:|---:|');
  for (const [name, options, flags] of modes) {
    const request = { op: 'render', scene: text, options: { ...options, size: [w, h] } };
    await callModule(page, 0, request); // a first, cold call
    const inPage = [];
    const native = [];
    for (let k = 0; k < Number(rounds); k++) {
      const { ms, answer } = await callModule(page, 0, request);
      const doc = JSON.parse(execFileSync(BIN, ['render', scenePath, '--size', size, '--threads', '1', ...flags, '--json',
        '-o', '/dev/null'], { encoding: 'utf8', stdio: ['ignore', 'pipe', 'ignore'] }));
      if (JSON.stringify(doc.rays) !== JSON.stringify(answer.rays)) throw new Error(`${name}: the page and the binary traced other rays`);
      inPage.push(ms);
      native.push(1000 * (doc.load_seconds + doc.build_seconds + doc.seconds));
    }
    const ratios = inPage.map((p, k) => p / native[k]);
    console.log(`| ${name} | ${median(inPage).toFixed(1)} | ${median(native).toFixed(1)} | ${median(ratios).toFixed(2)} (${Math.min(...ratios).toFixed(2)}–${Math.max(...ratios).toFixed(2)}) |`);
  }
  await browser.close();
}

const browser = await launch();
const page = await browser.newPage({ viewport: { width: 1280, height: 720 } });
await page.addInitScript(() => {
  self.longest = 0;
  new PerformanceObserver((list) => {
    for (const e of list.getEntries()) self.longest = Math.max(self.longest, e.duration);
  }).observe({ type: 'longtask', buffered: true });
});
const url = 'file://' + join(SITE, 'en', 'secondary-rays.html');
await page.goto(url);
await settled(page, 60000);
const marks = await page.evaluate(() => Object.fromEntries(
  performance.getEntriesByType('mark').map((m) => [m.name, Math.round(m.startTime)])));
report('interactive', `${marks['whitted-view-0']} ms (module ${marks['whitted-module']} ms, all 3 views ${Math.max(
  marks['whitted-view-0'], marks['whitted-view-1'], marks['whitted-view-2'])} ms)`, '≤ 1000 ms (the first view rendered and traced)');

// The pixel with the deepest ray tree (then the most events), on a lattice of every 4th pixel.
const scene = readFileSync(join(ROOT, 'scenes', 'whitted.json'), 'utf8');
const deepest = await page.evaluate(async (text) => {
  const call = async (r) => JSON.parse((await self.whitted.engines.quick.call(r)).text);
  const depth = (node) => 1 + Math.max(0, ...(node.children || []).map(depth));
  let best = null;
  for (let j = 2; j < 480; j += 4) {
    for (let i = 2; i < 640; i += 4) {
      const doc = await call({ op: 'trace', scene: text, target: { pixel: [i, j] } });
      const key = [depth(doc.tree), doc.events.length];
      if (!best || key[0] > best.key[0] || (key[0] === best.key[0] && key[1] > best.key[1])) best = { pixel: [i, j], key };
    }
  }
  return best;
}, scene);

// Click → figure and narration on screen, timed in the page from the click to the view settled.
const times = [];
for (let k = 0; k < CLICKS; k++) {
  times.push(await page.evaluate(async ([i, j]) => {
    const view = self.whitted.views[0];
    const box = view.canvas.getBoundingClientRect();
    const { width, height } = view.info;
    const x = box.left + ((i + 0.5) * box.width) / width;
    const y = box.top + ((height - 1 - j + 0.5) * box.height) / height;
    const start = performance.now();
    view.canvas.dispatchEvent(new MouseEvent('click', { clientX: x, clientY: y, bubbles: true }));
    await view.tracing;
    // On screen: the next frame, once the DOM is written.
    await new Promise((done) => requestAnimationFrame(() => done()));
    return performance.now() - start;
  }, deepest.pixel));
}
report('click', `${median(times).toFixed(1)} ms median, ${Math.max(...times).toFixed(1)} max`,
  `≤ 50 ms (pixel ${deepest.pixel}, tree depth ${deepest.key[0]}, ${deepest.key[1]} events)`);

// A 320×240 render in the page's render worker against the native single thread.
const inPage = [];
for (let k = 0; k < RUNS; k++) {
  inPage.push(await page.evaluate(async (text) => {
    const start = performance.now();
    const answer = await self.whitted.engines.render.call({ op: 'render', scene: text, options: { size: [320, 240] } });
    if (answer.status !== 0) throw new Error(answer.text);
    return performance.now() - start;
  }, scene));
}
const native = [];
for (let k = 0; k < RUNS; k++) {
  const out = execFileSync(BIN, ['render', join(ROOT, 'scenes', 'whitted.json'), '--size', '320x240', '--threads', '1',
    '--json', '-o', '/dev/null'], { encoding: 'utf8', stdio: ['ignore', 'pipe', 'ignore'] });
  const doc = JSON.parse(out);
  native.push(1000 * (doc.load_seconds + doc.build_seconds + doc.seconds));
}
report('render', `${(median(inPage) / median(native)).toFixed(2)}× (page ${median(inPage).toFixed(1)} ms, native ${median(native).toFixed(1)} ms)`, '≤ 1.5×');

const wasm = readFileSync(join(ROOT, 'target', 'wasm', 'whitted_web.wasm'));
report('size', `${(wasm.length / 1e6).toFixed(2)} MB, ${(gzipSync(wasm, { level: 9 }).length / 1e6).toFixed(2)} MB gzip`, '≤ 3 MB');

// Keys, then the longest task since the page opened.
for (let k = 0; k < 10; k++) await page.keyboard.press('ArrowRight');
const longest = await page.evaluate(() => self.longest);
report('long task', longest ? `${Math.round(longest)} ms` : 'none over 50 ms', '≤ 200 ms');
await browser.close();
