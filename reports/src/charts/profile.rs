//! The flat profile's charts: calls and self time per function (thesis fig. 51, 52).

use super::Chart;
use super::bars::{HorizontalBars, Row, horizontal_bars};
use super::numbers::{format_number, short_name};
use super::style::PALETTE;
use crate::results::Results;

/// Calls per function from the flat profile, log scale (thesis fig. 51).
pub fn calls_chart(results: &Results) -> Option<Chart> {
    let profile = results.profile.as_ref()?;
    let rows = largest(
        profile.baseline.flat.iter().filter_map(|r| {
            let calls = r.calls.filter(|c| *c > 0)? as f64;
            Some(Row {
                label: short_name(&r.name),
                value: calls,
                text: format_number(calls),
            })
        }),
        20,
    )?;
    Some(horizontal_bars(HorizontalBars {
        id: "calls",
        title: format!(
            "Calls per function ({}, {})",
            profile.scene, profile.baseline.variant
        ),
        caption: format!(
            "Thesis fig. 51. Exact calls {} of the profiled functions of {} at {}x{} ({}), counted by the instrumented tracer; log scale.",
            match profile.baseline.renders {
                Some(_) => "per render",
                None => "over all sampled renders",
            },
            profile.scene,
            profile.width,
            profile.height,
            profile.baseline.variant
        ),
        axis_title: if profile.baseline.renders.is_some() {
            "calls per render (log scale)"
        } else {
            "calls over the sampled renders (log scale)"
        },
        rows,
        log: true,
        colour: PALETTE[0],
    }))
}

/// Self seconds per function from the flat profile (thesis fig. 52).
pub fn self_seconds_chart(results: &Results) -> Option<Chart> {
    let profile = results.profile.as_ref()?;
    let rows = largest(
        profile
            .baseline
            .flat
            .iter()
            .filter(|r| r.self_seconds.is_finite() && r.self_seconds > 0.0)
            .map(|r| Row {
                label: short_name(&r.name),
                value: r.self_seconds,
                text: format!("{} s ({:.1} %)", format_number(r.self_seconds), r.percent),
            }),
        15,
    )?;
    Some(horizontal_bars(HorizontalBars {
        id: "self-seconds",
        title: format!(
            "Self time per function ({}, {})",
            profile.scene, profile.baseline.variant
        ),
        caption: format!(
            "Thesis fig. 52. CPU seconds spent in each function itself (not its callees), from {} samples at {} s each{}; the 15 largest.",
            profile.baseline.samples,
            format_number(profile.baseline.seconds_per_sample),
            profile
                .baseline
                .renders
                .map_or_else(String::new, |n| format!(", over {n} renders")),
        ),
        axis_title: "self time (s)",
        rows,
        log: false,
        colour: PALETTE[3],
    }))
}

/// The `keep` rows with the largest values, largest first; `None` without rows.
fn largest(rows: impl Iterator<Item = Row>, keep: usize) -> Option<Vec<Row>> {
    let mut rows: Vec<Row> = rows.collect();
    rows.sort_by(|a, b| b.value.total_cmp(&a.value));
    rows.truncate(keep);
    (!rows.is_empty()).then_some(rows)
}
