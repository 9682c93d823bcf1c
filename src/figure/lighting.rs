//! What a drawn figure's items light besides the events each kind tags them with: a step of the
//! narration that names a test lights the ray tested and the object it was tested against, a step
//! that names a light lights that light. Run once a kind has drawn and laid out its items, so it
//! adds indices to `Item::events` (the SVG's `data-events`) and moves nothing: the PNG and the
//! labels' places are those the kind drew.
//!
//! The rules, for each event `e` of node `n` in the main trace (issue 30 item 3):
//! - an `object_test` (or a `bound_test` of one object's volume) of object `o` in `n`'s search for
//!   its hit → the items that draw ray `n` (they carry the event that spawned it) and the items
//!   tagged `object:o`;
//! - the same after `n`'s hit → the shadow ray it belongs to (the `shadow_ray` event that follows
//!   it, which the tests of that ray come before) and object `o`;
//! - `n`'s `hit` on object `o` → the items that draw ray `n` and object `o` (the steps of the hit,
//!   its local model and its colour name it);
//! - a `shadow_ray` towards light `k` → the light's marker, tagged `light:k` ([`LIGHT_TAG`]);
//! - a `depth_limit` or a `total_internal_reflection` of `n` → the items that draw ray `n`.
//!
//! Nodes, cells and samples are the kinds' own (`with_events`): a step that names one the figure
//! does not draw lights nothing, and the page says so.

use crate::canvas::Drawing;
use crate::record::event::Event;
use crate::record::EventLog;

/// The tag prefix of a light's marker: `light:k` for light k of the scene.
pub const LIGHT_TAG: &str = "light:";
/// The tag prefix of an object's outline: `object:i` for object i of the scene.
pub const OBJECT_TAG: &str = "object:";

/// What one event lights beyond the items that already carry it.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
struct Extra {
    /// The events whose items also draw it (a ray's spawning event, a shadow ray's event).
    via: Vec<usize>,
    /// The tags of the items that also draw it (`object:2`, `light:0`).
    tags: Vec<String>,
}

/// Adds to `d`'s items the events they stand for by the rules above, from `log`, the main trace
/// whose indices the items carry.
pub fn complete<V>(d: &mut Drawing, log: &EventLog<V>) {
    let extras = extras(log);
    if extras.iter().all(|(_, x)| x.via.is_empty() && x.tags.is_empty()) {
        return;
    }
    for item in &mut d.items {
        let mut more: Vec<usize> = Vec::new();
        for (event, extra) in &extras {
            let by_event = extra.via.iter().any(|v| item.events.binary_search(v).is_ok());
            let by_tag = extra.tags.contains(&item.tag);
            if by_event || by_tag {
                more.push(*event);
            }
        }
        if !more.is_empty() {
            item.events.extend(more);
            item.events.sort_unstable();
            item.events.dedup();
        }
    }
}

/// Each event that lights more than the items tagged with it, and what it lights.
fn extras<V>(log: &EventLog<V>) -> Vec<(usize, Extra)> {
    let mut out = Vec::new();
    for node in 0..log.nodes.len() {
        let spawn: Vec<usize> = log.spawned_by(node).into_iter().collect();
        let indexed: Vec<(usize, &Event<V>)> = (log.events.iter().enumerate())
            .filter(|(_, l)| l.ray == Some(node))
            .map(|(k, l)| (k, &l.event))
            .collect();
        let mut searching = true;
        // The tests after the hit wait for the shadow ray they belong to.
        let mut pending: Vec<(usize, usize)> = Vec::new();
        for &(k, e) in &indexed {
            match e {
                Event::Hit { object, .. } => {
                    searching = false;
                    out.push((
                        k,
                        Extra { via: spawn.clone(), tags: vec![format!("{OBJECT_TAG}{}", object.index)] },
                    ));
                }
                Event::Miss { .. } => searching = false,
                Event::ObjectTest { object, .. } | Event::BoundTest { object: Some(object), .. } => {
                    let tag = format!("{OBJECT_TAG}{}", object.index);
                    if searching {
                        out.push((k, Extra { via: spawn.clone(), tags: vec![tag] }));
                    } else {
                        pending.push((k, object.index));
                    }
                }
                Event::ShadowRay { light, .. } => {
                    for (test, object) in pending.drain(..) {
                        out.push((test, Extra { via: vec![k], tags: vec![format!("{OBJECT_TAG}{object}")] }));
                    }
                    out.push((k, Extra { via: Vec::new(), tags: vec![format!("{LIGHT_TAG}{light}")] }));
                }
                Event::DepthLimit { .. } | Event::TotalInternalReflection { .. } => {
                    out.push((k, Extra { via: spawn.clone(), tags: Vec::new() }));
                }
                _ => {}
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::canvas::{Mark, Pen};
    use crate::record::event::{ObjectRef, RayKind};
    use crate::record::{Logged, RayNode, RayStart};
    use glam::DVec2;

    fn at(ray: usize, event: Event<DVec2>) -> Logged<DVec2> {
        Logged { ray: Some(ray), sample: None, event }
    }

    #[test]
    fn a_test_lights_its_ray_and_object_and_a_shadow_ray_its_light() {
        let object = |index| ObjectRef { index, triangle: None };
        let (o, x) = (DVec2::ZERO, DVec2::X);
        let mut log: EventLog<DVec2> = EventLog::new();
        log.nodes.push(RayNode {
            start: RayStart { kind: RayKind::Primary, level: 1, origin: o, direction: x },
            lights: Vec::new(),
            end: None,
            children: Vec::new(),
            parent: None,
            sample: None,
        });
        log.events = vec![
            at(0, Event::PrimaryRay { origin: o, direction: x, uv: vec![0.5] }),
            at(0, Event::ObjectTest { object: object(1), roots: vec![2.0], accepted: Some(2.0) }),
            at(0, Event::Hit { object: object(1), t: 2.0, point: x * 2.0, normal: -x, entering: true }),
            at(0, Event::ObjectTest { object: object(0), roots: vec![], accepted: None }),
            at(
                0,
                Event::ShadowRay {
                    light: 0,
                    origin: x * 2.0,
                    direction: x,
                    distance: 3.0,
                    occluders: vec![],
                    s: 1.0,
                },
            ),
        ];
        let mut d = Drawing::new(10, 10).unwrap();
        d.with_events([0, 2], |d| {
            d.segment("ray:primary", DVec2::ZERO, DVec2::ONE, Pen::NONE);
        });
        d.with_events([4], |d| {
            d.segment("ray:shadow", DVec2::ZERO, DVec2::ONE, Pen::NONE);
        });
        for tag in ["object:0", "object:1", "light:0", "light:1"] {
            d.push(tag, Pen::NONE, Mark::Line { points: vec![DVec2::ZERO, DVec2::ONE] });
        }
        complete(&mut d, &log);
        let events: Vec<(&str, &[usize])> =
            d.items.iter().map(|i| (i.tag.as_str(), i.events.as_slice())).collect();
        assert_eq!(
            events,
            [
                ("ray:primary", &[0, 1, 2][..]),
                ("ray:shadow", &[3, 4][..]),
                ("object:0", &[3][..]),
                ("object:1", &[1, 2][..]),
                ("light:0", &[4][..]),
                ("light:1", &[][..]),
            ]
        );
    }
}
