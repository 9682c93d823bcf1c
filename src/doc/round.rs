//! `round_floats`: snapshots that hold across platforms (numerics.md M3) — every float rounded to
//! a number of significant digits, and −0 written as 0.

use serde_json::Value;

/// Rounds every float in `value` to `digits` significant digits; maps −0.0 to 0.0.
#[must_use]
pub fn round_floats(value: &Value, digits: i32) -> Value {
    match value {
        Value::Number(n) if n.is_f64() => {
            let x = n.as_f64().unwrap_or(0.0);
            let r = round_sig(x, digits);
            serde_json::Number::from_f64(if r == 0.0 { 0.0 } else { r }).map_or(Value::Null, Value::Number)
        }
        Value::Array(items) => Value::Array(items.iter().map(|v| round_floats(v, digits)).collect()),
        Value::Object(map) => {
            Value::Object(map.iter().map(|(k, v)| (k.clone(), round_floats(v, digits))).collect())
        }
        other => other.clone(),
    }
}

/// `x` rounded to `digits` significant digits (values below 1e-15 in magnitude become 0).
fn round_sig(x: f64, digits: i32) -> f64 {
    if x == 0.0 || !x.is_finite() || x.abs() < 1e-15 {
        return 0.0;
    }
    // Through the decimal formatter, so the result is the shortest decimal of that precision.
    let p = usize::try_from(digits.max(1) - 1).unwrap_or(0);
    format!("{x:.p$e}").parse().unwrap_or(x)
}

#[cfg(test)]
// These tests pin exact IEEE results on purpose (numerics.md gives bit-exact expectations).
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn m3_rounds_and_drops_negative_zero() {
        let v = json!({"a": [1.1102230246251565e-16, -0.0, 0.123456789, 3], "b": "inf"});
        assert_eq!(round_floats(&v, 6), json!({"a": [0.0, 0.0, 0.123457, 3], "b": "inf"}));
    }
}
