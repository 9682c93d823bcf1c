#!/usr/bin/env python3
"""Random scenes rendered by whitted and by reference.py, compared byte for byte.

compare.py holds whitted to the independent reference on scenes written by hand; this script does
the same on scenes nobody chose: each is drawn from a seeded random generator (3D and 2D; spheres,
boxes, triangles, planes, segments and polygons, convex or not; mirrors, glass with any ior,
checkers, attenuated coloured lights, both projections, tilted cameras), rendered at a small size
with `--aa center`, `corners` and `adaptive` (and at centre with one of whitted's other structures),
and compared: the 8-bit pixels and the number of primary rays, which §8 makes exact.

A scene that disagrees is written to the output folder (default /tmp/whitted-fuzz) to be traced.

Usage (from the repository root, after `cargo build --release`):
    python3 bench/reference/fuzz.py                   # 40 scenes, seed 1
    python3 bench/reference/fuzz.py --scenes 200 --seed 7
"""
import argparse
import json
import math
import os
import random
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import compare  # noqa: E402  (the two renderers' command lines and the pixel comparison)

SIZE = "24x18"
MODES = [
    ("center", ["--aa", "center"]),
    ("corners", ["--aa", "corners"]),
    ("adaptive 0.1, K = 2", ["--aa", "adaptive", "--threshold", "0.1", "--max-level", "2"]),
]


def num(rng, lo, hi):
    """A number in [lo, hi) with 4 decimals, so that the scene file holds exactly what was drawn."""
    return round(rng.uniform(lo, hi), 4)


def vec(rng, lo, hi, n):
    return [num(rng, lo, hi) for _ in range(n)]


# --snap: the objects' coordinates and sizes on a grid of 1/4, so that boxes stand on planes, faces
# meet, and objects touch: the ties of §6 and the coincident surfaces, where a random scene never is.
SNAP = False


def coord(rng, lo, hi):
    return round(rng.uniform(lo, hi) * 4) / 4 if SNAP else num(rng, lo, hi)


def point(rng, lo, hi, n):
    return [coord(rng, lo, hi) for _ in range(n)]


def size(rng, lo, hi):
    return max(0.25, coord(rng, lo, hi)) if SNAP else num(rng, lo, hi)


def color(rng, lo=0.0, hi=1.0):
    """A material colour: a grey (one number, as product.md allows for ka, kd, kd2, ka2) or RGB."""
    return num(rng, lo, hi) if rng.random() < 0.3 else vec(rng, lo, hi, 3)


def material(rng, plane=False):
    m = {"ka": color(rng, 0, 0.2), "kd": color(rng, 0, 0.9)}
    kind = rng.random()
    if kind < 0.3:  # a mirror
        m.update(ks=num(rng, 0.3, 0.9), n=rng.choice([8, 32, 64, 100, num(rng, 2, 200)]))
    elif kind < 0.55 and not plane:  # glass, some of it dense enough for total internal reflection
        m.update(ks=num(rng, 0.05, 0.3), n=rng.choice([50, 128, num(rng, 5, 150)]),
                 kt=num(rng, 0.5, 0.95), ior=rng.choice([1.33, 1.5, num(rng, 1.05, 2.6)]))
    elif kind < 0.7:  # a faint mirror with a broad highlight (any ks > 0 spawns R)
        m.update(ks=num(rng, 0.02, 0.2), n=num(rng, 1, 64))
    if plane and rng.random() < 0.6:
        m["checker"] = {"size": num(rng, 0.2, 1.2), "kd2": color(rng, 0, 0.9)}
        if rng.random() < 0.5:
            m["checker"]["ka2"] = color(rng, 0, 0.2)
    return m


def light(rng, dims):
    position = [num(rng, -6, 6), num(rng, 2, 8)] + ([num(rng, -6, 6)] if dims == 3 else [])
    out = {"position": position, "intensity": vec(rng, 0.3, 1.0, 3)}
    if rng.random() < 0.3:
        out["attenuation"] = [num(rng, 0.3, 1), num(rng, 0, 0.2), num(rng, 0, 0.05)]
    return out


def polygon(rng):
    """A simple polygon (convex or not): vertices by angle around a centre, radii at random, in
    either winding."""
    c = point(rng, -1.2, 1.2, 2)
    k = rng.randint(3, 6)
    # k angles at least 2π/(5k) apart (a sliver of a wedge could round into a crossing).
    angles = [2 * math.pi * (i + rng.uniform(0.1, 0.9)) / k for i in range(k)]
    pts = [[round(c[0] + r * math.cos(a), 4), round(c[1] + r * math.sin(a), 4)]
           for a, r in ((a, rng.uniform(0.3, 0.9)) for a in angles)]
    return pts if rng.random() < 0.5 else pts[::-1]


def object_3d(rng):
    kind = rng.choice(["sphere", "sphere", "box", "triangle"])
    if kind == "sphere":
        return {"type": "sphere", "center": point(rng, -1.5, 1.5, 3), "radius": size(rng, 0.25, 1.0)}
    if kind == "box":
        lo = point(rng, -1.6, 1.0, 3)
        return {"type": "box", "min": lo, "max": [x + size(rng, 0.3, 1.2) for x in lo]}
    c = point(rng, -1.2, 1.2, 3)
    return {"type": "triangle", "vertices": [[x + coord(rng, -1, 1) for x in c] for _ in range(3)]}


def object_2d(rng):
    kind = rng.choice(["sphere", "box", "triangle", "segment", "polygon"])
    if kind == "sphere":
        return {"type": "sphere", "center": point(rng, -1.5, 1.5, 2), "radius": size(rng, 0.25, 0.9)}
    if kind == "box":
        lo = point(rng, -1.6, 1.0, 2)
        return {"type": "box", "min": lo, "max": [x + size(rng, 0.3, 1.2) for x in lo]}
    if kind == "segment":
        return {"type": "segment", "a": point(rng, -1.5, 1.5, 2), "b": point(rng, -1.5, 1.5, 2)}
    if kind == "triangle":
        c = point(rng, -1.2, 1.2, 2)
        return {"type": "triangle", "vertices": [[x + coord(rng, -0.9, 0.9) for x in c] for _ in range(3)]}
    return {"type": "polygon", "vertices": polygon(rng)}


def camera(rng, dims):
    distance = rng.uniform(4, 7)
    if dims == 3:
        a, e = rng.uniform(0, 2 * math.pi), rng.uniform(0.15, 0.9)
        eye = [distance * math.cos(e) * math.sin(a), distance * math.sin(e), distance * math.cos(e) * math.cos(a)]
    else:
        a = rng.uniform(0.2, math.pi - 0.2)
        eye = [distance * math.cos(a), distance * math.sin(a)]
    cam = {"eye": [round(x, 4) for x in eye], "center": vec(rng, -0.3, 0.3, dims)}
    ortho = rng.random() < 0.3
    if ortho:
        cam["projection"] = "orthographic"
    cam["p"] = num(rng, 0.8, 2.0)
    half = num(rng, 2.0, 3.0) if ortho else cam["p"] * num(rng, 0.35, 0.7)
    cam["window"] = {"l": -half, "r": half}
    if dims == 3:
        cam["window"].update(b=round(-half * 0.75, 4), t=round(half * 0.75, 4))
        if rng.random() < 0.3:
            cam["up"] = [num(rng, -0.4, 0.4), 1, num(rng, -0.4, 0.4)]
        cam["resolution"] = [24, 18]
    else:
        cam["resolution"] = [24]
    return cam


def mesh_obj(rng):
    """A small mesh as OBJ text: a bumpy grid patch (shared edges and vertices between its
    triangles) or a jittered octahedron (a closed surface, for glass)."""
    if rng.random() < 0.5:
        n, c, half = rng.randint(2, 5), vec(rng, -1, 1, 3), num(rng, 0.5, 1.5)
        lines = [f"v {c[0] - half + 2 * half * i / n:.4f} {c[1] + rng.uniform(-0.4, 0.4):.4f} "
                 f"{c[2] - half + 2 * half * j / n:.4f}" for j in range(n + 1) for i in range(n + 1)]
        for j in range(n):
            for i in range(n):
                a = j * (n + 1) + i + 1
                lines += [f"f {a} {a + n + 1} {a + n + 2}", f"f {a} {a + n + 2} {a + 1}"]
        return "\n".join(lines) + "\n"
    c, r = vec(rng, -1, 1, 3), num(rng, 0.4, 1.0)
    axes = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
    lines = [f"v {c[0] + r * x + rng.uniform(-0.1, 0.1):.4f} {c[1] + r * y + rng.uniform(-0.1, 0.1):.4f} "
             f"{c[2] + r * z + rng.uniform(-0.1, 0.1):.4f}" for x, y, z in axes]
    # Counter-clockwise seen from outside: the outward normals of algorithm.md §3.
    for a, b, d in [(1, 3, 5), (3, 2, 5), (2, 4, 5), (4, 1, 5), (3, 1, 6), (2, 3, 6), (4, 2, 6), (1, 4, 6)]:
        lines.append(f"f {a} {b} {d}")
    return "\n".join(lines) + "\n"


def scene(rng, hard=False):
    """A random scene, and for --hard its mesh's OBJ text (or None)."""
    dims = 3 if rng.random() < 0.7 else 2
    make = object_3d if dims == 3 else object_2d
    objects = [make(rng) for _ in range(rng.randint(2, 6))]
    if rng.random() < 0.7:
        tilt = (lambda: 0) if SNAP else (lambda: num(rng, -0.2, 0.2))
        normal = [tilt(), 1] + ([tilt()] if dims == 3 else [])
        objects.append({"type": "plane", "point": [0, coord(rng, -2, -1.2)] + ([0] if dims == 3 else []),
                        "normal": normal})
    obj = None
    if hard and dims == 3 and rng.random() < 0.6:
        obj = mesh_obj(rng)
        objects.append({"type": "mesh", "obj": "mesh.obj"})
    for o in objects:
        o["material"] = material(rng, plane=o["type"] == "plane")
    out = {
        "camera": camera(rng, dims),
        "background": vec(rng, 0, 0.6, 3),
        "ambient": vec(rng, 0.2, 1.0, 3),
        "max_depth": rng.randint(1, 5),
        "lights": [light(rng, dims) for _ in range(rng.randint(1, 2))],
        "objects": objects,
    }
    if hard and rng.random() < 0.3:
        # The eye inside a glass sphere: every primary ray starts inside an object.
        out["objects"].append({"type": "sphere", "center": out["camera"]["eye"], "radius": num(rng, 0.3, 0.8),
                               "material": {"ka": 0, "kd": 0.05, "ks": 0.1, "kt": 0.9,
                                            "ior": num(rng, 1.1, 1.8)}})
    if hard and rng.random() < 0.3:
        # A light inside a sphere (glass or not): its shadow rays all start or end inside.
        spheres = [o for o in objects if o["type"] == "sphere"]
        if spheres:
            out["lights"][0]["position"] = list(rng.choice(spheres)["center"])
    return out, obj


def accepts(cmd):
    """Whether a program takes the scene: exit 0, or 2 for a refused scene (anything else fails)."""
    code = subprocess.run(cmd, capture_output=True).returncode
    if code not in (0, 2):
        raise RuntimeError(f"{' '.join(cmd)}: exit {code}")
    return code == 0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--binary", default=os.path.join(compare.REPO, "target", "release", "whitted"))
    ap.add_argument("--scenes", type=int, default=40)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--out", default="/tmp/whitted-fuzz", help="where disagreeing scenes are written")
    ap.add_argument("--snap", action="store_true",
                    help="objects on a grid of 1/4 (level planes), so that they touch and tie")
    ap.add_argument("--hard", action="store_true",
                    help="also meshes (grid patches, octahedra), the eye inside glass, lights inside spheres")
    args = ap.parse_args()
    global SNAP
    SNAP = args.snap
    read_png = compare.load_png_reader()
    rng = random.Random(args.seed)
    started, renders, refused, bad = time.time(), 0, 0, []
    with tempfile.TemporaryDirectory() as work:
        for n in range(args.scenes):
            text, obj = scene(rng, args.hard)
            path = os.path.join(work, f"scene-{n}.json")
            with open(path, "w") as fh:
                json.dump(text, fh)
            if obj is not None:
                with open(os.path.join(work, "mesh.obj"), "w") as fh:
                    fh.write(obj)
            structure = rng.choice(["none", "bounds", "grid", "octree"])
            runs = [(label, m, m) for label, m in MODES]
            runs.append((f"center, --accel {structure}", ["--aa", "center", "--accel", structure], ["--aa", "center"]))
            # Both programs must refuse the same scenes (a polygon whose rounded vertices cross,
            # say), and render the others alike.
            ours_ok, ref_ok = accepts([args.binary, "check", path]), accepts(
                [sys.executable, os.path.join(compare.HERE, "reference.py"), path, "-o",
                 os.path.join(work, "check.json"), "--size", "1x1"])
            if not (ours_ok or ref_ok):
                refused += 1
                continue
            refs = {}
            for label, ours_args, ref_args in runs:
                if ours_ok != ref_ok:
                    worst, off, primary = "—", "—", ("refused" if not ours_ok else "—",
                                                     "refused" if not ref_ok else "—")
                else:
                    png = os.path.join(work, "w.png")
                    ours = compare.whitted(args.binary, path, ours_args, png, SIZE)
                    key = tuple(ref_args)
                    if key not in refs:
                        refs[key] = compare.reference(path, ref_args, os.path.join(work, f"r{len(refs)}.json"), SIZE)
                    worst, off = compare.compare(read_png, png, refs[key])
                    primary = (ours["rays"]["primary"], refs[key]["primary_rays"])
                    renders += 1
                if off or primary[0] != primary[1]:
                    os.makedirs(args.out, exist_ok=True)
                    kept = os.path.join(args.out, f"seed{args.seed}-scene{n}.json")
                    if obj is not None:  # the mesh beside it, under the scene's own name
                        with open(kept[:-5] + ".obj", "w") as fh:
                            fh.write(obj)
                        for o in text["objects"]:
                            if o["type"] == "mesh":
                                o["obj"] = os.path.basename(kept[:-5] + ".obj")
                    with open(kept, "w") as fh:
                        json.dump(text, fh)
                    bad.append(f"| {kept} | {label} | {worst} | {off} | {primary[0]} | {primary[1]} |")
                    if ours_ok != ref_ok:
                        break
    print(f"{args.scenes} random scenes (seed {args.seed}; {refused} refused by both), {renders} renders "
          f"at {SIZE}, {time.time() - started:.0f} s: {len(bad)} disagree.")
    if bad:
        print("\n| scene | sampling | largest difference (/255) | pixels off by > 1 | primary rays whitted "
              "| primary rays reference |")
        print("|---|---|---:|---:|---:|---:|")
        print("\n".join(bad))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
