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

use serde::de::{self, Deserialize, Deserializer, MapAccess, SeqAccess, Visitor};
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
    serde_json::from_str(text).map_err(|e| {
        let full = e.to_string();
        // serde_json appends " at line L column C"; the position is kept apart.
        let message = full.split(" at line ").next().unwrap_or(&full).to_string();
        SyntaxError { message, line: e.line(), column: e.column() }
    })
}

impl<'a> Value<'a> {
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
