//! The roofline section: how close each render runs to the machine, as a point of
//! attained GFLOP/s against arithmetic intensity under the measured peaks, the table of
//! those points and a sentence on the headline scene. Omitted when no variant has a
//! roofline point (files before `rtprof.results/3`'s efficiency).

use super::access;
use crate::document::{Block, Builder, Cell, Column, Section, Table, Tone};
use crate::format;
use crate::results::{Efficiency, MachinePeak, Results, SceneResult, VariantResult};

pub fn roofline(b: &mut Builder) -> Option<Section> {
    let r = b.results();
    let points: Vec<(&SceneResult, &VariantResult, &Efficiency)> = r
        .scenes
        .iter()
        .flat_map(|s| s.variants.iter().map(move |v| (s, v)))
        .filter_map(|(s, v)| Some((s, v, v.efficiency.as_ref()?)))
        .collect();
    if points.is_empty() {
        return None;
    }
    let mut s = b.section("roofline", None);
    match &r.peak {
        Some(peak) => s.text(peaks_line(peak)),
        None => s.blocks.push(Block::note(
            Tone::Fair,
            "The machine's peaks were not measured in this run: the points have no roof to be compared with.",
        )),
    }
    if let Some(sentence) = headline(r) {
        s.text(sentence);
    }
    if let Some(figure) = b.chart("roofline", 11.0) {
        s.blocks.push(figure);
    }
    s.blocks
        .push(Block::Table(points_table(r, &points, r.peak.as_ref())));
    Some(s)
}

/// What the kernels measured, which roof bounds a render's bytes and where it meets
/// the compute peak.
fn peaks_line(peak: &MachinePeak) -> String {
    let bandwidths = if peak.cache_bandwidth_gbs > 0.0 {
        format!(
            "{} GB/s by the STREAM triad within the L1 cache and {} GB/s from DRAM (arrays of {})",
            format::significant(peak.cache_bandwidth_gbs),
            format::significant(peak.bandwidth_gbs),
            format::bytes(peak.stream_bytes)
        )
    } else {
        format!(
            "{} GB/s by the STREAM triad from DRAM (arrays of {}; no cache bandwidth in this file, so DRAM's is the roof)",
            format::significant(peak.bandwidth_gbs),
            format::bytes(peak.stream_bytes)
        )
    };
    format!(
        "The machine's peaks, measured on the suite's {}: {} GFLOP/s by the FMA kernel ({}), {bandwidths}. A render's bytes count every record it reads, wherever it is found (the cache-aware roofline), so the fastest bandwidth is its roof: below an intensity of {} flop/byte a render is bandwidth-bound, above it compute-bound.{}",
        format::plural(peak.threads as usize, "thread"),
        format::significant(peak.peak_gflops),
        peak.fma_kernel,
        format::significant(peak.ridge_intensity()),
        if peak.cache_bandwidth_gbs > 0.0 {
            " A point above the DRAM roof read most of its records from the caches."
        } else {
            ""
        }
    )
}

/// The sentence on the headline scene: the reference's GFLOP/s against the peak, how
/// far the fastest variant is from its roof, and what the counts can and cannot say.
fn headline(r: &Results) -> Option<String> {
    let scene = access::headline_scene(r, |s| s.variants.iter().any(|v| v.efficiency.is_some()))?;
    let measured = |v: &&VariantResult| v.efficiency.is_some();
    let base = access::reference(r, scene)
        .filter(measured)
        .or_else(|| scene.variants.iter().find(measured))?;
    let e = base.efficiency.as_ref()?;
    let mut text = format!(
        "On {}, {} attains {} GFLOP/s at {} flop/byte",
        scene.name,
        base.variant,
        format::significant(e.achieved_gflops),
        format::significant(e.arithmetic_intensity)
    );
    if let Some(peak) = &r.peak {
        text += &format!(
            ", {} of the {} GFLOP/s peak",
            format::percent(e.achieved_gflops / peak.peak_gflops * 100.0, 1),
            format::significant(peak.peak_gflops)
        );
        let dram = peak.dram_roof_gflops(e.arithmetic_intensity);
        if peak.cache_bandwidth_gbs > 0.0 && e.achieved_gflops > dram {
            text += &format!(
                " and above the {} GFLOP/s DRAM alone could feed it: its records came mostly from the caches",
                format::significant(dram)
            );
        }
    }
    let fastest = access::fastest(scene)
        .filter(|v| v.variant != base.variant)
        .and_then(|v| Some((v, v.efficiency.as_ref()?)));
    if let Some((v, fe)) = fastest {
        text += &format!(
            "; the fastest variant, {}, attains {} GFLOP/s at {} flop/byte",
            v.variant,
            format::significant(fe.achieved_gflops),
            format::significant(fe.arithmetic_intensity)
        );
        if let Some(peak) = &r.peak {
            text += &roof_clause(fe, peak);
        }
    }
    text += ". The flops are the counted vector operations only, a lower bound of the floating-point work the processor did; the bytes are the records the render reads, estimated from the counts.";
    Some(text)
}

/// How far a point is from its roof, and which roof that is.
fn roof_clause(e: &Efficiency, peak: &MachinePeak) -> String {
    let roof = roof_of(e, peak);
    let share = e.achieved_gflops / roof * 100.0;
    let bound = bound_by(e.arithmetic_intensity, peak);
    if share > 100.0 {
        format!(
            ", {} of its {bound} roof of {} GFLOP/s: above it, so the kernels measured less than this render reached",
            format::percent(share, 1),
            format::significant(roof)
        )
    } else {
        format!(
            ", {} of its {bound} roof of {} GFLOP/s ({}× below it)",
            format::percent(share, 1),
            format::significant(roof),
            format::significant(roof / e.achieved_gflops)
        )
    }
}

/// The roof over a point: as the file records it, else from the peaks.
fn roof_of(e: &Efficiency, peak: &MachinePeak) -> f64 {
    e.roof_gflops
        .filter(|r| r.is_finite() && *r > 0.0)
        .unwrap_or_else(|| peak.roof_gflops(e.arithmetic_intensity))
}

/// Which roof caps a render of this intensity.
fn bound_by(intensity: f64, peak: &MachinePeak) -> &'static str {
    if intensity < peak.ridge_intensity() {
        "bandwidth"
    } else {
        "compute"
    }
}

/// One row per scene, one column per variant (the suite's order): the attained
/// GFLOP/s and, with the peaks, the share of the roof at that intensity. Hover: the
/// flops, the time, the intensity, the roof and which roof it is.
fn points_table(
    r: &Results,
    points: &[(&SceneResult, &VariantResult, &Efficiency)],
    peak: Option<&MachinePeak>,
) -> Table {
    let rows: Vec<(&SceneResult, &VariantResult)> =
        points.iter().map(|(s, v, _)| (*s, *v)).collect();
    let (scenes, variants) = access::pivot(r, &rows);
    let mut columns = vec![Column::text("scene")];
    columns.extend(variants.iter().map(|v| Column::number(*v)));
    let caption = if peak.is_some() {
        "Attained GFLOP/s (share of the roof at the render's intensity) per scene and variant; hover for the intensity and the roof"
    } else {
        "Attained GFLOP/s per scene and variant; hover for the intensity"
    };
    let mut t = Table::new(columns).sortable().dense().caption(caption);
    for scene in scenes {
        let mut row = vec![Cell::text(&scene.name)];
        for variant in &variants {
            row.push(
                match access::pivot_cell(&rows, scene, variant)
                    .and_then(|v| Some((v, v.efficiency.as_ref()?)))
                {
                    Some((v, e)) => point_cell(v, e, peak),
                    None => Cell::dash(),
                },
            );
        }
        t.rows.push(row);
    }
    t
}

/// `GFLOP/s (share of roof)`, sorted by the share (by GFLOP/s without peaks).
fn point_cell(v: &VariantResult, e: &Efficiency, peak: Option<&MachinePeak>) -> Cell {
    let attained = format::significant(e.achieved_gflops);
    let work = format!(
        "{} flops in {}; {} flop/byte ({} read)",
        format::count(e.flops),
        format::seconds(v.time.median),
        format::significant(e.arithmetic_intensity),
        format::bytes(e.bytes_moved)
    );
    let Some(peak) = peak else {
        return Cell::number(attained, e.achieved_gflops).hover(work);
    };
    let roof = roof_of(e, peak);
    let share = e.achieved_gflops / roof * 100.0;
    let cell =
        Cell::number(format!("{attained} ({})", format::percent(share, 1)), share).hover(format!(
            "{work}; roof {} GFLOP/s, {}-bound; DRAM roof {} GFLOP/s",
            format::significant(roof),
            bound_by(e.arithmetic_intensity, peak),
            format::significant(peak.dram_roof_gflops(e.arithmetic_intensity))
        ));
    if share > 100.0 {
        cell.tone(Tone::Warning)
    } else {
        cell
    }
}
