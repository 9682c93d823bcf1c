//! The closed list of events a trace can contain (product.md "The trace document"), and the
//! pieces of a ray node: its kind, its hit and its per-light terms.

use crate::scene::material::Rgb;

/// The kind of a ray node.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RayKind {
    /// From the eye through the image plane (level 1).
    Primary,
    /// The mirror ray R.
    Reflected,
    /// The refracted ray T.
    Transmitted,
}

impl RayKind {
    /// The name in the trace document.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Primary => "primary",
            Self::Reflected => "reflected",
            Self::Transmitted => "transmitted",
        }
    }
}

/// Which object: its index, and for a mesh the triangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ObjectRef {
    /// Index in the scene's `objects`.
    pub index: usize,
    /// For a mesh, the triangle's index in its OBJ.
    pub triangle: Option<usize>,
}

/// A node's hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NodeHit<V> {
    /// The object hit.
    pub object: ObjectRef,
    /// The distance along the ray.
    pub t: f64,
    /// The hit point I.
    pub point: V,
    /// The outward normal N.
    pub normal: V,
    /// `D·N ≤ 0`.
    pub entering: bool,
}

/// One light's contribution at a hit (§5).
#[derive(Clone, Debug, PartialEq)]
pub struct LightTerm<V> {
    /// The light's index.
    pub light: usize,
    /// The unit vector from I to the light (None when the light sits at I).
    pub l: Option<V>,
    /// `N_f·L`.
    pub n_dot_l: f64,
    /// 1 if `N·L > 0`, else 0.
    pub lum: f64,
    /// The attenuation `fat`.
    pub fat: f64,
    /// The shadow factor s; None when no shadow ray was cast (`lum = 0`).
    pub shadow: Option<f64>,
    /// `Isrc·fat·s·kd·(N·L)`.
    pub diffuse: Rgb,
    /// `Isrc·fat·s·ks·(N·H)^n`.
    pub specular: Rgb,
}

/// An occluder of a shadow ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Occluder {
    /// The object.
    pub object: ObjectRef,
    /// Its kt (0 for an opaque object).
    pub kt: f64,
}

/// Something the tracer did.
#[derive(Clone, Debug, PartialEq)]
pub enum Event<V> {
    /// A primary ray left the camera.
    PrimaryRay {
        /// Origin.
        origin: V,
        /// Unit direction.
        direction: V,
        /// `[u, v]` (`[u]` in 2D), or empty for a ray given by hand.
        uv: Vec<f64>,
    },
    /// A ray was tested against an object.
    ObjectTest {
        /// The object.
        object: ObjectRef,
        /// Every real root, ascending, whatever its sign.
        roots: Vec<f64>,
        /// The t taken, if any.
        accepted: Option<f64>,
    },
    /// The nearest hit of a ray.
    Hit {
        /// The object hit.
        object: ObjectRef,
        /// Distance.
        t: f64,
        /// I.
        point: V,
        /// The outward N.
        normal: V,
        /// `D·N ≤ 0`.
        entering: bool,
    },
    /// The ray hit nothing: the background.
    Miss {
        /// The background colour.
        color: Rgb,
    },
    /// A shadow ray towards a light and what it met.
    ShadowRay {
        /// The light's index.
        light: usize,
        /// The offset origin.
        origin: V,
        /// Unit direction towards the light.
        direction: V,
        /// `d_L`, from the offset origin to the light.
        distance: f64,
        /// The distinct objects met with `0 < t < d_L`.
        occluders: Vec<Occluder>,
        /// The product of their kt.
        s: f64,
    },
    /// A reflected ray was spawned.
    Reflect {
        /// Offset origin.
        origin: V,
        /// Unit direction R.
        direction: V,
        /// The spawn offset δ.
        offset: f64,
    },
    /// A transmitted ray was spawned.
    Refract {
        /// Offset origin.
        origin: V,
        /// Unit direction T.
        direction: V,
        /// The spawn offset δ.
        offset: f64,
        /// Index on the incoming side.
        n1: f64,
        /// Index on the far side.
        n2: f64,
    },
    /// `k < 0`: no T ray.
    TotalInternalReflection {
        /// `k = (1 − η²) + (η·c)²`.
        k: f64,
        /// Index on the incoming side.
        n1: f64,
        /// Index on the far side.
        n2: f64,
    },
    /// A node at this level may not spawn children (`level > max_depth`).
    DepthLimit {
        /// The node's level.
        level: u32,
    },
    /// A ray against a bounding volume (§9): per axis or slab the interval `[t_in, t_out]`.
    BoundTest {
        /// `sphere`, `aabb` or `kdop`.
        volume: &'static str,
        /// The object it bounds (per-object bounds), if any.
        object: Option<ObjectRef>,
        /// `[t_near, t_far]` per axis or slab (a sphere: its two roots, or none).
        intervals: Vec<[f64; 2]>,
        /// max of the `t_near`.
        t_in: f64,
        /// min of the `t_far`.
        t_out: f64,
        /// Whether the ray meets the volume (closed: `t_in ≤ t_out`, `t_out ≥ 0`).
        hit: bool,
    },
    /// A hierarchy node visited.
    NodeVisit {
        /// `bvh` or `octree`.
        structure: &'static str,
        /// The node's index in the structure.
        node: usize,
        /// Its depth (root = 0).
        depth: u32,
        /// Where the ray enters its volume.
        t_in: f64,
        /// Where it leaves.
        t_out: f64,
    },
    /// A hierarchy node whose box the ray meets, skipped unopened because its entry lies beyond
    /// the nearest hit found so far (§11's prune rule, `t_in > t_best`): the lecture's reason
    /// for not descending, distinct from a missed box.
    NodeSkip {
        /// `bvh` or `octree`.
        structure: &'static str,
        /// The node's index in the structure.
        node: usize,
        /// Where the ray enters its volume.
        t_in: f64,
        /// The nearest hit's t when the node was skipped (a shadow ray: its light's distance).
        t_best: f64,
    },
    /// A grid cell stepped into by the 3D DDA (Amanatides–Woo).
    VoxelStep {
        /// The cell's integer coordinates.
        cell: Vec<i64>,
        /// tMax per axis: the t of the next crossing of each axis.
        t_max: Vec<f64>,
        /// tDelta per axis: the t between crossings of each axis.
        t_delta: Vec<f64>,
        /// The objects tested in this cell (after the mailbox).
        objects: Vec<ObjectRef>,
    },
    /// An anti-aliasing sample.
    Sample {
        /// `[u, v]` (`[u]` in 2D).
        uv: Vec<f64>,
        /// Subdivision level (corners: 0).
        level: u32,
        /// Its colour.
        color: Rgb,
        /// Taken from the cache instead of traced.
        reused: bool,
    },
}

impl<V> Event<V> {
    /// The `kind` string of the trace document.
    #[must_use]
    pub fn kind(&self) -> &'static str {
        match self {
            Self::PrimaryRay { .. } => "primary_ray",
            Self::ObjectTest { .. } => "object_test",
            Self::Hit { .. } => "hit",
            Self::Miss { .. } => "miss",
            Self::ShadowRay { .. } => "shadow_ray",
            Self::Reflect { .. } => "reflect",
            Self::Refract { .. } => "refract",
            Self::TotalInternalReflection { .. } => "total_internal_reflection",
            Self::DepthLimit { .. } => "depth_limit",
            Self::Sample { .. } => "sample",
            Self::BoundTest { .. } => "bound_test",
            Self::NodeVisit { .. } => "node_visit",
            Self::NodeSkip { .. } => "node_skip",
            Self::VoxelStep { .. } => "voxel_step",
        }
    }
}
