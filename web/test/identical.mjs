// The WebAssembly module against the native binary, byte for byte: for many pixels of the lesson
// scenes, the trace document (`trace`) equals `whitted trace --json`, the narration's steps joined
// equal `whitted trace` (en, ro), and the figure SVGs equal `whitted figure KIND -o x.svg`.
//
//   web/build.sh && cargo build --release && node web/test/identical.mjs [path/to/whitted]
//
// Prints one line per scene and a summary; exits 1 on the first difference (saying where).
import { execFileSync, spawnSync } from "node:child_process";
import { mkdtempSync, readFileSync, readdirSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { load, root } from "./module.mjs";

const binary = process.argv[2] ?? join(root, "target", "release", "whitted");
const { call } = load();
const run = (args) => execFileSync(binary, args, { cwd: root, encoding: "utf8", maxBuffer: 1 << 28 });
const tmp = mkdtempSync(join(tmpdir(), "whitted-identical-"));
const kinds = ["ray-tree", "rays", "uv-map", "refraction", "local-model", "shadows", "bvh", "grid-dda"];

const scenes = readdirSync(join(root, "lessons", "scenes"))
  .filter((f) => f.endsWith(".json"))
  .sort()
  .map((f) => `lessons/scenes/${f}`)
  .concat(["scenes/whitted.json", "scenes/flat.json"]);

function fail(what, ours, theirs) {
  console.error(`DIFFERENT: ${what}\n--- wasm (${ours.length} bytes)\n${ours.slice(0, 400)}\n--- native (${theirs.length} bytes)\n${theirs.slice(0, 400)}`);
  rmSync(tmp, { recursive: true });
  process.exit(1);
}

let compared = 0;
for (const name of scenes) {
  const scene = readFileSync(join(root, name), "utf8");
  const info = JSON.parse(call({ op: "info", scene }).json);
  const { dimension, width, height } = info;
  const pixels = [];
  for (const [a, b] of [[1, 2], [0, 1], [1, 1], [1, 3], [2, 3], [1, 4], [3, 4], [1, 5]]) {
    const i = Math.min(Math.floor((width * a) / b), width - 1);
    const j = Math.min(Math.floor((height * (b - a)) / b), height - 1);
    const p = dimension === 2 ? [i] : [i, j];
    if (!pixels.some((q) => q.join() === p.join())) pixels.push(p);
  }
  let here = 0;
  for (const p of pixels) {
    const arg = p.join(",");
    const target = { pixel: p };
    const doc = call({ op: "trace", scene, target });
    const native = run(["trace", name, "--pixel", arg, "--json"]);
    if (doc.code !== 0 || doc.json !== native) fail(`${name} trace --pixel ${arg}`, doc.json, native);
    here++;
    for (const lang of ["en", "ro"]) {
      const told = call({ op: "narrate", scene, target, lang, name });
      const text = JSON.parse(told.json).steps.map((s) => s.text).join("\n") + "\n";
      const nativeText = run(["trace", name, "--pixel", arg, "--lang", lang]);
      if (text !== nativeText) fail(`${name} narrate --pixel ${arg} --lang ${lang}`, text, nativeText);
      here++;
    }
    for (const kind of kinds) {
      const fig = call({ op: "figure", kind, scene, name, target, lang: "en" });
      const out = join(tmp, "x.svg");
      const native = spawnSync(binary, ["figure", kind, name, "--pixel", arg, "-o", out], { cwd: root, encoding: "utf8" });
      if (native.status !== 0) {
        // The native figure refused this pixel: the wasm must refuse it with the same words.
        const words = native.stderr.trimEnd().replace(/^error: /, "");
        const ours = fig.code === 2 ? JSON.parse(fig.json).errors.join("\n") : fig.json;
        if (ours !== words) fail(`${name} figure ${kind} --pixel ${arg}: refused differently`, ours, words);
      } else {
        const nativeSvg = readFileSync(out, "utf8");
        const svg = fig.code === 0 ? JSON.parse(fig.json).svg : fig.json;
        if (svg !== nativeSvg) fail(`${name} figure ${kind} --pixel ${arg}`, svg, nativeSvg);
      }
      here++;
    }
  }
  compared += here;
  console.log(`${name}: ${pixels.length} pixels, ${here} outputs identical`);
}
rmSync(tmp, { recursive: true });
console.log(`identical: ${compared} outputs of ${scenes.length} scenes, wasm = native byte for byte`);
