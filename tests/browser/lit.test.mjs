// Issue 30 item 3, measured: in every view of every lesson page, the default pixel's steps are
// walked one by one and each step is counted as lit when at least one item of the figure (or of
// the pixel's ray tree the page draws under a figure that shows a part of the trace) carries the
// class `lit` (its `data-events` meet the step's), or as said when the page says beside the
// figure that what it names is not drawn (`data-whitted="undrawn"`). The fraction of lit steps is
// printed per view (WHITTED_LIT_OUT also writes it as JSON); it must be at least LIT_SHARE in
// every view, and every dark step must say so. A view that follows no pixel must say why where
// its steps would be (issue 30 item 4).
import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync, readdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { ROOT, launch, open, settled } from './support.mjs';

/** The share of a view's steps that must light an item of its figure (issue 30 item 3). */
const LIT_SHARE = 0.9;
/** The figure kinds that draw no one pixel's trace (issue 32's discriminant and complexity too). */
const PIXELLESS_KINDS = ['heat-map', 'discriminant', 'complexity'];
/** How long a lesson page may take to settle (renders in a worker on a shared machine). */
const PAGE_MS = 120000;

let browser;
before(async () => { browser = await launch(); });
after(async () => { await browser?.close(); });

/** The lessons' names in file order, as `whitted lessons` writes their pages. */
function lessons() {
  return readdirSync(join(ROOT, 'lessons')).filter((f) => f.endsWith('.json')).sort()
    .map((f) => JSON.parse(readFileSync(join(ROOT, 'lessons', f), 'utf8')).name);
}

/** Walks every step of view `k` through the page's own `go`; per step: lit items, whether the
 *  page says what it names is not drawn, and the step's first line. */
async function walk(page, k) {
  return page.evaluate((index) => {
    const view = self.whitted.views[index];
    const root = view.root;
    const drawn = '[data-whitted="figure"] svg .lit, [data-whitted="overview"] svg .lit';
    const undrawn = root.querySelector('[data-whitted="undrawn"]');
    const out = [];
    for (let s = 0; s < view.steps.length; s++) {
      view.go(s);
      out.push({
        lit: root.querySelectorAll(drawn).length,
        said: Boolean(undrawn && !undrawn.hidden && undrawn.textContent.trim()),
        title: view.steps[s].text.trim().split('\n')[0].replace(/^\d+\.\s*/, ''),
      });
    }
    return {
      kind: root.querySelector('[data-whitted="kind"]').value,
      accel: root.querySelector('[data-whitted="accel"]').value,
      command: root.querySelector('[data-whitted="command"]').textContent,
      message: root.querySelector('[data-whitted="message"]').textContent,
      overview: Boolean(root.querySelector('[data-whitted="overview"] svg')),
      nopixel: (() => {
        const line = root.querySelector('[data-whitted="nopixel"]');
        return line && !line.hidden ? line.textContent.trim() : '';
      })(),
      steps: out,
    };
  }, k);
}

test('every step of every lesson view lights what it names', { timeout: 40 * PAGE_MS }, async () => {
  const rows = [];
  for (const name of lessons()) {
    const page = await open(browser, `en/${name}.html`);
    await settled(page, PAGE_MS);
    const views = await page.evaluate(() => self.whitted.views.length);
    for (let k = 0; k < views; k++) {
      const v = await walk(page, k);
      const lit = v.steps.filter((s) => s.lit > 0).length;
      const said = v.steps.filter((s) => s.lit === 0 && s.said).length;
      // The titles of the dark steps, counted, to say what stays dark.
      const dark = new Map();
      for (const s of v.steps.filter((x) => x.lit === 0)) {
        const key = s.title.replace(/[“„][^”]*”/g, '“…”').replace(/\d+(\.\d+)?/g, 'N');
        dark.set(key, (dark.get(key) || 0) + 1);
      }
      rows.push({ lesson: name, view: k + 1, kind: v.kind, accel: v.accel, lit, said, steps: v.steps.length,
        command: v.command, message: v.message, overview: v.overview, nopixel: v.nopixel,
        dark: Object.fromEntries(dark) });
    }
    assert.deepEqual(page.problems, [], name);
    await page.close();
  }
  const table = ['| lesson | view | kind | ray tree under it | accel | lit / steps | share | dark, said |',
    '|---|---|---|---|---|---|---|---|'];
  for (const r of rows) {
    const share = r.steps ? (100 * r.lit / r.steps).toFixed(0) + ' %' : '–';
    table.push(`| ${r.lesson} | ${r.view} | ${r.kind} | ${r.overview ? 'yes' : 'no'} | ${r.accel} | ${r.lit} / ${r.steps} | ${share} | ${r.said} |`);
  }
  console.log(table.join('\n'));
  for (const r of rows.filter((x) => x.lit < x.steps)) console.log(`${r.lesson} ${r.view} dark:`, JSON.stringify(r.dark));
  if (process.env.WHITTED_LIT_OUT) writeFileSync(process.env.WHITTED_LIT_OUT, JSON.stringify(rows, null, 1));
  for (const r of rows) {
    // A heat map, the discriminant's three rays and the cost-against-n plot follow no single pixel
    // until one is clicked; every other view narrates one.
    // until one is clicked, and say why where the steps would be, in the page's words for the kind.
    if (PIXELLESS_KINDS.includes(r.kind) && r.steps === 0) {
      assert.match(r.nopixel, /^No pixel to follow here: this figure .+ Click the image/,
        `${r.lesson} view ${r.view} (${r.kind}) says why it follows no pixel`);
      continue;
    }
    assert.equal(r.nopixel, '', `${r.lesson} view ${r.view}: a view with steps says nothing of a missing pixel`);
    assert.ok(r.steps > 0, `${r.lesson} view ${r.view} has steps (${r.message})`);
    assert.equal(r.lit + r.said, r.steps, `${r.lesson} view ${r.view}: every dark step says it is not drawn`);
    assert.ok(r.lit >= LIT_SHARE * r.steps,
      `${r.lesson} view ${r.view} (${r.kind}): ${r.lit} of ${r.steps} steps light an item; dark: ${JSON.stringify(r.dark)}`);
  }
});

test('a view that follows no pixel says why where its steps would be, in Romanian too', { timeout: 4 * PAGE_MS }, async () => {
  for (const [lang, name, kind, why] of [
    ['ro', 'bounding-volumes', 'discriminant', /^Aici nu se urmărește niciun pixel: figura desenează trei raze proprii/],
    ['ro', 'cost', 'complexity', /^Aici nu se urmărește niciun pixel: figura arată testele pe rază/],
  ]) {
    const page = await open(browser, `${lang}/${name}.html`);
    await settled(page, PAGE_MS);
    const said = await page.evaluate((wanted) => {
      const root = self.whitted.views.map((v) => v.root)
        .find((r) => r.querySelector('[data-whitted="kind"]').value === wanted);
      const line = root.querySelector('[data-whitted="nopixel"]');
      return { line: line.hidden ? '' : line.textContent, current: root.querySelector('[data-whitted="current"]').textContent,
        steps: root.querySelector('[data-whitted="steps"]').children.length };
    }, kind);
    assert.equal(said.steps, 0, `${name}: the ${kind} view has no steps`);
    assert.match(said.line, why, `${lang}/${name}: ${kind}`);
    assert.equal(said.current, said.line, 'the same line stands beside the figure');
    assert.deepEqual(page.problems, [], name);
    await page.close();
  }
});
