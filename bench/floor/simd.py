#!/usr/bin/env python3
"""The scalar floor program against the SIMD one, as pairs of binaries, on Whitted's scene, one thread.

Each round runs every binary once as a fresh process (the order reversed every other round, so a
slow spell falls on both sides), with REPETITIONS renders in the process. Per binary: the median of
the first repetitions, and of the in-process medians; per pair: the median of the per-round ratios
scalar / SIMD (first repetition, and in-process median), with their range. It fails (exit 1) when
a binary wrote other PPM bytes than the first, or printed other rays.

From the repository root, with the binaries built (see the module doc of
bench/floor/src/bin/whitted-floor-simd.rs; a target CPU's pair in its own CARGO_TARGET_DIR):
    taskset -c 1 python3 bench/floor/simd.py --runs 15 \\
        bench/floor/target/release/whitted-floor bench/floor/target/release/whitted-floor-simd \\
        [SCALAR2 SIMD2 ...]
"""
import argparse
import filecmp
import re
import statistics
import subprocess
import sys

parser = argparse.ArgumentParser()
parser.add_argument("--runs", type=int, default=15)
parser.add_argument("--repetitions", type=int, default=5)
parser.add_argument("binaries", nargs="+", help="scalar, SIMD, scalar, SIMD, ...")
args = parser.parse_args()
bins = args.binaries
assert len(bins) % 2 == 0, "pairs of binaries: scalar then SIMD"
# By position in the list: a binary may stand in two pairs (it then runs twice a round).
first = [[] for _ in bins]
inproc = [[] for _ in bins]
rays = [None for _ in bins]
for r in range(args.runs):
    for k in range(len(bins)) if r % 2 == 0 else reversed(range(len(bins))):
        ppm = "/tmp/floor-compare-%d.ppm" % k
        out = subprocess.run([bins[k], ppm, str(args.repetitions)], capture_output=True, text=True,
                             check=True).stdout
        times = [float(t) for t in re.findall(r"repetition \d+: ([0-9.]+) s", out)]
        first[k].append(times[0])
        inproc[k].append(statistics.median(times))
        rays[k] = re.search(r"rays: .*", out).group(0)
bad = False
for k, b in enumerate(bins):
    same = filecmp.cmp("/tmp/floor-compare-0.ppm", "/tmp/floor-compare-%d.ppm" % k, shallow=False)
    print(f"{b}: first repetition {statistics.median(first[k]):.4f} s "
          f"({min(first[k]):.4f}-{max(first[k]):.4f}), in-process median {statistics.median(inproc[k]):.4f} s; "
          f"bytes {'identical' if same else 'DIFFERENT'}, {rays[k]}"
          + ("" if rays[k] == rays[0] else " (RAYS DIFFER)"))
    bad = bad or not same or rays[k] != rays[0]
for scalar in range(0, len(bins), 2):
    simd = scalar + 1
    for name, series in (("first repetition", first), ("in-process median", inproc)):
        ratios = [a / b for a, b in zip(series[scalar], series[simd])]
        print(f"{bins[scalar]} / {bins[simd]}, {name}: median {statistics.median(ratios):.3f} "
              f"(range {min(ratios):.3f}-{max(ratios):.3f}, {len(ratios)} rounds)")
sys.exit(1 if bad else 0)
