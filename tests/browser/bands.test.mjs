// Issue 30 item 8: every image is rendered in bands, drawn as they come with the share done
// ("Rendering: p %"), in every sampling mode and in 2D; the counts the page sums over its bands are
// those of the module's whole render (render::band; its unit tests hold the pixels equal too).
import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { launch, open, settled } from './support.mjs';

/** How long a lesson page may take to settle (renders in a worker on a shared machine). */
const PAGE_MS = 120000;

let browser;
before(async () => { browser = await launch(); });
after(async () => { await browser?.close(); });

/** Renders view `k` again with `aa`, watching its stats line; returns the lines it showed, the
 *  rays the page summed and those of one whole render by the module. */
async function rerender(page, k, aa) {
  return page.evaluate(async ([index, mode]) => {
    const view = self.whitted.views[index];
    view.part('aa').value = mode;
    view.updateAdaptive();
    const stats = view.part('stats');
    const seen = [];
    const watch = new MutationObserver(() => seen.push(stats.textContent));
    watch.observe(stats, { childList: true, characterData: true, subtree: true });
    await view.render();
    watch.disconnect();
    const whole = await self.whitted.engines.render.call({ op: 'render', ...view.base() });
    const rays = Object.values(whole.json.rays).reduce((a, b) => a + b, 0);
    const shown = /([\d,]+) rays/.exec(stats.textContent);
    return { seen, summed: shown ? Number(shown[1].replace(/,/g, '')) : -1, rays, dimension: view.info.dimension };
  }, [k, aa]);
}

test('every sampling mode and a 2D scene render in bands with the share done', { timeout: 4 * PAGE_MS }, async () => {
  // supersampling's first view is 3D (whitted_small); recursion-depth's first is a 2D strip.
  for (const [name, dimension] of [['supersampling', 3], ['recursion-depth', 2]]) {
    const page = await open(browser, `en/${name}.html`);
    await settled(page, PAGE_MS);
    for (const aa of ['center', 'corners', 'adaptive']) {
      const r = await rerender(page, 0, aa);
      assert.equal(r.dimension, dimension, name);
      const shares = r.seen.map((t) => /^Rendering: (\d+) %/.exec(t)).filter(Boolean).map((m) => Number(m[1]));
      assert.ok(shares.length >= 2, `${name} ${aa}: the share done shown as bands come (${JSON.stringify(r.seen)})`);
      assert.ok(shares.every((p, i) => p > 0 && p < 100 && (i === 0 || p >= shares[i - 1])), `${name} ${aa}: ${shares}`);
      assert.equal(r.summed, r.rays, `${name} ${aa}: the bands' rays are the whole render's`);
    }
    assert.deepEqual(page.problems, [], name);
    await page.close();
  }
});
