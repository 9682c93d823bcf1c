//! The diagrams (issue 6 item 5): a snapshot of each kind's display list on fixture scenes, one
//! test per kind, as the library lists it (`Drawing::to_text`); every SVG parses and holds one
//! tagged group per item; every PNG has its size, is not blank and shows the colour of each ray
//! kind its trace holds; labels come in both languages.

use crate::support::{fixture, fixture_path, whitted, SceneText, Scratch};
use glam::DVec2;
use whitted::canvas::{skia, svg};
use whitted::canvas::{Drawing, LegendIcon, Mark};
use whitted::figure::labels::Label;
use whitted::figure::plane::Planar;
use whitted::figure::source::{record, Aim, TraceOptions};
use whitted::figure::style::{RayRole, Rgba};
use whitted::figure::{draw, FigureKind, Lang, Options};
use whitted::geom::ray::Ray;
use whitted::record::event::{Event, RayKind};
use whitted::scene::load::load_str;
use whitted::scene::{AnyScene, Scene};

/// Every kind.
const DRAWN: [FigureKind; 19] = FigureKind::ALL;

/// How a kind is traced in the tests: the sampling kinds adaptively (threshold 0.1, K = 2); the
/// grid of the pitfall fixture with its 4 × 4 × 4 cells.
fn tracing_for(kind: FigureKind, scene: &str) -> TraceOptions {
    let mut t = TraceOptions::SCENE;
    if matches!(kind, FigureKind::HeatMap | FigureKind::Adaptive) {
        t.sampling = TraceOptions::ADAPTIVE;
    }
    if kind == FigureKind::GridDda && scene.starts_with("grid_pitfall") {
        t.accel.grid = Some(vec![4, 4, 4]);
    }
    t
}

fn tracing(kind: FigureKind) -> TraceOptions {
    tracing_for(kind, "")
}

/// A small canvas for the fast tests.
const SMALL: (u32, u32) = (480, 270);

fn figure_in<V: Planar>(
    scene: &Scene<V>,
    name: &str,
    kind: FigureKind,
    aim: &Aim<V>,
    lang: Lang,
    size: (u32, u32),
) -> Drawing {
    let traces = record(kind, scene, name, aim, &tracing_for(kind, name))
        .unwrap_or_else(|e| panic!("{name} {kind:?}: {e}"));
    let opts = Options { lang, width: size.0, height: size.1 };
    draw(kind, &traces, scene, &opts).unwrap_or_else(|e| panic!("{name} {kind:?}: {e}"))
}

/// Figure `kind` of a fixture, the figure picking its pixel.
fn figure(kind: FigureKind, name: &str, lang: Lang, size: (u32, u32)) -> Drawing {
    let stem = name.trim_end_matches(".json");
    match load_str(&fixture(name)).expect("fixture loads") {
        AnyScene::Flat(s) => figure_in(&s, stem, kind, &Aim::Auto, lang, size),
        AnyScene::Space(s) => figure_in(&s, stem, kind, &Aim::Auto, lang, size),
    }
}

/// The fixtures each kind is snapshot on: one 3D and one 2D scene where both make sense.
fn fixtures(kind: FigureKind) -> &'static [&'static str] {
    match kind {
        FigureKind::LocalModel => &["ortho_box.json", "lens_2d.json"],
        FigureKind::RayTree => &["glass.json", "corridor.json"],
        FigureKind::Refraction => &["glass.json", "lens_2d.json"],
        FigureKind::Bvh | FigureKind::Octree => &["glass.json", "groups_2d.json"],
        FigureKind::GridDda => &["grid_pitfall.json", "groups_2d.json"],
        FigureKind::KayKajiya => &["ortho_box.json", "lens_2d.json"],
        _ => &["glass.json", "lens_2d.json"],
    }
}

/// Snapshots the display list of `kind` on each of its fixtures, as the library lists it
/// (`Drawing::to_text`), in `snapshots/integration__figures__figure@KIND@FIXTURE.snap`.
fn display_list_snapshots(kind: FigureKind) {
    for name in fixtures(kind) {
        let d = figure(kind, name, Lang::En, (1920, 1080));
        insta::with_settings!({ snapshot_suffix => format!("{}@{name}", kind.name()), omit_expression => true }, {
            insta::assert_snapshot!("figure", d.to_text());
        });
    }
}

/// One display-list test per kind, so that a failing test's name says which kind broke; and
/// `SNAPSHOT_KINDS`, the kinds so covered.
macro_rules! display_list_tests {
    ($($test:ident: $kind:ident),* $(,)?) => {
        const SNAPSHOT_KINDS: &[FigureKind] = &[$(FigureKind::$kind),*];
        $(
            #[test]
            fn $test() {
                display_list_snapshots(FigureKind::$kind);
            }
        )*
    };
}

display_list_tests! {
    display_list_backward: BackwardRays,
    display_list_camera_frame: CameraFrame,
    display_list_uv_map: UvMap,
    display_list_projections: Projections,
    display_list_rays: Rays,
    display_list_refraction: Refraction,
    display_list_local_model: LocalModel,
    display_list_ray_tree: RayTree,
    display_list_shadows: Shadows,
    display_list_jagged_edges: JaggedEdges,
    display_list_complexity: Complexity,
    display_list_discriminant: Discriminant,
    display_list_slab_test: SlabTest,
    display_list_kay_kajiya: KayKajiya,
    display_list_bvh: Bvh,
    display_list_grid_dda: GridDda,
    display_list_octree: Octree,
    display_list_adaptive: Adaptive,
    display_list_heat_map: HeatMap,
}

#[test]
fn every_kind_has_its_display_list_test() {
    assert_eq!(SNAPSHOT_KINDS, DRAWN, "one display_list_* test per FigureKind, in FigureKind::ALL's order");
}

#[test]
fn the_ray_tree_keeps_its_words_clear_of_the_depth_limit_and_of_edges_straight_down() {
    // glass: words under the nodes, a stopped node with a shadow child below the line;
    // corridor: a deep tree, words beside the nodes, the last node stopped; the lesson's two
    // mirrors (pixel 4): the last level's shadow leaves and their s, all above the line.
    let mirrors = || {
        let path = format!("{}/lessons/scenes/mirrors_2d.json", env!("CARGO_MANIFEST_DIR"));
        let AnyScene::Flat(scene) = load_str(&std::fs::read_to_string(path).unwrap()).unwrap() else {
            panic!("a 2D scene")
        };
        figure_in(&scene, "mirrors_2d", FigureKind::RayTree, &Aim::Pixel(4, 0), Lang::En, (1920, 1080))
    };
    for name in ["glass.json", "corridor.json", "mirrors_2d"] {
        let d = if name == "mirrors_2d" {
            mirrors()
        } else {
            figure(FigureKind::RayTree, name, Lang::En, (1920, 1080))
        };
        let tf = d.transform();
        let line = d.tagged("depth-limit").next().unwrap_or_else(|| panic!("{name}: no depth-limit line"));
        let Mark::Line { points } = &line.mark else { panic!("{name}: the limit is a line") };
        let y = tf.to_px(points[0]).y;
        let (mut nodes, mut words) = (0, 0);
        for item in &d.items {
            match (&item.mark, item.tag.as_str()) {
                (Mark::Dot { center, radius, .. }, "node" | "node:shadow" | "stopped") => {
                    let (c, r) = (tf.to_px(*center).y, tf.ref_px(*radius));
                    assert!(
                        (c - y).abs() > r,
                        "{name}: a {} at y = {c:.1} ± {r:.1} px meets the line at {y:.1}",
                        item.tag
                    );
                    nodes += 1;
                }
                (Mark::Text(text), "name" | "object") => {
                    let placed = Drawing::place_text(text, &tf);
                    let (top, bottom) = (placed.bbox.min.y, placed.bbox.max.y);
                    assert!(
                        y < top || y > bottom,
                        "{name}: {:?} spans {top:.1}–{bottom:.1} px, the line is at {y:.1}",
                        text.text
                    );
                    words += 1;
                }
                _ => {}
            }
        }
        assert!(nodes > 3 && words > 3, "{name}: {nodes} nodes, {words} words");
        // An edge straight down runs below the word under its node, never through it.
        let boxes: Vec<_> = d
            .tagged("object")
            .filter_map(|i| match &i.mark {
                Mark::Text(t) => Some(Drawing::place_text(t, &tf).bbox),
                _ => None,
            })
            .collect();
        let mut vertical = 0;
        for item in &d.items {
            let Mark::Line { points } = &item.mark else { continue };
            let (a, b) = (tf.to_px(points[0]), tf.to_px(points[points.len() - 1]));
            if item.tag == "depth-limit" || (a.x - b.x).abs() > 1e-6 {
                continue;
            }
            vertical += 1;
            for bx in &boxes {
                let across =
                    bx.min.x < a.x && a.x < bx.max.x && a.y.max(b.y) > bx.min.y && a.y.min(b.y) < bx.max.y;
                assert!(
                    !across,
                    "{name}: a vertical {} edge at x = {:.1}, y {:.1}–{:.1}, crosses a word {bx:?}",
                    item.tag, a.x, a.y, b.y
                );
            }
        }
        assert!(vertical > 0, "{name}: no edge straight down");
    }
}

#[test]
fn refraction_draws_the_total_internal_reflection_of_a_given_ray() {
    let AnyScene::Flat(scene) = load_str(&fixture("tir_slab_2d.json")).unwrap() else { panic!("2D") };
    // numerics.md E3: inside the slab at 30° to the wall, θᵢ = 60° > θ_c ≈ 41.8°.
    let ray = Ray::new(DVec2::new(-0.5, 0.0), DVec2::new(3f64.sqrt() / 2.0, 0.5));
    let d = figure_in(&scene, "tir_slab_2d", FigureKind::Refraction, &Aim::Ray(ray), Lang::En, SMALL);
    let texts: Vec<&str> = d
        .items
        .iter()
        .filter_map(|i| match &i.mark {
            Mark::Text(t) => Some(t.text.as_str()),
            _ => None,
        })
        .collect();
    assert!(texts.iter().any(|t| t.contains("θ_c = asin(n_2/n_1) = 41.8°")), "{texts:?}");
    assert!(texts.iter().any(|t| t.contains("θ_i = 60.0°")), "{texts:?}");
    assert!(texts.iter().any(|t| t.contains(Label::NoT.text(Lang::En))), "{texts:?}");
    // No T ray is drawn for a total internal reflection.
    assert_eq!(d.tagged(RayRole::Transmitted.tag()).count(), 0);
    insta::assert_snapshot!("figure_refraction_tir", d.to_text());
}

#[test]
fn every_svg_parses_and_has_one_tagged_group_per_item() {
    for kind in DRAWN {
        for name in fixtures(kind) {
            for lang in [Lang::En, Lang::Ro] {
                let d = figure(kind, name, lang, SMALL);
                let text = svg::to_svg(&d);
                let doc =
                    roxmltree::Document::parse(&text).unwrap_or_else(|e| panic!("{kind:?} {name}: {e}"));
                let groups =
                    doc.descendants().filter(|n| n.has_tag_name("g") && n.attribute("data-tag").is_some());
                assert_eq!(groups.count(), d.items.len(), "{kind:?} {name} {lang:?}");
            }
        }
    }
}

/// The PNG's pixels as RGBA rows.
fn pixels(d: &Drawing) -> (u32, u32, Vec<[u8; 4]>) {
    let png = skia::to_png(d).expect("png");
    let img = image::load_from_memory(&png).expect("decode").to_rgba8();
    let (w, h) = img.dimensions();
    (w, h, img.pixels().map(|p| p.0).collect())
}

/// How many pixels are within `tolerance` per channel of `colour`.
fn count(pixels: &[[u8; 4]], colour: Rgba, tolerance: i32) -> usize {
    pixels
        .iter()
        .filter(|p| {
            (i32::from(p[0]) - i32::from(colour.r)).abs() <= tolerance
                && (i32::from(p[1]) - i32::from(colour.g)).abs() <= tolerance
                && (i32::from(p[2]) - i32::from(colour.b)).abs() <= tolerance
        })
        .count()
}

#[test]
fn every_png_has_its_size_and_is_not_blank() {
    for kind in DRAWN {
        for name in fixtures(kind) {
            let d = figure(kind, name, Lang::Ro, SMALL);
            let (w, h, px) = pixels(&d);
            assert_eq!((w, h), SMALL, "{kind:?} {name}");
            let white = count(&px, Rgba::rgb(255, 255, 255), 0);
            assert!(white < px.len() * 97 / 100, "{kind:?} {name}: almost blank");
        }
    }
}

/// The ray roles a trace holds, read from its events.
fn roles_of<V: Planar>(scene: &Scene<V>, pixel: (usize, usize)) -> Vec<RayRole> {
    let traces =
        record(FigureKind::Rays, scene, "s", &Aim::Pixel(pixel.0, pixel.1), &TraceOptions::SCENE).unwrap();
    let log = &traces.traces[0].log;
    let mut roles = vec![RayRole::Primary];
    if log.nodes.iter().any(|n| n.start.kind == RayKind::Reflected) {
        roles.push(RayRole::Reflected);
    }
    if log.nodes.iter().any(|n| n.start.kind == RayKind::Transmitted) {
        roles.push(RayRole::Transmitted);
    }
    for l in &log.events {
        if let Event::ShadowRay { occluders, .. } = &l.event {
            let role = if occluders.is_empty() { RayRole::Shadow } else { RayRole::BlockedShadow };
            if !roles.contains(&role) {
                roles.push(role);
            }
        }
    }
    roles
}

#[test]
fn a_slide_size_rays_png_shows_the_colour_of_every_ray_kind_in_its_trace() {
    let AnyScene::Space(scene) = load_str(&fixture("glass.json")).unwrap() else { panic!("3D") };
    let pixel = (4, 2);
    let roles = roles_of(&scene, pixel);
    assert!(roles.len() >= 4, "the fixture pixel shows most kinds: {roles:?}");
    let d =
        figure_in(&scene, "glass", FigureKind::Rays, &Aim::Pixel(pixel.0, pixel.1), Lang::En, (1920, 1080));
    let (w, h, px) = pixels(&d);
    assert_eq!((w, h), (1920, 1080));
    for role in RayRole::ALL {
        let n = count(&px, role.color(), 6);
        if roles.contains(&role) {
            assert!(n > 50, "{role:?}: {n} pixels of its colour");
        }
    }
    // The legend names exactly the roles present.
    let legend: Vec<&str> =
        d.legend.iter().filter(|e| e.sample == LegendIcon::Arrow).map(|e| e.label.as_str()).collect();
    assert_eq!(legend.len(), roles.len(), "{legend:?} vs {roles:?}");
}

#[test]
fn labels_come_in_both_languages() {
    let titles = [
        (FigureKind::UvMap, Label::TitleUvMap),
        (FigureKind::Projections, Label::TitleProjections),
        (FigureKind::Rays, Label::TitleRays),
        (FigureKind::Refraction, Label::TitleRefraction),
        (FigureKind::RayTree, Label::TitleRayTree),
        (FigureKind::Shadows, Label::TitleShadows),
        (FigureKind::Adaptive, Label::TitleAdaptive),
        (FigureKind::HeatMap, Label::TitleHeatMap),
        (FigureKind::SlabTest, Label::TitleSlabTest),
        (FigureKind::KayKajiya, Label::TitleKayKajiya),
        (FigureKind::Bvh, Label::TitleBvh),
        (FigureKind::GridDda, Label::TitleGridDda),
        (FigureKind::Octree, Label::TitleOctree),
        (FigureKind::BackwardRays, Label::TitleBackward),
        (FigureKind::CameraFrame, Label::TitleCameraFrame),
        (FigureKind::JaggedEdges, Label::TitleJagged),
        (FigureKind::Complexity, Label::TitleComplexity),
        (FigureKind::Discriminant, Label::TitleDiscriminant),
    ];
    for (kind, title) in titles {
        for lang in [Lang::En, Lang::Ro] {
            let d = figure(kind, "glass.json", lang, SMALL);
            assert_eq!(d.title.as_deref(), Some(title.text(lang)), "{kind:?}");
            // The scene's file name leads an English caption; a Romanian one leaves it out, as
            // English on the slide (issue 32 item 4).
            let caption = d.caption.as_deref().unwrap_or_default();
            match lang {
                Lang::En => assert!(caption.starts_with(Label::Scene.text(lang)), "{kind:?} {lang:?}"),
                Lang::Ro => {
                    assert!(!caption.starts_with(Label::Scene.text(lang)), "{kind:?} {lang:?}: {caption}")
                }
            }
        }
    }
    let ro = figure(FigureKind::Rays, "glass.json", Lang::Ro, SMALL);
    assert!(ro.legend.iter().any(|e| e.label == "rază primară P"));
    assert!(ro.legend.iter().any(|e| e.label == "rază transmisă T"));
    let tree = figure(FigureKind::RayTree, "glass.json", Lang::Ro, SMALL);
    assert!(tree.caption.as_deref().is_some_and(|c| c.contains("adâncimea maximă")));
}

#[test]
fn every_kind_is_listed_with_a_description_and_unknown_names_are_refused() {
    assert_eq!(FigureKind::ALL.len(), 19);
    for kind in FigureKind::ALL {
        assert_eq!(FigureKind::from_name(kind.name()), Some(kind));
        assert!(!kind.description().is_empty());
    }
    assert_eq!(FigureKind::from_name("ray_tree"), None);
}

#[test]
fn a_figure_reads_the_trace_it_was_given() {
    // The uv-map's (u, v) is the primary ray's recorded one, and the pixel the one asked for.
    let AnyScene::Space(scene) = load_str(&fixture("glass.json")).unwrap() else { panic!("3D") };
    let d = figure_in(&scene, "glass", FigureKind::UvMap, &Aim::Pixel(1, 5), Lang::En, SMALL);
    let (u, v) = scene.camera.pixel_center(1, 5);
    let expected = format!("({}, {})", whitted::format::slide_number(u), whitted::format::slide_number(v));
    assert!(d.items.iter().any(|i| matches!(&i.mark, Mark::Text(t) if t.text == expected)), "{expected}");
    // A pixel outside the image is an error, not a panic.
    assert!(record(FigureKind::Rays, &scene, "glass", &Aim::Pixel(8, 0), &TraceOptions::SCENE).is_err());
    // A kind that needs a refraction refuses a pixel without one.
    let AnyScene::Space(boxes) = load_str(&fixture("ortho_box.json")).unwrap() else { panic!("3D") };
    let err = record(FigureKind::Refraction, &boxes, "ortho_box", &Aim::Pixel(0, 0), &TraceOptions::SCENE)
        .unwrap_err();
    assert!(err.0.contains("has no refraction or total internal reflection"), "{err}");
}

#[test]
fn the_figure_command_lists_writes_both_formats_and_refuses_bad_input() {
    let (code, out, _) = whitted(&["figure", "--list"]);
    assert_eq!(code, 0);
    assert_eq!(out.lines().count(), 19);
    assert!(out.lines().any(|l| l.starts_with("ray-tree")));

    let dir = Scratch::new();
    let scene = fixture_path("lens_2d.json");
    // The Romanian rays figure of lens_2d pixel 3 at 640x360, written to `out` with `extra` options.
    let rays_svg = |extra: &[&str], out: &std::path::Path| {
        let mut args = vec!["figure", "rays", &scene, "--pixel", "3", "--lang", "ro", "--size", "640x360"];
        args.extend_from_slice(extra);
        args.extend(["-o", out.to_str().unwrap()]);
        let (code, _, err) = whitted(&args);
        assert_eq!(code, 0, "{err}");
    };
    let svg_path = dir.join("rays.svg");
    rays_svg(&[], &svg_path);
    let text = std::fs::read_to_string(&svg_path).unwrap();
    assert!(roxmltree::Document::parse(&text).is_ok());
    assert!(text.contains("width=\"640\" height=\"360\""));
    assert!(text.contains("rază primară P"));
    // `--svg-text paths`: the same words, kept for readers but not painted, drawn as paths, with
    // no font embedded.
    let paths_path = dir.join("rays-paths.svg");
    rays_svg(&["--svg-text", "paths"], &paths_path);
    let paths = std::fs::read_to_string(&paths_path).unwrap();
    let doc = roxmltree::Document::parse(&paths).unwrap();
    assert!(paths.contains("rază primară P") && !paths.contains("@font-face") && text.contains("@font-face"));
    let texts: Vec<_> = doc.descendants().filter(|n| n.has_tag_name("text")).collect();
    assert!(!texts.is_empty() && texts.iter().all(|t| t.attribute("fill-opacity") == Some("0")));
    assert_eq!(doc.descendants().filter(|n| n.has_tag_name("path")).count(), texts.len());
    let png_path = dir.join("tree.png");
    let (code, _, err) =
        whitted(&["figure", "ray-tree", &scene, "--size", "480x270", "-o", png_path.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let img = image::open(&png_path).unwrap();
    assert_eq!((img.width(), img.height()), (480, 270));

    for (args, expected) in [
        (vec!["figure", "rainbow", scene.as_str()], "unknown figure kind `rainbow`"),
        (vec!["figure", "rays", scene.as_str(), "--pixel", "99"], "outside the image"),
        (vec!["figure", "rays", scene.as_str(), "-o", "x.gif"], "must end in .png or .svg"),
        (vec!["figure", "rays"], "SCENE"),
    ] {
        let (code, _, err) = whitted(&args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(err.contains(expected), "{args:?}: {err}");
    }
}

#[test]
fn the_lessons_command_writes_both_languages_and_the_pages() {
    let scratch = Scratch::new();
    let out = scratch.join("course");
    let lessons = format!("{}/lessons", env!("CARGO_MANIFEST_DIR"));
    let args = [
        "lessons",
        "--lessons",
        &lessons,
        "--only",
        "pixel-uv",
        "--size",
        "480x270",
        "--out",
        out.to_str().unwrap(),
    ];
    let (code, stdout, err) = whitted(&args);
    assert_eq!(code, 0, "{err}");
    assert!(stdout.contains("1 lessons"), "{stdout}");
    for lang in ["en", "ro"] {
        for ext in ["png", "svg"] {
            assert!(out.join(lang).join(format!("pixel-uv-1-uv-map.{ext}")).exists(), "{lang} {ext}");
        }
    }
    let en = std::fs::read_to_string(out.join("index.html")).unwrap();
    let ro = std::fs::read_to_string(out.join("ro").join("index.html")).unwrap();
    assert!(en.contains("src=\"en/pixel-uv-1-uv-map.png\"") && en.contains("whitted figure uv-map"));
    assert!(ro.contains("src=\"pixel-uv-1-uv-map.png\"") && ro.contains("--lang ro"));
    assert!(ro.contains("Calculul coordonatelor (u, v)"));
    let (code, _, err) =
        whitted(&["lessons", "--lessons", &lessons, "--only", "nothing", "--out", out.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(err.contains("no lesson is named `nothing`"));
}

#[test]
fn every_lesson_file_reads() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons");
    let mut names = Vec::new();
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "json") {
            let lesson = whitted::lesson::parse(&std::fs::read_to_string(&path).unwrap())
                .unwrap_or_else(|e| panic!("{}: {e:?}", path.display()));
            for spec in &lesson.figures {
                let scene = std::fs::read_to_string(dir.join(&spec.scene)).unwrap();
                assert!(load_str(&scene).is_ok(), "{}: {}", path.display(), spec.scene);
            }
            names.push(lesson.name);
        }
    }
    let count = names.len();
    names.sort();
    names.dedup();
    assert_eq!(names.len(), count, "lesson names are unique");
}

/// Every finite coordinate of a display list (a NaN or an infinity is a bug).
fn assert_finite_items(d: &Drawing, what: &str) {
    let finite = |p: &DVec2| p.is_finite();
    for item in &d.items {
        let ok = match &item.mark {
            Mark::Line { points } | Mark::Polygon { points, .. } => points.iter().all(finite),
            Mark::Arrow { from, to, .. } => finite(from) && finite(to),
            Mark::Circle { center, radius, .. } => finite(center) && radius.is_finite(),
            Mark::Dot { center, .. } => finite(center),
            Mark::Rect { min, max, .. } => finite(min) && finite(max),
            Mark::Text(t) => finite(&t.anchor) && finite(&t.offset),
        };
        assert!(ok, "{what}: {}", item.to_text());
    }
}

#[test]
fn every_kind_draws_or_says_why_on_every_scene() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut scenes: Vec<(String, String)> = Vec::new();
    for dir in ["tests/data/scenes", "lessons/scenes", "scenes"] {
        for entry in std::fs::read_dir(root.join(dir)).unwrap() {
            let path = entry.unwrap().path();
            scenes.push((path.display().to_string(), std::fs::read_to_string(&path).unwrap()));
        }
    }
    // Edge cases: nothing in the scene, no light, a ray that leaves at once.
    let empty3 = SceneText::space3(4, 3);
    let dark2 = SceneText::flat2(3).object(
        serde_json::json!({"type": "sphere", "center": [0, 0], "radius": 1, "material": {"kt": 0.5, "ior": 1.3}}),
    );
    scenes.push(("empty3".into(), empty3.text()));
    scenes.push(("dark2".into(), dark2.text()));
    for (name, text) in &scenes {
        let scene = load_str(text).unwrap_or_else(|e| panic!("{name}: {e:?}"));
        for kind in DRAWN {
            let made = match &scene {
                AnyScene::Flat(s) => try_figure(s, kind),
                AnyScene::Space(s) => try_figure(s, kind),
            };
            match made {
                Ok(d) => assert_finite_items(&d, &format!("{name} {kind:?}")),
                // Only the kinds that need a refraction, a hit or a shadow ray may refuse.
                // Only the kinds that need a refraction, a hit, a shadow ray or a bounded object
                // may refuse.
                Err(e) => assert!(
                    matches!(
                        kind,
                        FigureKind::Refraction
                            | FigureKind::BackwardRays
                            | FigureKind::Discriminant
                            | FigureKind::LocalModel
                            | FigureKind::Shadows
                            | FigureKind::SlabTest
                            | FigureKind::KayKajiya
                            | FigureKind::Bvh
                            | FigureKind::Octree
                            | FigureKind::GridDda
                    ),
                    "{name} {kind:?}: {e}"
                ),
            }
        }
    }
}

fn try_figure<V: Planar>(scene: &Scene<V>, kind: FigureKind) -> Result<Drawing, String> {
    let traces = record(kind, scene, "s", &Aim::Auto, &tracing(kind)).map_err(|e| e.0)?;
    draw(kind, &traces, scene, &Options { lang: Lang::Ro, width: 480, height: 270 }).map_err(|e| e.0)
}

/// The aliasing lesson's point, measured on its figure: adjacent rays 0.5 apart at both rows of
/// discs in the orthographic panel, and 1 then 3 apart in the perspective one (discs 0.6 wide),
/// each spacing marked `Δ = …` where the rows lie.
#[test]
fn the_aliasing_figure_marks_the_ray_spacing_at_each_row_of_discs() {
    let path = format!("{}/lessons/scenes/aliasing_2d.json", env!("CARGO_MANIFEST_DIR"));
    let AnyScene::Flat(scene) = load_str(&std::fs::read_to_string(path).unwrap()).unwrap() else {
        panic!("a 2D scene")
    };
    let d = figure_in(&scene, "aliasing_2d", FigureKind::Projections, &Aim::Auto, Lang::En, (1920, 1080));
    let mut marks: Vec<&str> = d
        .tagged("spacing")
        .filter_map(|i| match &i.mark {
            Mark::Text(t) => Some(t.text.as_str()),
            _ => None,
        })
        .collect();
    marks.sort_unstable();
    assert_eq!(marks, ["Δ = 0.5", "Δ = 0.5", "Δ = 1", "Δ = 3"]);
}

/// The local model's pick says "N, L, H, V well apart" only when they are: on `lens_2d` every
/// lit pixel tried draws two of them within 10° (2.455° at the one picked), and the caption says
/// so in both languages, while `ortho_box`'s (15°) keeps the old words.
#[test]
fn the_local_model_says_when_no_pixel_keeps_its_vectors_apart() {
    let crowded = [
        (Lang::En, "no pixel tried keeps N, L, H, V 10° apart"),
        (Lang::Ro, "în niciun pixel încercat N, L, H, V nu sunt la 10° unul de altul"),
    ];
    for (lang, words) in crowded {
        let caption = figure(FigureKind::LocalModel, "lens_2d.json", lang, SMALL).caption.unwrap_or_default();
        assert!(caption.contains(words), "{caption}");
        assert!(!caption.contains("well apart") && !caption.contains("distincte"), "{caption}");
    }
    let caption =
        figure(FigureKind::LocalModel, "ortho_box.json", Lang::En, SMALL).caption.unwrap_or_default();
    assert!(caption.contains("N, L, H, V well apart"), "{caption}");
}

/// The BVH over groups_3d (three groups of four spheres on one level) is drawn from above, in the
/// plane xz, where the boxes of sibling groups lie apart: in the yz plane the ray's own direction
/// would suggest, the two front groups would be drawn one over the other.
#[test]
fn the_3d_bvh_figure_chooses_the_plane_where_sibling_groups_lie_apart() {
    let path = format!("{}/lessons/scenes/groups_3d.json", env!("CARGO_MANIFEST_DIR"));
    let AnyScene::Space(scene) = load_str(&std::fs::read_to_string(path).unwrap()).unwrap() else {
        panic!("a 3D scene")
    };
    let d = figure_in(&scene, "groups_3d", FigureKind::Bvh, &Aim::Auto, Lang::En, (1920, 1080));
    assert!(d.caption.as_deref().unwrap_or("").ends_with("drawn in the plane xz"), "{:?}", d.caption);
    let rect = |node: usize| {
        d.items
            .iter()
            .filter(|i| i.tag.starts_with("node-") && i.tag.ends_with(&format!(":{node}")))
            .find_map(|i| match i.mark {
                Mark::Rect { min, max, .. } => Some((min, max)),
                _ => None,
            })
            .unwrap_or_else(|| panic!("node N{node} drawn"))
    };
    let apart = |(a0, a1): (DVec2, DVec2), (b0, b1): (DVec2, DVec2)| {
        a1.x < b0.x || b1.x < a0.x || a1.y < b0.y || b1.y < a0.y
    };
    // N₁ is the far group; N₂ holds the two front groups N₃ and N₄.
    assert!(apart(rect(1), rect(2)) && apart(rect(3), rect(4)));
}

/// On a 640 × 480 image the chosen pixel's square is under a pixel at slide size: the uv-map
/// legend names what marks it, the ringed centre, not a yellow square no one can see.
#[test]
fn the_uv_map_legend_shows_the_pixel_as_it_is_drawn() {
    let whitted = format!("{}/scenes/whitted.json", env!("CARGO_MANIFEST_DIR"));
    let AnyScene::Space(scene) = load_str(&std::fs::read_to_string(whitted).unwrap()).unwrap() else {
        panic!("a 3D scene")
    };
    let d = figure_in(&scene, "whitted", FigureKind::UvMap, &Aim::Auto, Lang::En, (1920, 1080));
    let labels: Vec<&str> = d.legend.iter().map(|e| e.label.as_str()).collect();
    assert!(labels.contains(&"the pixel's centre (ringed)") && !labels.contains(&"the pixel"), "{labels:?}");
}
