//! Acceleration structures (algorithm.md §9): every one answers the same two questions — the
//! nearest hit of a ray, and the occluders of a shadow segment — and must give exactly the answer
//! of brute force (`list`), equal t broken by the object index (§6).

pub mod list;

use crate::geom::ray::Ray;
use crate::record::event::{Event, ObjectRef};
use crate::record::Recorder;
use crate::scene::Scene;
use crate::shape::{Dim, SurfaceHit};
use crate::trace::stats::Stats;

/// The `--accel` choice.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AccelKind {
    /// Brute force: every object, in index order.
    None,
}

impl AccelKind {
    /// The name used on the command line and in statistics.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::None => "none",
        }
    }
}

/// A built acceleration structure over a scene's objects.
#[derive(Clone, Debug)]
pub struct Accel<V: Dim> {
    kind: AccelKind,
    _dim: std::marker::PhantomData<V>,
}

impl<V: Dim> Accel<V> {
    /// Builds the structure of `kind` over `scene` (after the scene is complete and valid).
    #[must_use]
    pub fn build(_scene: &Scene<V>, kind: AccelKind) -> Self {
        Self { kind, _dim: std::marker::PhantomData }
    }
    /// Which structure this is.
    #[must_use]
    pub fn kind(&self) -> AccelKind {
        self.kind
    }
    /// The nearest hit with `t > 0`; equal t goes to the smaller object index.
    #[inline]
    pub fn nearest<R: Recorder<V>>(
        &self,
        scene: &Scene<V>,
        ray: &Ray<V>,
        stats: &mut Stats,
        rec: &mut R,
    ) -> Option<(ObjectRef, SurfaceHit<V>)> {
        match self.kind {
            AccelKind::None => list::nearest(scene, ray, stats, rec),
        }
    }
    /// Reports each distinct object with a hit at `0 < t < d_L` to `on` (with its t), until `on`
    /// returns false (an opaque occluder ends the search).
    #[inline]
    pub fn occluders<R: Recorder<V>>(
        &self,
        scene: &Scene<V>,
        ray: &Ray<V>,
        d_l: f64,
        stats: &mut Stats,
        rec: &mut R,
        on: impl FnMut(ObjectRef) -> bool,
    ) {
        match self.kind {
            AccelKind::None => list::occluders(scene, ray, d_l, stats, rec, on),
        }
    }
}

/// One ray–object test, counted and recorded (`object_test` with every root).
#[inline]
pub fn test_object<V: Dim, R: Recorder<V>>(
    scene: &Scene<V>,
    index: usize,
    ray: &Ray<V>,
    stats: &mut Stats,
    rec: &mut R,
) -> Option<SurfaceHit<V>> {
    stats.tests.object += 1;
    let shape = &scene.objects[index].shape;
    let hit = shape.hit(ray);
    rec.event(|| Event::ObjectTest {
        object: ObjectRef { index, triangle: None },
        roots: shape.roots(ray),
        accepted: hit.map(|h| h.t),
    });
    hit
}
