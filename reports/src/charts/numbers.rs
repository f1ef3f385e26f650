//! Formatting of the numbers and names the charts print.
//!
//! MERGE NOTE: this is the only formatting in `charts`; at merge these functions move
//! to (or are replaced by) the crate's one formatting module, `crate::format`. Users:
//! [`format_number`] (axis ticks, bar values, captions; also `html.rs`), [`short_name`]
//! (function names; also `html.rs`, `findings.rs`), [`truncate`] (category labels);
//! `trim` serves [`format_number`] only.

/// A number for an axis or a bar: 3 significant digits, SI suffix for large counts.
pub fn format_number(v: f64) -> String {
    if !v.is_finite() {
        return "–".to_string();
    }
    let a = v.abs();
    if a == 0.0 {
        "0".to_string()
    } else if a >= 1e9 {
        format!("{}G", trim(v / 1e9))
    } else if a >= 1e6 {
        format!("{}M", trim(v / 1e6))
    } else if a >= 1e4 {
        format!("{}k", trim(v / 1e3))
    } else if a < 1e-3 {
        format!("{v:.0e}")
    } else {
        trim(v)
    }
}

/// Up to 3 significant digits without trailing zeros.
fn trim(v: f64) -> String {
    let a = v.abs();
    let decimals = if a >= 100.0 {
        0
    } else if a >= 10.0 {
        1
    } else if a >= 1.0 {
        2
    } else if a >= 0.1 {
        3
    } else if a >= 0.01 {
        4
    } else {
        5
    };
    let s = format!("{v:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// The last two `::` segments of a function name, without generic arguments, at most
/// 36 characters.
pub fn short_name(name: &str) -> String {
    let mut plain = String::new();
    let mut depth = 0usize;
    for c in name.chars() {
        match c {
            '<' => depth += 1,
            '>' => depth = depth.saturating_sub(1),
            _ if depth == 0 => plain.push(c),
            _ => {}
        }
    }
    let segments: Vec<&str> = plain.split("::").filter(|s| !s.is_empty()).collect();
    let short = match segments.len() {
        0 => name.to_string(),
        1 => segments[0].to_string(),
        n => segments[n - 2..].join("::"),
    };
    truncate(&short, 36)
}

/// `text` cut to `max_chars` characters, the last one an ellipsis when it was cut.
pub(super) fn truncate(text: &str, max_chars: usize) -> String {
    if text.chars().count() <= max_chars {
        text.to_string()
    } else {
        let mut t: String = text.chars().take(max_chars.saturating_sub(1)).collect();
        t.push('…');
        t
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_keep_their_last_two_segments_without_generics() {
        let cases = [
            (
                "tracer::primitives::sphere::Sphere::intersect",
                "Sphere::intersect",
            ),
            ("tracer::render::render::{{closure}}", "render::{{closure}}"),
            ("main", "main"),
            (
                "<tracer::accel::bvh::Bvh as tracer::accel::Intersector>::occluded",
                "occluded",
            ),
        ];
        for (name, short) in cases {
            assert_eq!(short_name(name), short, "{name}");
        }
        let long = format!("a::{}", "x".repeat(50));
        assert_eq!(short_name(&long).chars().count(), 36);
        assert!(short_name(&long).ends_with('…'));
    }

    #[test]
    fn numbers_get_three_significant_digits_and_a_suffix() {
        let cases = [
            (4_223_520_000.0, "4.22G"),
            (1_500_000.0, "1.5M"),
            (12_345.0, "12.3k"),
            (999.4, "999"),
            (0.0184, "0.0184"),
            (0.0005, "5e-4"),
            (0.0, "0"),
            (f64::NAN, "–"),
        ];
        for (v, text) in cases {
            assert_eq!(format_number(v), text, "{v}");
        }
    }
}
