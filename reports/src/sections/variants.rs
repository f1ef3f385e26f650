//! The variants section: every variant on every scene, its time, speed-up, image error
//! and count changes against baseline.

use std::collections::BTreeSet;

use super::access;
use super::summary::scene_line;
use crate::document::{Block, Builder, Cell, Column, Section, Table, Tone};
use crate::format;
use crate::results::{Quality, SceneResult, TimeCovers, VariantResult};

/// What a time of the run covers, in words.
pub fn time_covers(covers: TimeCovers) -> &'static str {
    match covers {
        TimeCovers::Tracing => "tracing only (scene preparation and structure build apart)",
        TimeCovers::PreprocessingAndTracing => {
            "scene preparation, structure build and tracing together (an rtprof.results/1 file)"
        }
    }
}

/// Counters shown as their own columns: key and header.
const MAIN_COUNTERS: [(&str, &str); 5] = [
    ("ops.dot", "dot"),
    ("ops.sqrt", "sqrt"),
    ("ops.normalize", "normalize"),
    ("calls.intersect", "intersect calls"),
    ("rays.primary", "primary rays"),
];

/// How many changed counters the last column names before "n more".
const CHANGES_NAMED: usize = 3;

pub fn variants(b: &mut Builder) -> Section {
    let mut s = b.section(
        "variants",
        Some("ch. 8.3's proposed optimizations, each measured on every scene (the thesis tried them on one sphere)"),
    );
    let r = b.results();
    if r.scenes.iter().all(|s| s.variants.is_empty()) {
        return s.empty("No scene has a variant result (see Failures).");
    }
    s.blocks.push(Block::text(format!(
        "Time: {}, the median of the timed repeats with its 95 % bootstrap interval. Speed-up: baseline median / variant median, with its 95 % bootstrap interval; the variants were timed interleaved with baseline. Verdict: faster or slower only when the speed-up exceeds the noise threshold of {} and its interval excludes 1×, else within noise (the same rule as the regression gate). RMS, PSNR, SSIM: the image against baseline (PSNR ∞: identical); the band is the thesis's table 2. RMS vs f64: the image against the independent f64 reference renderer's picture (docs/reference.md), baseline's own included. Count columns: baseline's exact count, and each variant's change from it; the last column names the other counters that changed.",
        time_covers(r.suite.timing.covers),
        format::percent(
            r.suite.noise_threshold.unwrap_or(crate::results::NOISE_THRESHOLD) * 100.0,
            0
        )
    )));
    if let Some(figure) = b.chart("quality-speed", 11.0) {
        s.blocks.push(figure);
    }
    for scene in &r.scenes {
        s.blocks.push(Block::Heading {
            level: 2,
            text: scene.name.clone(),
            detail: Some(scene_line(scene)),
            anchor: Some(format!("variants-{}", crate::slug(&scene.name))),
        });
        if scene.variants.is_empty() {
            s.blocks
                .push(Block::empty("No variant of this scene ran (see Failures)."));
            continue;
        }
        let base = access::reference(r, scene);
        s.blocks.push(Block::Table(variant_table(scene, base)));
        if base.is_none() {
            s.blocks.push(Block::empty(
                "Baseline did not run on this scene: no speed-ups or count deltas to compare.",
            ));
        }
    }
    s
}

/// The variants of one scene; a preprocessing column when the file has the figure.
fn variant_table(scene: &SceneResult, base: Option<&VariantResult>) -> Table {
    let preprocessing = scene
        .variants
        .iter()
        .any(|v| v.preprocessing_seconds.is_some());
    let mut columns = vec![
        Column::text("variant"),
        Column::number("time").detail("[95 % interval]"),
    ];
    if preprocessing {
        columns.push(Column::number("preprocessing"));
    }
    columns.extend([
        Column::number("speed-up").detail("[95 % interval]"),
        Column::text("verdict"),
        Column::number("RMS"),
        Column::text("band"),
        Column::number("PSNR"),
        Column::number("SSIM"),
        Column::number("max diff"),
        Column::number("RMS vs f64").detail("reference"),
    ]);
    columns.extend(MAIN_COUNTERS.iter().map(|(_, name)| Column::number(*name)));
    columns.push(Column::text("other count changes").grow());
    let mut t = Table::new(columns).sortable().dense();
    for v in &scene.variants {
        let mut row = vec![
            Cell::text(v.variant.as_str()),
            Cell::estimate(v.time.median, v.time.low, v.time.high),
        ];
        if preprocessing {
            row.push(match v.preprocessing_seconds {
                Some(s) => Cell::number(format::seconds(s), s),
                None => Cell::dash(),
            });
        }
        let speedup = access::speedup(v);
        row.push(match v.verdict {
            Some(verdict) => {
                Cell::ratio(speedup, v.speedup_interval).tone(Tone::of_verdict(verdict))
            }
            None => Cell::ratio(speedup, v.speedup_interval),
        });
        row.push(match v.verdict {
            Some(verdict) => Cell::verdict(verdict),
            None if v.variant.is_reference() => Cell::text("reference").tone(Tone::Muted),
            None => Cell::dash(),
        });
        row.extend(quality_cells(v));
        row.push(match &v.vs_f64_reference {
            Some(q) => Cell::number(format::fixed(q.rms, 2), q.rms)
                .tone(Tone::of_band(q.band))
                .hover(format!(
                    "against the f64 reference renderer's picture: largest difference {}",
                    q.max_abs_diff
                )),
            None => Cell::dash(),
        });
        for (key, _) in MAIN_COUNTERS {
            row.push(counter_cell(v, base, key));
        }
        row.push(other_changes(base, v));
        t.rows.push(row);
    }
    t
}

/// RMS, band, PSNR, SSIM and max diff; one cell over all five without metrics.
fn quality_cells(v: &VariantResult) -> Vec<Cell> {
    match &v.quality {
        Some(q) => quality(q),
        None if v.variant.is_reference() => {
            vec![Cell::text("reference image").tone(Tone::Muted).span(5)]
        }
        None => vec![Cell::text("no image metrics").tone(Tone::Muted).span(5)],
    }
}

fn quality(q: &Quality) -> Vec<Cell> {
    let band = q.band;
    vec![
        Cell::number(format::fixed(q.rms, 2), q.rms),
        Cell::text(band.name()).tone(Tone::of_band(band)),
        match q.psnr {
            Some(p) => Cell::number(format!("{} dB", format::fixed(p, 1)), p),
            None => Cell::number("∞", f64::MAX),
        },
        Cell::number(format::fixed(q.ssim, 4), q.ssim),
        Cell::count(u64::from(q.max_abs_diff)),
    ]
}

/// A main counter: baseline's exact count; a variant's change from it.
fn counter_cell(v: &VariantResult, base: Option<&VariantResult>, key: &str) -> Cell {
    let value = v.counts.get(key).copied();
    let reference = base.and_then(|b| b.counts.get(key).copied());
    let inside_queries = ["ops.", "tests.", "accel."]
        .iter()
        .any(|p| key.starts_with(p));
    if inside_queries && !v.variant.counts_its_work() {
        // Embree: the work inside a query is uncounted, so a drop would be a lie.
        return Cell::text("not counted").tone(Tone::Muted).hover(format!(
            "{} counted outside Embree's queries (shading); the queries' own work is not counted",
            format::count(value.unwrap_or(0))
        ));
    }
    match (value, reference) {
        (Some(n), _) if v.variant.is_reference() => Cell::count(n),
        (Some(n), Some(b)) if n == b => Cell::number("=", 0.0)
            .tone(Tone::Muted)
            .hover(format::count(n)),
        (Some(n), Some(b)) if b > 0 => {
            let delta = (n as f64 - b as f64) / b as f64 * 100.0;
            Cell::number(format::signed_change(delta, 1), delta)
                .tone(Tone::of_count(n, b))
                .hover(format!(
                    "{} (baseline {})",
                    format::count(n),
                    format::count(b)
                ))
        }
        (Some(n), _) => Cell::count(n),
        (None, _) => Cell::dash(),
    }
}

/// The counters outside [`MAIN_COUNTERS`] whose counts differ from baseline, largest
/// relative change first.
fn other_changes(base: Option<&VariantResult>, v: &VariantResult) -> Cell {
    let Some(base) = base else {
        return Cell::text("no baseline").tone(Tone::Muted);
    };
    if v.variant.is_reference() {
        return Cell::text("reference").tone(Tone::Muted);
    }
    let keys: BTreeSet<&String> = base.counts.keys().chain(v.counts.keys()).collect();
    let mut changes: Vec<(f64, String)> = keys
        .into_iter()
        .filter(|k| !MAIN_COUNTERS.iter().any(|(main, _)| main == k))
        .filter_map(|k| {
            let old = base.counts.get(k).copied().unwrap_or(0);
            let new = v.counts.get(k).copied().unwrap_or(0);
            if old == new {
                return None;
            }
            Some(if old == 0 {
                (f64::INFINITY, format!("{k} 0 → {}", format::count(new)))
            } else {
                let pct = (new as f64 / old as f64 - 1.0) * 100.0;
                (pct.abs(), format!("{k} {}", format::signed_change(pct, 0)))
            })
        })
        .collect();
    if changes.is_empty() {
        return Cell::text("none").tone(Tone::Muted);
    }
    changes.sort_by(|a, b| b.0.total_cmp(&a.0).then_with(|| a.1.cmp(&b.1)));
    let all: Vec<String> = changes.into_iter().map(|(_, text)| text).collect();
    let mut shown: Vec<String> = all.iter().take(CHANGES_NAMED).cloned().collect();
    if all.len() > CHANGES_NAMED {
        shown.push(format!("{} more", all.len() - CHANGES_NAMED));
    }
    Cell::number(shown.join(", "), all.len() as f64).hover(all.join("\n"))
}
