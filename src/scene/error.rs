//! Scene errors: `SceneError { path, problem }`, printed as `objects[2].radius: must be > 0,
//! got -1`; loading collects all of them (a JSON syntax error stops at the first).

use std::fmt;

/// One problem in a scene, with the JSON path of the field it concerns.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SceneError {
    /// The JSON path, e.g. `objects[2].radius` (empty for the whole document).
    pub path: String,
    /// What is wrong, e.g. `must be > 0, got -1`.
    pub problem: String,
}

impl SceneError {
    /// An error at `path`.
    pub fn new(path: impl Into<String>, problem: impl Into<String>) -> Self {
        Self { path: path.into(), problem: problem.into() }
    }
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.path.is_empty() {
            write!(f, "{}", self.problem)
        } else {
            write!(f, "{}: {}", self.path, self.problem)
        }
    }
}

impl std::error::Error for SceneError {}

/// The closest of `known` to `word` by edit distance, if it is close enough to be a typo: at most
/// 2 edits (a third of a long name), and fewer than the name has letters, so that no name is
/// offered for a word it shares nothing with (`b` is not a typo of `l`).
#[must_use]
pub fn suggest<'a>(word: &str, known: &[&'a str]) -> Option<&'a str> {
    known
        .iter()
        .map(|k| (edit_distance(word, k), *k))
        .filter(|(d, k)| {
            let letters = k.chars().count();
            *d <= 2.max(letters / 3) && *d < letters
        })
        .min_by_key(|(d, _)| *d)
        .map(|(_, k)| k)
}

/// Levenshtein distance over chars.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut prev = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let cur = row[j + 1];
            row[j + 1] = (prev + usize::from(ca != *cb)).min(row[j] + 1).min(cur + 1);
            prev = cur;
        }
    }
    row[b.len()]
}

#[cfg(test)]
// These tests pin exact IEEE results on purpose (numerics.md gives bit-exact expectations).
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;

    #[test]
    fn suggests_the_nearest_field() {
        assert_eq!(suggest("radus", &["center", "radius", "material"]), Some("radius"));
        assert_eq!(suggest("zzzzzz", &["center", "radius"]), None);
        // A 3D window's `b` given to a 2D scene's window (l, r): no one-letter name to offer.
        assert_eq!(suggest("b", &["l", "r"]), None);
        assert_eq!(suggest("ambeint", &["ambient", "background"]), Some("ambient"));
    }
}
