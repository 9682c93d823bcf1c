//! A bounding volume per primitive (algorithm.md §9.1): test the ray against the volume first;
//! a miss skips the object. `--bounds sphere|aabb|kdop` chooses the volume; a mesh's triangles
//! each get their own. Still `O(n)` tests per ray, but each miss is cheaper than the object's test.

use super::{object_ref, prim_hull, Prim, Visitor};
use crate::bounds::{BoundingVolume, VolumeKind};
use crate::geom::ray::Ray;
use crate::record::event::Event;
use crate::record::stats::Stats;
use crate::record::Recorder;
use crate::scene::Scene;
use crate::shape::Dim;

/// Every primitive with its volume, in object order.
#[derive(Clone, Debug)]
pub struct Volumes<V> {
    entries: Vec<(Prim, BoundingVolume<V>)>,
    kind: VolumeKind,
}

impl<V: Dim> Volumes<V> {
    /// Fits a volume of `kind` around each primitive.
    #[must_use]
    pub fn build(scene: &Scene<V>, prims: &[Prim], kind: VolumeKind) -> Self {
        let entries = prims.iter().map(|&p| (p, BoundingVolume::fit(kind, &prim_hull(scene, p)))).collect();
        Self { entries, kind }
    }

    /// Every primitive with its volume, in object order (for figures).
    #[must_use]
    pub fn entries(&self) -> &[(Prim, BoundingVolume<V>)] {
        &self.entries
    }

    /// Each volume (a `bound_test` event with its intervals), then its primitive if it is hit.
    #[inline(never)]
    pub fn walk<R: Recorder<V>, W: Visitor<V>>(
        &self,
        scene: &Scene<V>,
        ray: &Ray<V>,
        visitor: &mut W,
        stats: &mut Stats,
        rec: &mut R,
    ) {
        for (prim, volume) in &self.entries {
            stats.tests.bound += 1;
            let mut intervals = Vec::new();
            let h = volume.test(ray, |i| {
                if R::ENABLED {
                    intervals.push(i);
                }
            });
            rec.event(|| Event::BoundTest {
                volume: self.kind.name(),
                object: Some(object_ref(scene, *prim)),
                intervals,
                t_in: h.t_in,
                t_out: h.t_out,
                hit: h.hit,
            });
            if h.hit && visitor.visit(*prim, stats, rec) {
                return;
            }
        }
    }
}
