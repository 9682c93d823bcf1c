//! Brute force (algorithm.md §7: `O(n)` tests per ray): every object in index order. The oracle
//! every other structure is tested against.

use super::test_object;
use crate::geom::ray::Ray;
use crate::record::event::ObjectRef;
use crate::record::Recorder;
use crate::scene::Scene;
use crate::shape::{Dim, SurfaceHit};
use crate::trace::stats::Stats;

/// The nearest hit over all objects; the strict `<` keeps the smaller index on equal t (§6).
pub fn nearest<V: Dim, R: Recorder<V>>(
    scene: &Scene<V>,
    ray: &Ray<V>,
    stats: &mut Stats,
    rec: &mut R,
) -> Option<(ObjectRef, SurfaceHit<V>)> {
    let mut best: Option<(ObjectRef, SurfaceHit<V>)> = None;
    for index in 0..scene.objects.len() {
        if let Some(hit) = test_object(scene, index, ray, stats, rec) {
            if best.is_none_or(|(_, b)| hit.t < b.t) {
                best = Some((ObjectRef { index, triangle: None }, hit));
            }
        }
    }
    best
}

/// Every object hit at `0 < t < d_L`, in index order, until `on` says stop.
pub fn occluders<V: Dim, R: Recorder<V>>(
    scene: &Scene<V>,
    ray: &Ray<V>,
    d_l: f64,
    stats: &mut Stats,
    rec: &mut R,
    mut on: impl FnMut(ObjectRef) -> bool,
) {
    for index in 0..scene.objects.len() {
        if let Some(hit) = test_object(scene, index, ray, stats, rec) {
            if hit.t < d_l && !on(ObjectRef { index, triangle: None }) {
                return;
            }
        }
    }
}
