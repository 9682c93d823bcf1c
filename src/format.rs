//! Numbers and text written for a reader: one function per output format, each named for it.
//!
//! A number reads differently on a slide, in a narration and in an error message, and text is
//! escaped differently for HTML and for a figure's label markup. Each function's doc says what
//! its format needs and why it differs from the others. The SVG back end's two
//! (`canvas::svg::svg_coordinate`, `canvas::svg::xml_escape`) stay in `canvas`, which imports
//! nothing from the crate; this module imports nothing either, so any module may use it.
//!
//! | function | where | why its own |
//! |---|---|---|
//! | [`slide_number`] | figure labels | little room: 3 decimals, `m·10^{e}` markup |
//! | [`narration_number`] | narration | checked by hand: 6 significant digits |
//! | [`as_written`] | input error messages | the file's own spelling, ASCII `-` |
//! | `svg_coordinate` | SVG attributes | SVG number syntax, 1/100 pixel |
//! | `xml_escape` | SVG text | XML 1.0 forbids some control characters |
//! | [`html_escape`] | the course pages | HTML, attributes in double quotes |
//! | [`markup_escape`] | figure labels | the label markup's `_ ^ { } \` |
//! | [`terminal_text`] | stdout and stderr text | a terminal executes ESC, BEL, CR; bidi reorders |
//! | [`json_text`] | stdout JSON | serde_json leaves DEL, C1 and bidi controls raw |

/// The true minus sign (U+2212) that slides and narrations print instead of ASCII `-`.
const MINUS: &str = "−";

/// A number on a slide (a figure's label): at most 3 decimals (1 from 100 up), trailing zeros
/// dropped, no `-0`, a true minus, `∞` for infinities. A label has little room, so tiny values
/// are `m·10^{e}` in the label markup, which draws the exponent raised.
#[must_use]
pub fn slide_number(x: f64) -> String {
    if x.is_infinite() {
        return if x > 0.0 { "∞".into() } else { format!("{MINUS}∞") };
    }
    if x != 0.0 && x.abs() < 1e-3 {
        // Tiny values as a·10^e, two significant digits.
        let e = x.abs().log10().floor();
        let m = x / 10f64.powf(e);
        let m = format!("{m:.1}").replace('-', MINUS);
        return format!("{m}·10^{{{}}}", slide_number(e));
    }
    let decimals = if x.abs() >= 100.0 { 1 } else { 3 };
    let s = format!("{x:.decimals$}");
    let s = if s.contains('.') { s.trim_end_matches('0').trim_end_matches('.').to_owned() } else { s };
    if s == "-0" {
        "0".into()
    } else {
        s.replace('-', MINUS)
    }
}

/// A number in a narration: up to 6 significant digits, `1.00000e−5` outside [1e-4, 1e7), no `-0`,
/// a true minus. More digits than [`slide_number`], because the reader redoes the arithmetic by
/// hand; plain text, because a narration is not drawn through the label markup.
#[must_use]
pub fn narration_number(x: f64) -> String {
    if x == f64::INFINITY {
        return "∞".into();
    }
    if x == f64::NEG_INFINITY {
        return format!("{MINUS}∞");
    }
    if x == 0.0 {
        return "0".into();
    }
    let a = x.abs();
    let s = if (1e-4..1e7).contains(&a) {
        // 1e-4 ≤ a < 1e7, so the exponent lies in [−4, 6] and the cast is exact.
        #[allow(clippy::cast_possible_truncation)]
        let exponent = a.log10().floor() as i64;
        let decimals = usize::try_from((5 - exponent).clamp(0, 12)).unwrap_or(0);
        let s = format!("{x:.decimals$}");
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    } else {
        format!("{x:.5e}")
    };
    if s == "-0" {
        "0".into()
    } else {
        s.replace('-', MINUS)
    }
}

/// A number in an input error message, as its author would have written it in the file: the
/// shortest text that reads back as the same number (`-1`, `0.5`), `e` notation outside
/// [1e-5, 1e16) (`1e100`). ASCII `-`, unlike the other two, so that it can be searched for in the file.
#[must_use]
pub fn as_written(x: f64) -> String {
    if x != 0.0 && !(1e-5..1e16).contains(&x.abs()) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

/// Text for HTML element content and double-quoted attribute values: `& < > "` become entities.
/// The pages quote every attribute with `"`, so `'` may stay; HTML, unlike XML, tolerates control
/// characters, so none is dropped.
#[must_use]
pub fn html_escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

/// Text for a figure's label markup (`canvas::text`), drawn as written: `_`, `^`, `{`, `}` and `\`
/// get a `\` before them, so that an object named `glass_ball` shows no subscript. Names that come
/// from a scene file go through it; the lecture's notation (`R_1`) does not.
#[must_use]
pub fn markup_escape(name: &str) -> String {
    let mut out = String::with_capacity(name.len());
    for c in name.chars() {
        if matches!(c, '_' | '^' | '{' | '}' | '\\') {
            out.push('\\');
        }
        out.push(c);
    }
    out
}

/// True for a character a terminal or a text renderer acts on instead of showing: the C0 and C1
/// controls and DEL (`char::is_control`: ESC starts a sequence that can clear the screen or set
/// the title, BEL rings, CR overwrites the line) and the bidirectional embeddings, overrides and
/// isolates U+202A–U+202E and U+2066–U+2069, which reorder the text after them.
#[must_use]
pub fn is_hidden_control(c: char) -> bool {
    c.is_control() || matches!(c, '\u{202A}'..='\u{202E}' | '\u{2066}'..='\u{2069}')
}

/// Text for a terminal (stdout and stderr): every [`is_hidden_control`] character but the line
/// feed and the tab becomes its Rust escape `\u{1b}`, so a name or a path is shown, never
/// executed. Scene names cannot hold them (the loader refuses them); this keeps the rest — an
/// unknown key, a file name, an `--object` argument — from acting on the terminal too.
#[must_use]
pub fn terminal_text(s: &str) -> String {
    if !s.chars().any(|c| is_hidden_control(c) && c != '\n' && c != '\t') {
        return s.to_owned();
    }
    s.chars()
        .map(|c| {
            if is_hidden_control(c) && c != '\n' && c != '\t' {
                c.escape_unicode().to_string()
            } else {
                c.to_string()
            }
        })
        .collect()
}

/// JSON text for a terminal: serde_json escapes C0 controls but writes DEL, the C1 controls and the
/// bidirectional characters raw; each becomes `\uXXXX`. Outside strings JSON holds none of them, so
/// the text stays valid JSON and reads back the same.
#[must_use]
pub fn json_text(json: &str) -> String {
    if !json.chars().any(is_hidden_control) {
        return json.to_owned();
    }
    json.chars()
        .map(|c| {
            // A raw C0 control (a line feed of pretty printing) is whitespace outside strings.
            if is_hidden_control(c) && u32::from(c) > 0x1F {
                format!("\\u{:04x}", u32::from(c))
            } else {
                c.to_string()
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn control_and_bidirectional_characters_are_shown_not_executed() {
        assert_eq!(terminal_text("a\u{1b}]0;t\u{7}b\rc\n\td"), "a\\u{1b}]0;t\\u{7}b\\u{d}c\n\td");
        assert_eq!(terminal_text("x\u{202e}y\u{2066}\u{9b}"), "x\\u{202e}y\\u{2066}\\u{9b}");
        assert_eq!(terminal_text("oglindă ── P → T₁"), "oglindă ── P → T₁");
        let json = serde_json::json!({ "name": "a\u{202e}b\u{1b}\u{9b}\u{7f}" });
        let text = json_text(&serde_json::to_string_pretty(&json).unwrap());
        assert_eq!(text, "{\n  \"name\": \"a\\u202eb\\u001b\\u009b\\u007f\"\n}");
        assert_eq!(serde_json::from_str::<serde_json::Value>(&text).unwrap(), json);
    }

    #[test]
    fn numbers_for_slides() {
        assert_eq!(slide_number(0.5), "0.5");
        assert_eq!(slide_number(-0.0001), "−1.0·10^{−4}");
        assert_eq!(slide_number(2.5e-7), "2.5·10^{−7}");
        assert_eq!(slide_number(-1.23456), "−1.235");
        assert_eq!(slide_number(123.456), "123.5");
        assert_eq!(slide_number(f64::INFINITY), "∞");
        assert_eq!(slide_number(f64::NEG_INFINITY), "−∞");
    }

    #[test]
    fn numbers_for_narrations() {
        assert_eq!(narration_number(-0.0), "0");
        assert_eq!(narration_number(1.0 / 3.0), "0.333333");
        assert_eq!(narration_number(-1234.5678), "−1234.57");
        assert_eq!(narration_number(2.0), "2");
        assert_eq!(narration_number(1e-5), "1.00000e−5");
        assert_eq!(narration_number(f64::NEG_INFINITY), "−∞");
    }

    #[test]
    fn numbers_as_written() {
        assert_eq!(as_written(-1.0), "-1");
        assert_eq!(as_written(0.5), "0.5");
        assert_eq!(as_written(1e100), "1e100");
        assert_eq!(as_written(1e-6), "1e-6");
        assert_eq!(as_written(0.0), "0");
    }

    #[test]
    fn escapes() {
        assert_eq!(
            html_escape("<a href=\"x\">R & T</a>'"),
            "&lt;a href=&quot;x&quot;&gt;R &amp; T&lt;/a&gt;'"
        );
        assert_eq!(markup_escape("glass_ball^2"), "glass\\_ball\\^2");
        assert_eq!(markup_escape("{a}\\"), "\\{a\\}\\\\");
    }
}
