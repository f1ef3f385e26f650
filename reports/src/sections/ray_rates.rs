//! The rays-per-second section: each render's rays per second by kind, its time split
//! between eye, secondary and shadow queries and the rest, and the SIMD variant's lane
//! utilization beside its speed-up, with a sentence on whether packing primitives into
//! lanes pays. Omitted when no variant has ray rates or lane counts (older files).

use super::access;
use crate::document::{Block, Builder, Cell, Column, Section, Table};
use crate::format;
use crate::results::{RayRates, SceneFamily, SceneResult, VariantResult};

pub fn ray_rates(b: &mut Builder) -> Option<Section> {
    let r = b.results();
    let rows: Vec<(&SceneResult, &VariantResult)> = r
        .scenes
        .iter()
        .flat_map(|s| s.variants.iter().map(move |v| (s, v)))
        .filter(|(_, v)| v.ray_rates.is_some() || v.lane_utilization.is_some())
        .collect();
    if rows.is_empty() {
        return None;
    }
    let mut s = b.section("ray-rates", None);
    // A table of every scene and variant: the HTML's (the PDF keeps the opening).
    s.html_only = true;
    if let Some(intro) = intro(&rows) {
        s.text(intro);
    }
    if let Some(sentence) = lanes_sentence(&rows) {
        s.text(sentence);
    }
    // Every render by kind is a long table on a full suite: the kinds for the SPD and
    // generated scenes (the scenes papers report), all rays per second for the rest.
    let detailed =
        |scene: &SceneResult| matches!(scene.family, SceneFamily::Spd | SceneFamily::Generated);
    let (by_kind, rest): (Vec<_>, Vec<_>) = rows.iter().partition(|(scene, _)| detailed(scene));
    if by_kind.is_empty() {
        s.blocks
            .push(Block::Table(rates_table(&rows.iter().collect::<Vec<_>>())));
    } else {
        s.blocks.push(Block::Table(
            rates_table(&by_kind).caption("By ray kind: the SPD and generated scenes"),
        ));
        if !rest.is_empty() {
            let rest: Vec<_> = rest.into_iter().copied().collect();
            s.blocks.push(Block::Table(all_rays_table(r, &rest)));
        }
    }
    Some(s)
}

/// Every ray per second, one row per scene and one column per variant.
fn all_rays_table(r: &crate::results::Results, rows: &[(&SceneResult, &VariantResult)]) -> Table {
    let (scenes, variants) = access::pivot(r, rows);
    let mut columns = vec![Column::text("scene")];
    columns.extend(variants.iter().map(|v| Column::number(*v)));
    let mut t = Table::new(columns).sortable().dense().caption(
        "All rays, Mrays/s, the other scenes (their split by kind is in results.json, ray_rates)",
    );
    for scene in scenes {
        let mut row = vec![Cell::text(&scene.name)];
        for variant in &variants {
            let rates = access::pivot_cell(rows, scene, variant).and_then(|v| v.ray_rates.as_ref());
            row.push(match rates {
                Some(x) if x.all_mrays_per_s.is_finite() => {
                    Cell::number(format::significant(x.all_mrays_per_s), x.all_mrays_per_s)
                }
                _ => Cell::dash(),
            });
        }
        t.rows.push(row);
    }
    t
}

/// How the rates were measured and what the clocked pass cost, from the data.
fn intro(rows: &[(&SceneResult, &VariantResult)]) -> Option<String> {
    let overheads: Vec<f64> = rows
        .iter()
        .filter_map(|(_, v)| v.ray_rates.as_ref().map(|r| r.clock_overhead))
        .filter(|x| x.is_finite())
        .collect();
    let low = overheads.iter().copied().reduce(f64::min)?;
    let high = overheads.iter().copied().reduce(f64::max)?;
    let overhead = if format::speedup(low) == format::speedup(high) {
        format::speedup(low)
    } else {
        format!("{} to {}", format::speedup(low), format::speedup(high))
    };
    Some(format!(
        "Rays per second of each kind: its rays over the time its queries took, in millions. The time split comes from a separate pass that reads a time-stamp counter around every closest-hit and shadow query; that pass took {overhead} the time of the timed renders (what reading the clock costs). Shares are of the worker threads' time; other is camera rays, shading, the secondary rays' set-up and framebuffer work, idle the workers' wait for rows to trace (a small frame has few to share); all is every ray over the whole tracing time."
    ))
}

/// Whether packing primitives into SIMD lanes pays, from the scenes where the lanes were
/// fullest and emptiest: their utilization and the speed-up that came with it.
fn lanes_sentence(rows: &[(&SceneResult, &VariantResult)]) -> Option<String> {
    let packed: Vec<(&SceneResult, &VariantResult, f64)> = rows
        .iter()
        .filter_map(|(s, v)| Some((*s, *v, v.lane_utilization.filter(|u| u.is_finite())?)))
        .collect();
    // Ties: the larger scene is the fuller one's example, the smaller the emptier's.
    let fullest = packed.iter().max_by(|a, b| {
        a.2.total_cmp(&b.2)
            .then(a.0.primitives.cmp(&b.0.primitives))
    })?;
    let emptiest = packed.iter().min_by(|a, b| {
        a.2.total_cmp(&b.2)
            .then(a.0.primitives.cmp(&b.0.primitives))
    })?;
    let busy = |used: f64| format::percent(used * 100.0, 1);
    let place = |scene: &SceneResult| {
        format!(
            "{} ({})",
            scene.name,
            format::kind_count(scene.primitives, "primitives")
        )
    };
    let pace = |v: &VariantResult| {
        v.speedup.map_or_else(String::new, |x| {
            format!(" at {} baseline's speed", format::speedup(x))
        })
    };
    let why = "A step tests a chunk of primitives of one kind in parallel lanes, so a scene with fewer primitives of a kind than a chunk has lanes leaves the rest empty";
    let name = &fullest.1.variant;
    let first = format!(
        "{name} keeps {} of its lanes busy on {}{}",
        busy(fullest.2),
        place(fullest.0),
        pace(fullest.1)
    );
    if fullest.2 == emptiest.2 {
        return Some(format!("{first}. {why}."));
    }
    let verdict = match (fullest.1.speedup, emptiest.1.speedup) {
        (Some(full), Some(empty)) if full > empty => {
            "fuller lanes bring the larger speed-up: packing pays where a scene has many primitives of each kind"
        }
        (Some(_), Some(_)) => {
            "here the speed-up does not follow the lanes' use: work outside the primitive tests (shading, the rays' set-up) sets the time"
        }
        _ => "without speed-ups the lanes' use cannot be set against the time",
    };
    Some(format!(
        "{first}, and only {} on {}{}. {why}; {verdict}.",
        busy(emptiest.2),
        place(emptiest.0),
        pace(emptiest.1)
    ))
}

/// One row per render: speed-up, lanes, rays per second by kind, time shares.
fn rates_table(rows: &[&(&SceneResult, &VariantResult)]) -> Table {
    let lanes = rows.iter().any(|(_, v)| v.lane_utilization.is_some());
    let rates = rows.iter().any(|(_, v)| v.ray_rates.is_some());
    let mut columns = vec![
        Column::text("scene"),
        Column::text("variant"),
        Column::number("speed-up"),
    ];
    if lanes {
        columns.push(Column::number("SIMD lanes").detail("active"));
    }
    if rates {
        columns.extend(
            ["eye", "secondary", "shadow", "all"].map(|k| Column::number(k).detail("Mrays/s")),
        );
        columns.extend(
            ["eye", "secondary", "shadow", "other", "idle"]
                .map(|k| Column::number(k).detail("% of time")),
        );
    }
    let mut t = Table::new(columns).sortable().dense();
    for (scene, v) in rows {
        let mut row = vec![
            Cell::text(&scene.name),
            Cell::text(v.variant.as_str()),
            match v.speedup {
                Some(x) => Cell::number(format::speedup(x), x),
                None => Cell::dash(),
            },
        ];
        if lanes {
            row.push(match v.lane_utilization {
                Some(u) => Cell::number(format::percent(u * 100.0, 1), u),
                None => Cell::dash(),
            });
        }
        if rates {
            row.extend(rate_cells(v.ray_rates.as_ref()));
        }
        t.rows.push(row);
    }
    t
}

/// Rays per second (eye, secondary, shadow, all) and time shares (eye, secondary,
/// shadow, other, idle); dashes without rates.
fn rate_cells(rates: Option<&RayRates>) -> Vec<Cell> {
    let Some(r) = rates else {
        return (0..9).map(|_| Cell::dash()).collect();
    };
    let speed = |m: Option<f64>| match m {
        Some(m) if m.is_finite() => Cell::number(format::significant(m), m),
        _ => Cell::dash(),
    };
    let share = |f: f64| {
        Cell::number(format::percent(f * 100.0, 1), f).hover(format!(
            "clocked pass: {} the timed render's time",
            format::speedup(r.clock_overhead)
        ))
    };
    vec![
        speed(r.eye_mrays_per_s),
        speed(r.secondary_mrays_per_s),
        speed(r.shadow_mrays_per_s),
        speed(Some(r.all_mrays_per_s)),
        share(r.eye_fraction),
        share(r.secondary_fraction),
        share(r.shadow_fraction),
        share(r.other_fraction),
        share(r.idle_fraction),
    ]
}
