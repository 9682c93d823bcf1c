//! What the figures read of a built structure: its volumes, its nodes or its cells
//! ([`Layout`], [`TreeNode`]), never its walk.

use super::Prim;
use crate::bounds::aabb::Aabb;
use crate::bounds::BoundingVolume;
use crate::shape::Dim;

/// A built structure as a figure draws it: its volumes, its nodes or its cells.
#[derive(Clone, Debug)]
pub enum Layout<'a, V: Dim> {
    /// Brute force: nothing to draw.
    List,
    /// One bounding volume per primitive, in object order.
    Volumes(&'a [(Prim, BoundingVolume<V>)]),
    /// A hierarchy (BVH, octree): entry `k` is the node that `node_visit` events call `k`.
    Tree(Vec<TreeNode<V>>),
    /// A regular grid: its box and its cells per axis.
    Grid {
        /// The grid's box.
        bounds: Aabb<V>,
        /// Cells per axis.
        cells: Vec<usize>,
    },
}

/// A node of a hierarchy, for drawing.
#[derive(Clone, Debug, PartialEq)]
pub struct TreeNode<V> {
    /// Its box.
    pub bounds: Aabb<V>,
    /// Its depth (the root is 0).
    pub depth: u32,
    /// Its children's node numbers (none for a leaf).
    pub children: Vec<usize>,
    /// A leaf's primitives.
    pub prims: Vec<Prim>,
}
