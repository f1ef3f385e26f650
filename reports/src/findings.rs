//! Headline findings: a few plain-English sentences written from a run's data.
//!
//! Each sentence is computed, never canned: the profile's top function and its share,
//! the fastest variant (geometric-mean speed-up over the scenes it ran on) and its worst
//! image error, the variants whose images leave the thesis's "visually identical" band,
//! baseline's own error against the f64 reference renderer, the range of hardware-over-software speed-ups, whether the thesis design fits the
//! validated device and what runs out, the model's worst error against table 8, and
//! failures. A sentence whose data is missing is left out.

use hwmodel::device::{FitState, headroom_warning, resources_above_headroom};

use crate::format::{self, join_list, percent_of};
use crate::results::{
    Band, CriterionEstimate, DeviceUse, HwColumn, HwRow, InstructionCount, Results, VariantName,
};

/// 3-6 sentences about the run beside the three answers (where the time goes and
/// what the variants buy are theirs: `sections::answers`), most important first.
pub fn headline_findings(results: &Results) -> Vec<String> {
    [
        quality_finding(results),
        truth_finding(results),
        hardware_speedup_finding(results),
        device_finding(results),
        model_error_finding(results),
        failures_finding(results),
    ]
    .into_iter()
    .flatten()
    .collect()
}

/// The hardware chapter's opening: how close the model is to the thesis, whether the
/// design fits, and the software-against-hardware speed-ups.
pub fn hardware_finding(results: &Results) -> Option<String> {
    let parts: Vec<String> = [
        model_error_finding(results),
        device_finding(results),
        hardware_speedup_finding(results),
    ]
    .into_iter()
    .flatten()
    .collect();
    (!parts.is_empty()).then(|| parts.join(" "))
}

/// Geometric mean of the finite positive values, with how many there were.
pub fn geometric_mean(values: impl IntoIterator<Item = f64>) -> Option<(f64, usize)> {
    let logs: Vec<f64> = values
        .into_iter()
        .filter(|v| v.is_finite() && *v > 0.0)
        .map(f64::ln)
        .collect();
    if logs.is_empty() {
        return None;
    }
    let mean = logs.iter().sum::<f64>() / logs.len() as f64;
    Some((mean.exp(), logs.len()))
}

/// One scene's image error for a variant.
struct ImageError {
    scene: String,
    rms: f64,
    band: Band,
}

/// What one variant (not baseline) did over the scenes it ran on.
struct VariantStats {
    variant: VariantName,
    /// (scene, speed-up over baseline).
    speedups: Vec<(String, f64)>,
    /// Image errors with a finite RMS.
    errors: Vec<ImageError>,
}

/// Per variant (except baseline), in first-seen order.
fn variant_stats(results: &Results) -> Vec<VariantStats> {
    let mut stats: Vec<VariantStats> = Vec::new();
    for scene in &results.scenes {
        // Findings are about rtprof's variants; outside tracers have their own table.
        let own = |v: &&crate::results::VariantResult| !v.variant.is_outside();
        for v in scene
            .variants
            .iter()
            .filter(own)
            .filter(|v| !v.variant.is_reference())
        {
            let index = match stats.iter().position(|s| s.variant == v.variant) {
                Some(i) => i,
                None => {
                    stats.push(VariantStats {
                        variant: v.variant.clone(),
                        speedups: Vec::new(),
                        errors: Vec::new(),
                    });
                    stats.len() - 1
                }
            };
            stats[index]
                .speedups
                .push((scene.name.clone(), v.speedup.unwrap_or(f64::NAN)));
            if let Some(q) = v.quality.as_ref().filter(|q| q.rms.is_finite()) {
                stats[index].errors.push(ImageError {
                    scene: scene.name.clone(),
                    rms: q.rms,
                    band: q.band,
                });
            }
        }
    }
    stats
}

fn quality_finding(results: &Results) -> Option<String> {
    let stats = variant_stats(results);
    if stats.iter().all(|s| s.errors.is_empty()) {
        return None;
    }
    let leaving: Vec<String> = stats
        .iter()
        .filter_map(|s| {
            let outside: Vec<&ImageError> = s
                .errors
                .iter()
                .filter(|e| e.band != Band::VisuallyIdentical)
                .collect();
            let worst = outside.iter().max_by(|a, b| a.rms.total_cmp(&b.rms))?;
            Some(format!(
                "{} on {} of {} scenes (worst RMS {:.1} on {}: {})",
                s.variant,
                outside.len(),
                s.errors.len(),
                worst.rms,
                worst.scene,
                worst.band
            ))
        })
        .collect();
    Some(if leaving.is_empty() {
        format!(
            "Every variant's images stay in the \"{}\" band against baseline (RMS below {}).",
            Band::VisuallyIdentical,
            Band::VisuallyIdentical.upper_edge().unwrap_or(f64::NAN)
        )
    } else {
        format!(
            "Images leave the \"{}\" band with {}.",
            Band::VisuallyIdentical,
            join_list(&leaving)
        )
    })
}

/// How far baseline (and the variant furthest from it) is from the f64 reference's
/// picture: the error every other image metric inherits.
pub fn truth_finding(results: &Results) -> Option<String> {
    // (scene, variant, RMS against the truth), finite only.
    let errors: Vec<(&str, &VariantName, f64)> = results
        .scenes
        .iter()
        .flat_map(|s| {
            s.variants.iter().filter_map(move |v| {
                let q = v.vs_f64_reference.as_ref()?;
                q.rms
                    .is_finite()
                    .then_some((s.name.as_str(), &v.variant, q.rms))
            })
        })
        .collect();
    let baseline: Vec<&(&str, &VariantName, f64)> =
        errors.iter().filter(|e| e.1.is_reference()).collect();
    let worst_base = baseline.iter().max_by(|a, b| a.2.total_cmp(&b.2))?;
    let exact = baseline.iter().filter(|e| e.2 == 0.0).count();
    let furthest = errors
        .iter()
        .filter(|e| !e.1.is_reference() && !e.1.is_outside())
        .max_by(|a, b| a.2.total_cmp(&b.2))
        .map(|(scene, variant, rms)| {
            format!(
                "; the variant furthest from it is {variant} (RMS {} on {scene})",
                format::fixed(*rms, 2)
            )
        })
        .unwrap_or_default();
    Some(format!(
        "Against the independent f64 reference renderer, {}'s pictures are at most RMS {} off (on {}), and the same to the 8-bit level on {} of {}{furthest}.",
        worst_base.1,
        format::fixed(worst_base.2, 2),
        worst_base.0,
        exact,
        format::plural(baseline.len(), "scene"),
    ))
}

fn hardware_speedup_finding(results: &Results) -> Option<String> {
    let speedups: Vec<(&str, f64)> = results
        .scenes
        .iter()
        .filter_map(|s| {
            s.hardware
                .as_ref()
                .map(|h| (s.name.as_str(), h.speedup))
                .filter(|h| h.1.is_finite() && h.1 > 0.0)
        })
        .collect();
    let low = speedups.iter().min_by(|a, b| a.1.total_cmp(&b.1))?;
    let high = speedups.iter().max_by(|a, b| a.1.total_cmp(&b.1))?;
    let verdict = if high.1 < 1.0 {
        "the software is faster on every scene"
    } else if low.1 > 1.0 {
        "the hardware is faster on every scene"
    } else {
        "each wins on some scenes"
    };
    Some(format!(
        "The hardware model's speed-up over software ranges from {:.2}× ({}) to {:.2}× ({}) across {} scenes, against 4.6 to 18 in the thesis: {verdict}.",
        low.1,
        low.0,
        high.1,
        high.0,
        speedups.len()
    ))
}

/// The fit of a device use: fits, fits on paper only (logic, memory bits or memory
/// blocks above their headroom, [`hwmodel::device::HEADROOM_RESOURCES`]), does not fit.
pub fn fit_state(d: &DeviceUse) -> FitState {
    d.fit_state
        .unwrap_or_else(|| FitState::of(d.fits, &resources_above_headroom_of(d)))
}

/// The routing-headroom warning of a device use ([`hwmodel::device::headroom_warning`]),
/// `None` unless it fits on paper only.
pub fn headroom_warning_of(d: &DeviceUse) -> Option<String> {
    if fit_state(d) != FitState::FitsOnPaper {
        return None;
    }
    let share = |used: u64, capacity: u64| percent_of(used, capacity) / 100.0;
    let above: Vec<(&str, f64)> = resources_above_headroom_of(d)
        .into_iter()
        .map(|r| match r {
            "le" => (r, share(d.le, d.le_capacity)),
            "mem_blocks" => (r, share(d.mem_blocks, d.mem_block_capacity)),
            _ => (r, share(d.mem_bits, d.mem_capacity)),
        })
        .collect();
    headroom_warning(&above)
}

fn resources_above_headroom_of(d: &DeviceUse) -> Vec<&'static str> {
    resources_above_headroom(
        (d.le, d.le_capacity),
        (d.mem_bits, d.mem_capacity),
        (d.mem_blocks, d.mem_block_capacity),
    )
}

/// Resources a device runs out of: demand at or above its capacity.
pub fn exhausted_resources(d: &DeviceUse) -> Vec<String> {
    let mut out = Vec::new();
    if d.le >= d.le_capacity {
        out.push("logic elements".to_string());
    }
    if d.mult + d.soft_mult_elements >= d.mult_capacity && d.mult_capacity > 0 {
        out.push(if d.soft_mult_elements > 0 {
            format!(
                "9-bit multipliers (all {} used, {} more built in logic)",
                d.mult_capacity, d.soft_mult_elements
            )
        } else {
            format!("9-bit multipliers (all {} used)", d.mult_capacity)
        });
    }
    if d.mem_bits >= d.mem_capacity {
        out.push("memory bits".to_string());
    }
    if d.plls >= d.pll_capacity {
        out.push("PLLs".to_string());
    }
    out
}

fn device_finding(results: &Results) -> Option<String> {
    let hardware = results.hardware.as_ref()?;
    let d = hardware
        .devices
        .iter()
        .find(|d| d.validated)
        .or_else(|| hardware.devices.first())?;
    let exhausted = exhausted_resources(d);
    let use_text = format!(
        "{:.0} % of its logic elements and {:.0} % of its memory bits",
        percent_of(d.le, d.le_capacity),
        percent_of(d.mem_bits, d.mem_capacity)
    );
    let runs_out = if exhausted.is_empty() {
        "nothing runs out".to_string()
    } else {
        format!("what runs out is {}", join_list(&exhausted))
    };
    let (verdict, only) = match fit_state(d) {
        FitState::Fits => ("fits", String::new()),
        FitState::FitsOnPaper => (
            "fits",
            format!(
                " only on paper, above the {} % routing headroom",
                hwmodel::device::ROUTING_HEADROOM_PERCENT
            ),
        ),
        FitState::DoesNotFit => ("does not fit", String::new()),
    };
    Some(format!(
        "The thesis design {verdict} the {}{}{only} ({use_text}); {runs_out}.",
        d.device,
        if d.validated {
            ""
        } else {
            " (unvalidated device data)"
        }
    ))
}

/// The largest |error| of `rows` against the thesis: (row, column, signed error %).
pub fn worst_error(rows: &[HwRow]) -> Option<(&str, HwColumn, f64)> {
    rows.iter()
        .filter_map(|r| r.error_pct.as_ref().map(|e| (r, e)))
        .flat_map(|(r, errors)| {
            errors.columns().into_iter().filter_map(move |(c, e)| {
                e.filter(|e| e.is_finite()).map(|e| (r.name.as_str(), c, e))
            })
        })
        .max_by(|a, b| a.2.abs().total_cmp(&b.2.abs()))
}

fn model_error_finding(results: &Results) -> Option<String> {
    let hardware = results.hardware.as_ref()?;
    let (block, column, error) = worst_error(&hardware.blocks)?;
    let latency_worst = hardware
        .blocks
        .iter()
        .filter_map(|r| r.error_pct.as_ref().and_then(|e| e.latency))
        .filter(|e| e.is_finite())
        .map(f64::abs)
        .fold(None, |acc: Option<f64>, e| {
            Some(acc.map_or(e, |a| a.max(e)))
        });
    // The IP cores whose latency the library takes from rtprof's RTL rather than from
    // the thesis: the block latencies above rest on them.
    let own_latencies: Vec<String> = hardware
        .ops
        .iter()
        .filter_map(|r| {
            let thesis = r.thesis?.latency;
            (r.model.latency != thesis).then(|| {
                format!(
                    "{} {} cycles for the thesis's {thesis}",
                    r.name, r.model.latency
                )
            })
        })
        .collect();
    let latency = latency_worst
        .map(|l| {
            if own_latencies.is_empty() {
                format!("; its latencies are within {l:.1} % of the thesis")
            } else {
                format!(
                    "; its latencies are within {l:.1} % of the thesis with rtprof's RTL's own {}",
                    join_list(&own_latencies)
                )
            }
        })
        .unwrap_or_default();
    // Figures the model has where the thesis has none have no percentage: named apart.
    let in_kind: Vec<String> = hardware
        .blocks
        .iter()
        .flat_map(|r| {
            let thesis = r.thesis;
            r.model
                .columns()
                .into_iter()
                .filter(move |&(c, m)| thesis.is_some_and(|t| t.get(c) == 0) && m > 0)
                .map(move |(c, m)| format!("{} {} {}", r.name, format::count(m), c.label()))
        })
        .collect();
    let in_kind = if in_kind.is_empty() {
        String::new()
    } else {
        format!(
            "; where table 8 has none the model has some: {}",
            join_list(&in_kind)
        )
    };
    Some(format!(
        "The hardware model's worst error against table 8 is {error:+.1} % ({block}, {}){latency}{in_kind}.",
        column.label()
    ))
}

fn failures_finding(results: &Results) -> Option<String> {
    let first = results.failures.first()?;
    let n = results.failures.len();
    let what = first.place();
    Some(format!(
        "{n} part{} of the run failed (first: {what}: {}); the other results stand.",
        if n == 1 { "" } else { "s" },
        first.message
    ))
}

/// One benchmark's row of the criterion section: its time estimates and, when
/// gungraun counted it, its instructions. Sorted by id; benchmarks with only one of the
/// two still get a row.
#[derive(Clone, Debug, PartialEq)]
pub struct BenchmarkRow<'a> {
    pub id: &'a str,
    pub time: Option<&'a CriterionEstimate>,
    pub instructions: Option<&'a InstructionCount>,
}

/// The rows of the criterion section: criterion's estimates joined with the
/// instruction counts of the same id.
pub fn benchmark_rows(results: &Results) -> Vec<BenchmarkRow<'_>> {
    let mut rows: std::collections::BTreeMap<&str, BenchmarkRow<'_>> = Default::default();
    for c in &results.criterion {
        rows.entry(&c.id)
            .or_insert(BenchmarkRow {
                id: &c.id,
                time: None,
                instructions: None,
            })
            .time = Some(c);
    }
    for i in &results.instructions {
        rows.entry(&i.id)
            .or_insert(BenchmarkRow {
                id: &i.id,
                time: None,
                instructions: None,
            })
            .instructions = Some(i);
    }
    let mut rows: Vec<BenchmarkRow<'_>> = rows.into_values().collect();
    rows.sort_by(|a, b| natural_order(a.id, b.id));
    rows
}

/// Orders ids part by part, numbers by value (`accel/bvh/91` before `accel/bvh/820`).
fn natural_order(a: &str, b: &str) -> std::cmp::Ordering {
    let key = |id: &str| -> Vec<(u64, String)> {
        id.split('/')
            .map(|part| match part.parse::<u64>() {
                Ok(n) => (n, String::new()),
                Err(_) => (u64::MAX, part.to_string()),
            })
            .collect()
    };
    key(a).cmp(&key(b))
}

/// When the benchmarks were measured, from the harness files' times:
/// " (measured 2026-11-21 22:50 UTC)" or " (measured 2026-11-20 09:12 – 2026-11-21
/// 22:50 UTC)", or nothing when no time is known. Old estimates stay in
/// `target/criterion` until overwritten, so the span tells a stale run.
pub fn measured_span(results: &Results) -> String {
    let times: Vec<&str> = results
        .criterion
        .iter()
        .filter_map(|c| c.measured.as_deref())
        .chain(
            results
                .instructions
                .iter()
                .filter_map(|i| i.measured.as_deref()),
        )
        .collect();
    // RFC 3339 UTC strings of one format sort in time order.
    let (Some(first), Some(last)) = (times.iter().min(), times.iter().max()) else {
        return String::new();
    };
    let minutes = |t: &str| t.get(..16).unwrap_or(t).replace('T', " ");
    if minutes(first) == minutes(last) {
        format!(" (measured {} UTC)", minutes(first))
    } else {
        format!(" (measured {} – {} UTC)", minutes(first), minutes(last))
    }
}

/// The parent of a benchmark id (`sqrt/fast-sqrt` → `sqrt`).
fn parent_id(id: &str) -> &str {
    id.rsplit_once('/').map_or("", |(parent, _)| parent)
}

/// The benchmark `id` is compared with: in its group, `<family>-std` for
/// `<family>-<method>` (`sqrt/inverse-classic` against `sqrt/inverse-std`), else `std`,
/// else the group's first id. A `std` benchmark of its own family is the reference, not
/// compared; `None` when nothing is left to compare with.
fn reference_of<'r, 'a>(id: &str, rows: &'r [BenchmarkRow<'a>]) -> Option<&'r BenchmarkRow<'a>> {
    let (group, name) = id.rsplit_once('/')?;
    let sibling = |n: &str| {
        rows.iter()
            .find(|r| r.id.rsplit_once('/') == Some((group, n)))
    };
    let family_std = name
        .split_once('-')
        .map(|(family, _)| format!("{family}-std"));
    let reference = family_std
        .as_deref()
        .and_then(sibling)
        .or_else(|| sibling("std"))
        .or_else(|| rows.iter().find(|r| parent_id(r.id) == group))?;
    let is_reference = reference.id == id || name == "std" || name.ends_with("-std");
    (!is_reference).then_some(reference)
}

/// How far apart the time and instruction ratios must be to be called misleading.
const MISLEADING_FACTOR: f64 = 1.5;

/// Sentences for the benchmarks whose instruction count and wall time point opposite
/// ways against their group's reference (`<group>/std` when there is one, otherwise
/// the group's first id): more instructions yet significantly less time, or the reverse.
/// Time counts only when the 95 % intervals of the medians do not overlap. When
/// nothing disagrees and both were measured, one sentence says so.
pub fn instruction_time_disagreements(results: &Results) -> Vec<String> {
    let rows: Vec<BenchmarkRow<'_>> = benchmark_rows(results)
        .into_iter()
        .filter(|r| r.time.is_some() && r.instructions.is_some())
        .collect();
    let mut sentences = Vec::new();
    let mut compared = 0;
    for row in &rows {
        let Some(reference) = reference_of(row.id, &rows) else {
            continue;
        };
        let (Some(t), Some(t_ref), Some(i), Some(i_ref)) = (
            row.time,
            reference.time,
            row.instructions,
            reference.instructions,
        ) else {
            continue;
        };
        compared += 1;
        let (t, t_ref) = (&t.median, &t_ref.median);
        let faster = t.high < t_ref.low;
        let slower = t.low > t_ref.high;
        let more = i.instructions > i_ref.instructions;
        let fewer = i.instructions < i_ref.instructions;
        let instruction_ratio = i.instructions as f64 / i_ref.instructions.max(1) as f64;
        let time_ratio = t.median / t_ref.median;
        if (more && faster) || (fewer && slower) {
            sentences.push(format!(
                "{} executes {instruction_ratio:.2}× the instructions of {} yet takes {time_ratio:.2}× its time: instruction counts are not time (vector width, latency and the execution ports differ).",
                row.id, reference.id,
            ));
        } else if (faster || slower)
            && (time_ratio / instruction_ratio > MISLEADING_FACTOR
                || instruction_ratio / time_ratio > MISLEADING_FACTOR)
        {
            sentences.push(format!(
                "{} executes {instruction_ratio:.2}× the instructions of {} and takes {time_ratio:.2}× its time: the instruction count alone is off by {:.1}×.",
                row.id,
                reference.id,
                (time_ratio / instruction_ratio).max(instruction_ratio / time_ratio),
            ));
        }
    }
    if sentences.is_empty() && compared > 0 {
        sentences.push(format!(
            "Instruction counts and wall time point the same way for all {compared} benchmarks compared with their group's reference."
        ));
    }
    sentences
}

/// Every (scene, width, height, variant) of any of `runs`, in first-seen order: the
/// rows of the side-by-side comparison.
pub fn comparison_keys(runs: &[crate::Run]) -> Vec<(String, u32, u32, VariantName)> {
    let mut keys = Vec::new();
    let mut seen = std::collections::BTreeSet::new();
    for run in runs {
        for s in &run.results.scenes {
            for v in &s.variants {
                let key = (s.name.clone(), s.width, s.height, v.variant.clone());
                if seen.insert(key.clone()) {
                    keys.push(key);
                }
            }
        }
    }
    keys
}

/// How many timed renders each figure rests on, in words ("3 timed repeats, more
/// until 0.2 s").
pub fn repeats_text(s: &crate::results::SuiteInfo) -> String {
    let t = &s.timing;
    let base = format!(
        "{} timed repeat{}",
        t.min_repeats,
        if t.min_repeats == 1 { "" } else { "s" }
    );
    if t.min_seconds > 0.0 {
        format!(
            "{base} (more, up to {}, until {} s is measured)",
            t.max_repeats, t.min_seconds
        )
    } else {
        base
    }
}

#[cfg(test)]
mod tests;
