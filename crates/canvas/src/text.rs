//! Label text: the embedded fonts, the sub/superscript markup of the lecture's notation, measuring
//! for layout, and glyph outlines in pixels for a back end to fill (tiny-skia draws no text).
//!
//! # Fonts
//!
//! Noto Sans (Regular and Bold) and, for the arrows and operators it lacks (→ − ≤ ∈ …), Noto Sans
//! Math: subsets of the OFL-licensed files, embedded from `assets/fonts/` (see the README and
//! `OFL.txt` there). They cover Romanian (ă â î ș ț and capitals), Greek (θ η λ Δ …) and the
//! Unicode sub- and superscripts (₁ ₂ ᵢ ₜ ₓ ₑ …).
//!
//! # Markup
//!
//! A label is written as the lecture writes it, with TeX-like scripts:
//! `n_1` → n₁, `θ_i` → θᵢ, `t_{ex}` → t with subscript "ex", `(N·H)^n` → superscript n.
//! `_` and `^` take one character, or a `{…}` group (not nested); `\` makes the next character
//! literal (`\_`, `\^`, `\{`, `\\`). Scripts are drawn at [`Script::scale`] of the size and
//! shifted by [`Script::shift`]. A Unicode sub- or superscript character (₁, ᵢ, ⁿ) is drawn with
//! the font's own glyph; one the fonts lack (ⱼ) falls back to its base letter, drawn small and
//! lowered.
//!
//! There is no shaping beyond advances: the fonts carry their kerning in GPOS, which `ab_glyph`
//! does not read, so pairs are not kerned. Labels are short, and this does not show.

use std::cell::RefCell;
use std::collections::HashMap;
use std::sync::OnceLock;

use ab_glyph::{Font, FontRef, GlyphId, OutlineCurve};
use glam::DVec2;

/// The family name of the embedded font, as SVG's `font-family` names it.
pub const FAMILY: &str = "Noto Sans";
/// The family name of the embedded fallback face for arrows and operators.
pub const MATH_FAMILY: &str = "Noto Sans Math";

/// A text line placed in canvas pixels.
#[derive(Clone, Debug, PartialEq)]
pub struct PlacedLine {
    /// The markup.
    pub text: String,
    /// The start of the baseline, in pixels.
    pub origin: DVec2,
    /// Font size in pixels.
    pub size: f64,
}

/// Line spacing of stacked text lines, in em.
pub const LINE_SPACING: f64 = 1.3;

/// The regular face (a subset of Noto Sans Regular 2.004).
static REGULAR_TTF: &[u8] = include_bytes!("../../../assets/fonts/NotoSans-Regular-subset.ttf");
/// The bold face (a subset of Noto Sans Bold 2.004).
static BOLD_TTF: &[u8] = include_bytes!("../../../assets/fonts/NotoSans-Bold-subset.ttf");
/// Arrows and mathematical operators (a subset of Noto Sans Math).
static MATH_TTF: &[u8] = include_bytes!("../../../assets/fonts/NotoSansMath-Regular-subset.ttf");

/// The weight of a piece of text.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Weight {
    /// Labels, legend and captions.
    Regular,
    /// Titles.
    Bold,
}

/// Where a run of text sits relative to the baseline.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Script {
    /// On the baseline, at full size.
    Normal,
    /// A subscript: smaller and lowered (`n_1`).
    Sub,
    /// A superscript: smaller and raised (`x^2`).
    Super,
}

impl Script {
    /// The size of this script relative to the text's size.
    #[must_use]
    pub const fn scale(self) -> f64 {
        match self {
            Self::Normal => 1.0,
            Self::Sub | Self::Super => 0.7,
        }
    }

    /// The baseline shift in em of the text's size, positive upwards.
    #[must_use]
    pub const fn shift(self) -> f64 {
        match self {
            Self::Normal => 0.0,
            Self::Sub => -0.2,
            Self::Super => 0.36,
        }
    }
}

/// A stretch of text in one script, after the markup has been read.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Run {
    /// The characters, with the markup removed.
    pub text: String,
    /// Where they sit.
    pub script: Script,
}

/// The three embedded faces, parsed once.
struct Faces {
    regular: FontRef<'static>,
    bold: FontRef<'static>,
    math: FontRef<'static>,
}

/// The parsed faces. The embedded files are fixed at compile time and a test parses them, so a
/// failure here is a broken build, not a runtime condition.
fn faces() -> &'static Faces {
    static FACES: OnceLock<Faces> = OnceLock::new();
    FACES.get_or_init(|| Faces {
        regular: FontRef::try_from_slice(REGULAR_TTF).expect("embedded Noto Sans Regular parses"),
        bold: FontRef::try_from_slice(BOLD_TTF).expect("embedded Noto Sans Bold parses"),
        math: FontRef::try_from_slice(MATH_TTF).expect("embedded Noto Sans Math parses"),
    })
}

/// The main face of a weight (Noto Sans Regular or Bold).
#[must_use]
pub fn font(weight: Weight) -> &'static FontRef<'static> {
    match weight {
        Weight::Regular => &faces().regular,
        Weight::Bold => &faces().bold,
    }
}

/// The fallback face for arrows and mathematical operators (Noto Sans Math).
#[must_use]
pub fn math_font() -> &'static FontRef<'static> {
    &faces().math
}

/// Which embedded face a glyph comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Face {
    /// Noto Sans Regular.
    Regular,
    /// Noto Sans Bold.
    Bold,
    /// Noto Sans Math.
    Math,
}

impl Face {
    /// The parsed font of this face.
    #[must_use]
    pub fn font(self) -> &'static FontRef<'static> {
        match self {
            Self::Regular => font(Weight::Regular),
            Self::Bold => font(Weight::Bold),
            Self::Math => math_font(),
        }
    }

    /// Font units per em (1000 for Noto Sans, which is what a broken table would also give).
    fn units_per_em(self) -> f64 {
        f64::from(self.font().units_per_em().unwrap_or(1000.0))
    }
}

/// The face and glyph that draw `c` at `weight`: the main face if it has the character, else the
/// math face, else the main face's missing-glyph box (glyph 0).
fn resolve(c: char, weight: Weight) -> (Face, GlyphId) {
    let main = match weight {
        Weight::Regular => Face::Regular,
        Weight::Bold => Face::Bold,
    };
    let id = main.font().glyph_id(c);
    if id.0 != 0 {
        return (main, id);
    }
    let id = math_font().glyph_id(c);
    if id.0 != 0 {
        return (Face::Math, id);
    }
    (main, GlyphId(0))
}

/// The face whose glyph draws `c` at `weight` (the main face for a character no face has).
#[must_use]
pub fn face_of(c: char, weight: Weight) -> Face {
    resolve(c, weight).0
}

/// The embedded file of a face (the SVG back end embeds a subset of it).
#[must_use]
pub fn face_file(face: Face) -> &'static [u8] {
    match face {
        Face::Regular => REGULAR_TTF,
        Face::Bold => BOLD_TTF,
        Face::Math => MATH_TTF,
    }
}

/// The file of Noto Sans Regular, embedded.
#[cfg(test)]
pub(crate) fn regular_ttf() -> &'static [u8] {
    REGULAR_TTF
}

/// The file of Noto Sans Math, embedded.
#[cfg(test)]
pub(crate) fn math_ttf() -> &'static [u8] {
    MATH_TTF
}

/// Whether the embedded fonts draw `c` with a real glyph (not the missing-glyph box), directly or
/// through the sub/superscript fallback.
#[must_use]
pub fn has_glyph(c: char) -> bool {
    resolve(c, Weight::Regular).1 .0 != 0
        || script_base(c).is_some_and(|(_, base)| resolve(base, Weight::Regular).1 .0 != 0)
}

/// Whether `c` is a Unicode sub- or superscript character (`₁`, `ᵢ`, `²`): drawn with the font's
/// own glyph when the font has one, so it looks unlike the markup's scripts (`t_1`, `r^2`: the
/// base character smaller and moved); figure texts write the markup instead.
#[must_use]
pub fn is_script_character(c: char) -> bool {
    script_base(c).is_some()
}

/// The base character and script of a Unicode sub- or superscript character (`₁` → `1` below).
fn script_base(c: char) -> Option<(Script, char)> {
    let sub = |b| Some((Script::Sub, b));
    let sup = |b| Some((Script::Super, b));
    match c {
        '\u{2080}'..='\u{2089}' => sub(char::from_digit(u32::from(c) - 0x2080, 10)?),
        '₊' => sub('+'),
        '₋' => sub('−'),
        '₌' => sub('='),
        '₍' => sub('('),
        '₎' => sub(')'),
        'ₐ' => sub('a'),
        'ₑ' => sub('e'),
        'ₒ' => sub('o'),
        'ₓ' => sub('x'),
        'ₔ' => sub('ə'),
        'ₕ' => sub('h'),
        'ₖ' => sub('k'),
        'ₗ' => sub('l'),
        'ₘ' => sub('m'),
        'ₙ' => sub('n'),
        'ₚ' => sub('p'),
        'ₛ' => sub('s'),
        'ₜ' => sub('t'),
        'ᵢ' => sub('i'),
        'ᵣ' => sub('r'),
        'ᵤ' => sub('u'),
        'ᵥ' => sub('v'),
        'ⱼ' => sub('j'),
        'ᵦ' => sub('β'),
        'ᵧ' => sub('γ'),
        'ᵨ' => sub('ρ'),
        'ᵩ' => sub('φ'),
        'ᵪ' => sub('χ'),
        '⁰' => sup('0'),
        '¹' => sup('1'),
        '²' => sup('2'),
        '³' => sup('3'),
        '\u{2074}'..='\u{2079}' => sup(char::from_digit(u32::from(c) - 0x2070, 10)?),
        '⁺' => sup('+'),
        '⁻' => sup('−'),
        '⁼' => sup('='),
        '⁽' => sup('('),
        '⁾' => sup(')'),
        'ⁿ' => sup('n'),
        'ⁱ' => sup('i'),
        _ => None,
    }
}

/// Reads the markup into runs (see the module doc), without looking at the fonts.
#[must_use]
pub fn parse(markup: &str) -> Vec<Run> {
    let mut runs = Vec::new();
    let mut chars = markup.chars().peekable();
    while let Some(c) = chars.next() {
        let script = match c {
            '\\' => {
                // A backslash makes the next character literal; a trailing one is itself.
                push(&mut runs, Script::Normal, chars.next().unwrap_or('\\'));
                continue;
            }
            '_' => Script::Sub,
            '^' => Script::Super,
            _ => {
                push(&mut runs, Script::Normal, c);
                continue;
            }
        };
        match chars.next() {
            // A group runs to the next closing brace (or the end of the text).
            Some('{') => {
                for g in chars.by_ref() {
                    if g == '}' {
                        break;
                    }
                    push(&mut runs, script, g);
                }
            }
            Some('\\') => push(&mut runs, script, chars.next().unwrap_or('\\')),
            Some(next) => push(&mut runs, script, next),
            // A marker at the very end is an ordinary character.
            None => push(&mut runs, Script::Normal, c),
        }
    }
    runs
}

/// Appends `c` in `script`, extending the last run when its script matches.
fn push(runs: &mut Vec<Run>, script: Script, c: char) {
    match runs.last_mut() {
        Some(last) if last.script == script => last.text.push(c),
        _ => runs.push(Run { text: c.to_string(), script }),
    }
}

/// The runs to display: [`parse`], then every Unicode sub/superscript character the fonts lack
/// becomes its base character in a script run (only on the baseline; a script is not scripted
/// twice). Both back ends draw these runs, so PNG and SVG agree.
#[must_use]
pub fn runs(markup: &str, weight: Weight) -> Vec<Run> {
    let mut out = Vec::new();
    for run in parse(markup) {
        for c in run.text.chars() {
            match script_base(c) {
                Some((script, base)) if run.script == Script::Normal && resolve(c, weight).1 .0 == 0 => {
                    push(&mut out, script, base);
                }
                _ => push(&mut out, run.script, c),
            }
        }
    }
    out
}

/// One glyph placed by [`layout`], in pixels relative to the start of the baseline.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlacedGlyph {
    /// The face the glyph is taken from.
    pub face: Face,
    /// The glyph in that face.
    pub id: GlyphId,
    /// The pen position along the baseline, in pixels.
    pub x: f64,
    /// The baseline shift, in pixels, positive upwards.
    pub rise: f64,
    /// The font size (em) the glyph is drawn at, in pixels.
    pub size: f64,
}

/// A line of text laid out at a size: its glyphs and its box.
#[derive(Clone, Debug, PartialEq)]
pub struct TextLayout {
    /// The glyphs, left to right.
    pub glyphs: Vec<PlacedGlyph>,
    /// The advance width, in pixels.
    pub width: f64,
    /// Height of the box above the baseline, in pixels (the font's ascent, or a superscript's top).
    pub ascent: f64,
    /// Depth of the box below the baseline, in pixels, positive (the font's descent, or a
    /// subscript's bottom).
    pub descent: f64,
}

impl TextLayout {
    /// The box's height, ascent + descent.
    #[must_use]
    pub fn height(&self) -> f64 {
        self.ascent + self.descent
    }

    /// How far the glyphs' ink reaches above and below the baseline, in pixels, `(above, below)`
    /// (below positive): the outlines' own bounds, raised or lowered with their script. Tighter
    /// than the box, whose ascent and descent are the font's for every line, so two lines set one
    /// under the other share box but never ink. `(0, 0)` for a line without ink.
    #[must_use]
    pub fn ink(&self) -> (f64, f64) {
        self.glyphs
            .iter()
            .filter_map(|g| {
                let (lo, hi) = vertical_bounds(g.face, g.id)?;
                let scale = g.size / g.face.units_per_em();
                Some((g.rise + hi * scale, -(g.rise + lo * scale)))
            })
            .fold(None, |acc: Option<(f64, f64)>, (a, b)| {
                Some(acc.map_or((a, b), |(x, y)| (x.max(a), y.max(b))))
            })
            .unwrap_or((0.0, 0.0))
    }
}

/// A vertical extent `(lowest, highest)`.
type Span = (f64, f64);

/// A glyph's outline from its lowest to its highest point, in font units, y up; `None` for a
/// glyph without an outline (a space). Read from the font once per glyph and thread: label
/// placement asks for the ink of every candidate spot.
fn vertical_bounds(face: Face, id: GlyphId) -> Option<Span> {
    thread_local! {
        static BOUNDS: RefCell<HashMap<(Face, u16), Option<Span>>> = RefCell::new(HashMap::new());
    }
    BOUNDS.with(|cache| {
        *cache.borrow_mut().entry((face, id.0)).or_insert_with(|| {
            let b = face.font().outline(id)?.bounds;
            Some((f64::from(b.min.y.min(b.max.y)), f64::from(b.min.y.max(b.max.y))))
        })
    })
}

/// At most this many layouts are kept per thread by [`layout`]; past it the memory starts over.
const LAYOUT_CACHE_ENTRIES: usize = 4096;

/// Lays out one line of markup at font size `size` (em, pixels). The same line at the same size
/// and weight is laid out once per thread and then copied: placing a label measures it at every
/// candidate spot.
#[must_use]
pub fn layout(markup: &str, size: f64, weight: Weight) -> TextLayout {
    thread_local! {
        static LAID: RefCell<HashMap<(String, u64, Weight), TextLayout>> = RefCell::new(HashMap::new());
    }
    LAID.with(|cache| {
        let mut cache = cache.borrow_mut();
        let key = (markup.to_owned(), size.to_bits(), weight);
        if let Some(laid) = cache.get(&key) {
            return laid.clone();
        }
        if cache.len() >= LAYOUT_CACHE_ENTRIES {
            cache.clear();
        }
        let laid = lay_out(markup, size, weight);
        cache.insert(key, laid.clone());
        laid
    })
}

/// [`layout`] without the memory: the glyphs of each run, advanced along the baseline.
fn lay_out(markup: &str, size: f64, weight: Weight) -> TextLayout {
    let main = font(weight);
    let units = f64::from(main.units_per_em().unwrap_or(1000.0));
    let line_ascent = f64::from(main.ascent_unscaled()) / units;
    let line_descent = -f64::from(main.descent_unscaled()) / units;
    let mut ascent = line_ascent * size;
    let mut descent = line_descent * size;
    let mut glyphs = Vec::new();
    let mut x = 0.0;
    for run in runs(markup, weight) {
        let run_size = size * run.script.scale();
        let rise = size * run.script.shift();
        ascent = ascent.max(rise + line_ascent * run_size);
        descent = descent.max(-rise + line_descent * run_size);
        for c in run.text.chars() {
            let (face, id) = resolve(c, weight);
            glyphs.push(PlacedGlyph { face, id, x, rise, size: run_size });
            let advance = f64::from(face.font().h_advance_unscaled(id));
            x += advance * run_size / face.units_per_em();
        }
    }
    TextLayout { glyphs, width: x, ascent, descent }
}

/// The width and height in pixels of one line of regular-weight markup at font size `size`
/// (the height is the font's ascent + descent, taller than the ink, so boxes of stacked lines
/// do not touch).
#[must_use]
pub fn measure(markup: &str, size: f64) -> (f64, f64) {
    let laid = layout(markup, size, Weight::Regular);
    (laid.width, laid.height())
}

/// The height of a capital letter (the top of "H") at font size `size`, in pixels: what
/// vertical centring on a point aligns to.
#[must_use]
pub fn cap_height(size: f64) -> f64 {
    let face = Face::Regular;
    let h = face.font().glyph_id('H');
    // ab_glyph keeps the unscaled top in `bounds.min.y`; take the larger so either order works.
    let top = face.font().outline(h).map_or(714.0, |o| f64::from(o.bounds.min.y.max(o.bounds.max.y)));
    top * size / face.units_per_em()
}

/// Splits markup into lines no wider than `max_width` pixels at `size`, breaking at spaces outside
/// `{…}` groups, but never beside a relation (`K = 2`, `16 × 10` stay on one line). A word wider
/// than the limit gets a line of its own.
#[must_use]
pub fn wrap(markup: &str, size: f64, weight: Weight, max_width: f64) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    let mut line = String::new();
    for word in unbreakable(words(markup)) {
        let candidate = if line.is_empty() { word.clone() } else { format!("{line} {word}") };
        if line.is_empty() || layout(&candidate, size, weight).width <= max_width {
            line = candidate;
        } else {
            lines.push(std::mem::replace(&mut line, word));
        }
    }
    if !line.is_empty() || lines.is_empty() {
        lines.push(line);
    }
    lines
}

/// How close the balanced width of [`wrap_even`] gets to the narrowest that keeps the line count,
/// in pixels.
const EVEN_WIDTH_STEP: f64 = 1.0;

/// [`wrap`] into as few lines, made as even as they can be: the narrowest width (to
/// [`EVEN_WIDTH_STEP`]) at which [`wrap`] still needs no more lines, found by bisection. A caption
/// never ends on an orphaned word.
#[must_use]
pub fn wrap_even(markup: &str, size: f64, weight: Weight, max_width: f64) -> Vec<String> {
    let greedy = wrap(markup, size, weight, max_width);
    let (mut narrow, mut wide) = (0.0, max_width);
    while wide - narrow > EVEN_WIDTH_STEP {
        let mid = 0.5 * (narrow + wide);
        if wrap(markup, size, weight, mid).len() > greedy.len() {
            narrow = mid;
        } else {
            wide = mid;
        }
    }
    wrap(markup, size, weight, wide)
}

/// Symbols that bind the words on both sides: a line never ends or starts with one.
const RELATIONS: [&str; 8] = ["=", "<", ">", "≤", "≥", "≠", "≈", "×"];

/// The dot that separates a caption's items: it binds to the word before it, so a line may end
/// with one and never starts with one.
const SEPARATOR: &str = "·";

/// `words` with every relation joined to its neighbours (`["K", "=", "2"]` → `["K = 2"]`), a
/// name ending in a colon joined to the number after it (`["opened:", "6"]` → `["opened: 6"]`),
/// the words of a formula's open bracket joined up to its close (`["2D·(O", "−", "C),"]` →
/// `["2D·(O − C),"]`: a formula's bracket is never cut, [`open_parentheses`]), and the
/// [`SEPARATOR`] joined to the word before it (`["40", "·", "grid"]` → `["40 ·", "grid"]`).
fn unbreakable(words: Vec<String>) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    let mut bind_next = false;
    for word in words {
        let relation = RELATIONS.contains(&word.as_str());
        let value = word.starts_with(|c: char| c.is_ascii_digit())
            && out.last().is_some_and(|last| last.ends_with(':'));
        match out.last_mut() {
            Some(last) if relation || bind_next || value || word == SEPARATOR => {
                last.push(' ');
                last.push_str(&word);
            }
            _ => out.push(word),
        }
        let open = out.last().is_some_and(|last| open_parentheses(last) > 0);
        bind_next = relation || open;
    }
    out
}

/// How many brackets of a formula are still open at the end of `word`: a `(` right after
/// another character (`2D·(O`, `min(t₁,`), not one that opens a word (a prose aside, `(picked:
/// …)`, may wrap); never below 0.
fn open_parentheses(word: &str) -> usize {
    let mut depth = 0_usize;
    let mut previous = None;
    for c in word.chars() {
        match c {
            '(' if previous.is_some_and(|p: char| !p.is_whitespace()) => depth += 1,
            ')' => depth = depth.saturating_sub(1),
            _ => {}
        }
        previous = Some(c);
    }
    depth
}

/// The space-separated words of markup, keeping `{…}` groups and escaped spaces whole.
fn words(markup: &str) -> Vec<String> {
    let mut words = Vec::new();
    let mut word = String::new();
    let mut depth = 0_u32;
    let mut escaped = false;
    for c in markup.chars() {
        if escaped {
            escaped = false;
        } else if c == '\\' {
            escaped = true;
        } else if c == '{' {
            depth += 1;
        } else if c == '}' {
            depth = depth.saturating_sub(1);
        } else if c == ' ' && depth == 0 {
            if !word.is_empty() {
                words.push(std::mem::take(&mut word));
            }
            continue;
        }
        word.push(c);
    }
    if !word.is_empty() {
        words.push(word);
    }
    words
}

/// Receives glyph outlines in pixel coordinates (y down), contour by contour.
pub trait PathSink {
    /// Starts a contour at `p`.
    fn move_to(&mut self, p: DVec2);
    /// A straight edge to `p`.
    fn line_to(&mut self, p: DVec2);
    /// A quadratic Bézier through control `c` to `p`.
    fn quad_to(&mut self, c: DVec2, p: DVec2);
    /// A cubic Bézier through controls `c1`, `c2` to `p`.
    fn cubic_to(&mut self, c1: DVec2, c2: DVec2, p: DVec2);
    /// Closes the current contour.
    fn close(&mut self);
}

/// Sends the outlines of `laid`, with its baseline starting at pixel `origin` (y down), to `sink`.
/// Glyphs without outlines (spaces) send nothing.
pub fn outline(laid: &TextLayout, origin: DVec2, sink: &mut impl PathSink) {
    for g in &laid.glyphs {
        let Some(shape) = g.face.font().outline(g.id) else {
            continue;
        };
        let k = g.size / g.face.units_per_em();
        let at = |p: ab_glyph::Point| {
            DVec2::new(origin.x + g.x + f64::from(p.x) * k, origin.y - g.rise - f64::from(p.y) * k)
        };
        // Curves come as one flat list; a contour ends where the next curve does not start at
        // the previous curve's end.
        let mut last_end: Option<ab_glyph::Point> = None;
        for curve in &shape.curves {
            let (start, end) = match *curve {
                OutlineCurve::Line(a, b) | OutlineCurve::Quad(a, _, b) => (a, b),
                OutlineCurve::Cubic(a, _, _, b) => (a, b),
            };
            let continues =
                last_end.is_some_and(|e| (e.x - start.x).abs() < 1e-3 && (e.y - start.y).abs() < 1e-3);
            if !continues {
                if last_end.is_some() {
                    sink.close();
                }
                sink.move_to(at(start));
            }
            match *curve {
                OutlineCurve::Line(_, b) => sink.line_to(at(b)),
                OutlineCurve::Quad(_, c, b) => sink.quad_to(at(c), at(b)),
                OutlineCurve::Cubic(_, c1, c2, b) => sink.cubic_to(at(c1), at(c2), at(b)),
            }
            last_end = Some(end);
        }
        if last_end.is_some() {
            sink.close();
        }
    }
}

#[cfg(test)]
// These tests pin exact IEEE results on purpose (numerics.md gives bit-exact expectations).
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;

    #[test]
    fn ink_reaches_the_cap_height_and_the_descenders_only() {
        let size = 100.0;
        let (above, below) = layout("H", size, Weight::Regular).ink();
        assert!((above - cap_height(size)).abs() < 0.5 && below.abs() < 0.5, "{above} {below}");
        let (_, below_g) = layout("g", size, Weight::Regular).ink();
        assert!(below_g > 15.0, "{below_g}");
        // A subscript goes lower than the letter it follows, and inside the box.
        let sub = layout("N_1", size, Weight::Regular);
        let (above_n, below_n) = sub.ink();
        assert!(below_n > 5.0 && below_n < sub.descent && above_n < sub.ascent, "{below_n} {}", sub.descent);
        assert_eq!(layout(" ", size, Weight::Regular).ink(), (0.0, 0.0));
    }

    /// Counts what a sink receives.
    #[derive(Default)]
    struct Count {
        contours: usize,
        segments: usize,
        min: Option<DVec2>,
        max: Option<DVec2>,
    }

    impl Count {
        fn see(&mut self, p: DVec2) {
            self.min = Some(self.min.map_or(p, |m| m.min(p)));
            self.max = Some(self.max.map_or(p, |m| m.max(p)));
        }
    }

    impl PathSink for Count {
        fn move_to(&mut self, p: DVec2) {
            self.contours += 1;
            self.see(p);
        }
        fn line_to(&mut self, p: DVec2) {
            self.segments += 1;
            self.see(p);
        }
        fn quad_to(&mut self, c: DVec2, p: DVec2) {
            self.segments += 1;
            self.see(c);
            self.see(p);
        }
        fn cubic_to(&mut self, c1: DVec2, c2: DVec2, p: DVec2) {
            self.segments += 1;
            self.see(c1);
            self.see(c2);
            self.see(p);
        }
        fn close(&mut self) {}
    }

    #[test]
    fn embedded_fonts_parse_and_name_themselves() {
        assert!(font(Weight::Regular).glyph_count() > 500);
        assert!(font(Weight::Bold).glyph_count() > 500);
        assert!(math_font().glyph_count() > 100);
    }

    #[test]
    fn lecture_characters_have_real_glyphs() {
        let needed = "ăâîșțĂÂÎȘȚşţ θηλΔαβγφπρ ₀₁₂ᵢₜₓₑₛ ⁿ²·×→−≤≥ N·L (u, v) Rază reflectată";
        for c in needed.chars().filter(|c| !c.is_whitespace()) {
            assert!(has_glyph(c), "no glyph for {c:?} (U+{:04X})", u32::from(c));
        }
        // The direct check of the brief: the main face itself has these.
        for c in "ăâîșțθn1".chars() {
            assert_ne!(font(Weight::Regular).glyph_id(c).0, 0, "{c:?}");
        }
    }

    #[test]
    fn markup_makes_scripts() {
        let sub = |t: &str| Run { text: t.into(), script: Script::Sub };
        let normal = |t: &str| Run { text: t.into(), script: Script::Normal };
        let sup = |t: &str| Run { text: t.into(), script: Script::Super };
        assert_eq!(parse("n_1"), vec![normal("n"), sub("1")]);
        assert_eq!(parse("θ_i"), vec![normal("θ"), sub("i")]);
        assert_eq!(parse("t_{ex} = 2"), vec![normal("t"), sub("ex"), normal(" = 2")]);
        assert_eq!(parse("(N·H)^n"), vec![normal("(N·H)"), sup("n")]);
        assert_eq!(parse("a\\_b"), vec![normal("a_b")]);
        assert_eq!(parse("x_"), vec![normal("x_")]);
        assert_eq!(parse("K_s"), vec![normal("K"), sub("s")]);
    }

    #[test]
    fn missing_unicode_subscripts_fall_back_to_small_base_letters() {
        // ⱼ is not in the embedded subset; ₁ is.
        assert_eq!(resolve('ⱼ', Weight::Regular).1 .0, 0);
        let runs = runs("uⱼ₁", Weight::Regular);
        assert_eq!(
            runs,
            vec![
                Run { text: "u".into(), script: Script::Normal },
                Run { text: "j".into(), script: Script::Sub },
                Run { text: "₁".into(), script: Script::Normal },
            ]
        );
    }

    #[test]
    fn measure_grows_with_text_and_size_and_scripts_are_narrower() {
        let (w1, h1) = measure("n", 40.0);
        let (w2, h2) = measure("nn", 40.0);
        let (w3, _) = measure("n", 80.0);
        assert!(w1 > 0.0 && (w2 - 2.0 * w1).abs() < 1e-9 && (w3 - 2.0 * w1).abs() < 1e-9);
        assert!((h1 - h2).abs() < 1e-9 && h1 > 40.0);
        let (normal, _) = measure("n1", 40.0);
        let (scripted, _) = measure("n_1", 40.0);
        assert!(scripted < normal);
        assert!(cap_height(40.0) > 25.0 && cap_height(40.0) < 32.0);
    }

    #[test]
    fn every_character_of_a_label_has_ink() {
        let label = "ă â î ș ț θ n_1";
        let laid = layout(label, 40.0, Weight::Regular);
        for g in &laid.glyphs {
            let space = g.face.font().glyph_id(' ');
            if g.id == space {
                continue;
            }
            assert_ne!(g.id.0, 0);
            let mut count = Count::default();
            let one = TextLayout { glyphs: vec![*g], ..laid.clone() };
            outline(&one, DVec2::new(0.0, 100.0), &mut count);
            assert!(count.contours > 0 && count.segments > 2, "{g:?}");
        }
    }

    #[test]
    fn outlines_sit_on_the_baseline_and_subscripts_go_lower() {
        let mut normal = Count::default();
        outline(&layout("n", 40.0, Weight::Regular), DVec2::new(10.0, 100.0), &mut normal);
        let (min, max) = (normal.min.unwrap(), normal.max.unwrap());
        assert!(min.x >= 10.0 && max.y <= 100.5 && min.y < 85.0);
        let mut sub = Count::default();
        outline(&layout("_n", 40.0, Weight::Regular), DVec2::new(10.0, 100.0), &mut sub);
        assert!(sub.max.unwrap().y > 105.0);
    }

    #[test]
    fn wrapping_breaks_at_spaces_outside_groups() {
        let lines = wrap("one two three t_{a b}", 40.0, Weight::Regular, 130.0);
        assert!(lines.len() >= 3, "{lines:?}");
        assert!(lines.iter().any(|l| l.contains("t_{a b}")));
        assert_eq!(wrap("", 40.0, Weight::Regular, 10.0), vec![String::new()]);
    }

    #[test]
    fn even_wrapping_leaves_no_orphan_and_no_more_lines() {
        let caption = "scene whitted · reference: the same sampling, traced deeper · times in the table";
        let width = layout(caption, 40.0, Weight::Regular).width;
        // Just narrower than the whole: greedy leaves one word alone on the second line.
        let greedy = wrap(caption, 40.0, Weight::Regular, width - 5.0);
        assert_eq!(greedy.len(), 2);
        assert!(!greedy[1].contains(' '), "{greedy:?}");
        let even = wrap_even(caption, 40.0, Weight::Regular, width - 5.0);
        assert_eq!(even.len(), 2);
        let widths: Vec<f64> = even.iter().map(|l| layout(l, 40.0, Weight::Regular).width).collect();
        assert!(widths[1] > 0.6 * widths[0], "{even:?}");
    }

    #[test]
    fn wrapping_keeps_a_count_with_its_name() {
        let lines = wrap("noduri testate: 11, deschise: 6", 40.0, Weight::Regular, 10.0);
        assert!(lines.contains(&"deschise: 6".to_owned()), "{lines:?}");
        assert!(lines.contains(&"testate: 11,".to_owned()), "{lines:?}");
    }

    #[test]
    fn wrapping_keeps_a_relation_with_both_its_sides() {
        // Narrow enough to break at every space otherwise.
        let lines = wrap("pragul = 0.1, K = 2 · grila 16 × 10", 40.0, Weight::Regular, 10.0);
        assert_eq!(lines, ["pragul = 0.1,", "K = 2 ·", "grila", "16 × 10"]);
        assert_eq!(unbreakable(words("= a")), ["= a"], "a leading relation binds what follows");
    }

    #[test]
    fn wrapping_never_cuts_a_bracket() {
        // The Romanian discriminant caption broke as "cu b = 2D·(O" / "− C), c = …".
        let lines = wrap("cu b = 2D·(O − C), c = |O − C|² − r²", 40.0, Weight::Regular, 10.0);
        assert!(lines.contains(&"b = 2D·(O − C),".to_owned()), "{lines:?}");
        assert_eq!(unbreakable(words("f(b c) d")), ["f(b c)", "d"]);
        assert_eq!(unbreakable(words("a (b c) d")), ["a", "(b", "c)", "d"], "a prose aside may wrap");
        assert_eq!(unbreakable(words("x) y")), ["x)", "y"], "a stray close opens nothing");
    }

    #[test]
    fn no_wrapped_line_starts_with_the_separator() {
        // The Romanian grid caption's second line began with "·".
        assert_eq!(unbreakable(words("mult) · grila 7 × 4")), ["mult) ·", "grila", "7 × 4"]);
        for width in [40.0, 80.0, 120.0, 200.0] {
            let lines = wrap("a b · c d · e f · g", 20.0, Weight::Regular, width);
            assert!(lines.iter().all(|l| !l.starts_with(SEPARATOR)), "{width}: {lines:?}");
        }
    }
}
