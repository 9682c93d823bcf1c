#!/usr/bin/env python3
"""Write the benchmark scenes that are generated rather than written by hand (bench/scenes/).

Each scene is the JSON twin of one of POV-Ray's bench scenes (shared bench/povray/), at 640x480:

  spheres-1k.json, spheres-10k.json   spheres-grid.pov with N = 1000 and N = 10000
  mesh-100k.json, mesh-1000k.json     mesh.pov with MESH_K = 100 and 1000; each names its OBJ file
                                      (mesh-100k.obj, mesh-1000k.obj), written next to it by the
                                      shared gen_mesh.py together with the mesh2 .inc POV-Ray reads

(whitted.json, the twin of whitted.pov, is written by hand.)

The camera is that of camera.inc: p = 1, window b = -0.5, t = 0.5, r = -l = 0.5 * width / height.
Every scene has max_depth 4 (POV-Ray's max_trace_level 5), ambient (1, 1, 1) and one white point
light without attenuation.

Usage (from anywhere):
    python3 bench/gen_scenes.py                  # every scene; mesh files only if missing
    python3 bench/gen_scenes.py --force-mesh     # regenerate the mesh files too
    python3 bench/gen_scenes.py --no-mesh        # spheres and the mesh JSON only
"""
import argparse
import json
import math
import os
import subprocess
import sys

BENCH = os.path.dirname(os.path.abspath(__file__))
SCENES = os.path.join(BENCH, "scenes")
WIDTH, HEIGHT = 640, 480
SPHERE_COUNTS = {"spheres-1k": 1000, "spheres-10k": 10000}
MESH_SIZES = {"mesh-100k": 100, "mesh-1000k": 1000}


def povray_dir(explicit=None):
    """The folder holding the POV-Ray scenes and gen_mesh.py: --povray-dir, then bench/povray/ in this
    repository if it exists, then the shared copy."""
    candidates = [explicit] if explicit else [os.path.join(BENCH, "povray"), os.path.join(BENCH, "..", "..", "shared", "bench", "povray")]
    for d in candidates:
        if d and os.path.isfile(os.path.join(d, "gen_mesh.py")):
            return os.path.abspath(d)
    sys.exit("gen_scenes.py: no POV-Ray bench folder with gen_mesh.py found (tried %s); pass --povray-dir"
             % ", ".join(c for c in candidates if c))


def num(x):
    """A float rounded to 12 decimals (far below what a render can show) so the JSON stays small
    and free of artefacts like 0.020000000000000004; whole numbers stay whole."""
    r = round(x, 12)
    return int(r) if r == int(r) and abs(r) < 1e15 else r


def vec(v):
    return [num(x) for x in v]


def camera(eye, center):
    """camera.inc's camera: window height 1 at distance p = 1, width following the image."""
    half_w = 0.5 * WIDTH / HEIGHT
    return {
        "eye": vec(eye), "center": vec(center), "up": [0, 1, 0], "projection": "perspective", "p": 1.0,
        "window": {"l": -half_w, "r": half_w, "b": -0.5, "t": 0.5},
        "resolution": [WIDTH, HEIGHT],
    }


def lattice_size(n):
    """K = ceil(N^(1/3)), computed as spheres-grid.pov does (the 1e-9 keeps 1000 -> 10)."""
    k = math.ceil(n ** (1.0 / 3.0) - 1e-9)
    assert k >= 2 and (k - 1) ** 3 < n <= k ** 3, (n, k)
    return k


def spheres_scene(n):
    """spheres-grid.pov with #declare N = n: sphere i = 0 .. n-1 of the K x K x K lattice."""
    k = lattice_size(n)
    s = 2.0 / k
    objects = []
    for i in range(n):
        ix, iy, iz = i % k, (i // k) % k, i // (k * k)
        center = (-1 + (ix + 0.5) * s, -1 + (iy + 0.5) * s, 1 - (iz + 0.5) * s)
        c = [0.2 + 0.6 * q / (k - 1) for q in (ix, iy, iz)]
        if (ix + iy + iz) % 4 == 0:
            # finish { ambient 0.1 diffuse 0.3 specular 0.6 roughness 1/64 reflection { 0.6 } }
            material = {"ka": vec(0.1 * q for q in c), "kd": vec(0.3 * q for q in c), "ks": 0.6, "n": 64}
        else:
            # finish { ambient 0.1 diffuse 0.8 specular 0 reflection { 0 } }
            material = {"ka": vec(0.1 * q for q in c), "kd": vec(0.8 * q for q in c), "ks": 0}
        objects.append({"type": "sphere", "center": vec(center), "radius": num(0.3 * s), "material": material})
    return {
        "camera": camera((2.2, 1.7, 2.9), (0, 0, 0)),
        "background": [0.05, 0.05, 0.1], "ambient": [1, 1, 1], "max_depth": 4,
        "lights": [{"position": [5, 8, 6], "intensity": [1, 1, 1]}],
        "objects": objects,
    }


def mesh_scene(obj_name):
    """mesh.pov: the height-field mesh, pigment c = (0.55, 0.7, 0.4), ambient 0.1, diffuse 0.9."""
    c = (0.55, 0.7, 0.4)
    return {
        "camera": camera((0, 2.0, 3.0), (0, -0.3, -0.2)),
        "background": [0.6, 0.75, 0.9], "ambient": [1, 1, 1], "max_depth": 4,
        "lights": [{"position": [-6, 4, -1], "intensity": [1, 1, 1]}],
        "objects": [{"type": "mesh", "name": "terrain", "obj": obj_name,
                     "material": {"ka": vec(0.1 * q for q in c), "kd": vec(0.9 * q for q in c), "ks": 0}}],
    }


def dump(scene, path):
    """One object per line: diffable, and far smaller than indent=2 for 10 000 spheres."""
    lines = ["{"]
    items = list(scene.items())
    for i, (key, value) in enumerate(items):
        comma = "," if i + 1 < len(items) else ""
        if key == "objects" and value:
            lines.append('  "objects": [')
            for j, obj in enumerate(value):
                lines.append("    " + json.dumps(obj) + ("," if j + 1 < len(value) else ""))
            lines.append("  ]" + comma)
        else:
            lines.append("  %s: %s%s" % (json.dumps(key), json.dumps(value), comma))
    lines.append("}")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    with open(path) as f:
        json.load(f)  # it must read back
    print("%-40s %8.1f kB" % (os.path.relpath(path), os.path.getsize(path) / 1024))


def ensure_mesh(k, pov_dir, force):
    """Run the shared gen_mesh.py in bench/scenes/ so that mesh-<k>k.obj (ours) and mesh-<k>k.inc
    (POV-Ray's) hold the very same triangles."""
    base = os.path.join(SCENES, "mesh-%dk" % k)
    if not force and os.path.exists(base + ".obj") and os.path.exists(base + ".inc"):
        print("%-40s exists (--force-mesh to redo)" % os.path.relpath(base + ".obj"))
        return
    subprocess.run([sys.executable, os.path.join(pov_dir, "gen_mesh.py"), str(k)], cwd=SCENES, check=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--povray-dir", help="folder with gen_mesh.py (default: bench/povray, else ../shared/bench/povray beside the repository)")
    ap.add_argument("--no-mesh", action="store_true", help="do not generate the OBJ/.inc mesh files")
    ap.add_argument("--force-mesh", action="store_true", help="regenerate the mesh files even if present")
    args = ap.parse_args()

    os.makedirs(SCENES, exist_ok=True)
    for name, n in SPHERE_COUNTS.items():
        dump(spheres_scene(n), os.path.join(SCENES, name + ".json"))
    for name, k in MESH_SIZES.items():
        dump(mesh_scene(name + ".obj"), os.path.join(SCENES, name + ".json"))
    if not args.no_mesh:
        pov_dir = povray_dir(args.povray_dir)
        for k in MESH_SIZES.values():
            ensure_mesh(k, pov_dir, args.force_mesh)


if __name__ == "__main__":
    main()
