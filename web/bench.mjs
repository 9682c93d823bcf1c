// Measures the WebAssembly module in node (20 or later; Chromium runs the same V8):
//   - its size, raw and gzipped;
//   - compile + instantiate;
//   - a warm `trace` of scenes/whitted.json pixel 400,200 (the median of many calls, after a
//     first, cold one) and its `narrate`;
//   - a warm `figure` SVG (ray-tree, same pixel);
//   - a 320×240 `render` of scenes/whitted.json against the native binary on one thread
//     (`whitted render --threads 1 --json`, its `seconds`), the ratio from one run of each.
//
//   web/build.sh && cargo build --release && node web/bench.mjs [path/to/whitted]
//
// A benchmark, not a test: it prints numbers and checks nothing but that each call succeeds.
import { execFileSync } from "node:child_process";
import { readFileSync, statSync, mkdtempSync, rmSync } from "node:fs";
import { gzipSync } from "node:zlib";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { performance } from "node:perf_hooks";
import { load, root, wasmPath as builtPath } from "./test/module.mjs";

const wasmPath = process.env.WHITTED_WASM ?? builtPath;

const binary = process.argv[2] ?? join(root, "target", "release", "whitted");
const bytes = readFileSync(wasmPath);
const mb = (n) => (n / 1e6).toFixed(2);
console.log(`module: ${wasmPath}`);
console.log(`size: ${mb(bytes.length)} MB raw, ${mb(gzipSync(bytes, { level: 9 }).length)} MB gzip -9`);

let t0 = performance.now();
const { call } = load(wasmPath);
console.log(`compile + instantiate: ${(performance.now() - t0).toFixed(1)} ms`);

const scene = readFileSync(join(root, "scenes", "whitted.json"), "utf8");
const ok = (answer, what) => {
  if (answer.code !== 0) throw new Error(`${what}: ${answer.json}`);
  return answer;
};
/** The first call's time and the median of `runs` more, in ms. */
function timed(what, request, runs) {
  let start = performance.now();
  ok(call(request), what);
  const cold = performance.now() - start;
  const times = [];
  for (let k = 0; k < runs; k++) {
    start = performance.now();
    ok(call(request), what);
    times.push(performance.now() - start);
  }
  times.sort((a, b) => a - b);
  const median = times[Math.floor(times.length / 2)];
  console.log(`${what}: first ${cold.toFixed(2)} ms, then median ${median.toFixed(2)} ms of ${runs}`);
  return median;
}

const target = { pixel: [400, 200] };
timed("trace whitted.json 400,200", { op: "trace", scene, target }, 200);
timed("narrate whitted.json 400,200", { op: "narrate", scene, target, lang: "en" }, 200);
timed("figure ray-tree SVG 400,200", { op: "figure", kind: "ray-tree", scene, target }, 50);
timed("figure rays SVG 400,200", { op: "figure", kind: "rays", scene, target }, 50);

// 320×240: the module once (warm), the native binary on one thread once.
ok(call({ op: "render", scene, options: { size: [320, 240] } }), "render");
t0 = performance.now();
const render = ok(call({ op: "render", scene, options: { size: [320, 240] } }), "render");
const wasmMs = performance.now() - t0;
const tmp = mkdtempSync(join(tmpdir(), "whitted-bench-"));
const native = JSON.parse(
  execFileSync(binary, ["render", join(root, "scenes", "whitted.json"), "--size", "320x240", "--threads", "1",
    "--json", "-o", join(tmp, "x.png")], { encoding: "utf8", stdio: ["ignore", "pipe", "ignore"] }),
);
rmSync(tmp, { recursive: true });
const nativeMs = (native.build_seconds + native.seconds) * 1000;
const stats = JSON.parse(render.json);
if (stats.rays.primary !== native.rays.primary || stats.tests.object !== native.tests.object) {
  throw new Error("the module and the binary traced different rays");
}
console.log(`render 320x240: wasm ${wasmMs.toFixed(1)} ms (whole call, RGBA copied out), native 1 thread ` +
  `${nativeMs.toFixed(1)} ms (build + trace) → ratio ${(wasmMs / nativeMs).toFixed(2)} (one run each)`);
console.log(`node ${process.version}`);
