//! The interactive course's pages (`docs/course.md`): one HTML page per lesson and language, and
//! the playground, each made of live views. A view is a scene with its image, its figure and the
//! narration of one pixel, all computed in the page by the WebAssembly build of this library
//! (`web/`), driven by `web/site/whitted.js`. This module only writes the markup: every word of
//! it in both languages, the view's starting state as `data-` attributes, the scene's JSON in its
//! editor; and the static index per language (`index_html`) that shows every lesson's figures
//! with their captions and the command that regenerates each. Reads values and returns text;
//! `cli::lessons` writes the files.
//!
//! `word` holds every word of the pages in both languages, handed to the script as JSON;
//! `module_script` carries the WebAssembly module in base64, since a page opened from disk may not
//! fetch; `play_page` offers the lessons' scenes as examples.

use serde_json::{Map, Value};

use crate::accel::AccelKind;
use crate::bounds::VolumeKind;
use crate::figure::{FigureKind, Lang};
use crate::format::html_escape;
use crate::lesson::{FigureSpec, Lesson};
use crate::request::figure::structure;
use crate::sample::{Sampling, DEFAULT_MAX_LEVEL, DEFAULT_THRESHOLD, MAX_LEVEL};

/// The file the page scripts read the module from (`whitted-wasm.js`, beside `whitted.js`).
pub const MODULE_SCRIPT: &str = "whitted-wasm.js";

/// Every word of the pages: key, English, Romanian. The keys whose text the script shows at run
/// time reach it as JSON (`words_json`); `{name}` marks a value the script fills in.
const WORDS: &[(&str, &str, &str)] = &[
    ("lessons", "Lessons", "Lecțiile"),
    ("figures", "the figures", "figurile"),
    ("other", "Română", "English"),
    ("play", "Playground: any scene", "Laborator: orice scenă"),
    ("play_title", "whitted — playground", "whitted — laborator"),
    ("play_intro",
     "Paste a scene's JSON below, open a scene file (with the OBJ files of its meshes) or pick an example: the image, the figures and the narration of any pixel are computed in this page by the same Rust code as the command line.",
     "Lipiți mai jos textul JSON al unei scene, deschideți un fișier de scenă (împreună cu fișierele OBJ ale rețelelor ei) sau alegeți un exemplu: imaginea, figurile și explicația oricărui pixel sunt calculate în această pagină de același cod Rust ca în linia de comandă."),
    ("prev", "← Previous lesson", "← Lecția anterioară"),
    ("next_lesson", "Next lesson →", "Lecția următoare →"),
    ("hint",
     "Click a pixel of an image, or type i, j, to follow its computation; ← and → (or the buttons) walk the steps, and the figure lights up what each step talks about.",
     "Dați clic pe un pixel al imaginii sau scrieți i, j ca să-i urmăriți calculul; tastele ← și → (sau butoanele) parcurg pașii, iar figura evidențiază ce explică fiecare pas."),
    ("image", "The rendered image", "Imaginea randată"),
    ("pixel", "Pixel i, j", "Pixelul i, j"),
    ("show", "Trace", "Urmărește"),
    ("back", "← Back", "← Înapoi"),
    ("next", "Next →", "Înainte →"),
    ("step_of", "Step {k} of {n}", "Pasul {k} din {n}"),
    ("controls", "What is traced", "Ce se calculează"),
    ("depth", "Depth", "Adâncimea"),
    ("aa", "Sampling", "Eșantionarea"),
    ("aa_center", "pixel centre", "centrul pixelului"),
    ("aa_corners", "the 4 corners", "cele 4 colțuri"),
    ("aa_adaptive", "adaptive", "adaptivă"),
    ("threshold", "Threshold", "Pragul"),
    ("max_level", "Max level", "Nivelul maxim"),
    ("accel", "Acceleration", "Structura de accelerare"),
    ("accel_none", "none: every object", "niciuna: toate obiectele"),
    ("accel_bounds", "a bounding volume per object", "câte un volum încadrator"),
    ("accel_bvh", "BVH", "ierarhie de volume (BVH)"),
    ("accel_grid", "regular grid", "grilă regulată"),
    ("accel_octree", "octree", "arbore octal"),
    ("kind", "Figure", "Figura"),
    // The figure menu's options: in English the kind's own name (`whitted figure KIND`), in
    // Romanian the lecture's words for what it draws.
    ("kind_backward", "backward", "razele în sens invers"),
    ("kind_camera-frame", "camera-frame", "sistemul camerei (lookAt)"),
    ("kind_uv-map", "uv-map", "pixel → (u, v)"),
    ("kind_projections", "projections", "proiecții"),
    ("kind_rays", "rays", "raze"),
    ("kind_refraction", "refraction", "refracție"),
    ("kind_local-model", "local-model", "iluminare locală"),
    ("kind_ray-tree", "ray-tree", "arborele de raze"),
    ("kind_shadows", "shadows", "umbre"),
    ("kind_jagged-edges", "jagged-edges", "margini zimțate"),
    ("kind_complexity", "complexity", "complexitate"),
    ("kind_discriminant", "discriminant", "discriminantul Δ"),
    ("kind_slab-test", "slab-test", "testul cu plăci"),
    ("kind_kay-kajiya", "kay-kajiya", "plăcile Kay–Kajiya"),
    ("kind_bvh", "bvh", "ierarhie de volume (BVH)"),
    ("kind_grid-dda", "grid-dda", "grilă regulată (DDA)"),
    ("kind_octree", "octree", "arbore octal"),
    ("kind_adaptive", "adaptive", "subdivizare adaptivă"),
    ("kind_heat-map", "heat-map", "raze pe pixel"),
    ("steps", "The computation, step by step", "Calculul, pas cu pas"),
    ("command", "The same computation from the command line:", "Același calcul din linia de comandă:"),
    ("scene", "The scene (JSON): edit it and the page re-checks and re-renders it",
     "Scena (JSON): modificați-o, iar pagina o verifică și o randează din nou"),
    ("open", "Open a scene file (and its OBJ meshes)", "Deschideți un fișier de scenă (și rețelele OBJ)"),
    ("example", "Example scene", "Scenă de exemplu"),
    ("loading", "Loading the WebAssembly module…", "Se încarcă modulul WebAssembly…"),
    ("ready", "WebAssembly module ready ({ms} ms).", "Modulul WebAssembly este gata ({ms} ms)."),
    ("rendering", "Rendering in the background…", "Se randează în fundal…"),
    ("rendered", "{w}×{h} pixels, {rays} rays, {ms} ms in the page",
     "{w}×{h} pixeli, {rays} raze, {ms} ms în pagină"),
    ("rendering_share", "Rendering: {p} %…", "Se randează: {p} %…"),
    ("cost_image", "The whole image: {cost}", "Toată imaginea: {cost}"),
    ("cost_pixel", "This pixel: {cost}", "Acest pixel: {cost}"),
    ("cost",
     "rays {rays} (primary {primary}, reflected {reflected}, transmitted {transmitted}, shadow {shadow}); tests: objects {object}, volumes {bound}, nodes {node}, voxels {voxel}",
     "raze {rays} (primare {primary}, reflectate {reflected}, transmise {transmitted}, de umbră {shadow}); teste: obiecte {object}, volume {bound}, noduri {node}, voxeli {voxel}"),
    ("fallback", "Pixel ({pixel}) has no {what}, which the “{kind}” figure draws: shown are its rays.",
     "Pixelul ({pixel}) nu are {what}, pe care o desenează figura „{kind}”: sunt arătate razele lui."),
    ("want_refraction", "refraction", "refracție"),
    ("want_hit", "hit", "intersecție"),
    ("want_shadow", "shadow ray", "rază de umbră"),
    ("want_volume", "bounding volume met by its ray", "intersecție a razei cu un volum încadrator"),
    ("want_other", "such a trace", "o asemenea urmă"),
    ("searching", "Looking for a nearby pixel that has it…", "Se caută un pixel vecin care o are…"),
    ("nearby", "Nearby pixel ({pixel}) has it", "Pixelul vecin ({pixel}) o are"),
    ("none_nearby", "No nearby pixel has it.", "Niciun pixel vecin nu o are."),
    ("lesson_pixel", "The lesson's pixel ({pixel})", "Pixelul lecției ({pixel})"),
    ("undrawn", "Not drawn in this figure: {what}", "Nu apare în această figură: {what}"),
    ("too_large",
     "The scene's image ({w}×{h}) is over the page's limit of 4096×2048 pixels: lower the camera's resolution in the scene.",
     "Imaginea scenei ({w}×{h}) depășește limita paginii, de 4096×2048 pixeli: micșorați rezoluția camerei în scenă."),
    ("last_good", "Last good image and steps, not of the scene as it is now.",
     "Ultima imagine și ultimii pași corecți, nu ai scenei de acum."),
    ("link_pixel", "The link's pixel {given} is outside the {w}×{h} image: shown is the nearest, ({pixel}).",
     "Pixelul {given} din link este în afara imaginii de {w}×{h}: este arătat cel mai apropiat, ({pixel})."),
    ("link_part", "The link's {part}={given} could not be used: shown is {used}.",
     "Partea {part}={given} a link-ului nu poate fi folosită: se arată {used}."),
    ("link_step", "The link's step {given} does not exist: shown is step {k} of {n}.",
     "Pasul {given} din link nu există: este arătat pasul {k} din {n}."),
    ("scene_depth", "the scene's depth", "adâncimea scenei"),
    ("figure_name", "Figure “{kind}”, pixel ({pixel})", "Figura „{kind}”, pixelul ({pixel})"),
    ("overview_name", "The ray tree of pixel ({pixel}): every ray of its computation",
     "Arborele de raze al pixelului ({pixel}): toate razele calculului său"),
    ("missing",
     "The interactive part needs the WebAssembly module, which was not built: run ./run.sh (web/build.sh --install installs its toolchain). The figures below are the static ones.",
     "Partea interactivă are nevoie de modulul WebAssembly, care nu a fost construit: rulați ./run.sh (web/build.sh --install instalează uneltele necesare). Figurile de mai jos sunt cele statice."),
    ("failed", "The WebAssembly module failed: {e}", "Modulul WebAssembly a eșuat: {e}"),
    ("pixel_format", "Write the pixel as i, j (or i in a 2D scene), whole numbers.",
     "Scrieți pixelul ca i, j (sau i într-o scenă 2D), numere întregi."),
    ("stale", "The scene has errors; the image is the last good one.",
     "Scena are erori; imaginea este ultima corectă."),
    ("no_steps", "This figure follows no single pixel: click one to see its computation.",
     "Figura nu urmărește un singur pixel: dați clic pe unul ca să-i vedeți calculul."),
    // Why a figure kind that draws no pixel's trace has no steps until a pixel is clicked (issue
    // 30 item 4), shown where the steps would be.
    ("no_pixel_discriminant",
     "No pixel to follow here: this figure draws three rays of its own against one sphere (Δ < 0, Δ = 0, Δ > 0), not a pixel of the image. Click the image to follow one of its pixels.",
     "Aici nu se urmărește niciun pixel: figura desenează trei raze proprii față de o sferă (Δ < 0, Δ = 0, Δ > 0), nu un pixel al imaginii. Dați clic pe imagine ca să urmăriți unul dintre pixelii ei."),
    ("no_pixel_complexity",
     "No pixel to follow here: this figure plots the tests per ray measured on crowds of n spheres, not one pixel's computation. Click the image to follow one of its pixels.",
     "Aici nu se urmărește niciun pixel: figura arată testele pe rază măsurate pe mulțimi de n sfere, nu calculul unui pixel. Dați clic pe imagine ca să urmăriți unul dintre pixelii ei."),
    ("no_pixel_heat-map",
     "No pixel to follow here: this figure counts the primary rays of every pixel of the image, not one pixel's computation. Click the image to follow one of them.",
     "Aici nu se urmărește niciun pixel: figura numără razele primare ale fiecărui pixel al imaginii, nu calculul unuia singur. Dați clic pe imagine ca să urmăriți unul dintre ei."),
    ("ray", "a ray given by hand", "o rază dată explicit"),
    ("empty", "This scene has no errors.", "Scena nu are erori."),
    // Checking a student's own numbers (web/site/grade.js, docs/grading.md "In the page").
    ("grade_box", "Check your own numbers", "Verificați-vă propriile calcule"),
    ("grade_intro",
     "Paste the trace document your own ray tracer writes for one pixel of this scene (the format of docs/grading.md; examples/student/tracer.py writes one), or open its file, then Check: the page compares it with this computation step by step and shows the first quantity that differs.",
     "Lipiți documentul de urmărire pe care îl scrie propriul vostru ray tracer pentru un pixel al acestei scene (formatul din docs/grading.md; examples/student/tracer.py scrie unul) sau deschideți fișierul lui, apoi apăsați Verifică: pagina îl compară pas cu pas cu acest calcul și arată prima mărime care diferă."),
    ("student", "Your document (JSON)", "Documentul vostru (JSON)"),
    ("student_file", "Open a document file", "Deschideți un fișier document"),
    ("check", "Check", "Verifică"),
    ("grade_empty", "Paste or open a document first.", "Lipiți sau deschideți mai întâi un document."),
    ("grade_errors", "The document has errors (each with its JSON path):",
     "Documentul are erori (fiecare cu calea ei JSON):"),
    ("grade_pixel", "The document is for pixel ({pixel}): the view now follows it.",
     "Documentul este pentru pixelul ({pixel}): vizualizarea îl urmărește acum."),
    ("grade_first", "First divergence: {chain}, {quantity}", "Prima divergență: {chain}, {quantity}"),
    ("grade_step", "Step {k} of the computation (now the current step)",
     "Pasul {k} al calculului (acum pasul curent)"),
    ("grade_goto", "Go to step {k}", "Mergi la pasul {k}"),
    ("expected", "expected (whitted)", "așteptat (whitted)"),
    ("found", "found (yours)", "găsit (al vostru)"),
    ("formula", "formula", "formula"),
    ("inputs", "with", "cu"),
    ("diagnosis", "diagnosis", "diagnostic"),
    ("rule", "the rule", "regula"),
    ("not_checked", "Not checked (absent from the document): {list}",
     "Neverificate (lipsesc din document): {list}"),
    ("grade_after", "What follows was not compared: the rays below start from a different point or direction.",
     "Ce urmează nu a mai fost comparat: razele de dedesubt pleacă din alt punct sau pe altă direcție."),
    ("exercise_mode", "Exercise mode: hide the step's numbers and compute them yourself",
     "Mod exercițiu: numerele pasului sunt ascunse, iar voi le calculați"),
    ("ex_hidden", "Exercise mode: the numbers of this step and of the ones after it are hidden.",
     "Mod exercițiu: numerele acestui pas și ale celor următori sunt ascunse."),
    ("ex_nothing", "Step {k} computes nothing to type: go on with Next →.",
     "Pasul {k} nu cere niciun calcul de scris: continuați cu Înainte →."),
    ("ask_window_point", "Step {k}: compute {name}, the pixel's centre on the view window.",
     "Pasul {k}: calculați {name}, centrul pixelului pe fereastra vizuală."),
    ("ask_direction", "Step {k}: compute the unit direction {name}.", "Pasul {k}: calculați direcția unitară {name}."),
    ("ask_t", "Step {k}: compute the t this test accepts (the least root t > 0).",
     "Pasul {k}: calculați t-ul acceptat de acest test (cea mai mică rădăcină t > 0)."),
    ("ask_point", "Step {k}: compute the hit point {name} = O + t·D.",
     "Pasul {k}: calculați punctul de intersecție {name} = O + t·D."),
    ("ask_shadow", "Step {k}: compute the shadow factor {name} = Π kt.",
     "Pasul {k}: calculați factorul de umbră {name} = Π kt."),
    ("ask_local", "Step {k}: compute I_local with the lecture's local model.",
     "Pasul {k}: calculați I_local cu modelul local din curs."),
    ("ask_colour", "Step {k}: compute the colour {name} = I_local + ks·R + kt·T.",
     "Pasul {k}: calculați culoarea {name} = I_local + ks·R + kt·T."),
    ("ex_count_one", "Type one number, e.g. {example}.", "Scrieți un număr, de exemplu {example}."),
    ("ex_count", "Type {count} numbers, e.g. {example}.", "Scrieți {count} numere, de exemplu {example}."),
    ("answer", "Your answer", "Răspunsul vostru"),
    ("ex_check", "Check the answer", "Verifică răspunsul"),
    ("reveal", "Show the worked step", "Arată pasul rezolvat"),
    ("ex_right", "Right: every component agrees (tolerance {tol}, relative; absolute below 1).",
     "Corect: toate componentele coincid (toleranța {tol}, relativă; absolută sub 1)."),
    ("ex_wrong", "{right} of {n} right (tolerance {tol}, relative; absolute below 1).",
     "{right} din {n} corecte (toleranța {tol}, relativă; absolută sub 1)."),
    ("component", "component", "componenta"),
    ("yours", "yours", "al vostru"),
    ("verdict", "verdict", "verdict"),
    ("comp_right", "✓ right", "✓ corect"),
    ("comp_off", "✗ off by {off}", "✗ diferă cu {off}"),
];

/// The word `key` in `lang` (the key itself if there is none: a page never loses a label).
#[must_use]
pub fn word(key: &str, lang: Lang) -> &str {
    WORDS.iter().find(|(k, _, _)| *k == key).map_or(key, |(_, en, ro)| match lang {
        Lang::En => en,
        Lang::Ro => ro,
    })
}

/// Every word in `lang` as a JSON object, safe inside a `<script>` element.
fn words_json(lang: Lang) -> String {
    let map: Map<String, Value> =
        WORDS.iter().map(|(k, _, _)| ((*k).to_owned(), Value::from(word(k, lang)))).collect();
    Value::Object(map).to_string().replace("</", "<\\/")
}

/// The language's code, also its folder under `out/`.
#[must_use]
pub const fn code(lang: Lang) -> &'static str {
    match lang {
        Lang::En => "en",
        Lang::Ro => "ro",
    }
}

/// One live view: a scene, its starting state and what the page shows before the module runs.
#[derive(Clone, Debug)]
pub struct View<'a> {
    /// The scene file as the lesson names it (`data-scene`).
    pub scene: &'a str,
    /// The scene file from where `whitted` runs (`data-path`): the name in the commands shown.
    pub path: Option<String>,
    /// The scene's JSON text, the editor's content.
    pub text: &'a str,
    /// The lesson's figure: kind, pixel or ray, depth, sampling, grid; none in the playground.
    pub spec: Option<&'a FigureSpec>,
    /// The static figure (PNG, relative to the page), shown until the live one replaces it.
    pub png: Option<String>,
    /// What the view shows, in the page's language.
    pub caption: &'a str,
}

/// Links of a page: to the index, the same page in the other language, neighbours.
#[derive(Clone, Debug, Default)]
pub struct Nav {
    /// The index page of this language.
    pub index: String,
    /// This page in the other language (the script appends the state to it).
    pub other: String,
    /// The previous and the next lesson's pages.
    pub prev: Option<String>,
    /// See `prev`.
    pub next: Option<String>,
    /// The playground of this language.
    pub play: String,
}

/// The page of `lesson` in `lang`: its title and text, then one live view per figure.
/// `module` says whether `whitted-wasm.js` was written beside the scripts.
#[must_use]
pub fn lesson_page(lesson: &Lesson, views: &[View], lang: Lang, nav: &Nav, module: bool) -> String {
    let mut body = format!("<h1>{}</h1>\n", html_escape(lesson.title.get(lang)));
    if !lesson.text.get(lang).is_empty() {
        body.push_str(&format!("<p class=\"intro\">{}</p>\n", html_escape(lesson.text.get(lang))));
    }
    body.push_str(&format!("<p class=\"hint\">{}</p>\n", html_escape(word("hint", lang))));
    for view in views {
        body.push_str(&view_html(view, lang, None));
    }
    // The lesson's exercise sheets (`whitted exercises`), written beside this page.
    if !lesson.exercises.is_empty() {
        let (title, sheet, answers) = match lang {
            Lang::En => ("Exercises", "sheet", "answers"),
            Lang::Ro => ("Exerciții", "fișa", "răspunsuri"),
        };
        body.push_str(&format!("<h2>{title}</h2>\n<ul class=\"exercises\">\n"));
        for k in 0..lesson.exercises.len() {
            let (ex, ans) = lesson.exercise_files(k);
            body.push_str(&format!(
                "<li><a href=\"{}\">{sheet} {}</a> (<a href=\"{}\">{answers}</a>)</li>\n",
                html_escape(&ex),
                k + 1,
                html_escape(&ans)
            ));
        }
        body.push_str("</ul>\n");
    }
    page(lesson.title.get(lang), &body, lang, nav, module)
}

/// The playground in `lang`: one view over a scene pasted, opened from disk or picked among
/// `examples` (name, JSON text; the first is shown first).
#[must_use]
pub fn play_page(examples: &[(String, String)], lang: Lang, nav: &Nav, module: bool) -> String {
    let mut body = format!(
        "<h1>{}</h1>\n<p class=\"intro\">{}</p>\n<p class=\"hint\">{}</p>\n",
        html_escape(word("play_title", lang)),
        html_escape(word("play_intro", lang)),
        html_escape(word("hint", lang))
    );
    let mut picker = format!(
        "<div class=\"picker\"><label>{} <input type=\"file\" data-whitted=\"file\" accept=\".json,.obj\" multiple></label>\n\
         <label>{} <select data-whitted=\"example\">",
        html_escape(word("open", lang)),
        html_escape(word("example", lang))
    );
    for (name, text) in examples {
        picker.push_str(&format!(
            "<option value=\"{n}\" data-text=\"{t}\">{n}</option>",
            n = html_escape(name),
            t = html_escape(text)
        ));
    }
    picker.push_str("</select></label></div>\n");
    let (name, text) = examples.first().map_or(("scene.json", ""), |(n, t)| (n.as_str(), t.as_str()));
    let view = View { scene: name, path: None, text, spec: None, png: None, caption: "" };
    body.push_str(&view_html(&view, lang, Some(&picker)));
    page(word("play_title", lang), &body, lang, nav, module)
}

/// The whole document around `body`.
fn page(title: &str, body: &str, lang: Lang, nav: &Nav, module: bool) -> String {
    let mut links =
        format!("<a href=\"{}\">{}</a>", html_escape(&nav.index), html_escape(word("lessons", lang)));
    if let Some(prev) = &nav.prev {
        links.push_str(&format!("<a href=\"{}\">{}</a>", html_escape(prev), html_escape(word("prev", lang))));
    }
    if let Some(next) = &nav.next {
        links.push_str(&format!(
            "<a href=\"{}\">{}</a>",
            html_escape(next),
            html_escape(word("next_lesson", lang))
        ));
    }
    links.push_str(&format!(
        "<a href=\"{}\">{}</a>",
        html_escape(&nav.play),
        html_escape(word("play", lang))
    ));
    let other_code = match lang {
        Lang::En => "ro",
        Lang::Ro => "en",
    };
    links.push_str(&format!(
        "<a data-whitted=\"lang\" hreflang=\"{other_code}\" lang=\"{other_code}\" href=\"{}\">{}</a>",
        html_escape(&nav.other),
        html_escape(word("other", lang))
    ));
    let module_script =
        if module { format!("<script src=\"../{MODULE_SCRIPT}\"></script>\n") } else { String::new() };
    format!(
        "<!DOCTYPE html>\n<html lang=\"{code}\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>{title}</title>\n\
         <link rel=\"stylesheet\" href=\"../whitted.css\">\n\
         <script type=\"application/json\" id=\"whitted-words\">{words}</script>\n\
         {module_script}<script src=\"../whitted.js\" defer></script>\n<script src=\"../grade.js\" defer></script>\n</head>\n<body class=\"{class}\">\n\
         <nav class=\"bar\">{links}</nav>\n<main>\n\
         <p class=\"module\" data-whitted=\"module\" role=\"status\">{status}</p>\n{body}</main>\n</body>\n</html>\n",
        code = code(lang),
        title = html_escape(title),
        words = words_json(lang),
        status = html_escape(word(if module { "loading" } else { "missing" }, lang)),
        class = if module { "live" } else { "static" },
    )
}

/// A `<select>` named `name` of `(value, label)` options with `chosen` selected.
fn select(name: &str, options: &[(&str, String)], chosen: &str) -> String {
    let mut out = format!("<select data-whitted=\"{name}\">");
    for (value, label) in options {
        let selected = if *value == chosen { " selected" } else { "" };
        out.push_str(&format!("<option value=\"{value}\"{selected}>{}</option>", html_escape(label)));
    }
    out.push_str("</select>");
    out
}

/// The structure a view narrates with at first: the one its figure draws (`request::figure::
/// structure`), and none where the figure draws no structure, as the lecture teaches ray casting
/// (every object tested) before any structure (issue 30 item 2).
#[must_use]
pub fn view_accel(kind: FigureKind) -> AccelKind {
    structure(kind, AccelKind::None)
}

/// One view's markup: the state attributes, image, figure, step controls, options, command,
/// steps, editor and errors list (the contract of `docs/course.md`).
fn view_html(view: &View, lang: Lang, picker: Option<&str>) -> String {
    let w = |key| html_escape(word(key, lang));
    let mut attrs = format!(" data-scene=\"{}\"", html_escape(view.scene));
    if let Some(path) = &view.path {
        attrs.push_str(&format!(" data-path=\"{}\"", html_escape(path)));
    }
    let spec = view.spec;
    let kind = spec.map_or(FigureKind::Rays, |s| s.kind);
    attrs.push_str(&format!(" data-kind=\"{}\"", kind.name()));
    if let Some(s) = spec {
        if let Some(pixel) = s.pixel_arg() {
            attrs.push_str(&format!(" data-pixel=\"{pixel}\""));
        } else if let Some(ray) = s.ray_arg() {
            attrs.push_str(&format!(" data-ray=\"{ray}\""));
        }
        if let Some(depth) = s.depth {
            attrs.push_str(&format!(" data-depth=\"{depth}\""));
        }
        if let Some(cells) = &s.grid {
            let cells: Vec<String> = cells.iter().map(ToString::to_string).collect();
            attrs.push_str(&format!(" data-grid=\"{}\"", cells.join(",")));
        }
    }
    let sampling = spec.and_then(|s| s.sampling).unwrap_or(Sampling::Center);
    let (threshold, max_level) = match sampling {
        Sampling::Adaptive { threshold, max_level } => (threshold, max_level),
        Sampling::Center | Sampling::Corners => (DEFAULT_THRESHOLD, DEFAULT_MAX_LEVEL),
    };
    let threshold = if threshold.is_finite() { threshold.to_string() } else { "inf".to_owned() };
    let aa = select(
        "aa",
        &["center", "corners", "adaptive"].map(|m| (m, word(&format!("aa_{m}"), lang).to_owned())),
        sampling.name(),
    );
    let accels: Vec<(&str, String)> =
        [AccelKind::None, AccelKind::Bounds, AccelKind::Bvh, AccelKind::Grid, AccelKind::Octree]
            .iter()
            .map(|a| (a.name(), word(&format!("accel_{}", a.name()), lang).to_owned()))
            .collect();
    let accel = select("accel", &accels, view_accel(kind).name());
    if kind == FigureKind::KayKajiya {
        attrs.push_str(&format!(" data-bounds=\"{}\"", VolumeKind::Kdop.name()));
    }
    let kinds: Vec<(&str, String)> = FigureKind::ALL
        .iter()
        .map(|k| (k.name(), word(&format!("kind_{}", k.name()), lang).to_owned()))
        .collect();
    let kinds = select("kind", &kinds, kind.name());
    let figure = view.png.as_ref().map_or(String::new(), |png| {
        format!("<img src=\"{}\" alt=\"{}\">", html_escape(png), html_escape(view.caption))
    });
    let caption = if view.caption.is_empty() {
        String::new()
    } else {
        format!("<p class=\"caption\">{}</p>\n", html_escape(view.caption))
    };
    format!(
        "<section class=\"view\" data-whitted=\"view\"{attrs} tabindex=\"-1\">\n{caption}{picker}\
         <p class=\"message\" data-whitted=\"message\" role=\"alert\"></p>\n\
         <p class=\"follow\" data-whitted=\"follow\" hidden></p>\n\
         <div class=\"panes\">\n<div class=\"pane image-pane\">\n\
         <div class=\"imagebox\" role=\"group\" aria-label=\"{image}\"><canvas data-whitted=\"image\" width=\"1\" height=\"1\"></canvas>\
         <div class=\"mark\" data-whitted=\"mark\" hidden></div></div>\n\
         <progress data-whitted=\"progress\" aria-label=\"{rendering}\" hidden></progress>\n\
         <p class=\"stats\" data-whitted=\"stats\"></p>\n\
         <form class=\"pixel-form\" data-whitted=\"pixel-form\"><label>{pixel} <input data-whitted=\"pixel\" size=\"9\" inputmode=\"numeric\" autocomplete=\"off\"></label> \
         <button type=\"submit\">{show}</button></form>\n\
         <p class=\"pick\" data-whitted=\"pick\"></p>\n</div>\n\
         <div class=\"pane figure-pane\">\n<div class=\"figure\" data-whitted=\"figure\" tabindex=\"0\">{figure}</div>\n\
         <div class=\"figure overview\" data-whitted=\"overview\" tabindex=\"0\" hidden></div>\n\
         <div class=\"stepnav\"><button type=\"button\" data-whitted=\"back\">{back}</button>\
         <span data-whitted=\"position\"></span>\
         <button type=\"button\" data-whitted=\"next\">{next}</button></div>\n\
         <pre class=\"current\" data-whitted=\"current\" aria-live=\"polite\"></pre>\n\
         <p class=\"undrawn\" data-whitted=\"undrawn\" hidden></p>\n{exercise}</div>\n</div>\n\
         <fieldset class=\"controls\"><legend>{controls}</legend>\
         <label>{depth} <input type=\"number\" data-whitted=\"depth\" min=\"0\" max=\"64\" step=\"1\"></label>\
         <label>{aa_label} {aa}</label>\
         <label class=\"adaptive-only\">{thr_label} <input data-whitted=\"threshold\" size=\"5\" value=\"{threshold}\"></label>\
         <label class=\"adaptive-only\">{ml_label} <input type=\"number\" data-whitted=\"max_level\" min=\"0\" max=\"{MAX_LEVEL}\" value=\"{max_level}\"></label>\
         <label>{accel_label} {accel}</label><label>{kind_label} {kinds}</label></fieldset>\n\
         <p class=\"command\">{command} <code data-whitted=\"command\"></code></p>\n\
         <details class=\"steps-box\" open><summary>{steps}</summary>\
         <p class=\"nopixel\" data-whitted=\"nopixel\" hidden></p><ol class=\"steps\" data-whitted=\"steps\" tabindex=\"0\"></ol>\
         <p class=\"stats\" data-whitted=\"cost\"></p></details>\n\
         {student}\
         <details class=\"editor\"><summary>{scene}</summary>\
         <textarea data-whitted=\"scene\" aria-label=\"{scene}\" spellcheck=\"false\" rows=\"16\">{text}</textarea></details>\n\
         <ul class=\"errors\" data-whitted=\"errors\"></ul>\n</section>\n",
        picker = picker.unwrap_or(""),
        image = w("image"),
        rendering = w("rendering"),
        pixel = w("pixel"),
        show = w("show"),
        back = w("back"),
        next = w("next"),
        controls = w("controls"),
        depth = w("depth"),
        aa_label = w("aa"),
        thr_label = w("threshold"),
        ml_label = w("max_level"),
        accel_label = w("accel"),
        kind_label = w("kind"),
        command = w("command"),
        steps = w("steps"),
        scene = w("scene"),
        text = html_escape(view.text),
        exercise = exercise_html(lang),
        student = student_html(lang),
    )
}

/// The exercise mode of a view (docs/course.md): its toggle, the question of the current step,
/// the answer field and the worked step on request; `web/site/grade.js` drives it.
fn exercise_html(lang: Lang) -> String {
    let w = |key| html_escape(word(key, lang));
    format!(
        "<div class=\"exercise\" data-whitted=\"exercise\">\
         <label class=\"toggle\"><input type=\"checkbox\" data-whitted=\"exercise-mode\"> {mode}</label>\
         <div class=\"exercise-body\" hidden><p class=\"question\" data-whitted=\"question\"></p>\
         <form class=\"answer-form\" data-whitted=\"answer-form\"><label>{answer} <input data-whitted=\"answer\" size=\"28\" autocomplete=\"off\" spellcheck=\"false\"></label> \
         <button type=\"submit\">{check}</button> <button type=\"button\" data-whitted=\"reveal\">{reveal}</button></form>\
         <div class=\"feedback\" data-whitted=\"feedback\" aria-live=\"polite\"></div></div></div>\n",
        mode = w("exercise_mode"),
        answer = w("answer"),
        check = w("ex_check"),
        reveal = w("reveal"),
    )
}

/// A view's place for a student's own trace document and its verdict (docs/course.md);
/// `web/site/grade.js` sends it to the module's `grade` and shows the answer.
fn student_html(lang: Lang) -> String {
    let w = |key| html_escape(word(key, lang));
    format!(
        "<details class=\"grade\"><summary>{title}</summary><p class=\"hint\">{intro}</p>\
         <label class=\"block\">{student}<textarea data-whitted=\"student\" spellcheck=\"false\" rows=\"8\"></textarea></label>\
         <p class=\"grade-actions\"><label>{file} <input type=\"file\" accept=\".json,application/json\" data-whitted=\"student-file\"></label> \
         <button type=\"button\" data-whitted=\"check\">{check}</button></p>\
         <div class=\"verdict\" data-whitted=\"verdict\" aria-live=\"polite\"></div></details>\n",
        title = w("grade_box"),
        intro = w("grade_intro"),
        student = w("student"),
        file = w("student_file"),
        check = w("check"),
    )
}

/// The script that hands the page the WebAssembly module without `fetch` (which `file://` pages
/// may not use): `self.WHITTED_WASM = "<the module in base64>";`, read by `whitted.js`.
#[must_use]
pub fn module_script(wasm: &[u8]) -> String {
    format!("self.WHITTED_WASM = \"{}\";\n", crate::canvas::subset::base64(wasm))
}

/// What the index page shows for one written figure.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Shown {
    /// The PNG, relative to the page.
    pub png: String,
    /// The SVG, relative to the page.
    pub svg: String,
    /// The command that regenerates the PNG.
    pub command: String,
    /// Why it could not be drawn, if it could not.
    pub error: Option<String>,
}

/// The static page of every lesson in `lang`: titles, introductions, each figure with its
/// caption, its SVG and the command that regenerates it; `other` links to the other language's
/// page. `shown[l][f]` is figure f of lesson l.
#[must_use]
pub fn index_html(lessons: &[Lesson], shown: &[Vec<Shown>], lang: Lang, other: &str) -> String {
    let (title, other_name, regenerate, vector) = match lang {
        Lang::En => {
            ("whitted — the lecture's figures, drawn from traces", "Română", "Regenerate", "SVG for print")
        }
        Lang::Ro => {
            ("whitted — figurile cursului, desenate din trasee", "English", "Regenerare", "SVG pentru tipar")
        }
    };
    let (figures, play) = (word("figures", lang), word("play", lang));
    let code = match lang {
        Lang::En => "en",
        Lang::Ro => "ro",
    };
    let mut out = format!(
        "<!DOCTYPE html>\n<html lang=\"{code}\">\n<head>\n<meta charset=\"utf-8\">\n<title>{title}</title>\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<style>\n\
         body {{ font-family: 'Noto Sans', sans-serif; max-width: 1100px; margin: 2em auto; padding: 0 1em; color: #1a1a1a; }}\n\
         figure {{ margin: 1.5em 0; }} img {{ width: 100%; border: 1px solid #ccc; }}\n\
         code {{ background: #f3f3f3; padding: 0.1em 0.3em; font-size: 0.9em; }}\n\
         nav a {{ margin-right: 1em; }} .error {{ color: #d55e00; }}\n\
         @media print {{ nav, .cmd {{ display: none; }} figure {{ page-break-inside: avoid; }} }}\n\
         </style>\n</head>\n<body>\n<h1>{title}</h1>\n<nav><a href=\"{}\">{other_name}</a></nav>\n<ol>\n",
        html_escape(other)
    );
    // The lesson pages and the playground live in the language's folder (`en/`, `ro/`); the
    // English index is one folder up from its pages.
    let pages = match lang {
        Lang::En => "en/",
        Lang::Ro => "",
    };
    for lesson in lessons {
        out.push_str(&format!(
            "<li><a href=\"{pages}{name}.html\">{}</a> (<a href=\"#{name}\">{figures}</a>)</li>\n",
            html_escape(lesson.title.get(lang)),
            name = lesson.name,
        ));
    }
    out.push_str(&format!("</ol>\n<p><a href=\"{pages}play.html\">{play}</a></p>\n"));
    for (lesson, figures) in lessons.iter().zip(shown) {
        out.push_str(&format!(
            "<section id=\"{}\">\n<h2>{}</h2>\n",
            lesson.name,
            html_escape(lesson.title.get(lang))
        ));
        if !lesson.text.get(lang).is_empty() {
            out.push_str(&format!("<p>{}</p>\n", html_escape(lesson.text.get(lang))));
        }
        for (spec, s) in lesson.figures.iter().zip(figures) {
            let caption = html_escape(spec.caption.get(lang));
            match &s.error {
                None => out.push_str(&format!(
                    "<figure>\n<a href=\"{svg}\"><img src=\"{png}\" alt=\"{caption}\"></a>\n<figcaption>{caption} \
                     (<a href=\"{svg}\">{vector}</a>)<br><span class=\"cmd\">{regenerate}: <code>{cmd}</code></span>\
                     </figcaption>\n</figure>\n",
                    svg = html_escape(&s.svg),
                    png = html_escape(&s.png),
                    cmd = html_escape(&s.command),
                )),
                Some(e) => out.push_str(&format!(
                    "<figure>\n<figcaption>{caption}<br><span class=\"error\">{}</span><br><code>{}</code></figcaption>\n</figure>\n",
                    html_escape(e),
                    html_escape(&s.command)
                )),
            }
        }
        out.push_str("</section>\n");
    }
    out.push_str("</body>\n</html>\n");
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lesson::parse;

    const LESSON: &str = r#"{ "name": "glass", "title": { "en": "Glass", "ro": "Sticlă" },
        "text": { "en": "R and T", "ro": "R și T" },
        "figures": [ { "kind": "refraction", "scene": "s.json", "pixel": [4, 2], "depth": 3,
                       "aa": "adaptive", "threshold": 0.3, "max_level": 1,
                       "caption": { "en": "a <b>", "ro": "ă" } } ] }"#;

    fn nav() -> Nav {
        Nav {
            index: "../index.html".into(),
            other: "../ro/glass.html".into(),
            play: "play.html".into(),
            ..Nav::default()
        }
    }

    #[test]
    fn a_lesson_page_carries_its_views_state_and_the_scene() {
        let lesson = parse(LESSON).unwrap();
        let views = [View {
            scene: "s.json",
            path: Some("lessons/s.json".into()),
            text: r#"{"a": "<x>"}"#,
            spec: Some(&lesson.figures[0]),
            png: Some("glass-1-refraction.png".into()),
            caption: lesson.figures[0].caption.get(Lang::En),
        }];
        let page = lesson_page(&lesson, &views, Lang::En, &nav(), true);
        for expected in [
            "<html lang=\"en\">",
            "data-whitted=\"view\" data-scene=\"s.json\" data-path=\"lessons/s.json\" data-kind=\"refraction\" data-pixel=\"4,2\" data-depth=\"3\"",
            "<option value=\"adaptive\" selected>",
            "value=\"0.3\"",
            "data-whitted=\"max_level\" min=\"0\" max=\"8\" value=\"1\"",
            "{&quot;a&quot;: &quot;&lt;x&gt;&quot;}</textarea>",
            "a &lt;b&gt;",
            "<script src=\"../whitted-wasm.js\">",
            "href=\"../ro/glass.html\"",
            // A figure that draws no structure is narrated with every object tested.
            "<option value=\"none\" selected>",
        ] {
            assert!(page.contains(expected), "{expected} in {page}");
        }
        let ro = lesson_page(&lesson, &views, Lang::Ro, &nav(), false);
        assert!(!ro.contains("whitted-wasm.js"), "no module, no script that would fail to load");
        assert!(ro.contains("Adâncimea") && ro.contains("nu a fost construit"));
    }

    #[test]
    fn every_word_exists_in_both_languages_and_romanian_uses_comma_below() {
        let mut keys: Vec<&str> = WORDS.iter().map(|(k, _, _)| *k).collect();
        keys.sort_unstable();
        keys.dedup();
        assert_eq!(keys.len(), WORDS.len(), "keys are unique");
        for (key, en, ro) in WORDS {
            assert!(!en.is_empty() && !ro.is_empty(), "{key}");
            // ş and ţ (cedilla) are the wrong letters in Romanian: ș and ț have a comma below.
            assert!(!ro.contains(['ş', 'ţ', 'Ş', 'Ţ']), "{key}: {ro}");
        }
        let json: Value = serde_json::from_str(&words_json(Lang::Ro)).unwrap();
        assert_eq!(json["depth"], "Adâncimea");
    }

    #[test]
    fn a_structure_figure_is_narrated_by_its_structure() {
        assert_eq!(view_accel(FigureKind::GridDda), AccelKind::Grid);
        assert_eq!(view_accel(FigureKind::Octree), AccelKind::Octree);
        assert_eq!(view_accel(FigureKind::Bvh), AccelKind::Bvh);
        assert_eq!(view_accel(FigureKind::SlabTest), AccelKind::Bounds);
        assert_eq!(view_accel(FigureKind::Rays), AccelKind::None);
        assert_eq!(view_accel(FigureKind::RayTree), AccelKind::None);
    }

    #[test]
    fn the_module_script_carries_the_module_in_base64() {
        assert_eq!(module_script(b"f"), "self.WHITTED_WASM = \"Zg==\";\n");
    }

    #[test]
    fn the_playground_lists_its_examples() {
        let examples = [("whitted.json".to_owned(), "{\"x\": 1}".to_owned())];
        let page = play_page(&examples, Lang::Ro, &nav(), true);
        assert!(page.contains("data-whitted=\"example\""));
        assert!(page.contains("data-text=\"{&quot;x&quot;: 1}\""));
        assert!(page.contains("data-scene=\"whitted.json\""));
    }

    #[test]
    fn the_page_has_every_figure_and_escapes_text() {
        let lesson = parse(LESSON).unwrap();
        let shown: Vec<Shown> = (0..1)
            .map(|k| Shown {
                png: format!("{k}.png"),
                svg: format!("{k}.svg"),
                command: "whitted figure rays s.json --lang ro -o <x>".into(),
                error: None,
            })
            .collect();
        let page = index_html(&[lesson], &[shown], Lang::Ro, "../index.html");
        assert!(page.contains("<html lang=\"ro\">"));
        assert!(page.contains("src=\"0.png\""));
        assert!(page.contains("-o &lt;x&gt;"));
        assert!(page.contains("href=\"../index.html\""));
        assert!(
            page.contains("<a href=\"glass.html\">Sticlă</a> (<a href=\"#glass\">figurile</a>)"),
            "{page}"
        );
        assert!(page.contains("href=\"play.html\""));
    }
}
