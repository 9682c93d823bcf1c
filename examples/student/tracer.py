#!/usr/bin/env python3
"""A student's Whitted ray tracer, small and readable: a starting point for the course.

It reads a scene in the course's format (whitted's docs/product.md, "Scene files": spheres,
planes, boxes and triangles in 3D; circles, lines, rectangles, segments, triangles and polygons
in 2D; point lights; materials with a checker) and traces ONE pixel, writing the student trace
document of whitted's docs/grading.md, which `whitted grade SCENE DOC.json` checks step by step:

    python3 tracer.py SCENE.json --pixel I,J > me.json
    whitted grade SCENE.json me.json

`--mistake NAME` switches on one classic mistake, to see what `whitted grade` says about it
(`--list-mistakes` lists them). Standard library only. Vectors are plain tuples, so the code
reads like the lecture's formulas and works in 2D and 3D alike.
"""

import argparse
import json
import math
import sys

MISTAKES = {
    "unnormalized-direction": "the primary ray's direction is S - O, not normalised",
    "unnormalized-normal": "a sphere's normal is I - C, not divided by r",
    "normal-not-flipped": "inside an object N is not turned toward the incoming ray",
    "inverted-eta": "eta = n2/n1 instead of n1/n2",
    "no-tir": "total internal reflection ignored: k < 0 is taken as 0 and T is spawned",
    "reflect-sign": "R = 2(N.D)N - D: D used in place of V = -D",
    "no-shadow-offset": "the shadow ray leaves from I itself, without an offset",
    "occluders-beyond-light": "objects beyond the light counted as occluders",
    "no-half-pixel": "u = l + (r - l) i / Nx: the pixel's corner, not its centre",
    "rows-from-top": "row j counted from the top of the image",
    "phong-rv": "highlight (R.V)^n instead of (N.H)^n",
    "no-attenuation": "fat left out",
    "unclamped-attenuation": "fat = 1/(c0 + c1 d + c2 d^2), not clamped to 1",
    "depth-off-by-one": "children only while level < max_depth",
    "transmit-kt0": "a T ray spawned even where kt = 0",
    "local-twice": "the local term added twice to the colour",
    "clamp-before-sum": "each term clamped to [0, 1] before the sum",
}

OFFSET = 1e-9  # how far a secondary or shadow ray starts off the surface, times max(1, |I|)


# ---------------------------------------------------------------- vectors (tuples, any dimension)

def add(a, b):
    return tuple(x + y for x, y in zip(a, b))


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def mul(a, k):
    return tuple(x * k for x in a)


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def length(a):
    return math.sqrt(dot(a, a))


def normalize(a):
    n = length(a)
    return mul(a, 1.0 / n) if n > 0 else None


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def rgb(x):
    return tuple(x) if isinstance(x, list) else (x, x, x)


def clamp01(c):
    return tuple(min(1.0, max(0.0, x)) for x in c)


# ---------------------------------------------------------------- the scene

class Material:
    def __init__(self, m):
        self.ka = rgb(m.get("ka", 0.1))
        self.kd = rgb(m.get("kd", 0.7))
        self.ks = m.get("ks", 0.0)
        self.n = m.get("n", 32.0)
        self.kt = m.get("kt", 0.0)
        self.ior = m.get("ior", 1.0)
        self.checker = m.get("checker")

    def colours_at(self, p):
        """(ka, kd) at p: a checker's second colours where sum(floor(x_i/size)) is odd."""
        c = self.checker
        if c is None:
            return self.ka, self.kd
        size = c.get("size", 1.0)
        cells = sum(math.floor(x / size + 1e-10) for x in p)
        if cells % 2 == 1:
            return rgb(c.get("ka2", list(self.ka))), rgb(c["kd2"])
        return self.ka, self.kd


class Scene:
    def __init__(self, data, mistake):
        self.mistake = mistake
        cam = data["camera"]
        self.eye = tuple(cam["eye"])
        self.dim = len(self.eye)
        center = tuple(cam["center"])
        self.w = normalize(sub(self.eye, center))
        if self.dim == 3:
            up = tuple(cam.get("up", [0, 1, 0]))
            self.u = normalize(cross(up, self.w))
            self.v = cross(self.w, self.u)
        else:
            self.u = (self.w[1], -self.w[0])
            self.v = (0.0, 0.0)
        self.perspective = cam.get("projection", "perspective") == "perspective"
        self.p = cam.get("p", 1.0)
        self.window = cam["window"]
        self.resolution = cam["resolution"]
        self.background = tuple(data.get("background", [0, 0, 0]))
        self.ambient = tuple(data.get("ambient", [1, 1, 1]))
        self.max_depth = data.get("max_depth", 5)
        self.lights = [
            {
                "position": tuple(l["position"]),
                "intensity": tuple(l.get("intensity", [1, 1, 1])),
                "attenuation": l.get("attenuation", [1, 0, 0]),
            }
            for l in data.get("lights", [])
        ]
        named = {k: Material(m) for k, m in data.get("materials", {}).items()}
        self.objects = []
        for index, o in enumerate(data.get("objects", [])):
            m = o.get("material", {})
            material = named[m] if isinstance(m, str) else Material(m)
            name = o.get("name", index)
            if isinstance(name, dict):
                name = name["en"]
            self.objects.append(make_object(o, material, name, self.dim))


# ---------------------------------------------------------------- objects: hit(origin, dir) -> [(t, normal)]

class Sphere:
    def __init__(self, o):
        self.c = tuple(o["center"])
        self.r = o["radius"]

    def roots(self, org, d, mistake):
        f = sub(org, self.c)
        b = dot(f, d)
        c = dot(f, f) - self.r * self.r
        disc = b * b - c
        if disc < 0:
            return []
        s = math.sqrt(disc)
        return [-b - s, -b + s]

    def normal(self, p, mistake):
        n = sub(p, self.c)
        return n if mistake == "unnormalized-normal" else mul(n, 1.0 / self.r)

    def snap(self, p):
        return add(self.c, mul(normalize(sub(p, self.c)), self.r))


class Plane:
    def __init__(self, o):
        self.p = tuple(o["point"])
        self.n = normalize(tuple(o["normal"]))

    def roots(self, org, d, mistake):
        dn = dot(d, self.n)
        if dn == 0:
            return []
        return [dot(sub(self.p, org), self.n) / dn]

    def normal(self, p, mistake):
        return self.n

    def snap(self, p):
        return sub(p, mul(self.n, dot(sub(p, self.p), self.n)))


class Box:
    """An axis-aligned box (a rectangle in 2D): the slab test; N is the axis of the face crossed."""

    def __init__(self, o):
        self.lo = tuple(o["min"])
        self.hi = tuple(o["max"])

    def roots(self, org, d, mistake):
        t_in, t_out = -math.inf, math.inf
        for a in range(len(org)):
            if d[a] == 0:
                if not (self.lo[a] <= org[a] <= self.hi[a]):
                    return []
                continue
            t1 = (self.lo[a] - org[a]) / d[a]
            t2 = (self.hi[a] - org[a]) / d[a]
            t_in = max(t_in, min(t1, t2))
            t_out = min(t_out, max(t1, t2))
        if t_in > t_out:
            return []
        return [t_in, t_out]

    def normal(self, p, mistake):
        # The face the point lies on: the axis where it is closest to a side.
        best = None
        for a in range(len(p)):
            for side, sign in ((self.lo[a], -1.0), (self.hi[a], 1.0)):
                gap = abs(p[a] - side)
                if best is None or gap < best[0]:
                    best = (gap, a, sign)
        _, a, sign = best
        return tuple(sign if k == a else 0.0 for k in range(len(p)))

    def snap(self, p):
        return p


class Segment:
    """A 2D segment a -> b; its normal is (d_y, -d_x)/|d| with d = b - a (the lecture's rule)."""

    def __init__(self, a, b, outward=None):
        self.a, self.b = tuple(a), tuple(b)
        d = sub(self.b, self.a)
        self.n = outward or normalize((d[1], -d[0]))

    def roots(self, org, d, mistake):
        e = sub(self.b, self.a)
        den = d[0] * e[1] - d[1] * e[0]
        if den == 0:
            return []
        w = sub(self.a, org)
        t = (w[0] * e[1] - w[1] * e[0]) / den
        s = (w[0] * d[1] - w[1] * d[0]) / den
        return [t] if 0.0 <= s <= 1.0 else []

    def normal(self, p, mistake):
        return self.n

    def snap(self, p):
        return p


class Polygon:
    """A 2D polygon (a triangle too): its edges, each with its outward normal."""

    def __init__(self, vertices):
        vs = [tuple(v) for v in vertices]
        area = sum(vs[i][0] * vs[(i + 1) % len(vs)][1] - vs[(i + 1) % len(vs)][0] * vs[i][1] for i in range(len(vs)))
        self.edges = []
        for i in range(len(vs)):
            a, b = vs[i], vs[(i + 1) % len(vs)]
            d = sub(b, a)
            n = normalize((d[1], -d[0]) if area > 0 else (-d[1], d[0]))
            self.edges.append(Segment(a, b, n))
        self.last = None

    def hits(self, org, d):
        return [(t, e) for e in self.edges for t in e.roots(org, d, None)]

    def roots(self, org, d, mistake):
        return [t for t, _ in self.hits(org, d)]

    def normal_at(self, org, d, t):
        return min(self.hits(org, d), key=lambda h: abs(h[0] - t))[1].n


class Triangle3:
    def __init__(self, o):
        self.a, self.b, self.c = (tuple(v) for v in o["vertices"])
        self.n = normalize(cross(sub(self.b, self.a), sub(self.c, self.a)))

    def roots(self, org, d, mistake):
        e1, e2 = sub(self.b, self.a), sub(self.c, self.a)
        pv = cross(d, e2)
        det = dot(e1, pv)
        if det == 0:
            return []
        tv = sub(org, self.a)
        u = dot(tv, pv) / det
        qv = cross(tv, e1)
        v = dot(d, qv) / det
        if u < 0 or v < 0 or u + v > 1:
            return []
        return [dot(e2, qv) / det]

    def normal(self, p, mistake):
        return self.n

    def snap(self, p):
        return p


class Object:
    def __init__(self, shape, material, name):
        self.shape, self.material, self.name = shape, material, name


def make_object(o, material, name, dim):
    kind = o["type"]
    if kind == "sphere":
        shape = Sphere(o)
    elif kind == "plane":
        shape = Plane(o)
    elif kind == "box":
        shape = Box(o)
    elif kind == "segment":
        shape = Segment(o["a"], o["b"])
    elif kind in ("triangle", "polygon") and dim == 2:
        shape = Polygon(o["vertices"])
    elif kind == "triangle":
        shape = Triangle3(o)
    else:
        raise SystemExit(f"this tracer does not know the object type {kind!r}")
    return Object(shape, material, name)


# ---------------------------------------------------------------- the tracer

def nearest(scene, org, d):
    """The nearest hit with t > 0: (t, object index), or None."""
    best = None
    for k, obj in enumerate(scene.objects):
        for t in obj.shape.roots(org, d, scene.mistake):
            if t > 0 and (best is None or t < best[0]):
                best = (t, k)
    return best


def normal_at(obj, org, d, t, p, mistake):
    if isinstance(obj.shape, Polygon):
        return obj.shape.normal_at(org, d, t)
    return obj.shape.normal(p, mistake)


def shadow_factor(scene, point, n_f, light_pos, own):
    """s = product of kt over the distinct objects between I and the light (0 < t < d_L)."""
    m = scene.mistake
    start = point if m == "no-shadow-offset" else add(point, mul(n_f, OFFSET * max(1.0, max(map(abs, point)))))
    to_light = sub(light_pos, start)
    d_l = length(to_light)
    d = mul(to_light, 1.0 / d_l)
    s = 1.0
    for obj in scene.objects:
        ts = [t for t in obj.shape.roots(start, d, m) if t > 0 and (t < d_l or m == "occluders-beyond-light")]
        if ts:
            s *= obj.material.kt
            if s == 0:
                break
    return s


def fat(light, dist, mistake):
    if mistake == "no-attenuation":
        return 1.0
    c0, c1, c2 = light["attenuation"]
    f = 1.0 / (c0 + c1 * dist + c2 * dist * dist)
    return f if mistake == "unclamped-attenuation" else min(1.0, f)


def refract(d, n_f, eta):
    """T = eta D + (eta c - sqrt(k)) N_f, c = -D.N_f, k = 1 - eta^2 (1 - c^2); None when k < 0."""
    c = max(-1.0, min(1.0, -dot(d, n_f)))
    k = (1 - eta * eta) + (eta * c) ** 2
    return k, add(mul(d, eta), mul(n_f, eta * c - math.sqrt(max(k, 0.0))))


def trace(scene, org, d, level):
    """TraceRay: returns (colour, node), the node being this ray's part of the document."""
    m = scene.mistake
    node = {"origin": list(org), "direction": list(d)}
    found = nearest(scene, org, d)
    if found is None:
        node["hit"] = None
        node["colour"] = list(scene.background)
        return scene.background, node
    t, k = found
    obj = scene.objects[k]
    mat = obj.material
    point = obj.shape.snap(add(org, mul(d, t))) if hasattr(obj.shape, "snap") else add(org, mul(d, t))
    n = normal_at(obj, org, d, t, point, m)
    node["hit"] = {"object": obj.name, "t": t, "point": list(point), "normal": list(n)}
    entering = dot(d, n) <= 0
    n_unit = normalize(n)
    n_f = n_unit if entering or m == "normal-not-flipped" else mul(n_unit, -1.0)
    view = mul(d, -1.0)
    # The local model: ambient, then each light.
    ka, kd = mat.colours_at(point)
    local = tuple(a * k_ for a, k_ in zip(scene.ambient, ka))
    lights = []
    for light in scene.lights:
        to_light = sub(light["position"], point)
        dist = length(to_light)
        l = mul(to_light, 1.0 / dist)
        n_dot_l = dot(n_f, l)
        entry = {"n_dot_l": n_dot_l}
        if n_dot_l > 0:
            s = shadow_factor(scene, point, n_f, light["position"], k)
            entry["shadow"] = s
            w = fat(light, dist, m) * s
            spec = 0.0
            if mat.ks > 0:
                if m == "phong-rv":
                    r = sub(mul(n_f, 2 * n_dot_l), l)
                    spec = max(0.0, dot(r, view)) ** mat.n
                else:
                    h = normalize(add(l, view))
                    spec = max(0.0, dot(n_f, h)) ** mat.n if h else 0.0
            local = tuple(
                c + i * w * (kd_ * n_dot_l + mat.ks * spec) for c, i, kd_ in zip(local, light["intensity"], kd)
            )
        lights.append(entry)
    node["lights"] = lights
    node["local"] = list(local)
    # The recursion: R, then T, while level <= max_depth.
    limit = level < scene.max_depth if m == "depth-off-by-one" else level <= scene.max_depth
    terms = []
    if limit:
        delta = OFFSET * max(1.0, max(map(abs, point)))
        if mat.ks > 0:
            if m == "reflect-sign":
                r = sub(mul(n_f, 2 * dot(n_f, d)), d)
            else:
                r = sub(d, mul(n_f, 2 * dot(d, n_f)))
            colour_r, node["reflected"] = trace(scene, add(point, mul(n_f, delta)), r, level + 1)
            terms.append((mat.ks, colour_r))
        if mat.kt > 0 or m == "transmit-kt0":
            n1, n2 = (1.0, mat.ior) if entering else (mat.ior, 1.0)
            eta = n2 / n1 if m == "inverted-eta" else n1 / n2
            k_, t_dir = refract(d, n_f, eta)
            if k_ >= 0 or m == "no-tir":
                t_dir = normalize(t_dir)
                colour_t, node["transmitted"] = trace(scene, sub(point, mul(n_f, delta)), t_dir, level + 1)
                terms.append((mat.kt, colour_t))
    if m == "clamp-before-sum":
        colour = clamp01(local)
        for weight, c in terms:
            colour = add(colour, mul(clamp01(c), weight))
    else:
        colour = local
        for weight, c in terms:
            colour = add(colour, mul(c, weight))
        if m == "local-twice":
            colour = add(colour, local)
    node["colour"] = list(colour)
    return colour, node


def trace_pixel(scene, pixel):
    """The pixel's centre on the window, the primary ray P, and its tree."""
    m = scene.mistake
    win, res = scene.window, scene.resolution
    i = pixel[0]
    half = 0.0 if m == "no-half-pixel" else 0.5
    u = win["l"] + (win["r"] - win["l"]) * (i + half) / res[0]
    if scene.dim == 3:
        j = pixel[1]
        row = res[1] - 1 - j if m == "rows-from-top" else j
        v = win["b"] + (win["t"] - win["b"]) * (row + half) / res[1]
        window_point = [u, v]
    else:
        v = 0.0
        window_point = [u]
    s = add(add(scene.eye, mul(scene.u, u)), add(mul(scene.v, v), mul(scene.w, -scene.p)))
    if scene.perspective:
        org = scene.eye
        d = sub(s, org) if m == "unnormalized-direction" else normalize(sub(s, org))
    else:
        org, d = s, mul(scene.w, -1.0)
    colour, node = trace(scene, org, d, 1)
    return {"pixel": list(pixel), "window_point": window_point, "ray": node, "colour": list(colour)}


def main():
    ap = argparse.ArgumentParser(description="A student's Whitted ray tracer: one pixel's trace document.")
    ap.add_argument("scene", nargs="?")
    ap.add_argument("--pixel", help="I,J (I in 2D): column from the left, row from the bottom")
    ap.add_argument("--mistake", choices=sorted(MISTAKES), help="switch one classic mistake on")
    ap.add_argument("--list-mistakes", action="store_true")
    a = ap.parse_args()
    if a.list_mistakes:
        for name, what in MISTAKES.items():
            print(f"{name:24} {what}")
        return
    if not a.scene or not a.pixel:
        ap.error("give SCENE and --pixel")
    with open(a.scene, encoding="utf-8") as f:
        scene = Scene(json.load(f), a.mistake)
    pixel = [int(x) for x in a.pixel.split(",")]
    if scene.dim == 2:
        pixel = pixel[:1]
    json.dump(trace_pixel(scene, pixel), sys.stdout, indent=1)
    print()


if __name__ == "__main__":
    main()
