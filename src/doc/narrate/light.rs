//! The local model's steps at a hit I_k (§5): the formula with the ambient term (and which
//! colour of a checker I takes), one step per light with its shadow ray L_k (its tests, its
//! occluders, s), L, H, N·L and N·H (N_f·L, N_f·H when the ray is inside the object: the
//! facing normal is what the model uses), the diffuse and specular components; then the colour
//! sum `I = I_local + ks·R_k + kt·T_k`.

use super::{rgb, vec_str, Indexed, Writer};
use crate::format::narration_number;
use crate::record::event::{Event, LightTerm, RayKind};
use crate::record::RayNode;
use crate::scene::material::{Material, Rgb};
use crate::shape::Dim;
use std::fmt::Write;

impl<'a, V: Dim> Writer<'a, V> {
    /// `Isrc`, in Romanian the lecture's `Isursa`.
    fn isrc(&self) -> &'static str {
        self.t("Isrc", "Isursa")
    }

    /// The local model's steps at the node's hit (event `hit`): its formula with the ambient
    /// term (the hit and every shadow ray), then one step per light.
    pub(super) fn local_model(
        &mut self,
        node: &RayNode<V>,
        index: usize,
        indent: usize,
        hit_event: Option<usize>,
    ) {
        let Some(hit) = node.end.as_ref().and_then(|e| e.hit) else {
            return;
        };
        let material = self.scene.material_of(hit.object.index);
        let (ka, _) = material.colors_at(hit.point);
        let ambient = self.scene.ambient.modulate(ka);
        let src = self.isrc();
        let title = format!(
            "{}: I_local = Ia·Ka + Σ {src}·fat·s·lum·[kd·(N·L) + ks·(N·H)^n]",
            self.t("Local model", "Modelul local")
        );
        let mut lines = Vec::new();
        if let Some(checker) = &material.checker {
            let line = if checker.is_odd(hit.point) {
                format!(
                    "{} ka2 = {}, kd2 = {}",
                    self.t(
                        "checker: I lies in an odd cell (Σ ⌊xᵢ/size⌋ odd) → the second colour:",
                        "tablă de șah: I este într-o celulă impară (Σ ⌊xᵢ/size⌋ impar) → a doua culoare:"
                    ),
                    rgb(checker.ka2),
                    rgb(checker.kd2)
                )
            } else {
                format!(
                    "{} ka = {}, kd = {}",
                    self.t(
                        "checker: I lies in an even cell (Σ ⌊xᵢ/size⌋ even) → the first colour:",
                        "tablă de șah: I este într-o celulă pară (Σ ⌊xᵢ/size⌋ par) → prima culoare:"
                    ),
                    rgb(material.ka),
                    rgb(material.kd)
                )
            };
            lines.push(line);
        }
        lines.push(format!("Ia·Ka = {} · {} = {}", rgb(self.scene.ambient), rgb(ka), rgb(ambient)));
        if !hit.entering {
            lines.push(
                self.t(
                    "the ray is inside the object: the model uses N_f = −N for N",
                    "raza este în interiorul obiectului: modelul folosește N_f = −N în locul lui N",
                )
                .to_owned(),
            );
        }
        let shadows: Vec<Indexed<'a, V>> =
            self.events_of(index).into_iter().filter(|(_, e)| matches!(e, Event::ShadowRay { .. })).collect();
        let events = hit_event.into_iter().chain(shadows.iter().map(|(k, _)| *k)).collect();
        self.step(indent, &title, &lines, events);
        for term in &node.lights {
            self.light(term, index, &shadows, indent + 1, material, hit_event);
        }
    }

    /// One light's step at node `index`'s hit: its shadow ray and that ray's tests, or the hit
    /// (`hit_event`) when the light is behind the surface.
    fn light(
        &mut self,
        term: &LightTerm<V>,
        index: usize,
        shadows: &[Indexed<'a, V>],
        indent: usize,
        material: &Material,
        hit_event: Option<usize>,
    ) {
        let node = &self.log.nodes[index];
        let inside = node.end.as_ref().and_then(|e| e.hit).is_some_and(|h| !h.entering);
        let n = if inside { "N_f" } else { "N" };
        let shadow = self.names.shadow_text(index, term.light);
        let title = format!(
            "{} {} (lights[{}]), {} {shadow}",
            self.t("Light", "Sursa de lumină"),
            term.light + 1,
            term.light,
            self.t("shadow ray", "raza de umbră")
        );
        let mut lines = Vec::new();
        match term.l {
            Some(l) => lines.push(format!("L = {}, {n}·L = {}", vec_str(l), narration_number(term.n_dot_l))),
            None => lines.push(
                self.t(
                    "the light sits at I: no direction, lum = 0",
                    "sursa este chiar în I: nicio direcție, lum = 0",
                )
                .to_string(),
            ),
        }
        if term.lum == 0.0 {
            let line = format!(
                "lum = 0 ({n}·L ≤ 0): {} {shadow} {}",
                self.t("the light is behind the surface,", "sursa este în spatele suprafeței,"),
                self.t("is not cast", "nu este trasă")
            );
            lines.push(line);
            self.step(indent, &title, &lines, hit_event.into_iter().collect());
            return;
        }
        lines.push(format!("lum = 1, fat = min(1, 1/(c0 + c1·d + c2·d²)) = {}", narration_number(term.fat)));
        let mut events = Vec::new();
        for (k, e) in shadows {
            if let Event::ShadowRay { light, origin, direction, distance, occluders, s } = e {
                if *light != term.light {
                    continue;
                }
                events.push(*k);
                let mine =
                    || self.shadow_tests.iter().filter(|(l, _)| *l == term.light).flat_map(|(_, t)| t.iter());
                events.extend(mine().map(|(k, _)| *k));
                let tests: Vec<String> = mine()
                    .map(|(_, t)| match t {
                        Event::ObjectTest { object, .. } => {
                            format!("  · {}: {}", self.object(*object), self.test_line(t))
                        }
                        _ => format!("  · {}", self.test_line(t)),
                    })
                    .collect();
                lines.push(format!(
                    "{shadow} {} O = {}, D = {}",
                    self.t("from the offset origin", "din originea deplasată"),
                    vec_str(*origin),
                    vec_str(*direction)
                ));
                lines.extend(tests);
                let occ = if occluders.is_empty() {
                    self.t("nothing in between", "nimic între ele").to_string()
                } else {
                    let list: Vec<String> = occluders
                        .iter()
                        .map(|o| format!("{} (kt = {})", self.object(o.object), narration_number(o.kt)))
                        .collect();
                    list.join(", ")
                };
                lines.push(format!(
                    "{} d_L = {}: {occ} → s = Π kt = {}",
                    self.t("segment to the light, length", "segment până la sursă, lungime"),
                    narration_number(*distance),
                    narration_number(*s)
                ));
            }
        }
        let src = self.isrc();
        lines.push(format!(
            "{} {src}·fat·s·kd·({n}·L) = {}",
            self.t("diffuse component", "componenta difuză"),
            rgb(term.diffuse)
        ));
        if let (Some(l), true) = (term.l, material.ks > 0.0) {
            let view = -node.start.direction;
            let n_f =
                node.end.as_ref().and_then(|e| e.hit).map(|h| if h.entering { h.normal } else { -h.normal });
            if let (Some(h), Some(n_f)) = ((l + view).try_unit(), n_f) {
                let n_dot_h = n_f.dot(h);
                let mut line =
                    format!("H = (L + V)/|L + V| = {}, {n}·H = {}", vec_str(h), narration_number(n_dot_h));
                let _ = write!(line, ", ({n}·H)^n = {}", narration_number(material.highlight(n_dot_h)));
                lines.push(line);
            }
        }
        lines.push(format!(
            "{} {src}·fat·s·ks·({n}·H)^n (n = {}) = {}",
            self.t("specular component", "componenta speculară"),
            narration_number(material.n),
            rgb(term.specular)
        ));
        if events.is_empty() {
            events.extend(hit_event);
        }
        events.sort_unstable();
        self.step(indent, &title, &lines, events);
    }

    /// The colour step of node `index`: the hit and the rays it sums (`events`).
    pub(super) fn sum(&mut self, node: &RayNode<V>, index: usize, indent: usize, events: Vec<usize>) {
        let Some(end) = &node.end else { return };
        let Some(local) = end.local else { return };
        let Some(hit) = end.hit else { return };
        let m = self.scene.material_of(hit.object.index);
        let mut formula = format!("I = I_local {}", rgb(local));
        let (mut r, mut t) = ("R".to_owned(), "T".to_owned());
        for &c in &node.children {
            let child = &self.log.nodes[c];
            let col = child.end.as_ref().map_or(Rgb::BLACK, |e| e.color);
            let sym = self.names.ray_text(c);
            let (k, name) = match child.start.kind {
                RayKind::Transmitted => {
                    t.clone_from(&sym);
                    (m.kt, "kt")
                }
                _ => {
                    r.clone_from(&sym);
                    (m.ks, "ks")
                }
            };
            let _ = write!(formula, " + {name}·{sym} = {} · {}", narration_number(k), rgb(col));
        }
        let name = self.names.ray_text(index);
        let i = self.names.hit_text(index).unwrap_or_default();
        let title = format!(
            "{} {name} {} {i}: I = I_local + ks·{r} + kt·{t}",
            self.t("Colour of", "Culoarea razei"),
            self.t("at", "în")
        );
        self.step(indent, &title, &[formula, format!("I = {}", rgb(end.color))], events);
    }
}
