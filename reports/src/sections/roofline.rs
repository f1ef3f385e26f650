//! The roofline section: how close each render runs to the machine, as a point of
//! attained GFLOP/s against arithmetic intensity under the measured roofs, the table of
//! those points and a sentence on the headline scene. Every share it states, in the
//! sentence and the table, is of one basis: the roof that applies to the render
//! ([`judged`]). Omitted when no variant has a roofline point (files before
//! `rtprof.results/3`'s efficiency).

use super::access;
use crate::document::{Block, Builder, Cell, Column, Section, Table, Tone};
use crate::format;
use crate::results::{
    Bound, CodeKind, Efficiency, MachinePeak, Results, Roof, SceneResult, VariantResult,
};

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

/// What the kernels measured, which roof holds a render and where the compute roofs
/// meet the bandwidth roof.
fn peaks_line(peak: &MachinePeak) -> String {
    let compute = match (peak.scalar_peak(), &peak.scalar_kernel) {
        (Some(scalar), kernel) => format!(
            "{} GFLOP/s in SIMD lanes by the FMA kernel ({}) and {} GFLOP/s in scalar instructions ({})",
            format::significant(peak.peak_gflops),
            peak.fma_kernel,
            format::significant(scalar),
            kernel.as_deref().unwrap_or("the same chains one lane wide")
        ),
        (None, _) => format!(
            "{} GFLOP/s in SIMD lanes by the FMA kernel ({}; this file has no scalar peak, so scalar code is set against this one too)",
            format::significant(peak.peak_gflops),
            peak.fma_kernel
        ),
    };
    let bandwidths = if peak.cache_bandwidth_gbs > 0.0 {
        format!(
            "{} GB/s by the STREAM triad within the L1 cache and {} GB/s from DRAM (arrays of {})",
            format::significant(peak.cache_bandwidth_gbs),
            format::significant(peak.bandwidth_gbs),
            format::bytes(peak.stream_bytes)
        )
    } else {
        format!(
            "{} GB/s by the STREAM triad from DRAM (arrays of {}; no cache bandwidth in this file, so DRAM's is the bandwidth roof)",
            format::significant(peak.bandwidth_gbs),
            format::bytes(peak.stream_bytes)
        )
    };
    let ridges = match peak.scalar_peak() {
        Some(_) => format!(
            "scalar code is bandwidth-bound below {} flop/byte, SIMD code below {}",
            format::significant(peak.ridge(CodeKind::Scalar)),
            format::significant(peak.ridge(CodeKind::Simd))
        ),
        None => format!(
            "a render is bandwidth-bound below {} flop/byte",
            format::significant(peak.ridge(CodeKind::Simd))
        ),
    };
    format!(
        "The machine's peaks, measured on {} as the timed renders run: {compute}; {bandwidths}. A render's bytes count every record it reads, wherever it is found (the cache-aware roofline), so the fastest bandwidth bounds them. Each render is set against the one roof that applies to it: the lower of its code's compute peak (SIMD for the variants that test in SIMD lanes, scalar for the others) and the {} bandwidth times its intensity; {ridges}. The shares below, in the text and the table, are of that roof.{}",
        format::plural(peak.threads as usize, "thread"),
        if peak.cache_bandwidth_gbs > 0.0 {
            "L1"
        } else {
            "DRAM"
        },
        if peak.cache_bandwidth_gbs > 0.0 {
            " A point above the DRAM roof read most of its records from the caches."
        } else {
            ""
        }
    )
}

/// A render against the roof that applies to it.
#[derive(Clone, Copy, Debug)]
struct Judged {
    roof: Roof,
    /// The code kind of the variant (the roof may be another kind's in files without
    /// the scalar peak).
    code: CodeKind,
    /// Attained over the roof, %.
    share: f64,
}

/// The one basis of every share the section states: attained GFLOP/s over the roof
/// that applies to the render, `min(compute peak of its code, bandwidth × intensity)`
/// ([`MachinePeak::roof`]), from the peaks (the roof the chart draws), not from the
/// file's `roof_gflops`, which files before the scalar peak computed otherwise.
fn judged(v: &VariantResult, e: &Efficiency, peak: &MachinePeak) -> Judged {
    let code = CodeKind::of_variant(&v.variant);
    let roof = peak.roof(code, e.arithmetic_intensity);
    Judged {
        roof,
        code,
        share: e.achieved_gflops / roof.gflops * 100.0,
    }
}

/// The roof by name: `the scalar peak of 18.6 GFLOP/s`, `the L1 bandwidth roof of
/// 2.40 GFLOP/s at that intensity`.
fn roof_name(j: &Judged, peak: &MachinePeak) -> String {
    let gflops = format::significant(j.roof.gflops);
    match j.roof.bound {
        Bound::Compute(kind) if kind == j.code => {
            format!("the {} peak of {gflops} GFLOP/s", kind.name())
        }
        Bound::Compute(kind) => format!(
            "the {} peak of {gflops} GFLOP/s (no {} peak in this file)",
            kind.name(),
            j.code.name()
        ),
        Bound::Bandwidth => format!(
            "the {} bandwidth roof of {gflops} GFLOP/s at that intensity",
            if peak.cache_bandwidth_gbs > 0.0 {
                "L1"
            } else {
                "DRAM"
            }
        ),
    }
}

/// `: 17.2 % of the roof that applies, the scalar peak of 18.6 GFLOP/s`, or that it
/// is above it.
fn share_clause(j: &Judged, peak: &MachinePeak) -> String {
    if j.share > 100.0 {
        let why = if j.roof.bound == Bound::Compute(CodeKind::Scalar) {
            // glam's Vec3A: a dot product's multiplies are one SSE instruction.
            "the scalar kernel runs one lane, while scalar code's vector maths (glam's Vec3A) runs three SSE lanes wide"
        } else {
            "the kernels measured less than this render reached"
        };
        format!(
            ": {} of its roof, {}, above it: {why}",
            format::percent(j.share, 1),
            roof_name(j, peak)
        )
    } else {
        format!(
            ": {} of its roof, {}",
            format::percent(j.share, 1),
            roof_name(j, peak)
        )
    }
}

/// The sentence on the headline scene: the reference's and the fastest variant's
/// GFLOP/s as shares of the roofs that apply to them, and what the counts can and
/// cannot say.
fn headline(r: &Results) -> Option<String> {
    let scene = access::headline_scene(r, |s| s.variants.iter().any(|v| v.efficiency.is_some()))?;
    let measured = |v: &&VariantResult| v.efficiency.is_some();
    let base = access::reference(r, scene)
        .filter(measured)
        .or_else(|| scene.variants.iter().find(measured))?;
    let e = base.efficiency.as_ref()?;
    let mut text = format!(
        "On {}, {} ({} code) attains {} GFLOP/s at {} flop/byte",
        scene.name,
        base.variant,
        CodeKind::of_variant(&base.variant).name(),
        format::significant(e.achieved_gflops),
        format::significant(e.arithmetic_intensity)
    );
    if let Some(peak) = &r.peak {
        text += &share_clause(&judged(base, e, peak), peak);
        let dram = peak.dram_roof_gflops(e.arithmetic_intensity);
        if peak.cache_bandwidth_gbs > 0.0 && e.achieved_gflops > dram {
            text += &format!(
                ", and above the {} GFLOP/s DRAM alone could feed it: its records came mostly from the caches",
                format::significant(dram)
            );
        }
    }
    let fastest = access::fastest(scene)
        .filter(|v| v.variant != base.variant)
        .and_then(|v| Some((v, v.efficiency.as_ref()?)));
    if let Some((v, fe)) = fastest {
        text += &format!(
            "; the fastest variant, {} ({} code), attains {} GFLOP/s at {} flop/byte",
            v.variant,
            CodeKind::of_variant(&v.variant).name(),
            format::significant(fe.achieved_gflops),
            format::significant(fe.arithmetic_intensity)
        );
        if let Some(peak) = &r.peak {
            text += &share_clause(&judged(v, fe, peak), peak);
        }
    }
    text += ". The flops are the counted vector operations only, a lower bound of the floating-point work the processor did; the bytes are the records the render reads, estimated from the counts.";
    Some(text)
}

/// One row per scene, one column per variant (the suite's order): the attained
/// GFLOP/s and, with the peaks, the share of the roof that applies to it. Hover: the
/// flops, the time, the intensity and that roof.
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
        "Attained GFLOP/s (share of the roof that applies: the lower of its code's compute peak and the bandwidth roof at its intensity) per scene and variant; hover for the intensity and the roof"
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
    let j = judged(v, e, peak);
    let cell = Cell::number(
        format!("{attained} ({})", format::percent(j.share, 1)),
        j.share,
    )
    .hover(format!(
        "{work}; {} code; roof: {}; DRAM roof {} GFLOP/s",
        j.code.name(),
        roof_name(&j, peak),
        format::significant(peak.dram_roof_gflops(e.arithmetic_intensity))
    ));
    if j.share > 100.0 {
        cell.tone(Tone::Warning)
    } else {
        cell
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn peak() -> MachinePeak {
        MachinePeak {
            peak_gflops: 100.0,
            bandwidth_gbs: 10.0,
            cache_bandwidth_gbs: 200.0,
            threads: 2,
            fma_kernel: "AVX2+FMA, 8 lanes × 12 chains".to_string(),
            stream_bytes: 1 << 20,
            scalar_peak_gflops: Some(12.5),
            scalar_kernel: Some("scalar FMA, 1 lane × 12 chains".to_string()),
        }
    }

    #[test]
    fn a_point_above_its_roof_says_why_it_can_be() {
        let p = peak();
        let scalar = Judged {
            roof: p.roof(CodeKind::Scalar, 1.0),
            code: CodeKind::Scalar,
            share: 120.0,
        };
        assert_eq!(
            share_clause(&scalar, &p),
            ": 120.0 % of its roof, the scalar peak of 12.5 GFLOP/s, above it: the scalar kernel runs one lane, while scalar code's vector maths (glam's Vec3A) runs three SSE lanes wide"
        );
        // 0.1 flop/byte: L1 feeds 20 GFLOP/s, below the SIMD peak.
        let simd = Judged {
            roof: p.roof(CodeKind::Simd, 0.1),
            code: CodeKind::Simd,
            share: 50.0,
        };
        assert_eq!(
            share_clause(&simd, &p),
            ": 50.0 % of its roof, the L1 bandwidth roof of 20.0 GFLOP/s at that intensity"
        );
    }
}
