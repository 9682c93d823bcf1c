#!/usr/bin/env bash
# What the browser tests need, installed when missing, then the WebAssembly module built: run by
# ./test.sh (and .ci/run) in the background while `cargo test` (and clippy) compile, so the
# downloads and the module's build overlap the native build. Prints its steps on stderr; exits
# non-zero when a step fails (the caller waits for it and fails with it).
#   1. apt (one at a time, apt holds a lock): the WebAssembly toolchain through
#      `web/build.sh --install` (which runs `apt-get update` first), then Debian's chromium
#      (`apt-get update` only if the step before did not run it);
#   2. npm, beside 1.: playwright-core, pinned in tests/browser/package-lock.json (`npm ci`): it
#      drives Chromium over the DevTools protocol, has no dependencies and downloads no browser;
#      and axe-core, pinned there too, the accessibility checker the browser tests run on every page;
#   3. after 1.: the module, target/wasm/whitted_web.wasm (web/build.sh).
# Installing needs root (as on CI); otherwise the missing piece and its command are printed.
set -euo pipefail
cd "$(dirname "$0")/.."

npm_job=
if ! [ -d tests/browser/node_modules/playwright-core ] || ! [ -d tests/browser/node_modules/axe-core ]; then
  echo "tests/setup.sh: installing playwright-core and axe-core (npm ci in tests/browser)" >&2
  (cd tests/browser && npm ci --no-audit --no-fund >&2) &
  npm_job=$!
fi

updated=no
code=0
web/build.sh --check 2> /dev/null || code=$?
if [ "$code" -eq 3 ]; then
  echo "tests/setup.sh: installing the WebAssembly toolchain (web/build.sh --install)" >&2
  web/build.sh --install --check
  updated=yes
elif [ "$code" -ne 0 ]; then
  exit "$code"
fi

if ! [ -x /usr/bin/chromium ]; then
  echo "tests/setup.sh: installing Debian's chromium for the browser tests" >&2
  [ "$updated" = yes ] || apt-get update >&2
  DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends chromium >&2
fi

web/build.sh > /dev/null

if [ -n "$npm_job" ]; then
  wait "$npm_job"
fi
