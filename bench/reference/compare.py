#!/usr/bin/env python3
"""Render every scene of bench/reference/scenes with whitted and with reference.py, in each sampling
mode, and compare: the 8-bit pixels (whitted's PNG against the reference's bytes) and the number
of primary rays, which algorithm.md §8 makes exact; then whitted's other acceleration structures
against the reference's `center` image. Prints a Markdown table; exits 1 on a mismatch.

reference.py is an independent implementation of algorithm.md and product.md, written from those
documents alone (see README.md). A pixel may differ by 1/255 where the two sum the same terms in a
different order and a channel lands next to a rounding edge; anything more is a disagreement.

Usage (from the repository root, after `cargo build --release`):
    python3 bench/reference/compare.py                 # every scene, every mode
    python3 bench/reference/compare.py --only dense-glass
"""
import argparse
import importlib.util
import json
import os
import random
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))

# (label, whitted/reference arguments): every sampling mode, and two overrides of the scene.
MODES = [
    ("center", ["--aa", "center"]),
    ("corners", ["--aa", "corners"]),
    ("adaptive 0.1, K = 2", ["--aa", "adaptive", "--threshold", "0.1", "--max-level", "2"]),
    ("adaptive 0, K = 1", ["--aa", "adaptive", "--threshold", "0", "--max-level", "1"]),
    ("adaptive 0.05, K = 3", ["--aa", "adaptive", "--threshold", "0.05", "--max-level", "3"]),
    ("corners, depth 2", ["--aa", "corners", "--depth", "2"]),
]
SIZE = "48x36"
# whitted's other acceleration structures (the default is bvh), each held to the reference's
# `center` image: every structure must give brute force's nearest hit (§11).
STRUCTURES = ["none", "bounds", "grid", "octree"]


# Pixels traced per scene, and how far a traced colour may be from the reference's: the two sum
# the same terms, in orders that may differ by an ulp or so per term.
TRACED = 8
TRACE_TOLERANCE = 1e-12


def reference_native(scene, path):
    """The reference's `center` render at the scene's own resolution."""
    subprocess.run([sys.executable, os.path.join(HERE, "reference.py"), scene, "-o", path],
                   capture_output=True, text=True, check=True)
    with open(path) as fh:
        return json.load(fh)


def load_png_reader():
    """bench/run.py's stdlib PNG reader."""
    spec = importlib.util.spec_from_file_location("bench_run", os.path.join(REPO, "bench", "run.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.read_png


def whitted(binary, scene, args, png, size=SIZE):
    out = subprocess.run([binary, "render", scene, "-o", png, "--size", size, "--json"] + args,
                         capture_output=True, text=True, check=True).stdout
    return json.loads(out.strip().splitlines()[-1])


def reference(scene, args, path, size=SIZE):
    subprocess.run([sys.executable, os.path.join(HERE, "reference.py"), scene, "-o", path,
                    "--size", size] + args, capture_output=True, text=True, check=True)
    with open(path) as fh:
        return json.load(fh)


def compare(read_png, png, ref):
    """(largest channel difference in 1/255, pixels differing by more than 1/255)."""
    width, height, pixels = read_png(png)
    assert (width, height) == (ref["width"], ref["height"])
    worst, off = 0, 0
    for j in range(height):  # the reference's row 0 is the bottom row; the file's, the top one
        for i in range(width):
            k = ((height - 1 - j) * width + i) * 3
            d = max(abs(a - b) for a, b in zip(pixels[k:k + 3], ref["bytes"][j * width + i]))
            worst = max(worst, d)
            off += d > 1
    return worst, off


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--binary", default=os.path.join(REPO, "target", "release", "whitted"))
    ap.add_argument("--only", action="append", help="a scene name (file name without .json)")
    args = ap.parse_args()
    read_png = load_png_reader()
    scenes = sorted(f[:-5] for f in os.listdir(os.path.join(HERE, "scenes")) if f.endswith(".json"))
    if args.only:
        scenes = [s for s in scenes if s in args.only]
    rows, bad = [], 0
    started = time.time()
    with tempfile.TemporaryDirectory() as work:
        for name in scenes:
            scene = os.path.join(HERE, "scenes", name + ".json")
            runs = [(label, mode, mode) for label, mode in MODES]
            runs += [(f"center, --accel {a}", ["--aa", "center", "--accel", a], ["--aa", "center"])
                     for a in STRUCTURES]
            refs = {}
            for label, ours_args, ref_args in runs:
                png = os.path.join(work, "w.png")
                ours = whitted(args.binary, scene, ours_args, png)
                key = tuple(ref_args)
                if key not in refs:
                    refs[key] = reference(scene, ref_args, os.path.join(work, f"r{len(refs)}.json"))
                ref = refs[key]
                worst, off = compare(read_png, png, ref)
                ours_primary, ref_primary = ours["rays"]["primary"], ref["primary_rays"]
                ok = off == 0 and ours_primary == ref_primary
                bad += not ok
                rows.append(f"| {name} | {label} | {worst} | {off} | {ours_primary} | {ref_primary} | "
                            f"{'yes' if ok else '**no**'} |")
        # The trace of one pixel against the reference's linear colour, to the last bits: a
        # sample of pixels of each scene at its own resolution (`trace` has no --size).
        traced, largest = 0, 0.0
        rng = random.Random(1)
        for name in scenes:
            scene = os.path.join(HERE, "scenes", name + ".json")
            ref = reference_native(scene, os.path.join(work, "native.json"))
            width, height = ref["width"], ref["height"]
            with open(scene) as fh:
                flat = len(json.load(fh)["camera"]["eye"]) == 2
            for _ in range(TRACED):
                # A 2D scene's pixel is named by its column; every row of its strip is the same.
                i, j = rng.randrange(width), 0 if flat else rng.randrange(height)
                pixel = f"{i}" if flat else f"{i},{j}"
                doc = json.loads(subprocess.run([args.binary, "trace", scene, "--pixel", pixel, "--json"],
                                                capture_output=True, text=True, check=True).stdout)
                difference = max(abs(a - b) for a, b in zip(doc["color"], ref["pixels"][j * width + i]))
                largest = max(largest, difference)
                traced += 1
                if difference > TRACE_TOLERANCE:
                    bad += 1
                    print(f"{name} pixel ({i}, {j}): traced {doc['color']}, reference "
                          f"{ref['pixels'][j * width + i]}", file=sys.stderr)
    print(f"{SIZE}, {len(rows)} renders, {time.time() - started:.0f} s\n")
    print("| scene | sampling | largest difference (/255) | pixels off by > 1 | primary rays whitted "
          "| primary rays reference | agree |")
    print("|---|---|---:|---:|---:|---:|---|")
    print("\n".join(rows))
    print(f"\n`whitted trace --pixel` against the reference's linear colour: {traced} pixels, largest "
          f"difference {largest:.3g} (allowed {TRACE_TOLERANCE:g}).")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
