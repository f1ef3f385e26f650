//! The run's tables for other tools, written beside the reports by `rtprof report` and
//! `rtprof suite`: `variants.csv` (every scene × variant with plain numbers and every
//! counter, for a spreadsheet or pandas) and `summary.md` (one page of Markdown: what
//! changed, the report's three answers with their tables, the other findings; for a
//! pull request or a CI job summary). The numbers and verdicts are the report's own.

use std::collections::BTreeSet;

use crate::Run;
use crate::findings::headline_findings;
use crate::gate_text;
use crate::results::{Results, SceneResult, Verdict};
use crate::sections::comparison::gate_against;
use crate::sections::summary::run_pairs;
use crate::text;

/// Every scene × variant of a run, one CSV row each: times in seconds, the speed-up
/// with its interval and verdict, image metrics, and every counter as its own column.
pub fn variants_csv(results: &Results) -> String {
    scenes_csv(&results.scenes)
}

/// The CSV of some scenes' variants: one row per scene and variant, one column per
/// counter any of them has. The one writer of variant rows: `variants.csv` and `rtprof
/// compare --format csv` both write through it.
pub fn scenes_csv(scenes: &[SceneResult]) -> String {
    let counters: BTreeSet<&String> = scenes
        .iter()
        .flat_map(|s| &s.variants)
        .flat_map(|v| v.counts.keys())
        .collect();
    let mut header: Vec<&str> = vec![
        "scene",
        "width",
        "height",
        "primitives",
        "variant",
        "median_s",
        "low_s",
        "high_s",
        "repeats",
        "preprocessing_s",
        "speedup",
        "speedup_low",
        "speedup_high",
        "verdict",
        "rms",
        "band",
        "psnr_db",
        "ssim",
        "max_abs_diff",
        "rms_vs_f64",
        "psnr_db_vs_f64",
        "max_abs_diff_vs_f64",
    ];
    header.extend(counters.iter().map(|c| c.as_str()));
    let n = |x: Option<f64>| text::csv_number(x);
    let mut rows = Vec::new();
    for s in scenes {
        for v in &s.variants {
            let q = v.quality.as_ref();
            let truth = v.vs_f64_reference.as_ref();
            let [low, high] = v
                .speedup_interval
                .map_or([None, None], |[l, h]| [Some(l), Some(h)]);
            let mut row = vec![
                s.name.clone(),
                s.width.to_string(),
                s.height.to_string(),
                s.primitives.to_string(),
                v.variant.to_string(),
                n(Some(v.time.median)),
                n(Some(v.time.low)),
                n(Some(v.time.high)),
                v.samples.len().to_string(),
                n(v.preprocessing_seconds),
                n(v.speedup),
                n(low),
                n(high),
                v.verdict
                    .map_or(
                        if v.variant.is_reference() {
                            "reference"
                        } else {
                            ""
                        },
                        Verdict::label,
                    )
                    .to_string(),
                n(q.map(|q| q.rms)),
                q.map_or(String::new(), |q| q.band.name().to_string()),
                n(q.and_then(|q| q.psnr)),
                n(q.map(|q| q.ssim)),
                q.map_or(String::new(), |q| q.max_abs_diff.to_string()),
                n(truth.map(|q| q.rms)),
                n(truth.and_then(|q| q.psnr)),
                truth.map_or(String::new(), |q| q.max_abs_diff.to_string()),
            ];
            row.extend(
                counters
                    .iter()
                    .map(|c| v.counts.get(*c).map_or(String::new(), u64::to_string)),
            );
            rows.push(row);
        }
    }
    text::csv(&header, &rows)
}

/// One variant's verdicts over the scenes.
/// A one-page Markdown summary of `runs` (the first in detail): what changed against
/// the first run when there are several, the report's three answers (the same model
/// as its first page), the other findings, the failures and the files.
pub fn summary_markdown(runs: &[Run]) -> String {
    let Some(main) = runs.first() else {
        return String::new();
    };
    let r = &main.results;
    let mut out = String::from("# rtprof summary\n\n");
    for pair in run_pairs(&main.label, r) {
        out += &format!("- **{}**: {}\n", pair.key, pair.value);
    }
    out.push('\n');
    for run in &runs[1..] {
        let g = gate_against(main, run);
        out += &format!(
            "## What changed: {} against {}\n\n{}\n\n{}\n\n",
            run.label,
            main.label,
            gate_text::headline(&g),
            gate_text::rule(&g)
        );
        let changed = crate::results::gate::GateReport {
            entries: g
                .entries
                .iter()
                .filter(|e| e.failed() || e.verdict != Verdict::WithinNoise)
                .cloned()
                .collect(),
            ..g.clone()
        };
        if !changed.entries.is_empty() {
            out += &text::markdown(&gate_text::table(&changed));
            out.push('\n');
        }
    }
    // The report's first page: the same three answers, sentences and tables.
    out += "## Answers\n\n";
    for answer in crate::sections::answers::three_answers(r) {
        out += &format!("### {}\n\n", answer.question);
        out += answer.sentence.as_deref().unwrap_or(answer.why_none);
        out += "\n\n";
        if let Some(warning) = &answer.warning {
            out += &format!("> {warning}\n\n");
        }
        if let Some(table) = &answer.table {
            if let Some(caption) = &table.caption {
                out += &format!("*{caption}*\n\n");
            }
            out += &text::markdown(table);
            out.push('\n');
        }
    }
    let findings = headline_findings(r);
    if !findings.is_empty() {
        out += "## Other findings\n\n";
        for f in findings {
            out += &format!("- {f}\n");
        }
        out.push('\n');
    }
    if !r.failures.is_empty() {
        out += "## Failures\n\n";
        for f in &r.failures {
            out += &format!("- {}: {}\n", f.place(), f.message);
        }
        out.push('\n');
    }
    out += "Files: `report.html`, `report.pdf`, `results.json`, `variants.csv`.\n";
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_csv_has_a_row_per_scene_and_variant_and_a_column_per_counter() {
        let r = testkit::sample::sample_results();
        let csv = variants_csv(&r);
        let mut lines = csv.lines();
        let header: Vec<&str> = lines.next().unwrap().split(',').collect();
        let rows = r.scenes.iter().map(|s| s.variants.len()).sum::<usize>();
        assert_eq!(lines.count(), rows);
        let counters: BTreeSet<&String> = r
            .scenes
            .iter()
            .flat_map(|s| &s.variants)
            .flat_map(|v| v.counts.keys())
            .collect();
        assert_eq!(header.len(), 22 + counters.len());
        assert!(header.contains(&"ops.dot") && header.contains(&"verdict"));
        assert!(header.contains(&"rms_vs_f64"));
    }
}
