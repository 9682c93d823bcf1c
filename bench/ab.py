#!/usr/bin/env python3
"""Two or more whitted binaries on one scene, interleaved: which is faster, and by how much.

    cp target/release/whitted /tmp/whitted-before     # build, keep, change, build again
    python3 bench/ab.py /tmp/whitted-before target/release/whitted [--aa adaptive] [--rounds 40]

Each round runs every binary once, in the order given, as fresh processes, one thread (or
`--threads N`), and reads the trace-phase `seconds` of `render --json` (`--aa adaptive` with
run.py's settings, `--threshold 0.3 --max-level 2`). It prints each binary's median and minimum
and the median over rounds of (first binary's seconds / this binary's seconds): above 1 is faster than the
first. Rounds of back-to-back runs are what make a few per cent visible on a machine whose speed
drifts by ±10 % within seconds; one run against another shows nothing. It also checks that every
binary writes the same PNG bytes and traces the same rays (a layout change must not change them).
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("binaries", nargs="+", help="whitted binaries; the first is the baseline")
    ap.add_argument("--scene", default=os.path.join(ROOT, "bench", "scenes", "whitted.json"))
    ap.add_argument("--aa", default="center", choices=["center", "corners", "adaptive"])
    ap.add_argument("--size", default="640x480")
    ap.add_argument("--rounds", type=int, default=40)
    ap.add_argument("--accel", help="pass --accel to every binary")
    ap.add_argument("--threads", type=int, default=1, help="--threads of every run (default 1)")
    args = ap.parse_args()
    if len(args.binaries) < 2:
        sys.exit("bench/ab.py: give at least two binaries")

    seconds = {b: [] for b in args.binaries}
    with tempfile.TemporaryDirectory() as tmp:
        outputs = {}
        for r in range(args.rounds):
            for k, binary in enumerate(args.binaries):
                png = os.path.join(tmp, f"{k}.png")
                cmd = [binary, "render", args.scene, "--size", args.size, "--threads", str(args.threads),
                       "--aa", args.aa, "--json", "-o", png]
                if args.aa == "adaptive":
                    cmd += ["--threshold", "0.3", "--max-level", "2"]
                if args.accel:
                    cmd += ["--accel", args.accel]
                run = subprocess.run(cmd, capture_output=True, text=True, check=True)
                stats = json.loads(run.stdout.splitlines()[0])
                seconds[binary].append(stats["seconds"])
                if r == 0:
                    with open(png, "rb") as f:
                        outputs[binary] = (f.read(), stats["rays"])
        first = args.binaries[0]
        for binary in args.binaries[1:]:
            if outputs[binary] != outputs[first]:
                sys.exit(f"bench/ab.py: {binary} writes other bytes or rays than {first}")

    scene = os.path.relpath(args.scene, ROOT)
    print(f"{scene}, {args.size}, --aa {args.aa}, one thread, {args.rounds} rounds "
          "(same bytes and rays from every binary)")
    print()
    print("| binary | median (s) | min (s) | speed-up over the first (median of rounds) |")
    print("|---|---:|---:|---:|")
    base = seconds[first]
    for binary in args.binaries:
        mine = seconds[binary]
        speedup = statistics.median(a / b for a, b in zip(base, mine))
        print(f"| `{binary}` | {statistics.median(mine):.4f} | {min(mine):.4f} | {speedup:.3f} |")


if __name__ == "__main__":
    main()
