#!/usr/bin/env python3
"""Several runs of bench/run.py read together: the time ratio POV-Ray / whitted by three estimators.

    python3 bench/pool.py bench/results/2026-11-29-cdebc22.json bench/results/2026-11-29-bdbf50d*.json

One run's ratio moves with the host by ±20–30 % (bench/README.md, "Current numbers"), so a goal at
a ratio is read over several runs of the same render. For each scene, sampling mode and thread
count the runs share, it prints:
  - the median over the runs of each run's paired median (run.py's "paired by round" table: run k
    of whitted against run k of POV-Ray, which follows it within seconds);
  - the rounds of every run pooled: POV-Ray's median trace time / whitted's median;
  - the rounds pooled: POV-Ray's fastest trace / whitted's fastest, where the host interfered
    least with each program;
and the range of the runs' paired medians. The files must come from runs of one render (the
script says which commits they name; it does not check that their renders agree).
"""
import argparse
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
# run.py's own reading of a results file and its estimators, so that a ratio here is one of its.
from run import f, least, median, paired_rounds, ratio, round_traces, spread  # noqa: E402


def key_of(config):
    return (config["scene"], config["mode"], config["threads"])


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("results", nargs="+", help="results files of bench/run.py")
    ap.add_argument("--threads", type=int, default=1, help="thread count to show (default 1; 0: all)")
    args = ap.parse_args()

    runs = []
    for path in args.results:
        with open(path) as file:
            runs.append(json.load(file))
    commits = sorted({r["machine"].get("commit", "?")[:7] for r in runs})
    keys = []
    for run in runs:
        for c in run["configs"]:
            if key_of(c) not in keys and (args.threads == 0 or c["threads"] == args.threads):
                keys.append(key_of(c))

    print(f"{len(runs)} runs, commits {', '.join(commits)}; time ratio POV-Ray / whitted:")
    print()
    print("| scene | AA | threads | runs | rounds | median of the runs' paired medians (range) "
          "| pooled medians | pooled fastest |")
    print("|---|---|---:|---:|---:|---:|---:|---:|")
    for key in keys:
        per_run, whitted, povray = [], [], []
        for run in runs:
            config = next((c for c in run["configs"] if key_of(c) == key), None)
            if config is None:
                continue
            pairs = paired_rounds(config)
            if pairs:
                per_run.append(median([p[0] / w[0] for w, p in pairs]))
            whitted += round_traces(config, "whitted")
            povray += round_traces(config, "povray")
        if not per_run:
            continue
        rounds = min(sum(t is not None for t in whitted), sum(t is not None for t in povray))
        print("| %s | %s | %d | %d | %d | %s | %s | %s |" % (
            *key, len(per_run), rounds, spread(per_run), f(ratio(median(povray), median(whitted))),
            f(ratio(least(povray), least(whitted)))))


if __name__ == "__main__":
    main()
