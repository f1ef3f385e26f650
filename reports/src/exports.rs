//! The run's tables for other tools, written beside the reports by `rtprof report` and
//! `rtprof suite`: `variants.csv` (every scene × variant with plain numbers and every
//! counter, for a spreadsheet or pandas) and `summary.md` (one page of Markdown: what
//! changed, the headline findings, each variant's verdicts; for a pull request or a CI
//! job summary). The numbers and verdicts are the report's own.

use std::collections::BTreeSet;

use crate::Run;
use crate::document::{Cell, Column, Table, Tone};
use crate::findings::{geometric_mean, headline_findings};
use crate::format;
use crate::gate_text;
use crate::results::{Results, VariantName, Verdict};
use crate::sections::comparison::gate_against;
use crate::sections::summary::run_pairs;
use crate::text;

/// Every scene × variant of a run, one CSV row each: times in seconds, the speed-up
/// with its interval and verdict, image metrics, and every counter as its own column.
pub fn variants_csv(results: &Results) -> String {
    let counters: BTreeSet<&String> = results
        .scenes
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
    for s in &results.scenes {
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
struct VariantLine {
    variant: VariantName,
    speedups: Vec<f64>,
    verdicts: [usize; 3],
    worst_rms: Option<f64>,
}

/// Per variant: geometric-mean speed-up, how many scenes were faster / within noise /
/// slower, and the worst image error.
fn variant_table(results: &Results) -> Table {
    let mut lines: Vec<VariantLine> = Vec::new();
    for v in results.scenes.iter().flat_map(|s| &s.variants) {
        if v.variant.is_reference() {
            continue;
        }
        let i = match lines.iter().position(|l| l.variant == v.variant) {
            Some(i) => i,
            None => {
                lines.push(VariantLine {
                    variant: v.variant.clone(),
                    speedups: Vec::new(),
                    verdicts: [0; 3],
                    worst_rms: None,
                });
                lines.len() - 1
            }
        };
        let line = &mut lines[i];
        line.speedups.extend(v.speedup);
        if let Some(verdict) = v.verdict {
            let slot = Verdict::ALL.iter().position(|x| *x == verdict).unwrap_or(2);
            line.verdicts[slot] += 1;
        }
        if let Some(q) = &v.quality {
            line.worst_rms = Some(line.worst_rms.map_or(q.rms, |w: f64| w.max(q.rms)));
        }
    }
    let mut t = Table::new(vec![
        Column::text("variant"),
        Column::number("geometric-mean speed-up"),
        Column::number("faster"),
        Column::number("within noise"),
        Column::number("slower"),
        Column::number("worst RMS"),
    ]);
    for l in &lines {
        let mean = geometric_mean(l.speedups.iter().copied()).map_or(f64::NAN, |m| m.0);
        let [faster, slower, noise] = l.verdicts;
        t.rows.push(vec![
            Cell::text(l.variant.as_str()),
            Cell::number(format::speedup(mean), mean),
            Cell::count(faster as u64),
            Cell::count(noise as u64),
            Cell::count(slower as u64).tone(if slower > 0 { Tone::Bad } else { Tone::Muted }),
            Cell::number(
                l.worst_rms
                    .map_or(format::DASH.to_string(), |r| format::fixed(r, 1)),
                l.worst_rms.unwrap_or(f64::NAN),
            ),
        ]);
    }
    t
}

/// A one-page Markdown summary of `runs` (the first in detail): what changed against
/// the first run when there are several, the headline findings, each variant's
/// verdicts, the failures and the files.
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
    let findings = headline_findings(r);
    if !findings.is_empty() {
        out += "## Headline findings\n\n";
        for f in findings {
            out += &format!("- {f}\n");
        }
        out.push('\n');
    }
    if r.scenes.iter().any(|s| s.variants.len() > 1) {
        out += &format!(
            "## Variants against baseline\n\nVerdicts per scene: faster or slower only beyond the noise threshold of {} with a 95 % interval that excludes 1×.\n\n",
            format::percent(
                r.suite
                    .noise_threshold
                    .unwrap_or(crate::results::NOISE_THRESHOLD)
                    * 100.0,
                0
            )
        );
        out += &text::markdown(&variant_table(r));
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
