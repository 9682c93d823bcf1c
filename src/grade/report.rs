//! A grade for the reader: the text in English or Romanian (as the narration words it), or the
//! JSON of docs/grading.md (`ok`, `checked`, `not_checked`, `tolerance`, `first`).

use super::{Divergence, Grade, Quantity, Shown};
use crate::format::narration_number;
use crate::lang::Lang;
use serde_json::{json, Map, Value};
use std::fmt::Write;

fn t(lang: Lang, en: &'static str, ro: &'static str) -> &'static str {
    match lang {
        Lang::En => en,
        Lang::Ro => ro,
    }
}

/// A value for the reader.
#[must_use]
pub fn shown_text(s: &Shown, lang: Lang) -> String {
    match s {
        Shown::Vector(v) => {
            format!("({})", v.iter().map(|x| narration_number(*x)).collect::<Vec<_>>().join(", "))
        }
        Shown::Number(x) => narration_number(*x),
        Shown::Name(n) if n.is_empty() => t(lang, "an object (unnamed)", "un obiect (nenumit)").to_owned(),
        Shown::Name(n) => n.clone(),
        Shown::Nothing => t(lang, "nothing (a miss)", "nimic (nicio intersecție)").to_owned(),
        Shown::NoShadowRay => {
            t(lang, "no shadow ray (N_f·L ≤ 0)", "nicio rază de umbră (N_f·L ≤ 0)").to_owned()
        }
        Shown::Ray(key) => match (*key, lang) {
            ("reflected", Lang::En) => "a reflected ray R".to_owned(),
            ("reflected", Lang::Ro) => "o rază reflectată R".to_owned(),
            (_, Lang::En) => "a transmitted ray T".to_owned(),
            (_, Lang::Ro) => "o rază transmisă T".to_owned(),
        },
        Shown::NoRay => t(lang, "no ray", "nicio rază").to_owned(),
    }
}

/// A value in `--json`: vectors as arrays, names as strings, "nothing" as null.
#[must_use]
pub fn shown_json(s: &Shown) -> Value {
    match s {
        Shown::Vector(v) => json!(v),
        Shown::Number(x) => json!(x),
        Shown::Name(n) => json!(n),
        Shown::Ray(key) => json!(key),
        Shown::Nothing | Shown::NoShadowRay | Shown::NoRay => Value::Null,
    }
}

/// What a quantity is called in a sentence.
#[must_use]
pub fn quantity_text(q: Quantity, light: Option<usize>, lang: Lang) -> String {
    let j = light.map_or(0, |j| j + 1);
    match (q, lang) {
        (Quantity::WindowPoint, Lang::En) => "the window point (u, v)".into(),
        (Quantity::WindowPoint, Lang::Ro) => "punctul ferestrei (u, v)".into(),
        (Quantity::Origin, Lang::En) => "origin".into(),
        (Quantity::Origin, Lang::Ro) => "originea".into(),
        (Quantity::Direction, Lang::En) => "direction".into(),
        (Quantity::Direction, Lang::Ro) => "direcția".into(),
        (Quantity::Object, Lang::En) => "object hit".into(),
        (Quantity::Object, Lang::Ro) => "obiectul lovit".into(),
        (Quantity::T, _) => "t".into(),
        (Quantity::Point, Lang::En) => "hit point I".into(),
        (Quantity::Point, Lang::Ro) => "punctul de intersecție I".into(),
        (Quantity::Normal, Lang::En) => "normal N".into(),
        (Quantity::Normal, Lang::Ro) => "normala N".into(),
        (Quantity::NDotL, Lang::En) => format!("N_f·L of light {j}"),
        (Quantity::NDotL, Lang::Ro) => format!("N_f·L al sursei {j}"),
        (Quantity::Shadow, Lang::En) => format!("shadow factor s of light {j}"),
        (Quantity::Shadow, Lang::Ro) => format!("factorul de umbră s al sursei {j}"),
        (Quantity::Local, _) => "I_local".into(),
        (Quantity::Colour, Lang::En) => "colour".into(),
        (Quantity::Colour, Lang::Ro) => "culoarea".into(),
        (Quantity::Missing, Lang::En) => "a ray the lecture spawns is missing".into(),
        (Quantity::Missing, Lang::Ro) => "lipsește o rază pe care cursul o generează".into(),
        (Quantity::Extra, Lang::En) => "a ray spawned where the lecture spawns none".into(),
        (Quantity::Extra, Lang::Ro) => "o rază generată acolo unde cursul nu generează niciuna".into(),
    }
}

fn formula(d: &Divergence, lang: Lang) -> &'static str {
    match lang {
        Lang::En => d.formula[0],
        Lang::Ro => d.formula[1],
    }
}

/// `N mărimi`, `20 de mărimi`: Romanian puts `de` after numbers whose last two digits are 00 or
/// 20 … 99 (not after 0 … 19).
fn quantities(n: usize, lang: Lang) -> String {
    match lang {
        Lang::En if n == 1 => "1 quantity".to_owned(),
        Lang::En => format!("{n} quantities"),
        Lang::Ro if n == 1 => "1 mărime".to_owned(),
        Lang::Ro if n % 100 >= 20 || (n >= 100 && n.is_multiple_of(100)) => format!("{n} de mărimi"),
        Lang::Ro => format!("{n} mărimi"),
    }
}

/// The grade as text, in the narration's language.
#[must_use]
pub fn text(g: &Grade, lang: Lang) -> String {
    let mut out = String::new();
    let pixel = g.pixel.iter().map(ToString::to_string).collect::<Vec<_>>().join(", ");
    let _ = writeln!(
        out,
        "{} ({pixel}) — {} {} ({})",
        t(lang, "whitted grade: pixel", "whitted grade: pixelul"),
        t(lang, "tolerance", "toleranța"),
        g.tolerance,
        t(lang, "relative; absolute below 1", "relativă; absolută sub 1"),
    );
    match &g.first {
        None => {
            let _ = writeln!(
                out,
                "{} {} {}.",
                t(lang, "Everything agrees:", "Totul coincide:"),
                quantities(g.checked, lang),
                t(lang, "checked", "verificate")
            );
        }
        Some(d) => {
            let _ = writeln!(
                out,
                "{} {}.",
                t(lang, "Agreed before the divergence:", "Au coincis înainte de divergență:"),
                quantities(g.checked, lang)
            );
            divergence(&mut out, d, lang);
        }
    }
    if !g.not_checked.is_empty() {
        let _ = writeln!(
            out,
            "{} {}",
            t(lang, "Not checked (absent from the document):", "Neverificate (lipsesc din document):"),
            g.not_checked.join(", ")
        );
    }
    out
}

fn divergence(out: &mut String, d: &Divergence, lang: Lang) {
    let step = d.step.map_or_else(String::new, |k| format!(", {} {k}", t(lang, "step", "pasul")));
    let level = t(lang, "level", "nivelul");
    let _ = writeln!(
        out,
        "{}{step} ({}, {level} {}): {} — {}",
        t(lang, "First divergence", "Prima divergență"),
        d.chain.join(" → "),
        d.level,
        d.ray,
        quantity_text(d.quantity, d.light, lang)
    );
    let width = 12;
    let _ = writeln!(out, "  {:width$} {}", t(lang, "expected", "așteptat"), shown_text(&d.expected, lang));
    let _ = writeln!(out, "  {:width$} {}", t(lang, "found", "găsit"), shown_text(&d.found, lang));
    let _ = writeln!(out, "  {:width$} {}", t(lang, "formula", "formula"), formula(d, lang));
    if !d.inputs.is_empty() {
        let inputs: Vec<String> =
            d.inputs.iter().map(|(name, v)| format!("{name} = {}", shown_text(v, lang))).collect();
        let _ = writeln!(out, "  {:width$} {}", t(lang, "with", "cu"), inputs.join(", "));
        let _ = writeln!(
            out,
            "  {:width$} {}",
            "",
            t(
                lang,
                "(your own earlier values, which agreed; the scene's where you gave none)",
                "(valorile tale de mai înainte, care au coincis; ale scenei acolo unde nu ai dat)"
            )
        );
    }
    if let Some(m) = d.diagnosis {
        let _ =
            writeln!(out, "  {:width$} {} [{}]", t(lang, "diagnosis", "diagnostic"), m.what(lang), m.name());
        let _ = writeln!(out, "  {:width$} {}", t(lang, "the rule", "regula"), m.rule(lang));
    }
    let _ = writeln!(
        out,
        "{}",
        t(
            lang,
            "What follows from it was not compared: the rays below start from a different point or direction.",
            "Ce urmează nu a mai fost comparat: razele de dedesubt pleacă din alt punct sau pe altă direcție."
        )
    );
}

/// The first divergence in the reader's words, for the page's verdict table: the ray chain
/// (`P → R₁`), the quantity, the expected and found values, the formula and its inputs, and the
/// diagnosis with the lecture's rule; null when everything agrees.
#[must_use]
pub fn words(g: &Grade, lang: Lang) -> Value {
    g.first.as_ref().map_or(Value::Null, |d| {
        let inputs: Vec<String> =
            d.inputs.iter().map(|(name, v)| format!("{name} = {}", shown_text(v, lang))).collect();
        json!({
            "chain": d.chain.join(" → "),
            "quantity": quantity_text(d.quantity, d.light, lang),
            "expected": shown_text(&d.expected, lang),
            "found": shown_text(&d.found, lang),
            "formula": formula(d, lang),
            "inputs": inputs.join(", "),
            "diagnosis": d.diagnosis.map_or(Value::Null, |m| json!(m.what(lang))),
            "rule": d.diagnosis.map_or(Value::Null, |m| json!(m.rule(lang))),
        })
    })
}

/// The grade as the JSON of docs/grading.md (the formula in `lang`).
#[must_use]
pub fn json(g: &Grade, lang: Lang) -> Value {
    let first = g.first.as_ref().map_or(Value::Null, |d| {
        let mut m = Map::new();
        m.insert("path".into(), json!(d.path));
        m.insert("ray".into(), json!(d.ray));
        m.insert("quantity".into(), json!(d.quantity.name()));
        if let Some(j) = d.light {
            m.insert("light".into(), json!(j));
        }
        m.insert("expected".into(), shown_json(&d.expected));
        m.insert("found".into(), shown_json(&d.found));
        m.insert("step".into(), d.step.map_or(Value::Null, |k| json!(k)));
        m.insert("level".into(), json!(d.level));
        m.insert("formula".into(), json!(formula(d, lang)));
        let inputs: Vec<Value> =
            d.inputs.iter().map(|(name, v)| json!({"name": name, "value": shown_json(v)})).collect();
        m.insert("inputs".into(), Value::Array(inputs));
        if let Some(mistake) = d.diagnosis {
            m.insert("diagnosis".into(), json!(mistake.name()));
        }
        Value::Object(m)
    });
    json!({
        "ok": g.ok(),
        "pixel": g.pixel,
        "checked": g.checked,
        "not_checked": g.not_checked,
        "tolerance": g.tolerance,
        "first": first,
    })
}
