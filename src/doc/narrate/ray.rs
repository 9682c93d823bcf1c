//! A ray's steps: its title (the figures' name, P, R₁, T₂, and its level), its object and
//! structure tests in the order they were made (a grid cell's header before the cell's tests),
//! its nearest hit I_k with the normal's side, or the background; then the local model, the
//! secondary rays and the colour (`light`, `optics`).

use super::{rgb, vec_str, Indexed, Lang, Writer};
use crate::format::narration_number;
use crate::geom::slab::widen_exit;
use crate::record::event::{Event, RayKind};
use crate::shape::Dim;

/// Puts each grid cell's `voxel_step` before the object tests made in that cell: the grid
/// records a cell after testing its objects (it lists them), while a student reads the cell
/// first. The cell's tests are the object tests just before it, as many as it lists.
fn cells_first<V>(events: &mut [Indexed<'_, V>]) {
    for k in 0..events.len() {
        let Event::VoxelStep { objects, .. } = events[k].1 else { continue };
        let n = objects.len();
        if n > k || !events[k - n..k].iter().all(|(_, e)| matches!(e, Event::ObjectTest { .. })) {
            continue;
        }
        events[k - n..=k].rotate_right(1);
    }
}

/// What an object test's t values are, by the shape's kind: the roots of a quadratic (sphere,
/// circle), where the ray enters and leaves a box's slabs (box, rectangle), the one crossing of a
/// flat shape (plane, line, a 3D triangle, a mesh's triangle, a segment), or where it crosses a 2D
/// outline's edges (a 2D triangle, a polygon).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Crossings {
    Roots,
    EntryExit,
    Single,
    Edges,
}

/// The text of `lang` of a pair.
fn pick(lang: Lang, en: &'static str, ro: &'static str) -> &'static str {
    match lang {
        Lang::En => en,
        Lang::Ro => ro,
    }
}

impl Crossings {
    /// The t values of a shape of this kind (`Shape::kind`) in dimension `dim`.
    fn of(kind: &str, dim: usize) -> Self {
        match (kind, dim) {
            ("sphere" | "circle", _) => Self::Roots,
            ("box" | "rectangle", _) => Self::EntryExit,
            ("polygon", _) | ("triangle", 2) => Self::Edges,
            _ => Self::Single,
        }
    }

    /// The name of `n` of them.
    fn name(self, n: usize, lang: Lang) -> &'static str {
        let (en, ro) = match (self, n) {
            (Self::Roots, 1) => ("root (tangent)", "rădăcina (tangentă)"),
            (Self::Roots, _) => ("roots", "rădăcini"),
            (Self::EntryExit, 1) => ("entry = exit (touching)", "intrare = ieșire (atingere)"),
            (Self::EntryExit, _) => ("entry and exit", "intrare și ieșire"),
            (Self::Single | Self::Edges, 1) => ("crossing", "intersecția"),
            (Self::Single | Self::Edges, _) => ("edge crossings", "intersecții cu laturile"),
        };
        pick(lang, en, ro)
    }

    /// None at all: the ray misses.
    fn none(self, lang: Lang) -> &'static str {
        match self {
            Self::Roots => pick(lang, "no real root: the ray misses", "nicio rădăcină reală: raza ratează"),
            _ => pick(lang, "no crossing: the ray misses", "nicio intersecție: raza ratează"),
        }
    }

    /// None ahead of the ray's origin.
    fn none_ahead(self, lang: Lang) -> &'static str {
        match self {
            Self::Roots => pick(lang, "no root with t > 0", "nicio rădăcină cu t > 0"),
            _ => pick(lang, "none with t > 0", "niciuna cu t > 0"),
        }
    }
}

impl<'a, V: Dim> Writer<'a, V> {
    /// One intersection test as a line: the t values the shape gives, named as the shape has them
    /// ([`Crossings`]: a sphere's roots, a box's entry and exit, a plane's one crossing), and what
    /// was taken.
    pub(super) fn test_line(&self, e: &Event<V>) -> String {
        match e {
            Event::ObjectTest { object, roots, accepted } => {
                let kind = Crossings::of(self.scene.objects[object.index].shape.kind(), V::DIM);
                let ts: Vec<String> = roots.iter().map(|x| narration_number(*x)).collect();
                let found = if ts.is_empty() {
                    kind.none(self.lang).to_owned()
                } else {
                    format!("{} t = {}", kind.name(ts.len(), self.lang), ts.join(", "))
                };
                let acc = match accepted {
                    Some(t) => format!(
                        "→ {} t = {}",
                        self.t("accepted (least t > 0)", "acceptat (cel mai mic t > 0)"),
                        narration_number(*t)
                    ),
                    None => format!("→ {}", kind.none_ahead(self.lang)),
                };
                format!("{found} {acc}")
            }
            Event::BoundTest { volume, t_in, t_out, hit, .. } => {
                format!("{volume}: {}", self.interval(*t_in, *t_out, *hit))
            }
            Event::NodeVisit { structure, node, .. } => format!("{structure} {node}"),
            Event::NodeSkip { structure, node, t_in, t_best } => format!(
                "{structure} {node}: tᵢ = {} > t = {} → {}",
                narration_number(*t_in),
                narration_number(*t_best),
                self.t("skipped", "sărit")
            ),
            Event::VoxelStep { cell, .. } => format!("{} {cell:?}", self.t("voxel", "voxelul")),
            _ => String::new(),
        }
    }

    /// A bounding volume's interval and verdict (closed, exit widened, §11): a hit, an empty
    /// interval (`max tᵢ > min tₑ`), or a volume wholly behind the ray (`min tₑ < 0`).
    fn interval(&self, t_in: f64, t_out: f64, hit: bool) -> String {
        let verdict = if hit {
            self.t("t_in ≤ t_out and t_out ≥ 0: hit", "t_in ≤ t_out și t_out ≥ 0: intersectat").to_owned()
        } else if widen_exit(t_out) < 0.0 {
            self.t(
                "t_out < 0: the volume is behind the ray, a miss",
                "t_out < 0: volumul este în spatele razei, ratat",
            )
            .to_owned()
        } else {
            self.t("t_in > t_out: the interval is empty, a miss", "t_in > t_out: intervalul este vid, ratat")
                .to_owned()
        };
        format!(
            "t_in = max tᵢ = {}, t_out = min tₑ = {} → {verdict}",
            narration_number(t_in),
            narration_number(t_out)
        )
    }

    /// The name and kind of a ray node: `P — primary ray`, `R₁ — reflected ray from I₁`.
    fn ray_title(&self, index: usize) -> String {
        let node = &self.log.nodes[index];
        let name = self.names.ray_text(index);
        let from = node.parent.and_then(|p| self.names.hit_text(p)).unwrap_or_default();
        let kind = match node.start.kind {
            RayKind::Primary => self.t("primary ray", "raza primară").to_owned(),
            RayKind::Reflected => format!("{} {from}", self.t("reflected ray from", "raza reflectată din")),
            RayKind::Transmitted => {
                format!("{} {from}", self.t("transmitted ray from", "raza transmisă din"))
            }
        };
        format!(
            "{name} — {kind}, {} {} (max_depth {})",
            self.t("level", "nivelul"),
            node.start.level,
            self.max_depth
        )
    }

    /// The steps of ray node `index` and its subtree; `opener` is the event that spawned the ray
    /// (its `primary_ray`, or the parent's `reflect`/`refract`).
    pub(super) fn node(&mut self, index: usize, indent: usize, opener: Option<usize>) {
        self.at = Some(index);
        let node = &self.log.nodes[index];
        let mut events = self.events_of(index);
        cells_first(&mut events);
        let opener = opener
            .or_else(|| events.iter().find(|(_, e)| matches!(e, Event::PrimaryRay { .. })).map(|(k, _)| *k));
        let hit_event =
            events.iter().find(|(_, e)| matches!(e, Event::Hit { .. } | Event::Miss { .. })).map(|(k, _)| *k);
        let ray_line = format!(
            "r(t) = O + t·D, O = {}, D = {}",
            vec_str(node.start.origin),
            vec_str(node.start.direction)
        );
        let title = self.ray_title(index);
        self.step(indent, &title, &[ray_line], opener.into_iter().collect());
        let name = self.names.ray_text(index);
        let mut children = node.children.iter();
        let mut lights_done = false;
        // The events that spawned the children, for the colour step.
        let mut spawned: Vec<usize> = Vec::new();
        // Tests after the hit belong to the shadow ray that follows them.
        let mut seen_hit = false;
        let mut pending: Vec<Indexed<'a, V>> = Vec::new();
        // The object tests of the grid cell being walked are told under its header.
        let mut in_cell: usize = 0;
        self.shadow_tests.clear();
        for (k, e) in events {
            let deeper = usize::from(in_cell > 0);
            match e {
                Event::ObjectTest { .. } if seen_hit => pending.push((k, e)),
                Event::BoundTest { .. }
                | Event::NodeVisit { .. }
                | Event::NodeSkip { .. }
                | Event::VoxelStep { .. }
                    if seen_hit =>
                {
                    pending.push((k, e));
                }
                Event::ObjectTest { object, .. } => {
                    in_cell = in_cell.saturating_sub(1);
                    let title = format!(
                        "{} {name} {} {}",
                        self.t("Intersection test of", "Testul de intersecție al razei"),
                        self.t("with", "cu"),
                        self.object(*object)
                    );
                    let line = self.test_line(e);
                    self.step(indent + 1 + deeper, &title, &[line], vec![k]);
                }
                Event::Hit { object, t, point, normal, entering } => {
                    seen_hit = true;
                    self.hit(index, indent + 1, k, (*object, *t, *point, *normal, *entering));
                }
                Event::Miss { color } => {
                    let title = format!(
                        "{name} {}",
                        self.t(
                            "hits no object: the colour is the background",
                            "nu intersectează niciun obiect: culoarea este fundalul"
                        )
                    );
                    self.step(indent + 1, &title, &[format!("I = {}", rgb(*color))], vec![k]);
                }
                Event::ShadowRay { light, .. } => {
                    self.shadow_tests.push((*light, std::mem::take(&mut pending)));
                }
                Event::Reflect { origin, direction, offset } => {
                    if !lights_done {
                        self.local_model(node, index, indent + 1, hit_event);
                        lights_done = true;
                    }
                    self.reflect(index, indent + 1, k, (*origin, *direction, *offset));
                    spawned.push(k);
                    if let Some(&c) = children.next() {
                        self.node(c, indent + 1, Some(k));
                        self.at = Some(index);
                    }
                }
                Event::Refract { origin, direction, offset, n1, n2 } => {
                    if !lights_done {
                        self.local_model(node, index, indent + 1, hit_event);
                        lights_done = true;
                    }
                    self.refract(index, indent + 1, k, (*origin, *direction, *offset), (*n1, *n2));
                    spawned.push(k);
                    if let Some(&c) = children.next() {
                        self.node(c, indent + 1, Some(k));
                        self.at = Some(index);
                    }
                }
                Event::TotalInternalReflection { k: radicand, n1, n2 } => {
                    if !lights_done {
                        self.local_model(node, index, indent + 1, hit_event);
                        lights_done = true;
                    }
                    self.total_internal_reflection(index, indent + 1, k, *radicand, (*n1, *n2));
                }
                Event::DepthLimit { level } => {
                    if !lights_done {
                        self.local_model(node, index, indent + 1, hit_event);
                        lights_done = true;
                    }
                    let title =
                        self.t("Depth limit: no secondary rays", "Limita de adâncime: fără raze secundare");
                    self.step(
                        indent + 1,
                        title,
                        &[format!("n = {level} > max_depth = {}", self.max_depth)],
                        vec![k],
                    );
                }
                Event::BoundTest { volume, object, t_in, t_out, hit, .. } => {
                    let of = object.map(|o| format!(" {} {}", self.t("of", "al obiectului"), self.object(o)));
                    let title = format!(
                        "{} ({volume}){}",
                        self.t("Bounding-volume test", "Test cu volumul încadrator"),
                        of.unwrap_or_default()
                    );
                    let mut line = self.interval(*t_in, *t_out, *hit);
                    if !*hit {
                        line.push_str(if object.is_some() {
                            self.t("; the object is not tested", "; obiectul nu este testat")
                        } else {
                            self.t("; what it bounds is not tested", "; ce încadrează nu este testat")
                        });
                    }
                    self.step(indent + 1, &title, &[line], vec![k]);
                }
                Event::NodeVisit { structure, node, depth, t_in, t_out } => {
                    let title = format!(
                        "{} {structure} {node} ({} {depth})",
                        self.t("Visit node", "Vizitează nodul"),
                        self.t("depth", "adâncimea")
                    );
                    self.step(
                        indent + 1,
                        &title,
                        &[format!("t ∈ [{}, {}]", narration_number(*t_in), narration_number(*t_out))],
                        vec![k],
                    );
                }
                Event::NodeSkip { structure, node, t_in, t_best } => {
                    let title = format!("{} {structure} {node}", self.t("Skip node", "Sare peste nodul"));
                    let line = format!(
                        "tᵢ = {} > t = {}: {}",
                        narration_number(*t_in),
                        narration_number(*t_best),
                        self.t(
                            "its box starts beyond the nearest hit found",
                            "volumul său începe dincolo de cea mai apropiată intersecție găsită"
                        )
                    );
                    self.step(indent + 1, &title, &[line], vec![k]);
                }
                Event::VoxelStep { cell, t_max, objects, .. } => {
                    in_cell = objects.len();
                    let title = format!("{} {cell:?}", self.t("Voxel", "Voxelul"));
                    let t: Vec<String> = t_max.iter().map(|x| narration_number(*x)).collect();
                    let exit = t_max.iter().copied().fold(f64::INFINITY, f64::min);
                    let tested = if objects.is_empty() {
                        self.t("no object to test here", "niciun obiect de testat aici").to_owned()
                    } else {
                        let names: Vec<String> = objects.iter().map(|o| self.object(*o)).collect();
                        format!("{}: {}", self.t("tested here", "testate aici"), names.join(", "))
                    };
                    let lines = [
                        format!(
                            "tMax = ({}): {} t = {}",
                            t.join(", "),
                            self.t("the ray leaves the voxel at", "raza iese din voxel la"),
                            narration_number(exit)
                        ),
                        tested,
                        self.t(
                            "a hit is accepted only if t ≤ the voxel's exit; a farther one waits for its voxel",
                            "o intersecție este acceptată doar dacă t ≤ ieșirea din voxel; una mai îndepărtată își așteaptă voxelul",
                        )
                        .to_owned(),
                    ];
                    self.step(indent + 1, &title, &lines, vec![k]);
                }
                Event::PrimaryRay { .. } | Event::Sample { .. } => {}
            }
        }
        if node.end.as_ref().is_some_and(|e| e.hit.is_some()) && !lights_done {
            self.local_model(node, index, indent + 1, hit_event);
        }
        let colour: Vec<usize> = hit_event.into_iter().chain(spawned).collect();
        self.sum(node, index, indent + 1, colour);
    }

    /// The nearest-hit step of node `index` (event `k`): I_k, the normal, its side and N_f·V.
    fn hit(
        &mut self,
        index: usize,
        indent: usize,
        k: usize,
        hit: (crate::record::event::ObjectRef, f64, V, V, bool),
    ) {
        let (object, t, point, normal, entering) = hit;
        let d = self.log.nodes[index].start.direction;
        let dn = d.dot(normal);
        let side = if entering {
            self.t("D·N ≤ 0: the ray is entering, N_f = N", "D·N ≤ 0: raza intră, N_f = N").to_owned()
        } else {
            format!(
                "{} = {}",
                self.t("D·N > 0: the ray is leaving, N_f = −N", "D·N > 0: raza iese, N_f = −N"),
                vec_str(-normal)
            )
        };
        let name = self.names.ray_text(index);
        let i = self.names.hit_text(index).unwrap_or_default();
        let title = format!(
            "{} {name}: {i} {} {}",
            self.t("Nearest hit of", "Cea mai apropiată intersecție a razei"),
            self.t("on", "pe"),
            self.object(object)
        );
        let n_f = if entering { normal } else { -normal };
        let lines = vec![
            format!("t = {}, {i} = r(t) = {}", narration_number(t), vec_str(point)),
            format!(
                "N = {} ({})",
                vec_str(normal),
                self.t("outward unit normal", "normala exterioară unitară")
            ),
            format!("D·N = {} — {side}", narration_number(dn)),
            format!(
                "V = −D ({}), N_f·V = {}",
                self.t("back along the ray", "înapoi pe rază"),
                narration_number(n_f.dot(-d))
            ),
        ];
        self.step(indent, &title, &lines, vec![k]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::record::event::ObjectRef;
    use glam::DVec3;

    fn test(object: usize) -> Event<DVec3> {
        Event::ObjectTest {
            object: ObjectRef { index: object, triangle: None },
            roots: vec![],
            accepted: None,
        }
    }

    #[test]
    fn a_cell_comes_before_the_tests_it_lists() {
        let cell = Event::VoxelStep {
            cell: vec![0, 0, 0],
            t_max: vec![1.0],
            t_delta: vec![1.0],
            objects: vec![ObjectRef { index: 1, triangle: None }, ObjectRef { index: 2, triangle: None }],
        };
        let (plane, a, b) = (test(0), test(1), test(2));
        let mut events = vec![(0, &plane), (1, &a), (2, &b), (3, &cell)];
        cells_first(&mut events);
        assert_eq!(events.iter().map(|(k, _)| *k).collect::<Vec<_>>(), [0, 3, 1, 2]);
    }
}
