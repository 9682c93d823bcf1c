//! Outputs are never destroyed, never torn (issue 21, item 3): every file the tool writes is whole
//! or untouched, even when the write fails or the process is killed midway; two `lessons` runs
//! into one folder are kept apart by a lock; an output that is the input scene, that has an
//! unknown extension, or whose folder is missing or not writable is refused before the work.

use crate::support::{fixture_path, whitted, Scratch};
use std::os::unix::process::ExitStatusExt;
use std::path::Path;
use std::process::{Command, Stdio};

/// The old contents every test puts in the destination before the tool runs.
const OLD: &[u8] = b"the previous file, which must survive";
/// The render size of these tests: its PNG (about 10 kB) is well above `FILE_LIMIT_BLOCKS`.
const SIZE: &str = "128x96";
/// The file-size limit of `ulimit -f` in the shell's 512-byte blocks (1 kB): the PNG's write
/// crosses it midway.
const FILE_LIMIT_BLOCKS: u32 = 2;
/// The lock file `whitted lessons` holds in its output folder.
const LOCK: &str = ".whitted-lessons.lock";
/// The signal of a write beyond `ulimit -f` (Linux).
const SIGXFSZ: i32 = 25;

fn s(path: &Path) -> &str {
    path.to_str().unwrap()
}

/// The names in `dir` that look like a temporary file of the tool (`.NAME.tmp-…`).
fn temporaries(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with('.') && n.contains(".tmp-"))
        .collect()
}

/// Runs `whitted ARGS` under `ulimit -f`, with SIGXFSZ left to kill the process (`ignore` false)
/// or ignored so that the write fails with EFBIG, as on a full disk (`ignore` true).
fn whitted_with_file_limit(args: &[&str], ignore: bool) -> std::process::Output {
    let trap = if ignore { "trap '' XFSZ; " } else { "" };
    let script = format!("{trap}ulimit -f {FILE_LIMIT_BLOCKS} && exec \"$0\" \"$@\"");
    Command::new("sh")
        .arg("-c")
        .arg(script)
        .arg(env!("CARGO_BIN_EXE_whitted"))
        .args(args)
        .output()
        .expect("run sh")
}

#[test]
fn a_write_killed_or_failing_midway_leaves_the_old_file() {
    let scratch = Scratch::new();
    let dir = scratch.path();
    let glass = fixture_path("glass.json");
    // The whole PNG is larger than the limit, so the limited write stops inside it.
    let whole = dir.join("whole.png");
    let (code, _, err) = whitted(&["render", &glass, "--size", SIZE, "-o", s(&whole)]);
    assert_eq!(code, 0, "{err}");
    let limit = u64::from(FILE_LIMIT_BLOCKS) * 512;
    assert!(std::fs::metadata(&whole).unwrap().len() > 4 * limit);
    for ignore in [false, true] {
        // Each case in a folder of its own: a killed run leaves its temporary file behind.
        let case = dir.join(if ignore { "failed" } else { "killed" });
        std::fs::create_dir(&case).unwrap();
        let dest = case.join("dest.png");
        std::fs::write(&dest, OLD).unwrap();
        let out = whitted_with_file_limit(&["render", &glass, "--size", SIZE, "-o", s(&dest)], ignore);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "the limited write succeeded: {err}");
        if !ignore {
            // Killed by the limit's signal midway through the PNG, as a kill would.
            assert_eq!(out.status.signal(), Some(SIGXFSZ), "{err}");
        } else {
            // The failed write is reported (exit 1, the file named) and its temporary removed.
            assert_eq!(out.status.code(), Some(1), "{err}");
            assert!(err.contains(s(&dest)) && err.contains("cannot write"), "{err}");
            assert_eq!(temporaries(&case), Vec::<String>::new());
        }
        let now = std::fs::read(&dest).unwrap();
        assert!(now == OLD, "ignore SIGXFSZ: {ignore}: the old file was torn ({} bytes now)", now.len());
        assert!(!err.contains("panicked"), "{err}");
    }
    // Without the limit the same command replaces the old file with the whole PNG.
    let dest = dir.join("killed").join("dest.png");
    let (code, _, err) = whitted(&["render", &glass, "--size", SIZE, "-o", s(&dest)]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(std::fs::read(&dest).unwrap(), std::fs::read(&whole).unwrap());
}

#[test]
fn a_destination_that_is_a_folder_is_refused_before_the_work() {
    let scratch = Scratch::new();
    let dir = scratch.path();
    let dest = dir.join("picture.png");
    std::fs::create_dir(&dest).unwrap();
    std::fs::write(dest.join("keep.txt"), OLD).unwrap();
    let glass = fixture_path("glass.json");
    for args in [
        vec!["render", &glass, "-o", s(&dest)],
        vec!["figure", "rays", &glass, "--size", "320x180", "-o", s(&dest)],
    ] {
        let (code, _, err) = whitted(&args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(err.contains(s(&dest)) && err.contains("is a folder"), "{args:?}: {err}");
        assert_eq!(std::fs::read(dest.join("keep.txt")).unwrap(), OLD);
        assert_eq!(temporaries(dir), Vec::<String>::new());
    }
}

#[test]
fn a_replaced_file_keeps_its_permissions() {
    use std::os::unix::fs::PermissionsExt;
    let scratch = Scratch::new();
    let dir = scratch.path();
    let dest = dir.join("private.png");
    std::fs::write(&dest, OLD).unwrap();
    set_mode(&dest, 0o640);
    let (code, _, err) = whitted(&["render", &fixture_path("glass.json"), "-o", s(&dest)]);
    assert_eq!(code, 0, "{err}");
    assert!(std::fs::read(&dest).unwrap().starts_with(b"\x89PNG"));
    assert_eq!(std::fs::metadata(&dest).unwrap().permissions().mode() & 0o777, 0o640);
}

#[test]
fn a_symlinked_output_is_written_through_the_link() {
    let scratch = Scratch::new();
    let dir = scratch.path();
    let real = dir.join("real.png");
    std::fs::write(&real, OLD).unwrap();
    let link = dir.join("link.png");
    std::os::unix::fs::symlink(&real, &link).unwrap();
    let (code, _, err) = whitted(&["render", &fixture_path("glass.json"), "-o", s(&link)]);
    assert_eq!(code, 0, "{err}");
    assert!(std::fs::symlink_metadata(&link).unwrap().file_type().is_symlink(), "the link was replaced");
    let bytes = std::fs::read(&real).unwrap();
    assert!(bytes.starts_with(b"\x89PNG"), "the link's target holds the new PNG");
}

#[test]
fn the_input_scene_is_never_an_output() {
    let scratch = Scratch::new();
    let dir = scratch.path();
    let scene = dir.join("scene.json");
    let text = std::fs::read(fixture_path("glass.json")).unwrap();
    std::fs::write(&scene, &text).unwrap();
    // The scene under a name with an output's extension, and links to it.
    let png_named = dir.join("heat-map.png");
    std::fs::write(&png_named, &text).unwrap();
    let link_png = dir.join("link.png");
    std::os::unix::fs::symlink(&scene, &link_png).unwrap();
    let link_svg = dir.join("link.svg");
    std::os::unix::fs::symlink(&scene, &link_svg).unwrap();
    let relative = format!("{}/../{}/scene.json", s(dir), dir.file_name().unwrap().to_str().unwrap());
    let cases: Vec<Vec<&str>> = vec![
        vec!["render", s(&scene), "-o", s(&scene)],
        vec!["render", s(&scene), "-o", &relative],
        vec!["render", s(&scene), "-o", s(&link_png)],
        vec!["render", s(&png_named), "-o", s(&png_named)],
        vec!["figure", "rays", s(&scene), "--size", "320x180", "-o", s(&link_svg)],
        vec!["tradeoff", s(&png_named), "--size", "4x3", "--runs", "1", "--out", s(dir)],
    ];
    for args in &cases {
        let (code, out, err) = whitted(args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(err.contains("is the input scene"), "{args:?}: {err}");
        assert!(out.is_empty(), "{args:?}: the work ran: {out}");
        assert_eq!(std::fs::read(&scene).unwrap(), text, "{args:?}: the scene was overwritten");
        assert_eq!(std::fs::read(&png_named).unwrap(), text, "{args:?}: the scene was overwritten");
    }
}

#[test]
fn an_unknown_extension_is_refused_as_figure_refuses_it() {
    let scratch = Scratch::new();
    let dir = scratch.path();
    let glass = fixture_path("glass.json");
    let jpg = dir.join("x.jpg");
    let (code, _, err) = whitted(&["render", &glass, "-o", s(&jpg)]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains(&format!("{}: the output must end in .png", s(&jpg))), "{err}");
    assert!(!jpg.exists(), "render wrote a PNG under .jpg");
    let (code, _, err) = whitted(&["figure", "rays", &glass, "-o", s(&jpg)]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains(&format!("{}: the output must end in .png or .svg", s(&jpg))), "{err}");
    // A device takes any bytes, whatever its name.
    let (code, _, err) = whitted(&["render", &glass, "-o", "/dev/null"]);
    assert_eq!(code, 0, "{err}");
}

#[test]
fn a_missing_or_unwritable_output_folder_is_reported_before_the_work() {
    let scratch = Scratch::new();
    let dir = scratch.path();
    let glass = fixture_path("glass.json");
    let missing = dir.join("missing");
    let file = dir.join("file.txt");
    std::fs::write(&file, OLD).unwrap();
    let (png, under_file, in_file) = (missing.join("x.png"), file.join("plots"), file.join("x.png"));
    let cases: Vec<(Vec<&str>, &Path, &str)> = vec![
        (vec!["render", &glass, "--json", "-o", s(&png)], &missing, "does not exist"),
        (vec!["figure", "rays", &glass, "-o", s(&png)], &missing, "does not exist"),
        (vec!["render", &glass, "--json", "-o", s(&in_file)], &file, "is not a folder"),
        (vec!["tradeoff", &glass, "--size", "4x3", "--runs", "1", "--out", s(&under_file)], &file, "folder"),
        (vec!["lessons", "--only", "pixel-uv", "--out", s(&under_file)], &file, "folder"),
    ];
    for (args, named, says) in &cases {
        let (code, out, err) = whitted(args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(err.contains(s(named)) && err.contains(says), "{args:?}: {err}");
        // The work never started: no statistics, no table, no summary line.
        assert!(out.is_empty(), "{args:?}: {out}");
        assert!(!err.contains("whitted:"), "{args:?}: {err}");
    }
    // A folder without write permission (a privileged user writes anyway: then there is nothing
    // to refuse, and the case is skipped with that reason).
    let locked = dir.join("read-only");
    std::fs::create_dir(&locked).unwrap();
    set_mode(&locked, 0o555);
    if std::fs::write(locked.join("probe"), b"").is_ok() {
        eprintln!("skipped: this user writes into a read-only folder (root), nothing to refuse");
    } else {
        let (code, out, err) = whitted(&["render", &glass, "--json", "-o", s(&locked.join("x.png"))]);
        assert_eq!(code, 2, "{err}");
        assert!(err.contains(s(&locked)) && err.contains("cannot be written"), "{err}");
        assert!(out.is_empty(), "{out}");
    }
    set_mode(&locked, 0o755);
}

fn set_mode(path: &Path, mode: u32) {
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(path, std::fs::Permissions::from_mode(mode)).unwrap();
}

/// The `whitted lessons` command of these tests: one small lesson into `out`.
fn lessons_command(out: &Path) -> Command {
    let lessons = format!("{}/lessons", env!("CARGO_MANIFEST_DIR"));
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_whitted"));
    cmd.args(["lessons", "--lessons", &lessons, "--only", "secondary-rays", "--size", "320x180", "--out"])
        .arg(out);
    cmd
}

/// Every PNG under `dir` decodes and every SVG is XML.
fn assert_whole(dir: &Path) -> usize {
    let mut files = 0;
    for lang in ["en", "ro"] {
        for entry in std::fs::read_dir(dir.join(lang)).unwrap() {
            let path = entry.unwrap().path();
            let bytes = std::fs::read(&path).unwrap();
            match path.extension().and_then(|e| e.to_str()) {
                Some("png") => {
                    let decoded = image::load_from_memory_with_format(&bytes, image::ImageFormat::Png);
                    assert!(decoded.is_ok(), "{}: torn PNG: {:?}", path.display(), decoded.err());
                }
                Some("svg") => {
                    let text = String::from_utf8(bytes).unwrap();
                    let parsed = roxmltree::Document::parse(&text);
                    assert!(parsed.is_ok(), "{}: torn SVG: {:?}", path.display(), parsed.err());
                }
                _ => continue,
            }
            files += 1;
        }
    }
    let page = std::fs::read_to_string(dir.join("index.html")).unwrap();
    assert!(page.trim_end().ends_with("</html>"), "torn index.html");
    files
}

#[test]
fn a_lessons_folder_in_use_is_refused_naming_the_lock() {
    let scratch = Scratch::new();
    let out = scratch.path();
    let lock = std::fs::File::create(out.join(LOCK)).unwrap();
    lock.try_lock().unwrap();
    let refused = lessons_command(out).output().unwrap();
    let err = String::from_utf8_lossy(&refused.stderr);
    assert_eq!(refused.status.code(), Some(2), "{err}");
    assert!(err.contains(s(&out.join(LOCK))) && err.contains("in use"), "{err}");
    assert!(!out.join("en").exists(), "the refused run wrote");
    lock.unlock().unwrap();
    let done = lessons_command(out).output().unwrap();
    assert!(done.status.success(), "{}", String::from_utf8_lossy(&done.stderr));
    assert!(assert_whole(out) > 0);
}

#[test]
fn two_concurrent_lessons_runs_never_tear_a_file() {
    let scratch = Scratch::new();
    let out = scratch.path();
    let spawn = || lessons_command(out).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().unwrap();
    let (first, second) = (spawn(), spawn());
    let outcomes = [first.wait_with_output().unwrap(), second.wait_with_output().unwrap()];
    let mut succeeded = 0;
    for o in &outcomes {
        let err = String::from_utf8_lossy(&o.stderr);
        match o.status.code() {
            Some(0) => succeeded += 1,
            // Refused while the other one runs: the lock is named.
            Some(2) => assert!(err.contains(LOCK) && err.contains("in use"), "{err}"),
            other => panic!("exit {other:?}: {err}"),
        }
    }
    assert!(succeeded >= 1, "both runs were refused");
    assert!(assert_whole(out) > 0);
    assert_eq!(temporaries(&out.join("en")), Vec::<String>::new());
}
