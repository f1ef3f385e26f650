//! The regression gate: a run against an earlier one (`rtprof suite --baseline
//! OLD/results.json`).
//!
//! For every scene × variant in both runs: the time change of the medians, and a
//! verdict. **Slower** means significantly slower: the new interval's lower end is
//! above the old interval's upper end by more than the threshold, so noise inside
//! either interval can never trip it. **Faster** is the mirror image. Any difference in
//! any exact count is a **count change** (counts do not depend on the machine or the
//! load, so a changed count is a changed program). The gate fails on a slower entry or
//! a count change; scenes or variants present in only one run are listed, not failed.

use serde::Serialize;

use crate::schema::{Results, VariantResult};
use crate::timing_policy::TimeCovers;
use crate::variant_name::VariantName;

/// What happened to one scene × variant.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Verdict {
    Slower,
    Faster,
    Unchanged,
}

/// One compared scene × variant.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Entry {
    pub scene: String,
    pub variant: VariantName,
    pub old_median: f64,
    pub old_interval: (f64, f64),
    pub new_median: f64,
    pub new_interval: (f64, f64),
    /// new / old − 1.
    pub change: f64,
    pub verdict: Verdict,
    /// Counters whose values differ: (name, old, new); a missing counter reads 0.
    pub count_changes: Vec<(String, u64, u64)>,
}

/// The whole comparison.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct GateReport {
    pub threshold: f64,
    pub entries: Vec<Entry>,
    /// `scene/variant` present in only one of the runs.
    pub unmatched: Vec<String>,
    /// Set when the runs' times cover different things (a `/1` file timed
    /// preprocessing and tracing together): the time changes then include that.
    pub covers_differ: Option<(TimeCovers, TimeCovers)>,
}

impl GateReport {
    /// True when some entry is significantly slower or changed a count.
    pub fn failed(&self) -> bool {
        self.entries
            .iter()
            .any(|e| e.verdict == Verdict::Slower || !e.count_changes.is_empty())
    }

    /// A plain-text table.
    pub fn to_text(&self) -> String {
        let mut out = format!(
            "regression gate (threshold {:.1} %): {} compared, {}\n",
            self.threshold * 100.0,
            self.entries.len(),
            if self.failed() { "FAILED" } else { "passed" }
        );
        out += &format!(
            "{:<16} {:<18} {:>28} {:>28} {:>8}  verdict\n",
            "scene", "variant", "old s [95 % interval]", "new s [95 % interval]", "change"
        );
        for e in &self.entries {
            let verdict = match (e.verdict, e.count_changes.is_empty()) {
                (Verdict::Slower, _) => "SLOWER".to_string(),
                (_, false) => format!("COUNTS CHANGED ({})", e.count_changes.len()),
                (Verdict::Faster, true) => "faster".to_string(),
                (Verdict::Unchanged, true) => "unchanged".to_string(),
            };
            out += &format!(
                "{:<16} {:<18} {:>28} {:>28} {:>+7.1}%  {verdict}\n",
                e.scene,
                e.variant,
                format!(
                    "{:.5} [{:.5}, {:.5}]",
                    e.old_median, e.old_interval.0, e.old_interval.1
                ),
                format!(
                    "{:.5} [{:.5}, {:.5}]",
                    e.new_median, e.new_interval.0, e.new_interval.1
                ),
                e.change * 100.0
            );
            for (name, old, new) in e.count_changes.iter().take(5) {
                out += &format!("    {name}: {old} → {new}\n");
            }
        }
        for u in &self.unmatched {
            out += &format!("only in one run: {u}\n");
        }
        if let Some((old, new)) = self.covers_differ {
            out += &format!(
                "note: the old run's times cover {}, the new run's {}: time changes include the difference\n",
                old.describe(),
                new.describe()
            );
        }
        out
    }
}

fn verdict(old: &VariantResult, new: &VariantResult, threshold: f64) -> Verdict {
    if new.time.low > old.time.high * (1.0 + threshold) {
        Verdict::Slower
    } else if new.time.high * (1.0 + threshold) < old.time.low {
        Verdict::Faster
    } else {
        Verdict::Unchanged
    }
}

fn count_changes(old: &VariantResult, new: &VariantResult) -> Vec<(String, u64, u64)> {
    let mut names: Vec<&String> = old.counts.keys().chain(new.counts.keys()).collect();
    names.sort();
    names.dedup();
    names
        .into_iter()
        .filter_map(|name| {
            let a = old.counts.get(name).copied().unwrap_or(0);
            let b = new.counts.get(name).copied().unwrap_or(0);
            (a != b).then(|| (name.clone(), a, b))
        })
        .collect()
}

/// Compares `new` against `old`; `threshold` is a fraction (0.05 for 5 %).
pub fn compare_runs(old: &Results, new: &Results, threshold: f64) -> GateReport {
    let mut entries = Vec::new();
    let mut unmatched = Vec::new();
    for scene in &new.scenes {
        let old_scene = old
            .scenes
            .iter()
            .find(|s| s.name == scene.name && s.width == scene.width && s.height == scene.height);
        for v in &scene.variants {
            let old_v = old_scene.and_then(|s| s.variants.iter().find(|o| o.variant == v.variant));
            match old_v {
                Some(o) => entries.push(Entry {
                    scene: scene.name.clone(),
                    variant: v.variant.clone(),
                    old_median: o.time.median,
                    old_interval: (o.time.low, o.time.high),
                    new_median: v.time.median,
                    new_interval: (v.time.low, v.time.high),
                    change: v.time.median / o.time.median - 1.0,
                    verdict: verdict(o, v, threshold),
                    count_changes: count_changes(o, v),
                }),
                None => unmatched.push(format!("{}/{} (new)", scene.name, v.variant)),
            }
        }
    }
    for scene in &old.scenes {
        for v in &scene.variants {
            let present = new.scenes.iter().any(|s| {
                s.name == scene.name
                    && s.width == scene.width
                    && s.height == scene.height
                    && s.variants.iter().any(|n| n.variant == v.variant)
            });
            if !present {
                unmatched.push(format!("{}/{} (old)", scene.name, v.variant));
            }
        }
    }
    let (old_covers, new_covers) = (old.suite.timing.covers, new.suite.timing.covers);
    GateReport {
        threshold,
        entries,
        unmatched,
        covers_differ: (old_covers != new_covers).then_some((old_covers, new_covers)),
    }
}
