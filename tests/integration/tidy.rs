//! Tidy checks: every source file opens with a `//!` line saying what it owns; every reference
//! the code and the top-level docs make to `docs/` resolves (a file, an `algorithm.md` section,
//! a `numerics.md` case, a `product.md` section); algorithm.md's Conventions cannot change
//! without this project noticing (a stored hash); only `cli/output.rs` writes files; the top-level
//! modules import one way, without a cycle (that `canvas` and `geom` import nothing from the crate
//! the compiler checks: they are crates of the workspace, `crates/`); no snapshot is too long to
//! review.

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

/// The longest a snapshot may be, in bytes: a reviewer reads a changed snapshot whole, so one
/// language's narration in full (the other is checked step by step against it) and a trace
/// document of one pixel. The longest today, a 2D slab's trace with its total internal
/// reflections, is 44 kB.
const MAX_SNAPSHOT_BYTES: u64 = 48 << 10;

#[test]
fn no_snapshot_is_too_long_to_review() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/integration/snapshots");
    let mut long = Vec::new();
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let bytes = std::fs::metadata(&path).unwrap().len();
        if bytes > MAX_SNAPSHOT_BYTES {
            long.push(format!("{}: {bytes} bytes", path.file_name().unwrap().to_string_lossy()));
        }
    }
    assert!(long.is_empty(), "snapshots over {MAX_SNAPSHOT_BYTES} bytes: {long:?}");
}

#[test]
fn every_source_file_opens_with_a_module_doc() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    for dir in ["src", "crates", "tests/integration", "benches"] {
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
    let text = read_doc(root, "algorithm.md");
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
    rust_files(&root.join("crates"), &mut files);
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

/// The text of `docs/NAME`; a missing reference document fails the test that needs it.
fn read_doc(root: &Path, name: &str) -> String {
    let path = root.join("docs").join(name);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The files whose references are checked: the sources, the tests and their fixtures, and the two
/// top-level documents. Snapshots are left out (they hold output, not references), and so are the
/// browser tests' npm packages (`node_modules`, which `tests/setup.sh` may be installing while
/// this test runs).
fn citing_files(root: &Path) -> Vec<PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                if path.file_name().is_some_and(|n| n == "node_modules") {
                    continue;
                }
                walk(&path, out);
            } else if path.extension().is_some_and(|e| e == "rs" || e == "json") {
                out.push(path);
            }
        }
    }
    let mut files = vec![root.join("README.md"), root.join("ARCHITECTURE.md")];
    walk(&root.join("src"), &mut files);
    walk(&root.join("crates"), &mut files);
    walk(&root.join("tests"), &mut files);
    files
}

/// A file's text with its lines joined by spaces and comment markers removed, so that a
/// reference wrapped across two comment lines reads as one.
fn flowing(text: &str) -> String {
    text.lines()
        .map(|line| {
            let line = line.trim_start();
            let line = ["//!", "///", "//"].iter().find_map(|m| line.strip_prefix(m)).unwrap_or(line);
            line.trim()
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// What the reference documents define: `algorithm.md`'s section numbers (`8`, `8.2`),
/// `numerics.md`'s section letters (`I`) and case labels (`I3`), `product.md`'s headings.
struct Defined {
    algorithm: String,
    sections: Vec<String>,
    letters: Vec<String>,
    cases: Vec<String>,
    product: String,
    headings: Vec<String>,
}

impl Defined {
    fn read(root: &Path) -> Self {
        let algorithm = read_doc(root, "algorithm.md");
        let numerics = read_doc(root, "numerics.md");
        let product = read_doc(root, "product.md");
        // `## 8. Title` and `### 8.2 Title` define `8` and `8.2`.
        let sections = algorithm
            .lines()
            .filter_map(|l| l.strip_prefix("## ").or_else(|| l.strip_prefix("### ")))
            .filter_map(|l| l.split_whitespace().next())
            .map(|n| n.trim_end_matches('.').to_string())
            .filter(|n| n.starts_with(|c: char| c.is_ascii_digit()))
            .collect();
        // `## I. Title` defines the letter; `**I3 Title.**` defines the case.
        let letters = numerics
            .lines()
            .filter_map(|l| l.strip_prefix("## "))
            .filter_map(|l| l.split_once(". ").map(|(x, _)| x.to_string()))
            .filter(|x| x.len() == 1)
            .collect();
        let cases = numerics
            .lines()
            .filter_map(|l| l.strip_prefix("**"))
            .filter_map(|l| l.split_whitespace().next())
            .filter(|l| label(l).is_some_and(|n| n == l.len()))
            .map(str::to_string)
            .collect();
        let headings = product
            .lines()
            .filter_map(|l| l.strip_prefix("## ").or_else(|| l.strip_prefix("### ")))
            .map(|h| h.trim().to_lowercase())
            .collect();
        Self { algorithm: algorithm.to_lowercase(), sections, letters, cases, product, headings }
    }
}

/// The length of a case label at the start of `s` (`I3`, `A9`; a capital A–M and 1–2 digits),
/// if there is one.
fn label(s: &str) -> Option<usize> {
    let b = s.as_bytes();
    let digits = b.iter().skip(1).take_while(|c| c.is_ascii_digit()).count();
    (b.first().is_some_and(|c| (b'A'..=b'M').contains(c)) && (1..=2).contains(&digits)).then_some(1 + digits)
}

/// The double-quoted titles at the start of `rest` (` "A", "B" and "C"`).
fn quoted_titles(rest: &str) -> Vec<&str> {
    let mut out = Vec::new();
    // A reference is prose: a space or a comma comes first (`"product.md"` in code is no title).
    if !rest.starts_with([' ', ',']) {
        return out;
    }
    let mut rest = rest.trim_start_matches([',', ' ']);
    while let Some(inner) = rest.strip_prefix('"') {
        let Some((title, after)) = inner.split_once('"') else { break };
        out.push(title);
        rest = after.trim_start_matches([',', ' ']);
        rest = rest.strip_prefix("and ").unwrap_or(rest);
    }
    out
}

/// A numerics.md section letter, A to M.
fn is_letter(s: &str) -> bool {
    s.len() == 1 && s.starts_with(|c: char| ('A'..='M').contains(&c))
}

/// `§8.2` (an algorithm.md section, with the titles quoted after it) and `§I` (a numerics.md
/// section) that the documents do not define.
fn broken_sections(text: &str, d: &Defined) -> Vec<String> {
    let mut broken = Vec::new();
    for (at, _) in text.match_indices('§') {
        let rest = &text[at + '§'.len_utf8()..];
        let token: String = rest.chars().take_while(|c| c.is_ascii_alphanumeric() || *c == '.').collect();
        let token = token.trim_end_matches('.');
        if token.starts_with(|c: char| c.is_ascii_digit()) {
            if !d.sections.iter().any(|s| s == token) {
                broken.push(format!("algorithm.md §{token}"));
            }
            for title in quoted_titles(&rest[token.len()..]) {
                if !d.algorithm.contains(&title.to_lowercase()) {
                    broken.push(format!("algorithm.md §{token} \"{title}\""));
                }
            }
        } else if is_letter(token) && !d.letters.iter().any(|s| s == token) {
            broken.push(format!("numerics.md §{token}"));
        }
    }
    broken
}

/// `numerics.md B5, E1, M1`, `numerics I3` or `numerics.md E, F, L`: the labels and letters up to
/// the end of the clause that the documents do not define.
fn broken_cases(text: &str, d: &Defined) -> Vec<String> {
    let mut broken = Vec::new();
    for (at, word) in text.match_indices("numerics") {
        let rest = text[at + word.len()..].trim_start_matches(".md");
        let end = rest.find([')', ';', ':']).unwrap_or(rest.len()).min(rest.find(". ").unwrap_or(rest.len()));
        for raw in rest[..end].split([' ', ',', '/']) {
            let letter = is_letter(raw) && !d.letters.iter().any(|s| s == raw);
            let case = label(raw) == Some(raw.len()) && !d.cases.iter().any(|c| c == raw);
            if letter || case {
                broken.push(format!("numerics.md {raw}"));
            }
        }
    }
    broken
}

/// Tests named after cases (`fn i3_ties…`, `fn c1_c2_…`, `fn a9a_…` for A9 (a)) whose case the
/// documents do not define.
fn broken_test_names(text: &str, d: &Defined) -> Vec<String> {
    let mut broken = Vec::new();
    for (at, _) in text.match_indices("fn ") {
        let mut rest = &text[at + 3..];
        while let Some((head, tail)) = rest.split_once('_') {
            if head.chars().any(|c| !(c.is_ascii_lowercase() || c.is_ascii_digit())) {
                break;
            }
            let upper = head.to_uppercase();
            let Some(n) = label(&upper).filter(|n| head.len() - n <= 1) else { break };
            let id = &upper[..n];
            if !d.cases.iter().any(|c| c == id) {
                broken.push(format!("numerics.md {id} (a test named `{head}_…`)"));
            }
            rest = tail;
        }
    }
    broken
}

/// `product.md "The trace document"` (a heading) or product.md `--aa` (a word of its text) that
/// the document does not hold.
fn broken_product(text: &str, d: &Defined) -> Vec<String> {
    let mut broken = Vec::new();
    for (at, word) in text.match_indices("product.md") {
        let rest = text[at + word.len()..].trim_start_matches("'s");
        for title in quoted_titles(rest) {
            if !d.headings.iter().any(|h| h.trim_matches('`') == title.to_lowercase()) {
                broken.push(format!("product.md \"{title}\""));
            }
        }
        if let Some((code, _)) = rest.strip_prefix(" `").and_then(|r| r.split_once('`')) {
            if !d.product.contains(&format!("`{code}`")) {
                broken.push(format!("product.md: no `{code}` in it"));
            }
        }
    }
    broken
}

/// Every Markdown file a text names, as written: bare (a document of `docs/`, or a top-level one
/// in capitals) or with its folder.
fn named_documents(text: &str) -> Vec<&str> {
    let is_name = |c: char| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '/' | '.');
    text.match_indices(".md")
        .filter(|(at, _)| !text[at + 3..].starts_with(|c: char| c.is_ascii_alphanumeric()))
        .map(|(at, _)| {
            let start = text[..at].rfind(|c: char| !is_name(c)).map_or(0, |i| i + 1);
            &text[start..at + 3]
        })
        .filter(|name| name.len() > 3)
        .collect()
}

#[test]
fn every_cited_document_and_section_exists_in_docs() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let defined = Defined::read(root);
    let outside = ["..", "shared"].join("/");
    let mut problems = Vec::new();
    for file in citing_files(root) {
        let raw = std::fs::read_to_string(&file).unwrap();
        let text = flowing(&raw);
        let name = file.strip_prefix(root).unwrap().display().to_string();
        if text.contains(&outside) {
            problems.push(format!("{name}: cites {outside}, outside the repository"));
        }
        for doc in named_documents(&text) {
            let path = if doc.contains('/') || doc.starts_with(|c: char| c.is_ascii_uppercase()) {
                root.join(doc.trim_start_matches("./"))
            } else {
                root.join("docs").join(doc)
            };
            if !path.exists() {
                problems.push(format!("{name}: {doc} does not exist"));
            }
        }
        let broken = [broken_sections, broken_cases, broken_test_names, broken_product]
            .iter()
            .flat_map(|check| check(&text, &defined));
        problems.extend(broken.map(|r| format!("{name}: {r}")));
    }
    assert!(problems.is_empty(), "references that docs/ does not define:\n{}", problems.join("\n"));
}

/// The ```json blocks of a document, in order.
fn json_blocks(doc: &str) -> Vec<&str> {
    doc.split("```json\n").skip(1).filter_map(|b| b.split_once("```").map(|(json, _)| json)).collect()
}

#[test]
fn product_md_examples_are_accepted_as_written() {
    let product = read_doc(Path::new(env!("CARGO_MANIFEST_DIR")), "product.md");
    let blocks = json_blocks(&product);
    assert_eq!(blocks.len(), 2, "product.md shows a scene and a lesson");
    // The scene's mesh names an OBJ file; any one-triangle file stands in for it.
    let obj = |_: &str| Ok("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n".to_string());
    let scene = whitted::scene::load::load_str_with(blocks[0], &obj);
    assert!(scene.is_ok(), "the example scene: {:?}", scene.err());
    let lesson = whitted::lesson::parse(blocks[1]);
    assert!(lesson.is_ok(), "the example lesson: {:?}", lesson.err());
}

/// The top-level module of `src/` a file belongs to (`src/accel/bvh.rs` → `accel`,
/// `src/render.rs` → `render`), with the depth of the file's module below the crate root
/// (`accel::bvh` → 2); `None` for the crate roots `lib.rs` and `main.rs`.
fn top_module(rel: &Path) -> Option<(String, usize)> {
    let parts: Vec<String> = rel.iter().map(|p| p.to_string_lossy().into_owned()).collect();
    let [first, rest @ ..] = parts.as_slice() else { return None };
    if rest.is_empty() {
        let name = first.strip_suffix(".rs")?;
        return (name != "lib" && name != "main").then(|| (name.to_owned(), 1));
    }
    let depth = if parts.last().is_some_and(|f| f == "mod.rs") { parts.len() - 1 } else { parts.len() };
    Some((first.clone(), depth))
}

/// A file's code with its comments blanked (line comments and doc comments; a `//` inside a
/// string cuts the rest of that line, which can only hide a path, never invent one).
fn code_only(text: &str) -> String {
    text.lines().map(|line| line.find("//").map_or(line, |at| &line[..at])).collect::<Vec<_>>().join("\n")
}

/// A file's text up to its unit tests (`#[cfg(test)]`, then attributes or comments, then
/// `mod tests`): a module's tests may build their fixtures from any part, only its code counts.
fn without_unit_tests(text: &str) -> &str {
    let starts_tests = |at: usize| {
        let mut lines = text[at..].lines().skip(1).map(str::trim_start);
        lines
            .find(|l| !(l.starts_with("//") || l.starts_with("#[")))
            .is_some_and(|l| l.starts_with("mod tests"))
    };
    text.match_indices("#[cfg(test)]")
        .map(|(at, _)| at)
        .find(|&at| starts_tests(at))
        .map_or(text, |at| &text[..at])
}

/// The leading identifier of `s` (letters, digits, `_`), possibly empty.
fn ident(s: &str) -> &str {
    let end = s.find(|c: char| !(c.is_alphanumeric() || c == '_')).unwrap_or(s.len());
    &s[..end]
}

/// Every top-level module `code` names through the crate root, with the byte offset where it
/// is named: `crate::X…`, each `X` of a group `crate::{X, Y::z}`, and `super::…::X` when the
/// `super`s climb from a module `depth` deep up to the root.
fn crate_paths(code: &str, depth: usize) -> Vec<(String, usize)> {
    let mut found = Vec::new();
    for (at, _) in code.match_indices("crate::") {
        // `$crate::` in a macro and `whitted_crate::`-like names are not the crate root.
        if code[..at].ends_with(|c: char| c.is_alphanumeric() || c == '_' || c == '$') {
            continue;
        }
        let rest = &code[at + "crate::".len()..];
        if let Some(group) = rest.strip_prefix('{') {
            // The top-level entries of the group: split on commas outside nested braces.
            let (mut level, mut start) = (0usize, 0usize);
            for (i, c) in group.char_indices() {
                match c {
                    '{' => level += 1,
                    '}' if level == 0 => {
                        found.push((ident(group[start..].trim_start()).to_owned(), at));
                        break;
                    }
                    '}' => level -= 1,
                    ',' if level == 0 => {
                        found.push((ident(group[start..].trim_start()).to_owned(), at));
                        start = i + 1;
                    }
                    _ => {}
                }
            }
        } else {
            found.push((ident(rest).to_owned(), at));
        }
    }
    for (at, _) in code.match_indices("super::") {
        if code[..at].ends_with("super::") {
            continue;
        }
        let mut rest = &code[at..];
        let mut climbs = 0;
        while let Some(r) = rest.strip_prefix("super::") {
            rest = r;
            climbs += 1;
        }
        if climbs >= depth {
            found.push((ident(rest).to_owned(), at));
        }
    }
    found.retain(|(name, _)| !name.is_empty());
    found
}

/// The import graph between the top-level modules of `src/`: for each module, the modules it
/// names and where it first names each (`src/accel/mod.rs:30`).
fn module_graph(
    root: &Path,
) -> std::collections::BTreeMap<String, std::collections::BTreeMap<String, String>> {
    crate_graph(root, "src")
}

/// The import graph between the top-level modules of the crate whose root folder is `src`
/// (relative to `root`: `src`, `crates/canvas/src`).
fn crate_graph(
    root: &Path,
    src: &str,
) -> std::collections::BTreeMap<String, std::collections::BTreeMap<String, String>> {
    let shown = src;
    let src = root.join(src);
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    files.sort();
    let tops: std::collections::BTreeSet<String> =
        files.iter().filter_map(|p| top_module(p.strip_prefix(&src).unwrap())).map(|(m, _)| m).collect();
    let mut graph: std::collections::BTreeMap<String, std::collections::BTreeMap<String, String>> =
        tops.iter().map(|m| (m.clone(), std::collections::BTreeMap::new())).collect();
    for path in &files {
        let rel = path.strip_prefix(&src).unwrap();
        let Some((from, depth)) = top_module(rel) else { continue };
        let text = std::fs::read_to_string(path).unwrap();
        let code = code_only(without_unit_tests(&text));
        for (to, at) in crate_paths(&code, depth) {
            if to != from && tops.contains(&to) {
                let line = code[..at].lines().count().max(1);
                let place = format!("{shown}/{}:{line}", rel.display());
                graph.get_mut(&from).unwrap().entry(to).or_insert(place);
            }
        }
    }
    graph
}

/// The import cycles of `graph`, each as `a → b → a` with where each step is imported: one
/// shortest cycle through every module that lies on one.
fn import_cycles(
    graph: &std::collections::BTreeMap<String, std::collections::BTreeMap<String, String>>,
) -> Vec<String> {
    let mut cycles: Vec<Vec<String>> = Vec::new();
    for start in graph.keys() {
        // Breadth first from `start`, back to `start`: the shortest cycle through it.
        let mut came_from: std::collections::BTreeMap<&str, &str> = std::collections::BTreeMap::new();
        let mut queue = std::collections::VecDeque::from([start.as_str()]);
        let mut closing = None;
        while let Some(m) = queue.pop_front() {
            if let Some(next) = graph[m].keys().find(|n| *n == start) {
                closing = Some((m, next.as_str()));
                break;
            }
            for n in graph[m].keys() {
                if n != start && !came_from.contains_key(n.as_str()) {
                    came_from.insert(n, m);
                    queue.push_back(n);
                }
            }
        }
        let Some((last, _)) = closing else { continue };
        let mut path = vec![last.to_owned()];
        while let Some(prev) = came_from.get(path.last().unwrap().as_str()) {
            path.push((*prev).to_owned());
        }
        path.reverse();
        // The same cycle seen from another of its modules is reported once.
        let mut key = path.clone();
        key.sort();
        if !cycles.iter().any(|c| {
            let mut k = c.clone();
            k.sort();
            k == key
        }) {
            cycles.push(path);
        }
    }
    cycles
        .into_iter()
        .map(|path| {
            let steps: Vec<String> = path
                .iter()
                .zip(path.iter().cycle().skip(1))
                .map(|(a, b)| format!("{a} → {b} ({})", graph[a][b]))
                .collect();
            steps.join(", ")
        })
        .collect()
}

#[test]
fn no_import_cycle_between_the_top_level_modules() {
    let graph = module_graph(Path::new(env!("CARGO_MANIFEST_DIR")));
    assert!(graph.len() > 10 && graph["figure"].contains_key("scene"), "the graph was not read: {graph:?}");
    let cycles = import_cycles(&graph);
    assert!(cycles.is_empty(), "import cycles between top-level modules of src/: {cycles:#?}");
}

/// Inside the drawing engine too: `Drawing`'s parts (label placement, legend, page) add methods
/// to it from their own files, and the types it stores live beside the items, so no two parts
/// import each other.
#[test]
fn no_import_cycle_between_the_canvas_modules() {
    let graph = crate_graph(Path::new(env!("CARGO_MANIFEST_DIR")), "crates/canvas/src");
    assert!(graph.len() > 8 && graph["label"].contains_key("drawing"), "the graph was not read: {graph:?}");
    let cycles = import_cycles(&graph);
    assert!(cycles.is_empty(), "import cycles between the modules of crates/canvas/src: {cycles:#?}");
}

#[test]
fn the_import_reader_finds_paths_groups_and_climbs() {
    let code = "use crate::geom::Vector;\nuse crate::{scene::Scene, shape};\nlet s = crate::trace::x();\n\
                use super::super::render;\n$crate::image";
    let names: Vec<String> = crate_paths(code, 2).into_iter().map(|(n, _)| n).collect();
    assert_eq!(names, ["geom", "scene", "shape", "trace", "render"]);
    // One `super` from a module two deep stays inside its top-level module.
    assert!(crate_paths("use super::render;", 2).is_empty());
    assert_eq!(top_module(Path::new("accel/bvh.rs")), Some(("accel".to_owned(), 2)));
    assert_eq!(top_module(Path::new("figure/kinds/mod.rs")), Some(("figure".to_owned(), 2)));
    assert_eq!(top_module(Path::new("render.rs")), Some(("render".to_owned(), 1)));
    assert_eq!(top_module(Path::new("lib.rs")), None);
    let file = "use super::a;\n#[cfg(test)]\nfn helper() {}\n#[cfg(test)]\n// why\n#[allow(x)]\nmod tests {\n    use super::b;\n}";
    assert_eq!(without_unit_tests(file), "use super::a;\n#[cfg(test)]\nfn helper() {}\n");
}
