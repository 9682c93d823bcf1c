//! The camera (algorithm.md §2): the lookAt frame, the view window `(l, t)`–`(r, b)` at distance
//! `p`, the resolution, pixel → (u, v) with rows counted from the bottom, and the primary rays of
//! the orthographic and perspective projections; in 2D the same on the line of the `u` axis.

use crate::geom::frame::Frame;
use crate::geom::ray::Ray;
use crate::geom::Vector;

/// Orthographic (parallel rays along −w) or perspective (rays from the eye through S).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Projection {
    /// Rays from the window point S along `−w`.
    Orthographic,
    /// Rays from the observer O through the window point S.
    Perspective,
}

/// The view window on the image plane; in 2D `b = t = 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Window {
    /// Left edge (u).
    pub l: f64,
    /// Right edge (u), `r > l`.
    pub r: f64,
    /// Bottom edge (v).
    pub b: f64,
    /// Top edge (v), `t > b`.
    pub t: f64,
}

/// The camera of a valid scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Camera<V> {
    /// The observer O.
    pub eye: V,
    /// The point looked at, C.
    pub center: V,
    /// The observer frame (u, v, w).
    pub frame: Frame<V>,
    /// The `up` vector lookAt was given (as written, not normalised; zero in 2D).
    pub up: V,
    /// Orthographic or perspective.
    pub projection: Projection,
    /// Distance from the observer to the image plane, `p > 0`.
    pub p: f64,
    /// The view window.
    pub window: Window,
    /// `Nx` (columns).
    pub nx: usize,
    /// `Ny` (rows); 1 in 2D.
    pub ny: usize,
}

impl<V: Vector> Camera<V> {
    /// The u of a point `x` pixels from the left edge: `u = l + (r − l)·x/Nx`
    /// (§2 with `x = i + 0.5` for a pixel centre; §8 with `x = i` for a corner).
    #[must_use]
    pub fn u_at(&self, x: f64) -> f64 {
        let w = &self.window;
        w.l + (w.r - w.l) * x / self.nx as f64
    }
    /// The v of a point `y` pixels from the bottom edge: `v = b + (t − b)·y/Ny` (0 in 2D).
    #[must_use]
    pub fn v_at(&self, y: f64) -> f64 {
        if V::DIM == 2 {
            return 0.0;
        }
        let w = &self.window;
        w.b + (w.t - w.b) * y / self.ny as f64
    }
    /// The centre of pixel `(i, j)`, column `i` from the left, row `j` from the **bottom** (§2):
    /// `u = l + (r − l)·(i + 0.5)/Nx`, `v = b + (t − b)·(j + 0.5)/Ny`.
    #[must_use]
    pub fn pixel_center(&self, i: usize, j: usize) -> (f64, f64) {
        (self.u_at(i as f64 + 0.5), self.v_at(j as f64 + 0.5))
    }
    /// The window point `S = O + u·u + v·v − p·w`.
    #[must_use]
    pub fn window_point(&self, u: f64, v: f64) -> V {
        let f = &self.frame;
        self.eye + f.u * u + f.v * v - f.w * self.p
    }
    /// The primary ray through `(u, v)`: orthographic from S along `−w`; perspective from O along
    /// `D = S − O`, normalised (§2).
    #[must_use]
    pub fn primary_ray(&self, u: f64, v: f64) -> Ray<V> {
        let s = self.window_point(u, v);
        match self.projection {
            Projection::Orthographic => Ray::new(s, -self.frame.w),
            Projection::Perspective => {
                // A valid scene has p > 0, so S − O is never zero.
                let d = (s - self.eye).try_unit().unwrap_or(-self.frame.w);
                Ray::new(self.eye, d)
            }
        }
    }
}
