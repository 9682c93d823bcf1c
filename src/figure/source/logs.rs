//! Questions a figure asks of a recorded log, answered without tracing: the first hit, the events
//! of a node or of a search, the incidence angle, the node that refracts, reflects totally or
//! casts a blocked shadow ray, a bounding volume's recorded slab intervals, and the grid walk's
//! pitfall. The picks of `source` score pixels with them; the kinds and the lessons' claims read
//! them to draw and to check.

use crate::geom::slab::culling_hit;
use crate::geom::Vector;
use crate::record::event::{Event, RayKind};
use crate::record::{EventLog, RayNode};
use crate::shape::Dim;

/// The first node with a hit (the primary ray's, when it hits).
#[must_use]
pub fn first_hit<V>(log: &EventLog<V>) -> Option<usize> {
    log.nodes.iter().position(|n| n.end.as_ref().is_some_and(|e| e.hit.is_some()))
}

/// The events of node `node`, in order.
pub fn node_events<V>(log: &EventLog<V>, node: usize) -> impl Iterator<Item = &Event<V>> {
    log.events.iter().filter(move |l| l.ray == Some(node)).map(|l| &l.event)
}

/// The angle of incidence at a node's hit, in degrees: between `−D` and the facing normal.
#[must_use]
pub fn incidence_deg<V: Vector>(node: &RayNode<V>) -> Option<f64> {
    let hit = node.end.as_ref()?.hit?;
    let cos = node.start.direction.dot(hit.normal).abs().min(1.0);
    Some(cos.acos().to_degrees())
}

/// The smallest angle, in degrees, between two of the vectors the `local-model` figure draws at
/// node `node`'s hit: the facing normal N_f, V = −D, and L and H = (L + V)/|L + V| of each light
/// whose L was computed. Two vectors closer than a few degrees would be drawn one over the other.
#[must_use]
pub fn vectors_apart_deg<V: Vector>(node: &RayNode<V>) -> Option<f64> {
    let hit = node.end.as_ref()?.hit?;
    let n_f = if hit.entering { hit.normal } else { -hit.normal };
    let view = -node.start.direction;
    let mut vectors = vec![n_f, view];
    for l in node.lights.iter().filter_map(|t| t.l) {
        vectors.push(l);
        vectors.extend((l + view).try_unit());
    }
    let angle = |a: V, b: V| a.dot(b).clamp(-1.0, 1.0).acos().to_degrees();
    let pairs = vectors.iter().enumerate().flat_map(|(k, a)| vectors[k + 1..].iter().map(move |b| (*a, *b)));
    pairs.map(|(a, b)| angle(a, b)).reduce(f64::min)
}

/// The node whose refraction shows best: θᵢ near 40°, the primary hit first.
#[must_use]
pub fn refraction_node<V: Dim>(log: &EventLog<V>) -> Option<(usize, f64)> {
    log.nodes
        .iter()
        .enumerate()
        .filter(|(k, _)| node_events(log, *k).any(|e| matches!(e, Event::Refract { .. })))
        .filter_map(|(k, n)| {
            let theta = incidence_deg(n)?;
            let primary = if n.start.kind == RayKind::Primary { 30.0 } else { 0.0 };
            Some((k, primary + 60.0 - (theta - 40.0).abs()))
        })
        .fold(None, |best: Option<(usize, f64)>, (k, s)| match best {
            Some((_, b)) if b >= s => best,
            _ => Some((k, s)),
        })
}

/// The first node (in pre-order, nearest the root) with a total internal reflection.
#[must_use]
pub fn tir_node<V>(log: &EventLog<V>) -> Option<usize> {
    log.events
        .iter()
        .filter(|l| matches!(l.event, Event::TotalInternalReflection { .. }))
        .filter_map(|l| l.ray)
        .min()
}

/// The node whose shadow rays show best: a blocked one, best at the primary hit and through
/// transparent objects (`0 < s < 1`, the product of kt), then opaque (`s = 0`); else the first
/// node with a shadow ray.
#[must_use]
pub fn shadow_node<V>(log: &EventLog<V>) -> Option<(usize, f64)> {
    let blocked = log
        .events
        .iter()
        .filter_map(|l| match &l.event {
            Event::ShadowRay { occluders, s, .. } if !occluders.is_empty() => {
                let at_primary = if l.ray == Some(0) { 10.0 } else { 0.0 };
                let transparent = if *s > 0.0 { 5.0 } else { 0.0 };
                Some((l.ray?, at_primary + transparent + occluders.len() as f64))
            }
            _ => None,
        })
        .fold(None, |best: Option<(usize, f64)>, (k, s)| match best {
            Some((_, b)) if b >= s => best,
            _ => Some((k, s)),
        });
    blocked.or_else(|| {
        log.events
            .iter()
            .find(|l| matches!(l.event, Event::ShadowRay { .. }))
            .and_then(|l| Some((l.ray?, 0.0)))
    })
}

/// The events of root `root`'s search for its nearest hit: those of its node before its `hit`
/// or `miss` (the shadow rays' tests come after).
pub fn search_events<V>(log: &EventLog<V>, root: usize) -> impl Iterator<Item = &Event<V>> {
    node_events(log, root).take_while(|e| !matches!(e, Event::Hit { .. } | Event::Miss { .. }))
}

/// [`search_events`] with each event's index in `log.events` (the trace document's index).
pub fn search_indexed<V>(log: &EventLog<V>, root: usize) -> impl Iterator<Item = (usize, &Event<V>)> {
    (log.events.iter().enumerate())
        .filter(move |(_, l)| l.ray == Some(root))
        .map(|(k, l)| (k, &l.event))
        .take_while(|(_, e)| !matches!(e, Event::Hit { .. } | Event::Miss { .. }))
}

/// Whether a recorded box interval counts as met, by the structures' own closed rule.
#[must_use]
pub fn met(t_in: f64, t_out: f64) -> bool {
    culling_hit(t_in, t_out)
}

/// A recorded `bound_test` of one object's volume: what [`bound_test_of`] finds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoundTestOf<'a> {
    /// Each slab pair's `[t_near, t_far]`.
    pub intervals: &'a [[f64; 2]],
    /// The interval's entry: the largest near end.
    pub t_in: f64,
    /// The interval's exit: the smallest far end.
    pub t_out: f64,
    /// Whether the test counted the volume as met.
    pub hit: bool,
}

/// The `bound_test` of object `object` in root 0's search.
#[must_use]
pub fn bound_test_of<V>(log: &EventLog<V>, object: usize) -> Option<BoundTestOf<'_>> {
    search_events(log, 0).find_map(|e| match e {
        Event::BoundTest { object: Some(o), intervals, t_in, t_out, hit, .. } if o.index == object => {
            Some(BoundTestOf { intervals: intervals.as_slice(), t_in: *t_in, t_out: *t_out, hit: *hit })
        }
        _ => None,
    })
}

/// The index in `log.events` of [`bound_test_of`]'s event.
#[must_use]
pub fn bound_test_index<V>(log: &EventLog<V>, object: usize) -> Option<usize> {
    search_indexed(log, 0)
        .find(|(_, e)| matches!(e, Event::BoundTest { object: Some(o), .. } if o.index == object))
        .map(|(k, _)| k)
}

/// The lecture's grid pitfall: a hit found in a cell but lying beyond the cell's exit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GridPitfall {
    /// The walk's step (from 0) whose cell found the hit.
    pub step: usize,
    /// The object hit.
    pub object: usize,
    /// The hit's t.
    pub t: f64,
    /// The cell's exit, `min tMax`, which `t` lies beyond.
    pub exit: f64,
}

/// The lecture's pitfall in root 0's grid walk: the first step whose cell found a hit (an
/// accepted `object_test` of an object the cell lists) lying beyond the cell's exit `min tMax`.
/// Unbounded objects, tested before the walk, do not count.
#[must_use]
pub fn grid_pitfall<V>(log: &EventLog<V>) -> Option<GridPitfall> {
    let mut found: Vec<(usize, f64)> = Vec::new();
    let mut step = 0;
    for e in search_events(log, 0) {
        match e {
            Event::ObjectTest { object, accepted: Some(t), .. } => found.push((object.index, *t)),
            Event::VoxelStep { t_max, objects, .. } => {
                let exit = t_max.iter().copied().fold(f64::INFINITY, f64::min);
                let listed = |o: usize| objects.iter().any(|x| x.index == o);
                if let Some((object, t)) = found.iter().find(|(o, t)| listed(*o) && *t > exit) {
                    return Some(GridPitfall { step, object: *object, t: *t, exit });
                }
                found.clear();
                step += 1;
            }
            _ => {}
        }
    }
    None
}
