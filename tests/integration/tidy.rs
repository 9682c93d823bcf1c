//! Tidy checks (design.md habit 2): every source file opens with a `//!` line saying what it owns,
//! algorithm.md's Conventions cannot change without this project noticing (a stored hash), and only
//! `cli/output.rs` writes files.

use std::path::{Path, PathBuf};

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

#[test]
fn every_source_file_opens_with_a_module_doc() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    for dir in ["src", "tests/integration", "benches"] {
        rust_files(&root.join(dir), &mut files);
    }
    let missing: Vec<String> = files
        .iter()
        .filter(|p| !std::fs::read_to_string(p).unwrap().starts_with("//!"))
        .map(|p| p.strip_prefix(root).unwrap().display().to_string())
        .collect();
    assert!(missing.is_empty(), "files without a leading `//!` doc line: {missing:?}");
}

/// FNV-1a, 64 bits: enough to notice an edit.
fn fnv1a(text: &str) -> u64 {
    text.bytes().fold(0xcbf2_9ce4_8422_2325, |h, b| (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3))
}

/// The Convention paragraphs of algorithm.md (each paragraph that holds `**Convention`) and §11,
/// the numerical policies, whole.
fn conventions(text: &str) -> String {
    let (body, policies) = text.split_once("## 11.").unwrap_or((text, ""));
    let mut out: Vec<&str> = body.split("\n\n").filter(|p| p.contains("**Convention")).collect();
    out.push(policies);
    out.join("\n\n")
}

#[test]
fn algorithm_conventions_are_the_ones_the_tests_were_written_for() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let doc = root.join("../shared/docs/algorithm.md");
    let Ok(text) = std::fs::read_to_string(&doc) else {
        // Outside the workplace layout (a crate download), there is nothing to compare.
        return;
    };
    let stored = std::fs::read_to_string(root.join("tests/data/conventions.hash")).unwrap();
    let now = format!("{:016x}", fnv1a(&conventions(&text)));
    assert_eq!(
        stored.trim(),
        now,
        "algorithm.md's Conventions changed: review the tests that pin them (tests/integration/traces.rs, \
         the numerics unit tests), then store the new hash in tests/data/conventions.hash"
    );
}

/// The calls that create or replace a file; only `src/cli/output.rs` may make them.
const FILE_WRITES: [&str; 5] = ["fs::write(", "File::create", "OpenOptions", "fs::rename(", "fs::copy("];

#[test]
fn every_file_is_written_through_the_one_atomic_writer() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    rust_files(&root.join("src"), &mut files);
    let writer = root.join("src/cli/output.rs");
    let offending: Vec<String> = files
        .iter()
        .filter(|p| **p != writer)
        .flat_map(|p| {
            let text = std::fs::read_to_string(p).unwrap();
            let name = p.strip_prefix(root).unwrap().display().to_string();
            FILE_WRITES
                .iter()
                .filter(|w| text.contains(*w))
                .map(move |w| format!("{name}: {w}"))
                .collect::<Vec<_>>()
        })
        .collect();
    assert!(
        offending.is_empty(),
        "write files through cli::write_file (temp + rename: whole or untouched), not: {offending:?}"
    );
}
