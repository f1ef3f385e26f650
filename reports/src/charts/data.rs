//! The fields of the results that the charts read, each behind one small function, so a
//! change of the results types touches this file only.

use super::scale::finite_positive;
use crate::results::{DeviceUse, Results, SceneHardware, SceneResult, VariantResult};

/// Whether `v` is the reference variant every other one is compared with.
pub(super) fn is_reference(v: &VariantResult) -> bool {
    v.variant.is_reference()
}

/// The reference variant's result on `scene`.
pub(super) fn reference<'a>(
    results: &Results,
    scene: &'a SceneResult,
) -> Option<&'a VariantResult> {
    results.baseline(scene)
}

/// The variant's name as the report shows it.
pub(super) fn variant_name(v: &VariantResult) -> &str {
    &v.variant
}

/// The speed-up against the reference (NaN when it was not measured).
pub(super) fn speedup(v: &VariantResult) -> f64 {
    v.speedup.unwrap_or(f64::NAN)
}

/// The RMS error against the reference, when it was measured and is a number.
pub(super) fn rms(v: &VariantResult) -> Option<f64> {
    v.quality.as_ref().map(|q| q.rms).filter(|r| r.is_finite())
}

/// The place of `variant` among the run's non-reference variants (`None` for the
/// reference), for its colour. A variant outside the suite's list gets a stable place
/// from its name.
pub(super) fn variant_place(results: &Results, variant: &VariantResult) -> Option<usize> {
    if is_reference(variant) {
        return None;
    }
    let name = variant_name(variant);
    let place = results
        .suite
        .variants
        .iter()
        .filter(|v| !v.is_reference())
        .position(|v| v.as_str() == name)
        .unwrap_or_else(|| name.bytes().map(usize::from).sum());
    Some(place)
}

/// The 256-bin gray histogram, when the variant recorded one.
pub(super) fn gray_histogram(v: &VariantResult) -> Option<&[u64]> {
    (v.histogram.len() == 256).then_some(v.histogram.as_slice())
}

/// The timed repeats of a render: its samples, or its median when no samples were kept.
pub(super) fn time_samples(v: &VariantResult) -> Vec<f64> {
    if v.samples.is_empty() {
        vec![v.time.median]
    } else {
        v.samples.clone()
    }
}

/// Scenes with a usable hardware result (finite positive model and software times), in
/// run order, with that result.
pub(super) fn hardware_scenes(results: &Results) -> Vec<(&SceneResult, &SceneHardware)> {
    results
        .scenes
        .iter()
        .filter_map(|s| s.hardware.as_ref().map(|h| (s, h)))
        .filter(|(_, h)| finite_positive(h.seconds) && finite_positive(h.software_seconds.median))
        .collect()
}

/// The hardware model's frame time per primitive count in `counts` (one per count, the
/// smallest), sorted by count.
pub(super) fn finite_hardware_times(
    results: &Results,
    counts: std::ops::RangeInclusive<u64>,
) -> Vec<(u64, f64)> {
    let mut times: Vec<(u64, f64)> = results
        .scenes
        .iter()
        .filter_map(|s| s.hardware.as_ref())
        .filter(|h| counts.contains(&h.primitives) && finite_positive(h.seconds))
        .map(|h| (h.primitives, h.seconds))
        .collect();
    times.sort_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)));
    times.dedup_by_key(|h| h.0);
    times
}

/// The resources of the device-utilization chart, in drawing order.
pub(super) const RESOURCES: [&str; 4] =
    ["logic elements", "9-bit multipliers", "memory bits", "PLLs"];

/// A device's name (marked when its figures are not validated) and its use of each of
/// [`RESOURCES`] in % of the device. Multipliers count the device's elements used (at
/// most all of them): those beyond the device are built in logic and counted in the
/// logic elements, so the bars and the fit verdict agree.
pub(super) fn device_shares(d: &DeviceUse) -> (String, [f64; 4]) {
    let pct = |used: u64, capacity: u64| {
        if capacity == 0 {
            0.0
        } else {
            used as f64 / capacity as f64 * 100.0
        }
    };
    let name = if d.validated {
        d.device.clone()
    } else {
        format!("{} (unvalidated)", d.device)
    };
    let shares = [
        pct(d.le, d.le_capacity),
        pct(d.mult.min(d.mult_capacity), d.mult_capacity),
        pct(d.mem_bits, d.mem_capacity),
        pct(u64::from(d.plls), u64::from(d.pll_capacity)),
    ];
    (name, shares)
}

/// The thesis's RMS bands (table 2) that end at a limit, with that limit, as the quality
/// chart marks them (the limits live in `analysis::Band`).
pub(super) fn rms_bands() -> impl Iterator<Item = (f64, &'static str)> {
    crate::results::Band::ALL
        .into_iter()
        .filter_map(|b| Some((b.upper_edge()?, b.name())))
}

/// One render as a roofline point: its variant, the kind of its code (which compute
/// roof holds it), arithmetic intensity (flop/byte) and attained GFLOP/s.
pub(super) struct RooflinePoint<'r> {
    pub variant: &'r VariantResult,
    pub code: crate::results::CodeKind,
    pub intensity: f64,
    pub gflops: f64,
}

/// Every render with a usable roofline point (finite positive intensity and GFLOP/s),
/// in run order.
pub(super) fn roofline_points(results: &Results) -> Vec<RooflinePoint<'_>> {
    results
        .scenes
        .iter()
        .flat_map(|s| &s.variants)
        .filter_map(|variant| {
            let e = variant.efficiency.as_ref()?;
            (finite_positive(e.arithmetic_intensity) && finite_positive(e.achieved_gflops))
                .then_some(RooflinePoint {
                    variant,
                    code: crate::results::CodeKind::of_variant(&variant.variant),
                    intensity: e.arithmetic_intensity,
                    gflops: e.achieved_gflops,
                })
        })
        .collect()
}

/// The machine's measured peaks, when the SIMD peak and the DRAM bandwidth are usable
/// (the scalar peak and the L1 bandwidth are drawn when they are there too).
pub(super) fn machine_peak(results: &Results) -> Option<&crate::results::MachinePeak> {
    results
        .peak
        .as_ref()
        .filter(|p| finite_positive(p.peak_gflops) && finite_positive(p.bandwidth_gbs))
}
