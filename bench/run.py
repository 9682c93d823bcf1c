#!/usr/bin/env python3
"""Benchmark whitted against POV-Ray 3.7 on the same scenes, and print the comparison as Markdown.

What it measures, for each scene x sampling mode x thread count (1 and 2), at 640x480:

  whitted   `target/release/whitted render SCENE.json --aa MODE --threads N --size 640x480 --json`;
            its own figures: trace-phase `seconds`, rays by kind, load and build times.
  POV-Ray   `povray SCENE.pov ...` with the exact options of the shared bench/povray/README.md
            (-D +V -J Antialias_Gamma=1.0 File_Gamma=1.0 +FN); its statistics block: Trace Time,
            Rays, Shadow Ray Tests, Reflected/Refracted Rays, Parse and Bounding Time.

Sampling modes (ours = POV-Ray's):
  center    --aa center                                         = -A
  corners   --aa corners                                        = +A0.3 +AM2 +R1
  adaptive  --aa adaptive --max-level 2 --threshold 0.3         = +A0.3 +AM2 +R3

Both programs run the same number of times (3, or 1 with --quick), one after the other and never
at once, whitted and POV-Ray alternating, and the 1- and 2-thread runs of a mode in turns; the
tables show medians (or, with --stat min, minima). For every run the script also
keeps the wall time, user/system CPU and peak resident memory of the process (from os.wait4), and
the CPU time other processes used meanwhile (from /proc/stat), so a disturbed run shows.
Rays/s: whitted = (primary + reflected + transmitted + shadow) / trace seconds;
        POV-Ray = (Rays + Shadow Ray Tests) / Trace Time.
Each round of a mode also runs two `whitted --threads 1` renders of the scene at once: the machine's
own ceiling for two threads on this work is 2 x (trace time alone) / (trace time of each of the two
at once), which is 2 only where two busy CPUs run as fast as one (shared or throttled CPUs, a busy
host make it less). The 2-thread speed-ups are shown against it.
Last, the images of each mode at one thread are compared pixel by pixel (a small PNG reader,
stdlib only): the share of pixels whose every channel is within 2/255 of POV-Ray's.

Usage (from the repository root; build first with `cargo build --release`):
    python3 bench/run.py                      # everything, 3 runs each (several minutes)
    python3 bench/run.py --quick --only whitted
    python3 bench/run.py --no-povray          # whitted only
Results: bench/results/DATE-COMMIT.json (UTC date, short commit, `-dirty` with local changes;
`-2`, `-3` … for another run of the same day and commit), written by this script and tracked: the
command line, the commit, the start and end times, the machine (CPU, cores, kernel, load average at the start and
at the end), every run's raw figures, and the Markdown tables it prints (`tables`). `--results DIR`
writes elsewhere (a trial run), `--dry-run` prints the commands and where the file would go
without running anything. The images and a copy of the tables stay in /tmp/whitted-bench.
"""
import argparse
import json
import os
import platform
import re
import shlex
import statistics
import struct
import subprocess
import sys
import tempfile
import threading
import time
import zlib

BENCH = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(BENCH)
SCENE_DIR = os.path.join(BENCH, "scenes")
WORK = "/tmp/whitted-bench"
RESULTS = os.path.join(BENCH, "results")
WIDTH, HEIGHT = 640, 480

# name, our scene file (in bench/scenes/), POV-Ray's scene file and declarations
SCENES = [
    ("whitted", "whitted.json", ["whitted.pov"]),
    ("spheres-1k", "spheres-1k.json", ["spheres-grid.pov", "Declare=N=1000"]),
    ("spheres-10k", "spheres-10k.json", ["spheres-grid.pov", "Declare=N=10000"]),
    ("mesh-100k", "mesh-100k.json", ["mesh.pov", "Declare=MESH_K=100"]),
    ("mesh-1000k", "mesh-1000k.json", ["mesh.pov", "Declare=MESH_K=1000"]),
]
# name, whitted options, POV-Ray options
MODES = [
    # center is whitted's default: no flag, so that a whitted without --aa (before anti-aliasing
    # was merged) runs this mode too.
    ("center", [], ["-A"]),
    ("corners", ["--aa", "corners"], ["+A0.3", "+AM2", "+R1"]),
    ("adaptive", ["--aa", "adaptive", "--max-level", "2", "--threshold", "0.3"], ["+A0.3", "+AM2", "+R3"]),
]
THREADS = [1, 2]
POV_COMMON = ["-D", "+V", "-J", "Antialias_Gamma=1.0", "File_Gamma=1.0", "+FN"]
RAY_KINDS = ["primary", "reflected", "transmitted", "shadow"]


def log(msg):
    print(msg, file=sys.stderr, flush=True)


# ----------------------------------------------------------------------------------------------
# Running a process and measuring it


def busy_jiffies():
    """Clock ticks all CPUs have spent doing anything but idling, since boot."""
    with open("/proc/stat") as f:
        fields = [int(x) for x in f.readline().split()[1:]]
    idle, iowait = fields[3], fields[4]
    guest = sum(fields[8:])  # guest time is already counted in user time
    return sum(fields) - idle - iowait - guest


def measure(cmd, cwd, timeout):
    """Run cmd to completion; return its output, exit code and resource usage.

    os.wait4 gives the usage of exactly this child (peak RSS, CPU), which resource.getrusage of
    RUSAGE_CHILDREN cannot: its ru_maxrss is the largest over all children so far."""
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        timed_out = threading.Event()
        jiffies0, start = busy_jiffies(), time.perf_counter()
        proc = subprocess.Popen(cmd, cwd=cwd, stdin=subprocess.DEVNULL, stdout=out, stderr=err)

        def kill():
            timed_out.set()
            proc.kill()

        timer = threading.Timer(timeout, kill)
        timer.start()
        _, status, usage = os.wait4(proc.pid, 0)
        wall = time.perf_counter() - start
        timer.cancel()
        proc.returncode = os.waitstatus_to_exitcode(status)  # reaped here; Popen must not wait again
        jiffies1 = busy_jiffies()
        out.seek(0)
        err.seek(0)
        stdout = out.read().decode("utf-8", "replace")
        stderr = err.read().decode("utf-8", "replace")
    cpu = usage.ru_utime + usage.ru_stime
    return {
        "cmd": cmd, "exit": proc.returncode, "timeout": timed_out.is_set(),
        "wall_s": wall, "user_s": usage.ru_utime, "sys_s": usage.ru_stime,
        "max_rss_mb": usage.ru_maxrss / 1024.0,  # Linux reports kilobytes
        "other_cpu_s": (jiffies1 - jiffies0) / os.sysconf("SC_CLK_TCK") - cpu,
        "stdout": stdout, "stderr": stderr,
    }


def measure_pair(cmds, cwd, timeout):
    """Run the commands at once; return each one's trace seconds (None for a failed run)."""
    procs, outs = [], []
    for cmd in cmds:
        out = tempfile.TemporaryFile()
        outs.append(out)
        procs.append(subprocess.Popen(cmd, cwd=cwd, stdin=subprocess.DEVNULL, stdout=out,
                                      stderr=subprocess.DEVNULL))
    seconds = []
    for proc, out in zip(procs, outs):
        try:
            code = proc.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()
            code = None
        out.seek(0)
        text = out.read().decode("utf-8", "replace")
        out.close()
        try:
            seconds.append(parse_whitted(text)["seconds"] if code == 0 else None)
        except (ValueError, KeyError, TypeError):
            seconds.append(None)
    return seconds


# ----------------------------------------------------------------------------------------------
# whitted


def whitted_command(binary, scene_path, mode_args, threads, image, accel):
    cmd = [binary, "render", scene_path, "-o", image] + mode_args
    cmd += ["--threads", str(threads), "--size", "%dx%d" % (WIDTH, HEIGHT), "--json"]
    if accel:
        cmd += ["--accel", accel]
    return cmd


def parse_whitted(stdout):
    """The one JSON object `render --json` prints (the last line that parses, to be lenient)."""
    try:
        return json.loads(stdout)
    except ValueError:
        pass
    for line in reversed(stdout.strip().splitlines()):
        line = line.strip()
        if line.startswith("{"):
            try:
                return json.loads(line)
            except ValueError:
                continue
    raise ValueError("no JSON object on stdout")


def whitted_figures(stats):
    rays = stats.get("rays") or {}
    total = sum(int(rays.get(k) or 0) for k in RAY_KINDS)
    return {
        "trace_s": float(stats["seconds"]),
        "setup_s": float(stats.get("load_seconds") or 0) + float(stats.get("build_seconds") or 0),
        "rays": total,
        "by_kind": {k: int(rays.get(k) or 0) for k in RAY_KINDS},
        "accel": stats.get("accel"),
        "threads_reported": stats.get("threads"),
    }


# ----------------------------------------------------------------------------------------------
# POV-Ray


def povray_command(pov_args, mode_args, threads, image):
    return (["povray"] + pov_args + ["+W%d" % WIDTH, "+H%d" % HEIGHT] + mode_args
            + ["+WT%d" % threads] + POV_COMMON + ["+O" + image])


def parse_povray(text):
    """Counts from POV-Ray's 'Render Statistics' block and its phase times (seconds)."""
    text = text.replace("\r", "\n")
    found = {}

    def grab(key, pattern, cast=int):
        m = re.search(pattern, text, re.M)
        if m:
            found[key] = cast(m.group(1))

    grab("pixels", r"^Pixels:\s+(\d+)")
    grab("samples", r"^Pixels:.*Samples:\s+(\d+)")
    grab("rays", r"^Rays:\s+(\d+)")
    grab("max_level", r"^Rays:.*Max Level:\s+(\d+/\d+)", str)
    grab("shadow_tests", r"^Shadow Ray Tests:\s+(\d+)")
    grab("shadow_succeeded", r"^Shadow Ray Tests:.*Succeeded:\s+(\d+)")
    grab("reflected", r"^Reflected Rays:\s+(\d+)")
    grab("total_internal", r"^Reflected Rays:.*Total Internal:\s+(\d+)")
    grab("refracted", r"^Refracted Rays:\s+(\d+)")
    grab("transmitted", r"^Transmitted Rays:\s+(\d+)")
    for phase in ("Parse", "Bounding", "Trace"):
        grab(phase.lower() + "_s", r"^\s*%s Time:.*\(([\d.]+) seconds\)" % phase, float)
    # the intersection-test table: 'Sphere   813989   349654   42.96'
    table = re.search(r"^Ray->Shape Intersection.*?\n-+\n(.*?)\n-+", text, re.M | re.S)
    if table:
        found["shape_tests"] = {}
        for row in table.group(1).splitlines():
            m = re.match(r"^(\S.*?)\s+(\d+)\s+(\d+)\s+[\d.]+\s*$", row)
            if m:
                found["shape_tests"][m.group(1)] = [int(m.group(2)), int(m.group(3))]
    return found


def povray_figures(stats):
    if "trace_s" not in stats or "rays" not in stats:
        raise ValueError("no statistics block (Trace Time, Rays) in POV-Ray's output")
    reflected, refracted = stats.get("reflected", 0), stats.get("refracted", 0)
    return {
        "trace_s": stats["trace_s"],
        "setup_s": stats.get("parse_s", 0.0) + stats.get("bounding_s", 0.0),
        "rays": stats["rays"] + stats.get("shadow_tests", 0),
        # POV-Ray's Rays = camera rays + reflected + refracted (those refused at the depth limit too)
        "by_kind": {"primary": stats["rays"] - reflected - refracted, "reflected": reflected,
                    "transmitted": refracted, "shadow": stats.get("shadow_tests", 0)},
    }


def prepare_povray_dir(pov_dir, scene_names):
    """POV-Ray (Debian's povray.conf) reads only its current folder, /tmp and a few others, and the
    shared folder is read-only, so render from WORK/povray: links to the .pov/.inc files and to the
    mesh .inc files gen_scenes.py wrote next to our OBJ files."""
    run_dir = os.path.join(WORK, "povray")
    os.makedirs(run_dir, exist_ok=True)
    links = {f: os.path.join(pov_dir, f) for f in os.listdir(pov_dir)
             if f.endswith((".pov", ".inc")) and not f.startswith("mesh-")}
    for name in scene_names:
        if name.startswith("mesh-"):
            links[name + ".inc"] = os.path.join(SCENE_DIR, name + ".inc")
    for link, target in links.items():
        path = os.path.join(run_dir, link)
        if os.path.lexists(path):
            os.remove(path)
        os.symlink(target, path)
    return run_dir


def povray_version():
    try:
        p = subprocess.run(["povray", "--version"], capture_output=True, text=True)
    except OSError:
        return None
    for line in (p.stdout + p.stderr).splitlines():
        if line.startswith("POV-Ray"):
            return line.strip()
    return "POV-Ray (version unknown)"


# ----------------------------------------------------------------------------------------------
# PNG reading (8- or 16-bit grey/RGB with or without alpha, non-interlaced), for the comparison


def paeth(a, b, c):
    p = a + b - c
    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
    if pa <= pb and pa <= pc:
        return a
    return b if pb <= pc else c


def unfilter(kind, line, prev, bpp):
    """Undo one scanline's PNG filter in place (line and prev are bytearrays of equal length)."""
    n = len(line)
    if kind == 0:
        return
    if kind == 1:  # Sub
        for i in range(bpp, n):
            line[i] = (line[i] + line[i - bpp]) & 0xFF
    elif kind == 2:  # Up
        for i in range(n):
            line[i] = (line[i] + prev[i]) & 0xFF
    elif kind == 3:  # Average
        for i in range(n):
            left = line[i - bpp] if i >= bpp else 0
            line[i] = (line[i] + ((left + prev[i]) >> 1)) & 0xFF
    elif kind == 4:  # Paeth
        for i in range(n):
            if i >= bpp:
                line[i] = (line[i] + paeth(line[i - bpp], prev[i], prev[i - bpp])) & 0xFF
            else:
                line[i] = (line[i] + prev[i]) & 0xFF
    else:
        raise ValueError("unknown PNG filter type %d" % kind)


def read_png(path):
    """Return (width, height, pixels): pixels is bytes, 8-bit RGB, rows top to bottom."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("%s: not a PNG file" % path)
    pos, header, compressed = 8, None, []
    while pos + 8 <= len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        pos += 12 + length  # length, type, body, CRC
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            compressed.append(body)
        elif kind == b"IEND":
            break
    if header is None:
        raise ValueError("%s: no IHDR chunk" % path)
    width, height, depth, colour, _, _, interlace = header
    channels = {0: 1, 2: 3, 4: 2, 6: 4}.get(colour)
    if channels is None or depth not in (8, 16) or interlace != 0:
        raise ValueError("%s: unsupported PNG (colour type %d, depth %d, interlace %d)"
                         % (path, colour, depth, interlace))
    bpp = channels * depth // 8
    stride = width * bpp
    raw = zlib.decompress(b"".join(compressed))
    if len(raw) < height * (stride + 1):
        raise ValueError("%s: image data too short" % path)
    rgb = bytearray()
    prev = bytearray(stride)
    for y in range(height):
        start = y * (stride + 1)
        line = bytearray(raw[start + 1:start + 1 + stride])
        unfilter(raw[start], line, prev, bpp)
        prev = line
        if depth == 16:  # keep the high byte... rounded: v16 / 257 to the nearest 8-bit value
            line = bytearray((((line[i] << 8) | line[i + 1]) + 128) // 257 for i in range(0, stride, 2))
        if channels == 3:
            rgb += line
        elif channels == 4:
            for x in range(width):
                rgb += line[4 * x:4 * x + 3]
        else:  # grey, grey + alpha
            step = channels
            for x in range(width):
                g = line[step * x]
                rgb += bytes((g, g, g))
    return width, height, bytes(rgb)


def compare_images(ours, theirs, tolerance=2):
    """Share of pixels whose R, G and B all differ by at most `tolerance` (of 255), and more."""
    w1, h1, a = read_png(ours)
    w2, h2, b = read_png(theirs)
    if (w1, h1) != (w2, h2):
        raise ValueError("sizes differ: %dx%d vs %dx%d" % (w1, h1, w2, h2))
    within = exact = 0
    worst = 0
    total_abs = 0
    for i in range(0, len(a), 3):
        d = max(abs(a[i] - b[i]), abs(a[i + 1] - b[i + 1]), abs(a[i + 2] - b[i + 2]))
        if d <= tolerance:
            within += 1
            if d == 0:
                exact += 1
        if d > worst:
            worst = d
        total_abs += d
    n = w1 * h1
    return {"pixels": n, "within": within / n, "exact": exact / n, "max_diff": worst,
            "mean_max_channel_diff": total_abs / n}


# ----------------------------------------------------------------------------------------------
# Summaries and tables


def median(values):
    values = [v for v in values if v is not None]
    return statistics.median(values) if values else None


def least(values):
    return min([v for v in values if v is not None], default=None)


def estimator(stat):
    """The function that summarises several runs' figures: median, or least for --stat min."""
    return median if stat != "min" else least


def summarise(runs, stat="median"):
    """Medians (or minima) over the successful runs; ray counts from the first (they do not vary)."""
    ok = [r for r in runs if r.get("figures")]
    if not ok:
        return None
    pick = estimator(stat)
    first = ok[0]["figures"]
    return {
        "runs": len(ok),
        "trace_s": pick([r["figures"]["trace_s"] for r in ok]),
        "setup_s": pick([r["figures"]["setup_s"] for r in ok]),
        "wall_s": pick([r["wall_s"] for r in ok]),
        "max_rss_mb": pick([r["max_rss_mb"] for r in ok]),
        "rays": first["rays"],
        "rays_vary": len({r["figures"]["rays"] for r in ok}) > 1,
        "by_kind": first["by_kind"],
        "accel": first.get("accel"),
    }


def f(value, digits=2):
    if value is None:
        return "—"
    return "%.*f" % (digits, value)


def pair(a, b, digits=2):
    return "%s / %s" % (f(a, digits), f(b, digits))


def ratio(num, den):
    return num / den if num is not None and den else None


def count(n):
    return "—" if n is None else "{:,}".format(n).replace(",", " ")


def mrays(s):
    return s["rays"] / s["trace_s"] / 1e6 if s and s["trace_s"] else None


def status_of(side):
    """What to show for a program with no usable run in a configuration."""
    if any(r.get("timeout") for r in side["runs"]):
        return "timeout"
    if side["runs"]:
        return "error"
    return "skipped" if side.get("skipped") else "—"


def paired_rounds(config):
    """(trace seconds, rays) of whitted and of POV-Ray in each round where both ran: run k of each
    (runs are kept in round order, and a program that fails is not run again)."""
    def figures(prog):
        return [r.get("figures") for r in config[prog]["runs"]]
    return [((w["trace_s"], w["rays"]), (p["trace_s"], p["rays"]))
            for w, p in zip(figures("whitted"), figures("povray")) if w and p and w["trace_s"] and p["trace_s"]]


def round_traces(config, prog):
    """The trace seconds of `prog`'s runs of a configuration, in round order (None for a failed run)."""
    return [(r.get("figures") or {}).get("trace_s") for r in config[prog]["runs"]]


def spread(values):
    """'median (least–most)' of a list of ratios, or '—'."""
    values = [v for v in values if v is not None]
    if not values:
        return "—"
    return "%s (%s–%s)" % (f(median(values)), f(min(values)), f(max(values)))


def tables(results):
    rows = results["configs"]
    by_key = {(c["scene"], c["mode"], c["threads"]): c for c in rows}
    out = []
    m = results["machine"]
    out.append("Measured %s on %s (%s cores), Linux %s, %s, whitted %s; %d run(s) a configuration, "
               "%s shown; %dx%d." % (m["date"], m["cpu"], m["cores"], m["kernel"], m["povray"] or "no POV-Ray",
                                      m["whitted"], results["runs"],
                                      "minima" if results.get("stat") == "min" else "medians", WIDTH, HEIGHT))
    out.append("")
    out.append("| scene | size | AA | threads | whitted trace (s) | POV-Ray trace (s) | time ratio POV/whitted "
               "| whitted Mrays/s | POV-Ray Mrays/s | throughput ratio whitted/POV | rays traced (M) whitted / POV "
               "| 2-thread speed-up whitted / POV | peak RSS (MB) whitted / POV |")
    out.append("|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for c in rows:
        w, p = c["whitted"]["summary"], c["povray"]["summary"]
        wt = w["trace_s"] if w else None
        pt = p["trace_s"] if p else None
        w_cell = f(wt, 3) if w else status_of(c["whitted"])
        p_cell = f(pt, 3) if p else status_of(c["povray"])
        speed = "—"
        if c["threads"] == 2:
            one = by_key.get((c["scene"], c["mode"], 1))
            if one:
                w1, p1 = one["whitted"]["summary"], one["povray"]["summary"]
                speed = pair(ratio(w1 and w1["trace_s"], wt), ratio(p1 and p1["trace_s"], pt))
        out.append("| %s | %dx%d | %s | %d | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            c["scene"], WIDTH, HEIGHT, c["mode"], c["threads"], w_cell, p_cell, f(ratio(pt, wt)),
            f(mrays(w)), f(mrays(p)), f(ratio(mrays(w), mrays(p))),
            pair(w and w["rays"] / 1e6, p and p["rays"] / 1e6, 3), speed,
            pair(w and w["max_rss_mb"], p and p["max_rss_mb"], 0)))
    out.append("")
    out.append("Trace = whitted's `seconds` (trace phase) and POV-Ray's `Trace Time`. Time ratio > 1 and "
               "throughput ratio > 1 both mean whitted is faster. Rays: whitted primary + reflected + "
               "transmitted + shadow; POV-Ray `Rays` + `Shadow Ray Tests`. Speed-up = trace time with 1 "
               "thread / with 2. Peak RSS of the whole process.")
    out.append("")

    other = "median" if results.get("stat") == "min" else "min"
    out.append("The same runs summarised by the other estimator (%s):" % ("medians" if other == "median" else "minima"))
    out.append("")
    out.append("| scene | AA | threads | whitted trace (s) | POV-Ray trace (s) | time ratio POV/whitted "
               "| throughput ratio whitted/POV | 2-thread speed-up whitted / POV |")
    out.append("|---|---|---:|---:|---:|---:|---:|---:|")
    alt = {key: {prog: summarise(c[prog]["runs"], other) for prog in ("whitted", "povray")}
           for key, c in by_key.items()}
    for c in rows:
        key = (c["scene"], c["mode"], c["threads"])
        w, p = alt[key]["whitted"], alt[key]["povray"]
        wt, pt = w and w["trace_s"], p and p["trace_s"]
        speed = "—"
        if c["threads"] == 2 and (c["scene"], c["mode"], 1) in alt:
            one = alt[(c["scene"], c["mode"], 1)]
            speed = pair(ratio(one["whitted"] and one["whitted"]["trace_s"], wt),
                         ratio(one["povray"] and one["povray"]["trace_s"], pt))
        out.append("| %s | %s | %d | %s | %s | %s | %s | %s |" % (
            c["scene"], c["mode"], c["threads"], f(wt, 3), f(pt, 3), f(ratio(pt, wt)),
            f(ratio(mrays(w), mrays(p))), speed))
    out.append("")

    out.append("The same runs paired by round: whitted's run k against POV-Ray's run k, which follows it "
               "within seconds, so that the machine's drift over the minutes of a table cancels in each "
               "ratio; the median over rounds of those ratios, and their range:")
    out.append("")
    out.append("| scene | AA | threads | rounds | time ratio POV/whitted (range) "
               "| throughput ratio whitted/POV (range) | 2-thread speed-up, run k of 1 thread / run k of 2: "
               "whitted (range) | POV-Ray (range) |")
    out.append("|---|---|---:|---:|---:|---:|---:|---:|")
    for c in rows:
        rounds = paired_rounds(c)
        times = [ratio(pt, wt) for (wt, _), (pt, _) in rounds]
        speeds = [ratio(wr / wt, pr / pt) for (wt, wr), (pt, pr) in rounds]
        one = by_key.get((c["scene"], c["mode"], 1))
        scaling = ["—", "—"]
        if c["threads"] == 2 and one:
            for n, prog in enumerate(("whitted", "povray")):
                pairs = zip(round_traces(one, prog), round_traces(c, prog))
                scaling[n] = spread([ratio(a, b) for a, b in pairs if a and b])
        out.append("| %s | %s | %d | %d | %s | %s | %s | %s |" % (
            c["scene"], c["mode"], c["threads"], len(rounds), spread(times), spread(speeds), *scaling))
    out.append("")

    ceilings = [c for c in results.get("ceilings", []) if any(t is not None for p in c["pairs"] for t in p)]
    if ceilings:
        pick = estimator(results.get("stat"))
        out.append("The machine's ceiling for two threads, measured in the same rounds: two `whitted --threads 1` "
                   "renders at once against one alone (%s; ceiling = 2 x alone / each at once, 2 where two busy "
                   "CPUs run as fast as one):" % ("minima" if results.get("stat") == "min" else "medians"))
        out.append("")
        out.append("| scene | AA | one alone: trace (s) | each of two at once: trace (s) | ceiling | 2-thread "
                   "speed-up whitted / POV | speed-up / ceiling whitted / POV |")
        out.append("|---|---|---:|---:|---:|---:|---:|")
        def trace_s(scene, mode, threads, prog):
            c = by_key.get((scene, mode, threads))
            return c and c[prog]["summary"] and c[prog]["summary"]["trace_s"]

        for c in ceilings:
            alone = trace_s(c["scene"], c["mode"], 1, "whitted")
            both = pick([t for p in c["pairs"] for t in p])
            top = ratio(2 * alone, both) if alone else None
            w, p = (ratio(trace_s(c["scene"], c["mode"], 1, prog), trace_s(c["scene"], c["mode"], 2, prog))
                    for prog in ("whitted", "povray"))
            out.append("| %s | %s | %s | %s | %s | %s | %s |" % (
                c["scene"], c["mode"], f(alone, 3), f(both, 3), f(top), pair(w, p),
                pair(ratio(w, top), ratio(p, top))))
        out.append("")

    out.append("Whole process (%s wall time) and the work before tracing:" % ("least" if results.get("stat") == "min" else "median"))
    out.append("")
    out.append("| scene | AA | threads | whitted wall (s) | whitted load + build (s) | whitted accel "
               "| POV-Ray wall (s) | POV-Ray parse + bounding (s) |")
    out.append("|---|---|---:|---:|---:|---|---:|---:|")
    for c in rows:
        w, p = c["whitted"]["summary"], c["povray"]["summary"]
        out.append("| %s | %s | %d | %s | %s | %s | %s | %s |" % (
            c["scene"], c["mode"], c["threads"], f(w and w["wall_s"]), f(w and w["setup_s"], 3),
            (w and w["accel"]) or "—", f(p and p["wall_s"]), f(p and p["setup_s"], 3)))
    out.append("")

    out.append("Rays by kind, one thread (whitted / POV-Ray; POV-Ray's primary = `Rays` − reflected − "
               "refracted, and it counts rays refused at the depth limit):")
    out.append("")
    out.append("| scene | AA | primary | reflected | transmitted (refracted) | shadow (Shadow Ray Tests) |")
    out.append("|---|---|---:|---:|---:|---:|")
    for c in rows:
        if c["threads"] != 1:
            continue
        w, p = c["whitted"]["summary"], c["povray"]["summary"]
        cells = []
        for kind in RAY_KINDS:
            cells.append("%s / %s" % (count(w and w["by_kind"][kind]), count(p and p["by_kind"][kind])))
        out.append("| %s | %s | %s |" % (c["scene"], c["mode"], " | ".join(cells)))
    out.append("")

    if results["images"]:
        out.append("Images, one thread, whitted against POV-Ray (share of pixels with every channel within "
                   "2/255; exactly equal; largest channel difference, of 255):")
        out.append("")
        out.append("| scene | AA | within 2/255 | equal | max diff |")
        out.append("|---|---|---:|---:|---:|")
        for img in results["images"]:
            if "error" in img:
                out.append("| %s | %s | %s | | |" % (img["scene"], img["mode"], img["error"]))
            else:
                out.append("| %s | %s | %.2f %% | %.2f %% | %d |" % (
                    img["scene"], img["mode"], 100 * img["within"], 100 * img["exact"], img["max_diff"]))
        out.append("")

    notes = []
    for c in rows:
        for prog in ("whitted", "povray"):
            for r in c[prog]["runs"]:
                if r.get("other_cpu_s", 0) > max(0.5, 0.1 * r.get("wall_s", 0)):
                    notes.append("%s %s %s %d thread(s): other processes used %.1f s of CPU during a run"
                                 % (prog, c["scene"], c["mode"], c["threads"], r["other_cpu_s"]))
            s = c[prog]["summary"]
            if s and s["rays_vary"]:
                notes.append("%s %s %s %d thread(s): ray counts differ between runs"
                             % (prog, c["scene"], c["mode"], c["threads"]))
        w = c["whitted"]["summary"]
        if c["whitted"]["runs"] and c["whitted"]["runs"][0].get("figures"):
            reported = c["whitted"]["runs"][0]["figures"].get("threads_reported")
            if reported is not None and reported != c["threads"]:
                notes.append("whitted %s %s: asked for %d thread(s), reports %s"
                             % (c["scene"], c["mode"], c["threads"], reported))
    notes += results.get("notes", [])
    if notes:
        out.append("Notes:")
        out.append("")
        out.extend("- " + n for n in notes)
    else:
        out.append("No run saw other processes use more than 0.5 s or 10 % of its wall time in CPU.")
    return "\n".join(out)


# ----------------------------------------------------------------------------------------------
# Main


def git(*args):
    """A git command's output in the repository, or None when it fails (no git, no repository)."""
    try:
        done = subprocess.run(["git", "-C", REPO, *args], capture_output=True, text=True)
    except OSError:
        return None
    return done.stdout.strip() if done.returncode == 0 else None


def machine_info(binary, povray, load_start):
    """Where and when the numbers were measured: the results file's header.

    `load_start` is the load average (1, 5, 15 minutes) read before the first run: on a shared
    machine it says how much other work the runs competed with."""
    cpu = "unknown CPU"
    with open("/proc/cpuinfo") as fh:
        for line in fh:
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    commit = git("rev-parse", "HEAD")
    dirty = bool(git("status", "--porcelain", "--untracked-files=no"))
    short = commit[:7] if commit else None
    rev = (short or "(no commit)") + (" + local changes" if dirty else "")
    now = time.gmtime()
    return {"date": time.strftime("%Y-%m-%d", now), "started": time.strftime("%Y-%m-%dT%H:%M:%SZ", now),
            "command": shlex.join(["python3", os.path.relpath(sys.argv[0], REPO)] + sys.argv[1:]),
            "commit": commit, "dirty": dirty, "cpu": cpu, "cores": os.cpu_count(),
            "kernel": platform.release(), "load_average_start": [round(x, 2) for x in load_start],
            "povray": povray, "whitted": rev, "binary": binary}


def shown(path):
    """A path as the reader of the log wants it: relative inside the repository, else absolute."""
    path = os.path.abspath(path)
    return os.path.relpath(path, REPO) if path.startswith(REPO + os.sep) else path


def results_path(folder, machine):
    """bench/results/DATE-COMMIT.json, numbered on when that name is taken (never overwritten)."""
    stem = "%s-%s%s" % (machine["date"], (machine["commit"] or "nocommit")[:7], "-dirty" if machine["dirty"] else "")
    path, n = os.path.join(folder, stem + ".json"), 1
    while os.path.exists(path):
        n += 1
        path = os.path.join(folder, "%s-%d.json" % (stem, n))
    return path


def find_povray_dir(explicit):
    candidates = [explicit] if explicit else [os.path.join(BENCH, "povray"), os.path.join(BENCH, "..", "..", "shared", "bench", "povray")]
    for d in candidates:
        if d and os.path.isfile(os.path.join(d, "whitted.pov")):
            return os.path.abspath(d)
    sys.exit("run.py: POV-Ray bench scenes (whitted.pov, ...) not found in %s; pass --povray-dir or --no-povray"
             % ", ".join(c for c in candidates if c))


def ensure_scene_files(selected, with_povray, pov_dir):
    """Run gen_scenes.py if a generated scene (or a mesh file) is missing."""
    missing = []
    for name, json_file, _ in selected:
        needed = [json_file]
        if name.startswith("mesh-"):
            needed.append(name + ".obj")
            if with_povray:
                needed.append(name + ".inc")
        missing += [n for n in needed if not os.path.exists(os.path.join(SCENE_DIR, n))]
    if not missing:
        return
    log("missing %s: running gen_scenes.py" % ", ".join(missing))
    cmd = [sys.executable, os.path.join(BENCH, "gen_scenes.py")]
    if not any(n.startswith("mesh-") for n, _, _ in selected):
        cmd.append("--no-mesh")
    if pov_dir:
        cmd += ["--povray-dir", pov_dir]
    subprocess.run(cmd, check=True)


def describe_failure(r):
    if r["timeout"]:
        return "timed out"
    lines = [l.strip() for l in r["stderr"].splitlines() if l.strip()]
    errors = [l for l in lines if l.lower().startswith("error")]
    shown = errors[:1] or lines[-3:] or ["(no output on stderr)"]
    return "exit %s: %s" % (r["exit"], " | ".join(shown))


def run_one(prog, cmd, cwd, timeout):
    """One measured run; 'figures' is set when it succeeded and its output parsed."""
    r = measure(cmd, cwd, timeout)
    if not r["timeout"] and r["exit"] == 0:
        try:
            if prog == "whitted":
                r["stats"] = parse_whitted(r["stdout"])
                r["figures"] = whitted_figures(r["stats"])
            else:
                r["stats"] = parse_povray(r["stderr"] + "\n" + r["stdout"])
                r["figures"] = povray_figures(r["stats"])
        except (ValueError, KeyError, TypeError) as e:
            r["parse_error"] = str(e)
    return r


def slim(r):
    """What the results file keeps of a run (POV-Ray's progress lines make its stderr long)."""
    keep = {k: v for k, v in r.items() if k not in ("stdout", "stderr")}
    if not r.get("figures"):
        keep["stderr_tail"] = r["stderr"][-2000:]
        keep["stdout_tail"] = r["stdout"][-2000:]
    return keep


def run_round(config, k, timeout, gave_up, notes):
    """Run k of one configuration: whitted, then POV-Ray; appends to config[prog]["runs"]."""
    failed = config.setdefault("failed", set())
    for prog, _, cwd in config["jobs"]:
        if gave_up[prog] or prog in failed:
            continue
        r = run_one(prog, config["commands"][prog], cwd, timeout)
        config[prog]["runs"].append(r)
        tag = config["tag"]
        if r.get("figures"):
            fig = r["figures"]
            log("%-28s %-7s run %d: trace %.3f s, wall %.2f s, %.2f Mrays/s, RSS %.0f MB" % (
                tag, prog, k + 1, fig["trace_s"], r["wall_s"],
                fig["rays"] / fig["trace_s"] / 1e6 if fig["trace_s"] else 0, r["max_rss_mb"]))
            continue
        why = r.get("parse_error") or describe_failure(r)
        log("%-28s %-7s run %d FAILED: %s\n    command: %s" % (
            tag, prog, k + 1, why, " ".join(config["commands"][prog])))
        failed.add(prog)
        if r["timeout"]:
            # too slow here: the scene's other modes trace at least as many rays
            gave_up[prog] = True
            why += "; the scene's remaining configurations were skipped"
        notes.append("%s on %s (%s, %d thread(s)), run %d: %s"
                     % (prog, config["scene"], config["mode"], config["threads"], k + 1, why))


def finish_config(config, gave_up, stat):
    """Summarises the runs of a configuration and drops what the results file does not keep."""
    for prog in ("whitted", "povray"):
        side = config[prog]
        side["skipped"] = gave_up[prog] and not side["runs"]
        side["summary"] = summarise(side["runs"], stat)
        side["runs"] = [slim(r) for r in side["runs"]]
    for key in ("jobs", "commands", "failed", "tag"):
        config.pop(key, None)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--only", action="append", default=[],
                    help="scene to run (exact name, else every scene whose name contains it); repeatable")
    ap.add_argument("--mode", action="append", default=[], choices=[m[0] for m in MODES],
                    help="sampling mode to run (default: all); repeatable")
    ap.add_argument("--quick", action="store_true", help="one run per configuration instead of three")
    ap.add_argument("--runs", type=int, help="runs per configuration (default 3, 1 with --quick)")
    ap.add_argument("--no-povray", action="store_true", help="run whitted only")
    ap.add_argument("--stat", choices=["median", "min"], default="median",
                    help="how the runs of a configuration are summarised (times and memory): the median "
                         "(default) or the minimum, the steadier estimator on a machine whose noise only "
                         "ever adds time")
    ap.add_argument("--accel", help="pass --accel NAME to whitted (default: whitted's own default)")
    ap.add_argument("--timeout", type=float, default=300, help="seconds before a run is killed (default 300)")
    ap.add_argument("--whitted", default=os.path.join(REPO, "target", "release", "whitted"),
                    help="the whitted binary (default: target/release/whitted)")
    ap.add_argument("--results", default=RESULTS,
                    help="folder of the results file DATE-COMMIT.json (default: bench/results, tracked)")
    ap.add_argument("--dry-run", action="store_true",
                    help="print the commands and the results file's name, run nothing, write nothing")
    ap.add_argument("--povray-dir", help="folder with the POV-Ray bench scenes "
                                         "(default: bench/povray if present, else ../shared/bench/povray beside the repository)")
    args = ap.parse_args()
    load_start = os.getloadavg()
    runs = args.runs or (1 if args.quick else 3)
    if runs < 1:
        sys.exit("run.py: --runs must be at least 1, got %d" % runs)

    binary = os.path.abspath(args.whitted)
    if not args.dry_run and not (os.path.isfile(binary) and os.access(binary, os.X_OK)):
        sys.exit("run.py: the whitted binary is missing: %s\n"
                 "Build it first, from %s:  cargo build --release" % (binary, REPO))
    with_povray = not args.no_povray
    povray = None
    pov_dir = None
    if with_povray:
        povray = povray_version()
        if povray is None:
            sys.exit("run.py: POV-Ray is not installed (`apt-get install -y povray`); or pass --no-povray")
        pov_dir = find_povray_dir(args.povray_dir)

    selected = SCENES
    if args.only:
        selected = []
        for want in args.only:
            exact = [s for s in SCENES if s[0] == want]
            matches = exact or [s for s in SCENES if want in s[0]]
            if not matches:
                sys.exit("run.py: no scene matches %r (scenes: %s)" % (want, ", ".join(s[0] for s in SCENES)))
            selected += [s for s in matches if s not in selected]

    image_dir = os.path.join(WORK, "images")
    if args.dry_run:
        pov_run_dir = os.path.join(WORK, "povray")
    else:
        ensure_scene_files(selected, with_povray, pov_dir)
        pov_run_dir = prepare_povray_dir(pov_dir, [s[0] for s in selected]) if with_povray else None
        os.makedirs(image_dir, exist_ok=True)

    results = {"machine": machine_info(binary, povray, load_start), "runs": runs, "stat": args.stat,
               "accel_option": args.accel,
               "povray_options": POV_COMMON, "configs": [], "ceilings": [], "images": [], "notes": []}
    for scene, json_file, pov_args in selected:
        gave_up = {"whitted": False, "povray": False}
        for mode, our_mode, pov_mode in MODES:
            if args.mode and mode not in args.mode:
                continue
            # The thread counts of a mode run in turns (run k of 1 thread, run k of 2 threads, …),
            # so that a slow spell of the machine lands on both and the speed-up holds.
            configs = []
            for threads in THREADS:
                tag = "%s-%s-t%d" % (scene, mode, threads)
                jobs = [("whitted", os.path.join(image_dir, tag + "-whitted.png"), REPO)]
                if with_povray:
                    jobs.append(("povray", os.path.join(image_dir, tag + "-povray.png"), pov_run_dir))
                commands = {
                    "whitted": whitted_command(binary, os.path.join(SCENE_DIR, json_file), our_mode, threads,
                                               jobs[0][1], args.accel),
                    "povray": with_povray and povray_command(pov_args, pov_mode, threads, jobs[-1][1]),
                }
                config = {"scene": scene, "mode": mode, "threads": threads, "images": {},
                          "jobs": jobs, "commands": commands, "tag": tag}
                for prog, image, _ in jobs:
                    config[prog] = {"cmd": " ".join(commands[prog]), "runs": []}
                    config["images"][prog] = image
                    if os.path.exists(image) and not args.dry_run:  # no stale image may stand in for a failed run
                        os.remove(image)
                config.setdefault("povray", {"runs": []})
                configs.append(config)
            # Two 1-thread renders at once, once a round: the machine's ceiling for 2 threads.
            ceiling = {"scene": scene, "mode": mode, "pairs": []}
            pair_cmds = [whitted_command(binary, os.path.join(SCENE_DIR, json_file), our_mode, 1,
                                         os.path.join(image_dir, "%s-%s-pair%d.png" % (scene, mode, n)),
                                         args.accel) for n in (0, 1)]
            if args.dry_run:
                for config in configs:
                    for prog, _, cwd in config["jobs"]:
                        print("%s, %d run(s), in %s:\n  %s" % (config["tag"], runs, cwd,
                                                               shlex.join(config["commands"][prog])))
                print("%s-%s, two at once, %d time(s):\n  %s" % (scene, mode, runs, shlex.join(pair_cmds[0])))
                continue
            for k in range(runs):
                for config in configs:
                    run_round(config, k, args.timeout, gave_up, results["notes"])
                if not gave_up["whitted"]:
                    ceiling["pairs"].append(measure_pair(pair_cmds, REPO, args.timeout))
                    log("%-28s whitted two 1-thread renders at once: trace %s s" % (
                        "%s-%s" % (scene, mode), " and ".join(f(t, 3) for t in ceiling["pairs"][-1])))
            results["ceilings"].append(ceiling)
            for config in configs:
                finish_config(config, gave_up, args.stat)
                results["configs"].append(config)

    for c in results["configs"]:
        if c["threads"] != 1 or not (c["whitted"]["summary"] and c["povray"]["summary"]):
            continue
        entry = {"scene": c["scene"], "mode": c["mode"]}
        try:
            entry.update(compare_images(c["images"]["whitted"], c["images"]["povray"]))
            log("image %-22s within 2/255: %.2f %%" % ("%s-%s" % (c["scene"], c["mode"]), 100 * entry["within"]))
        except (ValueError, OSError, zlib.error) as e:
            entry["error"] = str(e)
        results["images"].append(entry)

    if args.dry_run:
        print("results would go to %s" % shown(results_path(args.results, results["machine"])))
        return
    text = tables(results)
    results["machine"]["finished"] = time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())
    results["machine"]["load_average_end"] = [round(x, 2) for x in os.getloadavg()]
    results["tables"] = text
    os.makedirs(args.results, exist_ok=True)
    path = results_path(args.results, results["machine"])
    with open(path, "w") as fh:
        json.dump(results, fh, indent=1)
        fh.write("\n")
    os.makedirs(WORK, exist_ok=True)
    with open(os.path.join(WORK, "results.md"), "w") as fh:
        fh.write(text + "\n")
    print(text)
    log("\nresults: %s; tables: %s/results.md; images: %s" % (shown(path), WORK, image_dir))


if __name__ == "__main__":
    main()
