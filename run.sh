#!/usr/bin/env bash
# The main job: render and trace the example scenes into out/ (English and Romanian narrations),
# draw every lesson's figures (lessons/) into out/en/ and out/ro/ with the interactive course's
# pages, and measure what accuracy costs on Whitted's scene (out/tradeoff.md, out/tradeoff/).
#
# The course is live on a fresh machine: the WebAssembly toolchain is installed first when it is
# missing (`web/build.sh --install`, as ./test.sh does; it needs root) and the module built, so
# that the release build carries it (build.rs) and `whitted lessons` writes it beside the pages.
# Where it cannot be installed, the rest of out/ is written and the pages are static (stderr
# says so and how to get the live part).
set -euo pipefail
cd "$(dirname "$0")"

toolchain=yes
code=0
web/build.sh --check 2> /dev/null || code=$?
if [ "$code" -eq 3 ]; then
  echo "run.sh: installing the WebAssembly toolchain (web/build.sh --install)" >&2
  if ! web/build.sh --install --check; then
    toolchain=no
    echo "run.sh: no WebAssembly toolchain; the course's pages will be static" >&2
  fi
elif [ "$code" -ne 0 ]; then
  exit "$code"
fi

# The module (target/wasm/whitted_web.wasm), before the release build that embeds it.
if [ "$toolchain" = yes ]; then
  web/build.sh > /dev/null
fi
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
# Every lesson's figures, PNG and SVG, in English (out/en/) and Romanian (out/ro/), the pages
# out/index.html and out/ro/index.html, and the course: out/en/NAME.html, out/ro/NAME.html,
# out/en/play.html, out/ro/play.html, with the module out/whitted-wasm.js (docs/course.md).
"$bin" lessons --out out
# What accuracy costs on Whitted's scene: the table, and its plots in out/tradeoff/.
"$bin" tradeoff scenes/whitted.json --out out/tradeoff > out/tradeoff.md
echo "wrote out/"
