//! The narration (`whitted trace` without `--json`) as a student reads it: insta snapshots of
//! the fixtures in both languages, one per family of events (refraction and shadows through
//! glass, a 2D lens, total internal reflection, a grid walk, bounding volumes, an orthographic
//! box), so that every change of wording or number is a reviewed diff; the names it shares with
//! the figures, each step's place in the ray tree, `--object` and `whitted step` over a pipe.

use crate::support::{fixture, fixture_path, whitted, whitted_with_input, Scratch};
use whitted::accel::AccelKind;
use whitted::bounds::VolumeKind;
use whitted::doc::narrate::Lang;
use whitted::request::options::AccelChoice;
use whitted::request::target::Target;
use whitted::request::trace::Trace;
use whitted::sample::Sampling;
use whitted::scene::load::load_str;
use whitted::scene::AnyScene;

/// One narrated case: a fixture, what is traced, the structure.
struct Case {
    name: &'static str,
    scene: &'static str,
    target: Target,
    accel: AccelChoice,
}

fn pixel(i: i64, j: Option<i64>) -> Target {
    Target { pixel: Some((i, j)), ray: None }
}

fn ray(o: &[f64], d: &[f64]) -> Target {
    Target { pixel: None, ray: Some((o.to_vec(), d.to_vec())) }
}

fn accel(kind: AccelKind) -> AccelChoice {
    AccelChoice { kind, ..AccelChoice::default() }
}

fn cases() -> Vec<Case> {
    let (s, c) = (30f64.to_radians().sin(), 30f64.to_radians().cos());
    vec![
        Case { name: "glass", scene: "glass.json", target: pixel(4, Some(3)), accel: AccelChoice::default() },
        Case {
            name: "glass-floor",
            scene: "glass.json",
            target: pixel(1, Some(0)),
            accel: accel(AccelKind::None),
        },
        Case { name: "lens", scene: "lens_2d.json", target: pixel(3, None), accel: accel(AccelKind::None) },
        Case {
            name: "tir",
            scene: "tir_slab_2d.json",
            target: ray(&[0.0, 0.0], &[c, s]),
            accel: accel(AccelKind::None),
        },
        Case {
            name: "grid",
            scene: "grid_pitfall.json",
            target: pixel(0, Some(0)),
            accel: AccelChoice { kind: AccelKind::Grid, volume: None, grid: Some(vec![4, 4, 4]) },
        },
        Case {
            name: "bounds",
            scene: "groups_2d.json",
            target: pixel(5, None),
            accel: AccelChoice { kind: AccelKind::Bounds, volume: Some(VolumeKind::Kdop), grid: None },
        },
        Case {
            name: "ortho",
            scene: "ortho_box.json",
            target: pixel(2, Some(1)),
            accel: accel(AccelKind::None),
        },
    ]
}

fn narrate(case: &Case, lang: Lang) -> whitted::doc::narrate::Narration {
    let scene = load_str(&fixture(case.scene)).unwrap_or_else(|e| panic!("{}: {e:?}", case.scene));
    let trace = Trace {
        target: case.target.clone(),
        depth: None,
        sampling: Sampling::Center,
        accel: case.accel.clone(),
        max_events: whitted::record::DEFAULT_LIMIT,
    };
    trace.narration(&scene, lang).unwrap_or_else(|e| panic!("{}: {}", case.name, e.message)).narration
}

/// The English narration of every fixture, in full: the snapshot a reviewer reads. The Romanian one
/// is checked against it step by step (`the_romanian_narration_tells_the_english_steps`), so a
/// snapshot holds one language and stays small enough to read.
#[test]
fn narrations_of_the_fixtures() {
    for case in cases() {
        let narration = narrate(&case, Lang::En);
        insta::with_settings!({ input_file => fixture_path(case.scene), prepend_module_to_snapshot => false }, {
            insta::assert_snapshot!(format!("narration-{}-en", case.name), narration.text);
        });
    }
}

/// The numbers of a text, in order, as the narration writes them (`−0.374719`, `9.84450e−13`, `4`).
fn numbers(text: &str) -> Vec<String> {
    let mut found = Vec::new();
    let mut current = String::new();
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        let next_is_digit = chars.peek().is_some_and(char::is_ascii_digit);
        let continues = c.is_ascii_digit()
            || (c == '.' && !current.is_empty() && next_is_digit)
            || (c == 'e'
                && !current.is_empty()
                && chars.peek().is_some_and(|n| n.is_ascii_digit() || *n == '−'))
            || (c == '−' && (current.is_empty() || current.ends_with('e')) && next_is_digit);
        if continues {
            current.push(c);
        } else if !current.is_empty() {
            found.push(std::mem::take(&mut current));
        }
    }
    if !current.is_empty() {
        found.push(current);
    }
    found
}

/// The Romanian narration tells the steps of the English one: as many steps, each with the same
/// number, events, indentation, lines and numbers, only the words translated (and in Romanian:
/// diacritics present, no English left).
#[test]
fn the_romanian_narration_tells_the_english_steps() {
    for case in cases() {
        let (en, ro) = (narrate(&case, Lang::En).steps(), narrate(&case, Lang::Ro).steps());
        assert_eq!(en.len(), ro.len(), "{}: steps", case.name);
        for (e, r) in en.iter().zip(&ro) {
            let at = format!("{} step {}", case.name, e.number);
            assert_eq!((e.number, &e.events), (r.number, &r.events), "{at}");
            assert_eq!(e.text.lines().count(), r.text.lines().count(), "{at}:\n{}\n{}", e.text, r.text);
            for (le, lr) in e.text.lines().zip(r.text.lines()) {
                let indent = |l: &str| l.len() - l.trim_start().len();
                assert_eq!(indent(le), indent(lr), "{at}: {le} | {lr}");
                assert_eq!(numbers(le), numbers(lr), "{at}: {le} | {lr}");
            }
            assert_eq!(numbers(&e.place), numbers(&r.place), "{at}: {} | {}", e.place, r.place);
            for english in [" the ray ", "Intersection test", "Nearest hit", " roots ", "entry and exit"] {
                assert!(!r.text.contains(english), "{at}: `{english}` in {}", r.text);
            }
        }
        let all: String = ro.iter().map(|s| s.text.as_str()).collect();
        assert!(all.contains(['ă', 'â', 'î', 'ș', 'ț']), "{}: no diacritics", case.name);
    }
}

#[test]
fn numbers_are_read_as_the_narration_writes_them() {
    assert_eq!(
        numbers("t = −0.374719, −9.84450e−13 → lights[0], 4.5·2 e.g. I₁ max_depth 5."),
        ["−0.374719", "−9.84450e−13", "0", "4.5", "2", "5"]
    );
}

/// Every ray and hit the figures name (`record::names`) is named in the narration, in its own
/// heading, and every step's place ends with the level of a ray of the tree.
#[test]
fn the_narration_names_rays_and_hits_as_the_figures_do() {
    use glam::DVec3;
    use whitted::accel::Accel;
    use whitted::record::names::Names;
    use whitted::record::EventLog;
    use whitted::trace::Tracer;
    let text = fixture("glass.json");
    let AnyScene::Space(scene) = load_str(&text).unwrap() else { panic!("3D") };
    let (u, v) = scene.camera.pixel_center(4, 3);
    let accel = Accel::build(&scene, AccelKind::Bvh);
    let mut tracer = Tracer::new(&scene, &accel, EventLog::<DVec3>::new());
    tracer.trace_primary(&scene.camera.primary_ray(u, v), &[u, v]);
    let names = Names::of(&tracer.recorder);
    let told = narrate(&cases()[0], Lang::En);
    assert_eq!(names.ray_text(0), "P");
    for (node, ray) in tracer.recorder.nodes.iter().enumerate() {
        let name = names.ray_text(node);
        let title = format!(" {name} — ");
        assert!(told.text.contains(&title), "no heading `{title}`");
        if let Some(hit) = names.hit_text(node) {
            assert!(told.text.contains(&format!("Nearest hit of {name}: {hit} on")), "{name}: {hit}");
            for term in ray.lights.iter().filter(|t| t.lum > 0.0) {
                let shadow = names.shadow_text(node, term.light);
                assert!(told.text.contains(&format!("shadow ray {shadow}\n")), "{shadow}");
            }
        }
    }
    // The markup the figures draw spells the same names.
    assert_eq!(names.ray[1], "R_1");
    assert_eq!(names.ray_text(1), "R₁");
    let steps = told.steps();
    assert_eq!(steps.len(), told.places.len());
    assert_eq!(steps[0].place, "pixel (4, 3)");
    assert!(steps.iter().any(|s| s.place == "P → T₁ → R₂ @ glass, level 3"), "{:?}", told.places);
    for step in &steps {
        assert!(step.place == "pixel (4, 3)" || step.place.starts_with("P"), "{}", step.place);
    }
}

/// A grid walk tells each cell before the tests made in it, and still names each test's event.
#[test]
fn a_grid_cell_is_told_before_its_tests() {
    let told = narrate(&cases()[4], Lang::En);
    let cell = told.text.find("Voxel [0, 0, 2]").expect("the cell");
    let a = told.text.find("Intersection test of P with “A”").expect("the test of A");
    assert!(cell < a, "{}", told.text);
    let steps = told.steps();
    let k = steps.iter().position(|s| s.text.contains("Voxel [")).unwrap();
    // The log recorded the test before the cell; the narration tells the cell first.
    assert!(steps[k + 1].text.contains("“A”") && steps[k + 1].events[0] < steps[k].events[0]);
}

#[test]
fn object_picks_the_pixel_that_shows_it() {
    let glass = fixture_path("glass.json");
    let (code, out, err) = whitted(&["trace", &glass, "--object", "glass"]);
    assert_eq!(code, 0, "{err}");
    let at = err
        .lines()
        .find_map(|l| l.strip_prefix("whitted: --object glass: --pixel "))
        .expect("the pixel said");
    let (_, by_pixel, _) = whitted(&["trace", &glass, "--pixel", at]);
    assert_eq!(out, by_pixel);
    assert!(out.contains("Nearest hit of P: I₁ on “glass”"), "{out}");
    let (code, _, err) = whitted(&["trace", &glass, "--object", "chair"]);
    assert_eq!(code, 2);
    assert!(
        err.contains("--object: no object is named `chair`; the named objects: floor, mirror, glass"),
        "{err}"
    );
    let (code, _, err) = whitted(&["trace", &glass, "--object", "glass", "--pixel", "1,1"]);
    assert_eq!(code, 2, "{err}");
    let dir = Scratch::new();
    let (code, _, err) =
        whitted(&["figure", "rays", &glass, "--object", "mirror", "-o", &dir.arg("object.svg")]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("--object mirror: --pixel "), "{err}");
}

#[test]
fn step_over_a_pipe_echoes_the_answers_and_says_where_each_step_stands() {
    let glass = fixture_path("glass.json");
    let (_, shown, _) = whitted_with_input(&["step", &glass, "--pixel", "4,3", "--lang", "ro"], "44\nb\nq\n");
    assert!(shown.contains("[1/84] > 44\n── P → T₁ → R₂ → R₃ @ glass, nivelul 4\n"), "{shown}");
    assert!(shown.contains("[44/84] > b\n") && shown.contains("[43/84] > q\n"), "{shown}");
    assert!(shown.contains("── pixelul (4, 3)\n1. Pixelul"), "{shown}");
}
