//! Flat primitives of 2D scenes (algorithm.md §3): segments, triangles and simple polygons, all
//! as lists of edges. Watertight like the 3D triangle: each vertex's side of the ray's line,
//! `f(P) = D × (P − O)`, is computed once per vertex, so two edges sharing a vertex agree on it.
//! Outward normal of an edge `d = b − a`: `(d_y, −d_x)/|d|`; for a polygon or triangle the
//! outward one whatever the winding (by the sign of its area); a segment keeps `(d_y, −d_x)`.
//! The side values decide whether an edge is crossed; the crossing's t is the edge line's,
//! `((a − O)·N)/(D·N)` as a 2D line computes it, so an edge lying on a line object meets a ray at
//! exactly the line's t and §6's index rule settles the tie.

use super::plane::Plane;
use super::{Facet, SurfaceHit};
use crate::geom::ray::Ray;
use crate::geom::{diff_of_products, Vector};
use glam::DVec2;

/// A segment (open, 2 vertices) or a closed simple polygon (3 or more vertices).
#[derive(Clone, Debug, PartialEq)]
pub struct Polygon {
    /// The vertices in file order.
    pub vertices: Vec<DVec2>,
    /// Closed (a triangle or polygon) or open (a segment).
    pub closed: bool,
    /// The outward unit normal of each edge `vertices[k] → vertices[k + 1]`.
    pub normals: Vec<DVec2>,
    kind: &'static str,
}

/// Twice the signed area (positive for counter-clockwise).
fn twice_area(vertices: &[DVec2]) -> f64 {
    let n = vertices.len();
    (0..n).map(|k| vertices[k].perp_dot(vertices[(k + 1) % n])).sum()
}

/// Whether the closed segments `p1p2` and `q1q2` share a point.
fn segments_touch(p1: DVec2, p2: DVec2, q1: DVec2, q2: DVec2) -> bool {
    let orient = |a: DVec2, b: DVec2, c: DVec2| (b - a).perp_dot(c - a);
    let on = |a: DVec2, b: DVec2, c: DVec2| {
        c.x >= a.x.min(b.x) && c.x <= a.x.max(b.x) && c.y >= a.y.min(b.y) && c.y <= a.y.max(b.y)
    };
    let (d1, d2) = (orient(q1, q2, p1), orient(q1, q2, p2));
    let (d3, d4) = (orient(p1, p2, q1), orient(p1, p2, q2));
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        return true;
    }
    (d1 == 0.0 && on(q1, q2, p1))
        || (d2 == 0.0 && on(q1, q2, p2))
        || (d3 == 0.0 && on(p1, p2, q1))
        || (d4 == 0.0 && on(p1, p2, q2))
}

/// Why a flat 2D primitive cannot be built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PolygonError {
    /// A segment of zero length, or an edge of zero length.
    ZeroLength,
    /// A triangle or polygon of zero area.
    ZeroArea,
    /// Two non-adjacent edges of the polygon cross or touch.
    NotSimple,
}

impl Polygon {
    /// The segment from `a` to `b`, normal `(d_y, −d_x)/|d|`.
    ///
    /// # Errors
    /// [`PolygonError::ZeroLength`] when `a == b`.
    pub fn segment(a: DVec2, b: DVec2) -> Result<Self, PolygonError> {
        let d = b - a;
        let normal = DVec2::new(d.y, -d.x).try_unit().ok_or(PolygonError::ZeroLength)?;
        Ok(Self { vertices: vec![a, b], closed: false, normals: vec![normal], kind: "segment" })
    }

    /// A closed polygon (a triangle when it has 3 vertices), either winding.
    ///
    /// # Errors
    /// [`PolygonError`] for a zero-length edge, a zero area or crossing edges.
    pub fn closed(vertices: Vec<DVec2>) -> Result<Self, PolygonError> {
        let n = vertices.len();
        let area = twice_area(&vertices);
        if !(area.abs() > 0.0) {
            return Err(PolygonError::ZeroArea);
        }
        for i in 0..n {
            for j in i + 2..n {
                if i == 0 && j == n - 1 {
                    continue;
                }
                let (p1, p2) = (vertices[i], vertices[(i + 1) % n]);
                let (q1, q2) = (vertices[j], vertices[(j + 1) % n]);
                if segments_touch(p1, p2, q1, q2) {
                    return Err(PolygonError::NotSimple);
                }
            }
        }
        // Clockwise polygons flip the edge normal so that it points outwards.
        let sign = if area > 0.0 { 1.0 } else { -1.0 };
        let mut normals = Vec::with_capacity(n);
        for k in 0..n {
            let d = vertices[(k + 1) % n] - vertices[k];
            normals.push(DVec2::new(d.y, -d.x).try_unit().ok_or(PolygonError::ZeroLength)? * sign);
        }
        let kind = if n == 3 { "triangle" } else { "polygon" };
        Ok(Self { vertices, closed: true, normals, kind })
    }

    fn edge_count(&self) -> usize {
        if self.closed {
            self.vertices.len()
        } else {
            1
        }
    }

    /// Every crossing of the ray's line with an edge: `(t, edge)`, in edge order.
    fn crossings(&self, ray: &Ray<DVec2>, mut each: impl FnMut(f64, usize)) {
        let d = ray.dir;
        // f(P) = D × (P − O), one value per vertex, shared by the two edges that meet there.
        let side = |p: DVec2| {
            let q = p - ray.origin;
            diff_of_products(d.x, q.y, d.y, q.x)
        };
        let along = |p: DVec2| (p - ray.origin).dot(d);
        let n = self.vertices.len();
        let mut f_a = side(self.vertices[0]);
        for k in 0..self.edge_count() {
            let (a, b) = (self.vertices[k], self.vertices[(k + 1) % n]);
            let f_b = side(b);
            let crosses = (f_a <= 0.0 && f_b >= 0.0) || (f_a >= 0.0 && f_b <= 0.0);
            // An edge lying on the line (f_a = f_b = 0) is edge-on: invisible.
            #[allow(clippy::float_cmp)]
            let edge_on = f_a == f_b;
            if crosses && !edge_on {
                // t by the edge's line, as a line object computes it (see the module doc); the
                // side values decided that the edge is crossed, and t stays within the edge's
                // extent along D (a near-grazing ray could round past it).
                let (num, denom) = Plane { point: a, normal: self.normals[k] }.crossing_terms(ray);
                let t = num / denom;
                let (t_a, t_b) = (along(a), along(b));
                let t = t.max(t_a.min(t_b)).min(t_a.max(t_b));
                if t.is_finite() {
                    each(t, k);
                }
            }
            f_a = f_b;
        }
    }
}

impl Facet<DVec2> for Polygon {
    fn hit(&self, ray: &Ray<DVec2>) -> Option<SurfaceHit<DVec2>> {
        let mut best: Option<(f64, usize)> = None;
        self.crossings(ray, |t, k| {
            // Strict: the first edge wins a tie (a ray through a vertex).
            if t > 0.0 && best.is_none_or(|(bt, _)| t < bt) {
                best = Some((t, k));
            }
        });
        let (t, k) = best?;
        // Re-project onto the edge's line.
        let a = self.vertices[k];
        let normal = self.normals[k];
        let raw = ray.at(t);
        let point = raw - normal * (raw - a).dot(normal);
        Some(SurfaceHit { t, point, normal })
    }
    fn roots(&self, ray: &Ray<DVec2>) -> Vec<f64> {
        let mut out = Vec::new();
        self.crossings(ray, |t, _| out.push(t));
        out.sort_by(f64::total_cmp);
        out.dedup();
        out
    }
    fn bounds(&self) -> (DVec2, DVec2) {
        let first = self.vertices[0];
        self.vertices.iter().fold((first, first), |(lo, hi), p| (lo.min(*p), hi.max(*p)))
    }
    fn scale(&self) -> f64 {
        self.vertices.iter().fold(0.0, |m, p| m.max(p.max_abs()))
    }
    fn points(&self) -> Vec<DVec2> {
        self.vertices.clone()
    }
    fn kind(&self) -> &'static str {
        self.kind
    }
    /// An edge meets the box, or (a closed polygon) the box lies inside it: then its centre
    /// does, by the even–odd count of the edges crossed by a ray towards +x.
    fn meets_box(&self, lo: DVec2, hi: DVec2) -> bool {
        let n = self.vertices.len();
        if (0..self.edge_count())
            .any(|k| segment_meets_box(self.vertices[k], self.vertices[(k + 1) % n], lo, hi))
        {
            return true;
        }
        if !self.closed {
            return false;
        }
        let c = (lo + hi) * 0.5;
        let mut inside = false;
        for k in 0..n {
            let (a, b) = (self.vertices[k], self.vertices[(k + 1) % n]);
            if (a.y > c.y) != (b.y > c.y) && c.x < a.x + (c.y - a.y) * (b.x - a.x) / (b.y - a.y) {
                inside = !inside;
            }
        }
        inside
    }
}

/// Whether the closed segment `ab` shares a point with the closed box `[lo, hi]`: no separating
/// axis among x, y and the segment's normal `n` (the box's projection on `n` is its centre's
/// `n·c` ± `|n_x|·h_x + |n_y|·h_y`, the segment's a single value `n·a`).
fn segment_meets_box(a: DVec2, b: DVec2, lo: DVec2, hi: DVec2) -> bool {
    if a.x.max(b.x) < lo.x || a.x.min(b.x) > hi.x || a.y.max(b.y) < lo.y || a.y.min(b.y) > hi.y {
        return false;
    }
    let d = b - a;
    let n = DVec2::new(-d.y, d.x);
    let (c, h) = ((lo + hi) * 0.5, (hi - lo) * 0.5);
    (n.dot(c) - n.dot(a)).abs() <= n.x.abs() * h.x + n.y.abs() * h.y
}

#[cfg(test)]
// These tests pin exact IEEE results on purpose (numerics.md gives bit-exact expectations).
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;

    #[test]
    fn segment_normal_convention() {
        let s = Polygon::segment(DVec2::ZERO, DVec2::new(1.0, 0.0)).unwrap();
        assert_eq!(s.normals[0], DVec2::new(0.0, -1.0));
    }

    #[test]
    fn polygon_normals_point_outward_whatever_the_winding() {
        let ccw = vec![DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y];
        let mut cw = ccw.clone();
        cw.reverse();
        for vs in [ccw, cw] {
            let p = Polygon::closed(vs).unwrap();
            let h = p.hit(&Ray::new(DVec2::new(0.5, 3.0), DVec2::NEG_Y)).unwrap();
            assert_eq!(h.normal, DVec2::Y);
            assert_eq!(h.t, 2.0);
        }
    }

    #[test]
    fn an_edge_on_a_line_meets_a_ray_at_the_lines_t_bit_for_bit() {
        // A prism standing on the floor y = −1, its bottom edge on the floor line: rays from
        // inside (a transmitted ray) and from above meet both at the same t, so the tie is exact
        // and §6's object index decides, not rounding.
        use crate::shape::plane::Plane;
        let floor = Plane { point: DVec2::new(0.0, -1.0), normal: DVec2::Y };
        let prism = Polygon::closed(vec![DVec2::new(0.8, -1.0), DVec2::new(2.0, -1.0), DVec2::new(1.2, 1.2)])
            .unwrap();
        let mut met = 0;
        for k in 0..200 {
            let f = f64::from(k) / 200.0;
            let origin = DVec2::new(0.9 + 0.7 * f, -0.99 + 0.9 * f);
            let dir = DVec2::new(0.3 - 0.6 * f, -1.0).normalize();
            let ray = Ray::new(origin, dir);
            let (Some(edge), Some(line)) = (prism.hit(&ray), floor.hit(&ray)) else { continue };
            if edge.normal == DVec2::NEG_Y {
                assert_eq!(edge.t, line.t, "ray {k}");
                met += 1;
            }
        }
        assert!(met > 100, "{met} rays met the bottom edge");
    }

    #[test]
    fn a_segment_on_a_boxs_side_meets_a_ray_at_the_boxs_t_bit_for_bit() {
        // Found by fuzz.py --snap (seed 6, scene 131): the segment y = 0.25 runs along the bottom
        // side of the box [0, 0.5] × [0.25, 1.25]. The box's slab gives t = (0.25 − O_y)/D_y and
        // the segment its line's ((P − O)·N)/(D·N) with N = (0, −1): the same quotient exactly,
        // so the tie is exact and §6's object index decides, not rounding (an edge function
        // interpolated between the ends gives a t 3 ulps short on that ray).
        use crate::shape::aabox::AaBox;
        let side = Polygon::segment(DVec2::new(-0.5, 0.25), DVec2::new(1.25, 0.25)).unwrap();
        let block = AaBox { min: DVec2::new(0.0, 0.25), max: DVec2::new(0.5, 1.25) };
        let found = Ray::new(
            DVec2::new(7.105_427_357_601_002e-14, 0.259_734_539_181_147_03),
            DVec2::new(0.990_490_836_197_767_5, -0.137_578_717_134_037_05),
        );
        // That ray: both at the slab's quotient (0.25 − O_y)/D_y.
        let t = (0.25 - found.origin.y) / found.dir.y;
        assert_eq!((side.hit(&found).map(|h| h.t), block.hit(&found).map(|h| h.t)), (Some(t), Some(t)));
        let mut rays = vec![found];
        for k in 0..200 {
            let f = f64::from(k) / 200.0;
            // From inside the box down onto its bottom side, and from below up onto it.
            rays.push(Ray::new(
                DVec2::new(0.05 + 0.4 * f, 0.26 + f),
                DVec2::new(0.3 - 0.6 * f, -1.0).normalize(),
            ));
            rays.push(Ray::new(
                DVec2::new(0.45 - 0.4 * f, -0.5 - f),
                DVec2::new(0.6 * f - 0.3, 1.0).normalize(),
            ));
        }
        let mut met = 0;
        for (k, ray) in rays.iter().enumerate() {
            let (Some(edge), Some(face)) = (side.hit(ray), block.hit(ray)) else { continue };
            if face.point.y == 0.25 {
                assert_eq!(edge.t, face.t, "ray {k}");
                met += 1;
            }
        }
        assert!(met > 300, "{met} rays met the bottom side");
    }

    #[test]
    fn through_a_shared_vertex_is_hit() {
        let p = Polygon::closed(vec![DVec2::ZERO, DVec2::new(2.0, 0.0), DVec2::new(1.0, 1.0)]).unwrap();
        let d = DVec2::new(1.0, 1.0).normalize();
        let h = p.hit(&Ray::new(DVec2::new(0.0, 0.0) - d, d));
        assert!(h.is_some());
    }

    #[test]
    fn degenerate_and_self_crossing_polygons_are_rejected() {
        assert_eq!(
            Polygon::closed(vec![DVec2::ZERO, DVec2::X, DVec2::new(2.0, 0.0)]),
            Err(PolygonError::ZeroArea)
        );
        let bow = vec![DVec2::ZERO, DVec2::splat(2.0), DVec2::new(2.0, 0.0), DVec2::Y];
        assert_eq!(Polygon::closed(bow), Err(PolygonError::NotSimple));
        assert_eq!(Polygon::segment(DVec2::X, DVec2::X), Err(PolygonError::ZeroLength));
    }
}
