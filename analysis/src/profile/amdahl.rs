//! Amdahl's law applied to a profile: if one function alone became `s` times faster,
//! the whole run would take `(1 - p) + p / s` of its time, `p` being that function's
//! share of self time. The table answers "what would optimizing this buy?".

use serde::{Deserialize, Serialize};

/// Speed-ups of the whole run if one function became faster.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct AmdahlRow {
    pub name: String,
    /// The function's share of all self time (0-1).
    pub fraction: f64,
    /// Whole-run speed-up with the function 2x faster.
    pub speedup_2x: f64,
    /// … 10x faster.
    pub speedup_10x: f64,
    /// … taking no time at all (`1 / (1 - p)`).
    pub speedup_limit: f64,
}

/// Whole-run speed-up when a fraction `p` of the time runs `s` times faster.
pub fn speedup(p: f64, s: f64) -> f64 {
    let p = p.clamp(0.0, 1.0);
    let remaining = (1.0 - p) + if s.is_infinite() { 0.0 } else { p / s };
    if remaining > 0.0 {
        1.0 / remaining
    } else {
        f64::INFINITY
    }
}

/// Rows for the `top` functions by self time, from `(name, self seconds)` pairs.
pub fn amdahl_table(self_times: &[(String, f64)], top: usize) -> Vec<AmdahlRow> {
    let total: f64 = self_times.iter().map(|(_, t)| t.max(0.0)).sum();
    let mut sorted: Vec<&(String, f64)> = self_times.iter().collect();
    sorted.sort_by(|a, b| b.1.total_cmp(&a.1).then_with(|| a.0.cmp(&b.0)));
    sorted
        .into_iter()
        .take(top)
        .map(|(name, t)| {
            let p = if total > 0.0 { t.max(0.0) / total } else { 0.0 };
            AmdahlRow {
                name: name.clone(),
                fraction: p,
                speedup_2x: speedup(p, 2.0),
                speedup_10x: speedup(p, 10.0),
                speedup_limit: speedup(p, f64::INFINITY),
            }
        })
        .collect()
}

/// The table as text.
pub fn amdahl_text(rows: &[AmdahlRow]) -> String {
    let width = rows.iter().map(|r| r.name.len()).max().unwrap_or(8).max(8);
    let mut out = format!(
        "Whole-run speed-up if one function alone became faster (Amdahl's law)\n\n{:<width$}  {:>7}  {:>8}  {:>8}  {:>8}\n",
        "function", "% self", "2x", "10x", "infinite"
    );
    for r in rows {
        let limit = if r.speedup_limit.is_finite() {
            format!("{:.3}", r.speedup_limit)
        } else {
            "inf".to_string()
        };
        out += &format!(
            "{:<width$}  {:>7.2}  {:>8.3}  {:>8.3}  {:>8}\n",
            r.name,
            100.0 * r.fraction,
            r.speedup_2x,
            r.speedup_10x,
            limit
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hand_computed_speedups() {
        // p = 0.5: 2x → 1/(0.5 + 0.25) = 4/3; 10x → 1/0.55; limit 2.
        assert!((speedup(0.5, 2.0) - 4.0 / 3.0).abs() < 1e-12);
        assert!((speedup(0.5, 10.0) - 1.0 / 0.55).abs() < 1e-12);
        assert_eq!(speedup(0.5, f64::INFINITY), 2.0);
        assert_eq!(speedup(1.0, f64::INFINITY), f64::INFINITY);
        assert_eq!(speedup(0.0, 10.0), 1.0);
    }

    #[test]
    fn table_takes_the_top_functions_by_self_time() {
        let times = vec![
            ("a".to_string(), 1.0),
            ("b".to_string(), 3.0),
            ("c".to_string(), 4.0),
        ];
        let rows = amdahl_table(&times, 2);
        assert_eq!(rows.len(), 2);
        assert_eq!((rows[0].name.as_str(), rows[1].name.as_str()), ("c", "b"));
        assert!((rows[0].fraction - 0.5).abs() < 1e-12);
        assert_eq!(rows[0].speedup_limit, 2.0);
        assert!(amdahl_text(&rows).contains("inf") || rows[0].speedup_limit.is_finite());
    }
}
