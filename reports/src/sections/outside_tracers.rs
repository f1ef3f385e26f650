//! Outside tracers beside rtprof (docs/tracers.md): on each scene, rtprof's fastest
//! variant that kept the picture, and each outside tracer's time as a ratio of rtprof's
//! (rtprof's time ÷ its time: below 1× rtprof is faster), with their geometric means
//! over the scenes where the tracer drew rtprof's scene. A tracer whose picture is
//! another one (Tachyon's SPD gears, all white) is no comparison there: marked, and
//! kept out of the means.

use analysis::{Likeness, Mismatch};

use crate::document::{Block, Builder, Cell, Column, Table, Tone};
use crate::findings::geometric_mean;
use crate::format;
use crate::results::{Band, Results, SceneResult, VariantName, VariantResult};

/// rtprof's fastest variant on `scene` whose picture stayed visually identical to the
/// reference variant's (or, without one on the scene, to the f64 reference's).
pub(crate) fn fastest_kept(scene: &SceneResult) -> Option<&VariantResult> {
    let kept = |v: &&VariantResult| {
        let band = |q: Option<&crate::results::Quality>| q.map(|q| q.band);
        v.variant.is_reference()
            || band(v.quality.as_ref()) == Some(Band::VisuallyIdentical)
            || (v.quality.is_none()
                && band(v.vs_f64_reference.as_ref()) == Some(Band::VisuallyIdentical))
    };
    scene
        .variants
        .iter()
        .filter(|v| !v.variant.is_outside())
        .filter(kept)
        .min_by(|a, b| a.time.median.total_cmp(&b.time.median))
}

/// Why a tracer's picture is no comparison, in a few words; `None` when it is one.
pub(crate) fn not_comparable(v: &VariantResult) -> Option<&'static str> {
    match v.outside.as_ref()?.likeness.as_ref()? {
        Likeness::Different { reason, .. } => Some(match reason {
            Mismatch::PictureFlat => "its picture is flat",
            Mismatch::ReferenceFlat => "rtprof's picture is flat",
            Mismatch::EdgesDisagree => "another framing or scene",
        }),
        _ => None,
    }
}

/// The sentence and the table; `None` without an outside tracer in the run.
pub fn outside_tracers(r: &Results) -> Option<(String, Table)> {
    let (parts, table) = tracer_figures(r)?;
    let sentence = format!(
        "Outside tracers (docs/tracers.md), each against rtprof's fastest variant that kept the picture on the scene, whose time covers {}, or, for a tracer timed as a whole process, against rtprof's own whole process where the peer rtprof ran: {}.",
        super::summary::time_covers(r.suite.timing.covers),
        parts.join("; ")
    );
    Some((sentence, table))
}

/// The answer's clause on the outside tracers (what rtprof's fastest kept variant takes
/// of each tracer's time); `None` without one in the run.
pub fn answer_clause(r: &Results) -> Option<String> {
    let (parts, _) = tracer_figures(r)?;
    Some(format!(
        "Beside the outside tracers (their table is in the variants chapter): {}.",
        parts.join("; ")
    ))
}

/// Each tracer's figure in words, and the table of its times per scene.
fn tracer_figures(r: &Results) -> Option<(Vec<String>, Table)> {
    let tracers: Vec<&VariantName> = r.suite.variants.iter().filter(|v| v.is_outside()).collect();
    if tracers.is_empty() {
        return None;
    }
    let mut columns = vec![
        Column::text("scene"),
        Column::number("rtprof").detail("fastest kept"),
    ];
    columns.extend(
        tracers
            .iter()
            .map(|t| Column::number(t.as_str()).detail("rtprof ÷ it · its time")),
    );
    let mut table = Table::new(columns).dense();
    // rtprof itself run as a whole process (the built-in peer `rtprof`): what a tracer
    // timed as a whole process is set against, like for like.
    let whole_rtprof = tracers
        .iter()
        .find(|t| t.outside_name() == Some("rtprof"))
        .copied();
    let mut against_whole = vec![false; tracers.len()];
    // Per tracer, per family group (as the variants matrix groups scenes).
    let groups = super::family_groups::FAMILY_GROUPS;
    let mut ratios: Vec<Vec<Vec<f64>>> = vec![vec![Vec::new(); groups.len()]; tracers.len()];
    let mut excluded: Vec<Vec<String>> = vec![Vec::new(); tracers.len()];
    for scene in &r.scenes {
        if !scene.variants.iter().any(|v| v.variant.is_outside()) {
            continue;
        }
        let group = groups
            .iter()
            .position(|(_, members)| members.contains(&scene.family))
            .unwrap_or(groups.len() - 1);
        let best = fastest_kept(scene);
        let rtprof_process = whole_rtprof
            .and_then(|w| scene.variants.iter().find(|v| &v.variant == w))
            .filter(|v| not_comparable(v).is_none())
            .map(|v| v.time.median);
        let mut row = vec![
            Cell::text(scene.name.as_str()),
            match best {
                Some(b) => Cell::number(format::seconds(b.time.median), b.time.median)
                    .detail(b.variant.as_str()),
                None => Cell::dash(),
            },
        ];
        for (i, tracer) in tracers.iter().enumerate() {
            let Some(v) = scene.variants.iter().find(|v| &&v.variant == tracer) else {
                row.push(Cell::text("did not run").tone(Tone::Muted));
                continue;
            };
            let time = format::seconds(v.time.median);
            if let Some(why) = not_comparable(v) {
                excluded[i].push(format!("{} ({why})", scene.name));
                row.push(
                    Cell::text("not comparable")
                        .tone(Tone::Muted)
                        .detail(time)
                        .hover(why.to_string()),
                );
                continue;
            }
            let whole = v.outside.as_ref().is_some_and(|o| o.whole_process)
                && Some(*tracer) != whole_rtprof;
            let ours = match rtprof_process {
                Some(p) if whole => {
                    against_whole[i] = true;
                    Some(p)
                }
                _ => best.map(|b| b.time.median),
            };
            match ours {
                Some(ours) if v.time.median > 0.0 => {
                    let ratio = ours / v.time.median;
                    ratios[i][group].push(ratio);
                    row.push(Cell::number(format::speedup(ratio), ratio).detail(time));
                }
                _ => row.push(Cell::text(time)),
            }
        }
        table.rows.push(row);
    }
    for (g, (family, _)) in groups.iter().enumerate() {
        if ratios.iter().all(|r| r[g].is_empty()) {
            continue;
        }
        let mut row = vec![Cell::text(format!("{family}: geometric mean")).span(2)];
        for r in &ratios {
            row.push(match geometric_mean(r[g].iter().copied()) {
                Some((m, n)) => {
                    Cell::number(format::speedup(m), m).detail(format::plural(n, "scene"))
                }
                None => Cell::dash(),
            });
        }
        table.rows.push(row);
    }
    let mut parts = Vec::new();
    for (i, tracer) in tracers.iter().enumerate() {
        // The sentence gives the SPD scenes' mean where the tracer drew any (the
        // scenes peers are compared on), else the mean over every scene.
        let spd = groups.iter().position(|(name, _)| *name == "SPD");
        let (mean, over) = match spd.and_then(|g| geometric_mean(ratios[i][g].iter().copied())) {
            Some(m) => (Some(m), "SPD "),
            None => (geometric_mean(ratios[i].iter().flatten().copied()), ""),
        };
        let covers = r
            .scenes
            .iter()
            .flat_map(|s| &s.variants)
            .find(|v| &&v.variant == tracer)
            .and_then(|v| v.outside.as_ref())
            .map_or_else(String::new, |o| {
                format!("; its time covers {}", o.time_covers)
            });
        let name = tracer.outside_name().unwrap_or(tracer.as_str());
        let mut part = match mean {
            Some((m, n)) if Some(*tracer) == whole_rtprof => format!(
                "rtprof's fastest kept variant's tracing is {} of the whole process 'rtprof render' takes (geometric mean over {})",
                format::speedup(m),
                format::plural(n, &format!("{over}scene"))
            ),
            Some((m, n)) if against_whole[i] => format!(
                "rtprof takes {} of {name}'s time, both as whole processes (rtprof as 'rtprof render'; geometric mean over {})",
                format::speedup(m),
                format::plural(n, &format!("{over}scene"))
            ),
            Some((m, n)) => format!(
                "rtprof takes {} of {name}'s time (geometric mean over {}{covers})",
                format::speedup(m),
                format::plural(n, &format!("{over}scene"))
            ),
            None => format!("{name} drew no scene rtprof's time can be set against"),
        };
        if !excluded[i].is_empty() {
            part += &format!("; not comparable on {}", format::join_list(&excluded[i]));
        }
        parts.push(part);
    }
    Some((parts, table))
}

/// The outside tracers recorded with perf on the profile scene (`record = true` in
/// the suite's `[[tracers]]`): per tracer, a heading, what was sampled and the function
/// with the most self time, the files by name (beside the report), its gprof-layout
/// flat profile and its flamegraph.
pub fn recorded(b: &mut Builder) -> Vec<Block> {
    let r = b.results();
    let mut blocks = Vec::new();
    for p in &r.outside_profiles {
        blocks.push(Block::heading(format!(
            "{} recorded with perf on {}",
            p.variant, p.scene
        )));
        let top = p
            .profile
            .flat
            .iter()
            .filter(|r| !r.noise)
            .max_by(|a, b| a.percent.total_cmp(&b.percent))
            .map_or_else(String::new, |r| {
                format!(
                    " Most self time: {} ({}).",
                    r.name,
                    format::percent(r.percent, 1)
                )
            });
        blocks.push(Block::text(format!(
            "Its run of {} at {}, sampled as rtprof record samples a program: {} in {} of CPU ({} wall; {} Hz asked, callers by {}).{top} Its files are beside this report in {}/: the flat profile {}, the call graph {}, the folded stacks {}, the flamegraph {}, and rtprof record's own report, record.json and perf.data.",
            p.command.join(" "),
            format::size(p.width, p.height),
            format::plural(p.samples as usize, "sample"),
            format::seconds(p.cpu_seconds),
            format::seconds(p.wall_seconds),
            format::count(u64::from(p.frequency)),
            p.call_graph,
            p.directory,
            p.profile.flat_text,
            p.profile.callgraph_text,
            p.folded,
            p.profile.flame_svg,
        )));
        blocks.push(super::profile::flat_text_block(
            b,
            &p.profile.flat_text,
            &format!("{} flat profile", p.variant),
        ));
        blocks.push(super::profile::flame_block(
            b,
            &p.profile.flame_svg,
            format!("Flamegraph of {} on {} (native symbols, perf)", p.variant, p.scene),
            "The program's own functions as perf sampled them: each box a function, its width its share of the samples, its callees above it.".to_string(),
        ));
    }
    blocks
}

/// What an outside tracer's picture was judged to be, in a line: its likeness to
/// rtprof's picture and its Monte Carlo noise; `None` when neither was measured.
pub fn picture_note(o: &crate::results::OutsideTracer) -> Option<String> {
    let mut parts = Vec::new();
    match &o.likeness {
        Some(Likeness::Same { .. }) => {
            parts.push("the same scene with rtprof's conventions".to_string())
        }
        Some(Likeness::OtherConventions { .. }) => parts.push(
            "the same scene with other conventions (judge it against its own runs)".to_string(),
        ),
        Some(Likeness::Different { reason, .. }) => {
            let why = match reason {
                Mismatch::PictureFlat => "its picture is flat",
                Mismatch::ReferenceFlat => "rtprof's picture is flat",
                Mismatch::EdgesDisagree => "another framing or scene",
            };
            parts.push(format!("not comparable: {why}"));
        }
        None => {}
    }
    if let Some(n) = &o.noise {
        let efficiency = n
            .efficiency
            .map_or_else(|| format::DASH.to_string(), format::quantity);
        let flip = n.flip.map_or_else(String::new, |f| {
            format!(", mean FLIP {}", format::fixed(f, 3))
        });
        parts.push(format!(
            "noise against its own {} spp run: relMSE {}, efficiency {efficiency} (1 / (relMSE × s)){flip}",
            n.converged_spp,
            format::significant(n.rel_mse)
        ));
    }
    (!parts.is_empty()).then(|| parts.join("; "))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::results::{OutsideTracer, Results};
    use analysis::LikenessMeasures;
    use testkit::sample_results;

    const MEASURES: LikenessMeasures = LikenessMeasures {
        edge_agreement: 0.9,
        picture_edges: 10,
        reference_edges: 10,
        tone_rms: 1.0,
    };

    /// `r` with tracer `name` on its first two scenes at the times given, the second
    /// judged as drawing another picture when `second_differs`.
    fn with_tracer(mut r: Results, name: &str, seconds: [f64; 2], second_differs: bool) -> Results {
        let tracer = VariantName::outside(name).unwrap();
        r.suite.variants.push(tracer.clone());
        for (i, scene) in r.scenes.iter_mut().take(2).enumerate() {
            let mut v = scene.variants[0].clone();
            v.variant = tracer.clone();
            v.time.median = seconds[i];
            v.quality = None;
            v.outside = Some(OutsideTracer {
                definition: "built-in t.toml".into(),
                command: vec!["t".into()],
                scene_format: "nff".into(),
                time_covers: "the whole process".into(),
                whole_process: true,
                deterministic: true,
                spp: 1,
                conventions: String::new(),
                program: None,
                likeness: Some(if second_differs && i == 1 {
                    Likeness::Different {
                        reason: Mismatch::PictureFlat,
                        measures: MEASURES,
                    }
                } else {
                    Likeness::Same { measures: MEASURES }
                }),
                noise: None,
            });
            scene.variants.push(v);
        }
        r
    }

    #[test]
    fn each_scene_sets_rtprofs_fastest_kept_variant_against_the_tracer() {
        let r = with_tracer(sample_results(), "t", [2.0, 4.0], false);
        // rtprof's side, by hand: the fastest of the scene's own variants whose picture
        // stayed visually identical (or the reference itself).
        let best: Vec<f64> = r.scenes[..2]
            .iter()
            .map(|s| fastest_kept(s).unwrap().time.median)
            .collect();
        for s in &r.scenes[..2] {
            let b = fastest_kept(s).unwrap();
            assert!(!b.variant.is_outside());
            for v in s.variants.iter().filter(|v| !v.variant.is_outside()) {
                let kept = v.variant.is_reference()
                    || v.quality
                        .as_ref()
                        .is_some_and(|q| q.band == Band::VisuallyIdentical);
                assert!(!kept || v.time.median >= b.time.median);
            }
        }
        let (sentence, table) = outside_tracers(&r).unwrap();
        let ratios = [best[0] / 2.0, best[1] / 4.0];
        assert_eq!(table.rows[0][2].text, format::speedup(ratios[0]));
        assert_eq!(table.rows[1][2].text, format::speedup(ratios[1]));
        let mean = (ratios[0] * ratios[1]).sqrt();
        let last = table.rows.last().unwrap();
        assert_eq!(last[1].text, format::speedup(mean));
        assert!(
            sentence.contains(&format!(
                "rtprof takes {} of t's time",
                format::speedup(mean)
            )),
            "{sentence}"
        );
        assert!(sentence.contains("the whole process"), "{sentence}");
    }

    #[test]
    fn the_optimization_answer_sets_rtprof_beside_the_tracers() {
        let r = with_tracer(sample_results(), "t", [2.0, 4.0], false);
        let best: Vec<f64> = r.scenes[..2]
            .iter()
            .map(|s| fastest_kept(s).unwrap().time.median)
            .collect();
        let mean = (best[0] / 2.0 * best[1] / 4.0).sqrt();
        let [_, optimizations, _] = super::super::answers::three_answers(&r);
        let text = optimizations.sentence.unwrap();
        assert!(
            text.contains(&format!(
                "Beside the outside tracers (their table is in the variants chapter): rtprof takes {} of t's time",
                format::speedup(mean)
            )),
            "{text}"
        );
        // Without a tracer, the answer is rtprof's own variants alone.
        let plain = super::super::answers::three_answers(&sample_results())[1]
            .sentence
            .clone()
            .unwrap();
        assert!(!plain.contains("outside tracers"), "{plain}");
    }

    #[test]
    fn a_whole_process_is_set_against_rtprofs_own_whole_process() {
        // rtprof as a whole process took 0.5 s and 1 s; the peer 2 s and 4 s: a quarter.
        let r = with_tracer(sample_results(), "rtprof", [0.5, 1.0], false);
        let r = with_tracer(r, "pov", [2.0, 4.0], false);
        let (sentence, table) = outside_tracers(&r).unwrap();
        // Columns: scene, rtprof's fastest kept variant, tracer:rtprof, tracer:pov.
        assert_eq!(table.rows[0][3].text, format::speedup(0.25));
        assert_eq!(table.rows[1][3].text, format::speedup(0.25));
        // rtprof's own column: its fastest kept variant's tracing over its process.
        let best = fastest_kept(&r.scenes[0]).unwrap().time.median;
        assert_eq!(table.rows[0][2].text, format::speedup(best / 0.5));
        assert!(
            sentence.contains("rtprof takes 0.25× of pov's time, both as whole processes"),
            "{sentence}"
        );
    }

    #[test]
    fn another_picture_is_marked_and_kept_out_of_the_mean() {
        let r = with_tracer(sample_results(), "white", [2.0, 4.0], true);
        let (sentence, table) = outside_tracers(&r).unwrap();
        assert_eq!(table.rows[1][2].text, "not comparable");
        let best = fastest_kept(&r.scenes[0]).unwrap().time.median;
        // The mean is the first scene's ratio alone.
        assert_eq!(
            table.rows.last().unwrap()[1].text,
            format::speedup(best / 2.0)
        );
        assert!(sentence.contains("not comparable on"), "{sentence}");
        assert!(sentence.contains("its picture is flat"), "{sentence}");
        assert!(outside_tracers(&sample_results()).is_none());
    }

    #[test]
    fn the_web_pages_values_mark_another_picture_instead_of_a_speed_up() {
        let r = with_tracer(sample_results(), "white", [2.0, 4.0], true);
        let tracer = |i: usize| {
            let v = r.scenes[i].variants.last().unwrap();
            assert_eq!(v.variant.outside_name(), Some("white"));
            crate::page_values::variant_values(v)
        };
        assert_eq!(tracer(0).not_comparable, None);
        assert_eq!(tracer(1).not_comparable, Some("its picture is flat"));
        assert_eq!(tracer(1).time_covers.as_deref(), Some("the whole process"));
        let own = crate::page_values::variant_values(&r.scenes[0].variants[0]);
        assert_eq!((own.not_comparable, own.time_covers), (None, None));
    }

    #[test]
    fn the_picture_note_names_likeness_and_noise() {
        let r = with_tracer(sample_results(), "t", [2.0, 4.0], true);
        let mut o = r.scenes[1]
            .variants
            .last()
            .unwrap()
            .outside
            .clone()
            .unwrap();
        assert_eq!(
            picture_note(&o).unwrap(),
            "not comparable: its picture is flat"
        );
        o.likeness = None;
        o.noise = Some(crate::results::Noise {
            converged_spp: 256,
            rel_mse: 0.0400,
            mse: 0.002,
            efficiency: Some(34.5),
            flip: None,
        });
        assert_eq!(
            picture_note(&o).unwrap(),
            "noise against its own 256 spp run: relMSE 0.040, efficiency 34.5 (1 / (relMSE × s))"
        );
        o.noise = None;
        assert!(picture_note(&o).is_none());
    }
}
