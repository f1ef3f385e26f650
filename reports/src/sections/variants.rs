//! The variants chapter (one scene × variant matrix of speed-ups with their costs) and
//! the appendix's per-scene tables: every variant on every scene, its time, speed-up,
//! image error and count changes against baseline.

use std::collections::BTreeSet;

use super::summary::{scene_line, time_covers};
use super::{access, answers};
use crate::document::{Block, Builder, Cell, Column, Inline, Section, Table, Tone};
use crate::format;
use crate::results::{Band, Quality, SceneResult, VariantResult};

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

/// The variants chapter: its finding, how to read it, the image-error against
/// speed-up scatter, and one scene × variant matrix of speed-ups, each with its cost
/// on that scene (see [`matrix_cell`]), the scenes grouped by family under each
/// family's geometric means. The per-scene tables are [`variants_by_scene`].
pub fn variants(b: &mut Builder) -> Section {
    let mut s = b.section(
        "variants",
        Some("ch. 8.3's proposed optimizations, each measured on every scene (the thesis tried them on one sphere)"),
    );
    let r = b.results();
    if r.scenes.iter().all(|s| s.variants.is_empty()) {
        return s.empty("No scene has a variant result (see Failures).");
    }
    // The matrix shows every variant, outside tracers too; the sentences are about
    // rtprof's own.
    let lines = answers::variant_lines(r);
    let own = answers::own_variant_lines(r);
    s.text(answers::optimization_sentence(&own));
    // The peer as its users run it (the yardstick) first, then Embree inside rtprof.
    let yardstick = super::peer_yardstick::sentence(r);
    let in_tool = super::peer::sentence(&own, yardstick.is_none());
    for sentence in [yardstick, in_tool].into_iter().flatten() {
        s.text(sentence);
    }
    if let Some((sentence, table)) = super::outside_tracers::outside_tracers(r) {
        s.text(sentence);
        s.blocks.push(Block::Table(table));
    }
    let recorded = super::outside_tracers::recorded(b);
    s.blocks.extend(recorded);
    s.blocks.push(Block::Paragraph {
        content: vec![
            Inline::text(format!(
                "Each cell: baseline's median time over the variant's ({}); its digits follow the 95 % bootstrap interval (the interval itself is in the HTML report's per-scene tables and in variants.csv). Coloured by the verdict (faster or slower only beyond the {} noise threshold with an interval excluding 1×) when the variant kept baseline's picture and rays on that scene; otherwise by what it cost there, named under the figure: the image error (RMS against baseline, coloured by the thesis's table 2 band) or the ray count that changed. Scenes without baseline show the variant's time. Every figure is in ",
                time_covers(r.suite.timing.covers),
                format::percent(
                    r.suite.noise_threshold.unwrap_or(crate::results::NOISE_THRESHOLD) * 100.0,
                    0
                ),
            )),
            Inline::Link {
                text: "the per-scene tables".to_string(),
                target: "variants-by-scene".to_string(),
            },
            Inline::text("."),
        ],
    });
    if let Some(warning) = repeats_warning(r) {
        s.blocks.push(Block::note(Tone::Warning, warning));
    }
    if let Some(figure) = b.chart("quality-speed", 9.0) {
        s.blocks.push(figure);
    }
    s.blocks.push(Block::Table(matrix(r, &lines)));
    s
}

/// A warning when some timed entries rest on few repeats (their interval is the
/// spread of those few, not a reliable 95 % interval).
fn repeats_warning(r: &crate::results::Results) -> Option<String> {
    let few: Vec<usize> = r
        .scenes
        .iter()
        .flat_map(|s| s.variants.iter())
        .map(|v| v.samples.len())
        .filter(|&n| n > 0 && n < FEW_REPEATS)
        .collect();
    if few.is_empty() {
        return None;
    }
    let all = r.scenes.iter().map(|s| s.variants.len()).sum::<usize>();
    Some(format!(
        "{} of {} entries rest on fewer than {} timed repeats (the suite times each for at least {} and {}): a bootstrap over so few renders gives about their range (lowest to highest), not a 95 % interval, so a verdict there rests on a handful of renders.",
        few.len(),
        all,
        FEW_REPEATS,
        format::seconds(r.suite.timing.min_seconds),
        format::plural(r.suite.timing.min_repeats as usize, "repeat"),
    ))
}

/// Fewer timed repeats than this make an interval the spread of a handful.
pub const FEW_REPEATS: usize = 5;

/// The scene × variant matrix: a heading row per family with its geometric means,
/// then its scenes.
fn matrix(r: &crate::results::Results, lines: &[answers::VariantLine]) -> Table {
    let variants: Vec<&answers::VariantLine> = lines.iter().collect();
    let mut columns = vec![
        Column::text("scene"),
        Column::number("baseline").detail("time"),
    ];
    columns.extend(variants.iter().map(|l| Column::number(l.variant.as_str())));
    let mut t = Table::new(columns).dense();
    let width = 2 + variants.len() as u32;
    for (g, (family, members)) in super::family_groups::FAMILY_GROUPS.iter().enumerate() {
        let scenes: Vec<&SceneResult> = r
            .scenes
            .iter()
            .filter(|s| members.contains(&s.family) && !s.variants.is_empty())
            .collect();
        if scenes.is_empty() {
            continue;
        }
        let mut head = vec![Cell::text(format!("{family}: geometric mean")).span(2)];
        for l in &variants {
            let f = &l.families[g];
            head.push(match f.geomean {
                Some(m) => Cell::number(format::speedup(m), m)
                    .detail(format!("{}/{}/{}", f.faster, f.within_noise, f.slower))
                    .tone(l.tone(g))
                    .hover(format!(
                        "{}: faster on {}, within noise on {}, slower on {} of {}",
                        l.label(g),
                        f.faster,
                        f.within_noise,
                        f.slower,
                        format::plural(f.scenes, "scene")
                    )),
                None => Cell::dash(),
            });
        }
        debug_assert_eq!(head.iter().map(|c| c.span).sum::<u32>(), width);
        t.rows.push(head);
        for scene in scenes {
            let base = access::reference(r, scene);
            let name = Cell::text(&scene.name).hover(scene_line(scene));
            let mut row = vec![
                match scene.threads {
                    Some(n) => name.detail(format::plural(n as usize, "thread")),
                    None => name,
                },
                match base {
                    Some(v) => Cell::estimate(v.time.median, v.time.low, v.time.high),
                    None => Cell::dash(),
                },
            ];
            for l in &variants {
                row.push(
                    match scene.variants.iter().find(|v| v.variant == l.variant) {
                        Some(v) => matrix_cell(v, base),
                        None => Cell::dash(),
                    },
                );
            }
            t.rows.push(row);
        }
    }
    t.caption(
        "Speed-up over baseline per scene and variant. Family rows: geometric mean, and faster / within noise / slower counts.",
    )
}

/// What a variant cost on one scene beside its time: the picture's error against the
/// reference variant's, or the largest relative change of a ray count, or nothing.
#[derive(Clone, Debug, PartialEq)]
pub enum SceneCost {
    None,
    /// The picture differs: its RMS and band.
    Picture(Band, f64),
    /// A `rays.*` count differs (and maybe the picture too): the counter, its change
    /// in percent, and the picture's band when it differs as well.
    Rays(String, f64, Option<(Band, f64)>),
}

/// The cost of `v` on its scene against `base` (see [`SceneCost`]).
pub fn scene_cost(v: &VariantResult, base: &VariantResult) -> SceneCost {
    let picture = v
        .quality
        .as_ref()
        .filter(|q| q.max_abs_diff > 0)
        .map(|q| (q.band, q.rms));
    let rays = base
        .counts
        .iter()
        .filter(|(k, _)| k.starts_with("rays."))
        .filter_map(|(k, &old)| {
            let new = v.counts.get(k).copied().unwrap_or(0);
            (new != old).then(|| {
                let change = if old == 0 {
                    f64::INFINITY
                } else {
                    (new as f64 / old as f64 - 1.0) * 100.0
                };
                (k.trim_start_matches("rays.").to_string(), change)
            })
        })
        .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()));
    match (rays, picture) {
        (Some((key, change)), picture) => SceneCost::Rays(key, change, picture),
        (None, Some((band, rms))) => SceneCost::Picture(band, rms),
        (None, None) => SceneCost::None,
    }
}

/// One matrix cell: the speed-up, toned by its verdict when the variant cost nothing
/// on the scene, else by the cost, which the detail names (a costly variant never
/// shows as plainly faster). Without baseline: the variant's time.
pub fn matrix_cell(v: &VariantResult, base: Option<&VariantResult>) -> Cell {
    let Some(base) = base.filter(|_| v.speedup.is_some()) else {
        return Cell::estimate(v.time.median, v.time.low, v.time.high)
            .tone(Tone::Muted)
            .hover("no baseline on this scene: the variant's time");
    };
    // The digits follow the interval; the interval itself is in the hover and the
    // per-scene tables, so that the detail line is the cost alone.
    let mut cell = Cell::ratio(access::speedup(v), v.speedup_interval);
    let interval = cell
        .detail
        .take()
        .map_or_else(String::new, |i| format!("95 % interval {i}; "));
    let verdict = v.verdict.map_or(Tone::Neutral, Tone::of_verdict);
    let cell = cell.hover(format!(
        "{interval}{}",
        v.verdict.map_or("no verdict", |x| x.label())
    ));
    match scene_cost(v, base) {
        SceneCost::None => cell.tone(verdict),
        SceneCost::Picture(band, rms) => cell
            .detail(format!("RMS {}", format::fixed(rms, 1)))
            .tone(Tone::of_band(band).worse(Tone::Fair))
            .hover(format!(
                "{interval}the picture changed: RMS {} against baseline ({band})",
                format::fixed(rms, 2)
            )),
        SceneCost::Rays(key, change, picture) => {
            let band = picture.map_or(Tone::Fair, |(b, _)| Tone::of_band(b));
            cell.detail(format!("{key} {}", format::signed_change(change, 0)))
                .tone(band.worse(Tone::Warning))
                .hover(format!(
                    "{interval}the rays changed: {key} {} against baseline{}",
                    format::signed_change(change, 1),
                    picture.map_or_else(String::new, |(b, rms)| format!(
                        "; the picture too: RMS {} ({b})",
                        format::fixed(rms, 2)
                    ))
                ))
        }
    }
}

/// Every variant on every scene, one table per scene (the appendix).
pub fn variants_by_scene(b: &mut Builder) -> Section {
    let mut s = b.section(
        "variants-by-scene",
        Some("ch. 8.3's proposed optimizations, each measured on every scene (the thesis tried them on one sphere)"),
    );
    s.html_only = true;
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
        s.blocks
            .push(Block::Table(scene_table(scene, base, Detail::Full)));
        if base.is_none() {
            s.blocks.push(Block::empty(
                "Baseline did not run on this scene: no speed-ups or count deltas to compare.",
            ));
        }
    }
    s
}

/// How much of a scene's counts a [`scene_table`] shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Detail {
    /// The main counters as columns, then the other counters that changed (the
    /// report's appendix).
    Full,
    /// One column naming the counters that changed (a terminal's width: `rtprof
    /// compare`).
    Compact,
}

/// The variants of one scene against `base` (the reference variant's result): time,
/// speed-up, verdict, image error against `base` and against the f64 reference, and
/// the counts. The one table of a scene's variants: the report's appendix and `rtprof
/// compare` (terminal and Markdown) both print it. A preprocessing column when the
/// results have the figure; the f64 column when some variant has it.
pub fn scene_table(scene: &SceneResult, base: Option<&VariantResult>, detail: Detail) -> Table {
    let preprocessing = scene
        .variants
        .iter()
        .any(|v| v.preprocessing_seconds.is_some());
    let truth = scene.variants.iter().any(|v| v.vs_f64_reference.is_some());
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
    ]);
    if truth {
        columns.push(Column::number("RMS vs f64").detail("reference"));
    }
    if detail == Detail::Full {
        columns.extend(MAIN_COUNTERS.iter().map(|(_, name)| Column::number(*name)));
        columns.push(Column::text("other count changes").grow());
    } else {
        columns.push(Column::text("count changes").grow());
    }
    let mut t = Table::new(columns).sortable().dense();
    let is_base = |v: &VariantResult| base.is_some_and(|b| b.variant == v.variant);
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
            None if is_base(v) => Cell::text("reference").tone(Tone::Muted),
            None => Cell::dash(),
        });
        row.extend(quality_cells(v, is_base(v)));
        if truth {
            row.push(match &v.vs_f64_reference {
                Some(q) => Cell::number(format::fixed(q.rms, 2), q.rms)
                    .tone(Tone::of_band(q.band))
                    .hover(format!(
                        "against the f64 reference renderer's picture: largest difference {}",
                        q.max_abs_diff
                    )),
                None => Cell::dash(),
            });
        }
        if detail == Detail::Full {
            for (key, _) in MAIN_COUNTERS {
                row.push(counter_cell(v, base, key));
            }
        }
        row.push(if is_base(v) {
            Cell::text("reference").tone(Tone::Muted)
        } else if v.variant.is_outside() && v.counts.is_empty() {
            // An outside program counts only through the probe: nothing is not zero.
            Cell::text("not counted (no probe)").tone(Tone::Muted)
        } else {
            other_changes(base, v, detail == Detail::Full)
        });
        t.rows.push(row);
    }
    t
}

/// RMS, band, PSNR, SSIM and max diff; one cell over all five without metrics.
fn quality_cells(v: &VariantResult, is_base: bool) -> Vec<Cell> {
    match &v.quality {
        _ if is_base => vec![Cell::text("reference image").tone(Tone::Muted).span(5)],
        Some(q) => quality(q),
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
    if v.variant.is_outside() && value.is_none() {
        return Cell::text("not counted")
            .tone(Tone::Muted)
            .hover("an outside program: counted only where its probe counts".to_string());
    }
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

/// The counters whose counts differ from `base`'s (outside [`MAIN_COUNTERS`] with
/// `beside_main`), largest relative change first.
fn other_changes(base: Option<&VariantResult>, v: &VariantResult, beside_main: bool) -> Cell {
    let Some(base) = base else {
        return Cell::text("no reference").tone(Tone::Muted);
    };
    let keys: BTreeSet<&String> = base.counts.keys().chain(v.counts.keys()).collect();
    let mut changes: Vec<(f64, String)> = keys
        .into_iter()
        .filter(|k| !beside_main || !MAIN_COUNTERS.iter().any(|(main, _)| main == k))
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::results::Verdict;
    use testkit::sample::sample_results;

    /// A sample scene's baseline and one of its other variants.
    fn pair() -> (VariantResult, VariantResult) {
        let r = sample_results();
        let scene = r
            .scenes
            .iter()
            .find(|s| s.variants.len() > 1 && s.variants.iter().any(|v| v.variant.is_reference()))
            .unwrap_or_else(|| panic!("a sample scene with baseline and another variant"));
        let base = scene
            .variants
            .iter()
            .find(|v| v.variant.is_reference())
            .cloned()
            .unwrap_or_else(|| panic!("baseline"));
        let mut v = scene
            .variants
            .iter()
            .find(|v| !v.variant.is_reference())
            .cloned()
            .unwrap_or_else(|| panic!("a variant"));
        // Faster, same picture and rays as baseline.
        v.speedup = Some(2.0);
        v.speedup_interval = Some([1.9, 2.1]);
        v.verdict = Some(Verdict::Faster);
        v.counts = base.counts.clone();
        if let Some(q) = v.quality.as_mut() {
            q.max_abs_diff = 0;
            q.rms = 0.0;
            q.band = Band::of(0.0);
        }
        (base, v)
    }

    #[test]
    fn a_cell_that_cost_nothing_is_toned_by_its_verdict() {
        let (base, v) = pair();
        assert_eq!(scene_cost(&v, &base), SceneCost::None);
        let cell = matrix_cell(&v, Some(&base));
        assert_eq!(cell.tone, Tone::Good);
        assert_eq!(cell.detail, None, "no cost to name");
        assert!(cell.hover.as_deref().unwrap_or("").contains("interval"));
    }

    #[test]
    fn a_cell_whose_rays_or_picture_changed_is_never_plainly_faster() {
        let (base, mut v) = pair();
        // Primary hits fall from 100,698 to 24,605 (fast-sqrt on lattice5): -75.6 %.
        v.counts.insert("rays.primary_hit".into(), 24_605);
        let mut base = base;
        base.counts.insert("rays.primary_hit".into(), 100_698);
        match scene_cost(&v, &base) {
            SceneCost::Rays(key, change, None) => {
                assert_eq!(key, "primary_hit");
                assert!((change - (24_605.0 / 100_698.0 - 1.0) * 100.0).abs() < 1e-9);
            }
            other => panic!("{other:?}"),
        }
        let cell = matrix_cell(&v, Some(&base));
        assert_eq!(cell.tone, Tone::Warning);
        assert_eq!(cell.detail.as_deref(), Some("primary_hit −76 %"));

        // Same rays, a picture in the "similar" band (RMS 20): fair, the RMS named.
        let (base, mut v) = pair();
        if let Some(q) = v.quality.as_mut() {
            q.max_abs_diff = 40;
            q.rms = 20.0;
            q.band = Band::of(20.0);
        }
        let cell = matrix_cell(&v, Some(&base));
        assert_eq!(cell.detail.as_deref(), Some("RMS 20.0"));
        assert_ne!(cell.tone, Tone::Good);
        assert_eq!(cell.tone, Tone::of_band(Band::of(20.0)).worse(Tone::Fair));
    }

    #[test]
    fn a_scene_without_baseline_shows_the_variant_time() {
        let (_, mut v) = pair();
        v.speedup = None;
        let cell = matrix_cell(&v, None);
        assert_eq!(cell.tone, Tone::Muted);
        assert_eq!(cell.sort, Some(v.time.median));
    }
}
