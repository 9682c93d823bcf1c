//! The lecture's names of a trace's rays and hit points, one set for the figures and the
//! narration: the hits numbered I₁, I₂ … in the order the tracer reached them (pre-order), the
//! primary ray P, the R and T spawned at I_k named R_k and T_k, and the shadow ray from I_k toward
//! light j named L_k (one light) or L_{k,j} (several; j counts from 1, as the figures do).
//!
//! Each name comes in two spellings: markup for the figures' text (`R_1`, `L_{12}`, see
//! `figure::labels`) and plain text with Unicode subscripts for the narration (`R₁`, `L₁₂`).
//!
//! They live here, beside the log, so that `doc` need not import `figure`.

use super::event::RayKind;
use super::EventLog;

/// The names of every node of one log.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Names {
    /// Per node, the number k of its hit I_k.
    pub hit: Vec<Option<usize>>,
    /// Per node, its name as markup.
    pub ray: Vec<String>,
    /// Per node, its letter and number (the primary ray: `P`, no number).
    spelled: Vec<(&'static str, Option<usize>)>,
    /// Per node, its parent.
    parent: Vec<Option<usize>>,
    /// How many lights the scene has (read from the lights each hit records): with more than
    /// one, a shadow ray's name says which.
    lights: usize,
}

impl Names {
    /// The names of every node of `log`.
    #[must_use]
    pub fn of<V>(log: &EventLog<V>) -> Self {
        // Every hit records one term per light of the scene, lit or not.
        let lights = log.nodes.iter().map(|n| n.lights.len()).max().unwrap_or(0);
        let mut hit = Vec::with_capacity(log.nodes.len());
        let mut next = 0;
        for node in &log.nodes {
            if node.end.as_ref().is_some_and(|e| e.hit.is_some()) {
                next += 1;
                hit.push(Some(next));
            } else {
                hit.push(None);
            }
        }
        let spelled: Vec<(&'static str, Option<usize>)> = log
            .nodes
            .iter()
            .map(|node| match (node.parent, node.start.kind) {
                (None, _) | (_, RayKind::Primary) => ("P", None),
                (Some(p), kind) => {
                    let letter = if kind == RayKind::Reflected { "R" } else { "T" };
                    (letter, Some(hit[p].unwrap_or(0)))
                }
            })
            .collect();
        let ray = spelled
            .iter()
            .map(|&(letter, k)| k.map_or_else(|| letter.to_owned(), |k| sub(letter, k)))
            .collect();
        let parent = log.nodes.iter().map(|n| n.parent).collect();
        Self { hit, ray, spelled, parent, lights }
    }

    /// `I_k` of a node with a hit, as markup.
    #[must_use]
    pub fn hit_name(&self, node: usize) -> Option<String> {
        self.hit[node].map(|k| sub("I", k))
    }

    /// `I₂` of a node with a hit, as text.
    #[must_use]
    pub fn hit_text(&self, node: usize) -> Option<String> {
        self.hit[node].map(|k| subscript("I", &[k]))
    }

    /// `P`, `R₁`, `T₂` of a node, as text.
    #[must_use]
    pub fn ray_text(&self, node: usize) -> String {
        let (letter, k) = self.spelled[node];
        k.map_or_else(|| letter.to_owned(), |k| subscript(letter, &[k]))
    }

    /// The shadow ray from node `node`'s hit toward light `light` (0-based), as markup: `L_k`,
    /// or `L_{k,j}` with j = light + 1 when the scene has several lights.
    #[must_use]
    pub fn shadow_name(&self, node: usize, light: usize) -> String {
        let k = self.hit[node].unwrap_or(0);
        if self.lights > 1 {
            format!("L_{{{k},{}}}", light + 1)
        } else {
            sub("L", k)
        }
    }

    /// [`Names::shadow_name`] as text: `L₂`, or `L₂,₁` with several lights.
    #[must_use]
    pub fn shadow_text(&self, node: usize, light: usize) -> String {
        let k = self.hit[node].unwrap_or(0);
        if self.lights > 1 {
            subscript("L", &[k, light + 1])
        } else {
            subscript("L", &[k])
        }
    }

    /// The rays from the primary ray down to `node`, as text: `P → T₁ → R₂`.
    #[must_use]
    pub fn path_text(&self, node: usize) -> String {
        let mut chain = vec![node];
        while let Some(p) = chain.last().and_then(|&n| self.parent[n]) {
            chain.push(p);
        }
        chain.iter().rev().map(|&n| self.ray_text(n)).collect::<Vec<_>>().join(" → ")
    }
}

/// `X_k` in markup (`X_{12}` for two digits).
#[must_use]
pub fn sub(letter: &str, k: usize) -> String {
    if k < 10 {
        format!("{letter}_{k}")
    } else {
        format!("{letter}_{{{k}}}")
    }
}

/// `X` with the numbers `ks` as Unicode subscripts, joined by commas: `L₁₂,₁`.
#[must_use]
pub fn subscript(letter: &str, ks: &[usize]) -> String {
    const DIGITS: [char; 10] = ['₀', '₁', '₂', '₃', '₄', '₅', '₆', '₇', '₈', '₉'];
    let parts: Vec<String> = ks
        .iter()
        .map(|k| k.to_string().chars().map(|c| c.to_digit(10).map_or(c, |d| DIGITS[d as usize])).collect())
        .collect();
    format!("{letter}{}", parts.join(","))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn subscripts_spell_every_digit() {
        assert_eq!(subscript("R", &[1]), "R₁");
        assert_eq!(subscript("L", &[12, 3]), "L₁₂,₃");
        assert_eq!(subscript("I", &[1_234_567_890]), "I₁₂₃₄₅₆₇₈₉₀");
        assert_eq!(sub("T", 4), "T_4");
        assert_eq!(sub("T", 40), "T_{40}");
    }
}
