//! Amdahl's law applied to a profile: if a fraction `p` of the run became `s` times
//! faster, the whole run would take `(1 - p) + p / s` of its time. The table answers
//! "what would optimizing this buy?" twice per function:
//! - *alone*: `p` = its self share — only the function's own code gets faster;
//! - *with everything it calls*: `p` = its inclusive share — the function and all its
//!   callees get faster (making an intersection phase free frees the tests under it).
//!
//! Rows are the functions with the most inclusive time, leaving out the whole-run
//! frames ([`crate::profile::flat::WHOLE_RUN_PERCENT`]): the render's outermost frames
//! hold every sample, and "if the whole run were free" tells nothing.

use super::flat::{FlatProfile, FlatRow};
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;

/// Speed-ups of the whole run if one function became faster.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct AmdahlRow {
    pub name: String,
    /// The function's self share of all samples (0-1).
    pub fraction: f64,
    /// Whole-run speed-up with the function alone 2x faster.
    pub speedup_2x: f64,
    /// … alone 10x faster.
    pub speedup_10x: f64,
    /// … alone taking no time at all (`1 / (1 - p)`).
    pub speedup_limit: f64,
    /// The function's inclusive share of all samples (0-1): it anywhere on the stack.
    pub inclusive_fraction: f64,
    /// Whole-run speed-up with the function and everything it calls 2x faster.
    pub inclusive_speedup_2x: f64,
    /// … 10x faster.
    pub inclusive_speedup_10x: f64,
    /// … taking no time at all.
    pub inclusive_speedup_limit: f64,
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

/// Share of `part` samples in `total`, 0 without samples.
fn fraction(part: u64, total: u64) -> f64 {
    if total == 0 {
        0.0
    } else {
        part as f64 / total as f64
    }
}

impl AmdahlRow {
    /// The row of a function (or a group of functions) holding `own` of the time
    /// itself and `inclusive` with everything it calls (fractions, 0-1).
    pub fn new(name: &str, own: f64, inclusive: f64) -> Self {
        AmdahlRow {
            name: name.to_string(),
            fraction: own,
            speedup_2x: speedup(own, 2.0),
            speedup_10x: speedup(own, 10.0),
            speedup_limit: speedup(own, f64::INFINITY),
            inclusive_fraction: inclusive,
            inclusive_speedup_2x: speedup(inclusive, 2.0),
            inclusive_speedup_10x: speedup(inclusive, 10.0),
            inclusive_speedup_limit: speedup(inclusive, f64::INFINITY),
        }
    }
}

/// Rows for the `top` functions by inclusive samples (ties: more self samples, then
/// name), whole-run frames left out.
pub fn amdahl_table(flat: &FlatProfile, top: usize) -> Vec<AmdahlRow> {
    let mut rows: Vec<&FlatRow> = flat.rows.iter().filter(|r| !r.whole_run()).collect();
    rows.sort_by(|a, b| {
        (b.inclusive_samples, b.self_samples)
            .cmp(&(a.inclusive_samples, a.self_samples))
            .then_with(|| a.name.cmp(&b.name))
    });
    rows.into_iter()
        .take(top)
        .map(|r| {
            AmdahlRow::new(
                &r.name,
                fraction(r.self_samples, flat.samples),
                fraction(r.inclusive_samples, flat.samples),
            )
        })
        .collect()
}

/// A speed-up as text: `1.953x`, or `inf` for an unbounded one.
fn times(speedup: f64) -> String {
    if speedup.is_finite() {
        format!("{speedup:.3}x")
    } else {
        "inf".to_owned()
    }
}

/// The table as text: per function, its self share and the speed-ups if it alone
/// became faster, then its inclusive share and the speed-ups if it and everything it
/// calls did.
pub fn amdahl_text(rows: &[AmdahlRow]) -> String {
    let width = rows.iter().map(|r| r.name.len()).max().unwrap_or(8).max(8);
    let mut out = String::from(
        "Whole-run speed-up (Amdahl's law) if a function became 2x, 10x or infinitely\n\
         faster, for the functions with the most inclusive time (threads' roots and\n\
         frames on at least 99.5 % of the samples left out: they are the whole run).\n\
         \"alone\": if this function alone (its self time) became faster.\n\
         \"with callees\": if this function with everything it calls (its inclusive\n\
         time) became faster.\n\n",
    );
    // Each group's columns span 37 characters: `%7s  %8s  %8s  %8s`.
    let _ = writeln!(
        out,
        "{:<width$}  {:-^37}  {:-^37}",
        "", " alone ", " with callees "
    );
    let _ = writeln!(
        out,
        "{:<width$}  {:>7}  {:>8}  {:>8}  {:>8}  {:>7}  {:>8}  {:>8}  {:>8}",
        "function", "% self", "2x", "10x", "infinite", "% incl", "2x", "10x", "infinite"
    );
    for r in rows {
        let _ = writeln!(
            out,
            "{:<width$}  {:>7.2}  {:>8}  {:>8}  {:>8}  {:>7.2}  {:>8}  {:>8}  {:>8}",
            r.name,
            100.0 * r.fraction,
            times(r.speedup_2x),
            times(r.speedup_10x),
            times(r.speedup_limit),
            100.0 * r.inclusive_fraction,
            times(r.inclusive_speedup_2x),
            times(r.inclusive_speedup_10x),
            times(r.inclusive_speedup_limit),
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::profile::flat::flat_profile;
    use crate::profile::gprof::tests::{samples, three_functions};
    use crate::profile::tally::ProfileInput;
    use crate::profile::{CallCounts, StackSamples};

    fn flat(samples: &StackSamples) -> FlatProfile {
        flat_profile(&ProfileInput {
            samples,
            calls: &CallCounts::new(),
            renders: 1,
        })
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-12
    }

    #[test]
    fn hand_computed_speedups() {
        // p = 0.5: 2x → 1/(0.5 + 0.25) = 4/3; 10x → 1/0.55; limit 2.
        assert!(close(speedup(0.5, 2.0), 4.0 / 3.0));
        assert!(close(speedup(0.5, 10.0), 1.0 / 0.55));
        assert_eq!(speedup(0.5, f64::INFINITY), 2.0);
        assert_eq!(speedup(1.0, f64::INFINITY), f64::INFINITY);
        assert_eq!(speedup(0.0, 10.0), 1.0);
    }

    #[test]
    fn table_ranks_by_inclusive_time_and_gives_both_figures() {
        // main 100 % (whole run, left out); a 80 % inclusive / 30 % self; b 50/50; c 20/20.
        let rows = amdahl_table(&flat(&three_functions()), 10);
        let names: Vec<&str> = rows.iter().map(|r| r.name.as_str()).collect();
        assert_eq!(names, ["a", "b", "c"]);
        let a = &rows[0];
        // Self 0.3: 2x 1/(0.7 + 0.15) = 1.17647, 10x 1/0.73, limit 1/0.7.
        assert!(close(a.fraction, 0.3) && close(a.speedup_2x, 1.0 / 0.85));
        assert!(close(a.speedup_10x, 1.0 / 0.73) && close(a.speedup_limit, 1.0 / 0.7));
        // Inclusive 0.8: 2x 1/(0.2 + 0.4) = 1.6667, 10x 1/0.28, limit 5.
        assert!(close(a.inclusive_fraction, 0.8) && close(a.inclusive_speedup_2x, 1.0 / 0.6));
        assert!(close(a.inclusive_speedup_10x, 1.0 / 0.28));
        assert!((a.inclusive_speedup_limit - 5.0).abs() < 1e-9);
        // The top count is kept.
        assert_eq!(amdahl_table(&flat(&three_functions()), 1).len(), 1);
        // The case: a test with 45 % self but 88.9 % inclusive time (its phase
        // with the tests under it) gives 1/(1 - 0.889) = 9.01x, not 1.8x.
        let stacks = samples(
            &[
                (&["render", "intersect"], 444),
                (&["render", "intersect", "cylinder"], 445),
                (&["render", "shade"], 111),
            ],
            0.001,
        );
        let rows = amdahl_table(&flat(&stacks), 10);
        assert_eq!(rows[0].name, "intersect");
        assert!((rows[0].inclusive_speedup_limit - 1.0 / 0.111).abs() < 1e-9);
        assert!((rows[0].speedup_limit - 1.0 / 0.556).abs() < 1e-9);
    }

    #[test]
    fn text_says_which_figure_is_which() {
        let stacks = samples(&[(&["main", "a"], 1), (&["b"], 1)], 1.0);
        let rows = amdahl_table(&flat(&stacks), 10);
        // a and b: 50 % each, self and inclusive: 2x 1.333x, 10x 1.818x, limit 2x.
        let text = amdahl_text(&rows);
        assert!(text.contains("if this function alone (its self time)"));
        assert!(text.contains("if this function with everything it calls"));
        let line = text.lines().find(|l| l.starts_with("a ")).unwrap();
        let fields: Vec<&str> = line.split_whitespace().collect();
        assert_eq!(
            fields,
            [
                "a", "50.00", "1.333x", "1.818x", "2.000x", "50.00", "1.333x", "1.818x", "2.000x"
            ]
        );
        // The group headings span their columns: "alone" ends over the first
        // "infinite", "with callees" over the second.
        let groups = text.lines().find(|l| l.contains("- alone -")).unwrap();
        let heading = text.lines().find(|l| l.starts_with("function")).unwrap();
        let first_end = heading.find("infinite").unwrap() + "infinite".len();
        assert!(groups.contains("- with callees -"));
        assert_eq!(&groups[first_end - 1..first_end + 3], "-  -");
        assert_eq!(groups.trim_end().len(), heading.trim_end().len());
        // An unbounded speed-up prints "inf".
        let mut row = rows[0].clone();
        row.inclusive_speedup_limit = f64::INFINITY;
        assert!(amdahl_text(&[row]).lines().last().unwrap().ends_with("inf"));
    }
}
