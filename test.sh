#!/usr/bin/env bash
# The README's test command, and CI's after fmt and clippy: `cargo test`, then the course's pages
# in headless Chromium (tests/browser/). What the browser tests need (the WebAssembly toolchain,
# Debian's chromium, the pinned playwright-core and axe-core) is installed when missing and the WebAssembly
# module built by tests/setup.sh, in the background while `cargo test` runs; its failure fails
# this script, with its log (a failing `cargo test` leaves it to finish: an install is not cut
# short). Installing needs root (as on CI); otherwise the missing piece and its command are printed.
# With WHITTED_SETUP=PREFIX (.ci/run) a setup is already running: this script starts none, and
# after cargo test waits for PREFIX.status, that setup's exit code (while its process, PREFIX.pid,
# lives), and prints PREFIX.log.
set -euo pipefail
cd "$(dirname "$0")"
export CARGO_TERM_COLOR=${CARGO_TERM_COLOR:-never}

mkdir -p target
if [ -n "${WHITTED_SETUP:-}" ]; then
  setup_log=$WHITTED_SETUP.log
else
  setup_log=target/setup.log
  tests/setup.sh > "$setup_log" 2>&1 &
  setup=$!
fi

cargo test

code=0
if [ -n "${WHITTED_SETUP:-}" ]; then
  while ! [ -f "$WHITTED_SETUP.status" ]; do
    if ! kill -0 "$(cat "$WHITTED_SETUP.pid")" 2> /dev/null && ! [ -f "$WHITTED_SETUP.status" ]; then
      echo "test.sh: the setup of $WHITTED_SETUP.pid ended without writing $WHITTED_SETUP.status" >&2
      exit 1
    fi
    sleep 1
  done
  code=$(cat "$WHITTED_SETUP.status")
else
  wait "$setup" || code=$?
fi
cat "$setup_log" >&2
if [ "$code" -ne 0 ]; then
  echo "test.sh: tests/setup.sh failed (exit $code); its log is above" >&2
  exit "$code"
fi

# The site the browser opens: every page, the live module, and the static figures of the lessons
# the tests open (the CLI that `cargo test` just built).
site=target/browser-site
rm -rf "$site"
target/debug/whitted lessons --out "$site" --only secondary-rays --size 960x540 > /dev/null
(cd tests/browser && WHITTED_SITE="../../$site" WHITTED_BIN=../../target/debug/whitted node --test)
