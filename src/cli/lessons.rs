//! `whitted lessons`: read every lesson file of `lessons/` (`whitted::lesson`), draw each figure in
//! each language as PNG and SVG into `out/en/` and `out/ro/`, and write the pages `out/index.html`
//! (English) and `out/ro/index.html` (Romanian) that show them with their captions and the
//! command that regenerates each; then the interactive course (`whitted::site`): a page per lesson
//! and language (`out/en/NAME.html`, `out/ro/NAME.html`), the playgrounds (`play.html`), the
//! scripts and style of `web/site/`, and the WebAssembly module as `out/whitted-wasm.js` when
//! there is one (`--wasm`, the binary's own, or `web/build.sh`'s; otherwise stderr says how to get
//! it). The lessons and scenes are read from disk or from the binary (`course`).

use super::course::{self, tidy, Files};
use super::figure::{scene_name, Format, SvgTextArg};
use super::trace::LangArg;
use super::{output, print_out, write_file, Failure};
use clap::Args;
use rayon::prelude::*;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use whitted::canvas::Drawing;
use whitted::figure::{Lang, Options};
use whitted::lesson::claim::Verdict;
use whitted::lesson::{self, FigureSpec, Lesson};
use whitted::request::exercises::sheets;
use whitted::request::figure::{figure_checked, Request};
use whitted::request::options::{canvas, AccelChoice};
use whitted::request::parse;
use whitted::sample::Sampling;
use whitted::scene::load::MAX_SCENE_BYTES;
use whitted::scene::AnyScene;
use whitted::site::{self, Nav, Shown, View};

/// Options of `whitted lessons`.
#[derive(Args, Debug)]
pub struct LessonsArgs {
    /// Draw only the lesson with this name (its "name" field); the pages still list every lesson.
    #[arg(long)]
    only: Option<String>,
    /// The folder to write into: DIR/en/, DIR/ro/, DIR/index.html, DIR/ro/index.html. One run
    /// at a time: another run into the same folder is refused (the lock file .whitted-lessons.lock).
    #[arg(long, default_value = "out")]
    out: PathBuf,
    /// Only this language (default: both).
    #[arg(long, value_enum)]
    lang: Option<LangArg>,
    /// The folder of lesson files (default: lessons/ of the current folder if there is one, else
    /// the lessons this whitted carries).
    #[arg(long)]
    lessons: Option<PathBuf>,
    /// Canvas size WxH in pixels (default 1920x1080).
    #[arg(long, value_parser = parse::size, allow_hyphen_values = true)]
    size: Option<(usize, Option<usize>)>,
    /// How the figures' SVG files draw their words: `embed` (text in the fonts' subsets) or
    /// `paths` (glyph outlines, the words kept invisible for screen readers and search).
    #[arg(long, value_enum, default_value = "embed")]
    svg_text: SvgTextArg,
    /// The WebAssembly module that makes the pages live (default: the one built into this whitted,
    /// else target/wasm/whitted_web.wasm, built by web/build.sh).
    #[arg(long)]
    wasm: Option<PathBuf>,
}

/// The lock file a run holds in its output folder: a second run into the same folder is refused
/// (exit 2) rather than made to wait, since it would redraw the same files and its user is better
/// told at once than kept behind a long run.
const LOCK_FILE: &str = ".whitted-lessons.lock";
/// The playground's first scene.
const FIRST_EXAMPLE: &str = "whitted.json";

/// Where `web/build.sh` writes the module.
const DEFAULT_WASM: &str = "target/wasm/whitted_web.wasm";

/// What a `whitted` without a module tells its user: how to get the live part.
const HOW_TO_GET_THE_MODULE: &str = "the pages are written without their live part. In the \
     repository, ./run.sh builds the module (installing its toolchain when missing) and writes the \
     live course; or build it with `web/build.sh` (`web/build.sh --install` first installs its \
     toolchain, as root) and pass `--wasm target/wasm/whitted_web.wasm`. An installed whitted \
     carries the module when `web/build.sh` built it before `cargo install --path .`.";

/// The module the pages run: `--wasm FILE` when given; else the one built into this binary
/// (`build.rs`); else `web/build.sh`'s in the current folder. The error says why there is none
/// and how to get it.
fn wasm_module(wasm: Option<&Path>) -> Result<std::borrow::Cow<'static, [u8]>, String> {
    if let Some(path) = wasm {
        return std::fs::read(path)
            .map(Into::into)
            .map_err(|e| format!("{}: {e}; {HOW_TO_GET_THE_MODULE}", path.display()));
    }
    if let Some(module) = course::module() {
        return Ok(module.into());
    }
    std::fs::read(DEFAULT_WASM).map(Into::into).map_err(|e| {
        format!("this whitted carries no WebAssembly module and {DEFAULT_WASM}: {e}; {HOW_TO_GET_THE_MODULE}")
    })
}

/// The page scripts and style, written beside the pages (`out/whitted.js`, `out/grade.js`,
/// `out/whitted.css`).
const SITE_FILES: [(&str, &str); 3] = [
    ("whitted.js", include_str!("../../web/site/whitted.js")),
    ("grade.js", include_str!("../../web/site/grade.js")),
    ("whitted.css", include_str!("../../web/site/whitted.css")),
];

/// One figure drawn: (lesson, figure, language) and why it failed, if it did.
type Drawn = ((usize, usize, Lang), Option<String>);
/// One figure made, not yet written: its drawing and its claims' verdicts, or why it failed.
type Made = ((usize, usize, Lang), Result<(Drawing, Vec<Verdict>), String>);

/// A lesson file read, with the folder its scene paths are relative to.
struct Read {
    lesson: Lesson,
    dir: PathBuf,
}

/// The lesson files of `dir`, in file-name order.
fn read_lessons(from: Files, dir: &Path) -> Result<Vec<Read>, Failure> {
    let files = from
        .json_files(dir)
        .map_err(|e| Failure::input(format!("{}: cannot read the lessons folder: {e}", dir.display())))?;
    let mut problems = Vec::new();
    let mut lessons = Vec::new();
    // The file that first used each lesson name: a second one would overwrite its figures.
    let mut named: Vec<(String, PathBuf)> = Vec::new();
    for file in files {
        let text = from
            .read(&file, MAX_SCENE_BYTES)
            .map_err(|e| Failure::input(format!("{}: cannot read: {e}", file.display())))?;
        match lesson::parse(&text) {
            Ok(lesson) => {
                if let Some((_, first)) = named.iter().find(|(name, _)| *name == lesson.name) {
                    problems.push(format!(
                        "{}: name: `{}` is already the name of {}; each lesson needs its own",
                        file.display(),
                        lesson.name,
                        first.display()
                    ));
                }
                named.push((lesson.name.clone(), file.clone()));
                lessons.push(Read { lesson, dir: dir.to_path_buf() });
            }
            Err(errors) => problems.extend(errors.into_iter().map(|e| format!("{}: {e}", file.display()))),
        }
    }
    if problems.is_empty() && lessons.is_empty() {
        return Err(Failure::input(format!(
            "{}: no lesson files (NAME.json) in the lessons folder; give the folder with --lessons",
            dir.display()
        )));
    }
    if problems.is_empty() {
        Ok(lessons)
    } else {
        Err(Failure::input(problems.join("\n")))
    }
}

/// The folder of a language under the output folder.
fn lang_dir(lang: Lang) -> &'static str {
    match lang {
        Lang::En => "en",
        Lang::Ro => "ro",
    }
}

/// The command that regenerates one figure's PNG.
fn command(spec: &FigureSpec, scene: &Path, lang: Lang, png: &Path) -> String {
    let mut cmd =
        format!("whitted figure {} {}", spec.kind.name(), shell_quote(&scene.display().to_string()));
    if let Some(pixel) = spec.pixel_arg() {
        cmd.push_str(&format!(" --pixel {pixel}"));
    } else if let Some(ray) = spec.ray_arg() {
        cmd.push_str(&format!(" --ray={ray}"));
    }
    if let Some(depth) = spec.depth {
        cmd.push_str(&format!(" --depth {depth}"));
    }
    match spec.sampling {
        Some(Sampling::Corners) => cmd.push_str(" --aa corners"),
        Some(Sampling::Adaptive { threshold, max_level }) => {
            cmd.push_str(&format!(" --aa adaptive --threshold {threshold} --max-level {max_level}"));
        }
        Some(Sampling::Center) | None => {}
    }
    if let Some(cells) = &spec.grid {
        let cells: Vec<String> = cells.iter().map(ToString::to_string).collect();
        cmd.push_str(&format!(" --grid {}", cells.join(",")));
    }
    if let Some(title) = &spec.title {
        cmd.push_str(&format!(" --title {}", shell_quote(title.get(lang))));
    }
    cmd.push_str(&format!(" --lang {} -o {}", lang_dir(lang), shell_quote(&png.display().to_string())));
    cmd
}

/// A word as a POSIX shell reads it back unchanged: as it is when made only of characters no shell
/// treats specially, else in single quotes, a quote inside written `'\''`.
fn shell_quote(word: &str) -> String {
    let plain = |c: char| c.is_ascii_alphanumeric() || "/._-+,:=@%".contains(c);
    if !word.is_empty() && word.chars().all(plain) {
        word.to_owned()
    } else {
        format!("'{}'", word.replace('\'', "'\\''"))
    }
}

/// Runs `whitted lessons`.
pub fn run(args: &LessonsArgs) -> Result<(), Failure> {
    let (from, dir) = Files::choose(args.lessons.as_deref());
    let read = read_lessons(from, &dir)?;
    // `--only` draws one lesson; the pages still list every lesson (the others' files are those
    // an earlier run wrote).
    let drawn: Vec<bool> =
        read.iter().map(|r| args.only.as_ref().is_none_or(|o| &r.lesson.name == o)).collect();
    if let Some(only) = &args.only {
        if !drawn.contains(&true) {
            return Err(Failure::input(format!("--only: no lesson is named `{only}`")));
        }
    }
    let langs: Vec<Lang> = match args.lang {
        Some(l) => vec![l.lang()],
        None => vec![Lang::En, Lang::Ro],
    };
    // The folder is checked and locked before the work; the lock is held until the run ends.
    output::create_folder(&args.out)?;
    let _lock = output::lock_folder(&args.out, LOCK_FILE)?;
    for lang in &langs {
        output::create_folder(&args.out.join(lang_dir(*lang)))?;
    }
    // Each scene is read once.
    let mut scenes: HashMap<PathBuf, Result<AnyScene, String>> = HashMap::new();
    for r in read.iter().zip(&drawn).filter(|(_, d)| **d).map(|(r, _)| r) {
        for spec in &r.lesson.figures {
            let path = r.dir.join(&spec.scene);
            scenes.entry(path.clone()).or_insert_with(|| from.load_scene(&path).map_err(|f| f.message));
        }
    }
    let (width, height) = canvas(args.size)?;
    // One job per figure and language, drawn in parallel.
    let mut jobs: Vec<(usize, usize, Lang)> = Vec::new();
    for (l, r) in read.iter().enumerate().filter(|(l, _)| drawn[*l]) {
        for f in 0..r.lesson.figures.len() {
            jobs.extend(langs.iter().map(|g| (l, f, *g)));
        }
    }
    // Every figure is made and its claims checked before anything is written: a figure that no
    // longer shows its point stops the run (exit 1) with every failed claim listed.
    let made: Vec<Made> = jobs
        .par_iter()
        .map(|&(l, f, lang)| {
            let r = &read[l];
            let spec = &r.lesson.figures[f];
            let scene_path = r.dir.join(&spec.scene);
            let request = Request::of_lesson(spec, Options { lang, width, height });
            let made = scenes[&scene_path].as_ref().map_err(Clone::clone).and_then(|scene| {
                figure_checked(scene, &scene_name(&scene_path), &request, &spec.claims)
                    .map(|(mut made, verdicts)| {
                        if let Some(title) = &spec.title {
                            made.drawing.set_title(title.get(lang));
                        }
                        (made.drawing, verdicts)
                    })
                    .map_err(|f| f.message)
            });
            ((l, f, lang), made)
        })
        .collect();
    let mut unmet: Vec<String> = Vec::new();
    for ((l, f, _), made) in &made {
        for verdict in made.iter().flat_map(|(_, v)| v).filter(|v| !v.holds()) {
            let spec = &read[*l].lesson.figures[*f];
            let line = verdict.message(&read[*l].lesson.name, f + 1, spec.kind.name());
            if !unmet.contains(&line) {
                unmet.push(line);
            }
        }
    }
    if !unmet.is_empty() {
        return Err(Failure::other(format!(
            "{} claim(s) of the lessons do not hold; nothing was written:\n{}",
            unmet.len(),
            unmet.join("\n")
        )));
    }
    let results: Vec<Drawn> = made
        .into_par_iter()
        .map(|((l, f, lang), made)| {
            let stem = read[l].lesson.file_stem(f);
            let dir = args.out.join(lang_dir(lang));
            let (png, svg) = (dir.join(format!("{stem}.png")), dir.join(format!("{stem}.svg")));
            let written = made.and_then(|(drawing, _)| {
                for (path, format) in [(&png, Format::Png), (&svg, Format::Svg)] {
                    write_file(path, &format.encode(&drawing, args.svg_text.text()).map_err(|f| f.message)?)
                        .map_err(|f| f.message)?;
                }
                Ok(())
            });
            ((l, f, lang), written.err())
        })
        .collect();

    let mut failed = Vec::new();
    for lang in &langs {
        let shown: Vec<Vec<Shown>> = read
            .iter()
            .enumerate()
            .map(|(l, r)| {
                (0..r.lesson.figures.len())
                    .map(|f| {
                        let error = results
                            .iter()
                            .find(|(key, _)| *key == (l, f, *lang))
                            .and_then(|(_, e)| e.clone());
                        let stem = r.lesson.file_stem(f);
                        let png = args.out.join(lang_dir(*lang)).join(format!("{stem}.png"));
                        let page_dir =
                            if *lang == Lang::En { format!("{}/", lang_dir(*lang)) } else { String::new() };
                        let scene_path = r.dir.join(&r.lesson.figures[f].scene);
                        Shown {
                            png: format!("{page_dir}{stem}.png"),
                            svg: format!("{page_dir}{stem}.svg"),
                            command: command(&r.lesson.figures[f], &scene_path, *lang, &png),
                            error,
                        }
                    })
                    .collect()
            })
            .collect();
        for (r, figures) in read.iter().zip(&shown) {
            for (f, s) in figures.iter().enumerate() {
                if let Some(e) = &s.error {
                    failed.push(format!("{} ({}): {e}", r.lesson.file_stem(f), lang_dir(*lang)));
                }
            }
        }
        let lessons: Vec<Lesson> = read.iter().map(|r| r.lesson.clone()).collect();
        let (page, other) = match lang {
            Lang::En => (args.out.join("index.html"), "ro/index.html"),
            Lang::Ro => (args.out.join("ro").join("index.html"), "../index.html"),
        };
        write_file(&page, site::index_html(&lessons, &shown, *lang, other).as_bytes())?;
    }
    write_site(args, from, &read, &langs, &results)?;
    let figures: usize =
        read.iter().zip(&drawn).filter(|(_, d)| **d).map(|(r, _)| r.lesson.figures.len()).sum();
    print_out(&format!(
        "lessons: {} lessons, {figures} figures × {} language(s), PNG and SVG, into {}\n",
        drawn.iter().filter(|d| **d).count(),
        langs.len(),
        args.out.display()
    ))?;
    if failed.is_empty() {
        Ok(())
    } else {
        Err(Failure::other(failed.join("\n")))
    }
}

/// The interactive course: a page per lesson and language, the playgrounds, the scripts, and the
/// module if it was built. `results` says which static figures were drawn (the pages show them
/// until the module replaces them with live ones).
fn write_site(
    args: &LessonsArgs,
    from: Files,
    read: &[Read],
    langs: &[Lang],
    results: &[Drawn],
) -> Result<(), Failure> {
    let module = match wasm_module(args.wasm.as_deref()) {
        Ok(wasm) => {
            write_file(&args.out.join(site::MODULE_SCRIPT), site::module_script(&wasm).as_bytes())?;
            true
        }
        Err(why) => {
            eprintln!("whitted lessons: {why}");
            false
        }
    };
    for (name, text) in SITE_FILES {
        write_file(&args.out.join(name), text.as_bytes())?;
    }
    // Every scene a lesson names, read once, in the lessons' order: the views' editors and the
    // playground's examples.
    let mut texts: Vec<(PathBuf, String)> = Vec::new();
    for r in read {
        for spec in &r.lesson.figures {
            let path = r.dir.join(&spec.scene);
            if !texts.iter().any(|(p, _)| *p == path) {
                let text = from
                    .read(&path, MAX_SCENE_BYTES)
                    .map_err(|e| Failure::input(format!("{}: cannot read: {e}", path.display())))?;
                texts.push((path, text));
            }
        }
    }
    let text_of = |path: &Path| texts.iter().find(|(p, _)| p == path).map_or("", |(_, t)| t.as_str());
    for lang in langs {
        let code = site::code(*lang);
        let other = match lang {
            Lang::En => "ro",
            Lang::Ro => "en",
        };
        let index = match lang {
            Lang::En => "../index.html",
            Lang::Ro => "index.html",
        };
        let dir = args.out.join(code);
        for (l, r) in read.iter().enumerate() {
            let lesson = &r.lesson;
            let views: Vec<View> = lesson
                .figures
                .iter()
                .enumerate()
                .map(|(f, spec)| {
                    let drawn = results.iter().any(|(key, error)| *key == (l, f, *lang) && error.is_none());
                    let png = format!("{}.png", lesson.file_stem(f));
                    View {
                        scene: &spec.scene,
                        path: Some(tidy(&r.dir.join(&spec.scene))),
                        text: text_of(&r.dir.join(&spec.scene)),
                        spec: Some(spec),
                        png: (drawn || dir.join(&png).exists()).then_some(png),
                        caption: spec.caption.get(*lang),
                    }
                })
                .collect();
            let page_of = |k: usize| read.get(k).map(|n| format!("{}.html", n.lesson.name));
            let nav = Nav {
                index: index.to_owned(),
                other: format!("../{other}/{}.html", lesson.name),
                prev: l.checked_sub(1).and_then(page_of),
                next: page_of(l + 1),
                play: "play.html".to_owned(),
            };
            let page = site::lesson_page(lesson, &views, *lang, &nav, module);
            write_file(&dir.join(format!("{}.html", lesson.name)), page.as_bytes())?;
            // The lesson's exercise sheets beside its page (`whitted exercises`).
            for (k, spec) in lesson.exercises.iter().enumerate() {
                let path = r.dir.join(&spec.scene);
                let scene = from.load_scene(&path)?;
                let signed = |n: usize| i64::try_from(n).unwrap_or(i64::MAX);
                let pixel = (signed(spec.pixel.0), spec.pixel.1.map(signed));
                let made =
                    sheets(&scene, &scene_name(&path), pixel, *lang, spec.seed, &AccelChoice::default())
                        .map_err(|f| {
                            Failure::input(format!("{} exercises[{k}]: {}", lesson.name, f.message))
                        })?;
                let (ex, ans) = lesson.exercise_files(k);
                write_file(&dir.join(ex), made.exercises.as_bytes())?;
                write_file(&dir.join(ans), made.answers.as_bytes())?;
            }
        }
        // Whitted's scene first, then the others in the lessons' order.
        let mut examples: Vec<(String, String)> = texts
            .iter()
            .map(|(path, text)| {
                (
                    path.file_name().map_or_else(String::new, |n| n.to_string_lossy().into_owned()),
                    text.clone(),
                )
            })
            .collect();
        examples.sort_by_key(|(name, _)| name != FIRST_EXAMPLE);
        let nav = Nav {
            index: index.to_owned(),
            other: format!("../{other}/play.html"),
            play: "play.html".to_owned(),
            ..Nav::default()
        };
        write_file(&dir.join("play.html"), site::play_page(&examples, *lang, &nav, module).as_bytes())?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::shell_quote;

    #[test]
    fn quotes_only_what_a_shell_would_read_otherwise() {
        assert_eq!(shell_quote("lessons/scenes/spheres.json"), "lessons/scenes/spheres.json");
        assert_eq!(shell_quote("my scenes/a.json"), "'my scenes/a.json'");
        assert_eq!(shell_quote("a$(rm -rf x);b"), "'a$(rm -rf x);b'");
        assert_eq!(shell_quote("it's"), "'it'\\''s'");
        assert_eq!(shell_quote(""), "''");
    }
}
