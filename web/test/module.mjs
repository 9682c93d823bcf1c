// Loads target/wasm/whitted_web.wasm in node (20 or later) and calls it through the ABI of
// web/README.md: write the request into the inbox, call, read the outbox (and the bytes).
import { readFileSync } from "node:fs";
import { fileURLToPath } from "node:url";
import { dirname, join } from "node:path";

export const root = join(dirname(fileURLToPath(import.meta.url)), "..", "..");
export const wasmPath = join(root, "target", "wasm", "whitted_web.wasm");

/** Compiles and instantiates the module (the binding imports nothing). */
export function load(path = wasmPath) {
  const module = new WebAssembly.Module(readFileSync(path));
  const { exports } = new WebAssembly.Instance(module, {});
  const encoder = new TextEncoder();
  const decoder = new TextDecoder();
  /** One request (an object) → { code, json (text), bytes (Uint8Array, a copy) }. */
  function call(request) {
    const input = encoder.encode(JSON.stringify(request));
    const at = exports.whitted_inbox(input.length);
    new Uint8Array(exports.memory.buffer, at, input.length).set(input);
    const code = exports.whitted_call();
    const out = new Uint8Array(exports.memory.buffer, exports.whitted_outbox(), exports.whitted_outbox_len());
    const json = decoder.decode(out);
    const bytes = new Uint8Array(exports.memory.buffer, exports.whitted_bytes(), exports.whitted_bytes_len()).slice();
    return { code, json, bytes };
  }
  return { call, exports };
}
