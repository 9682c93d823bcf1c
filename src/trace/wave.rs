//! Ray trees a level at a time: the primary rays a packet could not finish (a sphere, a mirror,
//! a lane the packet cannot answer) wait in a batch, and their trees are traced in *waves*, all
//! the rays of one level of every tree together, [`LANES`] at a time: the packet search, the
//! hit's surface, the local model ([`packet::shade`]) and the spawned R and T, lane by lane the
//! scalar operations in the scalar order. Once the deepest level is done, each node's colour is
//! summed from the bottom up as [`Tracer::trace`] sums it, `I_local + (0 + ks·R + kt·T)`, R
//! before T. A lane the packet cannot answer is traced one ray at a time from there
//! ([`Tracer::trace`] at its level, with its kind). The colours, rays and tests counted are
//! those of one ray at a time, bit for bit.
//!
//! A level keeps its rays axis by axis (a structure of arrays), padded to whole packets, so
//! that a packet's lanes are loaded as they lie.

use super::surface::{keep, shade, spawn_origin, Colors, Hit, Surface};
use super::Tracer;
use crate::accel::packet::{Best, LaneCounts, Packets, NO_KEY};
use crate::geom::lanes::{
    and, and_not, any, axes, dot, holds, lanes, or, select, splat, test, vector, Vs, F, LANES, M,
};
use crate::geom::ray::Ray;
use crate::record::event::RayKind;
use crate::record::NoRecorder;
use crate::scene::material::Rgb;
use crate::shape::Dim;

/// A ray of a level, what the lanes do not hold.
#[derive(Clone, Copy)]
struct Node {
    kind: RayKind,
    /// Where its colour goes: its parent's place in the level above (level 1: the place of its
    /// primary ray in the caller's colours).
    parent: u32,
    /// The weight of its colour in its parent's sum: ks for R, kt for T (level 1: unused).
    weight: f64,
    /// Its `I_local` while its children are pending, then its colour.
    color: Rgb,
    /// The sum of a hit's children so far, from 0 (`None`: a miss, or a ray traced one at a
    /// time, whose colour is already whole).
    sum: Option<Rgb>,
}

/// The axes of a packet's rays, O then D, each axis's [`LANES`] values side by side.
type Block = [[f64; LANES]; 6];

/// The rays of one level of the batch's trees, in the order they were spawned.
#[derive(Default)]
struct Level {
    /// O and D, a [`Block`] per packet; the lanes of the last past its rays repeat its last ray.
    blocks: Vec<Block>,
    nodes: Vec<Node>,
    /// Level 1 only: each primary ray's search, when its packet made it.
    searched: Vec<Option<Searched>>,
}

/// A primary ray's nearest hit as its packet found it, and the tests that took.
#[derive(Clone, Copy)]
pub(super) struct Searched {
    pub t: f64,
    pub key: u64,
    /// The lane was flagged: the scalar code must search it.
    pub flagged: bool,
    pub object_tests: u64,
    pub node_tests: u64,
}

impl Level {
    #[inline(always)]
    fn push(&mut self, origin: [f64; 3], dir: [f64; 3], kind: RayKind, parent: usize, weight: f64) {
        let k = self.nodes.len() % LANES;
        if k == 0 {
            self.blocks.push([[0.0; LANES]; 6]);
        }
        let block = self.blocks.last_mut().expect("a block for the ray");
        for a in 0..3 {
            // The lanes past the ray hold it too, until a ray takes them.
            for lane in &mut block[a][k..] {
                *lane = origin[a];
            }
            for lane in &mut block[3 + a][k..] {
                *lane = dir[a];
            }
        }
        let parent = u32::try_from(parent).expect("a batch holds fewer than 2³² rays");
        self.nodes.push(Node { kind, parent, weight, color: Rgb::BLACK, sum: None });
    }

    /// Ray `i`, as a scalar ray.
    fn ray<V: Dim>(&self, i: usize) -> Ray<V> {
        let (block, k) = (&self.blocks[i / LANES], i % LANES);
        let mut ray = Ray::new(V::ZERO, V::ZERO);
        for a in 0..V::DIM {
            ray.origin[a] = block[a][k];
            ray.dir[a] = block[3 + a][k];
        }
        ray
    }

    /// The search of the packet of rays `first …`, when every ray of it has one: each lane's
    /// nearest hit, the lanes flagged, and the tests counted.
    #[inline(always)]
    fn searched(&self, first: usize, real: usize) -> Option<(Best, M, LaneCounts)> {
        let mut known = [None; LANES];
        for (k, slot) in known.iter_mut().enumerate() {
            *slot = Some(self.searched.get(first + k.min(real - 1)).copied().flatten()?);
        }
        let known = known.map(|k| k.expect("every lane searched"));
        let best = Best { t: lanes(|k| known[k].t), key: known.map(|k| k.key) };
        let tests = LaneCounts { object: known.map(|k| k.object_tests), node: known.map(|k| k.node_tests) };
        Some((best, test(|k| known[k].flagged), tests))
    }

    fn clear(&mut self) {
        self.blocks.clear();
        self.nodes.clear();
        self.searched.clear();
    }
}

thread_local! {
    /// The room of a thread's trees, allocated once and kept from batch to batch.
    static ROOM: std::cell::Cell<Trees> = std::cell::Cell::new(Trees::default());
}

/// The trees of a batch of primary rays, a [`Level`] per ray level `1 … max_depth + 1`.
#[derive(Default)]
pub(super) struct Trees {
    levels: Vec<Level>,
}

impl Trees {
    /// The calling thread's trees, empty; hand them back with [`Trees::keep`].
    pub fn take() -> Self {
        ROOM.take()
    }

    /// Keeps the trees' room for the thread's next batch.
    pub fn keep(self) {
        ROOM.set(self);
    }

    /// Adds the primary ray whose colour goes to place `slot` of the caller's colours, with its
    /// packet's search if it has one.
    #[inline(always)]
    pub fn root<V: Dim>(&mut self, ray: &Ray<V>, slot: usize, searched: Option<Searched>) {
        if self.levels.is_empty() {
            self.levels.push(Level::default());
        }
        let first = &mut self.levels[0];
        first.push(axes(ray.origin), axes(ray.dir), RayKind::Primary, slot, 1.0);
        first.searched.push(searched);
    }

    /// Traces every tree, a level at a time, and writes each primary ray's colour to its slot
    /// of `colors`; the trees are then empty.
    #[inline(always)]
    pub fn trace<V: Dim>(
        &mut self,
        tracer: &mut Tracer<'_, V, NoRecorder>,
        packets: &Packets<'_, V>,
        colors: &mut [Rgb],
    ) {
        // A node at level max_depth + 1 spawns nothing.
        let levels = tracer.max_depth as usize + 1;
        while self.levels.len() < levels {
            self.levels.push(Level::default());
        }
        let mut depth = 0;
        while depth < levels && !self.levels[depth].nodes.is_empty() {
            let (here, below) = self.levels.split_at_mut(depth + 1);
            let level = u32::try_from(depth + 1).expect("max_depth + 1 levels");
            wave(tracer, packets, &mut here[depth], below.first_mut(), level);
            depth += 1;
        }
        // From the deepest level up: a hit's colour is `I_local + sum`, then it joins its
        // parent's sum, children in the order they were spawned (R, then T).
        for d in (0..depth).rev() {
            let (above, here) = self.levels.split_at_mut(d);
            let here = &mut here[0].nodes;
            for node in here.iter_mut() {
                if let Some(sum) = node.sum {
                    node.color += sum;
                }
            }
            match above.last_mut() {
                Some(parent) => {
                    for node in here.iter() {
                        let sum = parent.nodes[node.parent as usize].sum.as_mut();
                        *sum.expect("a parent with children has a sum") += node.color * node.weight;
                    }
                }
                None => {
                    for node in here.iter() {
                        colors[node.parent as usize] = node.color;
                    }
                }
            }
        }
        for level in &mut self.levels {
            level.clear();
        }
    }
}

/// One level's rays, [`LANES`] at a time: the nearest hits in a packet; a miss takes the
/// background; a hit is shaded in the packet and spawns its children into `next`; the lanes
/// the packet cannot answer are traced one at a time.
#[inline(always)]
fn wave<V: Dim>(
    tracer: &mut Tracer<'_, V, NoRecorder>,
    packets: &Packets<'_, V>,
    here: &mut Level,
    mut next: Option<&mut Level>,
    level: u32,
) {
    let count = here.nodes.len();
    let spawns = level <= tracer.max_depth;
    for (p, block) in here.blocks.iter().enumerate() {
        let first = p * LANES;
        let real = (count - first).min(LANES);
        let o: Vs = std::array::from_fn(|a| block[a]);
        let d: Vs = std::array::from_fn(|a| block[3 + a]);
        let live = test(|k| k < real);
        let mut counts = LaneCounts::default();
        let mut shadows = [0; LANES];
        // Level 1's rays come with their packet's search, unless they were the row's last few.
        let (best, flagged) = match here.searched(first, real) {
            Some((best, flagged, tests)) => {
                counts = tests;
                (best, flagged)
            }
            None => packets.nearest(&o, &d, &mut counts),
        };
        let on = and_not(and(live, test(|k| best.key[k] != NO_KEY)), flagged);
        let mut color: Colors = std::array::from_fn(|c| splat(tracer.scene.background.0[c]));
        let mut scalar = flagged;
        let mut children = Children::default();
        if any(on) {
            let hit = Hit::new(tracer, packets, (&o, &d), &best.t, &best.key, on);
            let (shaded, ok) =
                shade(tracer, packets, &hit.surface, and_not(on, hit.scalar), (&mut counts, &mut shadows));
            scalar = or(scalar, and_not(on, ok));
            color = std::array::from_fn(|c| select(ok, shaded[c], color[c]));
            if spawns {
                children = spawn::<V>(&hit, &d, ok);
            }
        }
        for (k, i) in (first..first + real).enumerate() {
            let kind = here.nodes[i].kind;
            if holds(scalar, k) {
                here.nodes[i].color = tracer.trace(&here.ray(i), kind, level, &[]);
                continue;
            }
            keep(&mut tracer.stats, kind, (&counts, &shadows), k);
            let node = &mut here.nodes[i];
            node.color = Rgb(std::array::from_fn(|c| color[c][k]));
            if !holds(on, k) {
                continue;
            }
            node.sum = Some(Rgb::BLACK);
            for (child, kind) in
                [(&children.reflected, RayKind::Reflected), (&children.transmitted, RayKind::Transmitted)]
            {
                if holds(child.lanes, k) {
                    let next = next.as_deref_mut().expect("a level below while rays spawn");
                    let (origin, dir) = (lane(&child.origin, k), lane(&child.dir, k));
                    next.push(origin, dir, kind, i, child.weight[k]);
                }
            }
        }
    }
}

/// Lane `k` of a lane vector.
#[inline(always)]
fn lane(v: &Vs, k: usize) -> [f64; 3] {
    std::array::from_fn(|a| v[a][k])
}

/// The children of a packet of hits, one kind.
#[derive(Default)]
struct Child {
    /// The lanes that spawn one.
    lanes: M,
    origin: Vs,
    dir: Vs,
    /// Its weight in the parent's sum: ks or kt.
    weight: F,
}

/// R and T of a packet of hits.
#[derive(Default)]
struct Children {
    reflected: Child,
    transmitted: Child,
}

/// `Tracer::spawn` in the lanes `on`: R = `N_f·(2·N_f·V) − V` where ks > 0, T = `η·D + (η·c
/// − √k)·N_f` where kt > 0 and `k ≥ 0` (η = n1/n2, `c = −D·N_f` clamped to [−1, 1], `k = (1
/// − η²) + (η·c)²`), each from I offset by δ along ±N_f to the side it leaves to.
#[inline(always)]
fn spawn<V: Dim>(hit: &Hit<'_>, d: &Vs, on: M) -> Children {
    let Surface { point, n_f, delta, view, ks, .. } = &hit.surface;
    let origin = |dir: &Vs| spawn_origin::<V>(point, n_f, dir, delta);
    let reflects = and(on, test(|k| ks[k] > 0.0));
    let mut children = Children::default();
    if any(reflects) {
        let twice = dot::<V>(n_f, view);
        let dir = vector::<V>(|a, k| n_f[a][k] * (2.0 * twice[k]) - view[a][k]);
        children.reflected = Child { lanes: reflects, origin: origin(&dir), dir, weight: *ks };
    }
    let transmits = and(on, test(|k| hit.kt[k] > 0.0));
    if any(transmits) {
        // Swap n1, n2 for a leaving ray (§3).
        let n1 = select(hit.entering, splat(1.0), hit.ior);
        let n2 = select(hit.entering, hit.ior, splat(1.0));
        let eta = lanes(|k| n1[k] / n2[k]);
        let d_dot_n = dot::<V>(d, n_f);
        let c = lanes(|k| (-d_dot_n[k]).clamp(-1.0, 1.0));
        let k2 = lanes(|k| (1.0 - eta[k] * eta[k]) + (eta[k] * c[k]) * (eta[k] * c[k]));
        let refracts = and(transmits, test(|k| !(k2[k] < 0.0)));
        let bend = lanes(|k| eta[k] * c[k] - k2[k].sqrt());
        let dir = vector::<V>(|a, k| d[a][k] * eta[k] + n_f[a][k] * bend[k]);
        children.transmitted = Child { lanes: refracts, origin: origin(&dir), dir, weight: hit.kt };
    }
    children
}
