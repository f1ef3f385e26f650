//! One verdict rule everywhere: the report's comparison of two runs shows the gate's
//! verdict for every scene × variant, and every verdict label reaches every output
//! format (terminal text, Markdown, CSV, JSON of the gate; the report's cells).

use std::path::PathBuf;

use reports::Run;
use reports::document::{self, Block, Tone};
use reports::gate_text;
use reports::results::gate::{GateOptions, gate};
use reports::results::{Results, VariantName, Verdict};
use testkit::sample_results;

fn run(label: &str, results: Results) -> Run {
    Run {
        label: label.to_string(),
        results,
        base_dir: PathBuf::from("/nonexistent"),
    }
}

/// Scales every timed render (wall and CPU) of `variant` on every scene.
fn scale(r: &mut Results, variant: &str, factor: f64) {
    let name = VariantName::parse(variant).expect("a variant");
    for scene in &mut r.scenes {
        for v in scene.variants.iter_mut().filter(|v| v.variant == name) {
            for x in v.samples.iter_mut().chain(v.cpu_samples.iter_mut()) {
                *x *= factor;
            }
            v.time = v.time.scaled(factor);
        }
    }
}

/// The sample run, and a second one with bvh 25 % slower, fast-sqrt 25 % faster and
/// one count changed: all three labels and a count change.
fn two_runs() -> (Results, Results) {
    let old = sample_results();
    let mut new = old.clone();
    scale(&mut new, "bvh", 1.25);
    scale(&mut new, "fast-sqrt", 0.8);
    *new.scenes[0].variants[0]
        .counts
        .get_mut("ops.dot")
        .expect("ops.dot") += 1;
    (old, new)
}

#[test]
fn the_reports_comparison_shows_the_gates_verdicts() {
    let (old, new) = two_runs();
    let g = gate(&old, &new, GateOptions::default()).expect("comparable");
    let tally = g.tally();
    assert!(
        tally.slower > 0 && tally.faster > 0 && tally.within_noise > 0,
        "{tally:?}"
    );
    let doc = document::build(&[run("old", old), run("new", new)]).expect("document");
    let comparison = &doc.sections[0];
    assert_eq!(
        comparison.id, "comparison",
        "a report of several runs opens with it"
    );
    // The big table: scene, variant, medians, then change, verdict, counts.
    let table = comparison
        .blocks
        .iter()
        .filter_map(|b| match b {
            Block::Table(t) => Some(t),
            _ => None,
        })
        .find(|t| t.columns.iter().any(|c| c.title == "verdict new"))
        .expect("the per-run table");
    let verdict_column = table
        .columns
        .iter()
        .position(|c| c.title == "verdict new")
        .expect("verdict column");
    let mut checked = 0;
    for e in &g.entries {
        let row = table
            .rows
            .iter()
            .find(|row| row[0].text == e.scene && row[1].text == e.variant.as_str())
            .expect("a row per entry");
        let cell = &row[verdict_column];
        assert_eq!(cell.text, e.verdict.label(), "{} {}", e.scene, e.variant);
        assert_eq!(cell.tone, Tone::of_verdict(e.verdict));
        // The change cell is toned by the same verdict, never by the raw ratio.
        assert_eq!(row[verdict_column - 1].tone, Tone::of_verdict(e.verdict));
        checked += 1;
    }
    assert_eq!(checked, g.entries.len());
    // The first block after the heading is the gate's headline, failed in bad tone.
    let headline = gate_text::headline(&g);
    assert!(comparison.blocks.iter().any(|b| matches!(b,
        Block::Note(n) if n.text == headline && n.tone == Tone::Bad)));
}

#[test]
fn every_verdict_label_reaches_every_format() {
    let (old, new) = two_runs();
    let g = gate(&old, &new, GateOptions::default()).expect("comparable");
    let text = gate_text::to_text(&g);
    let markdown = gate_text::to_markdown(&g);
    let csv = gate_text::to_csv(&g);
    let json = serde_json::to_string(&g).expect("json");
    for v in Verdict::ALL {
        let label = v.label();
        assert!(text.contains(label), "text lacks {label}");
        assert!(markdown.contains(label), "markdown lacks {label}");
        assert!(csv.contains(&format!(",{label},")), "csv lacks {label}");
        let serde_name = serde_json::to_string(&v).expect("name");
        assert!(
            json.contains(&format!("\"verdict\":{serde_name}")),
            "json lacks {serde_name}"
        );
    }
    assert!(text.contains("changed: ops.dot: "), "{text}");
    assert!(markdown.contains("**slower**"));
    assert!(markdown.starts_with("### ❌ regression gate FAILED"));
    // The per-scene variant tables of one run label speed-ups by the same rule.
    let one = document::build(&[run("old", sample_results())]).expect("document");
    let variants = one
        .sections
        .iter()
        .find(|s| s.id == "variants-by-scene")
        .expect("variants-by-scene section");
    let labels: Vec<&str> = variants
        .blocks
        .iter()
        .filter_map(|b| match b {
            Block::Table(t) => Some(t),
            _ => None,
        })
        .flat_map(|t| t.rows.iter().flatten())
        .map(|c| c.text.as_str())
        .filter(|t| Verdict::ALL.iter().any(|v| v.label() == *t))
        .collect();
    assert!(!labels.is_empty());
}
