//! Watching the tracer at no cost when off (the tracer pushes each step to a recorder):
//! the [`Recorder`] trait, the zero-sized [`NoRecorder`] that compiles away, the [`CountingRecorder`]
//! that only counts (the benchmark's middle point) and the [`EventLog`] that keeps everything:
//! the events in order and the ray tree. The counters the tracer always keeps, recorder or
//! not, are [`stats::Stats`].
//!
//! `EventLog` keeps the ray tree as a pre-order arena of `RayNode`s, and says which events draw a
//! node: `spawned_by`, `ended_by`, `ray_events`, `shadow_events`.

pub mod event;
pub mod names;
pub mod stats;

use crate::scene::material::Rgb;
use event::{Event, LightTerm, NodeHit, RayKind};

/// What opens a ray node: its kind, level and geometry.
#[derive(Clone, Debug, PartialEq)]
pub struct RayStart<V> {
    /// Primary, reflected or transmitted.
    pub kind: RayKind,
    /// Primary = 1 (§6).
    pub level: u32,
    /// The ray's origin (for secondary rays, already offset).
    pub origin: V,
    /// The unit direction.
    pub direction: V,
}

/// What closes a ray node: the hit, the local term and the colour.
#[derive(Clone, Debug, PartialEq)]
pub struct RayEnd<V> {
    /// The nearest hit, if any.
    pub hit: Option<NodeHit<V>>,
    /// `I_local` (null on a miss).
    pub local: Option<Rgb>,
    /// The node's colour `I_local + ks·R + kt·T` (the background on a miss).
    pub color: Rgb,
}

/// Receives what the tracer does. Every method takes a closure that builds its payload, so a
/// recorder that is off never builds one.
pub trait Recorder<V> {
    /// False for [`NoRecorder`]: code guarded by it is removed at compile time.
    const ENABLED: bool;
    /// An event, in the order it happened.
    fn event(&mut self, make: impl FnOnce() -> Event<V>);
    /// A new ray node, child of the currently open one.
    fn open_ray(&mut self, make: impl FnOnce() -> RayStart<V>);
    /// One light's terms at the currently open node's hit.
    fn light(&mut self, make: impl FnOnce() -> LightTerm<V>);
    /// Closes the currently open node.
    fn close_ray(&mut self, make: impl FnOnce() -> RayEnd<V>);
    /// True once the recorder holds all it may: the tracer then spawns no more secondary rays,
    /// so that a tree that grows as 2^depth stops at the limit instead of filling the memory.
    /// Only read when [`Recorder::ENABLED`].
    #[inline(always)]
    fn full(&self) -> bool {
        false
    }
}

/// The default bound of an [`EventLog`]: events and ray nodes together. At about 200 bytes an
/// event (its document line being longer), a full log stays a few hundred megabytes.
pub const DEFAULT_LIMIT: usize = 1_000_000;
/// The largest limit `--max-events` accepts: a hundred times the default, tens of gigabytes.
pub const MAX_LIMIT: usize = 100 * DEFAULT_LIMIT;

/// Records nothing; zero-sized, every method empty and inlined: rendering uses only this.
#[derive(Clone, Copy, Debug, Default)]
pub struct NoRecorder;

impl<V> Recorder<V> for NoRecorder {
    const ENABLED: bool = false;
    #[inline(always)]
    fn event(&mut self, _make: impl FnOnce() -> Event<V>) {}
    #[inline(always)]
    fn open_ray(&mut self, _make: impl FnOnce() -> RayStart<V>) {}
    #[inline(always)]
    fn light(&mut self, _make: impl FnOnce() -> LightTerm<V>) {}
    #[inline(always)]
    fn close_ray(&mut self, _make: impl FnOnce() -> RayEnd<V>) {}
}

/// Counts calls without building any payload: measures the cost of the hooks themselves.
#[derive(Clone, Copy, Debug, Default)]
pub struct CountingRecorder {
    /// Events, nodes and light entries reported.
    pub calls: u64,
}

impl<V> Recorder<V> for CountingRecorder {
    const ENABLED: bool = true;
    #[inline]
    fn event(&mut self, _make: impl FnOnce() -> Event<V>) {
        self.calls += 1;
    }
    #[inline]
    fn open_ray(&mut self, _make: impl FnOnce() -> RayStart<V>) {
        self.calls += 1;
    }
    #[inline]
    fn light(&mut self, _make: impl FnOnce() -> LightTerm<V>) {
        self.calls += 1;
    }
    #[inline]
    fn close_ray(&mut self, _make: impl FnOnce() -> RayEnd<V>) {
        self.calls += 1;
    }
}

/// One node of the recorded ray tree.
#[derive(Clone, Debug, PartialEq)]
pub struct RayNode<V> {
    /// What opened it.
    pub start: RayStart<V>,
    /// Per light, in scene order (empty on a miss).
    pub lights: Vec<LightTerm<V>>,
    /// What closed it (None while open).
    pub end: Option<RayEnd<V>>,
    /// Indices of the children in [`EventLog::nodes`], in the order R, then T.
    pub children: Vec<usize>,
    /// The parent's index.
    pub parent: Option<usize>,
    /// The anti-aliasing sample this node belongs to, if any.
    pub sample: Option<usize>,
}

/// An event with the ray node it belongs to.
#[derive(Clone, Debug, PartialEq)]
pub struct Logged<V> {
    /// The index of the ray node (pre-order) or None for events outside any ray.
    pub ray: Option<usize>,
    /// The anti-aliasing sample it belongs to, if any.
    pub sample: Option<usize>,
    /// The event.
    pub event: Event<V>,
}

/// Keeps every event and the ray tree. Nodes are stored in the order they were opened, which is
/// the pre-order walk of the tree, so a node's index is the `ray` its events carry.
#[derive(Clone, Debug)]
pub struct EventLog<V> {
    /// Every event, in order.
    pub events: Vec<Logged<V>>,
    /// Every ray node, in pre-order; roots have no parent.
    pub nodes: Vec<RayNode<V>>,
    /// The chain of open nodes.
    open: Vec<usize>,
    /// The sample being traced (set by the sampler).
    pub current_sample: Option<usize>,
    /// The most events and nodes kept together; what comes after is dropped (see [`Self::overflowed`]).
    limit: usize,
    /// Whether an event was dropped because the log was full.
    overflowed: bool,
}

/// Why a trace that outgrew its [`EventLog`] is refused when its ray tree outgrew it: the limit,
/// and the worst-case size of the tree (`Scene::worst_tree_rays`) with the option that shrinks it.
#[must_use]
pub fn overflow_message(limit: usize, max_depth: u32, worst_rays: f64) -> String {
    format!(
        "the trace outgrew its limit of {limit} recorded events and ray nodes: at depth {max_depth} one ray's \
         tree may hold up to {worst_rays:.3e} rays; lower --depth"
    )
}

/// About how many bytes one recorded event or ray node costs by the time it is shown: the event
/// itself (about 200 bytes), its object in the trace document and its line of JSON or narration.
/// Measured: `trace --json` of 39 439 events (the 2D mirrors at depth 15) peaked at 157 MB, 4.0 kB
/// an event. `--max-events N` is refused before the work when `N` of them exceed the memory budget.
pub const BYTES_PER_RECORD: u64 = 4 << 10;

impl<V> Default for EventLog<V> {
    fn default() -> Self {
        Self::new()
    }
}

impl<V> EventLog<V> {
    /// An empty log that keeps up to [`DEFAULT_LIMIT`] events and nodes.
    #[must_use]
    pub fn new() -> Self {
        Self::with_limit(DEFAULT_LIMIT)
    }
    /// An empty log that keeps up to `limit` events and ray nodes together.
    #[must_use]
    pub fn with_limit(limit: usize) -> Self {
        Self {
            events: Vec::new(),
            nodes: Vec::new(),
            open: Vec::new(),
            current_sample: None,
            limit,
            overflowed: false,
        }
    }
    /// The bound this log was made with.
    #[must_use]
    pub fn limit(&self) -> usize {
        self.limit
    }
    /// True iff the trace outgrew the limit: events were dropped and secondary rays not spawned, so
    /// the log is incomplete and must not be shown as the trace.
    #[must_use]
    pub fn overflowed(&self) -> bool {
        self.overflowed
    }
    fn at_limit(&self) -> bool {
        self.events.len() + self.nodes.len() >= self.limit
    }
    /// Why this log outgrew its limit, named by what filled it: when most of what it kept are
    /// object tests, bounding-volume tests and node visits, or voxel steps, one ray's search did
    /// (the change is the structure or its cells); otherwise the ray tree did
    /// ([`overflow_message`], lower `--depth`).
    #[must_use]
    pub fn overflow_cause(&self, max_depth: u32, worst_rays: f64) -> String {
        let count = |test: fn(&Event<V>) -> bool| self.events.iter().filter(|l| test(&l.event)).count();
        let searches = [
            (
                count(|e| matches!(e, Event::ObjectTest { .. })),
                "object tests: a ray tests the objects its structure gives it; trace with a structure \
                 that tests fewer (--accel bvh)",
            ),
            (
                count(|e| {
                    matches!(e, Event::BoundTest { .. } | Event::NodeVisit { .. } | Event::NodeSkip { .. })
                }),
                "bounding-volume tests and node visits: trace with another structure (--accel)",
            ),
            (
                count(|e| matches!(e, Event::VoxelStep { .. })),
                "voxel steps of the grid: give the grid fewer cells (--grid)",
            ),
        ];
        let kept = self.events.len() + self.nodes.len();
        match searches.iter().max_by_key(|(n, _)| *n) {
            Some((n, cause)) if 2 * n > kept => format!(
                "the trace outgrew its limit of {} recorded events and ray nodes: {n} of them are {cause}",
                self.limit
            ),
            _ => overflow_message(self.limit, max_depth, worst_rays),
        }
    }
    /// The roots: one per primary ray traced.
    pub fn roots(&self) -> impl Iterator<Item = usize> + '_ {
        (0..self.nodes.len()).filter(|i| self.nodes[*i].parent.is_none())
    }
}

/// Which events of a log draw what (the figures' `data-events`): indices into
/// [`EventLog::events`], which are the trace document's `events`.
impl<V> EventLog<V> {
    /// The indices of the events of node `node` that satisfy `test`.
    pub fn indices_of(&self, node: usize, test: impl Fn(&Event<V>) -> bool) -> Vec<usize> {
        (self.events.iter().enumerate())
            .filter(|(_, l)| l.ray == Some(node) && test(&l.event))
            .map(|(k, _)| k)
            .collect()
    }

    /// The event that made node `node`: its `primary_ray`, or the parent's `reflect`/`refract`
    /// (a parent's children and its spawning events come in the same order, R then T).
    #[must_use]
    pub fn spawned_by(&self, node: usize) -> Option<usize> {
        let n = self.nodes.get(node)?;
        let Some(parent) = n.parent else {
            return self.indices_of(node, |e| matches!(e, Event::PrimaryRay { .. })).first().copied();
        };
        let position = self.nodes[parent].children.iter().position(|c| *c == node)?;
        let spawns = self.indices_of(parent, |e| matches!(e, Event::Reflect { .. } | Event::Refract { .. }));
        spawns.get(position).copied()
    }

    /// The event that ended node `node`'s search: its `hit` or `miss`.
    #[must_use]
    pub fn ended_by(&self, node: usize) -> Option<usize> {
        self.indices_of(node, |e| matches!(e, Event::Hit { .. } | Event::Miss { .. })).first().copied()
    }

    /// The events a drawn ray stands for: the one that made it and its hit or miss.
    #[must_use]
    pub fn ray_events(&self, node: usize) -> Vec<usize> {
        self.spawned_by(node).into_iter().chain(self.ended_by(node)).collect()
    }

    /// The `shadow_ray` events of node `node` towards light `light` (one at most).
    #[must_use]
    pub fn shadow_events(&self, node: usize, light: usize) -> Vec<usize> {
        self.indices_of(node, |e| matches!(e, Event::ShadowRay { light: l, .. } if *l == light))
    }
}

impl<V> Recorder<V> for EventLog<V> {
    const ENABLED: bool = true;
    fn event(&mut self, make: impl FnOnce() -> Event<V>) {
        if self.at_limit() {
            self.overflowed = true;
            return;
        }
        let ray = self.open.last().copied();
        self.events.push(Logged { ray, sample: self.current_sample, event: make() });
    }
    fn full(&self) -> bool {
        self.overflowed || self.at_limit()
    }
    // A node is always kept, so that every open is closed: the tracer spawns none once `full`,
    // and the sampler's primary rays add at most one node per sample beyond the limit.
    fn open_ray(&mut self, make: impl FnOnce() -> RayStart<V>) {
        if self.at_limit() {
            self.overflowed = true;
        }
        let index = self.nodes.len();
        let parent = self.open.last().copied();
        if let Some(p) = parent {
            self.nodes[p].children.push(index);
        }
        self.nodes.push(RayNode {
            start: make(),
            lights: Vec::new(),
            end: None,
            children: Vec::new(),
            parent,
            sample: self.current_sample,
        });
        self.open.push(index);
    }
    fn light(&mut self, make: impl FnOnce() -> LightTerm<V>) {
        if let Some(&i) = self.open.last() {
            self.nodes[i].lights.push(make());
        }
    }
    fn close_ray(&mut self, make: impl FnOnce() -> RayEnd<V>) {
        if let Some(i) = self.open.pop() {
            self.nodes[i].end = Some(make());
        }
    }
}
