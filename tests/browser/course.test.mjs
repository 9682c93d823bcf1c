// The course's pages in headless Chromium, opened from disk (file://), against the native CLI:
// docs/course.md's contract, the acceptance walk of issue 24, and the WebAssembly build's trace
// documents and SVGs byte for byte against the command line's. Every state is saved as a
// screenshot under target/browser-shots/.
import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtempSync, readFileSync, readdirSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { ROOT, cutSteps, dedent, launch, liveViews, open, settled, shot, whitted } from './support.mjs';

/** Whitted's scene as the secondary-rays lesson names it, and as the CLI reaches it. */
const LESSON = 'secondary-rays';
const SCENE = 'lessons/../scenes/whitted.json';
/** The first view's image and figure, scrolled to the top for a screenshot. */
const PANES = '[data-whitted="view"] .panes';
/** A pixel inside the glass sphere's image: a click near it lands on the glass. */
const GLASS = [430, 280];

let browser;
before(async () => { browser = await launch(); });
after(async () => { await browser?.close(); });

// The temporary folders the tests write into, removed when the file's tests end.
const scratchDirs = [];
function scratch(prefix) {
  const dir = mkdtempSync(join(tmpdir(), prefix));
  scratchDirs.push(dir);
  return dir;
}
after(() => { for (const dir of scratchDirs) rmSync(dir, { recursive: true, force: true }); });

/** The first view's steps, current step, lit items and controls, read from the page. */
async function state(page, view = 0) {
  return page.evaluate((k) => {
    const root = document.querySelectorAll('[data-whitted="view"]')[k];
    const part = (n) => root.querySelector(`[data-whitted="${n}"]`);
    const steps = [...part('steps').children].map((li) => ({
      step: Number(li.dataset.step), events: li.dataset.events, text: li.textContent,
      current: li.getAttribute('aria-current'),
    }));
    const items = [...part('figure').querySelectorAll('svg [data-events]')];
    return {
      steps,
      current: steps.find((s) => s.current === 'step'),
      currentText: part('current').textContent,
      position: part('position').textContent,
      lit: items.filter((g) => g.classList.contains('lit')).map((g) => g.getAttribute('data-events')),
      items: items.map((g) => g.getAttribute('data-events')),
      message: part('message').textContent,
      errors: [...part('errors').children].map((li) => li.textContent),
      command: part('command').textContent,
      depth: part('depth').value,
      aa: part('aa').value,
      canvas: [part('image').width, part('image').height],
      hash: location.hash,
    };
  }, view);
}

/** The items a step lights: those whose events meet the step's. */
function expectedLit(items, events) {
  const wanted = new Set(events.split(' ').filter(Boolean));
  return items.filter((e) => e.split(' ').some((x) => wanted.has(x)));
}

/** Clicks the centre of pixel (i, j) of a view's image (at fractional CSS pixels) and returns
 *  the pixel that the contract's formula gives for where the pointer landed:
 *  i = ⌊x·Nx/W⌋, j = Ny − 1 − ⌊y·Ny/H⌋, which is (i, j) itself (issue 30 item 7: the page reads
 *  the pointer's fractional position). The page must select exactly that pixel. */
async function clickPixel(page, [i, j], view = 0) {
  const canvas = page.locator('[data-whitted="view"]').nth(view).locator('[data-whitted="image"]');
  const box = await canvas.boundingBox();
  const { width: nx, height: ny } = await canvas.evaluate((c) => ({ width: c.width, height: c.height }));
  await canvas.evaluate((c) => c.addEventListener('click', (e) => {
    const r = c.getBoundingClientRect();
    self.landed = { x: e.clientX - r.left, y: e.clientY - r.top, w: r.width, h: r.height };
  }, { once: true, capture: true }));
  await canvas.evaluate((c) => c.addEventListener('pointerdown', (e) => {
    const r = c.getBoundingClientRect();
    self.pressedAt = { x: e.clientX - r.left, y: e.clientY - r.top };
  }, { once: true, capture: true }));
  await page.mouse.click(box.x + ((i + 0.5) * box.width) / nx, box.y + ((ny - 1 - (j || 0) + 0.5) * box.height) / ny);
  const at = await page.evaluate(() => ({ ...self.landed, ...self.pressedAt }));
  await settled(page);
  const chosen = [Math.floor((at.x * nx) / at.w), ny - 1 - Math.floor((at.y * ny) / at.h)];
  return j === undefined ? [chosen[0]] : chosen;
}

/** A request to the page's own module (the quick worker). */
async function call(page, request) {
  return page.evaluate(async (r) => {
    const a = await self.whitted.engines.quick.call(r);
    return { status: a.status, text: a.text };
  }, request);
}

test('the secondary-rays lesson: click, steps, keys, Romanian, editor, depth, refusal', async () => {
  const page = await open(browser, `en/${LESSON}.html`);
  await settled(page);
  const views = await page.locator('[data-whitted="view"]').evaluateAll((v) => v.map((e) => e.dataset.scene));
  assert.deepEqual(views, ['../scenes/whitted.json', 'scenes/prism_2d.json', 'scenes/prism_2d.json']);
  let s = await state(page);
  assert.deepEqual(s.canvas, [640, 480], 'the image is rendered at the scene size');
  await shot(page, '01-opened');

  // A click on the glass sphere: the narration is `whitted trace`'s, step by step.
  const pixel = await clickPixel(page, GLASS);
  assert.ok(Math.abs(pixel[0] - GLASS[0]) <= 1 && Math.abs(pixel[1] - GLASS[1]) <= 1, `${pixel}`);
  s = await state(page);
  await shot(page, '02-clicked-glass', PANES);
  assert.match(s.hash, new RegExp(`^#pixel=${pixel.join(',')}&step=1&`));
  const narration = cutSteps(whitted(['trace', SCENE, '--accel', 'none', '--pixel', pixel.join(',')]));
  assert.ok(narration.some((t) => t.includes('Nearest hit of P: I₁ on “glass”')), 'the pixel is on the glass sphere');
  assert.deepEqual(s.steps.map((x) => x.step), narration.map((_, k) => k + 1));
  s.steps.forEach((x, k) => assert.equal(x.text, narration[k], `step ${k + 1}`));
  assert.match(s.command, new RegExp(`^whitted trace scenes/whitted.json --pixel ${pixel.join(',')}`));
  // The command shown, run from the repository, tells the same steps.
  assert.deepEqual(cutSteps(whitted(s.command.split(' ').slice(1))), s.steps.map((x) => x.text));
  // The events each step names are the module's narrate answer, indices into `trace --json`.
  const doc = whitted(['trace', SCENE, '--accel', 'none', '--pixel', pixel.join(','), '--json']);
  const events = JSON.parse(doc).events.length;
  // The refraction figure draws no structure: its view traces with every object tested.
  const request = { scene: readFileSync(join(ROOT, 'scenes/whitted.json'), 'utf8'), name: SCENE, target: { pixel },
    options: { accel: 'none' } };
  const traced = await call(page, { op: 'trace', ...request });
  assert.equal(traced.text, doc, 'the page module traces as the CLI does');
  const narrated = JSON.parse((await call(page, { op: 'narrate', ...request, lang: 'en' })).text);
  assert.deepEqual(s.steps.map((x) => x.events), narrated.steps.map((x) => x.events.join(' ')));
  for (const x of narrated.steps) for (const e of x.events) assert.ok(e >= 0 && e < events, `event ${e}`);
  assert.equal(s.current.step, 1);
  assert.deepEqual(s.lit, expectedLit(s.items, s.current.events));

  // → three times: the fourth step is current, lit as it says, its numbers beside the figure.
  for (let k = 1; k <= 3; k++) {
    await page.keyboard.press('ArrowRight');
    s = await state(page);
    assert.equal(s.current.step, 1 + k);
    assert.deepEqual(s.lit, expectedLit(s.items, s.current.events));
    assert.equal(s.currentText, dedent(narration[k]));
    await shot(page, `03-step-${1 + k}`, PANES);
  }
  assert.match(s.position, /Step 4 of \d+/);
  assert.match(s.hash, /step=4/);
  // The step of the nearest hit, chosen in the list, lights the hit in the refraction figure.
  const hit = 1 + narration.findIndex((t) => t.includes('Nearest hit of P: I₁ on “glass”'));
  await page.locator(`[data-whitted="steps"] [data-step="${hit}"]`).first().click();
  s = await state(page);
  await shot(page, '03-nearest-hit', PANES);
  assert.equal(s.current.step, hit);
  assert.ok(s.lit.length > 0, `step ${hit} lights the hit`);
  assert.deepEqual(s.lit, expectedLit(s.items, s.current.events));
  for (let k = hit; k > 4; k--) await page.keyboard.press('ArrowLeft');
  assert.equal((await state(page)).current.step, 4);

  // Romanian: the same place, Romanian words and narration.
  await Promise.all([page.waitForURL(new RegExp(`/ro/secondary-rays\\.html#pixel=${pixel.join(',')}&step=4`)), page.click('[data-whitted="lang"]')]);
  await settled(page);
  s = await state(page);
  await shot(page, '04-romanian', PANES);
  assert.equal(s.current.step, 4);
  const ro = cutSteps(whitted(['trace', SCENE, '--accel', 'none', '--pixel', pixel.join(','), '--lang', 'ro']));
  assert.equal(s.currentText, dedent(ro[3]));
  assert.equal(await page.locator('[data-whitted="view"] label', { hasText: 'Adâncimea' }).count(), 3);
  assert.match(await page.textContent('[data-whitted="position"]'), /^Pasul 4 din/);

  // A bad value in the editor: `check`'s error naming the field; the image stays.
  const scene = readFileSync(join(ROOT, 'scenes/whitted.json'), 'utf8');
  const bad = scene.replace('"radius": 0.75', '"radius": -1');
  assert.notEqual(bad, scene);
  const file = join(scratch('whitted-'), 'bad.json');
  writeFileSync(file, bad);
  let checkErr = '';
  try { whitted(['check', file]); } catch (e) { checkErr = e.stderr.toString(); }
  await page.locator('.editor summary').first().click();
  await page.locator('[data-whitted="scene"]').first().fill(bad);
  await page.waitForFunction(() => document.querySelector('[data-whitted="errors"]').children.length > 0);
  await settled(page);
  s = await state(page);
  await shot(page, '05-bad-radius', '[data-whitted="view"] .editor');
  assert.ok(s.errors.some((e) => e.startsWith('objects[2].radius')), s.errors.join('\n'));
  for (const e of s.errors) assert.ok(checkErr.includes(e), `${e} is what check says: ${checkErr}`);
  assert.deepEqual(s.canvas, [640, 480]);
  await page.locator('[data-whitted="scene"]').first().fill(scene);
  await page.waitForFunction(() => document.querySelector('[data-whitted="errors"]').children.length === 0);
  await settled(page);

  // Depth 1: fewer steps (no R or T is traced past the first hit).
  const before = (await state(page)).steps.length;
  await page.locator('[data-whitted="depth"]').first().fill('1');
  await page.locator('[data-whitted="depth"]').first().dispatchEvent('change');
  await settled(page);
  s = await state(page);
  await shot(page, '06-depth-1', PANES);
  assert.ok(s.steps.length < before, `${s.steps.length} < ${before}`);
  assert.match(s.hash, /depth=1/);
  const depth1 = cutSteps(whitted(['trace', SCENE, '--accel', 'none', '--pixel', pixel.join(','), '--depth', '1', '--lang', 'ro']));
  assert.equal(s.steps.length, depth1.length);

  // A depth beyond the CLI's limit and a pixel outside the image are refused with a message.
  await page.locator('[data-whitted="depth"]').first().fill('65');
  await page.locator('[data-whitted="depth"]').first().dispatchEvent('change');
  await settled(page);
  s = await state(page);
  assert.match(s.message, /depth/);
  assert.equal(s.steps.length, depth1.length, 'the last good trace stays');
  await page.locator('[data-whitted="depth"]').first().fill('1');
  await page.locator('[data-whitted="depth"]').first().dispatchEvent('change');
  await settled(page);
  await page.locator('[data-whitted="pixel"]').first().fill('900, 900');
  await page.locator('[data-whitted="pixel"]').first().press('Enter');
  await settled(page);
  s = await state(page);
  await shot(page, '07-outside', PANES);
  assert.match(s.message, /900/);
  assert.equal(s.steps.length, depth1.length, 'the last good trace stays');
  assert.match(s.hash, new RegExp(`pixel=${pixel.join(',')}&`), 'with its pixel');
  assert.deepEqual(page.problems, []);
});

test('a page opened with a fragment shows that state', async () => {
  let page = await open(browser, `en/${LESSON}.html#pixel=400,200&step=7&depth=2&aa=center`);
  await settled(page);
  let s = await state(page);
  await shot(page, '08-fragment', PANES);
  assert.equal(s.current.step, 7);
  assert.equal(s.depth, '2');
  let cli = cutSteps(whitted(['trace', SCENE, '--accel', 'none', '--pixel', '400,200', '--depth', '2']));
  assert.deepEqual(s.steps.map((x) => x.text), cli);
  assert.equal(s.currentText, dedent(cli[6]));
  assert.deepEqual(page.problems, []);
  // Sampled: the narration of the pixel's samples, as `whitted trace --aa corners` tells it.
  page = await open(browser, `ro/${LESSON}.html#pixel=400,200&step=2&aa=corners`);
  await settled(page);
  s = await state(page);
  await shot(page, '08-fragment-corners', PANES);
  assert.equal(s.aa, 'corners');
  assert.equal(s.current.step, 2);
  cli = cutSteps(whitted(['trace', SCENE, '--accel', 'none', '--pixel', '400,200', '--aa', 'corners', '--lang', 'ro']));
  assert.deepEqual(s.steps.map((x) => x.text), cli);
  assert.deepEqual(page.problems, []);
});

// Every page in both languages is opened live, at phone width, by the accessibility test of
// follow.test.mjs (one load a page); here the shots of four pages at slide width, and a phone.
test('lesson and playground pages open live at slide width, and a lesson at phone width', async () => {
  for (const name of ['ray-tree', 'bvh', 'adaptive', 'play']) {
    const page = await open(browser, `en/${name}.html`);
    await settled(page);
    const views = await page.evaluate(liveViews);
    assert.ok(views.length > 0, name);
    for (const v of views) assert.ok(v.live, `en/${name}: ${JSON.stringify(v)}`);
    await shot(page, `09-${name}`);
    assert.deepEqual(page.problems, [], `en/${name}`);
    await page.close();
  }
  const phone = await open(browser, `ro/${LESSON}.html`, { width: 390, height: 844 });
  await settled(phone);
  await clickPixel(phone, GLASS);
  await phone.keyboard.press('ArrowRight');
  await shot(phone, '10-phone', PANES);
  const overflow = await phone.evaluate(() => document.scrollingElement.scrollWidth - innerWidth);
  assert.ok(overflow <= 0, `no sideways scrolling at phone width (${overflow} px too wide)`);
  assert.deepEqual(phone.problems, []);
});

test('the playground: an example picked, a pixel clicked', async () => {
  const page = await open(browser, 'en/play.html');
  await settled(page);
  await page.selectOption('[data-whitted="example"]', 'flat.json');
  await page.waitForFunction(() => document.querySelector('[data-whitted="view"]').dataset.scene === 'flat.json');
  await settled(page);
  const pixel = await clickPixel(page, [30]);
  const s = await state(page);
  await shot(page, '11-playground-flat', PANES);
  const cli = cutSteps(whitted(['trace', 'scenes/flat.json', '--accel', 'none', '--pixel', String(pixel[0])]));
  assert.deepEqual(s.steps.map((x) => x.text), cli);
  assert.deepEqual(page.problems, []);
});

/** The module's budget in bytes (issue 34): what the course's pages download before the first render. */
const MODULE_BUDGET = 3_000_000;

test('the WebAssembly module stays within its budget', () => {
  const bytes = readFileSync(join(ROOT, 'target', 'wasm', 'whitted_web.wasm')).length;
  assert.ok(bytes <= MODULE_BUDGET, `the module is ${bytes} bytes, over its ${MODULE_BUDGET}`);
});

test('the WebAssembly build traces and draws byte for byte as the CLI', async () => {
  const page = await open(browser, `en/${LESSON}.html`);
  await settled(page);
  const lessons = readdirSync(join(ROOT, 'lessons')).filter((f) => f.endsWith('.json'))
    .map((f) => JSON.parse(readFileSync(join(ROOT, 'lessons', f), 'utf8')));
  const scenes = [...new Set(lessons.flatMap((l) => l.figures.map((f) => 'lessons/' + f.scene)))];
  let compared = 0;
  for (const path of scenes) {
    const scene = readFileSync(join(ROOT, path), 'utf8');
    const info = JSON.parse((await call(page, { op: 'info', scene })).text);
    // A 4×3 lattice of pixels over the image (a 2D strip: 6 columns).
    const pixels = info.dimension === 2
      ? [0, 1, 2, 3, 4, 5].map((k) => [Math.floor(((k + 0.5) * info.width) / 6)])
      : [0, 1, 2, 3].flatMap((a) => [0, 1, 2].map((b) => [
        Math.floor(((a + 0.5) * info.width) / 4), Math.floor(((b + 0.5) * info.height) / 3)]));
    for (const pixel of pixels) {
      const cli = whitted(['trace', path, '--pixel', pixel.join(','), '--json']);
      const wasm = await call(page, { op: 'trace', scene, name: path, target: { pixel } });
      assert.equal(wasm.status, 0, wasm.text);
      assert.equal(wasm.text, cli, `${path} ${pixel}`);
      compared++;
    }
  }
  // Every lesson figure's SVG, in both languages, with the lesson's own options.
  const dir = scratch('whitted-svg-');
  for (const lesson of lessons) {
    for (const [k, f] of lesson.figures.entries()) {
      for (const lang of ['en', 'ro']) {
        const path = 'lessons/' + f.scene;
        const out = join(dir, `${lesson.name}-${k}-${lang}.svg`);
        const args = ['figure', f.kind, path, '--lang', lang, '-o', out];
        const options = {};
        let target;
        if (f.pixel) { args.push('--pixel', f.pixel.join(',')); target = { pixel: f.pixel }; }
        if (f.ray) {
          args.push(`--ray=${f.ray.origin.join(',')}:${f.ray.direction.join(',')}`);
          target = { ray: [f.ray.origin, f.ray.direction] };
        }
        if (f.depth !== undefined) { args.push('--depth', String(f.depth)); options.depth = f.depth; }
        if (f.aa) { args.push('--aa', f.aa); options.aa = f.aa; }
        if (f.aa === 'adaptive' || (!f.aa && ['adaptive', 'heat-map'].includes(f.kind))) {
          if (f.threshold !== undefined) { args.push('--threshold', String(f.threshold)); options.threshold = f.threshold; }
          if (f.max_level !== undefined) { args.push('--max-level', String(f.max_level)); options.max_level = f.max_level; }
        }
        if (f.grid) { args.push('--grid', f.grid.join(',')); options.grid = f.grid; }
        whitted(args);
        const scene = readFileSync(join(ROOT, path), 'utf8');
        const wasm = await call(page, { op: 'figure', scene, name: path, options, target, lang, kind: f.kind });
        assert.equal(wasm.status, 0, `${lesson.name} ${k}: ${wasm.text}`);
        assert.equal(JSON.parse(wasm.text).svg, readFileSync(out, 'utf8'), `${lesson.name} figure ${k + 1} (${lang})`);
        compared++;
      }
    }
  }
  assert.ok(compared > 150, `${compared} documents compared`);
  assert.deepEqual(page.problems, []);
});
