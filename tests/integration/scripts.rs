//! The course on a fresh machine and after `cargo install`: `run.sh`'s logic (the WebAssembly
//! toolchain installed when missing, then the module built before the release build that embeds
//! it, then the live course written; a
//! machine where it cannot be installed still gets the rest), run against stand-ins for cargo,
//! `web/build.sh` and the binary that log their calls; and the binary run from a folder outside
//! the repository, writing the whole course from the lessons it carries.

use crate::support::Scratch;
use std::path::Path;
use std::process::Command;

/// A stand-in for `web/build.sh`: the toolchain is "installed" when the file `installed` exists;
/// `--install` creates it when `INSTALL_OK=1` (else fails as without root, exit 3); `--check`
/// answers 0 or 3; a plain call "builds" only with the toolchain.
const BUILD_SH: &str = r#"#!/bin/sh
echo "build.sh $*" >> "$LOG"
case "$*" in
  *--install*)
    if [ "$INSTALL_OK" = 1 ]; then touch "$STATE/installed"; exit 0; fi
    echo "web/build.sh: --install needs root" >&2; exit 3 ;;
  --check) [ -e "$STATE/installed" ] || exit 3 ;;
  *) [ -e "$STATE/installed" ] || exit 3; echo "$STATE/whitted_web.wasm" ;;
esac
"#;

/// A stand-in for cargo and for the built binary: each logs its name and arguments.
const LOGGER: &str = "#!/bin/sh\necho \"$(basename \"$0\") $*\" >> \"$LOG\"\n";

/// Runs a copy of `run.sh` in a scratch repository whose toolchain is installed or not, and whose
/// install succeeds or not: (exit code, the calls in order, stderr).
fn run_sh(installed: bool, install_ok: bool) -> (i32, Vec<String>, String) {
    let scratch = Scratch::new();
    let repo = scratch.join("repo");
    let bin = scratch.join("bin");
    let state = scratch.join("state");
    for dir in
        [repo.join("web"), repo.join("scenes"), repo.join("target/release"), bin.clone(), state.clone()]
    {
        std::fs::create_dir_all(dir).unwrap();
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    std::fs::copy(root.join("run.sh"), repo.join("run.sh")).unwrap();
    std::fs::write(repo.join("scenes/example.json"), "{}").unwrap();
    for (path, text) in [
        (repo.join("web/build.sh"), BUILD_SH),
        (repo.join("target/release/whitted"), LOGGER),
        (bin.join("cargo"), LOGGER),
    ] {
        std::fs::write(&path, text).unwrap();
        set_executable(&path);
    }
    if installed {
        std::fs::write(state.join("installed"), "").unwrap();
    }
    let log = scratch.join("log");
    std::fs::write(&log, "").unwrap();
    let path = format!("{}:{}", bin.display(), std::env::var("PATH").unwrap_or_default());
    let out = Command::new("bash")
        .arg(repo.join("run.sh"))
        .env("PATH", path)
        .env("LOG", &log)
        .env("STATE", &state)
        .env("INSTALL_OK", if install_ok { "1" } else { "0" })
        .output()
        .expect("run bash");
    let calls = std::fs::read_to_string(&log).unwrap().lines().map(str::to_owned).collect();
    (out.status.code().unwrap_or(-1), calls, String::from_utf8_lossy(&out.stderr).into_owned())
}

fn set_executable(path: &Path) {
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(path, std::fs::Permissions::from_mode(0o755)).unwrap();
}

/// The calls among `calls` that belong to the course: the toolchain, the builds, `lessons`.
fn course_calls(calls: &[String]) -> Vec<&str> {
    calls
        .iter()
        .map(String::as_str)
        .filter(|c| c.starts_with("build.sh") || c.starts_with("cargo") || c.starts_with("whitted lessons"))
        .collect()
}

#[test]
fn run_sh_installs_a_missing_toolchain_before_the_build_then_writes_the_live_course() {
    let (code, calls, err) = run_sh(false, true);
    assert_eq!(code, 0, "{err}");
    assert_eq!(
        course_calls(&calls),
        [
            "build.sh --check",
            "build.sh --install --check",
            "build.sh ",
            "cargo build --release --quiet",
            "whitted lessons --out out"
        ],
        "{err}"
    );
    assert!(err.contains("installing the WebAssembly toolchain"), "{err}");
    // The rest of the job still runs: every scene checked and rendered, the tradeoff measured.
    assert!(calls.iter().any(|c| c == "whitted render scenes/example.json -o out/example.png"), "{calls:?}");
    assert!(calls.last().is_some_and(|c| c.starts_with("whitted tradeoff")), "{calls:?}");
}

#[test]
fn run_sh_with_the_toolchain_installs_nothing() {
    let (code, calls, err) = run_sh(true, false);
    assert_eq!(code, 0, "{err}");
    assert_eq!(
        course_calls(&calls),
        ["build.sh --check", "build.sh ", "cargo build --release --quiet", "whitted lessons --out out"]
    );
}

#[test]
fn run_sh_without_a_toolchain_it_cannot_install_writes_a_static_course_and_says_so() {
    let (code, calls, err) = run_sh(false, false);
    assert_eq!(code, 0, "{err}");
    assert_eq!(
        course_calls(&calls),
        [
            "build.sh --check",
            "build.sh --install --check",
            "cargo build --release --quiet",
            "whitted lessons --out out"
        ]
    );
    assert!(err.contains("--install needs root") && err.contains("pages will be static"), "{err}");
}

/// The binary in a folder with no `lessons/`: the lessons and scenes it carries, the whole course.
#[test]
fn the_binary_writes_the_whole_course_from_any_folder() {
    let scratch = Scratch::new();
    let out = Command::new(env!("CARGO_BIN_EXE_whitted"))
        .args(["lessons", "--only", "secondary-rays", "--lang", "en", "--size", "320x180", "--out", "course"])
        .current_dir(scratch.path())
        .output()
        .expect("run whitted");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{err}");
    let course = scratch.join("course");
    let lessons: Vec<String> = std::fs::read_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .map(|p| whitted::lesson::parse(&std::fs::read_to_string(p).unwrap()).unwrap().name)
        .collect();
    assert!(lessons.len() > 10, "{lessons:?}");
    for name in &lessons {
        let page = course.join("en").join(format!("{name}.html"));
        assert!(page.is_file(), "{} is missing", page.display());
    }
    for file in
        ["index.html", "whitted.js", "whitted.css", "en/play.html", "en/secondary-rays-1-refraction.png"]
    {
        assert!(course.join(file).is_file(), "{file} is missing");
    }
    // The playground offers the scenes the binary carries, Whitted's first.
    let play = std::fs::read_to_string(course.join("en/play.html")).unwrap();
    assert!(play.contains("whitted.json") && play.contains("groups_2d.json"), "the playground's examples");
    // A test build carries no module (build.rs embeds it in release builds only): the pages are
    // static, and stderr says how to get the live part.
    if course.join("whitted-wasm.js").exists() {
        assert!(!err.contains("without their live part"), "{err}");
    } else {
        assert!(err.contains("without their live part") && err.contains("cargo install --path ."), "{err}");
    }
}
