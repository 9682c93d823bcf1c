// whitted's WebAssembly modules instantiated in a page of Chromium and called through
// web/README.md's ABI, as the course's worker calls them: shared by browser.mjs (`--module`)
// and page-ab.mjs.

/**
 * Instantiates each module of `buffers` (Node Buffers of .wasm files) in `page`. Afterwards,
 * `callModule(page, i, request)` runs request `request` in module `i`.
 */
export async function loadModules(page, buffers) {
  await page.evaluate(async (all) => {
    const encoder = new TextEncoder();
    const decoder = new TextDecoder();
    self.whittedCalls = [];
    for (const b64 of all) {
      const bytes = Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
      const { instance } = await WebAssembly.instantiate(bytes, {});
      const x = instance.exports;
      self.whittedCalls.push((request) => {
        const start = performance.now();
        const input = encoder.encode(JSON.stringify(request));
        const at = x.whitted_inbox(input.length);
        new Uint8Array(x.memory.buffer, at, input.length).set(input);
        const code = x.whitted_call();
        const json = decoder.decode(new Uint8Array(x.memory.buffer, x.whitted_outbox(), x.whitted_outbox_len()));
        const ms = performance.now() - start;
        if (code !== 0) throw new Error(json);
        return { ms, answer: JSON.parse(json) };
      });
    }
  }, buffers.map((b) => b.toString('base64')));
}

/**
 * Module `i`'s answer to `request`, with the whole call's time by the page's own clock (the
 * request written in, the call, the answer read out): `{ ms, answer }`.
 */
export function callModule(page, i, request) {
  return page.evaluate(([k, r]) => self.whittedCalls[k](r), [i, request]);
}
