//! A ray `r(t) = O + t·D` (algorithm.md §2): origin, unit direction, and the point at a distance.

use super::Vector;

/// A ray with origin `O` and unit direction `D`; with `|D| = 1` its `t` is a Euclidean distance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray<V> {
    /// The origin O.
    pub origin: V,
    /// The unit direction D.
    pub dir: V,
}

impl<V: Vector> Ray<V> {
    /// A ray from `origin` along `dir` (the caller passes a unit vector).
    #[must_use]
    pub fn new(origin: V, dir: V) -> Self {
        Self { origin, dir }
    }
    /// The point `r(t) = O + t·D`.
    #[must_use]
    pub fn at(&self, t: f64) -> V {
        self.origin + self.dir * t
    }
}
