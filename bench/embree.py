#!/usr/bin/env python3
"""whitted against Intel Embree on the many-object scenes: ns per ray, build seconds, peak memory.

Embree is the practical limit for closest-hit queries on a CPU. This script loads the very scene
whitted renders (bench/scenes/*.json, a mesh's OBJ), builds Embree's default BVH over the same
primitives, and traces the same rays through it on one thread. Two peers answer the queries:

  embreex  the meshes: Embree 4.4 behind a small Cython binding (`pip install embreex`), which
           binds triangle meshes only;
  harness  spheres-10k: Embree 3.13 from Debian's libembree-dev through bench/embree_harness.c,
           a C program that holds Embree's true sphere primitive (RTC_GEOMETRY_TYPE_SPHERE_POINT:
           centre and radius, nothing tessellated) and answers batches of rays over a pipe. It
           takes triangles too: `--mesh-peer harness` runs the meshes through it (Embree 3
           against 4, a cross-check). The script compiles it (`cc -O2 … -lembree3`) into WORK,
           and bench/peak_rss.c too, which measures each process's peak memory.

Either way this script makes every ray, in f64 as whitted does, and gives it to Embree in f32
(Embree's precision); one set of rules for both peers:

  primary    one ray per pixel centre, the camera of docs/algorithm.md §2 (lookAt frame, window
             at p, rows counted from the bottom);
  hit        Embree's primitive and t; the point I = O + t·D and the outward normal N recomputed
             in f64 from the scene (a sphere's (I − C)/r with I put back on the sphere, a
             triangle's normalize((b − a) × (c − a))), the facing normal N_f = N when D·N ≤ 0;
  shadow     from each hit with N_f·L > 0 (whitted casts no shadow ray otherwise, §6), a segment
             to the light: `rtcOccluded1` with `tfar` = the distance, from I moved off the surface
             along N_f by EMBREE_OFFSET (Embree's f32 hit points need a larger offset than
             whitted's exact one);
  reflected  from each hit on an object with ks > 0 at level n ≤ max_depth (§6), R = D − 2(D·N_f)·N_f
             from the same offset origin, traced level by level (breadth first) like the primary
             rays. No scene here has glass (kt > 0): the script refuses transmitted rays.

So whitted traces the same rays: its `rays.primary`, `rays.reflected` and `rays.shadow` are
compared with Embree's. Per pixel, whitted's PNG tells the class of the pixel (background colour;
the ambient colour ka of the primitive hit — no light, or shadowed; lit; or, for a primitive with
ks > 0, "mirror", whose colour mixes its reflections) and Embree's rays tell it too: the script
counts the pixels whose class differs. f32 against f64 arithmetic and Embree's larger offset flip
a few on a silhouette, a terminator or a grazing shadow segment; a run fails when a ray count or
the differing pixels exceed MISMATCH_TOLERANCE.

A third peer answers the same way: whitted's own search through examples/queries.rs, a query
server that speaks the harness's batch protocol, loads the scene with whitted's loader and answers
each ray with `Accel::nearest` / `Accel::occluders` over the structure a render builds. Its rays
are made by the same rules from its own hits, and only its queries are timed: its ns per ray is
Embree's measure, where whitted's render figure also holds the camera, the shading and the image
(`--no-queries` leaves it out; the script builds it with `cargo build --release --example queries`).

Each round runs whitted (`render --threads 1 --json`), this script's Embree child and the query
server's child, one after the other in one command, each its own process (its peak RSS its own, from bench/peak_rss.c), pinned to
the same single CPU (Embree's build would otherwise use every core through TBB; whitted's build
runs in its one-thread pool; the harness also asks Embree for `threads=1`). The tables show the
medians of the rounds, the ratios of each round (whitted / Embree) as median [min–max], and the
load average of the machine.

    ns/ray    whitted: trace seconds / (primary + reflected + shadow rays), its whole render
              (sampling, shading, the image); Embree: (primary + reflected + shadow query seconds)
              / the same rays, the queries alone — so the ratio is an upper bound on the
              traversal's gap; whitted's queries: as Embree's, the queries alone (a second table,
              by kind of ray)
    build s   whitted: `build_seconds` (the BVH over the loaded scene); Embree: `rtcCommitScene`
              (its default BVH build); embreex: timed around the first query, of one ray (the
              binding's copy of the arrays into Embree's buffers, `upload_s`, is kept apart)
    peak MB   the process's peak resident memory (ru_maxrss); embreex's includes Python, NumPy and
              the mesh's arrays, the harness's is the C process alone (VmHWM, with its batch of rays);
              in brackets what Embree itself added to the peak (its buffers and its BVH: the
              growth of the resident memory across the upload and the build)

Usage (from the repository root; `cargo build --release` first; `pip install embreex` and
`apt-get install libembree-dev`, which bench/peers.sh does):
    python3 bench/embree.py                          # the meshes and spheres-10k, 5 rounds
    python3 bench/embree.py --only spheres-10k --runs 3
    python3 bench/embree.py --only mesh-100k --mesh-peer harness --runs 1   # Embree 3 on a mesh
Results: bench/results/DATE-COMMIT-embree.json (the raw rounds and the table), like run.py's;
DATE-COMMIT-embree-harness.json with --mesh-peer harness.
"""
import argparse
import json
import os
import statistics
import struct
import subprocess
import sys
import time

BENCH = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(BENCH)
sys.path.insert(0, BENCH)
import run as runpy  # noqa: E402  (the POV-Ray bench: its PNG reader, process measure, git helpers)

SCENES = ["mesh-100k", "mesh-1000k", "spheres-10k"]
WORK = "/tmp/whitted-bench/embree"
# The C programs this script compiles into WORK: the Embree 3 harness, and the wrapper that
# measures a process's peak memory (bench/peak_rss.c says why).
HARNESS = ("embree_harness", ["-lembree3"])
PEAK_RSS = ("peak_rss", [])
# How far a shadow or reflected ray's origin leaves the surface in Embree's run, relative to the
# hit point's largest coordinate (at least 1): f32 hit points are off by about 1e-7 of that.
EMBREE_OFFSET = 1e-4
# The most that whitted's and Embree's rays may disagree, as a fraction: of whitted's count for
# each kind of ray, of the image's pixels for the pixels whose class differs. f32 silhouettes and
# the larger offset flip a few hundred pixels of 307 200 (under 0.1 %); a wrong ray rule or camera
# flips thousands.
MISMATCH_TOLERANCE = 2e-3
# The child's peer name for whitted's query server, followed by the server's path.
QUERIES_PEER = "queries="
# A pixel's class, as both sides tell it.
BACKGROUND, AMBIENT, LIT, MIRROR = 0, 1, 2, 3


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


class Mesh:
    """The scene's one mesh object: Embree's triangles, and what a hit needs of them in f64."""

    kind = "triangles"

    def __init__(self, scene, scene_path):
        (obj,) = [o for o in scene["objects"] if o["type"] == "mesh"]
        if len(scene["objects"]) != 1:
            raise SystemExit("embree.py: a mesh scene must hold the mesh alone")
        self.verts, self.faces = load_obj(os.path.join(os.path.dirname(scene_path), obj["obj"]))
        self.ks = float(obj["material"].get("ks", 0))
        self.count = len(self.faces)

    def surface(self, prim, point):
        """The hit points and the outward unit normals normalize((b − a) × (c − a)) (§3)."""
        import numpy as np

        a, b, c = (self.verts[self.faces[prim, k]] for k in range(3))
        n = np.cross(b - a, c - a)
        return point, n / np.linalg.norm(n, axis=1)[:, None]

    def reflects(self, prim):
        import numpy as np

        return np.full(len(prim), self.ks > 0)


class Spheres:
    """The scene's spheres (every object a sphere), in the order of `objects`."""

    kind = "spheres"

    def __init__(self, scene):
        import numpy as np

        if any(o["type"] != "sphere" for o in scene["objects"]):
            raise SystemExit("embree.py: a sphere scene must hold spheres alone")
        self.centres = np.array([o["center"] for o in scene["objects"]], float)
        self.radii = np.array([o["radius"] for o in scene["objects"]], float)
        self.ks = np.array([o["material"].get("ks", 0) for o in scene["objects"]], float)
        if any(o["material"].get("kt", 0) > 0 for o in scene["objects"]):
            raise SystemExit("embree.py: glass (kt > 0) is not traced here")
        self.count = len(self.radii)

    def surface(self, prim, point):
        """The hit points put back on their sphere, C + r·N, and N = (I − C)/|I − C| (§3, §11)."""
        import numpy as np

        off = point - self.centres[prim]
        n = off / np.linalg.norm(off, axis=1)[:, None]
        return self.centres[prim] + self.radii[prim][:, None] * n, n

    def reflects(self, prim):
        return self.ks[prim] > 0


def scene_geometry(scene, scene_path):
    return Mesh(scene, scene_path) if any(o["type"] == "mesh" for o in scene["objects"]) else Spheres(scene)


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


class Embreex:
    """Embree 4.4 through the embreex binding: triangle meshes only."""

    def __init__(self, geom):
        import embreex
        import numpy as np
        from embreex import rtcore_scene
        from embreex.mesh_construction import TriangleMesh

        if geom.kind != "triangles":
            raise SystemExit("embree.py: embreex binds triangle meshes only (use the harness)")
        self.name = "Embree %s (embreex)" % embreex.__version__
        self.es = rtcore_scene.EmbreeScene()
        rss_before = resident_mb()
        t0 = time.perf_counter()
        # The binding copies the arrays into Embree's buffers one element at a time (Cython):
        # timed apart, it is not Embree's build.
        TriangleMesh(self.es, geom.verts.astype(np.float32), geom.faces.astype(np.int32))
        self.upload_s = time.perf_counter() - t0
        # The first query commits the scene (rtcCommitScene: the BVH build); one ray costs nothing.
        one = np.zeros((1, 3), np.float32)
        t0 = time.perf_counter()
        self.es.run(one, one + np.float32(1))
        self.build_s = time.perf_counter() - t0
        # What Embree itself holds: the growth of the resident memory across the upload and the build.
        self.embree_mb = resident_mb() - rss_before
        self.peak_mb = None  # this process's: the parent measures it

    def intersect(self, o, d):
        """(primitive or −1, t, seconds) of each ray's nearest hit."""
        import numpy as np

        o32, d32 = o.astype(np.float32), d.astype(np.float32)
        t0 = time.perf_counter()
        hit = self.es.run(o32, d32, output=1)
        seconds = time.perf_counter() - t0
        return np.asarray(hit["primID"]), np.asarray(hit["tfar"]).astype(float), seconds

    def occluded(self, o, d, tfar):
        """(whether something lies on each segment, seconds)."""
        import numpy as np

        o32, d32, t32 = o.astype(np.float32), d.astype(np.float32), tfar.astype(np.float32)
        t0 = time.perf_counter()
        occ = np.asarray(self.es.run(o32, d32, dists=t32, query="OCCLUDED"))
        seconds = time.perf_counter() - t0
        return (occ >= 0 if occ.dtype != bool else occ), seconds

    def close(self):
        pass


class Harness:
    """Embree 3 through bench/embree_harness.c, a process that answers batches over a pipe (its
    protocol is in the C file's header comment)."""

    KINDS = {"triangles": 1, "spheres": 2}
    INTERSECT, OCCLUDED, END = 1, 2, 0

    def __init__(self, geom, binary):
        import numpy as np

        self.proc = subprocess.Popen([binary], stdin=subprocess.PIPE, stdout=subprocess.PIPE)
        if geom.kind == "triangles":
            header = (len(geom.verts), len(geom.faces))
            body = [geom.verts.astype("<f4").tobytes(), geom.faces.astype("<u4").tobytes()]
        else:
            header = (geom.count, 0)
            body = [np.column_stack([geom.centres, geom.radii]).astype("<f4").tobytes()]
        self._send(struct.pack("<IQQ", self.KINDS[geom.kind], *header), *body)
        self.build_s, self.embree_mb, version = struct.unpack("<3d", self._receive(24))
        v = int(version)
        self.name = "Embree %d.%d.%d (C harness)" % (v // 10000, v // 100 % 100, v % 100)
        self.upload_s = None
        self.peak_mb = None

    def _send(self, *chunks):
        for c in chunks:
            self.proc.stdin.write(c)
        self.proc.stdin.flush()

    def _receive(self, n):
        data = self.proc.stdout.read(n)
        if len(data) != n:
            raise SystemExit("embree.py: the harness stopped (exit %s)" % self.proc.poll())
        return data

    def _batch(self, op, o, d, tfar):
        import numpy as np

        rays = np.column_stack([o, d, tfar]).astype("<f4")
        self._send(struct.pack("<IQ", op, len(rays)), rays.tobytes())
        (seconds,) = struct.unpack("<d", self._receive(8))
        return seconds

    def intersect(self, o, d):
        import numpy as np

        n = len(o)
        seconds = self._batch(self.INTERSECT, o, d, np.full(n, np.inf))
        prim = np.frombuffer(self._receive(4 * n), "<i4")
        t = np.frombuffer(self._receive(4 * n), "<f4").astype(float)
        return prim, t, seconds

    def occluded(self, o, d, tfar):
        import numpy as np

        seconds = self._batch(self.OCCLUDED, o, d, tfar)
        return np.frombuffer(self._receive(len(o)), np.uint8).astype(bool), seconds

    def close(self):
        self._send(struct.pack("<I", self.END))
        (self.peak_mb,) = struct.unpack("<d", self._receive(8))
        self.proc.wait()


class Queries(Harness):
    """whitted's search alone through examples/queries.rs: the harness's batches, answered by
    `Accel::nearest` and `Accel::occluders` over the structure a render builds. The server loads
    the scene file itself (whitted's loader), so nothing is uploaded; its protocol is in the
    example's header comment."""

    def __init__(self, scene_path, binary):
        self.proc = subprocess.Popen([binary, scene_path], stdin=subprocess.PIPE, stdout=subprocess.PIPE)
        self.build_s, self.embree_mb, _ = struct.unpack("<3d", self._receive(24))
        self.embree_mb = None
        self.name = "whitted's queries (examples/queries.rs)"
        self.upload_s = None
        self.peak_mb = None


def offset_origins(point, facing):
    """I moved off the surface along N_f by EMBREE_OFFSET · max(‖I‖∞, 1)."""
    import numpy as np

    scale = np.maximum(np.abs(point).max(axis=1), 1.0)
    return point + facing * (EMBREE_OFFSET * scale)[:, None]


def unit(v):
    """The rows of v divided by their lengths (a zero row left zero) and the lengths."""
    import numpy as np

    length = np.linalg.norm(v, axis=1)
    return v / np.where(length > 0, length, 1)[:, None], length


def trace(peer, geom, scene):
    """Every ray of the scene's ray trees through `peer`, level by level: figures and each pixel's
    class and primary primitive."""
    import numpy as np

    (light,) = scene["lights"]
    light = np.array(light["position"], float)
    max_depth = scene.get("max_depth", 5)
    o, d = camera_rays(scene["camera"])
    pixels = len(o)
    pixel = np.arange(pixels)
    seconds = {"primary_s": 0.0, "reflected_s": 0.0}
    reflected = 0
    hits = 0
    shadow = {"o": [], "d": [], "t": [], "pixel": []}
    primary_prim = primary_cast = None
    level = 1
    while len(o):
        prim, t, s = peer.intersect(o, d)
        seconds["primary_s" if level == 1 else "reflected_s"] += s
        if level > 1:
            reflected += len(o)
        hit = prim >= 0
        if level == 1:
            primary_prim, hits = prim.copy(), int(hit.sum())
        p, o, d, pixel = prim[hit], o[hit], d[hit], pixel[hit]
        point, n = geom.surface(p, o + d * t[hit][:, None])
        # Entering iff D·N ≤ 0; the facing normal N_f is N entering, −N leaving (§3).
        facing = np.where((np.einsum("ij,ij->i", n, d) <= 0)[:, None], n, -n)
        start = offset_origins(point, facing)
        ldir, _ = unit(light - point)
        cast = np.einsum("ij,ij->i", facing, ldir) > 0
        sdir, sdist = unit(light[None, :] - start[cast])
        shadow["o"].append(start[cast])
        shadow["d"].append(sdir)
        shadow["t"].append(sdist)
        shadow["pixel"].append(pixel[cast] if level == 1 else np.full(int(cast.sum()), -1))
        if level == 1:
            primary_cast = np.zeros(pixels, bool)
            primary_cast[pixel[cast]] = True
        if level > max_depth:
            break
        mirror = geom.reflects(p)
        dm, fm = d[mirror], facing[mirror]
        r, _ = unit(dm - 2 * np.einsum("ij,ij->i", dm, fm)[:, None] * fm)
        o, d, pixel = start[mirror], r, pixel[mirror]
        level += 1
    so, sd, st = (np.concatenate(shadow[k]) for k in ("o", "d", "t"))
    occluded, shadow_s = peer.occluded(so, sd, st)
    spixel = np.concatenate(shadow["pixel"])
    primary_lit = np.zeros(pixels, bool)
    primary_lit[spixel[(spixel >= 0) & ~occluded]] = True
    classes = np.where(primary_prim < 0, BACKGROUND, np.where(primary_lit, LIT, AMBIENT))
    classes = np.where((primary_prim >= 0) & geom.reflects(np.maximum(primary_prim, 0)), MIRROR, classes)
    assert not (primary_lit & ~primary_cast).any()
    figures = dict(seconds, shadow_s=shadow_s, primary=pixels, reflected=reflected, shadow=len(so), hits=hits,
                   occluded=int(occluded.sum()))
    return figures, classes.astype(np.uint8), primary_prim.astype(np.int32)


def child(scene_path, classes_out, peer_name):
    """Builds Embree's scene, traces the rays, prints the figures as JSON on stdout; writes each
    pixel's class (u8) to CLASSES and its primary primitive (i32, −1 none) to CLASSES.prim."""
    with open(scene_path) as fh:
        scene = json.load(fh)
    t0 = time.perf_counter()
    geom = scene_geometry(scene, scene_path)
    load_s = time.perf_counter() - t0
    if peer_name == "embreex":
        peer = Embreex(geom)
    elif peer_name.startswith(QUERIES_PEER):
        peer = Queries(scene_path, peer_name[len(QUERIES_PEER):])
    else:
        peer = Harness(geom, peer_name)
    figures, classes, prim = trace(peer, geom, scene)
    peer.close()
    classes.tofile(classes_out)
    prim.tofile(classes_out + ".prim")
    print(json.dumps(dict(figures, load_s=load_s, upload_s=peer.upload_s, build_s=peer.build_s, embree_mb=peer.embree_mb,
                          peer=peer.name, peer_peak_mb=peer.peak_mb, primitives=geom.count)))


def compiled(program):
    """bench/NAME.c compiled into WORK (again when the source is newer); its path."""
    name, libs = program
    source, binary = os.path.join(BENCH, name + ".c"), os.path.join(WORK, name)
    if os.path.exists(binary) and os.path.getmtime(binary) >= os.path.getmtime(source):
        return binary
    cmd = ["cc", "-O2", "-o", binary, source, *libs]
    runpy.log(" ".join(cmd))
    if subprocess.run(cmd).returncode != 0:
        sys.exit("embree.py: %s did not compile%s" % (source, " (apt-get install libembree-dev: Embree 3)" if libs else ""))
    return binary


def queries_server():
    """target/release/examples/queries, built by cargo (a no-op when it is up to date); its path."""
    cmd = ["cargo", "build", "--release", "--quiet", "--example", "queries"]
    if subprocess.run(cmd, cwd=REPO).returncode != 0:
        sys.exit("embree.py: %s failed" % " ".join(cmd))
    return os.path.join(REPO, "target", "release", "examples", "queries")


# ----------------------------------------------------------------------------------------------
# The parent: rounds of whitted and Embree


def measured(cmd, cpu, timeout):
    """Runs `cmd` on CPU `cpu`; (stdout, wall seconds, peak RSS MB), the peak from peak_rss."""
    peak_file = os.path.join(WORK, "peak_kb")
    cmd = [compiled(PEAK_RSS), peak_file] + cmd
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
    _, status, _ = os.wait4(pid, 0)
    wall = time.perf_counter() - start
    if os.waitstatus_to_exitcode(status) != 0:
        raise SystemExit("embree.py: %s failed (exit %d)" % (" ".join(cmd), os.waitstatus_to_exitcode(status)))
    with open(peak_file) as fh:
        peak_mb = int(fh.read()) / 1024.0
    return b"".join(chunks).decode(), wall, peak_mb


def rgb8(c):
    return tuple(round(255 * min(max(x, 0.0), 1.0)) for x in c)


def png_classes(path, scene, prim):
    """Each pixel of whitted's PNG (row-major from the top) as BACKGROUND (the background colour),
    MIRROR (the primitive Embree hit there has ks > 0: its colour mixes reflections), AMBIENT (the
    ambient colour ka of that primitive: no light, or shadowed) or LIT."""
    width, height, pixels = runpy.read_png(path)
    bg = rgb8(scene["background"])
    objects = scene["objects"]
    one = len(objects) == 1  # a mesh: every triangle is the one object
    amb = scene.get("ambient", [1, 1, 1])
    ka = [rgb8(a * k for a, k in zip(amb, o["material"]["ka"])) for o in objects]
    mirror = [o["material"].get("ks", 0) > 0 for o in objects]
    out = bytearray(width * height)
    for k in range(width * height):
        px = tuple(pixels[3 * k:3 * k + 3])
        j = 0 if one else max(int(prim[k]), 0)
        out[k] = BACKGROUND if px == bg else MIRROR if mirror[j] else AMBIENT if px == ka[j] else LIT
    return bytes(out)


CLASS_NAMES = {BACKGROUND: "background", AMBIENT: "unlit or shadowed", LIT: "lit", MIRROR: "mirror"}


def compare_rays(w, e, mine, theirs, pixels):
    """whitted's rays against Embree's: the counts, the pixels whose class differs (by pair of
    classes), and the mismatches beyond MISMATCH_TOLERANCE."""
    differ = {}
    for a, b in zip(mine, theirs):
        if a != b:
            key = "whitted %s / Embree %s" % (CLASS_NAMES[a], CLASS_NAMES[b])
            differ[key] = differ.get(key, 0) + 1
    check = {
        "primary": [w["rays"]["primary"], e["primary"]],
        "reflected": [w["rays"]["reflected"], e["reflected"]],
        "shadow": [w["rays"]["shadow"], e["shadow"]],
        "transmitted": w["rays"]["transmitted"],
        "hits": [sum(1 for c in mine if c != BACKGROUND), e["hits"]],
        "lit": [sum(1 for c in mine if c == LIT), sum(1 for c in theirs if c == LIT)],
        "pixels_whose_class_differs": sum(differ.values()),
        "differing_classes": differ,
        "tolerance": MISMATCH_TOLERANCE,
    }
    beyond = [k for k in ("reflected", "shadow") if abs(check[k][0] - check[k][1]) > MISMATCH_TOLERANCE * check[k][0]]
    if check["primary"][0] != check["primary"][1]:
        beyond.append("primary")
    if check["transmitted"]:
        beyond.append("transmitted")
    if check["pixels_whose_class_differs"] > MISMATCH_TOLERANCE * pixels:
        beyond.append("pixel classes")
    check["beyond_tolerance"] = beyond
    return check


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
    ap.add_argument("--mesh-peer", choices=["embreex", "harness"], default="embreex",
                    help="the meshes through embreex (Embree 4, the default) or the C harness (Embree 3); "
                         "spheres always go through the harness")
    ap.add_argument("--no-queries", action="store_true",
                    help="skip the third child, whitted's queries alone (examples/queries.rs)")
    ap.add_argument("--results", default=runpy.RESULTS, help="folder of the results file")
    ap.add_argument("--timeout", type=float, default=600)
    ap.add_argument("--povray-dir", help="folder of gen_mesh.py, when the meshes must be generated (see run.py)")
    ap.add_argument("--child", nargs=3, metavar=("SCENE", "CLASSES", "PEER"), help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child:
        child(*args.child)
        return
    binaries = [os.path.abspath(w) for w in args.whitted] or [os.path.join(REPO, "target", "release", "whitted")]
    for w in binaries:
        if not os.access(w, os.X_OK):
            sys.exit("embree.py: the whitted binary is missing: %s (cargo build --release)" % w)
    cpu = args.cpu if args.cpu is not None else max(os.sched_getaffinity(0))
    scenes = args.only or SCENES
    peers = {s: "harness" if s.startswith("spheres-") or args.mesh_peer == "harness" else "embreex" for s in scenes}
    if "embreex" in peers.values():
        try:
            import embreex  # noqa: F401
        except ImportError:
            sys.exit("embree.py: the embreex package is missing: pip install embreex")
    runpy.ensure_scene_files([(s, s + ".json", []) for s in scenes], False, args.povray_dir)
    os.makedirs(WORK, exist_ok=True)
    peers = {s: compiled(HARNESS) if p == "harness" else p for s, p in peers.items()}
    server = None if args.no_queries else queries_server()
    load_start = os.getloadavg()
    results = {"machine": runpy.machine_info(binaries[0], None, load_start), "cpu": cpu, "binaries": binaries,
               "runs": args.runs, "embree_offset": EMBREE_OFFSET, "scenes": []}
    for name in scenes:
        scene_path = os.path.join(runpy.SCENE_DIR, name + ".json")
        with open(scene_path) as fh:
            scene = json.load(fh)
        pngs = [os.path.join(WORK, "%s-whitted%d.png" % (name, i)) for i in range(len(binaries))]
        classes = os.path.join(WORK, name + "-embree.classes")
        e_cmd = [sys.executable, os.path.abspath(__file__), "--child", scene_path, classes, peers[name]]
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
            e_rays = e["primary"] + e["reflected"] + e["shadow"]
            e_s = e["primary_s"] + e["reflected_s"] + e["shadow_s"]
            # The harness's own peak when it answered (a C process); embreex's is the Python child's.
            er = dict(e, peak_mb=e["peer_peak_mb"] or rss, child_peak_mb=rss, wall_s=wall, ns_per_ray=1e9 * e_s / e_rays)
            one = {"whitted": sides, "embree": er}
            if server:
                q_cmd = [sys.executable, os.path.abspath(__file__), "--child", scene_path, classes + ".queries",
                         QUERIES_PEER + server]
                out, wall, rss = measured(q_cmd, cpu, args.timeout)
                q = json.loads(out)
                q_rays = q["primary"] + q["reflected"] + q["shadow"]
                one["queries"] = dict(q, peak_mb=q["peer_peak_mb"], wall_s=wall,
                                      ns_per_ray=1e9 * (q["primary_s"] + q["reflected_s"] + q["shadow_s"]) / q_rays)
            rounds.append(one)
            runpy.log("%-11s round %d: %s | Embree %.0f ns/ray, build %.3f s, %.0f MB" % (
                name, k + 1, " | ".join("whitted%d %.0f ns/ray, build %.3f s, %.0f MB"
                                        % (i, w["ns_per_ray"], w["build_s"], w["peak_mb"]) for i, w in enumerate(sides)),
                er["ns_per_ray"], er["build_s"], er["peak_mb"])
                + (" | whitted's queries %.0f ns/ray" % one["queries"]["ns_per_ray"] if server else ""))
        # Same rays? Counts from the last round (every round traces the same rays).
        w, e = rounds[-1]["whitted"][0], rounds[-1]["embree"]
        with open(classes, "rb") as fh:
            theirs = fh.read()
        with open(classes + ".prim", "rb") as fh:
            data = fh.read()
            prim = struct.unpack("<%di" % (len(data) // 4), data)
        mine = png_classes(pngs[0], scene, prim)
        images = []
        for png in pngs:
            with open(png, "rb") as fh:
                images.append(fh.read())
        check = compare_rays(w, e, mine, theirs, len(mine))
        if server:
            # The query server's rays against Embree's: made by the same rules from its own hits.
            q = rounds[-1]["queries"]
            check["queries"] = {k: [q[k], e[k]] for k in ("primary", "reflected", "shadow", "hits", "occluded")}
            check["beyond_tolerance"] += ["queries' " + k for k, (a, b) in check["queries"].items()
                                          if abs(a - b) > MISMATCH_TOLERANCE * max(a, b, 1)]
        check.update({
            "same_png_bytes": all(img == images[0] for img in images),
            "same_rays": all(x["rays"] == w["rays"] for x in rounds[-1]["whitted"]),
            # Node and object tests per ray of each binary: a render's wide BVH tests other nodes
            # (and may test other triangles first) than the binary tree, for the same answers.
            "tests_per_ray": [{k: round(v / max(1, sum(x["rays"].values())), 2) for k, v in x["tests"].items()}
                              for x in rounds[-1]["whitted"]],
        })
        results["scenes"].append({"scene": name, "peer": e["peer"], "primitives": e["primitives"], "rounds": rounds,
                                  "check": check})
    results["machine"]["load_average_end"] = [round(x, 2) for x in os.getloadavg()]
    text = table(results)
    results["table"] = text
    os.makedirs(args.results, exist_ok=True)
    # The meshes through Embree 3 (the cross-check) get a file of their own beside the main run's.
    suffix = "-embree.json" if args.mesh_peer == "embreex" else "-embree-harness.json"
    path = runpy.results_path(args.results, results["machine"]).replace(".json", suffix)
    with open(path, "w") as fh:
        json.dump(results, fh, indent=1)
        fh.write("\n")
    print(text)
    runpy.log("\nresults: %s" % runpy.shown(path))
    bad = ["%s (%s)" % (s["scene"], ", ".join(s["check"]["beyond_tolerance"])) for s in results["scenes"]
           if s["check"]["beyond_tolerance"]]
    bad += ["%s (the binaries' images or rays differ)" % s["scene"] for s in results["scenes"]
            if not s["check"]["same_png_bytes"] or not s["check"]["same_rays"]]
    if bad:
        sys.exit("embree.py: other rays than Embree's beyond the tolerance %g, or binaries that differ: %s"
                 % (MISMATCH_TOLERANCE, "; ".join(bad)))


def table(results):
    m = results["machine"]
    names = ["whitted"] if len(results["binaries"]) == 1 else [
        "whitted%d (%s)" % (i, runpy.shown(b)) for i, b in enumerate(results["binaries"])]
    peers = sorted({s["peer"] for s in results["scenes"]})
    lines = ["%s against whitted (%s), one thread each (CPU %d), %d rounds; load average %s → %s."
             % (" and ".join(peers), ", ".join(names), results["cpu"], results["runs"], m["load_average_start"],
                m["load_average_end"]),
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
    with_queries = [s for s in results["scenes"] if all("queries" in x for x in s["rounds"])]
    if with_queries:
        lines += ["", "whitted's search alone against Embree's (examples/queries.rs: the rays made by the same rules "
                  "from its own hits, timed around `Accel::nearest` and `Accel::occluders` alone, as the harness "
                  "times Embree's queries; medians, ratios per round):", "",
                  "| scene | whitted queries ns/ray (primary / reflected / shadow) | Embree ns/ray (primary / "
                  "reflected / shadow) | ratio | whitted render ns/ray | queries / render | rays, queries / Embree "
                  "(primary, reflected, shadow) |",
                  "|---|---:|---:|---:|---:|---:|---|"]
        for s in with_queries:
            r = s["rounds"]
            q = lambda key: statistics.median(x["queries"][key] for x in r)
            e = lambda key: statistics.median(x["embree"][key] for x in r)
            kinds = lambda f, side: " / ".join(
                "%.0f" % (1e9 * f(k + "_s") / side[k]) if side[k] else "—" for k in ("primary", "reflected", "shadow"))
            last_q, last_e = r[-1]["queries"], r[-1]["embree"]
            lines.append("| %s | %.0f (%s) | %.0f (%s) | %s | %.0f | %s | %d / %d, %d / %d, %d / %d |" % (
                s["scene"], q("ns_per_ray"), kinds(q, last_q), e("ns_per_ray"), kinds(e, last_e),
                spread([x["queries"]["ns_per_ray"] / x["embree"]["ns_per_ray"] for x in r]),
                statistics.median(x["whitted"][0]["ns_per_ray"] for x in r),
                spread([x["queries"]["ns_per_ray"] / x["whitted"][0]["ns_per_ray"] for x in r]),
                last_q["primary"], last_e["primary"], last_q["reflected"], last_e["reflected"],
                last_q["shadow"], last_e["shadow"]))
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
    lines += ["", "Same rays (whitted / Embree; tolerance %g of each count and of the pixels):" % MISMATCH_TOLERANCE]
    for s in results["scenes"]:
        c = s["check"]
        differ = "; ".join("%s %d" % kv for kv in sorted(c["differing_classes"].items())) or "none"
        lines.append("- %s (%d primitives, %s): primary %d / %d, reflected %d / %d, shadow %d / %d, hits %d / %d, "
                     "lit pixels %d / %d; pixels whose class (background, unlit or shadowed, lit, mirror) differs: "
                     "%d (%s)%s; the binaries' PNGs %s, their ray counts %s; node / object tests per ray %s"
                     % (s["scene"], s["primitives"], s["peer"], *c["primary"], *c["reflected"], *c["shadow"],
                        *c["hits"], *c["lit"], c["pixels_whose_class_differs"], differ,
                        "; BEYOND THE TOLERANCE: " + ", ".join(c["beyond_tolerance"]) if c["beyond_tolerance"] else "",
                        "byte for byte the same" if c["same_png_bytes"] else "DIFFER",
                        "the same" if c["same_rays"] else "DIFFER",
                        ", ".join("whitted%d %.2f / %.2f" % (i, t.get("node", 0), t.get("object", 0))
                                  for i, t in enumerate(c["tests_per_ray"]))))
    return "\n".join(lines)


if __name__ == "__main__":
    main()
