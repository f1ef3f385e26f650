//! The checks of the `results_file` fuzz target (fuzz/fuzz_targets/results_file.rs),
//! here so that the regression inputs it found replay in `cargo test`
//! (reports/tests/fuzz_regressions.rs).
//!
//! Bytes are read as a results file ([`Results::from_json`]); what is refused must be
//! refused with an error, never a panic. What is accepted is gated against itself and
//! against a copy with longer times and a changed count, written back and read again,
//! and rendered to HTML (charts included) against an empty directory (every referenced
//! file is then missing). The PDF is left out: typesetting takes about a second per
//! report, too slow for a fuzzer's millions of inputs.

use std::path::Path;

use crate::Run;
use crate::html::render_html;
use crate::results::Results;
use crate::results::gate::{GateOptions, gate};

/// What happened to one input.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// Not a results file: refused with this message.
    Refused(String),
    /// Read, gated and rendered; the HTML's length in bytes.
    Reported(usize),
}

/// A broken promise of the results contract or the report.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum Defect {
    #[error("a run gated against itself failed the gate")]
    SelfGateFailed,
    #[error("a changed count did not fail the gate")]
    CountChangeMissed,
    #[error("the results, written back, cannot be read: {0}")]
    NotReadBack(String),
    #[error("the HTML report failed: {0}")]
    Html(String),
}

/// The copy the gate must catch: every time three times as long and the first count
/// of the first variant that has one raised by one.
fn mutated(results: &Results) -> (Results, bool) {
    let mut copy = results.clone();
    let mut counted = false;
    for scene in &mut copy.scenes {
        for v in &mut scene.variants {
            v.time = v.time.scaled(3.0);
            for s in &mut v.samples {
                *s *= 3.0;
            }
            if !counted && let Some(n) = v.counts.values_mut().next() {
                *n = n.wrapping_add(1);
                counted = true;
            }
        }
    }
    (copy, counted)
}

/// Runs every check on `bytes`, with `empty_dir` as the results directory.
pub fn read_gate_and_render(bytes: &[u8], empty_dir: &Path) -> Result<Outcome, Defect> {
    let text = String::from_utf8_lossy(bytes);
    let results = match Results::from_json(&text) {
        Ok(r) => r,
        Err(e) => return Ok(Outcome::Refused(e.to_string())),
    };
    let force = GateOptions {
        force: true,
        ..GateOptions::default()
    };
    let self_gate = gate(&results, &results, force).map_err(|_| Defect::SelfGateFailed)?;
    if self_gate.failed() {
        return Err(Defect::SelfGateFailed);
    }
    let (copy, counted) = mutated(&results);
    // The copy was changed after validation: its counts may leave the exact range, but
    // the gate compares integers and must still see the change.
    if counted
        && !gate(&results, &copy, force)
            .map_err(|_| Defect::CountChangeMissed)?
            .failed()
    {
        return Err(Defect::CountChangeMissed);
    }
    let written =
        serde_json::to_string(&results).map_err(|e| Defect::NotReadBack(e.to_string()))?;
    Results::from_json(&written).map_err(|e| Defect::NotReadBack(e.to_string()))?;
    let run = Run {
        label: "fuzz".to_string(),
        results,
        base_dir: empty_dir.to_path_buf(),
    };
    let html = render_html(&[run]).map_err(|e| Defect::Html(e.to_string()))?;
    Ok(Outcome::Reported(html.len()))
}
