//! The narration (`whitted trace` without `--json`) as a student reads it: insta snapshots of
//! the fixtures in both languages, one per family of events (refraction and shadows through
//! glass, a 2D lens, total internal reflection, a grid walk, bounding volumes, an orthographic
//! box), so that every change of wording or number is a reviewed diff.

use crate::support::{fixture, fixture_path};
use whitted::accel::AccelKind;
use whitted::bounds::VolumeKind;
use whitted::doc::narrate::Lang;
use whitted::request::options::AccelChoice;
use whitted::request::target::Target;
use whitted::request::trace::Trace;
use whitted::sample::Sampling;
use whitted::scene::load::load_str;

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

#[test]
fn narrations_of_the_fixtures_in_both_languages() {
    for case in cases() {
        for (lang, tag) in [(Lang::En, "en"), (Lang::Ro, "ro")] {
            let narration = narrate(&case, lang);
            insta::with_settings!({ input_file => fixture_path(case.scene), prepend_module_to_snapshot => false }, {
                insta::assert_snapshot!(format!("narration-{}-{tag}", case.name), narration.text);
            });
        }
    }
}
