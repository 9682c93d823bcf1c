// Issue 30 items 1, 2, 4, 5, 6 and 7 in headless Chromium: any pixel is followed (a figure that
// cannot draw it falls back to its rays and offers a nearby pixel and the lesson's), a figure is
// narrated by the structure it draws, the cost is shown, refusals and bad links stay said, the
// pages pass axe-core with no serious or critical violation and read at a phone's width, keys do
// what they say, and a click selects the pixel under it at any size of the image.
import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync, readdirSync } from 'node:fs';
import { createRequire } from 'node:module';
import { join } from 'node:path';
import { ROOT, launch, liveViews, open, settled, shot } from './support.mjs';

const require = createRequire(import.meta.url);
/** axe-core, pinned in package.json and package-lock.json. */
const AXE = require.resolve('axe-core/axe.min.js');
/** The smallest label a figure may show, in CSS pixels (item 6). */
const LABEL_MIN_PX = 11;
/** A phone's width, in CSS pixels. */
const PHONE = 390;
/** How long a lesson page may take to settle. */
const PAGE_MS = 120000;

let browser;
before(async () => { browser = await launch(); });
after(async () => { await browser?.close(); });

/** A view's state as the page shows it. */
async function view(page, k = 0) {
  return page.evaluate((index) => {
    const root = document.querySelectorAll('[data-whitted="view"]')[index];
    const part = (n) => root.querySelector(`[data-whitted="${n}"]`);
    const v = self.whitted.views[index];
    return {
      steps: [...part('steps').children].map((li) => li.textContent),
      step: v.step,
      command: part('command').textContent,
      message: part('message').textContent,
      follow: part('follow').hidden ? '' : part('follow').textContent,
      nearby: [...part('follow').querySelectorAll('button[data-pixel]')].map((b) => b.dataset.pixel),
      kind: part('kind').value,
      accel: part('accel').value,
      aa: part('aa').value,
      depth: part('depth').value,
      svg: Boolean(part('figure').querySelector('svg')),
      target: v.target,
      stats: part('stats').textContent,
      cost: part('cost').textContent,
      stale: root.classList.contains('stale'),
    };
  }, k);
}

async function typePixel(page, text, k = 0) {
  const field = page.locator('[data-whitted="pixel"]').nth(k);
  await field.fill(text);
  await field.press('Enter');
  await settled(page, PAGE_MS);
}

test('a pixel the figure cannot draw is followed: its rays, why, a nearby pixel, the lesson pixel', async () => {
  const page = await open(browser, 'en/secondary-rays.html');
  await settled(page, PAGE_MS);
  const lesson = (await view(page)).target;
  await typePixel(page, '620, 65');
  let s = await view(page);
  await shot(page, 'follow-1280-refused-pixel-followed', '[data-whitted="view"]');
  assert.ok(s.steps.length > 3, 'its steps are shown');
  assert.match(s.command, /--pixel 620,65/);
  assert.ok(s.svg, 'a figure is shown');
  assert.equal(s.message, '', 'nothing is refused');
  assert.match(s.follow, /Pixel \(620, 65\) has no refraction/);
  // The search for a nearby pixel ends with one offered (settled waits for it).
  assert.ok(s.nearby.length >= 2, `a nearby pixel and the lesson's: ${s.follow}`);
  const near = s.nearby.find((p) => p !== (lesson ? lesson.pixel.join(',') : ''));
  await page.locator(`[data-whitted="follow"] button[data-pixel="${near}"]`).first().click();
  await settled(page, PAGE_MS);
  s = await view(page);
  assert.deepEqual(s.target.pixel.join(','), near);
  assert.doesNotMatch(s.follow, /has no refraction/, 'the nearby pixel is drawn by the lesson kind');
  // The lesson's pixel is one click away.
  await page.locator('[data-whitted="follow"] button[data-pixel]').first().click();
  await settled(page, PAGE_MS);
  assert.equal((await view(page)).follow, '');
  // Arrow keys walk the followed pixel's steps.
  await typePixel(page, '620, 65');
  const before = (await view(page)).step;
  await page.keyboard.press('ArrowRight');
  assert.equal((await view(page)).step, before + 1, 'Enter gives → back to the steps');
  const phone = await open(browser, 'en/secondary-rays.html', { width: PHONE, height: 844 });
  await settled(phone, PAGE_MS);
  await typePixel(phone, '620, 65');
  await shot(phone, 'follow-390-refused-pixel-followed', '[data-whitted="follow"]');
  assert.deepEqual(page.problems, []);
  await page.close();
  await phone.close();
});

/** Makes the first step of view 0 whose text matches `pattern` current; returns how many items
 *  of the figure it lights. */
async function stepTo(page, pattern) {
  return page.evaluate((source) => {
    const view = self.whitted.views[0];
    const k = view.steps.findIndex((s) => new RegExp(source).test(s.text));
    view.go(k);
    return k < 0 ? -1 : view.root.querySelectorAll('[data-whitted="figure"] svg .lit').length;
  }, pattern.source);
}

test('an intersection test lights its ray and its object, at 1280 and 390 px', async () => {
  for (const width of [1280, PHONE]) {
    const page = await open(browser, 'en/ray-casting.html', { width, height: width === PHONE ? 844 : 800 });
    await settled(page, PAGE_MS);
    // Each test of P lights P; the test of an object the figure draws lights that object too.
    const walked = await page.evaluate(() => {
      const view = self.whitted.views[0];
      const out = [];
      view.steps.forEach((s, k) => {
        if (!/Intersection test of P with/.test(s.text)) return;
        view.go(k);
        out.push({ k, tags: [...view.root.querySelectorAll('[data-whitted="figure"] svg .lit')].map((g) => g.dataset.tag) });
      });
      return out;
    });
    assert.ok(walked.length > 0 && walked.every((w) => w.tags.some((t) => t.startsWith('ray:'))), JSON.stringify(walked));
    const both = walked.find((w) => w.tags.some((t) => t.startsWith('object:')));
    assert.ok(both, JSON.stringify(walked));
    await page.evaluate((k) => self.whitted.views[0].go(k), both.k);
    const tags = both.tags;
    assert.ok(tags.some((t) => t.startsWith('ray:')) && tags.some((t) => t.startsWith('object:')), tags.join(' '));
    await shot(page, `lit-test-step-${width}`, width === PHONE ? '[data-whitted="view"] .figure-pane' : '[data-whitted="view"]');
    await page.close();
  }
});

test('a link opens with its steps, and bad links are corrected and said', async () => {
  let page = await open(browser, 'en/secondary-rays.html#pixel=384,416&step=2');
  await settled(page, PAGE_MS);
  let s = await view(page);
  assert.ok(s.steps.length > 2 && s.step === 1, `${s.steps.length} steps, at ${s.step}`);
  await page.close();
  page = await open(browser, 'en/secondary-rays.html#pixel=9999,5&step=500&depth=99');
  await settled(page, PAGE_MS);
  s = await view(page);
  await shot(page, 'link-corrected', '[data-whitted="view"]');
  assert.deepEqual(s.target.pixel, [639, 5]);
  assert.equal(s.depth, '', 'the scene\'s own depth');
  assert.match(s.message, /9999,5/);
  assert.match(s.message, /depth=99/);
  assert.match(s.message, /step 500/);
  assert.ok(s.steps.length > 0 && s.step === s.steps.length - 1);
  await page.close();
  for (const [fragment, said] of [['aa=bogus', /aa=bogus/], ['pixel=%E0%A4%A', /pixel=/]]) {
    page = await open(browser, 'en/secondary-rays.html#' + fragment);
    await settled(page, PAGE_MS);
    s = await view(page);
    assert.match(s.message, said, fragment);
    assert.ok(s.steps.length > 0 && s.svg, fragment);
    assert.equal(s.aa, 'center');
    assert.deepEqual(page.problems, [], fragment);
    await page.close();
  }
});

test('a structure figure is narrated by its structure, the others by every object', async () => {
  const page = await open(browser, 'en/grid.html');
  await settled(page, PAGE_MS);
  let s = await view(page);
  assert.ok(await stepTo(page, /Voxel \[/) > 0, 'a cell step lights its cell');
  await shot(page, 'grid-narrated-by-cells', '[data-whitted="view"]');
  assert.equal(s.accel, 'grid');
  assert.match(s.command, /--accel grid/);
  assert.ok(s.steps.some((t) => /Voxel \[/.test(t)), 'the steps walk the cells');
  assert.ok(!s.steps.some((t) => /Visit node/.test(t)), 'no BVH in the grid lesson');
  assert.match(s.stats, /voxels [1-9]/);
  const imageCost = s.stats;
  // The structure control changes the figure's structure too.
  await page.locator('[data-whitted="accel"]').first().selectOption('bvh');
  await settled(page, PAGE_MS);
  s = await view(page);
  assert.equal(s.kind, 'bvh');
  assert.ok(s.steps.some((t) => /Visit node/.test(t)));
  assert.notEqual(s.stats, imageCost, 'the image cost follows the structure');
  assert.match(s.cost, /nodes [1-9]/);
  const phone = await open(browser, 'en/grid.html', { width: PHONE, height: 844 });
  await settled(phone, PAGE_MS);
  await stepTo(phone, /Voxel \[/);
  await shot(phone, 'grid-narrated-by-cells-390', '[data-whitted="view"] .figure-pane');
  await phone.close();
  await page.close();
  const casting = await open(browser, 'en/ray-casting.html');
  await settled(casting, PAGE_MS);
  s = await view(casting);
  assert.equal(s.accel, 'none');
  assert.match(s.command, /--accel none/);
  assert.ok(!s.steps.some((t) => /Visit node/.test(t)));
  await casting.close();
});

test('a refusal stays at the top in the page words, the last good image marked', async () => {
  const page = await open(browser, 'en/play.html');
  await settled(page, PAGE_MS);
  const scene = JSON.parse(await page.locator('[data-whitted="scene"]').inputValue());
  scene.camera.resolution = [5000, 5000];
  await page.locator('.editor summary').click();
  await page.locator('[data-whitted="scene"]').fill(JSON.stringify(scene));
  await page.waitForFunction(() => document.querySelector('[data-whitted="message"]').textContent !== '');
  await settled(page, PAGE_MS);
  await page.waitForTimeout(1500);
  const s = await view(page);
  assert.match(s.message, /5000×5000/);
  assert.doesNotMatch(s.message, /--size/);
  assert.ok(s.stale, 'the image is marked as the last good one');
  assert.deepEqual(page.problems, []);
  await page.close();
});

test('keys: Enter traces and gives the arrows back; arrows never change a select', async () => {
  const page = await open(browser, 'en/secondary-rays.html');
  await settled(page, PAGE_MS);
  const aa = page.locator('[data-whitted="aa"]').first();
  await aa.focus();
  const before = await view(page);
  await page.keyboard.press('ArrowRight');
  await page.keyboard.press('ArrowRight');
  const after = await view(page);
  assert.equal(after.aa, before.aa, 'the select keeps its value');
  assert.equal(after.step, before.step + 2, '→ walks the steps');
  const a11y = await page.evaluate(() => {
    const svg = document.querySelector('[data-whitted="figure"] svg');
    return { role: svg.getAttribute('role'), name: svg.getAttribute('aria-label'),
      live: document.querySelector('[data-whitted="current"]').getAttribute('aria-live') };
  });
  assert.equal(a11y.role, 'img');
  assert.ok(a11y.name && a11y.name.length > 5);
  assert.equal(a11y.live, 'polite');
  await page.close();
});

/** The lessons' names. */
/** How many pages the accessibility pass keeps open at once. */
const PAGES_AT_ONCE = 2;

function lessons() {
  return readdirSync(join(ROOT, 'lessons')).filter((f) => f.endsWith('.json')).sort()
    .map((f) => JSON.parse(readFileSync(join(ROOT, 'lessons', f), 'utf8')).name);
}

test('every page opens live, passes axe-core (no serious or critical violation) and reads at 390 px', { timeout: 60 * PAGE_MS }, async () => {
  const rows = [];
  const pages = [];
  for (const lang of ['en', 'ro']) for (const name of [...lessons(), 'play']) pages.push(`${lang}/${name}.html`);
  // Each page is one renderer process, and the machine has two cores: two pages at once.
  const queue = [...pages];
  const check = async (path) => {
    const page = await open(browser, path, { width: PHONE, height: 844 });
    await settled(page, PAGE_MS);
    // Live: every view rendered its image, its cost and its figure, with no refusal.
    const views = await page.evaluate(liveViews);
    assert.ok(views.length > 0, path);
    for (const v of views) assert.ok(v.live, `${path}: ${JSON.stringify(v)}`);
    assert.deepEqual(page.problems, [], path);
    await page.addScriptTag({ path: AXE });
    const result = await page.evaluate(async () => {
      const r = await self.axe.run(document, { resultTypes: ['violations'] });
      return r.violations.map((v) => ({ id: v.id, impact: v.impact, nodes: v.nodes.length,
        first: v.nodes[0] && v.nodes[0].target.join(' ') }));
    });
    // The smallest label of every figure, in CSS pixels, and the dimmed labels' opacity.
    const labels = await page.evaluate(() => {
      const out = [];
      for (const svg of document.querySelectorAll('[data-whitted="figure"] svg')) {
        const scale = svg.getBoundingClientRect().width / svg.viewBox.baseVal.width;
        let smallest = Infinity;
        for (const t of svg.querySelectorAll('text')) {
          smallest = Math.min(smallest, parseFloat(t.getAttribute('font-size') || getComputedStyle(t).fontSize) * scale);
        }
        out.push(smallest);
      }
      return out;
    });
    const serious = result.filter((v) => v.impact === 'serious' || v.impact === 'critical');
    rows.push({ path, violations: result.length, serious: serious.length, smallest: Math.min(...labels), detail: result });
    await page.close();
  };
  await Promise.all(Array.from({ length: PAGES_AT_ONCE }, async () => {
    while (queue.length > 0) await check(queue.shift());
  }));
  rows.sort((a, b) => pages.indexOf(a.path) - pages.indexOf(b.path));
  console.log('| page | axe violations | serious or critical | smallest label at 390 px |\n|---|---|---|---|');
  for (const r of rows) {
    console.log(`| ${r.path} | ${r.violations} | ${r.serious} | ${Number.isFinite(r.smallest) ? r.smallest.toFixed(1) + ' px' : '–'} |`);
  }
  for (const r of rows) {
    assert.equal(r.serious, 0, `${r.path}: ${JSON.stringify(r.detail)}`);
    if (Number.isFinite(r.smallest)) assert.ok(r.smallest >= LABEL_MIN_PX - 0.05, `${r.path}: ${r.smallest}`);
  }
});

test('a click at the centre of a pixel selects it at three widths of the image', async () => {
  for (const width of [1280, 1003, PHONE]) {
    const page = await open(browser, 'en/secondary-rays.html', { width, height: 900 });
    await settled(page, PAGE_MS);
    const canvas = page.locator('[data-whitted="image"]').first();
    const [nx, ny] = await canvas.evaluate((c) => [c.width, c.height]);
    for (const [i, j] of [[10, 10], [11, 10], [nx - 3, ny - 2], [317, 241]]) {
      // Measured before every click: the line offering the lesson's pixel moves the image.
      await canvas.scrollIntoViewIfNeeded();
      const box = await canvas.boundingBox();
      await page.mouse.click(box.x + ((i + 0.5) * box.width) / nx, box.y + ((ny - 1 - j + 0.5) * box.height) / ny);
      await settled(page, PAGE_MS);
      const s = await view(page);
      assert.deepEqual(s.target.pixel, [i, j], `width ${width} (image ${box.width} CSS px)`);
    }
    await page.close();
  }
});
