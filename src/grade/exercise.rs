//! Exercise mode (docs/grading.md "In the page"): the one quantity a narration step computes, so
//! that the page can hide the step's numbers and ask the student for it, and a typed answer
//! checked component by component with the grader's own rule (`walk`'s agreement):
//!
//! ```text
//! agree  ⇔  ‖f − e‖∞ ≤ tol·max(1, ‖e‖∞)
//! ```
//!
//! so a component is right when `|fᵢ − eᵢ| ≤ tol·max(1, ‖e‖∞)`, and it is off by the relative
//! error `|fᵢ − eᵢ| / max(1, ‖e‖∞)` (absolute below 1, as the grader's tolerance).
//!
//! What a step computes is read from the events it explains, as `walk::step_of` places a
//! quantity: the first step that tells a hit computes the hit point, a later one the node's
//! colour; a node's local-model step lists its shadow rays and each light's step its own (the
//! factor s); a spawn step gives the new ray's direction; an intersection test its accepted t.

use super::Quantity;
use crate::format::narration_number;
use crate::geom::Vector;
use crate::record::event::Event;
use crate::record::names::Names;
use crate::record::EventLog;

/// What a step asks for: the quantity, its name as the narration writes it (`R₁`, `I₂`, `t`,
/// `s`, `I_local`, `I`, `(u, v)`), and the value it computes.
#[derive(Clone, Debug, PartialEq)]
pub struct Asked {
    /// The kind of value (`direction`, `t`, `point`, `shadow`, `local`, `colour`, `window_point`).
    pub quantity: Quantity,
    /// The name the narration gives it.
    pub name: String,
    /// The step's value: a vector's or a colour's components, or one number.
    pub expected: Vec<f64>,
}

/// One component of a typed answer against the step's value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Component {
    /// The step's value.
    pub expected: f64,
    /// The student's.
    pub found: f64,
    /// `|f − e| ≤ tol·max(1, ‖e‖∞)`.
    pub right: bool,
    /// `|f − e| / max(1, ‖e‖∞)`: how far off, on the tolerance's scale.
    pub off: f64,
}

/// A typed answer checked: per component, and whether all agree.
#[derive(Clone, Debug, PartialEq)]
pub struct Checked {
    /// Per component, in order.
    pub components: Vec<Component>,
    /// Every component right.
    pub ok: bool,
}

/// The quantity step `step` (from 1) of a narration computes, given the log it narrates and each
/// step's events (`Narration::events`); None for a step that computes nothing a student types
/// (a ray's test that finds no root, a structure's node, a light behind the surface, the depth
/// limit).
///
/// A step may tell several events (a light's step its shadow ray's tests, a colour step the
/// children's spawns, the pixel's colour its primary ray): the one that gives the step its title
/// wins, in this order — a hit's or a shadow ray's quantity, then a spawned ray's direction, then
/// the primary ray, then a test's t.
#[must_use]
pub fn asked<V: Vector>(log: &EventLog<V>, steps: &[Vec<usize>], step: usize) -> Option<Asked> {
    let events = steps.get(step.checked_sub(1)?)?;
    let names = Names::of(log);
    let told = |e: usize| -> Vec<usize> { (1..=steps.len()).filter(|k| steps[k - 1].contains(&e)).collect() };
    events
        .iter()
        .filter_map(|&e| role(log, &names, e, &told(e), step, steps.len()))
        .min_by_key(|(rank, _)| *rank)
        .map(|(_, asked)| asked)
}

/// What event `e`, told by the steps `told`, asks at step `step` (of `last` steps), and its
/// rank (lower wins).
fn role<V: Vector>(
    log: &EventLog<V>,
    names: &Names,
    e: usize,
    told: &[usize],
    step: usize,
    last: usize,
) -> Option<(u8, Asked)> {
    let logged = log.events.get(e)?;
    let at = told.iter().position(|&k| k == step)?;
    let ask = |quantity, name: String, expected: Vec<f64>| Asked { quantity, name, expected };
    match &logged.event {
        // A hit is told by its step (I), the local model's (I_local), a step per light whose
        // N·L ≤ 0 (nothing to compute), and the node's colour last (P's: then the pixel's).
        Event::Hit { point, .. } => {
            let node = logged.ray?;
            let root = log.nodes.get(node)?.parent.is_none();
            let colour_at = if root && told.len() >= 4 { told.len() - 2 } else { told.len() - 1 };
            match at {
                0 => Some((0, ask(Quantity::Point, names.hit_text(node)?, point.to_vec()))),
                1 => local(log, node).map(|a| (0, a)),
                _ if at >= colour_at => colour(log, node, step == last).map(|a| (0, a)),
                _ => None,
            }
        }
        Event::Miss { .. } => colour(log, logged.ray?, step == last).map(|a| (0, a)),
        // The local model's step lists every shadow ray of the hit; each light's step its own.
        Event::ShadowRay { s, light, .. } => {
            let node = logged.ray?;
            if at == 0 && told.len() > 1 {
                local(log, node).map(|a| (0, a))
            } else {
                Some((0, ask(Quantity::Shadow, format!("s ({})", names.shadow_text(node, *light)), vec![*s])))
            }
        }
        Event::Reflect { direction, .. } | Event::Refract { direction, .. } => {
            let child = spawned(log, logged.ray?, e);
            let name = child.map_or_else(|| "D".into(), |c| names.ray_text(c));
            Some((1, ask(Quantity::Direction, name, direction.to_vec())))
        }
        Event::PrimaryRay { direction, uv, .. } => {
            if !uv.is_empty() && at == 0 {
                let name = if uv.len() == 1 { "u" } else { "(u, v)" };
                Some((2, ask(Quantity::WindowPoint, name.into(), uv.clone())))
            } else {
                Some((2, ask(Quantity::Direction, "D".into(), direction.to_vec())))
            }
        }
        Event::ObjectTest { accepted: Some(t), .. } => Some((3, ask(Quantity::T, "t".into(), vec![*t]))),
        _ => None,
    }
}

/// The node's `I_local`.
fn local<V>(log: &EventLog<V>, node: usize) -> Option<Asked> {
    let local = log.nodes.get(node)?.end.as_ref()?.local?;
    Some(Asked { quantity: Quantity::Local, name: "I_local".into(), expected: local.0.to_vec() })
}

/// The node's colour (the pixel's, on the narration's last step).
fn colour<V>(log: &EventLog<V>, node: usize, pixel: bool) -> Option<Asked> {
    let end = log.nodes.get(node)?.end.as_ref()?;
    let name = if pixel { "I (pixel)" } else { "I" };
    Some(Asked { quantity: Quantity::Colour, name: name.into(), expected: end.color.0.to_vec() })
}

/// The child of `node` that spawn event `e` made (children and spawns come in the same order).
fn spawned<V>(log: &EventLog<V>, node: usize, e: usize) -> Option<usize> {
    log.nodes.get(node)?.children.iter().copied().find(|&c| log.spawned_by(c) == Some(e))
}

/// Checks `found` against `expected` with tolerance `tol`, component by component.
///
/// # Errors
/// The two have different lengths (the words say how many numbers the step asks for).
pub fn check(expected: &[f64], found: &[f64], tol: f64) -> Result<Checked, String> {
    if expected.len() != found.len() {
        return Err(format!("expected {} number(s), got {}", expected.len(), found.len()));
    }
    let scale = expected.iter().fold(1.0_f64, |m, x| m.max(x.abs()));
    let components: Vec<Component> = expected
        .iter()
        .zip(found)
        .map(|(&e, &f)| {
            let off = (f - e).abs() / scale;
            Component { expected: e, found: f, right: off <= tol, off }
        })
        .collect();
    let ok = components.iter().all(|c| c.right);
    Ok(Checked { components, ok })
}

/// The numbers a student typed: `(0.8, −0.5, 0.3)`, `0.8 -0.5 0.3`, `[0.8, 0.5]` or one
/// number; the narration's minus sign `−` and `e−5` exponents read as `-`.
///
/// # Errors
/// A piece that is not a finite number (named), or nothing typed.
pub fn parse(text: &str) -> Result<Vec<f64>, String> {
    let plain = text.replace('\u{2212}', "-");
    let pieces: Vec<&str> = plain
        .split(|c: char| c.is_whitespace() || matches!(c, ',' | ';' | '(' | ')' | '[' | ']'))
        .filter(|p| !p.is_empty())
        .collect();
    if pieces.is_empty() {
        return Err("no number typed".into());
    }
    pieces
        .iter()
        .map(|p| {
            p.parse::<f64>().ok().filter(|x| x.is_finite()).ok_or_else(|| format!("`{p}` is not a number"))
        })
        .collect()
}

/// A value as the narration writes it: `(0.8, 0.5)` for several components, `0.8` for one.
#[must_use]
pub fn shown(values: &[f64]) -> String {
    let parts: Vec<String> = values.iter().map(|x| narration_number(*x)).collect();
    if parts.len() == 1 {
        parts[0].clone()
    } else {
        format!("({})", parts.join(", "))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn typed_numbers_are_read_with_the_narrations_minus_sign() {
        assert_eq!(parse("(0.801716, −0.511449, 3e−2)").unwrap(), vec![0.801716, -0.511449, 0.03]);
        assert_eq!(parse(" 5.1 ").unwrap(), vec![5.1]);
        assert_eq!(parse("[1; 2]").unwrap(), vec![1.0, 2.0]);
        assert!(parse("(1, x)").unwrap_err().contains("`x`"));
        assert!(parse("  ").is_err());
        assert!(parse("inf").is_err());
    }

    #[test]
    fn a_component_is_right_within_the_graders_tolerance_and_off_by_its_relative_error() {
        // ‖e‖∞ = 4: the scale is 4, so 1e-4 allows 4e-4 on every component.
        let c = check(&[4.0, 0.5, -1.0], &[4.0003, 0.6, -1.0], 1e-4).unwrap();
        assert!(!c.ok);
        assert!(c.components[0].right);
        assert!((c.components[0].off - 0.0003 / 4.0).abs() < 1e-12);
        assert!(!c.components[1].right);
        assert!((c.components[1].off - 0.1 / 4.0).abs() < 1e-12);
        assert!(c.components[2].right);
        // Below 1 the tolerance is absolute.
        assert!(check(&[0.01], &[0.01005], 1e-4).unwrap().ok);
        assert!(!check(&[0.01], &[0.0102], 1e-4).unwrap().ok);
        assert!(check(&[1.0, 2.0], &[1.0], 1e-4).unwrap_err().contains("2 number"));
    }
}
