# Checks of ref.py against the worked values of shared/docs/numerics.md
import sys, json, math, os, tempfile
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import reference as ref
from reference import Sphere, Plane, Box, Triangle, normalize, normalize_scaled, cross, sub

fails = 0
def check(name, cond, info=""):
    global fails
    print(("ok   " if cond else "FAIL ") + name + ("  " + str(info) if info else ""))
    if not cond: fails += 1

def run_scene(scene, *args):
    d = tempfile.mkdtemp()
    p = os.path.join(d, "s.json"); o = os.path.join(d, "o.json")
    json.dump(scene, open(p, "w"))
    rc = ref.main([p, "-o", o] + list(args))
    assert rc in (0, None), rc
    return json.load(open(o))

# L2 mirror corridor
for k, want in ((0, 0.1), (1, 0.15), (2, 0.175), (10, 0.19990234375)):
    sc = {"camera": {"eye": [0, 0, 0], "center": [1, 0, 0], "window": {"l": -0.1, "r": 0.1, "b": -0.1, "t": 0.1}, "resolution": [1, 1]},
          "max_depth": k, "lights": [],
          "objects": [{"type": "plane", "point": [-1, 0, 0], "normal": [1, 0, 0], "material": {"ka": 0.1, "kd": 0, "ks": 0.5}},
                      {"type": "plane", "point": [1, 0, 0], "normal": [-1, 0, 0], "material": {"ka": 0.1, "kd": 0, "ks": 0.5}}]}
    out = run_scene(sc)
    c = out["pixels"][0][0]
    check("L2 corridor k=%d" % k, abs(c - want) <= 1e-15, c)

# B1 tangent, B4 roots, B2 far
s = Sphere((0.0, 0.0, 0.0), 1.0)
h = s.intersect((-2.0, 1.0, 0.0), (1.0, 0.0, 0.0)); check("B1a tangent t=2", h and h[0] == 2.0, h)
check("B1b start at tangent point: miss", s.intersect((0.0, 1.0, 0.0), (1.0, 0.0, 0.0)) is None)
h = s.intersect((0.0, 0.0, 0.0), (0.0, 0.0, 1.0)); check("B4a inside t=1", h and h[0] == 1.0, h)
check("B4b behind: miss", s.intersect((0.0, 0.0, 5.0), (0.0, 0.0, 1.0)) is None)
far = Sphere((0.0, 0.0, -1e8), 1.0)
h = far.intersect((0.5, 0.0, 0.0), (0.0, 0.0, -1.0)); check("B2 far t", h and abs(h[0] - 99999999.1339746) < 1e-6, h)
check("B2 far miss 1.001", far.intersect((1.001, 0.0, 0.0), (0.0, 0.0, -1.0)) is None)
tiny = Sphere((0.0, 0.0, -1.0), 1e-8)
h = tiny.intersect((0.5e-8, 0.0, 0.0), (0.0, 0.0, -1.0)); check("B3 tiny", h and abs(h[0] - 0.99999999133974596) <= 1e-15, h)

# A boxes
b = Box((1.0, 0.0, 0.0), (2.0, 1.0, 1.0))
h = b.intersect((0.0, 0.0, 0.0), (1.0, 0.0, 0.0)); check("A1 along edge hit t=1", h and h[0] == 1.0, h)
check("A1 parallel outside miss", b.intersect((0.0, 1.5, 0.5), (1.0, 0.0, 0.0)) is None)
check("A2 face plane, box behind: miss", b.intersect((5.0, 1.0, 0.5), (1.0, 0.0, 0.0)) is None)
h = b.intersect((0.0, 0.5, 0.5), (1.0, -0.0, 0.0)); check("A3 -0.0", h and h[0] == 1.0, h)
h = b.intersect((1.5, 0.5, 0.5), (1.0, 0.0, 0.0)); P, N = b.surface((1.5, 0.5, 0.5), (1.0, 0.0, 0.0), h[0], h[1])
check("A6 inside: t=0.5 N=+x", h[0] == 0.5 and N == (1.0, 0.0, 0.0), (h, P, N))
b2 = Box((0.0, 0.0, 0.0), (1.0, 1.0, 1.0)); D = normalize((1.0, 1.0, 0.0)); O = (-1.0, -1.0, 0.5)
h = b2.intersect(O, D); P, N = b2.surface(O, D, h[0], h[1]); check("A7 edge tie N=-x", N == (-1.0, 0.0, 0.0), (h, P, N))
b3 = Box((1.0, 0.0, -1.0), (2.0, 1.0, 1.0)); h = b3.intersect((0.0, 0.0, 0.0), normalize((1.0, 1.0, 0.0)))
check("A4 corner touch", h is not None and abs(h[0] - math.sqrt(2)) < 1e-15, h)

# C planes
pl = Plane((0.0, 0.0, 0.0), (0.0, 1.0, 0.0))
check("C1 parallel off", pl.intersect((0.0, 1.0, 0.0), (1.0, 0.0, 0.0)) is None)
check("C1 in plane", pl.intersect((0.0, 0.0, 0.0), (1.0, 0.0, 0.0)) is None)
check("C2 -0.0", pl.intersect((0.0, 1.0, 0.0), (-1.0, -0.0, -0.0)) is None)

# D triangles
a = (0.1, 0.2, 0.3); bb = (0.7, 0.9, 0.4); c1 = (0.7, 0.2, 0.5); c2 = (0.1, 0.9, 0.2)
T1 = Triangle(a, c1, bb, normalize_scaled(cross(sub(c1, a), sub(bb, a))))
T2 = Triangle(a, bb, c2, normalize_scaled(cross(sub(bb, a), sub(c2, a))))
O = (0.3, -0.4, 2.0); D = (-0.10292378028109408, 0.3389280194817812, -0.9351654896662976)
h1 = T1.intersect(O, D); h2 = T2.intersect(O, D)
check("D1 shared edge: T1 hit t", h1 is not None and abs(h1[0] - 1.8155182358213868) <= 1e-15, (h1, h2))
# many rays along the edge: never both missed
miss = 0
for q in range(1, 10000):
    s_ = q / 10000.0
    tgt = tuple(a[k] + s_ * (bb[k] - a[k]) for k in range(3))
    Dq = normalize(sub(tgt, O))
    if T1.intersect(O, Dq) is None and T2.intersect(O, Dq) is None: miss += 1
check("D2 watertight 9999 rays along shared edge", miss == 0, miss)
T3 = Triangle((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.5, 1e-12, 0.0), (0.0, 0.0, 1.0))
h = T3.intersect((0.5, 5e-13, 1.0), (0.0, 0.0, -1.0)); check("D3 needle t=1", h and h[0] == 1.0, h)
T4 = Triangle((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
check("D4 edge-on miss", T4.intersect((-1.0, 0.2, 0.0), (1.0, 0.0, 0.0)) is None)

# E2 / F1 refraction: reproduce shade_point's formula
def refract(D, Nf, eta):
    ci = min(1.0, max(-1.0, -ref.dot(D, Nf)))
    k = (1.0 - eta * eta) + (eta * ci) * (eta * ci)
    if k < 0: return None, k
    return tuple(eta * D[q] + (eta * ci - math.sqrt(k)) * Nf[q] for q in range(3)), k
T, k = refract((math.sqrt(0.5), -math.sqrt(0.5), 0.0), (0.0, 1.0, 0.0), 1 / 1.5)
check("E2 45deg T", abs(T[0] - 0.4714045207910317) < 1e-15 and abs(T[1] + 0.881917103688197) < 1e-15, (T, k))
T, k = refract((0.6666666666666666, -0.7453559924999299, 0.0), (0.0, 1.0, 0.0), 1.5)
# numerics.md F1 quotes k = 0.0 exactly, from the lecture form 1 - eta^2 (1 - c^2); algorithm.md
# section 11 (which wins) prescribes k = (1 - eta^2) + (eta c)^2, which here gives 2.22e-16 (refracts,
# T nearly grazing).  We follow section 11.
check("F1 critical angle (sec.11 form): refracts, T ~ grazing", T is not None and abs(T[0] - 1.0) < 1e-15 and abs(T[1]) < 1e-7, (T, k))
T, k = refract((math.sin(math.asin(2/3) + 1e-6), -math.cos(math.asin(2/3) + 1e-6), 0.0), (0.0, 1.0, 0.0), 1.5)
check("F1 theta_c + 1e-6: TIR", T is None and k < 0, k)
T, k = refract((math.sin(math.asin(2/3) - 1e-6), -math.cos(math.asin(2/3) - 1e-6), 0.0), (0.0, 1.0, 0.0), 1.5)
check("F1 theta_c - 1e-6: refracts", T is not None and abs(k - 2.236e-6) < 1e-9, k)

# E4 shadow segments: floor y=0, light at (0,2,0), opaque plane through the light
def e4(yplane):
    sc = {"camera": {"eye": [0, 1, 5], "center": [0, 0, 0], "window": {"l": -1e-3, "r": 1e-3, "b": -1e-3, "t": 1e-3}, "resolution": [1, 1]},
          "ambient": [0, 0, 0], "lights": [{"position": [0, 2, 0]}],
          "objects": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": {"kd": 1}},
                      {"type": "plane", "point": [0, yplane, 0], "normal": [0, -1, 0]}]}
    return run_scene(sc)["pixels"][0][0]
check("E4a plane through light: lit", e4(2) > 0.5, e4(2))
check("E4a plane at 1.999999: shadow", e4(1.999999) == 0.0, e4(1.999999))

# G5 1x1 image: D = -w; corners 4 rays; adaptive counts
sc = {"camera": {"eye": [0, 0, 5], "center": [0, 0, 0], "window": {"l": -0.8, "r": 0.8, "b": -0.6, "t": 0.6}, "resolution": [1, 1]},
      "objects": [{"type": "sphere", "center": [0.3, 0.1, 0], "radius": 0.5}], "lights": [{"position": [1, 2, 3]}]}
check("G5 corners 4 rays", run_scene(sc, "--aa", "corners")["primary_rays"] == 4)
check("adaptive K=3 t=0 rays", run_scene(sc, "--size", "5x3", "--aa", "adaptive", "--threshold", "0", "--max-level", "3")["primary_rays"] == 41 * 25)
o1 = run_scene(sc, "--size", "7x5", "--aa", "corners"); o2 = run_scene(sc, "--size", "7x5", "--aa", "adaptive", "--max-level", "0")
o3 = run_scene(sc, "--size", "7x5", "--aa", "adaptive", "--threshold", "1e308", "--max-level", "4")
check("adaptive K=0 == corners bitwise", o1["pixels"] == o2["pixels"] and o1["primary_rays"] == o2["primary_rays"])
check("adaptive threshold huge == corners", o1["pixels"] == o3["pixels"] and o3["primary_rays"] == 48)

# byte rounding
check("to_byte", [ref.to_byte(x) for x in (0.5, -1, 2, 0.0019607843137254, 1/255, 127.5/255)] == [128, 0, 255, 0, 1, 128],
      [ref.to_byte(x) for x in (0.5, -1, 2, 0.0019607843137254, 1/255, 127.5/255)])
print("FAILURES:", fails)
