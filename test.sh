#!/usr/bin/env bash
# The README's test command, and CI's after fmt and clippy: `cargo test`, then the course's pages
# in headless Chromium (tests/browser/). What the browser tests need is installed when missing:
#   - the WebAssembly toolchain (Debian's rustc-web, cargo-web, rust-web-src, lld) through
#     `web/build.sh --install`, which runs `apt-get update` first;
#   - Debian's chromium (apt-get update only if the step above did not already run it);
#   - playwright-core, pinned in tests/browser/package-lock.json (`npm ci`): it drives Chromium
#     over the DevTools protocol, has no dependencies and downloads no browser; and axe-core,
#     pinned there too, the accessibility checker the browser tests run in every page.
# Installing needs root (as on CI); otherwise the missing piece and its command are printed.
set -euo pipefail
cd "$(dirname "$0")"
export CARGO_TERM_COLOR=${CARGO_TERM_COLOR:-never}

cargo test

# The WebAssembly module (target/wasm/whitted_web.wasm); exit code 3 = toolchain missing.
updated=no
code=0
web/build.sh > /dev/null || code=$?
if [ "$code" -eq 3 ]; then
  echo "test.sh: installing the WebAssembly toolchain (web/build.sh --install)" >&2
  web/build.sh --install > /dev/null
  updated=yes
elif [ "$code" -ne 0 ]; then
  exit "$code"
fi

if ! [ -x /usr/bin/chromium ]; then
  echo "test.sh: installing Debian's chromium for the browser tests" >&2
  [ "$updated" = yes ] || apt-get update
  DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends chromium >&2
fi

if ! [ -d tests/browser/node_modules/playwright-core ] || ! [ -d tests/browser/node_modules/axe-core ]; then
  echo "test.sh: installing playwright-core and axe-core (npm ci in tests/browser)" >&2
  (cd tests/browser && npm ci --no-audit --no-fund >&2)
fi

# The site the browser opens: every page, the live module, and the static figures of the lessons
# the tests open (the CLI that `cargo test` just built).
site=target/browser-site
rm -rf "$site"
target/debug/whitted lessons --out "$site" --only secondary-rays --size 960x540 > /dev/null
(cd tests/browser && WHITTED_SITE="../../$site" WHITTED_BIN=../../target/debug/whitted node --test)
