//! The self-intersection policy (algorithm.md §3, §11 "The spawn offset"): a secondary or shadow
//! ray starts at the hit point pushed off the surface, along ±N_f, on the side it travels to.
//!
//! The offset is `δ = 2⁻⁴⁴·M`, M the largest magnitude at hand ([`offset_distance`]).

use super::Vector;

/// `2^-44`, the relative size of the spawn offset (about 256 ulps of the magnitude M).
pub const OFFSET_SCALE: f64 = 1.0 / 17_592_186_044_416.0;

/// The spawn offset `δ = 2^-44 · M` with `M` the largest of `‖I‖∞`, `‖O‖∞` of the incoming ray,
/// its `t`, and the object's scale (§11). Including O and t keeps `δ > 0` at `I = 0`.
#[inline]
#[must_use]
pub fn offset_distance<V: Vector>(point: V, ray_origin: V, t: f64, object_scale: f64) -> f64 {
    let m = point.max_abs().max(ray_origin.max_abs()).max(t.abs()).max(object_scale);
    OFFSET_SCALE * m
}

/// The origin of a ray leaving `point` along `dir`: `I + δ·N_f` if `dir·N_f ≥ 0` (reflected and
/// shadow rays, a grazing T), else `I − δ·N_f` (transmitted rays), §11.
#[inline]
#[must_use]
pub fn spawn_origin<V: Vector>(point: V, n_f: V, dir: V, delta: f64) -> V {
    if dir.dot(n_f) >= 0.0 {
        point + n_f * delta
    } else {
        point - n_f * delta
    }
}

#[cfg(test)]
// These tests pin exact IEEE results on purpose (numerics.md gives bit-exact expectations).
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn e4_offset_is_positive_at_the_origin() {
        let delta = offset_distance(DVec3::ZERO, DVec3::new(0.0, 1.0, 5.0), 5.1, 0.0);
        assert!(delta > 0.0 && delta < 1e-12, "{delta}");
    }

    #[test]
    fn side_follows_the_direction() {
        let n = DVec3::Y;
        assert!(spawn_origin(DVec3::ZERO, n, DVec3::X, 1.0).y > 0.0);
        assert!(spawn_origin(DVec3::ZERO, n, -DVec3::Y, 1.0).y < 0.0);
    }
}
