#!/usr/bin/env bash
# The main job: render and trace the example scenes into out/ (English and Romanian narrations),
# draw every lesson's figures (lessons/) into out/en/ and out/ro/ with the interactive course's
# pages, and measure what accuracy costs on Whitted's scene (out/tradeoff.md, out/tradeoff/).
set -euo pipefail
cd "$(dirname "$0")"
cargo build --release --quiet
mkdir -p out
bin=target/release/whitted
for scene in scenes/*.json; do
  name=$(basename "$scene" .json)
  "$bin" check "$scene" > "out/$name.check.txt"
  "$bin" render "$scene" -o "out/$name.png"
done
"$bin" trace scenes/whitted.json --pixel 400,200 > out/whitted.trace.en.txt
"$bin" trace scenes/whitted.json --pixel 400,200 --lang ro > out/whitted.trace.ro.txt
"$bin" trace scenes/whitted.json --pixel 400,200 --json > out/whitted.trace.json
"$bin" trace scenes/flat.json --pixel 30 --json > out/flat.trace.json
# The WebAssembly module of the interactive course (target/wasm/whitted_web.wasm). Where its
# toolchain is missing, web/build.sh says so with the command that installs it, and `lessons`
# writes the pages without their live part.
web/build.sh > /dev/null || echo "run.sh: no WebAssembly module; the course's pages will be static" >&2
# Every lesson's figures, PNG and SVG, in English (out/en/) and Romanian (out/ro/), the pages
# out/index.html and out/ro/index.html, and the course: out/en/NAME.html, out/ro/NAME.html,
# out/en/play.html, out/ro/play.html (docs/course.md).
"$bin" lessons --out out
# What accuracy costs on Whitted's scene: the table, and its plots in out/tradeoff/.
"$bin" tradeoff scenes/whitted.json --out out/tradeoff > out/tradeoff.md
echo "wrote out/"
