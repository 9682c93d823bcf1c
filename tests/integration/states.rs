//! Every drawn state has its reason (issue 23 item 2): each state a figure draws is its own
//! legend entry and its own item tag, shown here on the lesson scene that teaches it.

use whitted::canvas::svg;
use whitted::canvas::{Drawing, Mark};
use whitted::figure::labels::Label;
use whitted::figure::plane::Planar;
use whitted::figure::source::{record, Aim, TraceOptions};
use whitted::figure::{draw, FigureKind, Lang, Options};
use whitted::record::event::Event;
use whitted::sample::Sampling;
use whitted::scene::load::load_str;
use whitted::scene::{AnyScene, Scene};

/// A lesson scene's text (`lessons/scenes/NAME`).
fn lesson_scene(name: &str) -> AnyScene {
    let path = format!("{}/lessons/scenes/{name}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    load_str(&text).unwrap_or_else(|e| panic!("{path}: {e:?}"))
}

/// Figure `kind` of `scene` as drawn at slide size, the figure picking its pixel unless `aim`
/// gives one.
fn drawn<V: Planar>(
    scene: &Scene<V>,
    name: &str,
    kind: FigureKind,
    aim: &Aim<V>,
    tracing: &TraceOptions,
) -> Drawing {
    let traces = record(kind, scene, name, aim, tracing).unwrap_or_else(|e| panic!("{name} {kind:?}: {e}"));
    let opts = Options { lang: Lang::En, width: 1920, height: 1080 };
    draw(kind, &traces, scene, &opts).unwrap_or_else(|e| panic!("{name} {kind:?}: {e}"))
}

/// Whether the drawing has a legend entry reading `label` (English) and its SVG says it.
fn has_legend(d: &Drawing, label: Label) -> bool {
    let text = label.text(Lang::En);
    let markup = text.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;");
    d.legend.iter().any(|e| e.label == text) && svg::to_svg(d).contains(&markup)
}

/// The number of items whose tag starts with `prefix`, checked against the SVG's groups.
fn tagged(d: &Drawing, prefix: &str) -> usize {
    let n = d.items.iter().filter(|i| i.tag.starts_with(prefix)).count();
    let in_svg = svg::to_svg(d).matches(&format!("data-tag=\"{prefix}")).count();
    assert_eq!(n, in_svg, "{prefix}");
    n
}

#[test]
fn the_bvh_lesson_shows_a_node_skipped_beyond_the_nearest_hit() {
    let AnyScene::Flat(scene) = lesson_scene("groups_2d.json") else { panic!("2D") };
    let d = drawn(&scene, "groups_2d", FigureKind::Bvh, &Aim::Auto, &TraceOptions::SCENE);
    assert!(has_legend(&d, Label::NodeSkipped));
    assert!(tagged(&d, "node-skipped:") >= 1);
    // Its subtree is not reached because of it, and says so; no node there is called missed.
    assert!(has_legend(&d, Label::NodeUnderSkipped));
    assert!(tagged(&d, "node-under-skipped:") >= 1);
    assert!(!has_legend(&d, Label::NodeUnderMissed), "no node of this walk is below a missed box");
    let caption = d.caption.clone().unwrap_or_default();
    assert!(caption.contains(Label::NodesSkipped.text(Lang::En)), "{caption}");
}

#[test]
fn a_skipped_node_starts_beyond_the_best_hit_and_is_never_opened() {
    for (name, structure) in
        [("groups_2d.json", "bvh"), ("groups_2d.json", "octree"), ("crowd_2d.json", "bvh")]
    {
        let AnyScene::Flat(scene) = lesson_scene(name) else { panic!("2D") };
        let kind = if structure == "bvh" { FigureKind::Bvh } else { FigureKind::Octree };
        let mut skips = 0;
        for i in 0..scene.camera.nx {
            let traces = record(kind, &scene, name, &Aim::Pixel(i, 0), &TraceOptions::SCENE).expect("traced");
            let log = &traces.traces[0].log;
            let events: Vec<&Event<_>> = log.events.iter().map(|l| &l.event).collect();
            for (k, e) in events.iter().enumerate() {
                if let Event::NodeSkip { node, t_in, t_best, structure: s } = e {
                    skips += 1;
                    assert_eq!(*s, structure);
                    assert!(t_in > t_best, "{name} pixel {i}: {t_in} ≤ {t_best}");
                    // The node was met by an earlier visit of the same search.
                    let met = events[..k].iter().any(|p| matches!(p, Event::NodeVisit { node: n, t_in: a, t_out: b, .. } if n == node && a <= b));
                    assert!(met, "{name} pixel {i}: node {node} skipped unmet");
                }
            }
        }
        assert!(skips > 0, "{name} {structure}: no pixel skips a node");
    }
}

/// An adaptive tracing of `K = max_level` and `threshold`, or the lecture's uniform corners.
fn sampled(sampling: Sampling) -> TraceOptions {
    let mut t = TraceOptions::SCENE;
    t.sampling = sampling;
    t
}

#[test]
fn adaptive_leaves_say_whether_the_threshold_or_the_maximum_level_stopped_them() {
    let AnyScene::Space(scene) = lesson_scene("whitted_small.json") else { panic!("3D") };
    let tracing = sampled(Sampling::adaptive(0.1, 2).expect("valid"));
    let d = drawn(&scene, "whitted_small", FigureKind::Adaptive, &Aim::Auto, &tracing);
    assert!(has_legend(&d, Label::LeafUnderThreshold));
    assert!(has_legend(&d, Label::LeafAtMaxLevel));
    assert!(tagged(&d, "leaf-colour:threshold") >= 1);
    assert!(tagged(&d, "leaf-colour:max-level") >= 1);
}

#[test]
fn uniform_supersampling_is_its_own_method_not_adaptive_with_an_infinite_threshold() {
    let AnyScene::Space(scene) = lesson_scene("whitted_small.json") else { panic!("3D") };
    let d = drawn(
        &scene,
        "whitted_small",
        FigureKind::Adaptive,
        &Aim::Pixel(100, 60),
        &sampled(Sampling::Corners),
    );
    assert_eq!(d.title.as_deref(), Some(Label::TitleUniform.text(Lang::En)));
    let caption = d.caption.clone().unwrap_or_default();
    assert!(!caption.contains('∞') && !caption.contains(Label::Threshold.text(Lang::En)), "{caption}");
    assert!(caption.contains(Label::UniformRule.text(Lang::En)), "{caption}");
    assert!(has_legend(&d, Label::UniformMean));
    assert!(!has_legend(&d, Label::LeafUnderThreshold));
    assert_eq!(tagged(&d, "leaf-colour:uniform"), 1);
}

#[test]
fn an_opaque_occluder_and_a_transparent_one_draw_different_shadow_rays() {
    let AnyScene::Flat(scene) = lesson_scene("shadows_2d.json") else { panic!("2D") };
    // Pixel 15: the one the shadows lesson's figure picks, whose two shadow rays are stopped
    // one by the glass and one by the block.
    for kind in [FigureKind::Shadows, FigureKind::Rays] {
        let d = drawn(&scene, "shadows_2d", kind, &Aim::Pixel(15, 0), &TraceOptions::SCENE);
        assert!(has_legend(&d, Label::BlockedShadowRay), "{kind:?}");
        assert!(has_legend(&d, Label::OpaqueShadowRay), "{kind:?}");
        assert!(tagged(&d, "ray:shadow-opaque") >= 1, "{kind:?}");
        assert!(tagged(&d, "ray:shadow-blocked") >= 1, "{kind:?}");
        let style = |tag: &str| d.items.iter().find(|i| i.tag == tag).map(|i| i.pen).expect(tag);
        let (opaque, glass) = (style("ray:shadow-opaque"), style("ray:shadow-blocked"));
        assert!(opaque.color != glass.color && opaque.dash != glass.dash, "{kind:?}");
    }
}

#[test]
fn the_ray_tree_shows_an_uncast_shadow_leaf_where_the_light_is_behind() {
    let path = format!("{}/scenes/whitted.json", env!("CARGO_MANIFEST_DIR"));
    let AnyScene::Space(scene) = load_str(&std::fs::read_to_string(path).expect("scene")).expect("loads")
    else {
        panic!("3D")
    };
    let d = drawn(&scene, "whitted", FigureKind::RayTree, &Aim::Auto, &TraceOptions::SCENE);
    assert!(has_legend(&d, Label::ShadowNotCast));
    assert!(tagged(&d, "ray:shadow-not-cast") >= 1);
    // One shadow leaf per light at every node that hit something, cast or not.
    let hits = d.items.iter().filter(|i| i.tag == "node").count()
        - d.items
            .iter()
            .filter(|i| i.tag == "object" && matches!(&i.mark, Mark::Text(t) if t.text == "background"))
            .count();
    assert_eq!(tagged(&d, "node:shadow"), hits * scene.lights.len());
}

// The depth limit of a ray tree lies between level max_depth and the level under it (issue 32
// item 3): `layout::a_ray_tree_s_depth_limit_lies_between_the_last_level_that_spawns_and_the_next`
// checks it over every lesson tree, the mirrors' among them (it replaced the test that the last
// level's shadow leaves sat above a line drawn under the whole tree).

#[test]
fn the_heat_maps_legend_names_every_count_a_pixel_has() {
    let AnyScene::Space(scene) = lesson_scene("whitted_small.json") else { panic!("3D") };
    let tracing = sampled(Sampling::adaptive(0.1, 2).expect("valid"));
    let traces = record(FigureKind::HeatMap, &scene, "whitted_small", &Aim::Auto, &tracing).expect("traced");
    let counts = traces.counts.as_ref().expect("counts").per_pixel.clone();
    let opts = Options { lang: Lang::En, width: 1920, height: 1080 };
    let d = draw(FigureKind::HeatMap, &traces, &scene, &opts).expect("drawn");
    let unit = format!(" {}", Label::SamplesUnit.text(Lang::En));
    // The swatches (the last line says the scale is shared).
    let ranges: Vec<(u32, u32)> = d
        .legend
        .iter()
        .filter(|e| matches!(e.sample, whitted::canvas::LegendIcon::Swatch(_)))
        .map(|e| {
            let range = e.label.strip_suffix(&unit).unwrap_or_else(|| panic!("{}", e.label));
            let (a, b) = range.split_once('–').unwrap_or((range, range));
            (a.parse().expect("a count"), b.parse().expect("a count"))
        })
        .collect();
    assert!(ranges.len() >= 3, "{ranges:?}");
    for n in counts {
        assert!(ranges.iter().any(|(a, b)| (*a..=*b).contains(&n)), "{n} is in no legend line of {ranges:?}");
    }
    assert!(d.title.as_deref() == Some(Label::TitleHeatMap.text(Lang::En)));
    assert!(d.caption.clone().unwrap_or_default().contains(Label::HeatMapCounts.text(Lang::En)));
}

#[test]
fn an_object_listed_in_a_cell_only_through_its_bounding_box_is_drawn_and_named_as_such() {
    // groups_2d, the grid lesson's walk: cell 2, (4, 2), lists the segment h because h's box
    // reaches into it; h itself lies below the cell.
    let AnyScene::Flat(scene) = lesson_scene("groups_2d.json") else { panic!("2D") };
    let d = drawn(&scene, "groups_2d", FigureKind::GridDda, &Aim::Auto, &TraceOptions::SCENE);
    assert!(has_legend(&d, Label::ListedByBox));
    let h = (0..scene.objects.len()).find(|o| scene.object_label(*o, Lang::En) == "h").expect("h");
    assert_eq!(tagged(&d, &format!("object-box-only:{h}")), 1);
    let listing = d.to_text();
    assert!(
        listing.contains(&format!("2: (4, 2) · (8.482, 8.968) · h ({})", Label::BoxOnly.text(Lang::En))),
        "{listing}"
    );
    // Cell 1 lists e, whose circle does reach into it: no such mark.
    assert!(listing.contains("1: (4, 3) · (8.482, 7.473) · e\""), "{listing}");
}
