//! Counters of rays by kind and tests by kind: plain integers, always on (pbrt's `STAT_COUNTER`),
//! merged across threads after a render.
//!
//! The tracer counts the rays and `accel`'s tests count the tests; both count whatever the
//! recorder.

use super::event::RayKind;
use std::ops::AddAssign;

/// Rays traced, by kind.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RayCounts {
    /// Primary rays (one per pixel centre, or per sample).
    pub primary: u64,
    /// Reflected rays R.
    pub reflected: u64,
    /// Transmitted rays T.
    pub transmitted: u64,
    /// Shadow rays (one per light with `lum = 1` at each hit).
    pub shadow: u64,
}

impl RayCounts {
    /// All rays.
    #[must_use]
    pub fn total(&self) -> u64 {
        self.primary + self.reflected + self.transmitted + self.shadow
    }
    /// One more ray of `kind`.
    #[inline(always)]
    pub fn count(&mut self, kind: RayKind) {
        match kind {
            RayKind::Primary => self.primary += 1,
            RayKind::Reflected => self.reflected += 1,
            RayKind::Transmitted => self.transmitted += 1,
        }
    }
}

/// Tests done, by kind.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TestCounts {
    /// Ray–object intersection tests.
    pub object: u64,
    /// Ray–bounding-volume tests.
    pub bound: u64,
    /// Hierarchy nodes visited (BVH, octree).
    pub node: u64,
    /// Grid cells stepped through.
    pub voxel: u64,
}

/// Everything counted while tracing.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    /// Rays by kind.
    pub rays: RayCounts,
    /// Tests by kind.
    pub tests: TestCounts,
}

impl AddAssign for Stats {
    fn add_assign(&mut self, o: Stats) {
        self.rays.primary += o.rays.primary;
        self.rays.reflected += o.rays.reflected;
        self.rays.transmitted += o.rays.transmitted;
        self.rays.shadow += o.rays.shadow;
        self.tests.object += o.tests.object;
        self.tests.bound += o.tests.bound;
        self.tests.node += o.tests.node;
        self.tests.voxel += o.tests.voxel;
    }
}
