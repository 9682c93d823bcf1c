//! Where a drawing's world lands on its canvas: the world rectangle shown ([`View`], y up), a
//! rectangle in canvas pixels ([`PxRect`], y down, with the overlap and crossing tests of label
//! placement), and the one uniform world → pixel map ([`Transform`]).

use glam::DVec2;

/// A rectangle of the world, `[xmin, xmax] × [ymin, ymax]`, y up.
///
/// Guarantees: all four bounds are finite, `xmin < xmax` and `ymin < ymax`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    xmin: f64,
    xmax: f64,
    ymin: f64,
    ymax: f64,
}

impl View {
    /// The square [−1, 1]², a new drawing's view.
    pub const SQUARE: Self = Self { xmin: -1.0, xmax: 1.0, ymin: -1.0, ymax: 1.0 };

    /// The rectangle `[xmin, xmax] × [ymin, ymax]`, or `None` unless the bounds are finite and
    /// each minimum is below its maximum.
    #[must_use]
    pub fn new(xmin: f64, xmax: f64, ymin: f64, ymax: f64) -> Option<Self> {
        let finite = [xmin, xmax, ymin, ymax].iter().all(|v| v.is_finite());
        (finite && xmin < xmax && ymin < ymax).then_some(Self { xmin, xmax, ymin, ymax })
    }

    /// The smallest rectangle of aspect `aspect` (width / height) that holds every finite point
    /// of `points` with a margin of `margin` times the larger extent on each side, centred on
    /// the points. A single point (or a flat set) gets an extent of 1 along its flat axes.
    /// `None` if no point is finite, or if `margin` or `aspect` is not finite and positive
    /// (`margin` may be 0).
    #[must_use]
    pub fn fit(points: &[DVec2], margin: f64, aspect: f64) -> Option<Self> {
        if !(margin.is_finite() && margin >= 0.0 && aspect.is_finite() && aspect > 0.0) {
            return None;
        }
        let mut finite = points.iter().filter(|p| p.is_finite());
        let first = *finite.next()?;
        let (lo, hi) = finite.fold((first, first), |(lo, hi), p| (lo.min(*p), hi.max(*p)));
        let center = (lo + hi) / 2.0;
        let mut extent = hi - lo;
        let largest = extent.max_element();
        let fallback = if largest > 0.0 { largest } else { 1.0 };
        if extent.x <= 0.0 {
            extent.x = fallback;
        }
        if extent.y <= 0.0 {
            extent.y = fallback;
        }
        let pad = margin * extent.max_element();
        let mut w = extent.x + 2.0 * pad;
        let mut h = extent.y + 2.0 * pad;
        if w / h < aspect {
            w = h * aspect;
        } else {
            h = w / aspect;
        }
        Self::new(center.x - w / 2.0, center.x + w / 2.0, center.y - h / 2.0, center.y + h / 2.0)
    }

    /// The left edge.
    #[must_use]
    pub fn xmin(&self) -> f64 {
        self.xmin
    }
    /// The right edge.
    #[must_use]
    pub fn xmax(&self) -> f64 {
        self.xmax
    }
    /// The bottom edge.
    #[must_use]
    pub fn ymin(&self) -> f64 {
        self.ymin
    }
    /// The top edge.
    #[must_use]
    pub fn ymax(&self) -> f64 {
        self.ymax
    }
    /// The width, `xmax − xmin` (> 0).
    #[must_use]
    pub fn width(&self) -> f64 {
        self.xmax - self.xmin
    }
    /// The height, `ymax − ymin` (> 0).
    #[must_use]
    pub fn height(&self) -> f64 {
        self.ymax - self.ymin
    }
    /// The centre.
    #[must_use]
    pub fn center(&self) -> DVec2 {
        DVec2::new(self.xmin + self.xmax, self.ymin + self.ymax) / 2.0
    }
}

/// A rectangle in canvas pixels, y down.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PxRect {
    /// Top-left corner.
    pub min: DVec2,
    /// Bottom-right corner.
    pub max: DVec2,
}

impl PxRect {
    /// The width.
    #[must_use]
    pub fn width(&self) -> f64 {
        self.max.x - self.min.x
    }
    /// The height.
    #[must_use]
    pub fn height(&self) -> f64 {
        self.max.y - self.min.y
    }
    /// The rectangle grown by `d` on every side.
    #[must_use]
    pub fn inflate(&self, d: f64) -> Self {
        Self { min: self.min - DVec2::splat(d), max: self.max + DVec2::splat(d) }
    }
    /// The area shared with `other` (0 when they are apart).
    #[must_use]
    pub fn overlap(&self, other: &Self) -> f64 {
        let lo = self.min.max(other.min);
        let hi = self.max.min(other.max);
        let d = (hi - lo).max(DVec2::ZERO);
        d.x * d.y
    }
    /// Whether `p` lies inside (edges included).
    #[must_use]
    pub fn contains_point(&self, p: DVec2) -> bool {
        p.cmpge(self.min).all() && p.cmple(self.max).all()
    }
    /// Whether `other` lies wholly inside.
    #[must_use]
    pub fn contains_rect(&self, other: &Self) -> bool {
        other.min.cmpge(self.min).all() && other.max.cmple(self.max).all()
    }
    /// Whether the segment `a`–`b` meets the rectangle (Liang–Barsky clipping).
    #[must_use]
    pub fn meets_segment(&self, a: DVec2, b: DVec2) -> bool {
        self.clip_segment(a, b).is_some()
    }
    /// How long a stretch of the segment `a`–`b` lies inside the rectangle, in pixels (0 when
    /// it misses, or only touches a corner).
    #[must_use]
    pub fn length_inside(&self, a: DVec2, b: DVec2) -> f64 {
        self.clip_segment(a, b).map_or(0.0, |(t0, t1)| (t1 - t0) * (b - a).length())
    }
    /// The parameters `t0 ≤ t1` in [0, 1] of the part of `a + t·(b − a)` inside the rectangle
    /// (Liang–Barsky clipping), or `None` when the segment misses it.
    ///
    /// A segment whose box lies farther than [`SURE_MISS`] outside the rectangle misses it
    /// without the divisions: the clip itself would find `t0 > t1` there (its entry parameter
    /// is then above 1 by far more than a rounding), so the answer is the same, only sooner.
    fn clip_segment(&self, a: DVec2, b: DVec2) -> Option<(f64, f64)> {
        if self.surely_missed(a, b) {
            return None;
        }
        self.clip(a, b)
    }
    /// Whether the box of the segment `a`–`b` lies farther than [`SURE_MISS`] outside.
    fn surely_missed(&self, a: DVec2, b: DVec2) -> bool {
        let (lo, hi) = (a.min(b), a.max(b));
        hi.x < self.min.x - SURE_MISS
            || lo.x > self.max.x + SURE_MISS
            || hi.y < self.min.y - SURE_MISS
            || lo.y > self.max.y + SURE_MISS
    }
    /// [`PxRect::clip_segment`] by Liang–Barsky's four divisions, for any segment.
    fn clip(&self, a: DVec2, b: DVec2) -> Option<(f64, f64)> {
        let d = b - a;
        let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
        for (p, q) in [
            (-d.x, a.x - self.min.x),
            (d.x, self.max.x - a.x),
            (-d.y, a.y - self.min.y),
            (d.y, self.max.y - a.y),
        ] {
            if p == 0.0 {
                if q < 0.0 {
                    return None;
                }
            } else {
                let t = q / p;
                if p < 0.0 {
                    t0 = t0.max(t);
                } else {
                    t1 = t1.min(t);
                }
            }
        }
        (t0 <= t1).then_some((t0, t1))
    }
}

/// How far outside a rectangle, in pixels, a segment's box must lie for
/// [`PxRect::meets_segment`] to answer without clipping: a millionth of a pixel, far above the
/// rounding of a clip in a drawing's coordinates.
const SURE_MISS: f64 = 1e-6;

/// The world → pixel map of a drawing: `px = (tx + s·x, ty − s·y)`, one uniform scale `s` and a
/// y flip. Back ends narrow its f64 results to f32 at the last moment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform {
    scale: f64,
    tx: f64,
    ty: f64,
    px_scale: f64,
}

impl Transform {
    /// `view` scaled uniformly to fit `plot`, centred, with `px_scale` canvas pixels per
    /// reference pixel.
    #[must_use]
    pub fn fit(view: &View, plot: &PxRect, px_scale: f64) -> Self {
        let scale = (plot.width() / view.width()).min(plot.height() / view.height());
        let c = view.center();
        let mid = (plot.min + plot.max) / 2.0;
        Self { scale, tx: mid.x - scale * c.x, ty: mid.y + scale * c.y, px_scale }
    }

    /// Pixels per world unit.
    #[must_use]
    pub fn scale(&self) -> f64 {
        self.scale
    }
    /// The pixel position of world point `p`.
    #[must_use]
    pub fn to_px(&self, p: DVec2) -> DVec2 {
        DVec2::new(self.tx + self.scale * p.x, self.ty - self.scale * p.y)
    }
    /// The world point at pixel `q` (the inverse of [`Transform::to_px`]).
    #[must_use]
    pub fn to_world(&self, q: DVec2) -> DVec2 {
        DVec2::new((q.x - self.tx) / self.scale, (self.ty - q.y) / self.scale)
    }
    /// A world length in pixels.
    #[must_use]
    pub fn len_px(&self, world: f64) -> f64 {
        world * self.scale
    }
    /// A length in reference pixels, in this canvas's pixels.
    #[must_use]
    pub fn ref_px(&self, reference: f64) -> f64 {
        reference * self.px_scale
    }
    /// A reference-pixel offset with y up (as items give them) → a canvas pixel offset, y down.
    #[must_use]
    pub fn offset_px(&self, offset: DVec2) -> DVec2 {
        DVec2::new(offset.x, -offset.y) * self.px_scale
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_segment_surely_missed_is_one_the_clip_misses() {
        let rect = PxRect { min: DVec2::new(10.25, -3.5), max: DVec2::new(47.0, 12.125) };
        // Coordinates on, near and away from each edge, in every pairing.
        let xs = [-1e4, 0.0, 10.25 - 1e-6, 10.25 - 2e-6, 10.25, 30.0, 47.0, 47.0 + 2e-6, 47.0 + 1e-3, 1e4];
        let ys = [-1e4, -3.5 - 2e-6, -3.5 - 1e-9, -3.5, 4.0, 12.125, 12.125 + 2e-6, 12.2, 1e4];
        let points: Vec<DVec2> = xs.iter().flat_map(|&x| ys.iter().map(move |&y| DVec2::new(x, y))).collect();
        let mut missed = 0;
        for &a in &points {
            for &b in &points {
                if rect.surely_missed(a, b) {
                    missed += 1;
                    assert_eq!(rect.clip(a, b), None, "{a} {b}");
                }
                assert_eq!(rect.clip_segment(a, b), rect.clip(a, b), "{a} {b}");
            }
        }
        assert!(missed > 1000, "the sweep reaches the early answer ({missed})");
    }
}
