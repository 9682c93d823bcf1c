#!/usr/bin/env bash
# Builds the WebAssembly module of web/ (package whitted-web) for wasm32-unknown-unknown, optimises
# it with Binaryen's wasm-opt into target/wasm/whitted_web.wasm, and prints that path on stdout.
#
# rustup cannot add the wasm32 target on every machine; Debian's toolchain can (see web/README.md):
#   apt-get update && apt-get install -y rustc-web cargo-web rust-web-src lld binaryen
# gives /usr/bin/rustc, /usr/bin/cargo (1.96), the standard library's sources, wasm-ld and wasm-opt; the
# standard library is then compiled for wasm32 with the module (-Zbuild-std, allowed by
# RUSTC_BOOTSTRAP=1). When something is missing this script says what on stderr, with the command
# that installs it, and exits 3; with --install it runs that command itself (as root). With --check
# it stops there: exit 0 when the toolchain is complete, 3 when not, and builds nothing.
#
# Its target folder is target/wasm-build: another rustc's artefacts must not share the native one
# (mixing them gives E0514).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
install=no
check=no
for arg in "$@"; do
  case "$arg" in
    --install) install=yes ;;
    --check) check=yes ;;
    *) echo "web/build.sh: unknown argument \`$arg\` (only --install, --check)" >&2; exit 2 ;;
  esac
done

packages="rustc-web cargo-web rust-web-src lld binaryen"
install_cmd="apt-get update && apt-get install -y $packages"
rustc=/usr/bin/rustc
cargo=/usr/bin/cargo

# What is missing, one line each (empty when the toolchain is complete).
missing() {
  [ -x "$rustc" ] || echo "  $rustc (Debian package rustc-web)"
  [ -x "$cargo" ] || echo "  $cargo (Debian package cargo-web)"
  command -v wasm-ld > /dev/null || echo "  wasm-ld (Debian package lld)"
  command -v wasm-opt > /dev/null || echo "  wasm-opt (Debian package binaryen)"
  if [ -x "$rustc" ]; then
    local sysroot
    sysroot=$("$rustc" --print sysroot)
    [ -f "$sysroot/lib/rustlib/src/rust/library/Cargo.lock" ] \
      || echo "  the standard library's sources under $sysroot/lib/rustlib/src (Debian package rust-web-src)"
    # The crates' rust-version (Cargo.toml); without `apt-get update` Debian offers rustc-web 1.85.
    local minor want
    want=$(sed -nE 's/^rust-version = "1\.([0-9]+)"/\1/p' "$root/Cargo.toml")
    minor=$("$rustc" --version | sed -E 's/^rustc 1\.([0-9]+).*/\1/')
    [ "$minor" -ge "$want" ] 2>/dev/null \
      || echo "  rustc ≥ 1.$want at $rustc (it is $("$rustc" --version); run apt-get update first)"
  fi
}

gaps=$(missing)
if [ -n "$gaps" ] && [ "$install" = yes ]; then
  echo "web/build.sh: installing the WebAssembly toolchain: $install_cmd" >&2
  if [ "$(id -u)" -ne 0 ]; then
    echo "web/build.sh: --install needs root" >&2
    exit 3
  fi
  DEBIAN_FRONTEND=noninteractive sh -c "$install_cmd" >&2
  gaps=$(missing)
fi
if [ -n "$gaps" ]; then
  {
    echo "web/build.sh: the WebAssembly toolchain is incomplete; missing:"
    echo "$gaps"
    echo "install it with (as root): $install_cmd"
    echo "or run: web/build.sh --install"
  } >&2
  exit 3
fi
[ "$check" = no ] || exit 0

cd "$root"
build_dir="$root/target/wasm-build"
# A panic cannot happen on any request (web/src/lib.rs) and would abort the module either way:
# `-Cpanic=immediate-abort` and `-Zlocation-detail=none` leave out the panic messages' formatting
# and their file names (3 060 040 -> 2 979 778 bytes, the module's 3 MB budget).
flags="-C linker=wasm-ld -Zlocation-detail=none -Zunstable-options -Cpanic=immediate-abort"
# At the usual priority: beside cargo test (./test.sh, .ci/run) this build ends last, and the
# browser tests wait for both.
RUSTC="$rustc" RUSTC_BOOTSTRAP=1 RUSTFLAGS="$flags" CARGO_TARGET_DIR="$build_dir" \
  "$cargo" build --quiet --profile wasm --target wasm32-unknown-unknown \
  -Zbuild-std=std,panic_abort -p whitted-web >&2
mkdir -p "$root/target/wasm"
out="$root/target/wasm/whitted_web.wasm"
# Binaryen's optimiser on the linked module: the same speed in the page (bench/page-ab.mjs) and
# about 280 KB less (2 999 678 -> 2 721 601 bytes when this was added). The features are those
# rustc's wasm32 target emits (Binaryen 108 cannot detect them in a stripped module). It writes
# a temporary file, moved into place whole.
features="--enable-sign-ext --enable-mutable-globals --enable-nontrapping-float-to-int \
  --enable-bulk-memory --enable-multivalue --enable-reference-types"
# shellcheck disable=SC2086 # the features are separate words
wasm-opt -O3 $features "$build_dir/wasm32-unknown-unknown/wasm/whitted_web.wasm" -o "$out.part"
mv "$out.part" "$out"
echo "$out"
