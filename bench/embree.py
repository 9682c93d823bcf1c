#!/usr/bin/env python3
"""whitted against Intel Embree 4 on the mesh scenes: ns per ray, build seconds, peak memory.

Embree is the practical limit for closest-hit queries on a CPU. This script loads the very scene
whitted renders (bench/scenes/mesh-*.json and its OBJ), builds Embree's default BVH over the same
triangles (the `embreex` package: Embree 4.4 behind a small Cython binding; Debian's libembree
with a C harness would do the same, but embreex needs no compiler and gives the same library
calls), and traces the same rays on one thread:

  primary  one ray per pixel centre, the camera of docs/algorithm.md §2 (lookAt frame, window at
           p, rows counted from the bottom), computed in f64 as whitted does, given to Embree in
           f32 (Embree's precision);
  shadow   from each primary hit whose facing normal N_f has N_f·L > 0 (whitted casts no shadow
           ray otherwise, §6), a segment to the light: `rtcOccluded1` with `tfar` = the distance,
           from the hit point moved off the surface along N_f by EMBREE_OFFSET (Embree's f32 hit
           points need a larger offset than whitted's exact one).

The mesh scenes have ks = 0 and no glass, so whitted traces exactly these rays: its `rays.primary`
and `rays.shadow` must equal Embree's pixel count and shadow-ray count. Per pixel, whitted's PNG
tells the class of the pixel (background colour, the ambient colour ka — no light, or shadowed —
or lit) and Embree's rays tell it too: the script counts the pixels whose class differs (f32 against
f64 arithmetic can flip a pixel on a silhouette or a grazing light; the counts say how many).

Each round runs whitted (`render --threads 1 --json`) and this script's Embree child, one after the
other in one command, each its own process (so its peak RSS is its own, from os.wait4), pinned to
the same single CPU (Embree's build would otherwise use every core through TBB; whitted's build
runs in its one-thread pool). The tables show the medians of the rounds, the ratios of each round
(whitted / Embree) as median [min–max], and the load average of the machine.

    ns/ray    whitted: trace seconds / (primary + shadow rays), its whole render (sampling,
              shading, the image); Embree: (primary + shadow query seconds) / the same rays,
              the queries alone — so the ratio is an upper bound on the traversal's gap
    build s   whitted: `build_seconds` (the BVH over the loaded mesh); Embree: `rtcCommitScene`
              (its default BVH build), timed around the first query, of one ray (the binding's
              copy of the arrays into Embree's buffers, `upload_s`, is kept apart)
    peak MB   the process's peak resident memory (ru_maxrss); Embree's includes Python, NumPy and
              the mesh's arrays; in brackets what Embree itself added to the peak (its buffers
              and its BVH: the growth of the resident memory across the upload and the build)

Usage (from the repository root; `cargo build --release` first; `pip install embreex`):
    python3 bench/embree.py                          # both meshes, 5 rounds
    python3 bench/embree.py --only mesh-100k --runs 3
Results: bench/results/DATE-COMMIT-embree.json (the raw rounds and the table), like run.py's.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import time

BENCH = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(BENCH)
sys.path.insert(0, BENCH)
import run as runpy  # noqa: E402  (the POV-Ray bench: its PNG reader, process measure, git helpers)

SCENES = ["mesh-100k", "mesh-1000k"]
WORK = "/tmp/whitted-bench/embree"
# How far a shadow ray's origin leaves the surface in Embree's run, relative to the hit point's
# largest coordinate (at least 1): f32 hit points are off by about 1e-7 of that.
EMBREE_OFFSET = 1e-4


# ----------------------------------------------------------------------------------------------
# The child: Embree alone in its own process


def load_obj(path):
    """Vertices (f64, n×3) and triangles (i64, m×3, 0-based) of an OBJ of `v x y z` and
    `f a b c` lines (what gen_mesh.py writes), read in chunks of lines so that the text never
    lives in memory whole (the process's peak is Embree's, not the parser's)."""
    import numpy as np

    chunk = 1 << 16
    parts = {"v": [], "f": []}
    pending = {"v": [], "f": []}

    def flush(kind):
        if pending[kind]:
            dtype = np.float64 if kind == "v" else np.int64
            parts[kind].append(np.array(" ".join(pending[kind]).split(), dtype=dtype))
            pending[kind].clear()

    with open(path) as fh:
        for line in fh:
            kind = line[:2]
            if kind in ("v ", "f "):
                pending[kind[0]].append(line[2:])
                if len(pending[kind[0]]) >= chunk:
                    flush(kind[0])
    flush("v")
    flush("f")
    v = np.concatenate(parts["v"]).reshape(-1, 3)
    f = np.concatenate(parts["f"]).reshape(-1, 3) - 1
    return v, f


def camera_rays(cam):
    """Origins and unit directions (f64) of the primary rays, pixel (i, j) at row-major index
    (ny − 1 − j)·nx + i of the image (rows from the top), as whitted's camera makes them."""
    import numpy as np

    eye, center = np.array(cam["eye"], float), np.array(cam["center"], float)
    up = np.array(cam.get("up", [0, 1, 0]), float)
    w = (eye - center) / np.linalg.norm(eye - center)
    up = up / np.linalg.norm(up)
    u = np.cross(up, w)
    u /= np.linalg.norm(u)
    v = np.cross(w, u)
    nx, ny = cam["resolution"]
    win, p = cam["window"], cam.get("p", 1.0)
    i = np.arange(nx, dtype=float)
    j = np.arange(ny, dtype=float)
    uu = win["l"] + (win["r"] - win["l"]) * (i + 0.5) / nx
    vv = win["b"] + (win["t"] - win["b"]) * (j + 0.5) / ny
    vv = vv[::-1]  # image rows from the top
    s = eye + uu[None, :, None] * u + vv[:, None, None] * v - w * p
    d = (s - eye).reshape(-1, 3)
    d /= np.linalg.norm(d, axis=1)[:, None]
    return np.broadcast_to(eye, d.shape).copy(), d


def resident_mb():
    """This process's resident memory now (VmRSS), in MB."""
    with open("/proc/self/status") as fh:
        for line in fh:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024.0
    return float("nan")


def child(scene_path, classes_out):
    """Builds Embree's scene, traces the rays, prints the figures as JSON on stdout."""
    import numpy as np
    from embreex import rtcore_scene
    from embreex.mesh_construction import TriangleMesh

    with open(scene_path) as fh:
        scene = json.load(fh)
    (obj,) = [o for o in scene["objects"] if o["type"] == "mesh"]
    t0 = time.perf_counter()
    verts, faces = load_obj(os.path.join(os.path.dirname(scene_path), obj["obj"]))
    load_s = time.perf_counter() - t0
    origins, dirs = camera_rays(scene["camera"])
    (light,) = scene["lights"]
    light = np.array(light["position"], float)

    es = rtcore_scene.EmbreeScene()
    rss_before = resident_mb()
    t0 = time.perf_counter()
    # The binding copies the arrays into Embree's buffers one element at a time (Cython): timed
    # apart, it is not Embree's build.
    TriangleMesh(es, verts.astype(np.float32), faces.astype(np.int32))
    upload_s = time.perf_counter() - t0
    # The first query commits the scene (rtcCommitScene: the BVH build); one ray costs nothing.
    t0 = time.perf_counter()
    es.run(origins[:1].astype(np.float32), dirs[:1].astype(np.float32))
    build_s = time.perf_counter() - t0
    # What Embree itself holds: the growth of the resident memory across the upload and the build.
    embree_mb = resident_mb() - rss_before

    o32, d32 = origins.astype(np.float32), dirs.astype(np.float32)
    t0 = time.perf_counter()
    hit = es.run(o32, d32, output=1)
    primary_s = time.perf_counter() - t0
    prim = hit["primID"]
    is_hit = prim >= 0
    t = hit["tfar"].astype(float)
    n = hit["Ng"].astype(float)
    n /= np.linalg.norm(n, axis=1)[:, None] + (~is_hit)[:, None]
    # The facing normal: N when the ray enters (N·D < 0), else −N.
    facing = np.where((np.einsum("ij,ij->i", n, dirs) < 0)[:, None], n, -n)
    point = origins + dirs * t[:, None]
    to_light = light - point
    dist = np.linalg.norm(to_light, axis=1)
    ldir = to_light / np.where(dist > 0, dist, 1)[:, None]
    cast = is_hit & (np.einsum("ij,ij->i", facing, ldir) > 0)
    scale = np.maximum(np.abs(point).max(axis=1), 1.0)
    so = point + facing * (EMBREE_OFFSET * scale)[:, None]
    sd = light - so
    sdist = np.linalg.norm(sd, axis=1)
    sd /= np.where(sdist > 0, sdist, 1)[:, None]
    idx = np.nonzero(cast)[0]
    s_o, s_d = so[idx].astype(np.float32), sd[idx].astype(np.float32)
    s_t = sdist[idx].astype(np.float32)
    t0 = time.perf_counter()
    occ = es.run(s_o, s_d, dists=s_t, query="OCCLUDED")
    shadow_s = time.perf_counter() - t0
    occluded = np.zeros(len(prim), bool)
    occluded[idx] = np.asarray(occ) >= 0 if np.asarray(occ).dtype != bool else np.asarray(occ)
    # 0 background, 1 ambient only (no light or shadowed), 2 lit
    classes = np.where(~is_hit, 0, np.where(cast & ~occluded, 2, 1)).astype(np.uint8)
    classes.tofile(classes_out)
    print(json.dumps({"load_s": load_s, "upload_s": upload_s, "build_s": build_s, "embree_mb": embree_mb, "primary_s": primary_s, "shadow_s": shadow_s,
                      "primary": int(len(prim)), "hits": int(is_hit.sum()), "shadow": int(cast.sum()),
                      "occluded": int(occluded.sum()), "triangles": int(len(faces))}))


# ----------------------------------------------------------------------------------------------
# The parent: rounds of whitted and Embree


def measured(cmd, cpu, timeout):
    """Runs `cmd` on CPU `cpu`; (stdout, wall seconds, peak RSS MB) from os.wait4."""
    r, w = os.pipe()
    start = time.perf_counter()
    pid = os.fork()
    if pid == 0:
        try:
            os.sched_setaffinity(0, {cpu})
            os.dup2(w, 1)
            devnull = os.open(os.devnull, os.O_WRONLY)
            os.dup2(devnull, 2)
            os.close(r)
            os.chdir(REPO)
            os.execvp(cmd[0], cmd)
        finally:
            os._exit(127)
    os.close(w)
    chunks = []
    while True:
        b = os.read(r, 1 << 16)
        if not b:
            break
        chunks.append(b)
    os.close(r)
    _, status, usage = os.wait4(pid, 0)
    wall = time.perf_counter() - start
    if os.waitstatus_to_exitcode(status) != 0:
        raise SystemExit("embree.py: %s failed (exit %d)" % (" ".join(cmd), os.waitstatus_to_exitcode(status)))
    return b"".join(chunks).decode(), wall, usage.ru_maxrss / 1024.0


def png_classes(path, scene):
    """Each pixel of whitted's PNG as 0 background, 1 ambient only, 2 lit (row-major from the top)."""
    width, height, pixels = runpy.read_png(path)
    bg = tuple(round(255 * min(max(c, 0.0), 1.0)) for c in scene["background"])
    (obj,) = [o for o in scene["objects"] if o["type"] == "mesh"]
    amb = scene.get("ambient", [1, 1, 1])
    ka = tuple(round(255 * min(max(a * k, 0.0), 1.0)) for a, k in zip(amb, obj["material"]["ka"]))
    out = bytearray(width * height)
    for k in range(width * height):
        px = tuple(pixels[3 * k:3 * k + 3])
        out[k] = 0 if px == bg else 1 if px == ka else 2
    return bytes(out)


def spread(xs):
    return "%.3g [%.3g–%.3g]" % (statistics.median(xs), min(xs), max(xs))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--only", action="append", default=[], choices=SCENES, help="scene (repeatable)")
    ap.add_argument("--runs", type=int, default=5, help="rounds per scene (default 5)")
    ap.add_argument("--cpu", type=int, default=None, help="the CPU both run on (default: the last)")
    ap.add_argument("--whitted", action="append", default=[],
                    help="a whitted binary (default: target/release/whitted); repeatable: several binaries "
                         "run in the same rounds (before and after a change), their PNGs compared byte for byte")
    ap.add_argument("--results", default=runpy.RESULTS, help="folder of the results file")
    ap.add_argument("--timeout", type=float, default=600)
    ap.add_argument("--povray-dir", help="folder of gen_mesh.py, when the meshes must be generated (see run.py)")
    ap.add_argument("--child", nargs=2, metavar=("SCENE", "CLASSES"), help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child:
        child(*args.child)
        return
    try:
        import embreex  # noqa: F401
    except ImportError:
        sys.exit("embree.py: the embreex package is missing: pip install embreex")
    binaries = [os.path.abspath(w) for w in args.whitted] or [os.path.join(REPO, "target", "release", "whitted")]
    for w in binaries:
        if not os.access(w, os.X_OK):
            sys.exit("embree.py: the whitted binary is missing: %s (cargo build --release)" % w)
    cpu = args.cpu if args.cpu is not None else max(os.sched_getaffinity(0))
    scenes = args.only or SCENES
    runpy.ensure_scene_files([(s, s + ".json", []) for s in scenes], False, args.povray_dir)
    os.makedirs(WORK, exist_ok=True)
    load_start = os.getloadavg()
    results = {"machine": runpy.machine_info(binaries[0], None, load_start), "cpu": cpu, "binaries": binaries,
               "runs": args.runs, "embree_offset": EMBREE_OFFSET, "scenes": []}
    for name in scenes:
        scene_path = os.path.join(runpy.SCENE_DIR, name + ".json")
        with open(scene_path) as fh:
            scene = json.load(fh)
        pngs = [os.path.join(WORK, "%s-whitted%d.png" % (name, i)) for i in range(len(binaries))]
        classes = os.path.join(WORK, name + "-embree.classes")
        e_cmd = [sys.executable, os.path.abspath(__file__), "--child", scene_path, classes]
        rounds = []
        for k in range(args.runs):
            sides = []
            for binary, png in zip(binaries, pngs):
                cmd = [binary, "render", scene_path, "--threads", "1", "--json", "--output", png]
                out, wall, rss = measured(cmd, cpu, args.timeout)
                w = json.loads(out)
                rays = w["rays"]
                n = rays["primary"] + rays["reflected"] + rays["transmitted"] + rays["shadow"]
                sides.append({"trace_s": w["seconds"], "build_s": w["build_seconds"], "load_s": w["load_seconds"],
                              "rays": rays, "tests": w.get("tests"), "peak_mb": rss, "wall_s": wall,
                              "ns_per_ray": 1e9 * w["seconds"] / n})
            out, wall, rss = measured(e_cmd, cpu, args.timeout)
            e = json.loads(out)
            e_rays = e["primary"] + e["shadow"]
            er = dict(e, peak_mb=rss, wall_s=wall, ns_per_ray=1e9 * (e["primary_s"] + e["shadow_s"]) / e_rays)
            rounds.append({"whitted": sides, "embree": er})
            runpy.log("%-11s round %d: %s | Embree %.0f ns/ray, build %.3f s, %.0f MB" % (
                name, k + 1, " | ".join("whitted%d %.0f ns/ray, build %.3f s, %.0f MB"
                                        % (i, w["ns_per_ray"], w["build_s"], w["peak_mb"]) for i, w in enumerate(sides)),
                er["ns_per_ray"], er["build_s"], er["peak_mb"]))
        # Same rays? Counts from the last round (every round traces the same rays).
        w, e = rounds[-1]["whitted"][0], rounds[-1]["embree"]
        mine = png_classes(pngs[0], scene)
        with open(classes, "rb") as fh:
            theirs = fh.read()
        images = []
        for png in pngs:
            with open(png, "rb") as fh:
                images.append(fh.read())
        check = {
            "primary": [w["rays"]["primary"], e["primary"]],
            "shadow": [w["rays"]["shadow"], e["shadow"]],
            "secondary": w["rays"]["reflected"] + w["rays"]["transmitted"],
            "hits": [sum(1 for c in mine if c != 0), e["hits"]],
            "lit": [sum(1 for c in mine if c == 2), sum(1 for c in theirs if c == 2)],
            "pixels_whose_class_differs": sum(1 for a, b in zip(mine, theirs) if a != b),
            "same_png_bytes": all(img == images[0] for img in images),
            "same_rays": all(x["rays"] == w["rays"] for x in rounds[-1]["whitted"]),
            # Node and object tests per ray of each binary: a render's wide BVH tests other nodes
            # (and may test other triangles first) than the binary tree, for the same answers.
            "tests_per_ray": [{k: round(v / max(1, sum(x["rays"].values())), 2) for k, v in x["tests"].items()}
                              for x in rounds[-1]["whitted"]],
        }
        results["scenes"].append({"scene": name, "triangles": e["triangles"], "rounds": rounds, "check": check})
    results["machine"]["load_average_end"] = [round(x, 2) for x in os.getloadavg()]
    text = table(results)
    results["table"] = text
    os.makedirs(args.results, exist_ok=True)
    path = runpy.results_path(args.results, results["machine"]).replace(".json", "-embree.json")
    with open(path, "w") as fh:
        json.dump(results, fh, indent=1)
        fh.write("\n")
    print(text)
    runpy.log("\nresults: %s" % runpy.shown(path))
    bad = [s["scene"] for s in results["scenes"] if s["check"]["primary"][0] != s["check"]["primary"][1]
           or s["check"]["secondary"] or not s["check"]["same_png_bytes"] or not s["check"]["same_rays"]]
    if bad:
        sys.exit("embree.py: other rays than Embree's, or binaries whose images differ, on %s" % ", ".join(bad))


def table(results):
    m = results["machine"]
    names = ["whitted"] if len(results["binaries"]) == 1 else [
        "whitted%d (%s)" % (i, runpy.shown(b)) for i, b in enumerate(results["binaries"])]
    lines = ["Embree 4.4 (embreex) against whitted (%s), one thread each (CPU %d), %d rounds; load average %s → %s."
             % (", ".join(names), results["cpu"], results["runs"], m["load_average_start"], m["load_average_end"]),
             "Medians; ratios = whitted / Embree per round, median [min–max].", "",
             "| scene | binary | whitted ns/ray | Embree ns/ray | ratio | whitted build s | Embree build s | ratio "
             "| whitted peak MB | Embree peak MB (Embree's own) | ratio |",
             "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for s in results["scenes"]:
        r = s["rounds"]
        e = lambda key: statistics.median(x["embree"][key] for x in r)
        for i, name in enumerate(names):
            w = lambda key: statistics.median(x["whitted"][i][key] for x in r)
            ratio = lambda key: spread([x["whitted"][i][key] / x["embree"][key] for x in r])
            lines.append("| %s | %s | %.0f | %.0f | %s | %.3f | %.3f | %s | %.0f | %.0f (%.0f) | %s |" % (
                s["scene"], name.split(" ")[0], w("ns_per_ray"), e("ns_per_ray"), ratio("ns_per_ray"),
                w("build_s"), e("build_s"), ratio("build_s"),
                w("peak_mb"), e("peak_mb"), e("embree_mb"), ratio("peak_mb")))
    if len(names) > 1:
        lines += ["", "Each binary against the first, per round (time ratio = first / this, > 1 faster), median [min–max]:", ""]
        for s in results["scenes"]:
            r = s["rounds"]
            for i in range(1, len(names)):
                lines.append("- %s, whitted%d: trace %s, build %s, peak memory %s" % (
                    s["scene"], i,
                    spread([x["whitted"][0]["trace_s"] / x["whitted"][i]["trace_s"] for x in r]),
                    spread([x["whitted"][0]["build_s"] / x["whitted"][i]["build_s"] for x in r]),
                    spread([x["whitted"][i]["peak_mb"] / x["whitted"][0]["peak_mb"] for x in r])))
    lines += ["", "Same rays (whitted / Embree):"]
    for s in results["scenes"]:
        c = s["check"]
        lines.append("- %s (%d triangles): primary %d / %d, shadow %d / %d, hits %d / %d, lit pixels %d / %d; "
                     "pixels whose class (background, unlit or shadowed, lit) differs: %d; the binaries' PNGs %s, "
                     "their ray counts %s; node / object tests per ray %s"
                     % (s["scene"], s["triangles"], *c["primary"], *c["shadow"], *c["hits"], *c["lit"],
                        c["pixels_whose_class_differs"], "byte for byte the same" if c["same_png_bytes"] else "DIFFER",
                        "the same" if c["same_rays"] else "DIFFER",
                        ", ".join("whitted%d %.2f / %.2f" % (i, t.get("node", 0), t.get("object", 0))
                                  for i, t in enumerate(c["tests_per_ray"]))))
    return "\n".join(lines)


if __name__ == "__main__":
    main()
