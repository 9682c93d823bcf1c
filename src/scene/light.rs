//! Point lights (algorithm.md §5): position, intensity Isrc and the attenuation
//! `fat = min(1, 1/(c0 + c1·d + c2·d²))`.

use super::material::Rgb;

/// A point light.
#[derive(Clone, Debug, PartialEq)]
pub struct Light<V> {
    /// Where it is.
    pub position: V,
    /// Isrc (RGB); default white.
    pub intensity: Rgb,
    /// `(c0, c1, c2)`, each ≥ 0, not all 0; default `(1, 0, 0)`.
    pub attenuation: [f64; 3],
}

impl<V> Light<V> {
    /// §5 convention: `fat = min(1, 1/(c0 + c1·d + c2·d²))`.
    #[must_use]
    pub fn fat(&self, d: f64) -> f64 {
        let [c0, c1, c2] = self.attenuation;
        (1.0 / (c0 + c1 * d + c2 * d * d)).min(1.0)
    }
}
