//! Lesson claims (product.md "Lessons", `lesson::claim`): every figure of every lesson states what
//! it must show and shows it; the old scenes and pixels that did not show their point fail.

use crate::support::lesson_files;
use std::path::Path;
use whitted::figure::{Lang, Options};
use whitted::lesson::claim::Verdict;
use whitted::lesson::{self, FigureSpec};
use whitted::request::figure::{figure_checked, Request};
use whitted::scene::load::load_str;

/// The verdicts of one lesson figure's claims, drawn as `whitted lessons` draws it (no PNG).
fn verdicts(dir: &Path, spec: &FigureSpec, lang: Lang) -> Vec<Verdict> {
    let scene = load_str(&std::fs::read_to_string(dir.join(&spec.scene)).unwrap()).unwrap();
    let request = Request::of_lesson(spec, Options::slide(lang));
    figure_checked(&scene, "scene", &request, &spec.claims).unwrap().1
}

/// The failed claims of a lesson's figures, as `whitted lessons` words them.
fn failures(dir: &Path, text: &str, lang: Lang) -> Vec<String> {
    let lesson = lesson::parse(text).unwrap_or_else(|e| panic!("{e:?}"));
    let mut failed = Vec::new();
    for (k, spec) in lesson.figures.iter().enumerate() {
        for v in verdicts(dir, spec, lang).iter().filter(|v| !v.holds()) {
            failed.push(v.message(&lesson.name, k + 1, spec.kind.name()));
        }
    }
    failed
}

#[test]
fn every_lesson_figure_states_its_point_and_shows_it_in_both_languages() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons");
    let mut failed = Vec::new();
    for (path, text) in lesson_files() {
        let lesson = lesson::parse(&text).unwrap();
        for (k, spec) in lesson.figures.iter().enumerate() {
            assert!(!spec.claims.is_empty(), "{} figure {}: no claim", path.display(), k + 1);
        }
        for lang in [Lang::En, Lang::Ro] {
            failed.extend(failures(&dir, &text, lang));
        }
    }
    assert!(failed.is_empty(), "{}", failed.join("\n"));
}

/// Numbers keep the decimal point in both languages (docs/algorithm.md, the lecture's `i + 0.5`):
/// a Romanian caption that wrote 0,5 beside a figure that writes 0.5 would teach two notations.
#[test]
fn every_lesson_writes_numbers_with_the_decimal_point_in_both_languages() {
    let mut found = Vec::new();
    for (path, text) in lesson_files() {
        let lesson = lesson::parse(&text).unwrap();
        let captions = lesson.figures.iter().map(|f| &f.caption);
        for words in [&lesson.title, &lesson.text].into_iter().chain(captions) {
            for text in [&words.en, &words.ro] {
                let chars: Vec<char> = text.chars().collect();
                let comma =
                    chars.windows(3).any(|w| w[0].is_ascii_digit() && w[1] == ',' && w[2].is_ascii_digit());
                if comma {
                    found.push(format!("{}: {text}", path.display()));
                }
            }
        }
    }
    assert!(found.is_empty(), "a decimal comma:\n{}", found.join("\n"));
}

/// A lesson scene names its objects in both languages (`{ "en": "mirror", "ro": "oglindă" }`): a
/// Romanian figure that labels "ball" teaches in two languages at once. Letters and codes (`a`,
/// `A`, `o12`) are the same in both and may stay one string.
#[test]
fn every_lesson_scene_names_its_objects_in_both_languages() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons/scenes");
    let mut english_only = Vec::new();
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let scene: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
        for object in scene["objects"].as_array().into_iter().flatten() {
            if let Some(name) = object["name"].as_str() {
                let code = name.chars().count() <= 1 || name.chars().skip(1).all(|c| c.is_ascii_digit());
                if !code {
                    english_only.push(format!("{}: {name}", path.display()));
                }
            }
        }
    }
    assert!(english_only.is_empty(), "named in one language only:\n{}", english_only.join("\n"));
}

/// The old scenes and pixels that did not show their point (issue "taught right", item 1), each
/// with the claim that now fails on it: the grid pitfall whose first voxel already held the
/// nearer sphere (its box leaked into it, the ray ran along a cell boundary), the 3D slab chart
/// of a near-axis ray, the flat heat map of corner sampling, the BVH of one node, and Whitted's
/// shadow figure whose primary ray was drawn through the glass sphere, and the 2D local model
/// whose L and N lay 3.25° apart — the same hit on the mirror that the ray-casting lesson drew,
/// its N hidden under L.
#[test]
fn the_old_scenes_and_pixels_fail_their_claims() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/claims");
    let old = r#"{ "name": "old", "title": { "en": "old", "ro": "vechi" }, "figures": [
        { "kind": "grid-dda", "scene": "pitfall-old.json", "grid": [4, 4, 4],
          "claims": [ { "kind": "grid-pitfall", "min": 1 } ],
          "caption": { "en": "", "ro": "" } },
        { "kind": "slab-test", "scene": "../../../scenes/whitted.json",
          "claims": [ { "kind": "intervals", "min": 5 } ], "caption": { "en": "", "ro": "" } },
        { "kind": "heat-map", "scene": "../../../lessons/scenes/whitted_small.json", "aa": "corners",
          "claims": [ { "kind": "heat-values", "min": 3 } ], "caption": { "en": "", "ro": "" } },
        { "kind": "bvh", "scene": "../../../scenes/whitted.json",
          "claims": [ { "kind": "nodes", "min": 5 } ], "caption": { "en": "", "ro": "" } },
        { "kind": "shadows", "scene": "../../../scenes/whitted.json", "pixel": [292, 227],
          "claims": [ { "kind": "false-crossings", "max": 0 } ], "caption": { "en": "", "ro": "" } },
        { "kind": "local-model", "scene": "../../../scenes/flat.json", "pixel": [20],
          "claims": [ { "kind": "apart", "min": 10 } ], "caption": { "en": "", "ro": "" } },
        { "kind": "refraction", "scene": "prism-old.json",
          "claims": [ { "kind": "incidence", "min": 20, "max": 60 } ], "caption": { "en": "", "ro": "" } },
        { "kind": "rays", "scene": "../../../scenes/flat.json", "pixel": [20], "depth": 0,
          "claims": [ { "kind": "apart", "min": 10 } ], "caption": { "en": "", "ro": "" } },
        { "kind": "bvh", "scene": "../../../lessons/scenes/crowd_2d.json", "pixel": [13],
          "claims": [ { "kind": "events", "event": "hit", "min": 1 } ], "caption": { "en": "", "ro": "" } } ] }"#;
    let failed = failures(&dir, old, Lang::En);
    let expected = [
        "old figure 1 (grid-dda): claim grid-pitfall (voxels from the early find to the accepted hit): wanted ≥ 1, measured 0",
        "old figure 2 (slab-test): claim intervals",
        "old figure 3 (heat-map): claim heat-values: wanted ≥ 3, measured 1",
        "old figure 4 (bvh): claim nodes: wanted ≥ 5, measured 1",
        "old figure 5 (shadows): claim false-crossings: wanted ≤ 0, measured 1",
        "old figure 6 (local-model): claim apart (least angle between N, V, L, H, °): wanted ≥ 10, measured 3.25",
        "old figure 7 (refraction): claim incidence",
        "old figure 8 (rays): claim apart (least angle between N, V, L, H, °): wanted ≥ 10, measured 3.25",
        "old figure 9 (bvh): claim events hit: wanted ≥ 1, measured 0",
    ];
    assert_eq!(failed.len(), expected.len(), "{}", failed.join("\n"));
    for (line, want) in failed.iter().zip(expected) {
        assert!(line.starts_with(want), "{line}\nwanted it to start with {want}");
    }
}

#[test]
fn lessons_writes_nothing_and_exits_1_when_a_claim_fails() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let tmp = crate::support::Scratch::new();
    let lessons = tmp.join("lessons");
    std::fs::create_dir(&lessons).unwrap();
    let scene = root.join("scenes/whitted.json");
    let text = format!(
        r#"{{ "name": "one", "title": {{ "en": "t", "ro": "t" }}, "figures": [
            {{ "kind": "bvh", "scene": "{}", "claims": [ {{ "kind": "nodes", "min": 5 }} ],
               "caption": {{ "en": "", "ro": "" }} }} ] }}"#,
        scene.display()
    );
    std::fs::write(lessons.join("one.json"), text).unwrap();
    let out = tmp.join("out");
    let (code, _, err) = crate::support::whitted(&[
        "lessons",
        "--lessons",
        lessons.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--lang",
        "en",
    ]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("one figure 1 (bvh): claim nodes: wanted ≥ 5, measured 1"), "{err}");
    assert!(!out.join("en/one-1-bvh.png").exists() && !out.join("index.html").exists());
}

/// A lesson figure drawn as `whitted lessons` draws it, with what it traced.
fn made(dir: &Path, spec: &FigureSpec, lang: Lang) -> whitted::request::figure::Made {
    let scene = load_str(&std::fs::read_to_string(dir.join(&spec.scene)).unwrap()).unwrap();
    let stem = Path::new(&spec.scene).file_stem().unwrap().to_string_lossy().into_owned();
    whitted::request::figure::figure(&scene, &stem, &Request::of_lesson(spec, Options::slide(lang))).unwrap()
}

/// Every lesson, in the course's order.
fn lessons() -> Vec<lesson::Lesson> {
    lesson_files().iter().map(|(_, text)| lesson::parse(text).unwrap()).collect()
}

/// What a citation says of the figure it cites.
#[derive(Clone, Copy, Debug)]
enum Fact {
    /// The same scene and traced pixel ("the same pixel", "that pixel").
    SamePixel,
    /// The same scene, pixel and depth: the same ray tree ("its tree").
    SameTrace,
    /// The cited figure traces this pixel, and its first hit is on this object (the English
    /// name): "pixel 32, whose first hit is the lens".
    PixelHit(usize, &'static str),
    /// The cited figure samples adaptively with this threshold and K.
    Adaptive(f64, u32),
}

/// Words of a caption that cite a figure: the caption's lesson and figure (from 1), the words
/// in English and Romanian, the figure cited and what the words say of it.
struct Citation {
    at: (&'static str, usize),
    words: [&'static str; 2],
    cites: (&'static str, usize),
    fact: Fact,
}

/// Every citation of a figure in the lessons' captions (issue 32 item 2). A caption that says
/// "lesson", "the same pixel", "that pixel", "its tree" or "the same scene" (`CITATION_MARKERS`)
/// must have its words here, and what they say is checked on the figures.
const CITATIONS: &[Citation] = &[
    Citation {
        at: ("ray-casting", 2),
        words: ["Ray tracing of the same pixel", "Ray tracing pentru același pixel"],
        cites: ("ray-casting", 1),
        fact: Fact::SamePixel,
    },
    Citation {
        at: ("secondary-rays", 3),
        words: ["The whole trace of that pixel", "Întregul traseu al acelui pixel"],
        cites: ("secondary-rays", 2),
        fact: Fact::SamePixel,
    },
    Citation {
        at: ("ray-tree", 2),
        words: [
            "whose first hit is the mirror (pixel 20",
            "a cărui primă intersecție este oglinda (pixelul 20",
        ],
        cites: ("ray-tree", 2),
        fact: Fact::PixelHit(20, "mirror"),
    },
    Citation {
        at: ("ray-tree", 2),
        words: [
            "the first lesson draws pixel 32, whose first hit is the lens",
            "prima lecție desenează pixelul 32, a cărui primă intersecție este lentila",
        ],
        cites: ("ray-casting", 1),
        fact: Fact::PixelHit(32, "lens"),
    },
    Citation {
        at: ("recursion-depth", 2),
        words: ["The same pixel with max_depth = 3", "Același pixel cu adâncimea maximă 3"],
        cites: ("recursion-depth", 1),
        fact: Fact::SamePixel,
    },
    Citation {
        at: ("recursion-depth", 3),
        words: ["Its tree", "Arborele său"],
        cites: ("recursion-depth", 2),
        fact: Fact::SameTrace,
    },
    Citation {
        at: ("cost", 2),
        words: [
            "The same scene and pixel in a regular grid",
            "Aceeași scenă și același pixel într-o grilă regulată",
        ],
        cites: ("cost", 1),
        fact: Fact::SamePixel,
    },
    Citation {
        at: ("cost", 3),
        words: [
            "the adaptive lesson's 0.1 and K = 2",
            "pragul 0.1 și K = 2 din lecția despre eșantionarea adaptivă",
        ],
        cites: ("adaptive", 2),
        fact: Fact::Adaptive(0.1, 2),
    },
];

/// The words that make a caption or text a citation of another figure, lower-cased, in English
/// and Romanian; each counts as a whole word or phrase (not "the same pixels" of one figure).
const CITATION_MARKERS: [&[&str]; 2] = [
    &["lesson", "same pixel", "that pixel", "its tree", "same scene", "same hit"],
    &["lecți", "același pixel", "acelui pixel", "arborele său", "aceeași scenă"],
];

/// Where `marker` occurs in `text` (both lower-cased) as a phrase: not after a letter (not
/// "subarborele său"), nor followed by one unless the marker is a stem (`lecți` for lecția …).
fn occurrences(text: &str, marker: &str) -> Vec<usize> {
    let stem = marker == "lecți";
    text.match_indices(marker)
        .filter(|(k, _)| !text[..*k].chars().next_back().is_some_and(char::is_alphabetic))
        .filter(|(k, m)| stem || !text[k + m.len()..].chars().next().is_some_and(char::is_alphabetic))
        .map(|(k, _)| k)
        .collect()
}

/// Issue 32 item 2, "a caption that cites another lesson's pixel or figure is checked against
/// it": every citation in the lessons' captions and texts, in both languages, is declared in
/// `CITATIONS`, and what it says holds: the same scene and pixel, the same trace, the pixel and
/// first hit it names, the sampling it quotes; "the first lesson" is the first. Before the rule,
/// ray-tree 2 called pixel 20 (first hit: the mirror) "the 2D pixel drawn in the first lesson",
/// which draws pixel 32 (first hit: the lens).
#[test]
fn every_citation_of_another_figure_is_declared_and_true() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons");
    let lessons = lessons();
    let find = |(name, k): (&str, usize)| -> (usize, &FigureSpec) {
        let at = lessons.iter().position(|l| l.name == name).unwrap_or_else(|| panic!("no lesson {name}"));
        (at, lessons[at].figures.get(k - 1).unwrap_or_else(|| panic!("{name} has no figure {k}")))
    };
    let mut wrong = Vec::new();
    // Every marker lies inside declared words.
    for lesson in &lessons {
        let texts = std::iter::once((0, &lesson.text))
            .chain(lesson.figures.iter().enumerate().map(|(k, f)| (k + 1, &f.caption)));
        for (k, words) in texts {
            for (l, lang) in [Lang::En, Lang::Ro].into_iter().enumerate() {
                let text = words.get(lang).to_lowercase();
                let declared: Vec<(usize, usize)> = CITATIONS
                    .iter()
                    .filter(|c| c.at == (lesson.name.as_str(), k))
                    .flat_map(|c| {
                        let w = c.words[l].to_lowercase();
                        text.match_indices(&w).map(|(at, _)| (at, at + w.len())).collect::<Vec<_>>()
                    })
                    .collect();
                for marker in CITATION_MARKERS[l] {
                    for at in occurrences(&text, marker) {
                        if !declared.iter().any(|(a, b)| *a <= at && at + marker.len() <= *b) {
                            wrong.push(format!(
                                "{} {} ({}): \"{marker}\" cites undeclared words: {}",
                                lesson.name,
                                if k == 0 { "text".to_owned() } else { format!("figure {k}") },
                                lang.code(),
                                words.get(lang)
                            ));
                        }
                    }
                }
            }
        }
    }
    // Every declared citation is in its caption, and true.
    for c in CITATIONS {
        let ((_, at), (cited_lesson, cited)) = (find(c.at), find(c.cites));
        for (l, lang) in [Lang::En, Lang::Ro].into_iter().enumerate() {
            if !at.caption.get(lang).contains(c.words[l]) {
                wrong.push(format!("{} {}: the caption no longer says \"{}\"", c.at.0, c.at.1, c.words[l]));
            }
        }
        if c.words[0].contains("first lesson") && cited_lesson != 0 {
            wrong.push(format!("{} {}: \"the first lesson\" is {}", c.at.0, c.at.1, c.cites.0));
        }
        let scene = |s: &FigureSpec| dir.join(&s.scene).canonicalize().unwrap();
        let pixel = |s: &FigureSpec| made(&dir, s, Lang::En).traced.pixel;
        let (same_scene, same_pixel) = (scene(at) == scene(cited), pixel(at) == pixel(cited));
        let holds = match c.fact {
            Fact::SamePixel => same_scene && same_pixel,
            Fact::SameTrace => same_scene && same_pixel && at.depth == cited.depth,
            Fact::PixelHit(i, object) => {
                let traced = pixel(cited);
                let hit = traced.as_ref().map(|p| first_hit(cited, p));
                let ok = traced.as_deref() == Some(&[i][..]) && hit.as_deref() == Some(object);
                if !ok {
                    wrong.push(format!(
                        "{} {}: says pixel {i} hits the {object} first; {} {} traces {traced:?}, first hit {hit:?}",
                        c.at.0, c.at.1, c.cites.0, c.cites.1
                    ));
                }
                ok
            }
            Fact::Adaptive(threshold, k) => {
                let wanted = whitted::sample::Sampling::Adaptive { threshold, max_level: k };
                cited.sampling == Some(wanted)
            }
        };
        if !holds {
            wrong.push(format!(
                "{} {}: \"{}\" does not hold of {} {} ({:?})",
                c.at.0, c.at.1, c.words[0], c.cites.0, c.cites.1, c.fact
            ));
        }
    }
    assert!(wrong.is_empty(), "{} citations wrong:\n{}", wrong.len(), wrong.join("\n"));
}

/// The English name of the object that pixel `pixel` of figure `spec`'s scene hits first, as
/// `whitted trace --json` says it (`tree.hit.object`).
fn first_hit(spec: &FigureSpec, pixel: &[usize]) -> String {
    let doc = crate::support::lesson_trace(spec, pixel);
    doc["tree"]["hit"]["object"].as_str().unwrap_or("nothing").to_owned()
}

/// The lecture's adaptive example (lecture "Îmbunătățirea calității imaginii (2)"): the mean of
/// one of its squares, in its own drawing's letters.
const LECTURE_MEAN: &str = "(CN + CL + CG + CM)/4";

/// The word that says a formula is the lecture's, in English and Romanian.
const LECTURE_WORD: [&str; 2] = ["lecture", "curs"];

/// The corner means `(CA + CB + …)/n` quoted in `text`.
fn corner_means(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(open) = rest.find("(C") {
        let tail = &rest[open..];
        let Some(close) = tail.find(")/") else { break };
        let digits = tail[close + 2..].chars().take_while(char::is_ascii_digit).count();
        let quote = &tail[..close + 2 + digits];
        let names = &quote[1..close];
        let is_mean = digits > 0
            && names
                .split(" + ")
                .all(|n| n.len() == 2 && n.starts_with('C') && n.chars().all(|c| c.is_ascii_uppercase()));
        if is_mean {
            out.push(quote.to_owned());
        }
        rest = &tail[1..];
    }
    out
}

/// The lecture's sample names (`CA` … `CZ`) that `text` uses as words.
fn sample_names(text: &str) -> Vec<String> {
    text.split(|c: char| !c.is_alphanumeric())
        .filter(|w| w.len() == 2 && w.starts_with('C') && w.chars().all(|c| c.is_ascii_uppercase()))
        .map(str::to_owned)
        .collect()
}

/// Issue 32 item 2, "the lecture's letters only where the figure draws them as the lecture does":
/// a lesson's text or caption names samples (CA, CB, …) only as its figures print them, and
/// quotes a corner mean `(… )/4` only as one of its figures prints it — the four names at the
/// corners of one square of that figure — or as the lecture's own, said to be the lecture's
/// (`LECTURE_MEAN`, in a sentence with "lecture"/"curs"). Before the rule the adaptive lesson
/// quoted the lecture's (CN + CL + CG + CM)/4 as a square's mean under a figure in which CN, CL,
/// CG and CM are not the corners of any square.
#[test]
fn every_lecture_letter_of_a_lesson_is_drawn_as_the_words_say() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons");
    let mut wrong = Vec::new();
    let mut quotes = 0;
    for lesson in lessons() {
        for (l, lang) in [Lang::En, Lang::Ro].into_iter().enumerate() {
            let drawings: Vec<whitted::canvas::Drawing> =
                lesson.figures.iter().map(|f| made(&dir, f, lang).drawing).collect();
            let texts = std::iter::once((None, lesson.text.get(lang)))
                .chain(lesson.figures.iter().enumerate().map(|(k, f)| (Some(k), f.caption.get(lang))));
            for (figure, text) in texts {
                // The figures whose print counts: the caption's own, or any for the lesson's text.
                let shown: Vec<&whitted::canvas::Drawing> = match figure {
                    Some(k) => vec![&drawings[k]],
                    None => drawings.iter().collect(),
                };
                let where_ = match figure {
                    Some(k) => format!("{} figure {} ({})", lesson.name, k + 1, lang.code()),
                    None => format!("{} text ({})", lesson.name, lang.code()),
                };
                let mut lecture_quotes = String::new();
                for sentence in text.split(". ") {
                    for quote in corner_means(sentence) {
                        quotes += 1;
                        if quote == LECTURE_MEAN && sentence.contains(LECTURE_WORD[l]) {
                            lecture_quotes.push_str(&quote);
                            continue;
                        }
                        let square = shown.iter().any(|d| printed(d, &quote) && square_corners(d, &quote));
                        if !square {
                            wrong.push(format!(
                                "{where_}: {quote} is not a square's mean that a figure prints"
                            ));
                        }
                    }
                }
                for name in sample_names(text).into_iter().filter(|n| !lecture_quotes.contains(n.as_str())) {
                    if !shown.iter().any(|d| sample_named(d, &name)) {
                        wrong.push(format!("{where_}: {name} is not a sample its figure names"));
                    }
                }
            }
        }
    }
    assert!(quotes >= 2, "only {quotes} corner means quoted");
    assert!(wrong.is_empty(), "{} lecture letters not drawn:\n{}", wrong.len(), wrong.join("\n"));
}

/// Whether `d` prints `words` in one of its texts.
fn printed(d: &whitted::canvas::Drawing, words: &str) -> bool {
    d.items.iter().any(|i| matches!(&i.mark, whitted::canvas::Mark::Text(t) if t.text.contains(words)))
}

/// Where `d` names sample `name`.
fn sample_at(d: &whitted::canvas::Drawing, name: &str) -> Option<glam::DVec2> {
    d.tagged("sample-name").find_map(|i| match &i.mark {
        whitted::canvas::Mark::Text(t) if t.text == name => Some(t.anchor),
        _ => None,
    })
}

/// Whether `d` names a sample `name`.
fn sample_named(d: &whitted::canvas::Drawing, name: &str) -> bool {
    sample_at(d, name).is_some()
}

/// Whether the samples of corner mean `quote` lie at the four corners of one square of `d`
/// (two x, two y, as far apart), or are the two ends of an interval (2D).
fn square_corners(d: &whitted::canvas::Drawing, quote: &str) -> bool {
    let names = &quote[1..quote.find(")/").unwrap()];
    let Some(points) = names.split(" + ").map(|n| sample_at(d, n)).collect::<Option<Vec<_>>>() else {
        return false;
    };
    let distinct = |v: Vec<f64>| {
        let mut v = v;
        v.sort_by(f64::total_cmp);
        v.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
        v
    };
    let xs = distinct(points.iter().map(|p| p.x).collect());
    let ys = distinct(points.iter().map(|p| p.y).collect());
    match points.len() {
        2 => xs.len() == 2,
        4 => {
            xs.len() == 2 && ys.len() == 2 && ((xs[1] - xs[0]) - (ys[1] - ys[0])).abs() < 1e-9 && {
                let mut corners: Vec<(usize, usize)> = points
                    .iter()
                    .map(|p| {
                        let at = |v: &[f64], x: f64| v.iter().position(|a| (a - x).abs() < 1e-9).unwrap();
                        (at(&xs, p.x), at(&ys, p.y))
                    })
                    .collect();
                corners.sort_unstable();
                corners.dedup();
                corners.len() == 4
            }
        }
        _ => false,
    }
}

/// The words that say what a hierarchy's numbers count: the order the nodes were opened, in
/// English and Romanian.
const ORDER_OPENED: [&str; 2] = ["order opened", "ordinea deschiderii"];
/// The words that would say every test is numbered: false where only the opened nodes are.
const TEST_ORDER: [&[&str]; 2] =
    [&["test order", "order tested", "order they were tested"], &["ordinea testelor", "ordinea testului"]];

/// Issue 32 item 2, "a numbering says what it counts": a hierarchy figure (bvh, octree) numbers
/// the nodes it opened 1, 2, … in order, and as it numbers none of the boxes it tested and
/// missed, its legend says "order opened" and neither legend nor caption says "test order"; a
/// grid figure numbers every cell it visited 1, 2, … (its legend's "k: order"). Before the rule
/// the legend of the 3 hierarchy lesson figures, and the captions of bvh 1 and octree 1, said
/// "test order" over numbers that skipped every missed box.
#[test]
fn every_numbering_of_a_lesson_figure_says_what_it_counts() {
    use whitted::canvas::Mark;
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons");
    let (mut wrong, mut numbered) = (Vec::new(), 0);
    let numbers = |d: &whitted::canvas::Drawing, tag: &str| -> Vec<usize> {
        d.tagged(tag)
            .filter_map(|i| match &i.mark {
                Mark::Text(t) => t.text.parse().ok(),
                _ => None,
            })
            .collect()
    };
    let count = |d: &whitted::canvas::Drawing, prefix: &str| {
        d.items.iter().filter(|i| i.tag.starts_with(prefix) && matches!(i.mark, Mark::Rect { .. })).count()
    };
    for lesson in lessons() {
        for (k, spec) in lesson.figures.iter().enumerate() {
            for (l, lang) in [Lang::En, Lang::Ro].into_iter().enumerate() {
                let d = made(&dir, spec, lang).drawing;
                let name = format!("{} figure {} ({})", lesson.name, k + 1, lang.code());
                let opened = numbers(&d, "tree-order");
                // The grid's step numbers (another kind's `step` tags number something else).
                let steps = if spec.kind.name() == "grid-dda" { numbers(&d, "step") } else { Vec::new() };
                if !opened.is_empty() {
                    numbered += 1;
                    let entered = count(&d, "node-entered:");
                    let tested = entered + count(&d, "node-missed:") + count(&d, "node-skipped:");
                    let mut sorted = opened.clone();
                    sorted.sort_unstable();
                    if sorted != (1..=entered).collect::<Vec<_>>() {
                        wrong.push(format!("{name}: numbers {opened:?} for {entered} opened boxes"));
                    }
                    let says = |text: &str| TEST_ORDER[l].iter().any(|w| text.contains(w));
                    let legend_opened = d.legend.iter().any(|e| e.label.contains(ORDER_OPENED[l]));
                    if tested > entered
                        && (!legend_opened
                            || d.legend.iter().any(|e| says(&e.label))
                            || says(spec.caption.get(lang)))
                    {
                        wrong.push(format!(
                            "{name}: {entered} of {tested} tested boxes numbered, but the words do not say \"{}\"",
                            ORDER_OPENED[l]
                        ));
                    }
                }
                if !steps.is_empty() {
                    numbered += 1;
                    let cells = count(&d, "cell:visited");
                    let mut sorted = steps.clone();
                    sorted.sort_unstable();
                    if sorted != (1..=cells).collect::<Vec<_>>() {
                        wrong.push(format!("{name}: steps {steps:?} for {cells} cells visited"));
                    }
                }
            }
        }
    }
    assert!(numbered >= 10, "only {numbered} numbered figures");
    assert!(wrong.is_empty(), "{} numberings wrong:\n{}", wrong.len(), wrong.join("\n"));
}

/// An adaptive figure's count of samples read again is the trace's: the corner reads that traced
/// no new ray, each a `sample` event with `reused: true` in `whitted trace --json`. Before, it
/// printed how many samples were read again at least once ("reused 22" beside 22 traced: every
/// sample of a split pixel is), which read as 22 rays saved.
#[test]
fn an_adaptive_figure_counts_the_corner_reads_that_traced_no_new_ray() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons");
    let mut checked = 0;
    for lesson in lessons() {
        for spec in lesson.figures.iter().filter(|f| f.kind.name() == "adaptive") {
            let Some(whitted::sample::Sampling::Adaptive { threshold, max_level }) = spec.sampling else {
                continue;
            };
            for (lang, words) in
                [(Lang::En, "re-read without a new ray: "), (Lang::Ro, "recitite fără rază nouă: ")]
            {
                let m = made(&dir, spec, lang);
                let printed: Vec<usize> = m
                    .drawing
                    .items
                    .iter()
                    .filter_map(|i| match &i.mark {
                        whitted::canvas::Mark::Text(t) => {
                            let at = t.text.find(words)? + words.len();
                            t.text[at..].split(|c: char| !c.is_ascii_digit()).next()?.parse().ok()
                        }
                        _ => None,
                    })
                    .collect();
                assert_eq!(printed.len(), 1, "{}: {printed:?}", lesson.name);
                let pixel = m.traced.pixel.expect("an adaptive figure traces a pixel");
                let pixel = pixel.iter().map(ToString::to_string).collect::<Vec<_>>().join(",");
                let scene = dir.join(&spec.scene);
                let (code, out, err) = crate::support::whitted(&[
                    "trace",
                    scene.to_str().unwrap(),
                    "--pixel",
                    &pixel,
                    "--aa",
                    "adaptive",
                    "--threshold",
                    &threshold.to_string(),
                    "--max-level",
                    &max_level.to_string(),
                    "--json",
                ]);
                assert_eq!(code, 0, "{err}");
                let doc: serde_json::Value = serde_json::from_str(&out).unwrap();
                let events = doc["events"].as_array().expect("the trace's events");
                let reads = events.iter().filter(|e| e["reused"] == serde_json::json!(true)).count();
                assert_eq!(printed[0], reads, "{}", lesson.name);
                let traced = doc["samples"].as_array().map_or(0, Vec::len);
                assert!(reads > traced / 2, "{reads} reads again, {traced} traced");
                checked += 1;
            }
        }
    }
    assert!(checked >= 4, "{checked}");
}
