//! An axis-aligned box in 3D, a rectangle in 2D (algorithm.md §9 "slab test"), as an object:
//! tested exactly (not widened); the normal is the axis normal of the face hit, on an edge or
//! corner the axis that set `t_in` (ties in the order x, y, z), §3.

use super::SurfaceHit;
use crate::geom::ray::Ray;
use crate::geom::slab::box_crossing;
use crate::geom::Vector;

/// The box `[min, max]`, `min < max` on every axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AaBox<V> {
    /// The lower corner.
    pub min: V,
    /// The upper corner.
    pub max: V,
}

impl<V: Vector> AaBox<V> {
    /// The entry `t_in` if it is ahead, else the exit `t_out` (origin inside, numerics A6).
    #[inline]
    pub fn hit(&self, ray: &Ray<V>) -> Option<SurfaceHit<V>> {
        let c = box_crossing(ray, self.min, self.max, |_, _| {});
        if !(c.t_in <= c.t_out) {
            return None;
        }
        let (t, axis, exiting) = if c.t_in > 0.0 {
            (c.t_in, c.axis_in, false)
        } else if c.t_out > 0.0 {
            (c.t_out, c.axis_out, true)
        } else {
            return None;
        };
        if !t.is_finite() {
            return None;
        }
        // The face crossed: entering through the min face when D points up the axis.
        let towards_max = ray.dir[axis] > 0.0;
        let on_max_face = towards_max == exiting;
        let mut point = ray.at(t);
        point[axis] = if on_max_face { self.max[axis] } else { self.min[axis] };
        let normal = V::axis(axis) * if on_max_face { 1.0 } else { -1.0 };
        Some(SurfaceHit { t, point, normal })
    }
    /// `[t_in, t_out]` when the line meets the box.
    #[must_use]
    pub fn roots(&self, ray: &Ray<V>) -> Vec<f64> {
        let c = box_crossing(ray, self.min, self.max, |_, _| {});
        if c.t_in <= c.t_out && c.t_in.is_finite() && c.t_out.is_finite() {
            // A touch (corner or tangent face) is one root, not two equal ones.
            #[allow(clippy::float_cmp)]
            let touch = c.t_in == c.t_out;
            if touch {
                vec![c.t_in]
            } else {
                vec![c.t_in, c.t_out]
            }
        } else {
            vec![]
        }
    }
}

#[cfg(test)]
// These tests pin exact IEEE results on purpose (numerics.md gives bit-exact expectations).
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn a6_origin_inside_hits_the_far_face_leaving() {
        let b = AaBox { min: DVec3::new(1.0, 0.0, 0.0), max: DVec3::new(2.0, 1.0, 1.0) };
        let h = b.hit(&Ray::new(DVec3::new(1.5, 0.5, 0.5), DVec3::X)).unwrap();
        assert_eq!(h.t, 0.5);
        assert_eq!(h.normal, DVec3::X);
        assert_eq!(h.point.x, 2.0);
    }

    #[test]
    fn a7_edge_normal_is_x() {
        let b = AaBox { min: DVec3::ZERO, max: DVec3::ONE };
        let d = DVec3::new(1.0, 1.0, 0.0).normalize();
        let h = b.hit(&Ray::new(DVec3::new(-1.0, -1.0, 0.5), d)).unwrap();
        assert_eq!(h.normal, DVec3::NEG_X);
        assert!(d.dot(h.normal) < 0.0);
    }
}
