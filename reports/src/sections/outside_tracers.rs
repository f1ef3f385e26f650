//! Outside tracers beside rtprof (docs/tracers.md): on each scene, rtprof's fastest
//! variant that kept the picture, and each outside tracer's time as a ratio of rtprof's
//! (rtprof's time ÷ its time: below 1× rtprof is faster), with their geometric means
//! over the scenes where the tracer drew rtprof's scene. A tracer whose picture is
//! another one (Tachyon's SPD gears, all white) is no comparison there: marked, and
//! kept out of the means.

use analysis::{Likeness, Mismatch};

use crate::document::{Cell, Column, Table, Tone};
use crate::findings::geometric_mean;
use crate::format;
use crate::results::{Band, Results, SceneResult, VariantName, VariantResult};

/// rtprof's fastest variant on `scene` whose picture stayed visually identical to the
/// reference variant's (or, without one on the scene, to the f64 reference's).
fn fastest_kept(scene: &SceneResult) -> Option<&VariantResult> {
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
fn not_comparable(v: &VariantResult) -> Option<&'static str> {
    match v.outside.as_ref()?.likeness.as_ref()? {
        Likeness::Different { reason, .. } => Some(match reason {
            Mismatch::PictureFlat => "its picture is flat",
            Mismatch::ReferenceFlat => "rtprof's picture is flat",
            Mismatch::EdgesDisagree => "another picture (framing or scene)",
        }),
        _ => None,
    }
}

/// The sentence and the table; `None` without an outside tracer in the run.
pub fn outside_tracers(r: &Results) -> Option<(String, Table)> {
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
    let mut ratios: Vec<Vec<f64>> = vec![Vec::new(); tracers.len()];
    let mut excluded: Vec<Vec<String>> = vec![Vec::new(); tracers.len()];
    for scene in &r.scenes {
        if !scene.variants.iter().any(|v| v.variant.is_outside()) {
            continue;
        }
        let best = fastest_kept(scene);
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
            match best {
                Some(b) if v.time.median > 0.0 => {
                    let ratio = b.time.median / v.time.median;
                    ratios[i].push(ratio);
                    row.push(Cell::number(format::speedup(ratio), ratio).detail(time));
                }
                _ => row.push(Cell::text(time)),
            }
        }
        table.rows.push(row);
    }
    let mut means = vec![Cell::text("geometric mean").span(2)];
    let mut parts = Vec::new();
    for (i, tracer) in tracers.iter().enumerate() {
        let mean = geometric_mean(ratios[i].iter().copied());
        means.push(match mean {
            Some((m, n)) => Cell::number(format::speedup(m), m).detail(format::plural(n, "scene")),
            None => Cell::dash(),
        });
        let covers = r
            .scenes
            .iter()
            .flat_map(|s| &s.variants)
            .find(|v| &&v.variant == tracer)
            .and_then(|v| v.outside.as_ref())
            .map_or_else(String::new, |o| {
                format!("; its time covers {}", o.time_covers)
            });
        let mut part = match mean {
            Some((m, n)) => format!(
                "rtprof takes {} of {}'s time (geometric mean over {}{covers})",
                format::speedup(m),
                tracer.outside_name().unwrap_or(tracer.as_str()),
                format::plural(n, "scene")
            ),
            None => format!(
                "{} drew no scene rtprof's time can be set against",
                tracer.outside_name().unwrap_or(tracer.as_str())
            ),
        };
        if !excluded[i].is_empty() {
            part += &format!("; not comparable on {}", format::join_list(&excluded[i]));
        }
        parts.push(part);
    }
    table.rows.push(means);
    let sentence = format!(
        "Outside tracers (docs/tracers.md), each against rtprof's fastest variant that kept the picture on the scene, whose time covers {}: {}.",
        super::summary::time_covers(r.suite.timing.covers),
        parts.join("; ")
    );
    Some((sentence, table))
}
