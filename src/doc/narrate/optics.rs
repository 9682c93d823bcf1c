//! The secondary rays' steps at a hit I_k: the reflected ray R_k (§3, `R = 2(N_f·V)·N_f − V`),
//! the transmitted ray T_k by Snell's law with its angles, in the lecture's form and in the
//! computed one, total internal reflection, and the spawn offset `δ = 2⁻⁴⁴·M` with its M.
//! The cosines and angles are read from the recorded hit (c = −D·N_f, k by `geom::optics`'s
//! own formula), so they are the numbers the tracer used.

use super::{degrees, vec_str, Writer};
use crate::format::narration_number;
use crate::geom::offset::OFFSET_SCALE;
use crate::geom::optics::{refract, Refraction};
use crate::record::event::NodeHit;
use crate::shape::Dim;

impl<V: Dim> Writer<'_, V> {
    /// The hit of node `index` and its facing normal N_f.
    fn facing(&self, index: usize) -> Option<(NodeHit<V>, V)> {
        let hit = self.log.nodes[index].end.as_ref().and_then(|e| e.hit)?;
        let n_f = if hit.entering { hit.normal } else { -hit.normal };
        Some((hit, n_f))
    }

    /// The spawn offset's lines for ray `child` leaving node `index`'s hit along `direction`
    /// from `origin`: δ = 2⁻⁴⁴·M with M = max(‖I‖∞, ‖O‖∞, |t|, the object's scale), §11, and
    /// the side it is pushed to (+N_f for R, −N_f for a T that goes through).
    fn offset_lines(&self, index: usize, child: &str, origin: V, direction: V, offset: f64) -> [String; 2] {
        let Some((hit, n_f)) = self.facing(index) else { return [String::new(), String::new()] };
        let start = self.log.nodes[index].start.origin;
        let scale = self.scene.objects[hit.object.index].scale;
        let i = self.names.hit_text(index).unwrap_or_default();
        let side = if direction.dot(n_f) >= 0.0 { "+" } else { "−" };
        [
            format!(
                "{}: M = max(‖{i}‖∞, ‖O‖∞, |t|, {}) = max({}, {}, {}, {}) = {} ({})",
                self.t("spawn offset δ = 2⁻⁴⁴·M", "deplasarea δ = 2⁻⁴⁴·M"),
                self.t("scale", "scara"),
                narration_number(hit.point.max_abs()),
                narration_number(start.max_abs()),
                narration_number(hit.t.abs()),
                narration_number(scale),
                narration_number(offset / OFFSET_SCALE),
                self.t(
                    "‖·‖∞ the largest |coordinate|, O the incoming ray's origin, scale the object's size",
                    "‖·‖∞ cea mai mare |coordonată|, O originea razei incidente, scara mărimea obiectului"
                )
            ),
            format!(
                "δ = {} → {child} {} {i} {side} δ·N_f = {}",
                narration_number(offset),
                self.t("starts at", "pornește din"),
                vec_str(origin)
            ),
        ]
    }

    /// The step of the reflected ray spawned at node `index`'s hit (event `k`).
    pub(super) fn reflect(&mut self, index: usize, indent: usize, k: usize, spawned: (V, V, f64)) {
        let (origin, direction, offset) = spawned;
        let child = self.names.hit[index].map_or_else(|| "R".to_owned(), |h| sub_text("R", h));
        let i = self.names.hit_text(index).unwrap_or_default();
        let n_f_v =
            self.facing(index).map_or(0.0, |(_, n_f)| n_f.dot(-self.log.nodes[index].start.direction));
        let title = format!(
            "{} {child} {} {i} (ks > 0)",
            self.t("Reflected ray", "Raza reflectată"),
            self.t("at", "în")
        );
        let mut lines = vec![format!(
            "R = 2(N_f·V)·N_f − V, V = −D, N_f·V = {} → {child} = {}",
            narration_number(n_f_v),
            vec_str(direction)
        )];
        lines.extend(self.offset_lines(index, &child, origin, direction, offset));
        self.step(indent, &title, &lines, vec![k]);
    }

    /// The step of the transmitted ray spawned at node `index`'s hit (event `k`): the angles,
    /// Snell's check, T in the lecture's form and in the computed one.
    pub(super) fn refract(
        &mut self,
        index: usize,
        indent: usize,
        k: usize,
        spawned: (V, V, f64),
        n: (f64, f64),
    ) {
        let (origin, direction, offset) = spawned;
        let (n1, n2) = n;
        let eta = n1 / n2;
        let child = self.names.hit[index].map_or_else(|| "T".to_owned(), |h| sub_text("T", h));
        let i = self.names.hit_text(index).unwrap_or_default();
        let title = format!(
            "{} {child} {} {i} (kt > 0), Snell: n1·sin θi = n2·sin θt",
            self.t("Transmitted ray", "Raza transmisă"),
            self.t("at", "în")
        );
        let mut lines = vec![format!(
            "n1 = {}, n2 = {}, η = n1/n2 = {}",
            narration_number(n1),
            narration_number(n2),
            narration_number(eta)
        )];
        if let Some((_, n_f)) = self.facing(index) {
            let d = self.log.nodes[index].start.direction;
            let c = (-d.dot(n_f)).clamp(-1.0, 1.0);
            if let Refraction::Transmitted { k: radicand, .. } = refract(d, n_f, eta) {
                let cos_t = radicand.sqrt();
                let (sin_i, sin_t) = ((1.0 - c * c).max(0.0).sqrt(), (1.0 - radicand).max(0.0).sqrt());
                lines.extend([
                    format!("cos θi = c = −D·N_f = {} → θi = {}", narration_number(c), degrees(c)),
                    format!(
                        "k = 1 − η²·(1 − c²) = (1 − η²) + (η·c)² = {}; cos θt = √k = {} → θt = {}",
                        narration_number(radicand),
                        narration_number(cos_t),
                        degrees(cos_t)
                    ),
                    format!(
                        "{}: n1·sin θi = {}·{} = {}, n2·sin θt = {}·{} = {}",
                        self.t("check", "verificare"),
                        narration_number(n1),
                        narration_number(sin_i),
                        narration_number(n1 * sin_i),
                        narration_number(n2),
                        narration_number(sin_t),
                        narration_number(n2 * sin_t)
                    ),
                    format!(
                        "{}: T = L·(n1/n2) − (cos θt + (n1/n2)·(L·N_f))·N_f = L·{} − ({} + {}·({}))·N_f, {}",
                        self.t("the lecture's form", "forma din curs"),
                        narration_number(eta),
                        narration_number(cos_t),
                        narration_number(eta),
                        narration_number(d.dot(n_f)),
                        self.t("L = D the incoming direction", "L = D direcția incidentă")
                    ),
                ]);
            }
        }
        lines.push(format!(
            "{}: T = η·D + (η·c − √k)·N_f → {child} = {}",
            self.t("as computed", "forma calculată"),
            vec_str(direction)
        ));
        lines.extend(self.offset_lines(index, &child, origin, direction, offset));
        self.step(indent, &title, &lines, vec![k]);
    }

    /// The step of total internal reflection at node `index`'s hit (event `k`): `k < 0`.
    pub(super) fn total_internal_reflection(
        &mut self,
        index: usize,
        indent: usize,
        k: usize,
        radicand: f64,
        n: (f64, f64),
    ) {
        let (n1, n2) = n;
        let title =
            self.t("Total internal reflection: no T ray", "Reflexie totală internă: nu există raza T");
        let mut lines = vec![format!(
            "n1 = {}, n2 = {}, η = n1/n2 = {}",
            narration_number(n1),
            narration_number(n2),
            narration_number(n1 / n2)
        )];
        if let Some((_, n_f)) = self.facing(index) {
            let c = (-self.log.nodes[index].start.direction.dot(n_f)).clamp(-1.0, 1.0);
            let critical = if n2 < n1 {
                format!(" > θc = arcsin(n2/n1) = {:.2}°", (n2 / n1).asin().to_degrees())
            } else {
                String::new()
            };
            lines.push(format!(
                "cos θi = c = −D·N_f = {} → θi = {}{critical}",
                narration_number(c),
                degrees(c)
            ));
        }
        lines.push(format!(
            "k = (1 − η²) + (η·c)² = {} < 0: {} → {}",
            narration_number(radicand),
            self.t("no cos θt = √k", "nu există cos θt = √k"),
            self.t("the kt·T term is dropped", "termenul kt·T lipsește")
        ));
        self.step(indent, title, &lines, vec![k]);
    }
}

/// `X` with subscript k, as the narration writes names.
fn sub_text(letter: &str, k: usize) -> String {
    crate::record::names::subscript(letter, &[k])
}
