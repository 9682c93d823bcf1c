#!/usr/bin/env python3
"""Independent reference implementation of the Whitted ray tracer described in
the project's algorithm.md (conventions + section 11) and product.md, now docs/
(scene format, defaults, image writing).  Python 3 standard library only.

Scope: 3D and 2D scenes (the camera's eye and center decide: 3 or 2 numbers);
camera (perspective / orthographic), background, ambient, max_depth, point lights
with attenuation, materials (by name or inline, with checker).  Objects in 3D:
sphere / plane / box / triangle / mesh (a Wavefront OBJ file); in 2D: sphere
(circle) / plane (line) / box (rectangle) / triangle / segment / polygon.  Brute
force over all objects (a mesh is one object: its triangles are all tested, after
a padded bounding-box pre-test that never changes a result).

Usage:
    python3 reference.py SCENE.json [--size WxH | --size W] [--aa center|corners|adaptive]
                   [--threshold X] [--max-level K] [--depth N] -o OUT.json

OUT.json = {"width", "height", "primary_rays", "pixels", "bytes"}; pixels in
row-major order, row 0 = BOTTOM row of the image (j counted from the bottom),
i from the left.  A 2D scene gives a strip Nx wide and max(1, Nx/8) rows tall
(H rows with --size WxH), every row the same; primary_rays counts the one line.
"""

import argparse
import json
import math
import os
import re
import sys
import time
from fractions import Fraction

INF = float("inf")


# ----------------------------------------------------------------------------
# Small vector helpers: tuples of floats of any length (3 in 3D, 2 in 2D).
# Sums are evaluated left to right from the first term (a0*b0 + a1*b1 + a2*b2),
# never from a 0.0 start, so 3D results are bit-identical to the 3-term forms
# and the sign of a zero survives.
# ----------------------------------------------------------------------------

def add(a, b):
    return tuple(x + y for x, y in zip(a, b))


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def scale(a, s):
    return tuple(x * s for x in a)


def neg(a):
    return tuple(-x for x in a)


def dot(a, b):
    s = a[0] * b[0]
    for k in range(1, len(a)):
        s += a[k] * b[k]
    return s


def cross(a, b):
    """3D only."""
    return (a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0])


def turn_cw(a):
    """2D: a turned by -90 degrees, (a_y, -a_x) (algorithm.md section 2 and section 3)."""
    return (a[1], -a[0])


def length(a):
    return math.sqrt(dot(a, a))


def norm_inf(a):
    return max(abs(x) for x in a)


def normalize(a):
    """Checked normalisation: returns None instead of producing NaN/inf."""
    n = length(a)
    if not (n > 0.0) or not math.isfinite(n):
        return None
    return tuple(x / n for x in a)


def normalize_scaled(a):
    """Scene vectors (up, normal) and derived normals: divide by the largest
    |component| first, so tiny and huge vectors work (algorithm.md section 11)."""
    m = norm_inf(a)
    if not (m > 0.0) or not math.isfinite(m):
        return None
    return normalize(tuple(x / m for x in a))


# ----------------------------------------------------------------------------
# Scene loading and validation
# ----------------------------------------------------------------------------

class SceneError(Exception):
    pass


class Loader:
    """Collects every validation error and reports them at once."""

    def __init__(self, lenient=False):
        self.errors = []
        self.lenient = lenient

    def err(self, field, msg):
        self.errors.append("%s: %s" % (field, msg))

    def unknown(self, field):
        if self.lenient:
            sys.stderr.write("warning: %s: unknown field (ignored)\n" % field)
        else:
            self.err(field, "unknown field")

    def check_fields(self, obj, field, allowed):
        if not isinstance(obj, dict):
            self.err(field, "must be an object")
            return False
        for k in obj:
            if k not in allowed:
                self.unknown("%s.%s" % (field, k))
        return True

    def number(self, v, field):
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            self.err(field, "must be a number, got %r" % (v,))
            return None
        v = float(v)
        if not math.isfinite(v) or abs(v) > 1e100:
            self.err(field, "must be finite and at most 1e100 in magnitude, got %r" % v)
            return None
        return v

    def vec(self, v, field, dim):
        """A point or direction of the scene's dimension (product.md: "3D vectors have 3
        numbers, 2D vectors 2; the camera's vectors decide the dimension, and mixing is an
        error")."""
        if not isinstance(v, list) or len(v) != dim:
            if dim == 2 and isinstance(v, list) and len(v) == 3:
                self.err(field, "must be a list of 2 numbers in a 2D scene (the camera's vectors "
                                "have 2), got %r" % (v,))
            elif dim == 3 and isinstance(v, list) and len(v) == 2:
                self.err(field, "must be a list of 3 numbers in a 3D scene (the camera's vectors "
                                "have 3), got %r" % (v,))
            else:
                self.err(field, "must be a list of %d numbers, got %r" % (dim, v))
            return None
        out = [self.number(x, "%s[%d]" % (field, k)) for k, x in enumerate(v)]
        if any(x is None for x in out):
            return None
        return tuple(out)

    def vec3(self, v, field):
        """Three numbers whatever the dimension: RGB colours, attenuation (c0, c1, c2)."""
        return self.vec(v, field, 3)

    def colour(self, v, field, grey_ok=False, lo=None, hi=None):
        """An RGB triple (or, where grey_ok, one number meaning grey)."""
        if grey_ok and not isinstance(v, list):
            x = self.number(v, field)
            if x is None:
                return None
            c = (x, x, x)
        else:
            c = self.vec3(v, field)
            if c is None:
                return None
        for k in range(3):
            if (lo is not None and c[k] < lo) or (hi is not None and c[k] > hi):
                self.err(field, "must be in [%s, %s] per channel, got %r" % (lo, hi, list(c)))
                break
        return c


class Material:
    def __init__(self):
        self.ka = (0.1, 0.1, 0.1)
        self.kd = (0.7, 0.7, 0.7)
        self.ks = 0.0
        self.n = 32.0
        self.kt = 0.0
        self.ior = 1.0
        self.checker = None  # (size, kd2, ka2)

    def colours_at(self, p):
        """(ka, kd) at point p, with the product.md checker rule."""
        if self.checker is None:
            return self.ka, self.kd
        size, kd2, ka2 = self.checker
        # floor(x/size + 1e-10) + floor(y/size + 1e-10) [+ floor(z/size + 1e-10)]: "in 2D, x and y"
        s = 0
        for x in p:
            s += math.floor(x / size + 1e-10)
        if s % 2 == 1:          # Python's % on ints is rem_euclid for divisor 2
            return ka2, kd2
        return self.ka, self.kd


def load_material(L, m, field):
    mat = Material()
    if not L.check_fields(m, field, ("ka", "kd", "ks", "n", "kt", "ior", "checker")):
        return mat
    if "ka" in m:
        c = L.colour(m["ka"], field + ".ka", grey_ok=True, lo=0.0, hi=1.0)
        if c is not None:
            mat.ka = c
    if "kd" in m:
        c = L.colour(m["kd"], field + ".kd", grey_ok=True, lo=0.0, hi=1.0)
        if c is not None:
            mat.kd = c
    for key, lo, hi in (("ks", 0.0, 1.0), ("kt", 0.0, 1.0), ("n", 0.0, None), ("ior", None, None)):
        if key in m:
            x = L.number(m[key], field + "." + key)
            if x is None:
                continue
            if key == "ior" and not x > 0:
                L.err(field + ".ior", "must be > 0, got %r" % x)
                continue
            if (lo is not None and x < lo) or (hi is not None and x > hi):
                L.err(field + "." + key, "out of range, got %r" % x)
                continue
            setattr(mat, key, x)
    if "checker" in m:
        ch = m["checker"]
        cf = field + ".checker"
        if L.check_fields(ch, cf, ("size", "kd2", "ka2")):
            size = 1.0   # NOTE: product.md documents no default for checker.size; 1 is our choice
            if "size" in ch:
                x = L.number(ch["size"], cf + ".size")
                if x is not None:
                    if x > 0:
                        size = x
                    else:
                        L.err(cf + ".size", "must be > 0, got %r" % x)
            kd2 = None
            if "kd2" in ch:
                kd2 = L.colour(ch["kd2"], cf + ".kd2", grey_ok=True, lo=0.0, hi=1.0)
            else:
                L.err(cf + ".kd2", "required")
            ka2 = mat.ka  # default: the material's ka (product.md)
            if "ka2" in ch:
                c = L.colour(ch["ka2"], cf + ".ka2", grey_ok=True, lo=0.0, hi=1.0)
                if c is not None:
                    ka2 = c
            if kd2 is not None:
                mat.checker = (size, kd2, ka2)
    return mat


# ----------------------------------------------------------------------------
# Objects.  intersect(O, D) -> (t, extra) for the least root t > 0, or None.
# surface(O, D, t, extra) -> (reprojected hit point, outward unit normal).
# ----------------------------------------------------------------------------

class Sphere:
    """A sphere, or in 2D a circle (the same formulas in 2 coordinates)."""

    def __init__(self, c, r):
        self.c = c
        self.r = r
        self.scale = norm_inf(c) + r

    def intersect(self, O, D):
        f = sub(O, self.c)
        b = dot(f, D)
        perp = sub(f, scale(D, b))
        disc = self.r * self.r - dot(perp, perp)
        if disc < 0.0:
            return None
        cc = dot(f, f) - self.r * self.r
        sgn = 1.0 if math.copysign(1.0, b) > 0 else -1.0   # sign(b'), Rust signum style
        q = -(b + sgn * math.sqrt(disc))
        if q == 0.0:
            roots = [-b, -b]
        else:
            roots = [q, cc / q]
        best = None
        for t in roots:
            if t > 0.0 and math.isfinite(t) and (best is None or t < best):
                best = t
        if best is None:
            return None
        return (best, None)

    def surface(self, O, D, t, extra):
        p = add(O, scale(D, t))
        d = sub(p, self.c)
        dl = length(d)
        if dl > 0.0:
            p = add(self.c, scale(d, self.r / dl))
        n = sub(p, self.c)
        n = tuple(x / self.r for x in n)   # N = (I - C)/r
        return p, n


class Plane:
    """A plane, or in 2D a line (point, unit normal)."""

    def __init__(self, point, normal):
        self.point = point
        self.n = normal
        self.scale = norm_inf(point)

    def intersect(self, O, D):
        den = dot(D, self.n)
        if den == 0.0:
            return None
        t = dot(sub(self.point, O), self.n) / den
        if not (t > 0.0) or not math.isfinite(t):
            return None
        return (t, None)

    def surface(self, O, D, t, extra):
        p = add(O, scale(D, t))
        sd = dot(sub(p, self.point), self.n)   # signed distance
        p = sub(p, scale(self.n, sd))
        return p, self.n


class Box:
    """An axis-aligned box, or in 2D a rectangle; a closed set, tested exactly."""

    def __init__(self, lo, hi):
        self.lo = lo
        self.hi = hi
        self.scale = max(norm_inf(lo), norm_inf(hi))

    def intersect(self, O, D):
        t_in, t_out = -INF, INF
        ax_in, ax_out = None, None
        for a in range(len(O)):
            o, d = O[a], D[a]
            if d == 0.0:
                # parallel slab: inside iff min <= o <= max, recorded (-inf, +inf)
                if self.lo[a] <= o <= self.hi[a]:
                    continue
                return None
            t1 = (self.lo[a] - o) / d
            t2 = (self.hi[a] - o) / d
            ti, te = min(t1, t2), max(t1, t2)
            if ti > t_in:               # strict: ties keep the earlier axis (x, y[, z])
                t_in, ax_in = ti, a
            if te < t_out:
                t_out, ax_out = te, a
        if not (t_in <= t_out):
            return None
        if t_in > 0.0:
            return (t_in, (ax_in, True))
        if t_out > 0.0:
            return (t_out, (ax_out, False))
        return None

    def surface(self, O, D, t, extra):
        axis, is_entry = extra
        d = D[axis]
        # entry face: min plane if d > 0, max plane if d < 0; exit face the other one
        on_max = (d < 0.0) if is_entry else (d > 0.0)
        p = list(add(O, scale(D, t)))
        p[axis] = self.hi[axis] if on_max else self.lo[axis]   # face coordinate set exactly
        n = [0.0] * len(D)
        n[axis] = 1.0 if on_max else -1.0
        return tuple(p), tuple(n)


class Triangle:
    def __init__(self, a, b, c, normal):
        self.a, self.b, self.c = a, b, c
        self.n = normal
        self.scale = max(norm_inf(a), norm_inf(b), norm_inf(c))

    def intersect(self, O, D):
        # Woop, Benthin, Wald 2013 watertight test (f64), exact re-evaluation on a 0 edge function.
        ad = (abs(D[0]), abs(D[1]), abs(D[2]))
        kz = 0
        if ad[1] > ad[kz]:
            kz = 1
        if ad[2] > ad[kz]:
            kz = 2
        kx = (kz + 1) % 3
        ky = (kx + 1) % 3
        if D[kz] < 0.0:
            kx, ky = ky, kx
        Sx = D[kx] / D[kz]
        Sy = D[ky] / D[kz]
        Sz = 1.0 / D[kz]
        A = sub(self.a, O)
        B = sub(self.b, O)
        C = sub(self.c, O)
        Ax = A[kx] - Sx * A[kz]
        Ay = A[ky] - Sy * A[kz]
        Bx = B[kx] - Sx * B[kz]
        By = B[ky] - Sy * B[kz]
        Cx = C[kx] - Sx * C[kz]
        Cy = C[ky] - Sy * C[kz]
        U = Cx * By - Cy * Bx
        V = Ax * Cy - Ay * Cx
        W = Bx * Ay - By * Ax
        if U == 0.0 or V == 0.0 or W == 0.0:
            F = Fraction
            U = float(F(Cx) * F(By) - F(Cy) * F(Bx))
            V = float(F(Ax) * F(Cy) - F(Ay) * F(Cx))
            W = float(F(Bx) * F(Ay) - F(By) * F(Ax))
        if (U < 0.0 or V < 0.0 or W < 0.0) and (U > 0.0 or V > 0.0 or W > 0.0):
            return None
        det = U + V + W
        if det == 0.0:
            return None      # edge-on (or degenerate): invisible
        Az = Sz * A[kz]
        Bz = Sz * B[kz]
        Cz = Sz * C[kz]
        T = U * Az + V * Bz + W * Cz
        if det < 0.0 and T >= 0.0:
            return None
        if det > 0.0 and T <= 0.0:
            return None
        t = T / det
        if not (t > 0.0) or not math.isfinite(t):
            return None
        return (t, None)

    def surface(self, O, D, t, extra):
        return add(O, scale(D, t)), self.n


class Mesh:
    """A triangle mesh read from a Wavefront OBJ file: ONE object (algorithm.md section 6: "Where
    two objects are hit at the same t, the nearest hit is the one with the smaller index in
    objects (within a mesh, the smaller triangle index)"; section 11: "Each distinct object
    multiplies s by its kt once, however many times the segment crosses it").  Every triangle is a
    Triangle (the watertight test, normal (b - a) x (c - a) normalised); the nearest hit is the
    least t over the triangles, ties to the lower triangle index.  extra = the triangle index.

    The offset scale is "the largest |coordinate| of its vertices" (section 11), taken over the
    vertices the triangles use.

    Pre-test: the ray must meet the triangles' bounding box grown by pad = 2^-32 * max(scale,
    |O|_inf) on every side (closed slabs, a parallel slab inside iff within the grown bounds).  A
    triangle hit of the watertight test lies within a few ulps of max(|vertex|, |O|) of the
    triangle, about 1e6 times less than pad, so the pre-test only skips rays that miss every
    triangle and never changes a result (selftest.py checks it against CULL = False)."""

    CULL = True

    def __init__(self, tris):
        self.tris = tris
        self.scale = max(tr.scale for tr in tris)
        pts = [p for tr in tris for p in (tr.a, tr.b, tr.c)]
        self.lo = tuple(min(p[k] for p in pts) for k in range(3))
        self.hi = tuple(max(p[k] for p in pts) for k in range(3))

    def box_maybe(self, O, D):
        pad = 2.0 ** -32 * max(self.scale, norm_inf(O))
        t_in, t_out = -INF, INF
        for k in range(3):
            lo, hi = self.lo[k] - pad, self.hi[k] + pad
            if D[k] == 0.0:
                if lo <= O[k] <= hi:
                    continue
                return False
            t1 = (lo - O[k]) / D[k]
            t2 = (hi - O[k]) / D[k]
            t_in = max(t_in, min(t1, t2))
            t_out = min(t_out, max(t1, t2))
        return t_in <= t_out and t_out >= 0.0

    def intersect(self, O, D):
        if Mesh.CULL and not self.box_maybe(O, D):
            return None
        best = None
        for k, tr in enumerate(self.tris):
            h = tr.intersect(O, D)
            if h is not None and (best is None or h[0] < best[0]):   # ties: the lower triangle index
                best = (h[0], k)
        return best

    def surface(self, O, D, t, extra):
        return self.tris[extra].surface(O, D, t, None)


# ---- Wavefront OBJ reading ----

OBJ_NUMBER = re.compile(r"[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?$")
# i, i/j, i//k or i/j/k
OBJ_FACE_VERTEX = re.compile(r"([+-]?[0-9]+)(?:/[+-]?[0-9]+|//[+-]?[0-9]+|/[+-]?[0-9]+/[+-]?[0-9]+)?$")


def read_obj(L, path, field):
    """The triangles of an OBJ file, or None after reporting to L (every message names field).

    Read: `v x y z` (more numbers, a w or vertex colours, are ignored) and `f` with 3 or more
    vertices written i, i/j, i//k or i/j/k (only i is used), 1-based; a negative i counts back from
    the last `v` read so far (-1 = the latest), as the OBJ format defines it; a positive i may name
    any `v` of the file.  A face of n > 3 vertices is the fan (v0, v1, v2), (v0, v2, v3), ...,
    (v0, v_{n-2}, v_{n-1}); triangle indices run over the whole file in that order.  Every other
    line kind (vt, vn, vp, o, g, s, usemtl, mtllib, l, p, ...) and `#` comments are ignored.
    Errors: unreadable file, a malformed number or index, a number that is not finite or above
    1e100 in magnitude (as for the scene's numbers), index 0 or out of range, a face of fewer than
    3 vertices, a zero-area triangle (section 11: "Degenerate triangles (zero area) are rejected
    when the scene loads"), a file with no face."""
    try:
        with open(path, encoding="utf-8") as fh:
            text = fh.read()
    except (OSError, UnicodeDecodeError) as e:
        L.err(field, "cannot read OBJ file %r: %s" % (path, e))
        return None
    name = os.path.basename(path)
    verts = []
    faces = []        # (line number, [0-based vertex indices], [as written])
    ok = True
    for lineno, line in enumerate(text.split("\n"), 1):
        line = line.split("#", 1)[0]
        tok = line.split()
        if not tok:
            continue
        where = "%s line %d" % (name, lineno)
        if tok[0] == "v":
            if len(tok) < 4:
                L.err(field, "%s: a vertex needs 3 numbers, got %d" % (where, len(tok) - 1))
                ok = False
                verts.append((0.0, 0.0, 0.0))     # keeps later indices where the file means them
                continue
            xyz = []
            for s in tok[1:4]:
                x = float(s) if OBJ_NUMBER.match(s) else None
                if x is None or not math.isfinite(x) or abs(x) > 1e100:
                    L.err(field, "%s: %r is not a finite number of magnitude at most 1e100" % (where, s))
                    ok = False
                    x = 0.0
                xyz.append(x)
            verts.append(tuple(xyz))
        elif tok[0] == "f":
            if len(tok) < 4:
                L.err(field, "%s: a face needs 3 or more vertices, got %d" % (where, len(tok) - 1))
                ok = False
                continue
            idx = []
            for s in tok[1:]:
                m = OBJ_FACE_VERTEX.match(s)
                i = int(m.group(1)) if m else None
                if i is None or i == 0:
                    L.err(field, "%s: bad face vertex %r (i, i/j, i//k or i/j/k, i != 0)" % (where, s))
                    ok = False
                    idx = None
                    break
                if i < 0:
                    j = len(verts) + i          # relative to the vertices read so far
                    if j < 0:
                        L.err(field, "%s: face vertex %d: only %d vertices before this line" % (where, i, len(verts)))
                        ok = False
                        idx = None
                        break
                    idx.append(j)
                else:
                    idx.append(i - 1)
            if idx is not None:
                faces.append((lineno, idx, tok[1:]))
        # every other line kind is ignored
    tris = []
    for lineno, idx, written in faces:
        where = "%s line %d" % (name, lineno)
        bad = [w for w, i in zip(written, idx) if i >= len(verts)]
        if bad:
            L.err(field, "%s: face vertex %s out of range (%d vertices)" % (where, bad[0], len(verts)))
            ok = False
            continue
        for q in range(1, len(idx) - 1):                  # the fan from v0
            a, b, c = verts[idx[0]], verts[idx[q]], verts[idx[q + 1]]
            nn = normalize_scaled(cross(sub(b, a), sub(c, a)))
            if nn is None:
                L.err(field, "%s: zero-area triangle (triangle %d, face vertices %s %s %s)"
                      % (where, len(tris), written[0], written[q], written[q + 1]))
                ok = False
                tris.append(None)
            else:
                tris.append(Triangle(a, b, c, nn))
    if ok and not tris:
        L.err(field, "%s: no face" % name)
        ok = False
    return tris if ok else None


# ---- 2D: segments and polygons (2D triangles are polygons of 3 vertices) ----

def edge_hit_2d(a, b, O, D):
    """t > 0 where the ray O + t*D (unit D) crosses the closed segment [a, b], or None.

    algorithm.md section 11 fixes the watertight Woop-Benthin-Wald test for (3D) triangles and
    names no method for 2D edges; this is the same test in one dimension less: translate to O,
    shear so that D becomes the kz axis, and the sheared transverse coordinates ea, eb of a and b
    are the edge functions (exactly re-evaluated where one is 0).  The ray crosses [a, b] iff
    they do not have the same strict sign, so two polygon edges sharing a vertex (whose value is
    computed once per vertex, identically) are never both missed.  Both 0: the ray runs along
    the segment, an edge-on hit, invisible (as edge-on triangles are)."""
    kz = 0 if abs(D[0]) >= abs(D[1]) else 1   # the larger |component| (ties: x), as in 3D
    kx = 1 - kz
    S = D[kx] / D[kz]
    A = sub(a, O)
    B = sub(b, O)
    ea = A[kx] - S * A[kz]
    eb = B[kx] - S * B[kz]
    if ea == 0.0 or eb == 0.0:
        F = Fraction
        ea = float(F(A[kx]) - F(S) * F(A[kz]))
        eb = float(F(B[kx]) - F(S) * F(B[kz]))
    if (ea < 0.0 and eb < 0.0) or (ea > 0.0 and eb > 0.0):
        return None
    det = ea - eb
    if det == 0.0:
        return None          # edge-on: invisible
    Sz = 1.0 / D[kz]
    ta = Sz * A[kz]          # t of a's and b's projections on the ray
    tb = Sz * B[kz]
    t = (ea * tb - eb * ta) / det    # = ta + (ea / (ea - eb)) * (tb - ta)
    if not (t > 0.0) or not math.isfinite(t):
        return None
    return t


def segment_normal(a, b):
    """algorithm.md section 3: "for a 2D segment from a to b, (d_y, -d_x)/|d| with d = b - a"."""
    return normalize_scaled(turn_cw(sub(b, a)))


class Segment:
    def __init__(self, a, b):
        self.a, self.b = a, b
        self.n = segment_normal(a, b)
        self.scale = max(norm_inf(a), norm_inf(b))

    def intersect(self, O, D):
        t = edge_hit_2d(self.a, self.b, O, D)
        return None if t is None else (t, None)

    def surface(self, O, D, t, extra):
        # section 11 lists no re-projection for segments: O + t*D, as for triangles
        return add(O, scale(D, t)), self.n


class Polygon:
    """A simple polygon (a 2D triangle too), either winding.  algorithm.md section 3: the
    normal is "the outward edge normal whatever the winding (by the sign of its area)"."""

    def __init__(self, vertices, area_sign):
        self.v = vertices
        n = len(vertices)
        self.edges = [(vertices[k], vertices[(k + 1) % n]) for k in range(n)]
        # (d_y, -d_x) is the right of a -> b: outward for a counter-clockwise polygon (area > 0)
        self.normals = [segment_normal(a, b) if area_sign > 0 else neg(segment_normal(a, b))
                        for a, b in self.edges]
        self.scale = max(norm_inf(p) for p in vertices)

    def intersect(self, O, D):
        best = None
        for k, (a, b) in enumerate(self.edges):
            t = edge_hit_2d(a, b, O, D)
            if t is not None and (best is None or t < best[0]):   # ties: the lower edge index
                best = (t, k)
        return best

    def surface(self, O, D, t, extra):
        return add(O, scale(D, t)), self.normals[extra]


def orient_exact(p, q, r):
    """Sign of (q - p) x (r - p), exactly (for validating polygons at load)."""
    F = Fraction
    v = ((F(q[0]) - F(p[0])) * (F(r[1]) - F(p[1]))
         - (F(q[1]) - F(p[1])) * (F(r[0]) - F(p[0])))
    return (v > 0) - (v < 0)


def on_segment_exact(p, q, r):
    """r on the closed segment [p, q], given that the three are collinear."""
    return (min(p[0], q[0]) <= r[0] <= max(p[0], q[0])
            and min(p[1], q[1]) <= r[1] <= max(p[1], q[1]))


def segments_meet_exact(p1, q1, p2, q2):
    o1, o2 = orient_exact(p1, q1, p2), orient_exact(p1, q1, q2)
    o3, o4 = orient_exact(p2, q2, p1), orient_exact(p2, q2, q1)
    if o1 != o2 and o3 != o4 and o1 * o2 <= 0 and o3 * o4 <= 0:
        return True
    return ((o1 == 0 and on_segment_exact(p1, q1, p2)) or (o2 == 0 and on_segment_exact(p1, q1, q2))
            or (o3 == 0 and on_segment_exact(p2, q2, p1)) or (o4 == 0 and on_segment_exact(p2, q2, q1)))


def polygon_problem(vs):
    """None for a simple polygon with non-zero area, else what is wrong; and the area's sign."""
    F = Fraction
    n = len(vs)
    twice_area = sum(F(vs[k][0]) * F(vs[(k + 1) % n][1]) - F(vs[(k + 1) % n][0]) * F(vs[k][1])
                     for k in range(n))
    sign = (twice_area > 0) - (twice_area < 0)
    for k in range(n):
        if vs[k] == vs[(k + 1) % n]:
            return "vertices %d and %d coincide (zero-length edge)" % (k, (k + 1) % n), sign
    for k in range(n):
        a, b, c = vs[k], vs[(k + 1) % n], vs[(k + 2) % n]
        # adjacent edges a-b, b-c may only share b: collinear and folding back is an overlap
        if orient_exact(a, b, c) == 0 and ((F(b[0]) - F(a[0])) * (F(c[0]) - F(b[0]))
                                           + (F(b[1]) - F(a[1])) * (F(c[1]) - F(b[1]))) < 0:
            return "edges %d and %d overlap (not simple)" % (k, (k + 1) % n), sign
    for i in range(n):
        for j in range(i + 2, n):
            if i == 0 and j == n - 1:
                continue       # adjacent through vertex 0
            if segments_meet_exact(vs[i], vs[(i + 1) % n], vs[j], vs[(j + 1) % n]):
                return "edges %d and %d cross or touch (not simple)" % (i, j), sign
    if sign == 0:
        return "zero area", sign
    return None, sign


class Obj:
    def __init__(self, shape, material, name):
        self.shape = shape
        self.mat = material
        self.name = name


class Light:
    def __init__(self, pos, intensity, att):
        self.pos = pos
        self.intensity = intensity
        self.att = att


class Camera:
    pass


class Scene:
    pass


def reject_constant(name):
    # Python's json accepts NaN / Infinity literals; JSON (and serde_json) does not.
    raise SceneError("JSON syntax error: %s is not a JSON literal" % name)


def scene_dimension(L, cj):
    """product.md: "3D vectors have 3 numbers, 2D vectors 2; the camera's vectors decide the
    dimension, and mixing is an error".  The camera's vectors are eye and center (2D has no up)."""
    lens = [len(cj[k]) for k in ("eye", "center") if isinstance(cj, dict) and isinstance(cj.get(k), list)]
    if lens and lens[0] == 2 and all(n == 2 for n in lens):
        return 2
    if len(lens) == 2 and set(lens) == {2, 3}:
        L.err("camera.center", "has %d numbers but camera.eye has %d (mixing 2D and 3D is an error)"
              % (lens[1], lens[0]))
    return 3


def camera_common(L, cj, cam, dim, fields, window_keys):
    """eye, center, projection, p and the window sides, for either dimension."""
    L.check_fields(cj, "camera", fields)
    for req in ("eye", "center", "window", "resolution"):
        if req not in cj:
            L.err("camera." + req, "required")
    eye = L.vec(cj.get("eye", [0, 0, 1][3 - dim:]), "camera.eye", dim)
    ctr = L.vec(cj.get("center", [0, 0, 0][3 - dim:]), "camera.center", dim)
    proj = cj.get("projection", "perspective")
    if proj not in ("perspective", "orthographic"):
        L.err("camera.projection", "must be perspective or orthographic, got %r" % (proj,))
    cam.ortho = (proj == "orthographic")
    p = L.number(cj.get("p", 1.0), "camera.p")
    if p is not None and not p > 0:
        L.err("camera.p", "must be > 0, got %r" % p)
    cam.p = p
    win = cj.get("window", {})
    if L.check_fields(win, "camera.window", ("l", "r", "b", "t")):   # 2D reports b, t itself
        for k in window_keys:
            if k not in win:
                L.err("camera.window." + k, "required")
        cam.l = L.number(win.get("l", -1), "camera.window.l")
        cam.r = L.number(win.get("r", 1), "camera.window.r")
        if None not in (cam.l, cam.r) and not cam.r > cam.l:
            L.err("camera.window", "r must be > l")
        if dim == 3:
            cam.b = L.number(win.get("b", -1), "camera.window.b")
            cam.t = L.number(win.get("t", 1), "camera.window.t")
            if None not in (cam.b, cam.t) and not cam.t > cam.b:
                L.err("camera.window", "t must be > b")
    return eye, ctr


def load_camera_3d(L, cj, cam, size_override):
    eye, ctr = camera_common(L, cj, cam, 3, ("eye", "center", "up", "projection", "p", "window",
                                             "resolution"), ("l", "r", "b", "t"))
    up = L.vec3(cj.get("up", [0, 1, 0]), "camera.up")
    res = cj.get("resolution", [1, 1])
    if not (isinstance(res, list) and len(res) == 2 and all(isinstance(x, int) and not isinstance(x, bool) for x in res)):
        L.err("camera.resolution", "must be [Nx, Ny] integers in a 3D scene")
        res = [1, 1]
    cam.nx, cam.ny = res
    if size_override is not None:
        if size_override[1] is None:
            L.err("--size", "a 3D scene needs WxH")
        else:
            cam.nx, cam.ny = size_override     # --size keeps the window
    if cam.nx < 1 or cam.ny < 1:
        L.err("camera.resolution", "must be >= 1")
    if eye is not None and ctr is not None and up is not None:
        w = normalize(sub(eye, ctr))
        if w is None:
            L.err("camera.eye", "equals camera.center")
        else:
            upn = normalize_scaled(up)
            if upn is None:
                L.err("camera.up", "zero vector")
            else:
                cu = cross(upn, w)
                if length(cu) < 1e-12:        # |up x w| < 1e-12 |up| with |upn| = 1
                    L.err("camera.up", "parallel to eye - center")
                else:
                    u = normalize(cu)
                    v = cross(w, u)
                    cam.eye, cam.U, cam.V, cam.W = eye, u, v, w


def load_camera_2d(L, cj, cam, size_override):
    """product.md: "resolution is [Nx]; the window has only l and r; eye, center ... have 2
    numbers; there is no up"."""
    if isinstance(cj, dict) and "up" in cj:
        L.err("camera.up", "a 2D scene has no up (the camera's eye and center have 2 numbers)")
    if isinstance(cj, dict) and isinstance(cj.get("window"), dict):
        for k in ("b", "t"):
            if k in cj["window"]:
                L.err("camera.window." + k, "a 2D window has only l and r")
    fields = ("eye", "center", "up", "projection", "p", "window", "resolution")  # up: reported above
    eye, ctr = camera_common(L, cj, cam, 2, fields, ("l", "r"))
    res = cj.get("resolution", [1])
    if not (isinstance(res, list) and len(res) == 1 and isinstance(res[0], int) and not isinstance(res[0], bool)):
        L.err("camera.resolution", "must be [Nx] (one integer) in a 2D scene, got %r" % (res,))
        res = [1]
    cam.nx = res[0]
    if size_override is not None:
        cam.nx = size_override[0]               # --size keeps the window
    if cam.nx < 1:
        L.err("camera.resolution", "must be >= 1")
    # product.md: "A 2D scene renders to a strip Nx wide and max(1, Nx/8) rows tall, every row the
    # same (--size W or WxH)".  Our reading: --size WxH gives the strip H rows, --size W (or none)
    # max(1, W/8).
    cam.ny = max(1, cam.nx // 8)
    if size_override is not None and size_override[1] is not None:
        cam.ny = size_override[1]
        if cam.ny < 1:
            L.err("--size", "H must be >= 1")
    if eye is not None and ctr is not None:
        w = normalize(sub(eye, ctr))
        if w is None:
            L.err("camera.eye", "equals camera.center")
        else:
            # algorithm.md section 2: "w = normalize(O - C) and u = (w_y, -w_x) (w turned by -90 deg)"
            cam.eye, cam.U, cam.V, cam.W = eye, turn_cw(w), None, w


def load_polygon(L, vs, f, count):
    """A 2D triangle (count 3) or polygon (count None: 3 or more), validated: no repeated
    vertex, non-zero area, simple.  Either winding (algorithm.md section 3)."""
    what = "3 points" if count == 3 else "a list of 3 or more points"
    if not isinstance(vs, list) or (len(vs) != count if count else len(vs) < 3):
        L.err(f + ".vertices", "must be %s" % what)
        return None
    pts = [L.vec(vv, "%s.vertices[%d]" % (f, q), 2) for q, vv in enumerate(vs)]
    if None in pts:
        return None
    problem, sign = polygon_problem(pts)
    if problem is not None:
        L.err(f + ".vertices", ("zero-area triangle" if count == 3 and sign == 0 else problem))
        return None
    return Polygon(pts, sign)


def load_scene(path, size_override=None, depth_override=None, lenient=False):
    with open(path) as fh:
        text = fh.read()
    try:
        data = json.loads(text, parse_constant=reject_constant)
    except json.JSONDecodeError as e:
        raise SceneError("JSON syntax error at line %d column %d: %s" % (e.lineno, e.colno, e.msg))
    L = Loader(lenient)
    L.check_fields(data, "scene", ("camera", "background", "ambient", "max_depth",
                                   "lights", "materials", "objects"))
    sc = Scene()

    # camera: it decides the dimension
    cam = Camera()
    cj = data.get("camera")
    if cj is None:
        raise SceneError("camera: required")
    dim = scene_dimension(L, cj)
    cam.dim = dim
    if dim == 3:
        load_camera_3d(L, cj, cam, size_override)
    else:
        load_camera_2d(L, cj, cam, size_override)
    sc.dim = dim
    sc.camera = cam

    # globals
    sc.background = L.colour(data.get("background", [0, 0, 0]), "background") or (0.0, 0.0, 0.0)
    sc.ambient = L.colour(data.get("ambient", [1, 1, 1]), "ambient") or (1.0, 1.0, 1.0)
    md = data.get("max_depth", 5)
    if not isinstance(md, int) or isinstance(md, bool) or md < 0 or md > 64:
        L.err("max_depth", "must be an integer in [0, 64], got %r" % (md,))
        md = 5
    sc.max_depth = md if depth_override is None else depth_override

    # lights
    sc.lights = []
    for k, lj in enumerate(data.get("lights", [])):
        f = "lights[%d]" % k
        if not L.check_fields(lj, f, ("position", "intensity", "attenuation", "name")):
            continue
        if "position" not in lj:
            L.err(f + ".position", "required")
            continue
        pos = L.vec(lj["position"], f + ".position", dim)
        inten = L.colour(lj.get("intensity", [1, 1, 1]), f + ".intensity")
        att = L.vec3(lj.get("attenuation", [1, 0, 0]), f + ".attenuation")
        if att is not None:
            if min(att) < 0 or max(att) == 0:
                L.err(f + ".attenuation", "coefficients must be >= 0 and not all 0")
        if pos is not None and inten is not None and att is not None:
            sc.lights.append(Light(pos, inten, att))

    # materials
    mats = {}
    mj = data.get("materials", {})
    if isinstance(mj, dict):
        for name, m in mj.items():
            mats[name] = load_material(L, m, "materials." + name)
    else:
        L.err("materials", "must be an object")

    # objects (product.md: "In 2D: sphere is a circle (center, radius), plane a line (point,
    # normal), box a rectangle (min, max); triangle (vertices: 3 points), segment (a, b) and
    # polygon (vertices: 3 or more points, simple, either winding) are available")
    sc.objects = []
    allowed = {
        "sphere": ("center", "radius"),
        "plane": ("point", "normal"),
        "box": ("min", "max"),
        "triangle": ("vertices",),
    }
    if dim == 3:
        allowed["mesh"] = ("obj",)
    if dim == 2:
        allowed["segment"] = ("a", "b")
        allowed["polygon"] = ("vertices",)
    for k, oj in enumerate(data.get("objects", [])):
        f = "objects[%d]" % k
        if not isinstance(oj, dict):
            L.err(f, "must be an object")
            continue
        typ = oj.get("type")
        if typ not in allowed:
            if typ in ("segment", "polygon"):
                L.err(f + ".type", "%s is a 2D object (this scene's camera is 3D)" % typ)
            elif typ == "mesh":
                L.err(f + ".type", "mesh is a 3D object (this scene's camera is 2D)")
            else:
                L.err(f + ".type", "unsupported in this reference: %r" % (typ,))
            continue
        L.check_fields(oj, f, ("type", "name", "material") + allowed[typ])
        for g in allowed[typ]:
            if g not in oj:
                L.err(f + "." + g, "required")
        if "material" in oj:
            mref = oj["material"]
            if isinstance(mref, str):
                if mref in mats:
                    mat = mats[mref]
                else:
                    L.err(f + ".material", "unknown material %r" % mref)
                    mat = Material()
            else:
                mat = load_material(L, mref, f + ".material")
        else:
            mat = Material()
        shape = None
        try:
            if typ == "sphere":
                c = L.vec(oj["center"], f + ".center", dim)
                r = L.number(oj["radius"], f + ".radius")
                if r is not None and not r > 0:
                    L.err(f + ".radius", "must be > 0, got %r" % r)
                elif c is not None and r is not None:
                    shape = Sphere(c, r)
            elif typ == "plane":
                pt = L.vec(oj["point"], f + ".point", dim)
                nv = L.vec(oj["normal"], f + ".normal", dim)
                if nv is not None:
                    nn = normalize_scaled(nv)
                    if nn is None:
                        L.err(f + ".normal", "zero vector")
                    elif pt is not None:
                        shape = Plane(pt, nn)
            elif typ == "box":
                lo = L.vec(oj["min"], f + ".min", dim)
                hi = L.vec(oj["max"], f + ".max", dim)
                if lo is not None and hi is not None:
                    if not all(lo[a] < hi[a] for a in range(dim)):
                        L.err(f, "box needs min < max on every axis")
                    else:
                        shape = Box(lo, hi)
            elif typ == "triangle" and dim == 2:
                shape = load_polygon(L, oj["vertices"], f, 3)
            elif typ == "polygon":
                shape = load_polygon(L, oj["vertices"], f, None)
            elif typ == "segment":
                a = L.vec(oj["a"], f + ".a", 2)
                b = L.vec(oj["b"], f + ".b", 2)
                if a is not None and b is not None:
                    if a == b:
                        L.err(f, "segment needs a != b")
                    else:
                        shape = Segment(a, b)
            elif typ == "triangle":
                vs = oj["vertices"]
                if not isinstance(vs, list) or len(vs) != 3:
                    L.err(f + ".vertices", "must be 3 points")
                else:
                    pts = [L.vec3(vv, "%s.vertices[%d]" % (f, q)) for q, vv in enumerate(vs)]
                    if None not in pts:
                        a, b, c = pts
                        nn = normalize_scaled(cross(sub(b, a), sub(c, a)))
                        if nn is None:
                            L.err(f + ".vertices", "zero-area triangle")
                        else:
                            shape = Triangle(a, b, c, nn)
            elif typ == "mesh":
                # product.md: "A mesh reads a Wavefront OBJ file, the path relative to the scene
                # file; its triangles share the mesh's material."
                of = oj["obj"]
                if not isinstance(of, str) or not of:
                    L.err(f + ".obj", "must be a file name (a string), got %r" % (of,))
                else:
                    tris = read_obj(L, os.path.join(os.path.dirname(os.path.abspath(path)), of), f + ".obj")
                    if tris is not None:
                        shape = Mesh(tris)
        except KeyError:
            pass   # missing field already reported
        if shape is not None:
            sc.objects.append(Obj(shape, mat, oj.get("name", k)))

    if L.errors:
        raise SceneError("\n".join(L.errors))
    return sc


# ----------------------------------------------------------------------------
# Tracing
# ----------------------------------------------------------------------------

class Stats:
    def __init__(self):
        self.rays = {"primary": 0, "reflected": 0, "transmitted": 0, "shadow": 0}
        self.tir = 0
        self.log = None      # a list to record every hit (level, object index, P, N, entering)


def offset_origin(P, Nf, delta, omega):
    """Spawned ray origin: I + delta*N_f if omega.N_f >= 0 else I - delta*N_f."""
    if dot(omega, Nf) >= 0.0:
        return add(P, scale(Nf, delta))
    return sub(P, scale(Nf, delta))


def nearest_hit(scene, O, D):
    best = None
    for idx, obj in enumerate(scene.objects):
        h = obj.shape.intersect(O, D)
        if h is not None and (best is None or h[0] < best[0]):   # ties: smaller index wins
            best = (h[0], h[1], idx)
    return best


def trace_ray(scene, O, D, level, stats):
    hit = nearest_hit(scene, O, D)
    if hit is None:
        return scene.background
    t, extra, idx = hit
    obj = scene.objects[idx]
    P, N = obj.shape.surface(O, D, t, extra)
    if stats.log is not None:
        stats.log.append((level, idx, P, N, dot(D, N) <= 0.0))
    return shade_point(scene, obj, O, D, t, P, N, level, stats)


def shade_point(scene, obj, O, D, t, P, N, level, stats):
    mat = obj.mat
    entering = dot(D, N) <= 0.0          # tangent counts as entering
    Nf = N if entering else neg(N)
    ka, kd = mat.colours_at(P)
    delta = 2.0 ** -44 * max(norm_inf(P), norm_inf(O), t, obj.shape.scale)
    V = neg(D)

    c = [scene.ambient[k] * ka[k] for k in range(3)]

    for light in scene.lights:
        Lvec = sub(light.pos, P)
        L = normalize(Lvec)
        if L is None:
            continue                      # light at the hit point: lum = 0
        n_dot_l = dot(Nf, L)
        if not n_dot_l > 0.0:
            continue                      # lum = 0: no shadow ray
        d = length(Lvec)                  # distance from I (for fat)
        # shadow segment from the offset origin to the light
        so = offset_origin(P, Nf, delta, L)
        seg = sub(light.pos, so)
        d_L = length(seg)
        sdir = normalize(seg)
        s = 1.0
        stats.rays["shadow"] += 1
        if sdir is not None:
            for occ in scene.objects:
                h = occ.shape.intersect(so, sdir)
                if h is not None and h[0] < d_L:
                    s *= occ.mat.kt       # once per distinct object
        c0, c1, c2 = light.att
        fat = min(1.0, 1.0 / (c0 + c1 * d + c2 * d * d))
        H = normalize(add(L, V))
        if H is None:
            nh_term = 0.0
        else:
            nh_term = max(0.0, dot(Nf, H)) ** mat.n     # 0**0 == 1 in Python
        for k in range(3):
            diffuse = light.intensity[k] * fat * s * kd[k] * n_dot_l
            specular = light.intensity[k] * fat * s * mat.ks * nh_term
            c[k] += diffuse + specular

    def child(kind, direction, weight):
        """Trace a secondary ray from the offset origin and add weight * its colour."""
        if direction is None:
            return
        stats.rays[kind] += 1
        colour = trace_ray(scene, offset_origin(P, Nf, delta, direction), direction, level + 1, stats)
        for k in range(3):
            c[k] += weight * colour[k]

    if level <= scene.max_depth:
        if mat.ks > 0.0:
            # R = 2(N.V)N - V with V = -D
            nv = dot(Nf, V)
            child("reflected", normalize(sub(scale(Nf, 2.0 * nv), V)), mat.ks)
        if mat.kt > 0.0:
            if entering:
                n1, n2 = 1.0, mat.ior
            else:
                n1, n2 = mat.ior, 1.0
            eta = n1 / n2
            ci = min(1.0, max(-1.0, -dot(D, Nf)))
            kk = (1.0 - eta * eta) + (eta * ci) * (eta * ci)
            if kk < 0.0:
                stats.tir += 1            # total internal reflection: kt*T dropped
            else:
                if eta == 1.0:
                    T = D
                else:
                    T = normalize(add(scale(D, eta), scale(Nf, eta * ci - math.sqrt(kk))))
                child("transmitted", T, mat.kt)
    return (c[0], c[1], c[2])


def primary_ray(cam, u, v):
    if cam.dim == 2:
        # algorithm.md section 2, "2D scenes": "The same in a plane: basis (u, w), a window [l, r]
        # on the image line, Nx pixels, no v".
        if cam.ortho:
            S = sub(add(cam.eye, scale(cam.U, u)), scale(cam.W, cam.p))   # S = O + u*u - p*w
            return S, neg(cam.W)
        D = sub(scale(cam.U, u), scale(cam.W, cam.p))                     # S - O = u*u - p*w
        return cam.eye, normalize(D)
    if cam.ortho:
        S = sub(add(add(cam.eye, scale(cam.U, u)), scale(cam.V, v)), scale(cam.W, cam.p))
        return S, neg(cam.W)
    # D = S - O = u*U + v*V - p*W, normalised
    D = sub(add(scale(cam.U, u), scale(cam.V, v)), scale(cam.W, cam.p))
    return cam.eye, normalize(D)


def trace_uv(scene, u, v, stats):
    O, D = primary_ray(scene.camera, u, v)
    stats.rays["primary"] += 1
    return trace_ray(scene, O, D, 1, stats)


def mean4(a, b, c, d):
    return tuple((a[k] + b[k] + c[k] + d[k]) / 4.0 for k in range(3))


def mean2(a, b):
    return tuple((a[k] + b[k]) / 2.0 for k in range(3))


def render_2d(scene, aa, threshold, max_level, stats):
    """A 2D scene: one image line of Nx pixels, repeated on every row of the strip (product.md:
    "A 2D scene renders to a strip Nx wide and max(1, Nx/8) rows tall, every row the same").
    algorithm.md section 8: "In 2D the same holds along the one axis: a pixel's "square" is its
    interval, with 2 ends" -- corners traces Nx + 1 ends, adaptive splits an interval in 2 halves
    (threshold 0, level K: Nx*2^K + 1 samples)."""
    cam = scene.camera
    nx, ny = cam.nx, cam.ny
    l, r = cam.l, cam.r

    if aa == "center":
        line = []
        for i in range(nx):
            u = l + (r - l) * (i + 0.5) / nx
            line.append(trace_uv(scene, u, None, stats))
        return line * ny, nx

    K = 0 if aa == "corners" else max_level
    S = 2 ** K
    NX = nx * S                     # lattice size (in lattice steps)
    cache = {}

    def sample(I):
        col = cache.get(I)
        if col is None:
            u = l + (r - l) * I / NX
            col = trace_uv(scene, u, None, stats)
            cache[I] = col
        return col

    def interval(I0, s, level):
        ends = (sample(I0), sample(I0 + s))
        spread = max(max(cc[k] for cc in ends) - min(cc[k] for cc in ends) for k in range(3))
        if level < K and spread >= threshold:
            h = s // 2
            return mean2(interval(I0, h, level + 1), interval(I0 + h, h, level + 1))
        return mean2(*ends)

    line = [interval(i * S, S, 0) for i in range(nx)]
    return line * ny, len(cache)


def render(scene, aa, threshold, max_level, stats):
    cam = scene.camera
    if cam.dim == 2:
        return render_2d(scene, aa, threshold, max_level, stats)
    nx, ny = cam.nx, cam.ny
    l, r, b, t = cam.l, cam.r, cam.b, cam.t
    pixels = [None] * (nx * ny)

    if aa == "center":
        for j in range(ny):
            v = b + (t - b) * (j + 0.5) / ny
            for i in range(nx):
                u = l + (r - l) * (i + 0.5) / nx
                pixels[j * nx + i] = trace_uv(scene, u, v, stats)
        return pixels, nx * ny

    K = 0 if aa == "corners" else max_level
    S = 2 ** K
    NX, NY = nx * S, ny * S         # lattice size (in lattice steps)
    cache = {}

    def sample(I, J):
        key = (I, J)
        col = cache.get(key)
        if col is None:
            u = l + (r - l) * I / NX
            v = b + (t - b) * J / NY
            col = trace_uv(scene, u, v, stats)
            cache[key] = col
        return col

    def square(I0, J0, s, level):
        cs = (sample(I0, J0), sample(I0 + s, J0), sample(I0, J0 + s), sample(I0 + s, J0 + s))
        spread = max(max(cc[k] for cc in cs) - min(cc[k] for cc in cs) for k in range(3))
        if level < K and spread >= threshold:
            h = s // 2
            return mean4(square(I0, J0, h, level + 1),
                         square(I0 + h, J0, h, level + 1),
                         square(I0, J0 + h, h, level + 1),
                         square(I0 + h, J0 + h, h, level + 1))
        return mean4(*cs)

    for j in range(ny):
        for i in range(nx):
            pixels[j * nx + i] = square(i * S, j * S, S, 0)
    return pixels, len(cache)


def to_byte(c):
    """round(255*clamp(c, 0, 1)), round half away from zero."""
    x = 255.0 * min(1.0, max(0.0, c))
    fl = math.floor(x)
    return int(fl + 1) if x - fl >= 0.5 else int(fl)


def parse_size(s):
    """WxH -> (W, H); W (2D scenes only) -> (W, None)."""
    try:
        parts = s.lower().split("x")
        if len(parts) == 1:
            return int(parts[0]), None
        w, h = parts
        w, h = int(w), int(h)
    except ValueError:
        raise SystemExit("--size must be WxH (or W for a 2D scene)")
    return w, h


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene")
    ap.add_argument("--size")
    ap.add_argument("--aa", choices=("center", "corners", "adaptive"), default="center")
    ap.add_argument("--threshold", type=float, default=0.1)
    ap.add_argument("--max-level", type=int, default=2)
    ap.add_argument("--depth", type=int, default=None, help="override max_depth")
    ap.add_argument("-o", "--out", required=True)
    ap.add_argument("--lenient", action="store_true",
                    help="unknown scene fields are warnings instead of errors")
    args = ap.parse_args(argv)

    if math.isnan(args.threshold) or args.threshold < 0:
        raise SystemExit("--threshold must be >= 0 and not NaN")
    if not 0 <= args.max_level <= 8:
        raise SystemExit("--max-level must be in [0, 8]")
    if args.depth is not None and not 0 <= args.depth <= 64:
        raise SystemExit("--depth must be in [0, 64]")

    t0 = time.time()
    try:
        scene = load_scene(args.scene, parse_size(args.size) if args.size else None,
                           args.depth, args.lenient)
    except SceneError as e:
        sys.stderr.write("scene error:\n%s\n" % e)
        return 2
    sys.setrecursionlimit(10000)
    stats = Stats()
    pixels, nprimary = render(scene, args.aa, args.threshold, args.max_level, stats)
    assert nprimary == stats.rays["primary"], (nprimary, stats.rays)
    for px in pixels:
        for x in px:
            if not math.isfinite(x):
                raise SystemExit("BUG: non-finite pixel value %r" % (px,))
    out = {
        "width": scene.camera.nx,
        "height": scene.camera.ny,
        "primary_rays": nprimary,
        "pixels": [list(px) for px in pixels],
        "bytes": [[to_byte(x) for x in px] for px in pixels],
    }
    with open(args.out, "w") as fh:
        json.dump(out, fh, allow_nan=False)
    sys.stderr.write("%s: %dx%d aa=%s primary=%d rays=%s tir=%d %.2fs\n" % (
        args.scene, scene.camera.nx, scene.camera.ny, args.aa, nprimary,
        stats.rays, stats.tir, time.time() - t0))
    return 0


if __name__ == "__main__":
    sys.exit(main())
