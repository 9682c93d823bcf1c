//! The JSON tree the input files (scenes, lessons) are read from: a compact, borrowed stand-in
//! for `serde_json::Value` that keeps what a reader of untrusted files needs to say exactly.
//!
//! - **Every key, in file order, duplicates included.** [`Map::duplicates`] lists the keys that
//!   occur twice, so that the reader names them with their path instead of letting one value
//!   silently win.
//! - **Strings borrow the file's text** where they hold no escape, and an object is a plain list
//!   of pairs (no hash table), so a scene's tree stays within a few times its file's size (the
//!   hashed, owned `serde_json::Value` took sixteen).
//! - **A UTF-8 byte-order mark is skipped** (editors write one), and the nesting depth is
//!   serde_json's (128), so a hostile file cannot overflow the stack.
//!
//! [`reader`] reads such a tree field by field and collects every problem with its path: the
//! scene loader and the lesson reader share it, so both word their errors alike.

pub mod reader;

use serde::de::{self, Deserialize, DeserializeSeed, Deserializer, MapAccess, SeqAccess, Visitor};
use serde_json::value::RawValue;
use std::borrow::Cow;
use std::fmt;

/// A JSON value, borrowing its strings from the text it was parsed from.
#[derive(Clone, Debug, PartialEq)]
pub enum Value<'a> {
    /// `null`.
    Null,
    /// `true` or `false`.
    Bool(bool),
    /// A number, integer or not.
    Number(Number),
    /// A string.
    String(Cow<'a, str>),
    /// An array.
    Array(Vec<Value<'a>>),
    /// An object: its pairs in file order.
    Object(Map<'a>),
    /// A value not parsed yet, checked as JSON ([`parse_deferring`]): the reader parses it when
    /// it comes to it and drops its tree after, so a long list never lives as a tree all at once.
    Deferred(&'a str),
}

/// A JSON number as written: a whole number keeps its integer value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Number {
    /// A whole number ≥ 0.
    Unsigned(u64),
    /// A negative whole number.
    Signed(i64),
    /// Any other number.
    Float(f64),
}

/// An object's pairs in file order; a key written twice appears twice.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Map<'a> {
    pairs: Vec<(Cow<'a, str>, Value<'a>)>,
}

/// Why a text is not JSON: serde_json's message, and where.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SyntaxError {
    /// What is wrong (without the position).
    pub message: String,
    /// The line, from 1.
    pub line: usize,
    /// The column, from 1.
    pub column: usize,
}

/// The byte-order mark some editors write at the start of a UTF-8 file.
const BYTE_ORDER_MARK: char = '\u{feff}';

/// Parses `text` (a leading byte-order mark skipped) into a [`Value`] that borrows from it.
///
/// # Errors
/// The first syntax error, with its line and column.
pub fn parse(text: &str) -> Result<Value<'_>, SyntaxError> {
    let text = text.strip_prefix(BYTE_ORDER_MARK).unwrap_or(text);
    serde_json::from_str(text).map_err(syntax_error)
}

/// [`parse`], but the items of the top-level array `key` (a scene's `objects`) are left as
/// [`Value::Deferred`] text, checked as JSON but not parsed into a tree: the reader parses each in
/// turn ([`Value::parsed`]), so the file's largest part is never a tree all at once. Any other
/// value under `key` is parsed as usual.
///
/// # Errors
/// The first syntax error, with its line and column.
pub fn parse_deferring<'a>(text: &'a str, key: &str) -> Result<Value<'a>, SyntaxError> {
    let text = text.strip_prefix(BYTE_ORDER_MARK).unwrap_or(text);
    let mut de = serde_json::Deserializer::from_str(text);
    let value = de.deserialize_any(RootVisitor { deferred: key }).and_then(|v| de.end().map(|()| v));
    value.map_err(syntax_error)
}

impl SyntaxError {
    /// The error of a parse of `part`, a slice of `whole`, placed in `whole`: its line counted
    /// from `whole`'s first, and on `part`'s first line its column too (columns count bytes, as
    /// serde_json's do).
    #[must_use]
    pub fn within(self, whole: &str, part: &str) -> Self {
        let offset = (part.as_ptr() as usize).saturating_sub(whole.as_ptr() as usize).min(whole.len());
        let before = &whole.as_bytes()[..offset];
        let lines = before.iter().filter(|b| **b == b'\n').count();
        let column = before.iter().rev().take_while(|b| **b != b'\n').count();
        let column = if self.line == 1 { self.column + column } else { self.column };
        Self { line: self.line + lines, column, ..self }
    }
}

fn syntax_error(e: serde_json::Error) -> SyntaxError {
    let full = e.to_string();
    // serde_json appends " at line L column C"; the position is kept apart.
    let message = full.split(" at line ").next().unwrap_or(&full).to_string();
    SyntaxError { message, line: e.line(), column: e.column() }
}

impl<'a> Value<'a> {
    /// This value, or the tree of a [`Value::Deferred`] one (parsed now; its text is valid JSON).
    ///
    /// # Errors
    /// A syntax error, which a deferred value cannot have but is reported rather than assumed.
    pub fn parsed(&self) -> Result<Cow<'_, Value<'a>>, SyntaxError> {
        match self {
            Self::Deferred(text) => parse(text).map(Cow::Owned),
            other => Ok(Cow::Borrowed(other)),
        }
    }
    /// The object, if this is one.
    #[must_use]
    pub fn as_object(&self) -> Option<&Map<'a>> {
        match self {
            Self::Object(m) => Some(m),
            _ => None,
        }
    }
    /// The array, if this is one.
    #[must_use]
    pub fn as_array(&self) -> Option<&Vec<Value<'a>>> {
        match self {
            Self::Array(a) => Some(a),
            _ => None,
        }
    }
    /// The string, if this is one.
    #[must_use]
    pub fn as_str(&self) -> Option<&str> {
        match self {
            Self::String(s) => Some(s),
            _ => None,
        }
    }
    /// The boolean, if this is one.
    #[must_use]
    pub fn as_bool(&self) -> Option<bool> {
        match self {
            Self::Bool(b) => Some(*b),
            _ => None,
        }
    }
    /// The number as an `f64`, if this is a number.
    #[must_use]
    pub fn as_f64(&self) -> Option<f64> {
        match self {
            Self::Number(n) => Some(n.as_f64()),
            _ => None,
        }
    }
    /// The number, if this is a whole number ≥ 0 written without a fraction or exponent.
    #[must_use]
    pub fn as_u64(&self) -> Option<u64> {
        match self {
            Self::Number(Number::Unsigned(n)) => Some(*n),
            _ => None,
        }
    }
    /// True iff this is a number.
    #[must_use]
    pub fn is_number(&self) -> bool {
        matches!(self, Self::Number(_))
    }
    /// True iff this is `null`.
    #[must_use]
    pub fn is_null(&self) -> bool {
        matches!(self, Self::Null)
    }
    /// The value of `key`, if this is an object that has it (the first, if written twice).
    #[must_use]
    pub fn get(&self, key: &str) -> Option<&Value<'a>> {
        self.as_object()?.get(key)
    }
}

impl Number {
    /// The number as an `f64` (a whole number above 2^53 rounds).
    #[must_use]
    pub fn as_f64(self) -> f64 {
        match self {
            Self::Unsigned(n) => n as f64,
            Self::Signed(n) => n as f64,
            Self::Float(x) => x,
        }
    }
}

impl<'a> Map<'a> {
    /// The value of `key` (the first, if written twice).
    #[must_use]
    pub fn get(&self, key: &str) -> Option<&Value<'a>> {
        self.pairs.iter().find(|(k, _)| k == key).map(|(_, v)| v)
    }
    /// True iff `key` is written.
    #[must_use]
    pub fn contains_key(&self, key: &str) -> bool {
        self.get(key).is_some()
    }
    /// The keys in file order, duplicates included.
    pub fn keys(&self) -> impl Iterator<Item = &str> {
        self.pairs.iter().map(|(k, _)| k.as_ref())
    }
    /// The pairs in file order, duplicates included.
    pub fn iter(&self) -> impl Iterator<Item = (&str, &Value<'a>)> {
        self.pairs.iter().map(|(k, v)| (k.as_ref(), v))
    }
    /// The number of pairs written.
    #[must_use]
    pub fn len(&self) -> usize {
        self.pairs.len()
    }
    /// True iff the object is `{}`.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.pairs.is_empty()
    }
    /// Each key written more than once, once, in the order of its second occurrence.
    #[must_use]
    pub fn duplicates(&self) -> Vec<&str> {
        let mut seen: Vec<&str> = Vec::new();
        for (i, (key, _)) in self.pairs.iter().enumerate() {
            let again = self.pairs[..i].iter().any(|(k, _)| k == key);
            if again && !seen.contains(&key.as_ref()) {
                seen.push(key);
            }
        }
        seen
    }
}

impl<'a> std::ops::Index<&str> for Map<'a> {
    type Output = Value<'a>;
    /// The value of `key`; `Null` when it is missing, as `serde_json::Map` indexing gives.
    fn index(&self, key: &str) -> &Value<'a> {
        const NULL: Value<'static> = Value::Null;
        self.get(key).unwrap_or(&NULL)
    }
}

impl<'m, 'a> IntoIterator for &'m Map<'a> {
    type Item = (&'m str, &'m Value<'a>);
    type IntoIter = std::iter::Map<
        std::slice::Iter<'m, (Cow<'a, str>, Value<'a>)>,
        fn(&'m (Cow<'a, str>, Value<'a>)) -> (&'m str, &'m Value<'a>),
    >;
    fn into_iter(self) -> Self::IntoIter {
        self.pairs.iter().map(|(k, v)| (k.as_ref(), v))
    }
}

impl<'de> Deserialize<'de> for Value<'de> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(ValueVisitor)
    }
}

/// Builds a [`Value`] from serde's calls, borrowing strings where the text allows.
struct ValueVisitor;

impl<'de> Visitor<'de> for ValueVisitor {
    type Value = Value<'de>;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("any JSON value")
    }
    fn visit_unit<E: de::Error>(self) -> Result<Self::Value, E> {
        Ok(Value::Null)
    }
    fn visit_bool<E: de::Error>(self, b: bool) -> Result<Self::Value, E> {
        Ok(Value::Bool(b))
    }
    fn visit_u64<E: de::Error>(self, n: u64) -> Result<Self::Value, E> {
        Ok(Value::Number(Number::Unsigned(n)))
    }
    fn visit_i64<E: de::Error>(self, n: i64) -> Result<Self::Value, E> {
        Ok(Value::Number(match u64::try_from(n) {
            Ok(n) => Number::Unsigned(n),
            Err(_) => Number::Signed(n),
        }))
    }
    fn visit_f64<E: de::Error>(self, x: f64) -> Result<Self::Value, E> {
        Ok(Value::Number(Number::Float(x)))
    }
    fn visit_borrowed_str<E: de::Error>(self, s: &'de str) -> Result<Self::Value, E> {
        Ok(Value::String(Cow::Borrowed(s)))
    }
    fn visit_str<E: de::Error>(self, s: &str) -> Result<Self::Value, E> {
        Ok(Value::String(Cow::Owned(s.to_owned())))
    }
    fn visit_string<E: de::Error>(self, s: String) -> Result<Self::Value, E> {
        Ok(Value::String(Cow::Owned(s)))
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
        let mut items = Vec::new();
        while let Some(item) = seq.next_element()? {
            items.push(item);
        }
        items.shrink_to_fit();
        Ok(Value::Array(items))
    }
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Self::Value, A::Error> {
        let mut pairs = Vec::new();
        while let Some((key, value)) = map.next_entry::<Key<'de>, Value<'de>>()? {
            pairs.push((key.0, value));
        }
        pairs.shrink_to_fit();
        Ok(Value::Object(Map { pairs }))
    }
}

/// Forwards the visits of scalars and strings to [`ValueVisitor`].
macro_rules! scalars_as_values {
    () => {
        fn visit_unit<E: de::Error>(self) -> Result<Self::Value, E> {
            ValueVisitor.visit_unit()
        }
        fn visit_bool<E: de::Error>(self, b: bool) -> Result<Self::Value, E> {
            ValueVisitor.visit_bool(b)
        }
        fn visit_u64<E: de::Error>(self, n: u64) -> Result<Self::Value, E> {
            ValueVisitor.visit_u64(n)
        }
        fn visit_i64<E: de::Error>(self, n: i64) -> Result<Self::Value, E> {
            ValueVisitor.visit_i64(n)
        }
        fn visit_f64<E: de::Error>(self, x: f64) -> Result<Self::Value, E> {
            ValueVisitor.visit_f64(x)
        }
        fn visit_borrowed_str<E: de::Error>(self, s: &'de str) -> Result<Self::Value, E> {
            ValueVisitor.visit_borrowed_str(s)
        }
        fn visit_str<E: de::Error>(self, s: &str) -> Result<Self::Value, E> {
            ValueVisitor.visit_str(s)
        }
        fn visit_string<E: de::Error>(self, s: String) -> Result<Self::Value, E> {
            ValueVisitor.visit_string(s)
        }
    };
}

/// The top-level value of [`parse_deferring`]: the array under `deferred` keeps its items as text.
struct RootVisitor<'k> {
    deferred: &'k str,
}

impl<'de> Visitor<'de> for RootVisitor<'_> {
    type Value = Value<'de>;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("any JSON value")
    }
    scalars_as_values!();
    fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<Self::Value, A::Error> {
        ValueVisitor.visit_seq(seq)
    }
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Self::Value, A::Error> {
        let mut pairs = Vec::new();
        while let Some(key) = map.next_key::<Key<'de>>()? {
            let value = if key.0 == self.deferred {
                map.next_value_seed(Deferring)?
            } else {
                map.next_value::<Value<'de>>()?
            };
            pairs.push((key.0, value));
        }
        pairs.shrink_to_fit();
        Ok(Value::Object(Map { pairs }))
    }
}

/// A value whose array items stay text ([`Value::Deferred`]).
struct Deferring;

impl<'de> DeserializeSeed<'de> for Deferring {
    type Value = Value<'de>;
    fn deserialize<D: Deserializer<'de>>(self, deserializer: D) -> Result<Self::Value, D::Error> {
        deserializer.deserialize_any(self)
    }
}

impl<'de> Visitor<'de> for Deferring {
    type Value = Value<'de>;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("any JSON value")
    }
    scalars_as_values!();
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
        let mut items = Vec::new();
        while let Some(raw) = seq.next_element::<&'de RawValue>()? {
            items.push(Value::Deferred(raw.get()));
        }
        items.shrink_to_fit();
        Ok(Value::Array(items))
    }
    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<Self::Value, A::Error> {
        ValueVisitor.visit_map(map)
    }
}

/// An object's key, borrowed from the text where it holds no escape.
struct Key<'a>(Cow<'a, str>);

impl<'de> Deserialize<'de> for Key<'de> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct KeyVisitor;
        impl<'de> Visitor<'de> for KeyVisitor {
            type Value = Key<'de>;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a string key")
            }
            fn visit_borrowed_str<E: de::Error>(self, s: &'de str) -> Result<Self::Value, E> {
                Ok(Key(Cow::Borrowed(s)))
            }
            fn visit_str<E: de::Error>(self, s: &str) -> Result<Self::Value, E> {
                Ok(Key(Cow::Owned(s.to_owned())))
            }
            fn visit_string<E: de::Error>(self, s: String) -> Result<Self::Value, E> {
                Ok(Key(Cow::Owned(s)))
            }
        }
        deserializer.deserialize_str(KeyVisitor)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keeps_duplicates_in_order() {
        let v = parse(r#"{"a": 1, "b": 2, "a": 3, "b": 4, "a": 5}"#).unwrap();
        let map = v.as_object().unwrap();
        assert_eq!(map.keys().collect::<Vec<_>>(), ["a", "b", "a", "b", "a"]);
        assert_eq!(map.duplicates(), ["a", "b"]);
        assert_eq!(map.get("a").and_then(Value::as_u64), Some(1));
    }

    #[test]
    fn skips_a_byte_order_mark() {
        let v = parse("\u{feff}{\"x\": [1, -2, 0.5]}").unwrap();
        let xs: Vec<f64> = v.get("x").unwrap().as_array().unwrap().iter().filter_map(Value::as_f64).collect();
        assert_eq!(xs, [1.0, -2.0, 0.5]);
        assert_eq!(v.get("x").unwrap().as_array().unwrap()[1], Value::Number(Number::Signed(-2)));
    }

    #[test]
    fn borrows_plain_strings_and_owns_escaped_ones() {
        let text = r#"{"plain": "glass", "esc\u0061ped": "a\"b"}"#;
        let v = parse(text).unwrap();
        assert!(matches!(v.get("plain"), Some(Value::String(Cow::Borrowed("glass")))));
        assert!(matches!(v.get("escaped"), Some(Value::String(Cow::Owned(s))) if s == "a\"b"));
    }

    #[test]
    fn deferred_items_parse_to_what_parse_gives() {
        let text = r#"{"objects": [{"a": 1, "a": 2}, [true, null]], "other": [{"b": "x"}]}"#;
        let lazy = parse_deferring(text, "objects").unwrap();
        let eager = parse(text).unwrap();
        let items = lazy.get("objects").unwrap().as_array().unwrap();
        assert!(matches!(items[0], Value::Deferred(_)));
        let parsed: Vec<Value<'_>> = items.iter().map(|v| v.parsed().unwrap().into_owned()).collect();
        assert_eq!(&parsed, eager.get("objects").unwrap().as_array().unwrap());
        assert_eq!(lazy.get("other"), eager.get("other"));
        assert_eq!(parsed[0].as_object().unwrap().duplicates(), ["a"]);
        // Not an array: parsed as it is; a syntax error inside an item is still the file's.
        assert_eq!(
            parse_deferring(r#"{"objects": 3}"#, "objects").unwrap().get("objects"),
            Some(&Value::Number(Number::Unsigned(3)))
        );
        let e = parse_deferring("{\"objects\": [{\"a\": }]}", "objects").unwrap_err();
        assert_eq!((e.line, e.column), (1, 20));
        assert!(parse_deferring("{} x", "objects").is_err());
        // A number out of range passes the first scan; its item's parse places it in the file.
        let text = "{\"objects\": [\n  {\"r\": 1},\n  {\"r\": 1e400}]}";
        let lazy = parse_deferring(text, "objects").unwrap();
        let Value::Deferred(part) = lazy.get("objects").unwrap().as_array().unwrap()[1] else { panic!() };
        let e = parse(part).unwrap_err().within(text, part);
        assert_eq!((e.line, e.column), (parse(text).unwrap_err().line, parse(text).unwrap_err().column));
    }

    #[test]
    fn syntax_errors_say_where() {
        let e = parse("{\n  \"a\": ,\n}").unwrap_err();
        assert_eq!((e.line, e.column), (2, 8));
        assert!(!e.message.contains(" at line "), "{}", e.message);
    }

    #[test]
    fn refuses_deep_nesting_without_overflowing() {
        let deep = "[".repeat(100_000);
        assert!(parse(&deep).is_err());
    }
}
