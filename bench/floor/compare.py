#!/usr/bin/env python3
"""whitted against the floor program (bench/floor/src/main.rs) on Whitted's scene, 640x480, one ray
per pixel centre, one thread: the same rays and the same bytes, and how much longer whitted takes.

Both must be built first:
    cargo build --release
    cargo build --release --manifest-path bench/floor/Cargo.toml
Then, from the repository root:
    python3 bench/floor/compare.py [--runs 15]

Each round runs both once, in alternating order, as fresh processes: whitted's trace-phase
`seconds` against the floor program's first repetition (both then trace into a fresh image). It
prints the medians and the median of the per-round ratios, and checks that the two images are
byte-identical and the rays by kind equal.
"""
import argparse
import importlib.util
import json
import os
import statistics
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
WHITTED = [os.path.join(ROOT, "target", "release", "whitted"), "render",
           os.path.join(ROOT, "bench", "scenes", "whitted.json"), "--size", "640x480",
           "--threads", "1", "--aa", "center", "--json", "-o", "/tmp/floor-whitted.png"]
FLOOR = [os.path.join(ROOT, "bench", "floor", "target", "release", "whitted-floor"), "/tmp/floor.ppm"]


def run_whitted():
    stats = json.loads(subprocess.run(WHITTED, capture_output=True, text=True, check=True)
                       .stdout.splitlines()[0])
    rays = stats["rays"]
    return stats["seconds"], [rays[k] for k in ("primary", "reflected", "transmitted", "shadow")]


def run_floor():
    lines = subprocess.run(FLOOR, capture_output=True, text=True, check=True).stdout.splitlines()
    first = float(next(l for l in lines if l.startswith("repetition 0:")).split()[2])
    words = next(l for l in lines if l.startswith("rays:")).replace(",", "").split()
    return first, [int(words[i]) for i in (1, 3, 5, 7)]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--runs", type=int, default=15)
    runs = parser.parse_args().runs
    w, f = [], []
    for k in range(runs):
        for name in (("whitted", "floor") if k % 2 == 0 else ("floor", "whitted")):
            if name == "whitted":
                seconds, w_rays = run_whitted()
                w.append(seconds)
            else:
                seconds, f_rays = run_floor()
                f.append(seconds)
    spec = importlib.util.spec_from_file_location("bench_run", os.path.join(ROOT, "bench", "run.py"))
    bench_run = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(bench_run)
    width, height, png = bench_run.read_png("/tmp/floor-whitted.png")
    ppm = open("/tmp/floor.ppm", "rb").read()
    header = f"P6\n{width} {height}\n255\n".encode()
    same = ppm.startswith(header) and ppm[len(header):] == bytes(png)
    print(f"rays (primary, reflected, transmitted, shadow): whitted {w_rays}, floor {f_rays}"
          f" ({'equal' if w_rays == f_rays else 'DIFFERENT'})")
    print(f"images: {'byte-identical' if same else 'DIFFERENT'}")
    print(f"trace seconds, median of {runs}: whitted {statistics.median(w):.4f}, floor {statistics.median(f):.4f}")
    print(f"whitted / floor, median of the per-round ratios: {statistics.median([a / b for a, b in zip(w, f)]):.2f}")


if __name__ == "__main__":
    main()
