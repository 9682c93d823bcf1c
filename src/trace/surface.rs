//! A packet's hits in the lanes, for the render's packets ([`super::packet`]) and ray trees
//! ([`super::wave`]): each lane's surface as `Nearest::found` and [`Tracer::trace`] make it
//! ([`Hit::new`]), the local model of §5 with its shadow segments ([`shade`]), the spawn offset
//! ([`spawn_origin`]) and a kept lane's counts ([`keep`]), lane by lane the scalar operations in
//! the scalar order.

use super::Tracer;
use crate::accel::packet::{key, LaneCounts, Packets};
use crate::accel::Prim;
use crate::geom::lanes::{
    and, and_not, any, axes, dot, dot_axes, holds, lanes, max_abs, ones, or, select, select_v, splat, test,
    unit, vector, Vs, F, LANES, M, NONE,
};
use crate::geom::offset::OFFSET_SCALE;
use crate::record::event::RayKind;
use crate::record::stats::Stats;
use crate::record::NoRecorder;
use crate::scene::material::Material;
use crate::scene::Scene;
use crate::shape::Dim;

/// A colour per lane, channel by channel.
pub(super) type Colors = [F; 3];

/// The nearest hits of a packet, each lane's as `Nearest::found` and [`Tracer::trace`] make it.
pub(super) struct Hit<'m> {
    pub surface: Surface<'m>,
    /// §3: `D·N ≤ 0`.
    pub entering: M,
    /// The materials' kt and ior.
    pub kt: F,
    pub ior: F,
    /// The lanes whose surface is off the packet's common case (the scalar code takes them).
    pub scalar: M,
}

impl<'m> Hit<'m> {
    /// The hits of the lanes `on` of rays `o + t·d` on the primitives `keys`: I and N as
    /// `Plane::surface_at` (`I = R(t) − N·((R(t) − P)·N)`) or `Sphere::surface_at` (`N = (R(t)
    /// − C)/|R(t) − C|`, `I = C + r·N`) make them, N_f, δ = 2⁻⁴⁴·max(|I|∞, |O|∞, |t|, scale), and
    /// the material's colours at I.
    #[inline(always)]
    pub fn new<V: Dim>(
        tracer: &Tracer<'m, V, NoRecorder>,
        packets: &Packets<'_, V>,
        (o, d): (&Vs, &Vs),
        t: &F,
        keys: &[u64; LANES],
        on: M,
    ) -> Self {
        let scene = tracer.scene;
        let raw = vector::<V>(|a, k| o[a][k] + d[a][k] * t[k]);
        let mut found = Gathered::new(raw);
        for (prim, plane) in packets.planes() {
            let at = and(on, test(|k| keys[k] == key(*prim)));
            if any(at) {
                let n = axes(plane.normal);
                let point = plane_point::<V>(axes(plane.point), n, &raw);
                found.take::<V>(scene, *prim, at, &point, &vector::<V>(|a, _| n[a]));
            }
        }
        for (prim, sphere) in packets.spheres() {
            let at = and(on, test(|k| keys[k] == key(*prim)));
            if any(at) {
                let c = axes(sphere.center);
                let (n, usual, _) = unit::<V>(&vector::<V>(|a, k| raw[a][k] - c[a]));
                found.scalar = or(found.scalar, and_not(at, usual));
                let p = vector::<V>(|a, k| c[a] + n[a][k] * sphere.radius);
                found.take::<V>(scene, *prim, at, &p, &n);
            }
        }
        let Gathered { point, normal, scale, ks, kt, ior, ka, kd, scalar, materials } = found;
        let (entering, n_f) = facing::<V>(d, &normal);
        let delta = offset::<V>(&point, o, t, &scale);
        let view = vector::<V>(|a, k| -d[a][k]);
        let materials = materials.expect("a lane on a plane or a sphere");
        Self {
            surface: Surface { point, n_f, delta, view, ka, kd, ks, materials },
            entering,
            kt,
            ior,
            scalar,
        }
    }
}

/// The surfaces and materials of a packet's hits, gathered object by object.
struct Gathered<'m> {
    point: Vs,
    normal: Vs,
    /// The object's scale, for δ.
    scale: F,
    ks: F,
    kt: F,
    ior: F,
    ka: Colors,
    kd: Colors,
    /// The lanes the scalar code must take.
    scalar: M,
    materials: Option<[&'m Material; LANES]>,
}

impl<'m> Gathered<'m> {
    fn new(raw: Vs) -> Self {
        let zero = splat(0.0);
        Self {
            point: raw,
            normal: raw,
            scale: zero,
            ks: zero,
            kt: zero,
            ior: splat(1.0),
            ka: [zero; 3],
            kd: [zero; 3],
            scalar: NONE,
            materials: None,
        }
    }

    /// The lanes `at` hit `prim` at I = `p` with normal `n`: its scale, its material's
    /// coefficients and its colours at I (`Material::colors_at`).
    #[inline(always)]
    fn take<V: Dim>(&mut self, scene: &'m Scene<V>, prim: Prim, at: M, p: &Vs, n: &Vs) {
        let object = &scene.objects[prim.object()];
        let material = &scene.materials[object.material];
        self.point = select_v(at, p, &self.point);
        self.normal = select_v(at, n, &self.normal);
        self.scale = select(at, splat(object.scale), self.scale);
        self.ks = select(at, splat(material.ks), self.ks);
        self.kt = select(at, splat(material.kt), self.kt);
        self.ior = select(at, splat(material.ior), self.ior);
        let (ka, kd) = colors_at::<V>(material, p);
        self.ka = std::array::from_fn(|c| select(at, ka[c], self.ka[c]));
        self.kd = std::array::from_fn(|c| select(at, kd[c], self.kd[c]));
        let materials = self.materials.get_or_insert([material; LANES]);
        for (k, m) in materials.iter_mut().enumerate() {
            if holds(at, k) {
                *m = material;
            }
        }
    }
}

/// A hit in each lane of a packet, as [`Tracer::local`] reads it: I, N_f, δ, the view vector
/// `V = −D`, the material's colours at I (after its checker), its ks, and the material itself
/// (for the highlight's exponent).
pub(super) struct Surface<'m> {
    pub point: Vs,
    pub n_f: Vs,
    pub delta: F,
    pub view: Vs,
    pub ka: Colors,
    pub kd: Colors,
    pub ks: F,
    pub materials: [&'m Material; LANES],
}

/// `I_local` of [`Tracer::local`] in the lanes `on` of `at`, every light in scene order, lane
/// by lane its operations in its order; also the lanes shaded (the others need the scalar code:
/// a normalisation off its common case, a shadow ray the packet cannot search). Tests and shadow
/// rays are counted per lane.
#[inline(always)]
pub(super) fn shade<V: Dim>(
    tracer: &Tracer<'_, V, NoRecorder>,
    packets: &Packets<'_, V>,
    at: &Surface<'_>,
    on: M,
    (counts, shadows): (&mut LaneCounts, &mut [u64; LANES]),
) -> (Colors, M) {
    let scene = tracer.scene;
    let (point, n_f, ks) = (&at.point, &at.n_f, &at.ks);
    let mut sum: Colors = std::array::from_fn(|c| lanes(|k| scene.ambient.0[c] * at.ka[c][k]));
    let mut scalar = NONE;
    // The lanes whose material has a highlight: ks > 0.
    let glossy = and(on, test(|k| ks[k] > 0.0));
    for light in &scene.lights {
        let position = axes(light.position);
        let to_light = vector::<V>(|a, k| position[a] - point[a][k]);
        let (l, usual, dd) = unit::<V>(&to_light);
        let distance = lanes(|k| dd[k].sqrt());
        let fat = lanes(|k| light.fat(distance[k]));
        // try_unit's other branch (a light nearly at I, or very far) is the scalar code's.
        scalar = or(scalar, and_not(on, usual));
        let n_dot_l = dot::<V>(n_f, &l);
        // lum = 1 iff N·L > 0; no shadow ray otherwise (§6).
        let lit = and(and(on, usual), test(|k| n_dot_l[k] > 0.0));
        if !any(lit) {
            continue;
        }
        let (s, flagged) = shadow_factor(packets, (point, n_f, &at.delta), &to_light, position, lit, counts);
        scalar = or(scalar, flagged);
        let lit_once = ones(lit);
        *shadows = std::array::from_fn(|k| shadows[k] + lit_once[k]);
        let weight = lanes(|k| fat[k] * s[k]);
        // H = normalize(L + V) where ks > 0, the highlight (N·H)^n; where H is off try_unit's
        // common case (L = −V among them), the scalar code. Elsewhere the term is `·0`.
        let shiny = and(glossy, lit);
        let mut highlight = splat(0.0);
        if any(shiny) {
            let (h, usual_h, _) = unit::<V>(&vector::<V>(|a, k| l[a][k] + at.view[a][k]));
            scalar = or(scalar, and_not(shiny, usual_h));
            let n_dot_h = dot::<V>(n_f, &h);
            highlight = lanes(|k| if holds(shiny, k) { at.materials[k].highlight(n_dot_h[k]) } else { 0.0 });
        }
        for (c, total) in sum.iter_mut().enumerate() {
            let intensity = light.intensity.0[c];
            let diffuse = lanes(|k| intensity * at.kd[c][k] * (weight[k] * n_dot_l[k]));
            let specular = lanes(|k| intensity * (weight[k] * ks[k] * highlight[k]));
            *total = select(lit, lanes(|k| total[k] + (diffuse[k] + specular[k])), *total);
        }
    }
    (sum, and_not(on, scalar))
}

/// `Material::colors_at` in each lane: `(ka2, kd2)` where the checker's cell is odd, else `(ka,
/// kd)`. The parity of `Σ floor(x_i/size + 1e-10)` is `Checker::is_odd`'s: the floors and their
/// sum are exact integers in `f64` below 2⁵³, and `s − 2·floor(s/2)` is then exactly 0 or 1.
#[inline(always)]
#[allow(clippy::float_cmp)] // The parity is exactly 1 or not.
pub(super) fn colors_at<V: Dim>(material: &Material, point: &Vs) -> (Colors, Colors) {
    let (ka, kd) = (material.ka.0, material.kd.0);
    let plain = (std::array::from_fn(|c| splat(ka[c])), std::array::from_fn(|c| splat(kd[c])));
    let Some(checker) = &material.checker else { return plain };
    let mut cells = splat(0.0);
    for axis in point.iter().take(V::DIM) {
        cells = lanes(|k| cells[k] + (axis[k] / checker.size + 1e-10).floor());
    }
    let odd = test(|k| cells[k] - 2.0 * (cells[k] * 0.5).floor() == 1.0);
    let pick = |odd_value: [f64; 3], even: &Colors| -> Colors {
        std::array::from_fn(|c| select(odd, splat(odd_value[c]), even[c]))
    };
    (pick(checker.ka2.0, &plain.0), pick(checker.kd2.0, &plain.1))
}

/// `Tracer::shadow_factor` in the lanes `lit`: the segment from the offset origin to the light,
/// searched by the packet; also the lanes the scalar code must take.
#[inline(always)]
fn shadow_factor<V: Dim>(
    packets: &Packets<'_, V>,
    (point, n_f, delta): (&Vs, &Vs, &F),
    to_light: &Vs,
    position: [f64; 3],
    lit: M,
    counts: &mut LaneCounts,
) -> (F, M) {
    let origin = spawn_origin::<V>(point, n_f, to_light, delta);
    let to_light = vector::<V>(|a, k| position[a] - origin[a][k]);
    let (direction, usual, dd) = unit::<V>(&to_light);
    let distance = lanes(|k| dd[k].sqrt());
    let live = and(lit, usual);
    let (s, flagged) = packets.shadow(&origin, &direction, distance, live, counts);
    (s, or(flagged, and_not(lit, usual)))
}

/// `Plane::surface_at` in each lane: the raw `R(t)` re-projected onto the plane through `p` of
/// normal `n`, `I = R(t) − N·((R(t) − P)·N)`.
#[inline(always)]
pub(super) fn plane_point<V: Dim>(p: [f64; 3], n: [f64; 3], raw: &Vs) -> Vs {
    let off = dot_axes::<V>(&vector::<V>(|a, k| raw[a][k] - p[a]), &n);
    vector::<V>(|a, k| raw[a][k] - n[a] * off[k])
}

/// §3 in each lane: entering iff `D·N ≤ 0` (a tangent counts as entering), and the facing normal
/// N_f, N when entering, −N when leaving.
#[inline(always)]
pub(super) fn facing<V: Dim>(d: &Vs, normal: &Vs) -> (M, Vs) {
    let d_dot_n = dot::<V>(d, normal);
    let entering = test(|k| d_dot_n[k] <= 0.0);
    (entering, select_v(entering, normal, &vector::<V>(|a, k| -normal[a][k])))
}

/// `offset_distance` in each lane: δ = 2⁻⁴⁴·max(|I|∞, |O|∞, |t|, scale).
#[inline(always)]
pub(super) fn offset<V: Dim>(point: &Vs, o: &Vs, t: &F, scale: &F) -> F {
    let (point_max, origin_max) = (max_abs::<V>(point), max_abs::<V>(o));
    lanes(|k| OFFSET_SCALE * point_max[k].max(origin_max[k]).max(t[k].abs()).max(scale[k]))
}

/// `spawn_origin` in each lane: I + N_f·δ where `dir·N_f ≥ 0`, else I − N_f·δ (the side the
/// direction leaves to).
#[inline(always)]
pub(super) fn spawn_origin<V: Dim>(point: &Vs, n_f: &Vs, dir: &Vs, delta: &F) -> Vs {
    let side = dot::<V>(dir, n_f);
    let up = vector::<V>(|a, k| point[a][k] + n_f[a][k] * delta[k]);
    let down = vector::<V>(|a, k| point[a][k] - n_f[a][k] * delta[k]);
    select_v(test(|k| side[k] >= 0.0), &up, &down)
}

/// Lane `k`'s answer kept: its ray of `kind`, its shadow rays and its tests counted.
#[inline(always)]
pub(super) fn keep(
    stats: &mut Stats,
    kind: RayKind,
    (counts, shadows): (&LaneCounts, &[u64; LANES]),
    k: usize,
) {
    stats.rays.count(kind);
    stats.rays.shadow += shadows[k];
    stats.tests.object += counts.object[k];
    stats.tests.node += counts.node[k];
}
