//! The [`Drawing`]: a canvas size, the world rectangle it shows, the display list, the legend's
//! rows, title and caption, and the builders that add to them (`line`, `arrow`, `circle`, `dot`,
//! `text`, `legend_entry` …). Every item added inside [`Drawing::with_events`] carries the
//! indices of the trace events it draws.

use glam::DVec2;

use super::items::{Inset, Item, LegendEntry, LegendPlace, Mark};
use super::style::{self, Pen, Rgba};
use super::view::View;

/// How one panel of a drawing shows a scene: the drawing's world position of the scene's origin
/// and, for each of the scene's axes in order (x, y, and z in 3D), the drawing's components of
/// its unit vector. A scene drawn in its own axes, x to the right and y up at one scale `s`, has
/// `axes == [(s, 0), (0, s)]`; a 3D scene's axes are projected onto the panel's plane.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneAxes {
    /// Where the scene's origin is drawn.
    pub origin: DVec2,
    /// The drawn components of each scene axis's unit vector.
    pub axes: Vec<DVec2>,
}

/// A figure: the display list, the world rectangle it shows, its canvas size, and its legend,
/// title and caption.
///
/// The canvas is laid out once, by [`Drawing::frame`], for both back ends: a title band at the
/// top, a caption band at the bottom, the plot area between them, and the legend box in a clear
/// corner of the plot area, in a column to its right or in a band under it ([`LegendPlace`]).
/// Build in this order: the title, caption and legend (and [`LegendPlace::Outside`] or
/// [`LegendPlace::Below`] if the legend will not fit inside), then the view, then the items and
/// labels; a label placed with `TextOpts::avoid_overlap` is placed against the transform in
/// force when it is added.
#[derive(Clone, Debug, PartialEq)]
pub struct Drawing {
    width: u32,
    height: u32,
    /// The world rectangle shown (uniformly scaled and centred in the plot area).
    pub view: View,
    /// The display list, drawn in order (later items on top).
    pub items: Vec<Item>,
    /// The legend's rows; no box is drawn when empty.
    pub legend: Vec<LegendEntry>,
    /// Where the legend box goes.
    pub legend_place: LegendPlace,
    /// The caption under the plot (markup), wrapped to the canvas width.
    pub caption: Option<String>,
    /// The title above the plot (markup), in bold.
    pub title: Option<String>,
    /// Where labels placed clear ([`TextOpts::avoid_overlap`](crate::TextOpts::avoid_overlap)) may go: a world rectangle, or the
    /// whole plot area when `None` ([`Drawing::keep_labels_within`]).
    pub label_area: Option<(DVec2, DVec2)>,
    /// The tag prefix of the lines a label placed clear keeps off unless it names them
    /// ([`Drawing::guard_lines`]).
    pub guard: Option<String>,
    /// The tag prefix of the object outlines a label placed clear keeps off unless it names
    /// the object or its point lies on it ([`Drawing::guard_outlines`]).
    pub outline_guard: Option<String>,
    /// The tag prefixes of the lines and arrows a label placed clear keeps off even when it
    /// names them, arrows' heads too ([`Drawing::guard_strictly`]).
    pub strict_guards: Vec<String>,
    /// How each panel that draws a scene maps the scene's axes onto the world of the drawing
    /// ([`Drawing::record_axes`]), in the order the panels were drawn; empty for a drawing of no
    /// scene (a chart, a tree). Metadata for tests and readers: no back end draws it.
    pub scene_axes: Vec<SceneAxes>,
    /// The magnified details ([`Inset`](crate::Inset), [`Drawing::add_inset`]): each a frame of
    /// the world drawn larger in a panel. Labels anchored in a panel stay in it; the others
    /// keep out of it.
    pub insets: Vec<Inset>,
    /// The events of the items added now ([`Drawing::with_events`]).
    pub(super) events: Vec<usize>,
    /// The labels placed clear, as indices into `items`, each with whether it may go far
    /// ([`TextOpts::far`]): the ones [`Drawing::settle_labels`] may move again.
    pub(super) placed_clear: Vec<(usize, bool)>,
}

impl Drawing {
    /// An empty drawing for a `width` × `height` pixel canvas showing the world square
    /// [−1, 1]², or `None` if either size is 0.
    #[must_use]
    pub fn new(width: u32, height: u32) -> Option<Self> {
        (width > 0 && height > 0).then(|| Self::blank(width, height))
    }

    /// An empty drawing of `width` × `height` pixels showing [−1, 1]².
    fn blank(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            view: View::SQUARE,
            items: Vec::new(),
            legend: Vec::new(),
            legend_place: LegendPlace::Auto,
            caption: None,
            title: None,
            label_area: None,
            guard: None,
            outline_guard: None,
            strict_guards: Vec::new(),
            scene_axes: Vec::new(),
            insets: Vec::new(),
            events: Vec::new(),
            placed_clear: Vec::new(),
        }
    }

    /// An empty drawing on the reference slide canvas, 1920 × 1080.
    #[must_use]
    pub fn slide() -> Self {
        Self::blank(style::REFERENCE_WIDTH, style::REFERENCE_HEIGHT)
    }

    /// Canvas width in pixels.
    #[must_use]
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Canvas height in pixels.
    #[must_use]
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Reference pixels → canvas pixels (see [`style::px_scale`]).
    #[must_use]
    pub fn px_scale(&self) -> f64 {
        style::px_scale(self.width, self.height)
    }

    /// Sets the title (markup).
    pub fn set_title(&mut self, title: &str) -> &mut Self {
        self.title = Some(title.to_owned());
        self
    }

    /// Sets the caption (markup).
    pub fn set_caption(&mut self, caption: &str) -> &mut Self {
        self.caption = Some(caption.to_owned());
        self
    }

    /// Keeps the labels placed from now on with [`TextOpts::avoid_overlap`](crate::TextOpts::avoid_overlap) inside the world
    /// rectangle spanned by `a` and `b` where they can be (a plot's data area, so that no name
    /// lands among the tick names).
    pub fn keep_labels_within(&mut self, a: DVec2, b: DVec2) -> &mut Self {
        self.label_area = Some((a.min(b), a.max(b)));
        self
    }

    /// Makes the lines tagged `prefix…` (a figure's rays) guarded: a label placed clear from now
    /// on keeps off each one it does not name, that is, whose events it does not draw
    /// ([`Drawing::with_events`]), at [`GUARDED_LINE_COST`](super::label::GUARDED_LINE_COST) a crossing; see also
    /// [`Drawing::labels_on_lines`], the check.
    pub fn guard_lines(&mut self, prefix: &str) -> &mut Self {
        self.guard = Some(prefix.to_owned());
        self
    }

    /// Makes the outlines tagged `prefix…` (the objects) guarded: a label placed clear from now
    /// on keeps off each one unless it names that object (`object-name:2` names `object:2`) or
    /// its anchor lies on it, at [`OUTLINE_COST`](super::label::OUTLINE_COST) an outline; see
    /// also [`Drawing::labels_on_outlines`], the check.
    pub fn guard_outlines(&mut self, prefix: &str) -> &mut Self {
        self.outline_guard = Some(prefix.to_owned());
        self
    }

    /// Makes the lines and arrows tagged `prefix…` (a mapping between two panels, the normals)
    /// strictly guarded, in addition to those guarded before: a label placed clear from now on
    /// keeps off each one, even one it names (the mapping's two ends, the point a normal is
    /// drawn from), an arrow's head too, at [`GUARDED_LINE_COST`](super::label::GUARDED_LINE_COST)
    /// a crossing; see also [`Drawing::labels_on_strict_lines`], the check.
    pub fn guard_strictly(&mut self, prefix: &str) -> &mut Self {
        self.strict_guards.push(prefix.to_owned());
        self
    }

    /// Records how a panel draws its scene ([`SceneAxes`]): where the scene's origin lands and
    /// the drawing's components of the scene's unit axes.
    pub fn record_axes(&mut self, origin: DVec2, axes: impl IntoIterator<Item = DVec2>) -> &mut Self {
        self.scene_axes.push(SceneAxes { origin, axes: axes.into_iter().collect() });
        self
    }

    /// Records a magnified detail ([`Inset`]); labels placed clear from now on keep to their
    /// side of its panel: a label anchored in the panel stays in it, any other keeps out of it.
    pub fn add_inset(&mut self, inset: Inset) -> &mut Self {
        self.insets.push(inset);
        self
    }

    /// Sets the world rectangle shown.
    pub fn set_view(&mut self, view: View) -> &mut Self {
        self.view = view;
        self
    }

    /// Shows every finite point of `points` with a margin of `margin` times their larger extent,
    /// at the plot area's aspect ratio. Leaves the view unchanged when no point is finite.
    pub fn fit_view(&mut self, points: &[DVec2], margin: f64) -> &mut Self {
        let plot = self.plot_area();
        if let Some(view) = View::fit(points, margin, plot.width() / plot.height()) {
            self.view = view;
        }
        self
    }

    /// The aspect ratio (width / height) of the plot area, for [`View::fit`].
    #[must_use]
    pub fn plot_aspect(&self) -> f64 {
        let plot = self.plot_area();
        plot.width() / plot.height()
    }

    /// Adds an item (drawing the events of the enclosing [`Drawing::with_events`], if any).
    pub fn push(&mut self, tag: &str, pen: Pen, mark: Mark) -> &mut Self {
        self.items.push(Item { tag: tag.to_owned(), pen, mark, events: self.events.clone() });
        self
    }

    /// Runs `draw`, every item it adds drawing `events` (indices into the main trace's events,
    /// sorted and deduplicated here); the events in force before are restored after.
    pub fn with_events<R>(
        &mut self,
        events: impl IntoIterator<Item = usize>,
        draw: impl FnOnce(&mut Self) -> R,
    ) -> R {
        let mut now: Vec<usize> = events.into_iter().collect();
        now.sort_unstable();
        now.dedup();
        let before = std::mem::replace(&mut self.events, now);
        let out = draw(self);
        self.events = before;
        out
    }

    /// Adds a polyline.
    pub fn line(&mut self, tag: &str, points: impl IntoIterator<Item = DVec2>, style: Pen) -> &mut Self {
        let points = points.into_iter().collect();
        self.push(tag, style, Mark::Line { points })
    }

    /// Adds the segment `a`–`b`.
    pub fn segment(&mut self, tag: &str, a: DVec2, b: DVec2, style: Pen) -> &mut Self {
        self.push(tag, style, Mark::Line { points: vec![a, b] })
    }

    /// Adds an arrow from `from` to `to`, its head sized for the stroke ([`style::arrow_head`]).
    pub fn arrow(&mut self, tag: &str, from: DVec2, to: DVec2, style: Pen) -> &mut Self {
        let head = style::arrow_head(style.width);
        self.push(tag, style, Mark::Arrow { from, to, head })
    }

    /// Adds a circle of world radius `radius`, stroked with `style` and filled with `fill`.
    pub fn circle(
        &mut self,
        tag: &str,
        center: DVec2,
        radius: f64,
        style: Pen,
        fill: Option<Rgba>,
    ) -> &mut Self {
        self.push(tag, style, Mark::Circle { center, radius, fill })
    }

    /// Adds a dot of the standard radius ([`style::DOT_RADIUS`]) filled with `fill`, no outline.
    pub fn dot(&mut self, tag: &str, center: DVec2, fill: Rgba) -> &mut Self {
        self.marker(tag, center, style::DOT_RADIUS, fill, Pen::NONE)
    }

    /// Adds a dot of `radius` reference pixels, filled with `fill` and outlined with `outline`.
    pub fn marker(&mut self, tag: &str, center: DVec2, radius: f64, fill: Rgba, outline: Pen) -> &mut Self {
        self.push(tag, outline, Mark::Dot { center, radius, fill })
    }

    /// Adds a closed polygon.
    pub fn polygon(
        &mut self,
        tag: &str,
        points: impl IntoIterator<Item = DVec2>,
        style: Pen,
        fill: Option<Rgba>,
    ) -> &mut Self {
        let points = points.into_iter().collect();
        self.push(tag, style, Mark::Polygon { points, fill })
    }

    /// Adds the world rectangle spanned by corners `a` and `b` (in any order).
    pub fn rect(&mut self, tag: &str, a: DVec2, b: DVec2, style: Pen, fill: Option<Rgba>) -> &mut Self {
        self.push(tag, style, Mark::Rect { min: a.min(b), max: a.max(b), fill })
    }

    /// The items whose tag is `tag`.
    pub fn tagged<'a>(&'a self, tag: &'a str) -> impl Iterator<Item = &'a Item> + 'a {
        self.items.iter().filter(move |item| item.tag == tag)
    }
}

#[cfg(test)]
// These tests pin exact IEEE results on purpose (numerics.md gives bit-exact expectations).
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;
    use crate::label::{LEADER_FROM, NEAR_STEPS};
    use crate::{Align, Corner, HAlign, LegendIcon, LegendPlace, PxRect, TextOpts, VAlign};

    use crate::style::test_strokes::{BLUE_LINE, FILL, OUTLINE, RED_LINE};

    pub(super) fn v(x: f64, y: f64) -> DVec2 {
        DVec2::new(x, y)
    }

    #[test]
    pub(super) fn an_inset_maps_its_frame_onto_its_panel_scaled_by_its_factor() {
        let inset = Inset::new((DVec2::new(1.0, 1.0), DVec2::new(0.0, 0.0)), 3.5, DVec2::new(10.0, 0.0));
        assert_eq!(inset.map(DVec2::new(0.5, 0.5)), DVec2::new(10.0, 0.0));
        assert_eq!(inset.map(DVec2::new(1.0, 1.0)), inset.panel.1);
        assert_eq!(inset.map(DVec2::new(0.0, 0.0)), inset.panel.0);
        assert!((inset.panel.1.x - inset.panel.0.x - 3.5).abs() < 1e-12);
        assert!(inset.in_frame(DVec2::new(0.2, 0.9)) && !inset.in_frame(DVec2::new(1.2, 0.9)));
        assert!(inset.in_panel(DVec2::new(11.0, 1.0)) && !inset.in_panel(DVec2::new(0.5, 0.5)));
    }

    #[test]
    pub(super) fn views_validate() {
        assert!(View::new(0.0, 1.0, 0.0, 1.0).is_some());
        assert!(View::new(1.0, 1.0, 0.0, 1.0).is_none());
        assert!(View::new(0.0, f64::NAN, 0.0, 1.0).is_none());
        assert!(Drawing::new(0, 10).is_none());
    }

    #[test]
    pub(super) fn fit_holds_the_points_at_the_requested_aspect() {
        let pts = [v(-2.0, 0.0), v(3.0, 1.0), v(0.0, -1.0)];
        let view = View::fit(&pts, 0.1, 16.0 / 9.0).unwrap();
        assert!((view.width() / view.height() - 16.0 / 9.0).abs() < 1e-9);
        for p in pts {
            assert!(p.x > view.xmin() && p.x < view.xmax() && p.y > view.ymin() && p.y < view.ymax());
        }
        // One point still gives a view; no finite point gives none.
        assert!(View::fit(&[v(1.0, 1.0)], 0.1, 1.0).is_some());
        assert!(View::fit(&[v(f64::NAN, 0.0)], 0.1, 1.0).is_none());
        assert!(View::fit(&pts, 0.1, 0.0).is_none());
    }

    #[test]
    pub(super) fn transform_is_uniform_with_y_up() {
        let mut d = Drawing::slide();
        d.set_view(View::new(0.0, 2.0, 0.0, 1.0).unwrap());
        let tf = d.transform();
        let a = tf.to_px(v(0.0, 0.0));
        let b = tf.to_px(v(1.0, 1.0));
        assert!(b.y < a.y, "y goes up in the world, down in pixels");
        assert!(((b.x - a.x) - (a.y - b.y)).abs() < 1e-9, "one scale for both axes");
        let back = tf.to_world(tf.to_px(v(0.3, 0.7)));
        assert!((back - v(0.3, 0.7)).length() < 1e-12);
        // The view's centre lands in the middle of the plot area.
        let frame = d.frame();
        let mid = (frame.plot.min + frame.plot.max) / 2.0;
        assert!((tf.to_px(v(1.0, 0.5)) - mid).length() < 1e-9);
    }

    #[test]
    pub(super) fn fitted_view_keeps_circles_round_on_any_canvas() {
        let mut d = Drawing::new(800, 1200).unwrap();
        d.set_title("t").set_caption("c");
        d.fit_view(&[v(0.0, 0.0), v(10.0, 1.0)], 0.05);
        let tf = d.transform();
        let plot = d.frame().plot;
        let corner_lo = tf.to_px(v(d.view.xmin(), d.view.ymin()));
        let corner_hi = tf.to_px(v(d.view.xmax(), d.view.ymax()));
        // The fitted view fills the plot area exactly.
        assert!((corner_lo.x - plot.min.x).abs() < 1e-6 && (corner_hi.x - plot.max.x).abs() < 1e-6);
        assert!((corner_hi.y - plot.min.y).abs() < 1e-6 && (corner_lo.y - plot.max.y).abs() < 1e-6);
    }

    #[test]
    pub(super) fn builders_add_one_tagged_item_each() {
        let mut d = Drawing::slide();
        d.segment("ray:primary", v(0.0, 0.0), v(1.0, 0.0), BLUE_LINE)
            .arrow("ray:reflected", v(0.0, 0.0), v(0.0, 1.0), RED_LINE)
            .circle("object:0", v(0.0, 0.0), 0.5, OUTLINE, Some(FILL))
            .dot("hit", v(0.5, 0.0), style::BLACK)
            .polygon("object:1", [v(0.0, 0.0), v(1.0, 0.0), v(0.0, 1.0)], OUTLINE, None)
            .rect("cell", v(1.0, 1.0), v(0.0, 0.0), style::grid(), None)
            .text("label", v(0.0, 0.0), "θ_i", TextOpts::LABEL);
        assert_eq!(d.items.len(), 7);
        assert_eq!(d.tagged("object:1").count(), 1);
        let Mark::Rect { min, max, .. } = d.tagged("cell").next().unwrap().mark else {
            panic!("not a rect");
        };
        assert!(min.cmple(max).all());
    }

    #[test]
    pub(super) fn segment_rectangle_meeting() {
        let r = PxRect { min: v(0.0, 0.0), max: v(10.0, 10.0) };
        assert!(r.meets_segment(v(-5.0, 5.0), v(15.0, 5.0)));
        assert!(r.meets_segment(v(2.0, 2.0), v(3.0, 3.0)));
        assert!(!r.meets_segment(v(-5.0, -1.0), v(15.0, -1.0)));
        assert!(!r.meets_segment(v(11.0, 0.0), v(20.0, 10.0)));
        assert!(r.meets_segment(v(-1.0, 5.0), v(5.0, -1.0)));
    }

    #[test]
    pub(super) fn avoid_overlap_moves_a_label_off_an_earlier_one_and_off_lines() {
        let mut d = Drawing::slide();
        d.set_view(View::new(-2.0, 2.0, -1.0, 1.0).unwrap());
        d.segment("ray:primary", v(-2.0, 0.0), v(2.0, 0.0), BLUE_LINE);
        d.text("label", v(0.0, 0.0), "first", TextOpts::LABEL.avoid_overlap());
        d.text("label", v(0.0, 0.0), "second", TextOpts::LABEL.avoid_overlap());
        let tf = d.transform();
        let boxes = d.text_boxes(&tf);
        assert_eq!(boxes.len(), 2);
        assert!(boxes[0].overlap(&boxes[1]) <= 0.0, "{boxes:?}");
        let y = tf.to_px(v(0.0, 0.0)).y;
        for b in &boxes {
            assert!(b.min.y > y || b.max.y < y, "label crosses the ray: {b:?}");
        }
    }

    pub(super) fn text_items(d: &Drawing) -> Vec<&crate::items::Text> {
        d.items
            .iter()
            .filter_map(|item| if let Mark::Text(t) = &item.mark { Some(t) } else { None })
            .collect()
    }

    #[test]
    pub(super) fn a_plot_keeps_its_names_inside_the_axes() {
        // A point on the x axis, the area above it: the name must not go below the axis.
        let mut d = Drawing::slide();
        d.set_view(View::new(-1.0, 3.0, -1.0, 1.0).unwrap());
        d.keep_labels_within(v(0.0, 0.0), v(3.0, 1.0));
        d.marker("point", v(1.0, 0.0), 6.0, style::BLUE, Pen::NONE);
        d.text(
            "name",
            v(1.0, 0.0),
            "a name",
            TextOpts::NOTE.align(Align::BELOW).offset(0.0, -14.0).avoid_overlap(),
        );
        let tf = d.transform();
        let placed = Drawing::place_text(text_items(&d)[0], &tf);
        assert!(placed.bbox.max.y <= tf.to_px(v(0.0, 0.0)).y, "above the axis: {:?}", placed.bbox);
    }

    #[test]
    pub(super) fn a_name_keeps_off_other_points_and_its_leader_off_other_names() {
        let mut d = Drawing::slide();
        d.set_view(View::new(-2.0, 2.0, -1.0, 1.0).unwrap());
        // A marker just right of the anchor, where the name is asked to go.
        d.marker("other", v(0.12, 0.0), 6.0, style::BLUE, Pen::NONE);
        let right = TextOpts::NOTE.align(Align::RIGHT_OF).offset(14.0, 0.0);
        d.text("name", v(0.0, 0.0), "a name", right.avoid_overlap());
        let tf = d.transform();
        let dot = tf.to_px(v(0.12, 0.0));
        let b = Drawing::place_text(text_items(&d)[0], &tf).bbox;
        assert!(!b.contains_point(dot), "the name left the other point visible: {b:?} {dot:?}");

        // Hatching around the anchor makes every near spot cost more than the third ring; of the
        // third ring's spots, the first tried (right) has a leader through the label "b": the
        // name goes to the next clear one (above) instead.
        let mut d = Drawing::slide();
        d.set_view(View::new(-2.0, 2.0, -1.0, 1.0).unwrap());
        let tf = d.transform();
        // World units per reference pixel.
        let world = tf.ref_px(1.0) / (tf.to_px(v(1.0, 0.0)).x - tf.to_px(v(0.0, 0.0)).x);
        let at = |x: f64, y: f64| v(x * world, y * world);
        for k in -5..=5 {
            let x = 10.0 * f64::from(k);
            d.segment("hatch", at(x, -50.0), at(x, 50.0), Pen::solid(style::BLACK, 1.0));
        }
        d.text("b", at(40.0, 0.0), "b", TextOpts::NOTE);
        d.text("name", v(0.0, 0.0), "a name", right.avoid_overlap_with_leader());
        let tf = d.transform();
        let texts = text_items(&d);
        let name = Drawing::place_text(texts[1], &tf);
        let b = Drawing::place_text(texts[0], &tf).bbox;
        let (from, to) = name.leader.expect("set apart, with a leader");
        assert!(!b.meets_segment(from, to), "the leader crosses b: {name:?} {b:?}");
        assert!(name.bbox.min.y < tf.to_px(v(0.0, 0.0)).y, "above the anchor: {name:?}");
    }

    #[test]
    pub(super) fn a_name_set_far_from_its_anchor_gets_a_leader_to_its_box() {
        let mut d = Drawing::slide();
        d.set_view(View::new(-2.0, 2.0, -1.0, 1.0).unwrap());
        // Three names of one point: the later ones must move away, the last farther than
        // LEADER_FROM; only labels that ask for a leader get one.
        for _ in 0..3 {
            d.text("name", v(0.0, 0.0), "a long name", TextOpts::LABEL.avoid_overlap_with_leader());
        }
        d.text("symbol", v(0.0, 0.0), "a long name", TextOpts::LABEL.avoid_overlap());
        let tf = d.transform();
        let texts = text_items(&d);
        assert!(!texts[0].leader, "the first name sits where asked");
        let far = texts[2];
        assert!(far.leader && far.offset.length() > LEADER_FROM, "{far:?}");
        let placed = Drawing::place_text(far, &tf);
        let (from, to) = placed.leader.expect("a leader in pixels");
        assert_eq!(from, tf.to_px(far.anchor));
        // It stops just short of the box, on the side facing the anchor.
        let near = placed.bbox.inflate(tf.ref_px(4.5));
        assert!(near.contains_point(to) && !placed.bbox.contains_point(to), "{to:?} {:?}", placed.bbox);
        assert!(!texts[3].leader, "a symbol never gets a leader");
        assert!(Drawing::place_text(texts[3], &tf).leader.is_none());
    }

    #[test]
    pub(super) fn a_box_s_name_takes_the_corner_clear_of_the_ray_and_keeps_that_anchor() {
        let mut d = Drawing::slide();
        d.set_view(View::new(-2.0, 2.0, -1.0, 1.0).unwrap());
        d.guard_lines("ray:");
        let (lo, hi) = (v(-1.0, -0.5), v(0.0, 0.5));
        d.rect("node", lo, hi, OUTLINE, None);
        // A ray through the box's upper left corner and down its left side.
        d.segment("ray:primary", v(-0.9, 1.0), v(-0.9, -1.0), BLUE_LINE);
        let inside =
            |h, v, dx, dy| TextOpts::NOTE.align(Align { h, v }).offset(dx, dy).avoid_overlap_with_leader();
        // 8 px in from the corner, off the box's own edges (a placed label keeps 4 px clear).
        let corners = [
            (v(lo.x, hi.y), inside(HAlign::Left, VAlign::Top, 8.0, -6.0), &NEAR_STEPS[..]),
            (hi, inside(HAlign::Right, VAlign::Top, -8.0, -6.0), &NEAR_STEPS[..]),
        ];
        d.text_at_cheapest("node-name", &corners, "N_{1}", |_, _| 0.0);
        let Mark::Text(t) = &d.items[2].mark else { panic!() };
        assert_eq!(t.anchor, hi, "the upper right corner, clear of the ray");
        assert_eq!((t.offset, t.leader), (v(-8.0, -6.0), false), "inside, where asked: {t:?}");
        // The caller's cost is weighed: with the right half of the picture barred, the name goes
        // to a ring of the upper left corner, still off the ray.
        d.items.pop();
        let middle = d.transform().to_px(v(-0.5, 0.0)).x;
        d.text_at_cheapest(
            "node-name",
            &corners,
            "N_{1}",
            |ink, _| if ink.max.x > middle { 100.0 } else { 0.0 },
        );
        let Mark::Text(t) = &d.items[2].mark else { panic!() };
        assert_eq!(t.anchor, v(lo.x, hi.y), "{t:?}");
        assert!(d.labels_on_lines("ray:").is_empty());
    }

    #[test]
    pub(super) fn a_clear_label_stays_where_asked() {
        let mut d = Drawing::slide();
        let opts = TextOpts::LABEL.offset(10.0, 20.0).align(Align::ABOVE).avoid_overlap();
        d.text("label", v(0.0, 0.0), "N", opts);
        let Mark::Text(t) = &d.items[0].mark else { panic!() };
        assert_eq!(t.offset, v(10.0, 20.0));
        assert_eq!(t.align, Align::ABOVE);
    }

    #[test]
    pub(super) fn legend_goes_to_the_emptiest_corner() {
        let mut d = Drawing::slide();
        d.set_view(View::new(0.0, 16.0, 0.0, 9.0).unwrap());
        // Clutter the top right corner.
        for i in 0..10 {
            let y = 9.0 - f64::from(i) * 0.2;
            d.segment("clutter", v(10.0, y), v(16.0, y), style::grid());
        }
        d.legend_entry("primary", BLUE_LINE, LegendIcon::Line);
        let legend = d.frame().legend.unwrap();
        let plot = d.frame().plot;
        assert!(legend.rect.min.x < (plot.min.x + plot.max.x) / 2.0, "{legend:?}");
        assert_eq!(legend.rows.len(), 1);
    }

    #[test]
    pub(super) fn legend_goes_outside_when_no_corner_is_clear_and_stays_where_fixed() {
        let mut d = Drawing::slide();
        d.set_view(View::new(0.0, 16.0, 0.0, 9.0).unwrap());
        for i in 0..=16 {
            let x = f64::from(i);
            d.segment("grid", v(x, 0.0), v(x, 9.0), style::grid());
        }
        d.legend_entry("primary", BLUE_LINE, LegendIcon::Line);
        let full = Drawing::slide().frame().plot;
        let frame = d.frame();
        let legend = frame.legend.unwrap();
        assert!(frame.plot.width() < full.width());
        assert!(legend.rect.min.x > frame.plot.max.x);
        assert!(legend.rect.max.x <= 1920.0);
        // The transform follows the narrowed plot area.
        assert!(d.transform().to_px(v(16.0, 0.0)).x <= frame.plot.max.x + 1e-9);

        d.legend_place = LegendPlace::Inside(Corner::BottomLeft);
        let frame = d.frame();
        let legend = frame.legend.unwrap();
        assert!((frame.plot.width() - full.width()).abs() < 1e-9);
        assert!(legend.rect.max.y > frame.plot.max.y - 20.0 && legend.rect.min.x < 100.0);
    }

    #[test]
    pub(super) fn a_legend_below_shortens_the_plot_and_keeps_a_wide_picture_larger_than_a_column() {
        // A picture three times as wide as tall, which the slide's plot area fits by its width.
        let wide = |place: LegendPlace| {
            let mut d = Drawing::slide();
            d.set_view(View::new(0.0, 30.0, 0.0, 10.0).unwrap());
            d.legend_entry("a legend entry with a long label", BLUE_LINE, LegendIcon::Line);
            d.legend_place = place;
            d
        };
        let (column, band) = (wide(LegendPlace::Outside), wide(LegendPlace::Below));
        let (full, frame) = (Drawing::slide().frame().plot, band.frame());
        let legend = frame.legend.unwrap();
        // The band: the plot keeps its width, loses the legend's height and a margin, and the
        // legend sits under it at its right end, above the caption band and inside the canvas.
        assert!((frame.plot.width() - full.width()).abs() < 1e-9);
        assert!(frame.plot.max.y < full.max.y - legend.rect.height());
        assert!(legend.rect.min.y > frame.plot.max.y);
        assert!((legend.rect.max.x - frame.plot.max.x).abs() < 1e-9);
        assert!(legend.rect.max.y <= full.max.y + 1e-9);
        // The picture is drawn larger under a band than beside a column.
        assert!(
            band.picture_scale() > column.picture_scale(),
            "{} {}",
            band.picture_scale(),
            column.picture_scale()
        );
        // A tall picture is the other way round.
        let tall = |place: LegendPlace| {
            let mut d = wide(place);
            d.set_view(View::new(0.0, 10.0, 0.0, 10.0).unwrap());
            d
        };
        assert!(tall(LegendPlace::Outside).picture_scale() >= tall(LegendPlace::Below).picture_scale());
    }

    #[test]
    pub(super) fn title_and_caption_bands_shrink_the_plot() {
        let mut d = Drawing::slide();
        let full = d.frame().plot;
        d.set_title("Title").set_caption("A caption");
        let frame = d.frame();
        assert!(frame.plot.height() < full.height());
        let title = frame.title.unwrap();
        assert!(title.origin.y < frame.plot.min.y);
        assert!(frame.caption[0].origin.y > frame.plot.max.y);
        assert!(frame.caption[0].origin.y < 1080.0);
    }
}
