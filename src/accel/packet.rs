//! The render's two searches for [`LANES`] rays at once, a *packet* (`geom::lanes`): the nearest
//! hit ([`Packets::nearest`]) and a shadow segment's factor ([`Packets::shadow`]), each lane
//! the answer of [`Accel::nearest`] and [`Accel::occluders`] for its ray, bit for bit, with the
//! same tests counted.
//!
//! Each lane computes the scalar search's operations in the scalar order: the plane test `t =
//! (P − O)·N / (D·N)`, the root box's slabs `t = (x − O)·(1/D)`, the stable sphere roots of §11
//! (`q = −(b' + sign(b')·√Δ')`, `t = q` or `c/q`). It visits what the scalar walk visits, in its
//! order: the planes, then the root box (the node test), then the box's spheres, with the same
//! prune ([`beyond`]) and, for a shadow segment, the same end at an opaque occluder.
//!
//! The packet search covers the scenes of the lecture: planes, then a BVH that is one leaf of
//! spheres (every scene of at most `bvh::MAX_LEAF` bounded objects, all spheres);
//! [`Accel::packets`] says `None` for any other structure. A lane whose ray is parallel to a
//! slab (some `1/D` infinite) and starts outside the box takes the scalar code's other branch:
//! it is flagged, and its caller traces that ray one at a time.

use super::{beyond, Accel, Prim, Structure};
use crate::bounds::aabb::Aabb;
use crate::geom::lanes::{
    and, and_not, any, axes, dot, dot_axes, finite, lanes, max_abs, ones, or, select, splat, test, vector,
    Vs, ALL, F, LANES, M, NONE,
};
use crate::geom::slab::widen_exit;
use crate::scene::Scene;
use crate::shape::plane::Plane;
use crate::shape::sphere::Sphere;
use crate::shape::{Dim, Shape};
use arrayvec::ArrayVec;

/// The most objects a packet search sees (planes and the leaf's spheres): a shadow segment's
/// occluders are kept per object, on the stack.
pub const MAX_OBJECTS: usize = 16;

/// The key of a primitive, `object·2³² + part`, which orders as [`Prim`] orders.
#[must_use]
pub fn key(prim: Prim) -> u64 {
    u64::from(prim.object) << 32 | u64::from(prim.part)
}

/// The key of no primitive.
pub const NO_KEY: u64 = u64::MAX;

/// Tests counted per lane, added to a ray's statistics only when the packet's answer for that
/// lane is kept.
#[derive(Clone, Copy, Debug, Default)]
pub struct LaneCounts {
    /// Object tests.
    pub object: [u64; LANES],
    /// Hierarchy node tests.
    pub node: [u64; LANES],
}

impl LaneCounts {
    /// Adds one to each of `counter`'s lanes where `m` holds.
    #[inline(always)]
    fn add(counter: &mut [u64; LANES], m: M) {
        let one = ones(m);
        *counter = std::array::from_fn(|k| counter[k] + one[k]);
    }
}

/// The nearest hit in each lane: its t (`+∞` while none) and its primitive's [`key`]
/// ([`NO_KEY`] while none).
#[derive(Clone, Copy, Debug)]
pub struct Best {
    /// t of the nearest hit.
    pub t: F,
    /// Its primitive.
    pub key: [u64; LANES],
}

impl Best {
    /// `Nearest::offer` in every lane where `ok`: keeps `t` when nearer, or equal with a smaller
    /// primitive (§6).
    #[inline(always)]
    #[allow(clippy::float_cmp)] // An exact tie is exactly what the rule is about.
    fn offer(&mut self, prim: Prim, t: F, ok: M) {
        let key = key(prim);
        let nearer = test(|k| t[k] < self.t[k]);
        let tie = and(test(|k| t[k] == self.t[k]), test(|k| key < self.key[k]));
        let take = and(ok, or(nearer, tie));
        self.t = select(take, t, self.t);
        self.key = std::array::from_fn(|k| (key & take[k]) | (self.key[k] & !take[k]));
    }
}

/// What the packet search reads of a scene: its planes, tested first, and the one leaf of the
/// BVH, its box and its spheres (see the module's doc).
#[derive(Clone, Debug)]
pub struct Packets<'a, V: Dim> {
    scene: &'a Scene<V>,
    planes: &'a [(Prim, Plane<V>)],
    root_box: &'a Aabb<V>,
    spheres: ArrayVec<(Prim, &'a Sphere<V>), MAX_OBJECTS>,
    /// Every object the search sees, by its place in the walk (the planes, then the spheres),
    /// listed in ascending object index with its `kt`: the order of the product `s = Π kt`.
    by_index: ArrayVec<(usize, f64), MAX_OBJECTS>,
}

impl<V: Dim> Accel<V> {
    /// The packet search of this structure over `scene` (the scene it was built for), when it
    /// has one: a BVH that is one leaf of spheres, or no bounded object at all.
    #[must_use]
    pub fn packets<'a>(&'a self, scene: &'a Scene<V>) -> Option<Packets<'a, V>> {
        let Structure::Bvh(bvh) = &self.structure else { return None };
        let (root_box, prims) = bvh.one_leaf()?;
        if self.unbounded.len() + prims.len() > MAX_OBJECTS {
            return None;
        }
        let mut spheres = ArrayVec::new();
        for prim in prims {
            let Shape::Sphere(sphere) = &scene.objects[prim.object()].shape else { return None };
            spheres.push((*prim, sphere));
        }
        let walked: ArrayVec<Prim, MAX_OBJECTS> =
            self.unbounded.iter().map(|(p, _)| *p).chain(prims.iter().copied()).collect();
        let mut order: ArrayVec<usize, MAX_OBJECTS> = (0..walked.len()).collect();
        order.sort_unstable_by_key(|&place| walked[place].object);
        let by_index =
            order.iter().map(|&place| (place, scene.material_of(walked[place].object()).kt)).collect();
        Some(Packets { scene, planes: &self.unbounded, root_box, spheres, by_index })
    }
}

impl<'a, V: Dim> Packets<'a, V> {
    /// The planes, each with the primitive that names it.
    #[must_use]
    pub fn planes(&self) -> &'a [(Prim, Plane<V>)] {
        self.planes
    }

    /// The leaf's spheres, each with the primitive that names it.
    #[must_use]
    pub fn spheres(&self) -> &[(Prim, &'a Sphere<V>)] {
        &self.spheres
    }

    /// [`Accel::nearest`] in each lane of rays `o + t·d`, without a recorder: the nearest hit's
    /// t and primitive, the tests counted into `counts`, and the lanes the packet cannot answer
    /// (to be searched one ray at a time; their counts are to be dropped).
    #[inline(always)]
    pub fn nearest(&self, o: &Vs, d: &Vs, counts: &mut LaneCounts) -> (Best, M) {
        let mut best = Best { t: splat(f64::INFINITY), key: [NO_KEY; LANES] };
        for (prim, plane) in self.planes {
            LaneCounts::add(&mut counts.object, ALL);
            let (t, ok) = plane_t::<V>(plane, o, d);
            best.offer(*prim, t, ok);
        }
        if self.spheres.is_empty() {
            return (best, NONE);
        }
        let (pass, scalar) = self.root(o, d, ALL, best.t, counts);
        // Rays that miss the box test no sphere: a packet that misses it whole, no lane either.
        if !any(pass) {
            return (best, scalar);
        }
        for (prim, sphere) in &self.spheres {
            LaneCounts::add(&mut counts.object, pass);
            let (t, ok) = sphere_t::<V>(sphere, o, d);
            best.offer(*prim, t, and(pass, ok));
        }
        (best, scalar)
    }

    /// [`Accel::occluders`] of the segments `o + t·d`, `0 < t < d_l`, in the lanes `live`, each
    /// lane's occluders multiplied into the shadow factor `s = Π kt` as `Tracer::shadow_factor`
    /// multiplies them (the transparent ones in object-index order, then the opaque one that
    /// ended the search). Also the lanes the packet cannot answer.
    #[inline(always)]
    pub fn shadow(&self, o: &Vs, d: &Vs, d_l: F, live: M, counts: &mut LaneCounts) -> (F, M) {
        let mut segments =
            Segments { found: [NONE; MAX_OBJECTS], open: live, opaque: NONE, opaque_kt: splat(1.0) };
        for (place, (prim, plane)) in self.planes.iter().enumerate() {
            LaneCounts::add(&mut counts.object, segments.open);
            let (t, ok) = plane_t::<V>(plane, o, d);
            segments.meet(place, self.kt(*prim), and(ok, test(|k| t[k] < d_l[k])));
        }
        let mut scalar = NONE;
        if !self.spheres.is_empty() && any(segments.open) {
            let (pass, flagged) = self.root(o, d, segments.open, d_l, counts);
            scalar = flagged;
            segments.open = pass;
            for (place, (prim, sphere)) in self.spheres.iter().enumerate() {
                if !any(segments.open) {
                    break;
                }
                LaneCounts::add(&mut counts.object, segments.open);
                let (t, ok) = sphere_t::<V>(sphere, o, d);
                segments.meet(self.planes.len() + place, self.kt(*prim), and(ok, test(|k| t[k] < d_l[k])));
            }
        }
        let mut s = splat(1.0);
        for &(place, kt) in &self.by_index {
            s = select(segments.found[place], lanes(|k| s[k] * kt), s);
        }
        (select(segments.opaque, lanes(|k| s[k] * segments.opaque_kt[k]), s), scalar)
    }

    /// The `kt` of a primitive's material.
    #[inline(always)]
    fn kt(&self, prim: Prim) -> f64 {
        self.scene.material_of(prim.object()).kt
    }

    /// The root box's node test in the lanes `live` (counted), as `Bvh::walk` makes it: a ray
    /// that starts in the box passes; any other passes when its slabs meet the box
    /// (`culling_hit`) no later than `bound` (`beyond`). Also the lanes that need the scalar
    /// walk's parallel-slab branch.
    #[inline(always)]
    fn root(&self, o: &Vs, d: &Vs, live: M, bound: F, counts: &mut LaneCounts) -> (M, M) {
        LaneCounts::add(&mut counts.node, live);
        let (min, max) = (axes(self.root_box.min), axes(self.root_box.max));
        let mut inside = ALL;
        let mut oblique = ALL;
        let inv = vector::<V>(|a, k| 1.0 / d[a][k]);
        for a in 0..V::DIM {
            inside = and(inside, and(test(|k| min[a] <= o[a][k]), test(|k| o[a][k] <= max[a])));
            oblique = and(oblique, finite(inv[a]));
        }
        let (t_in, t_out) = slabs::<V>(&min, &max, o, &inv);
        let wide = lanes(|k| widen_exit(t_out[k]));
        let met = and(test(|k| t_in[k] <= wide[k]), test(|k| wide[k] >= 0.0));
        // A lane outside `live` may hold any bound (even NaN): `beyond` asks for a true one.
        let bound = select(live, bound, splat(f64::INFINITY));
        let near = and_not(met, test(|k| beyond(t_in[k], bound[k])));
        let scalar = and_not(and_not(live, inside), oblique);
        (and_not(and(live, or(inside, near)), scalar), scalar)
    }
}

/// A packet's shadow segments as the search meets their occluders.
struct Segments {
    /// The lanes each object (by its place in the walk) occludes, when it is transparent.
    found: [M; MAX_OBJECTS],
    /// The lanes no opaque occluder has ended yet.
    open: M,
    /// The lanes an opaque occluder ended, and its `kt`.
    opaque: M,
    opaque_kt: F,
}

impl Segments {
    /// The object at `place` in the walk, of `kt`, hit on the segment (`0 < t < d_l`) in the lanes
    /// `hit`: where the segment is still open, a transparent one is kept, an opaque one ends the
    /// search (`Shadow::offer`).
    #[inline(always)]
    fn meet(&mut self, place: usize, kt: f64, hit: M) {
        let on = and(self.open, hit);
        if kt > 0.0 {
            self.found[place] = on;
        } else {
            self.opaque = or(self.opaque, on);
            self.opaque_kt = select(on, splat(kt), self.opaque_kt);
            self.open = and_not(self.open, on);
        }
    }
}

/// `Plane::hit_t` in every lane: `num = (P − O)·N`, `denom = D·N` of one strict sign, `t =
/// num/denom` finite and positive.
#[inline(always)]
fn plane_t<V: Dim>(plane: &Plane<V>, o: &Vs, d: &Vs) -> (F, M) {
    let (p, n) = (axes(plane.point), axes(plane.normal));
    let to_plane = vector::<V>(|a, k| p[a] - o[a][k]);
    let num = dot_axes::<V>(&to_plane, &n);
    let denom = dot_axes::<V>(d, &n);
    let t = lanes(|k| num[k] / denom[k]);
    let positive = and(test(|k| num[k] > 0.0), test(|k| denom[k] > 0.0));
    let negative = and(test(|k| num[k] < 0.0), test(|k| denom[k] < 0.0));
    let ok = and(or(positive, negative), and(finite(t), test(|k| t[k] > 0.0)));
    (t, ok)
}

/// `RecipRay::box_interval` of an oblique ray in every lane: `[max t_near, min t_far]` over the
/// slabs.
#[inline(always)]
fn slabs<V: Dim>(min: &[f64; 3], max: &[f64; 3], o: &Vs, inv: &Vs) -> (F, F) {
    let (mut t_in, mut t_out) = (splat(f64::NEG_INFINITY), splat(f64::INFINITY));
    for a in 0..V::DIM {
        let t1 = lanes(|k| (min[a] - o[a][k]) * inv[a][k]);
        let t2 = lanes(|k| (max[a] - o[a][k]) * inv[a][k]);
        let ordered = test(|k| t1[k] <= t2[k]);
        let (near, far) = (select(ordered, t1, t2), select(ordered, t2, t1));
        t_in = select(test(|k| near[k] > t_in[k]), near, t_in);
        t_out = select(test(|k| far[k] < t_out[k]), far, t_out);
    }
    (t_in, t_out)
}

/// `Sphere::hit_t` in every lane: with `f = O − C`, `b' = f·D`, `c = f·f − r²`, none when the
/// origin is outside with the centre behind (`b' > 0`, `c > 0`); else `Δ' = r² − |f − b'·D|²`,
/// `q = −(b' + sign(b')·√Δ')` and the roots `q`, `c/q` (one root `−b'` when `Δ' = 0` or `q = 0`),
/// the least positive one, kept when `I − C` normalises.
#[inline(always)]
#[allow(clippy::float_cmp)] // §11: one root exactly at Δ' = 0 or q = 0.
fn sphere_t<V: Dim>(sphere: &Sphere<V>, o: &Vs, d: &Vs) -> (F, M) {
    let (center, radius) = (axes(sphere.center), sphere.radius);
    let f = vector::<V>(|a, k| o[a][k] - center[a]);
    let b = dot::<V>(&f, d);
    let ff = dot::<V>(&f, &f);
    let c = lanes(|k| ff[k] - radius * radius);
    let behind = and(test(|k| b[k] > 0.0), test(|k| c[k] > 0.0));
    let perp = vector::<V>(|a, k| f[a][k] - d[a][k] * b[k]);
    let pp = dot::<V>(&perp, &perp);
    let delta = lanes(|k| radius * radius - pp[k]);
    let sign = select(test(|k| b[k] >= 0.0), splat(1.0), splat(-1.0));
    let q = lanes(|k| -(b[k] + delta[k].sqrt().copysign(sign[k])));
    let one = or(test(|k| delta[k] == 0.0), test(|k| q[k] == 0.0));
    let t1 = lanes(|k| c[k] / q[k]);
    let minus_b = lanes(|k| -b[k]);
    let low = select(one, minus_b, lanes(|k| q[k].min(t1[k])));
    let high = select(one, minus_b, lanes(|k| q[k].max(t1[k])));
    let low_ahead = test(|k| low[k] > 0.0);
    let t = select(low_ahead, low, high);
    let radial = vector::<V>(|a, k| o[a][k] + d[a][k] * t[k] - center[a]);
    let m = max_abs::<V>(&radial);
    let root = and(test(|k| delta[k] >= 0.0), or(low_ahead, test(|k| high[k] > 0.0)));
    let normalises = and(test(|k| m[k] > 0.0), finite(m));
    (t, and_not(and(root, normalises), behind))
}
