//! The magnified detail of a crowded figure (issue 32, ray-casting 2's lens): when the names a
//! figure would print crowd one spot at slide size, a lecturer draws that spot again, larger, in
//! a free part of the slide. This module decides when (a measured crowding, [`crowded`]), where
//! ([`plan`]: the main picture keeps its scene, the panel takes the room beside the legend) and
//! how a figure draws into either panel through one code path ([`Panel`]: clip, then map).
//! Drawing only: nothing here traces.

use glam::DVec2;

use super::parts::clip_segment;
use super::style::{self, Rgba};
use crate::canvas::{Align, Corner, Drawing, HAlign, Inset, LegendPlace, Pen, TextOpts, VAlign, View};

/// The radius, in reference pixels, within which names crowd: about four label heights.
pub const CROWD_RADIUS: f64 = 120.0;

/// How many names' anchors (the point's own among them) within [`CROWD_RADIUS`] of one anchor
/// make it crowded: more than a lecturer can name legibly around one spot.
pub const CROWD_COUNT: usize = 8;

/// The room left around the crowded anchors inside the frame, in reference pixels of the main
/// picture: a name's height, so that the names find their spots inside the panel.
pub const FRAME_PAD: f64 = 30.0;

/// The magnifications an inset may print, largest first: half steps, so "×3.5" reads at once.
pub const FACTORS: [f64; 5] = [4.0, 3.5, 3.0, 2.5, 2.0];

/// The shares of its full size the main picture may keep beside an inset, largest first: it
/// shrinks (to no less than the last) only while that buys the inset a larger magnification.
pub const MAIN_SHARES: [f64; 3] = [1.0, 0.9, 0.8];

/// The gap, in reference pixels, between the main picture, the panel and the legend.
pub const PANEL_GAP: f64 = 30.0;

/// The colour of the frame, the panel's border and the two lines that join them.
pub const INSET_COLOUR: Rgba = style::DARK_GREY;

/// The tag of the frame, the panel and their joining lines.
pub const INSET_TAG: &str = "inset";

/// The tag of the printed magnification ("×3.5").
pub const FACTOR_TAG: &str = "inset-factor";

/// The anchors (indices into `anchors`, pixels) around the most crowded one, or `None` when no
/// anchor has [`CROWD_COUNT`] anchors (its own included) within `radius` pixels.
#[must_use]
pub fn crowded(anchors: &[DVec2], radius: f64) -> Option<Vec<usize>> {
    let near = |a: DVec2| -> Vec<usize> {
        anchors.iter().enumerate().filter(|(_, b)| a.distance(**b) <= radius).map(|(k, _)| k).collect()
    };
    let densest = anchors.iter().map(|a| near(*a)).max_by_key(Vec::len)?;
    (densest.len() >= CROWD_COUNT).then_some(densest)
}

/// Where a figure draws: its main picture, clipped to `clip` (with the inset's frame marked
/// when there is one), or the inset's panel.
#[derive(Clone, Copy, Debug)]
pub enum Panel {
    /// The whole scene, clipped to `clip`; with an inset, the names of what lies in its frame
    /// are printed in the panel instead.
    Main {
        /// What the main picture shows (world).
        clip: View,
        /// The detail drawn elsewhere, if any.
        inset: Option<Inset>,
    },
    /// The inset's frame, magnified into its panel.
    Detail(Inset),
}

impl Panel {
    /// The region of the scene this panel shows, in the main picture's world.
    #[must_use]
    pub fn clip(&self) -> View {
        match self {
            Self::Main { clip, .. } => *clip,
            Self::Detail(inset) => frame_view(inset),
        }
    }

    /// Where a point of the scene's page is drawn in this panel.
    #[must_use]
    pub fn map(&self, p: DVec2) -> DVec2 {
        match self {
            Self::Main { .. } => p,
            Self::Detail(inset) => inset.map(p),
        }
    }

    /// Whether the name of what stands at page point `p` is printed in this panel: each name
    /// once, in the panel where it is legible (the inset's, for what its frame holds).
    #[must_use]
    pub fn names(&self, p: DVec2) -> bool {
        match self {
            Self::Main { inset: Some(inset), .. } => !inset.in_frame(p),
            Self::Main { inset: None, .. } => true,
            Self::Detail(inset) => inset.in_frame(p),
        }
    }

    /// Whether page point `p` is drawn in this panel.
    #[must_use]
    pub fn shows(&self, p: DVec2) -> bool {
        let v = self.clip();
        v.xmin() <= p.x && p.x <= v.xmax() && v.ymin() <= p.y && p.y <= v.ymax()
    }

    /// The part of segment `a`–`b` this panel shows, drawn (clipped, then mapped).
    #[must_use]
    pub fn segment(&self, a: DVec2, b: DVec2) -> Option<(DVec2, DVec2)> {
        match self {
            Self::Main { .. } => Some((a, b)),
            Self::Detail(inset) => {
                clip_segment(a, b, &frame_view(inset)).map(|(p, q)| (inset.map(p), inset.map(q)))
            }
        }
    }
}

/// An inset's frame as a view.
fn frame_view(inset: &Inset) -> View {
    let (lo, hi) = inset.frame;
    View::new(lo.x, hi.x, lo.y, hi.y).unwrap_or(View::SQUARE)
}

/// Rounds a magnification down to the largest of [`FACTORS`] it reaches, or `None` below them.
fn nice_factor(room: f64) -> Option<f64> {
    FACTORS.iter().copied().find(|f| *f <= room)
}

/// The layout of a figure with an inset: the main picture's region, and the inset.
#[derive(Clone, Copy, Debug)]
pub struct Plan {
    /// What the main picture shows (world).
    pub main: View,
    /// The detail.
    pub inset: Inset,
}

/// Lays a crowded figure out with an inset, or leaves `d` as it is and returns `None`. The
/// view is already fitted to `content` (the points the main picture must show) with `margin`;
/// `anchors` are the world points its names will stand at. When they crowd ([`crowded`], at
/// the scale the figure is drawn), the legend goes to the plot's top right corner, the main
/// picture to its left edge at the largest share of its size ([`MAIN_SHARES`]) that leaves the
/// inset its largest magnification ([`FACTORS`]), and the inset into the larger free region:
/// beside the legend, the plot's full height, or under it.
pub fn plan(d: &mut Drawing, content: &[DVec2], margin: f64, anchors: &[DVec2]) -> Option<Plan> {
    let tf = d.transform();
    let px: Vec<DVec2> = anchors.iter().map(|a| tf.to_px(*a)).collect();
    let crowd = crowded(&px, tf.ref_px(CROWD_RADIUS))?;
    let (lo, hi) = bounds(crowd.iter().map(|k| anchors[*k]))?;
    let (c_lo, c_hi) = bounds(content.iter().copied())?;
    let pad = margin * (c_hi - c_lo).max_element();
    let (c_lo, c_hi) = (c_lo - DVec2::splat(pad), c_hi + DVec2::splat(pad));

    let mut trial = d.clone();
    trial.legend_place = LegendPlace::Inside(Corner::TopRight);
    let page = trial.frame();
    let (plot, legend) = (page.plot, page.legend.map(|l| l.rect));
    let gap = tf.ref_px(PANEL_GAP);
    let size = c_hi - c_lo;
    let full = (plot.width() / size.x).min(plot.height() / size.y);
    let frame_pad = FRAME_PAD / tf.scale() * tf.ref_px(1.0);
    let frame = (lo - DVec2::splat(frame_pad), hi + DVec2::splat(frame_pad));
    let frame_size = frame.1 - frame.0;

    // (factor, share, region's pixel corners)
    let mut best: Option<(f64, f64, DVec2, DVec2)> = None;
    for share in MAIN_SHARES {
        let scale = full * share;
        let right = plot.min.x + scale * size.x + gap;
        let (top, bottom) = (plot.min.y, plot.max.y);
        let regions = match legend {
            Some(l) => vec![
                (DVec2::new(right, top), DVec2::new(l.min.x - gap, bottom)),
                (DVec2::new(right, l.max.y + gap), DVec2::new(plot.max.x, bottom)),
            ],
            None => vec![(DVec2::new(right, top), DVec2::new(plot.max.x, bottom))],
        };
        for (a, b) in regions {
            let room = (b - a) / (frame_size * scale);
            let Some(factor) = nice_factor(room.min_element()) else { continue };
            if best.is_none_or(|(f, ..)| factor > f) {
                best = Some((factor, share, a, b));
            }
        }
    }
    let (factor, share, a, b) = best?;

    // The main picture at its share, against the plot's left edge, centred up and down.
    let scale = full * share;
    let (w, h) = (plot.width() / scale, plot.height() / scale);
    let cy = (c_lo.y + c_hi.y) / 2.0;
    let view = View::new(c_lo.x, c_lo.x + w, cy - h / 2.0, cy + h / 2.0)?;
    d.legend_place = LegendPlace::Inside(Corner::TopRight);
    d.set_view(view);
    let tf = d.transform();
    let main = View::new(view.xmin(), c_hi.x, view.ymin(), view.ymax())?;
    let inset = Inset::new(frame, factor, tf.to_world((a + b) / 2.0));
    d.add_inset(inset);
    Some(Plan { main, inset })
}

/// The least and greatest corners of `points`, or `None` when there are none.
fn bounds(points: impl Iterator<Item = DVec2>) -> Option<(DVec2, DVec2)> {
    points.fold(None, |acc, p| match acc {
        None => Some((p, p)),
        Some((lo, hi)) => Some((lo.min(p), hi.max(p))),
    })
}

/// Draws what joins an inset to its frame: the frame in the main picture, the panel's border,
/// the two lines from the frame's corners to the panel's facing ones, and the magnification
/// printed in the panel's top left corner as `factor_text` (`×3.5`).
pub fn draw_frame(d: &mut Drawing, inset: &Inset, factor_text: &str) {
    let pen = Pen::solid(INSET_COLOUR, style::GRID_WIDTH);
    let (f, p) = (inset.frame, inset.panel);
    d.rect(INSET_TAG, f.0, f.1, pen, None);
    d.rect(INSET_TAG, p.0, p.1, pen, None);
    let corners = |(lo, hi): (DVec2, DVec2)| {
        [lo, DVec2::new(hi.x, lo.y), hi, DVec2::new(lo.x, hi.y)] // bl, br, tr, tl
    };
    let (fc, pc) = (corners(f), corners(p));
    // The panel lies to one side of the frame: join the frame's corners on that side to the
    // panel's corners facing them.
    let pairs = if p.0.x >= f.1.x {
        [(fc[1], pc[0]), (fc[2], pc[3])]
    } else if p.1.x <= f.0.x {
        [(fc[0], pc[1]), (fc[3], pc[2])]
    } else if p.0.y >= f.1.y {
        [(fc[3], pc[0]), (fc[2], pc[1])]
    } else {
        [(fc[0], pc[3]), (fc[1], pc[2])]
    };
    for (a, b) in pairs {
        d.segment(INSET_TAG, a, b, pen);
    }
    // The factor inside the first of the panel's corners (top left first) where it lies on no
    // line: a corner where a ray leaves the panel would strike it through.
    let inward = [
        (pc[3], HAlign::Left, VAlign::Top, DVec2::new(1.0, -1.0)),
        (pc[2], HAlign::Right, VAlign::Top, DVec2::new(-1.0, -1.0)),
        (pc[0], HAlign::Left, VAlign::Bottom, DVec2::new(1.0, 1.0)),
        (pc[1], HAlign::Right, VAlign::Bottom, DVec2::new(-1.0, 1.0)),
    ];
    for (k, (corner, h, v, dir)) in inward.iter().enumerate() {
        let opts = TextOpts::LABEL
            .color(INSET_COLOUR)
            .align(Align { h: *h, v: *v })
            .offset(dir.x * FACTOR_INDENT, dir.y * FACTOR_INDENT);
        d.text(FACTOR_TAG, *corner, factor_text, opts);
        let last = d.items.len() - 1;
        let crossed = d
            .labels_on_lines("")
            .iter()
            .any(|(label, line)| *label == last && d.items[*line].tag != INSET_TAG);
        if !crossed || k + 1 == inward.len() {
            break;
        }
        d.pop_item();
    }
}

/// How far the printed factor stands in from the panel's corner, in reference pixels.
const FACTOR_INDENT: f64 = 10.0;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crowding_is_counted_within_the_radius() {
        let ring: Vec<DVec2> = (0..CROWD_COUNT).map(|k| DVec2::from_angle(k as f64) * 50.0).collect();
        assert_eq!(crowded(&ring, 100.0).map(|c| c.len()), Some(CROWD_COUNT));
        assert!(crowded(&ring[1..], 100.0).is_none(), "one fewer is not crowded");
        let spread: Vec<DVec2> = (0..20).map(|k| DVec2::new(300.0 * f64::from(k), 0.0)).collect();
        assert!(crowded(&spread, 100.0).is_none());
    }

    #[test]
    fn factors_round_down_to_half_steps() {
        assert_eq!(nice_factor(3.9), Some(3.5));
        assert_eq!(nice_factor(9.0), Some(4.0));
        assert_eq!(nice_factor(1.9), None);
    }
}
