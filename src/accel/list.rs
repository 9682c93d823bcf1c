//! Brute force (algorithm.md §7: `O(n)` tests per ray): every object in index order, a mesh's
//! triangles in their order. The oracle every other structure is tested against.

use super::{Prim, Visitor};
use crate::record::stats::Stats;
use crate::record::Recorder;
use crate::scene::Scene;
use crate::shape::Dim;

/// Hands every primitive of every object, in index order, to the visitor.
#[inline(never)]
pub fn walk<V: Dim, R: Recorder<V>, W: Visitor<V>>(
    scene: &Scene<V>,
    visitor: &mut W,
    stats: &mut Stats,
    rec: &mut R,
) {
    for (object, o) in scene.objects.iter().enumerate() {
        for part in 0..o.shape.parts() {
            // Indices fit: Accel::build checked that objects and parts fit in u32.
            #[allow(clippy::cast_possible_truncation)]
            let prim = Prim { object: object as u32, part: part as u32 };
            if visitor.visit(prim, stats, rec) {
                return;
            }
        }
    }
}
