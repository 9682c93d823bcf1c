//! Camera bases (algorithm.md §2 "Camera frame"): `w = normalize(O − C)`, in 3D
//! `u = normalize(up × w)`, `v = w × u`; in 2D `u = (w_y, −w_x)`.

use glam::{DVec2, DVec3};

/// Why a camera frame cannot be built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameError {
    /// `eye == center`: no view direction.
    EyeIsCenter,
    /// `up` is parallel to `eye − center` (`|up × w| < 1e-12·|up|`) or zero.
    UpParallel,
}

/// The observer's orthonormal frame; the camera looks along `−w`. In 2D `v` is zero.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame<V> {
    /// Right.
    pub u: V,
    /// Up (zero in 2D).
    pub v: V,
    /// Backwards: from the centre towards the eye.
    pub w: V,
}

/// `lookAt(eye O, centre C, up)` in 3D, §2.
///
/// # Errors
/// [`FrameError`] when `O == C` or `up` is parallel to `O − C` (a scene error, never a NaN).
pub fn look_at(eye: DVec3, center: DVec3, up: DVec3) -> Result<Frame<DVec3>, FrameError> {
    let w = crate::Vector::try_unit(eye - center).ok_or(FrameError::EyeIsCenter)?;
    let up = crate::Vector::try_unit(up).ok_or(FrameError::UpParallel)?;
    let cross = up.cross(w);
    if cross.length() < 1e-12 {
        return Err(FrameError::UpParallel);
    }
    let u = cross.normalize();
    let v = w.cross(u);
    Ok(Frame { u, v, w })
}

/// The 2D frame, §2 "2D scenes": `w = normalize(O − C)`, `u = (w_y, −w_x)` (w turned by −90°).
///
/// # Errors
/// [`FrameError::EyeIsCenter`] when `O == C`.
pub fn look_at_2d(eye: DVec2, center: DVec2) -> Result<Frame<DVec2>, FrameError> {
    let w = crate::Vector::try_unit(eye - center).ok_or(FrameError::EyeIsCenter)?;
    Ok(Frame { u: DVec2::new(w.y, -w.x), v: DVec2::ZERO, w })
}

#[cfg(test)]
// These tests pin exact IEEE results on purpose (numerics.md gives bit-exact expectations).
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;

    #[test]
    fn g3_degenerate_look_at() {
        let eye = DVec3::new(0.0, 0.0, 5.0);
        assert_eq!(look_at(eye, DVec3::ZERO, DVec3::Z), Err(FrameError::UpParallel));
        assert_eq!(look_at(eye, DVec3::ZERO, DVec3::NEG_Z), Err(FrameError::UpParallel));
        assert_eq!(look_at(eye, eye, DVec3::Y), Err(FrameError::EyeIsCenter));
        let f = look_at(eye, DVec3::ZERO, DVec3::new(1e-6, 0.0, 1.0)).unwrap();
        assert_eq!(f.u, DVec3::new(0.0, -1.0, 0.0));
        assert_eq!(f.v, DVec3::new(1.0, 0.0, 0.0));
    }

    #[test]
    fn g2_tiny_and_huge_up() {
        let eye = DVec3::new(0.0, 0.0, 5.0);
        for up in [DVec3::new(0.0, 1e-200, 0.0), DVec3::new(0.0, 1e200, 0.0)] {
            let f = look_at(eye, DVec3::ZERO, up).unwrap();
            assert_eq!(f.v, DVec3::Y);
        }
    }

    #[test]
    fn two_d_frames_turn_minus_90_degrees() {
        let f = look_at_2d(DVec2::new(0.0, 5.0), DVec2::ZERO).unwrap();
        assert_eq!(f.u, DVec2::new(1.0, 0.0));
        let f = look_at_2d(DVec2::ZERO, DVec2::new(1.0, 0.0)).unwrap();
        assert_eq!(f.u, DVec2::new(0.0, 1.0));
    }
}
