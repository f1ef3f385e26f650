//! The answers: the report's first section, the three questions the study asks, each a
//! sentence written from the data with one table:
//! - *where the time goes*: the run's profile set against the thesis's table 6 row by
//!   row (share of the time and calls per eye ray), and the most-called operation;
//! - *what each optimization buys and costs*: per scene family, each variant's
//!   geometric-mean speed-up with its faster / within noise / slower counts, beside what
//!   it changed (the picture's worst band and RMS, the rays). A variant that changed
//!   the picture or the rays is never labelled plainly "faster": its label carries the
//!   cost and its cells its tone;
//! - *would the FPGA pay off*: the break-even of [`super::fpga_answer`].
//!
//! The computations are plain functions of the results (tested by hand); the section
//! only lays them out.

use super::family_groups::FAMILY_GROUPS;
use super::fpga_answer::{FpgaAnswer, break_even_table, fpga_answer};
use crate::document::{Block, Builder, Cell, Column, Inline, Section, Table, Tone};
use crate::findings::geometric_mean;
use crate::format;
use crate::results::thesis_profile::{TABLE_6, TABLE_6_EYE_RAYS, TABLE_6_SCENE};
use crate::results::{Band, Profile, Results, VariantName, Verdict};

pub fn answers(b: &mut Builder) -> Section {
    let mut s = b.section(
        "answers",
        Some("the questions of ch. 8: bottleneck, optimizations, hardware"),
    );
    let answers = three_answers(b.results());
    // The three sentences first, so that the first screen (or page) holds all three
    // answers; then each answer's table under its question.
    for answer in &answers {
        s.blocks.push(Block::Paragraph {
            content: vec![
                Inline::strong(if answer.question.ends_with('?') {
                    answer.question.to_string()
                } else {
                    format!("{}:", answer.question)
                }),
                Inline::text(" "),
                Inline::text(answer.sentence.as_deref().unwrap_or(answer.why_none)),
            ],
        });
    }
    for answer in answers {
        if answer.warning.is_none() && answer.table.is_none() {
            continue;
        }
        s.blocks.push(Block::heading(answer.question));
        if let Some(warning) = answer.warning {
            s.blocks.push(Block::note(Tone::Warning, warning));
        }
        if let Some(table) = answer.table {
            s.blocks.push(Block::Table(table));
        }
    }
    s
}

/// One of the three answers: its question, the sentence written from the data and its
/// table, or why there is none.
#[derive(Clone, Debug)]
pub struct Answer {
    /// The question, as a heading: "Where the time goes", "Would the FPGA pay off?".
    pub question: &'static str,
    pub sentence: Option<String>,
    pub warning: Option<String>,
    pub table: Option<Table>,
    /// Why there is no answer (shown when `sentence` is `None`).
    pub why_none: &'static str,
}

/// Where the time goes, what each optimization buys and costs, whether the FPGA pays
/// off: the one model the report's first page and summary.md are written from.
pub fn three_answers(r: &Results) -> [Answer; 3] {
    let time = match r.profile.as_ref() {
        Some(p) => {
            let rows = table6_rows(&p.baseline);
            Answer {
                question: "Where the time goes",
                sentence: Some(time_sentence(&p.scene, &p.baseline, &rows)),
                warning: (!is_thesis_scene(&p.scene)).then(|| format!(
                    "The profile is of {}, not of the thesis's {TABLE_6_SCENE}: the rows below compare different scenes.",
                    p.scene
                )),
                table: Some(table6_table(&rows).caption(format!(
                    "{} at {} (baseline) against table 6 ({TABLE_6_SCENE}); calls per eye ray make the two frame sizes comparable",
                    p.scene,
                    format::size(p.width, p.height)
                ))),
                why_none: "",
            }
        }
        None => Answer {
            question: "Where the time goes",
            sentence: None,
            warning: None,
            table: None,
            why_none: "No profile in this run: the suite ran without profiling, or the profile failed (see Failures).",
        },
    };
    let lines = own_variant_lines(r);
    let optimizations = Answer {
        question: "What each optimization buys and costs",
        // The outside tracers are no optimization; the answer sets rtprof beside them.
        sentence: (!lines.is_empty()).then(|| {
            let own = optimization_sentence(&lines);
            match super::outside_tracers::answer_clause(r) {
                Some(clause) => format!("{own} {clause}"),
                None => own,
            }
        }),
        warning: None,
        table: (!lines.is_empty()).then(|| variants_table(&lines, &families_present(r))),
        why_none: "No variant ran beside the reference variant on any scene.",
    };
    let answer = fpga_answer(r);
    let fpga = Answer {
        question: "Would the FPGA pay off?",
        sentence: answer.as_ref().map(FpgaAnswer::sentence),
        warning: None,
        table: answer.as_ref().map(break_even_table),
        why_none: "No break-even: the run timed rtprof's peer variant on the hardware's job on fewer than two primitive counts of the thesis's test bench.",
    };
    [time, optimizations, fpga]
}

/// Whether a profiled scene is the thesis's (SPD rings).
fn is_thesis_scene(scene: &str) -> bool {
    scene == "rings" || scene.starts_with("rings-") || scene.starts_with("rings.")
}

/// One row of table 6 beside the run's profile.
#[derive(Clone, Debug, PartialEq)]
pub struct Table6Comparison {
    pub thesis_name: &'static str,
    pub thesis_percent: f64,
    pub thesis_per_ray: f64,
    /// The phase's share of the samples (self), when the work is a profile phase.
    pub percent: Option<f64>,
    /// Calls per eye ray from the profile's counts; `None` without counts.
    pub per_ray: Option<f64>,
}

/// Table 6's rows with the run's shares and calls per eye ray.
pub fn table6_rows(profile: &Profile) -> Vec<Table6Comparison> {
    let eye_rays = profile.counts.get("rays.primary").copied().unwrap_or(0);
    TABLE_6
        .iter()
        .map(|row| Table6Comparison {
            thesis_name: row.thesis_name,
            thesis_percent: row.percent,
            thesis_per_ray: row.calls / TABLE_6_EYE_RAYS as f64,
            percent: row.phase.and_then(|phase| {
                profile
                    .flat
                    .iter()
                    .find(|f| f.name == phase)
                    .map(|f| f.percent)
                    .or(Some(0.0))
            }),
            per_ray: (eye_rays > 0).then(|| {
                profile.counts.get(row.counter).copied().unwrap_or(0) as f64 / eye_rays as f64
            }),
        })
        .collect()
}

/// The most-called vector or scalar operation of table 6's rows: (name, per ray).
fn most_called(
    rows: &[Table6Comparison],
    of: impl Fn(&Table6Comparison) -> Option<f64>,
) -> Option<(&'static str, f64)> {
    rows.iter()
        .filter(|r| {
            TABLE_6
                .iter()
                .any(|t| t.thesis_name == r.thesis_name && t.counter.starts_with("ops."))
        })
        .filter_map(|r| Some((r.thesis_name, of(r)?)))
        .max_by(|a, b| a.1.total_cmp(&b.1))
}

/// The answer's sentence: the bottleneck by self time, set beside table 6's, and the
/// most-called operation in both.
pub fn time_sentence(scene: &str, profile: &Profile, rows: &[Table6Comparison]) -> String {
    let top = profile.bottleneck().map_or_else(
        || "no phase has samples".to_string(),
        |f| {
            format!(
                "the {} takes the most time itself, {}",
                f.name,
                format::percent(f.percent, 1)
            )
        },
    );
    let thesis_top = TABLE_6
        .iter()
        .filter(|t| t.phase.is_some())
        .max_by(|a, b| a.percent.total_cmp(&b.percent))
        .map_or_else(String::new, |t| {
            format!(
                " (table 6: {}, {} of the run)",
                t.thesis_name,
                format::percent(t.percent, 1)
            )
        });
    let ours = most_called(rows, |r| r.per_ray);
    let theirs = most_called(rows, |r| Some(r.thesis_per_ray));
    let calls = match (ours, theirs) {
        (Some((ours, n)), Some((theirs, m))) => format!(
            " The most-called operation is {ours}, {} calls per eye ray; in table 6 it is {theirs}, {} per ray{}.",
            format::quantity(n),
            format::quantity(m),
            if theirs == "Vector dotPoint" {
                ", as the thesis says"
            } else {
                ", although the thesis names the dot product"
            }
        ),
        _ => String::new(),
    };
    format!("In the profile of {scene}, {top}{thesis_top}.{calls}")
}

fn table6_table(rows: &[Table6Comparison]) -> Table {
    let mut t = Table::new(vec![
        Column::text("table 6 row"),
        Column::number("thesis % self"),
        Column::number("rtprof % self"),
        Column::number("thesis calls").detail("per eye ray"),
        Column::number("rtprof calls").detail("per eye ray"),
    ])
    .dense();
    for r in rows {
        t.rows.push(vec![
            Cell::text(r.thesis_name),
            Cell::number(format::fixed(r.thesis_percent, 2), r.thesis_percent),
            match r.percent {
                Some(p) => Cell::number(format::fixed(p, 2), p),
                None => Cell::text("counted, not timed")
                    .tone(Tone::Muted)
                    .hover("inlined into its callers: the profile's phases time the tests and shading that call it"),
            },
            Cell::number(format::quantity(r.thesis_per_ray), r.thesis_per_ray),
            match r.per_ray {
                Some(n) => Cell::number(format::quantity(n), n),
                None => Cell::dash(),
            },
        ]);
    }
    t
}

/// A variant in one family group: geometric-mean speed-up and verdicts.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FamilyFigures {
    pub geomean: Option<f64>,
    pub scenes: usize,
    pub faster: usize,
    pub within_noise: usize,
    pub slower: usize,
}

impl FamilyFigures {
    /// "faster" or "slower" when most scenes say so, "within noise" when none is
    /// either, else "mixed".
    pub fn verdict(&self) -> &'static str {
        let (f, n, s) = (self.faster, self.within_noise, self.slower);
        if f > s + n {
            "faster"
        } else if s > f + n {
            "slower"
        } else if f + s == 0 {
            "within noise"
        } else {
            "mixed"
        }
    }
}

/// What a variant bought and cost over the run.
#[derive(Clone, Debug, PartialEq)]
pub struct VariantLine {
    pub variant: VariantName,
    /// One per [`FAMILY_GROUPS`] entry.
    pub families: Vec<FamilyFigures>,
    /// The worst band and RMS of its pictures against the reference variant's.
    pub worst: Option<(Band, f64)>,
    /// Whether any of its pictures differs from the reference variant's at all.
    pub picture_changed: bool,
    /// Scenes where some `rays.*` count differs from the reference variant's.
    pub rays_changed: usize,
    pub compared: usize,
}

impl VariantLine {
    /// Whether the speed-up comes with a cost a reader must see beside it.
    pub fn has_cost(&self) -> bool {
        self.picture_changed || self.rays_changed > 0
    }

    /// What it costs beside its time: "nothing" or what it changes.
    pub fn cost_label(&self) -> String {
        match (self.picture_changed, self.rays_changed > 0) {
            (false, false) => "nothing: the same picture and rays".to_string(),
            (true, false) => "changes the picture".to_string(),
            (false, true) => "changes the rays".to_string(),
            (true, true) => "changes the picture and the rays".to_string(),
        }
    }

    /// The verdict in family group `g` (see [`FamilyFigures::verdict`]), with the cost
    /// when there is one: a costly variant is never plainly "faster".
    pub fn label(&self, g: usize) -> String {
        let verdict = self.families[g].verdict();
        if self.has_cost() {
            format!("{verdict}, but {}", self.cost_label())
        } else {
            verdict.to_string()
        }
    }

    /// The tone of its speed-ups in family group `g`: by the verdict when the picture
    /// and rays are kept; otherwise the cost's tone (the worse of the band's and, for
    /// changed rays, a warning), never better than fair.
    pub fn tone(&self, g: usize) -> Tone {
        if !self.has_cost() {
            return match self.families[g].verdict() {
                "faster" => Tone::Good,
                "slower" => Tone::Bad,
                _ => Tone::Neutral,
            };
        }
        self.cost_tone()
    }

    /// The cost's tone: the worse of the picture's band and, for changed rays, a
    /// warning; never better than fair. Neutral without a cost.
    pub fn cost_tone(&self) -> Tone {
        if !self.has_cost() {
            return Tone::Muted;
        }
        let band = self.worst.map_or(Tone::Fair, |(b, _)| Tone::of_band(b));
        let rays = if self.rays_changed > 0 {
            Tone::Warning
        } else {
            Tone::Fair
        };
        band.worse(rays).worse(Tone::Fair)
    }
}

/// Every variant but the reference, in first-seen order, over the scenes that ran the
/// reference variant too.
pub fn variant_lines(r: &Results) -> Vec<VariantLine> {
    let mut lines: Vec<VariantLine> = Vec::new();
    for scene in &r.scenes {
        let Some(base) = scene.variants.iter().find(|v| v.variant.is_reference()) else {
            continue;
        };
        let group = FAMILY_GROUPS
            .iter()
            .position(|(_, members)| members.contains(&scene.family))
            .unwrap_or(FAMILY_GROUPS.len() - 1);
        for v in scene.variants.iter().filter(|v| !v.variant.is_reference()) {
            let i = match lines.iter().position(|l| l.variant == v.variant) {
                Some(i) => i,
                None => {
                    lines.push(VariantLine {
                        variant: v.variant.clone(),
                        families: vec![FamilyFigures::default(); FAMILY_GROUPS.len()],
                        worst: None,
                        picture_changed: false,
                        rays_changed: 0,
                        compared: 0,
                    });
                    lines.len() - 1
                }
            };
            let line = &mut lines[i];
            let fam = &mut line.families[group];
            fam.scenes += 1;
            match v.verdict {
                Some(Verdict::Faster) => fam.faster += 1,
                Some(Verdict::Slower) => fam.slower += 1,
                Some(Verdict::WithinNoise) => fam.within_noise += 1,
                None => {}
            }
            line.compared += 1;
            if let Some(q) = &v.quality {
                if q.max_abs_diff > 0 {
                    line.picture_changed = true;
                }
                let worse = line.worst.is_none_or(|(_, rms)| q.rms > rms);
                if worse && q.rms.is_finite() {
                    line.worst = Some((q.band, q.rms));
                }
            }
            let rays_differ = base
                .counts
                .iter()
                .filter(|(k, _)| k.starts_with("rays."))
                .any(|(k, n)| v.counts.get(k) != Some(n));
            if rays_differ {
                line.rays_changed += 1;
            }
        }
    }
    // The geometric means per family, from the speed-ups.
    for line in &mut lines {
        for (g, (_, members)) in FAMILY_GROUPS.iter().enumerate() {
            let speedups = r
                .scenes
                .iter()
                .filter(|s| members.contains(&s.family))
                .flat_map(|s| s.variants.iter())
                .filter(|v| v.variant == line.variant)
                .filter_map(|v| v.speedup);
            line.families[g].geomean = geometric_mean(speedups).map(|(m, _)| m);
        }
    }
    lines
}

/// [`variant_lines`] of rtprof's own variants: the answers and findings are about
/// them; outside tracers have their own table (`sections::outside_tracers`).
pub fn own_variant_lines(r: &Results) -> Vec<VariantLine> {
    let mut lines = variant_lines(r);
    lines.retain(|l| !l.variant.is_outside());
    lines
}

/// The family groups that hold a scene with the reference variant.
fn families_present(r: &Results) -> Vec<usize> {
    (0..FAMILY_GROUPS.len())
        .filter(|&g| {
            r.scenes.iter().any(|s| {
                FAMILY_GROUPS[g].1.contains(&s.family)
                    && s.variants.iter().any(|v| v.variant.is_reference())
            })
        })
        .collect()
}

/// The answer's sentence: per family, the fastest variant that kept the picture and
/// the rays; then the variants whose speed comes with a cost.
pub fn optimization_sentence(lines: &[VariantLine]) -> String {
    let mut parts = Vec::new();
    for (g, (family, _)) in FAMILY_GROUPS.iter().enumerate() {
        let best = lines
            .iter()
            .filter(|l| !l.has_cost())
            .filter_map(|l| Some((l, l.families[g].geomean?)))
            .max_by(|a, b| a.1.total_cmp(&b.1));
        if let Some((l, mean)) = best {
            let f = &l.families[g];
            parts.push(format!(
                "on the {family} scenes, {} ({} geometric mean; faster on {} of {}, slower on {})",
                l.variant,
                format::speedup(mean),
                f.faster,
                format::plural(f.scenes, "scene"),
                f.slower
            ));
        }
    }
    let costly: Vec<String> = lines
        .iter()
        .filter(|l| l.has_cost())
        .map(|l| {
            let worst = l.worst.map_or_else(String::new, |(band, rms)| {
                format!("worst RMS {}, {band}", format::fixed(rms, 1))
            });
            let rays = if l.rays_changed > 0 {
                format!(
                    "{}rays changed on {} of {}",
                    if worst.is_empty() { "" } else { ", " },
                    l.rays_changed,
                    format::plural(l.compared, "scene")
                )
            } else {
                String::new()
            };
            format!("{} ({worst}{rays})", l.variant)
        })
        .collect();
    let kept = if parts.is_empty() {
        "No variant kept both the picture and the rays.".to_string()
    } else {
        format!(
            "The fastest variant that keeps the picture and the rays: {}.",
            parts.join("; ")
        )
    };
    if costly.is_empty() {
        kept
    } else {
        format!(
            "{kept} Faster at a cost, to be weighed against it: {}.",
            format::join_list(&costly)
        )
    }
}

fn variants_table(lines: &[VariantLine], families: &[usize]) -> Table {
    let mut columns = vec![Column::text("variant")];
    for &g in families {
        columns.push(Column::number(FAMILY_GROUPS[g].0).detail("geo. mean · faster/noise/slower"));
    }
    columns.extend([
        Column::text("cost"),
        Column::text("picture").detail("worst vs baseline"),
        Column::text("rays"),
    ]);
    let mut t = Table::new(columns).dense();
    for l in lines {
        let mut row = vec![Cell::text(l.variant.as_str())];
        for &g in families {
            let f = &l.families[g];
            row.push(match f.geomean {
                Some(m) => Cell::number(format::speedup(m), m)
                    .detail(format!("{}/{}/{}", f.faster, f.within_noise, f.slower))
                    .tone(l.tone(g))
                    .hover(l.label(g)),
                None => Cell::dash(),
            });
        }
        row.push(Cell::text(l.cost_label()).tone(l.cost_tone()));
        row.push(match l.worst {
            Some((band, rms)) if l.picture_changed => {
                Cell::text(format!("RMS {} · {band}", format::fixed(rms, 1)))
                    .tone(Tone::of_band(band))
            }
            _ => Cell::text("unchanged").tone(Tone::Muted),
        });
        row.push(if l.rays_changed > 0 {
            Cell::text(format!(
                "changed on {} of {}",
                l.rays_changed,
                format::plural(l.compared, "scene")
            ))
            .tone(Tone::Warning)
        } else {
            Cell::text("unchanged").tone(Tone::Muted)
        });
        t.rows.push(row);
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::results::{FlatRow, SceneFamily};
    use testkit::sample::sample_results;

    fn test_bench(f: SceneFamily) -> bool {
        FAMILY_GROUPS[0].1.contains(&f)
    }

    #[test]
    fn family_means_are_computed_per_family() {
        let mut r = sample_results();
        // bvh: 2× and 0.5× alternately on the test bench, 8× on the SPD scenes.
        let (mut up, mut down) = (0i32, 0i32);
        for scene in &mut r.scenes {
            let bench = test_bench(scene.family);
            let spd = scene.family == SceneFamily::Spd;
            for v in &mut scene.variants {
                if v.variant.as_str() != "bvh" {
                    continue;
                }
                v.speedup = if bench {
                    if (up + down) % 2 == 0 {
                        up += 1;
                        Some(2.0)
                    } else {
                        down += 1;
                        Some(0.5)
                    }
                } else if spd {
                    Some(8.0)
                } else {
                    Some(1.0)
                };
            }
        }
        assert!(
            up > 0 && down > 0,
            "the sample has test-bench scenes with bvh"
        );
        let lines = variant_lines(&r);
        let bvh = lines.iter().find(|l| l.variant.as_str() == "bvh").unwrap();
        // 2^(up - down) over up + down scenes, by hand.
        let want = 2f64.powf(f64::from(up - down) / f64::from(up + down));
        let got = bvh.families[0].geomean.unwrap();
        assert!((got - want).abs() < 1e-12, "{got} against {want}");
        if let Some(spd) = bvh.families[1].geomean {
            assert!((spd - 8.0).abs() < 1e-12, "{spd}");
        }
    }

    #[test]
    fn a_variant_that_changed_the_picture_or_the_rays_is_never_plainly_faster() {
        let mut r = sample_results();
        for scene in &mut r.scenes {
            for v in &mut scene.variants {
                if v.variant.is_reference() {
                    continue;
                }
                v.verdict = Some(Verdict::Faster);
                v.speedup = Some(3.0);
                let name = v.variant.as_str().to_string();
                if let Some(q) = v.quality.as_mut() {
                    // Only fast-sqrt's picture differs; the others are bit for bit.
                    q.max_abs_diff = u32::from(name == "fast-sqrt") * 9;
                    q.rms = if name == "fast-sqrt" { 20.0 } else { 0.0 };
                    q.band = Band::of(q.rms);
                }
                if name == "ortho" {
                    *v.counts.entry("rays.primary_hit".into()).or_default() += 7;
                }
            }
        }
        // The reference's rays are the others' (the sample's counts may differ).
        for scene in &mut r.scenes {
            let Some(base) = scene.variants.iter().find(|v| v.variant.is_reference()) else {
                continue;
            };
            let rays: Vec<(String, u64)> = base
                .counts
                .iter()
                .filter(|(k, _)| k.starts_with("rays."))
                .map(|(k, n)| (k.clone(), *n))
                .collect();
            for v in &mut scene.variants {
                if v.variant.as_str() == "ortho" || v.variant.is_reference() {
                    continue;
                }
                for (k, n) in &rays {
                    v.counts.insert(k.clone(), *n);
                }
            }
        }
        let lines = variant_lines(&r);
        let line = |name: &str| lines.iter().find(|l| l.variant.as_str() == name).unwrap();
        // Group 0: the thesis's test bench.
        assert_eq!(line("bvh").label(0), "faster");
        assert_eq!(line("bvh").tone(0), Tone::Good);
        assert_eq!(
            line("fast-sqrt").label(0),
            "faster, but changes the picture"
        );
        assert_eq!(line("fast-sqrt").tone(0), Tone::Fair);
        assert!(line("ortho").label(0).contains("changes the rays"));
        assert_eq!(line("ortho").tone(0), Tone::Warning);
        for l in &lines {
            for g in 0..FAMILY_GROUPS.len() {
                if l.has_cost() {
                    assert_ne!(l.label(g), "faster", "{}", l.variant);
                    assert_ne!(l.tone(g), Tone::Good, "{}", l.variant);
                }
            }
        }
        let said = optimization_sentence(&lines);
        assert!(said.contains("fast-sqrt (worst RMS 20.0"), "{said}");
    }

    #[test]
    fn table_6_rows_are_per_eye_ray_and_name_the_most_called_operation() {
        let mut p = sample_results().profile.unwrap().baseline;
        p.counts = [
            ("rays.primary", 100),
            ("ops.dot", 5_000),
            ("ops.sub", 4_000),
            ("tests.sphere.tests", 1_000),
        ]
        .into_iter()
        .map(|(k, n)| (k.to_string(), n))
        .collect();
        p.flat = vec![FlatRow {
            name: "sphere test".into(),
            percent: 40.0,
            self_seconds: 0.4,
            total_seconds: 0.4,
            calls: Some(1_000),
            inclusive_percent: Some(40.0),
            self_interval: None,
            inclusive_interval: None,
            noise: false,
            root: false,
        }];
        let rows = table6_rows(&p);
        let row = |name: &str| rows.iter().find(|r| r.thesis_name == name).unwrap();
        assert_eq!(row("Vector dotPoint").per_ray, Some(50.0));
        assert_eq!(row("Vector dotPoint").percent, None);
        assert_eq!(row("Sphere Intersection test").per_ray, Some(10.0));
        assert_eq!(row("Sphere Intersection test").percent, Some(40.0));
        assert_eq!(row("Cylinder Intersection test").percent, Some(0.0));
        // 3,902,026,000 dot products over 640 × 480 eye rays.
        assert!((row("Vector dotPoint").thesis_per_ray - 3.902026e9 / 307_200.0).abs() < 1e-9);
        let said = time_sentence("rings", &p, &rows);
        assert_eq!(
            said,
            "In the profile of rings, the sphere test takes the most time itself, 40.0 % (table 6: Cylinder Intersection test, 21.1 % of the run). The most-called operation is Vector dotPoint, 50.0 calls per eye ray; in table 6 it is Vector -, 13,530 per ray, although the thesis names the dot product."
        );
    }
}
