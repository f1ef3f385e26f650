//! What the web page (`rtprof serve`) shows of a run, with every number already
//! written by [`crate::format`]: the page's script only places these strings, so the
//! page and the report cannot write one figure two ways. Each value that the report
//! also shows is built as the report builds its cell (a speed-up as
//! [`format::ratio_estimate`], a time as [`format::estimate`], a count as
//! [`format::count`]).

use serde::Serialize;

use crate::format;
use crate::results::{
    Profile, ProfileResult, Quality, Results, SceneHardware, SceneResult, VariantResult,
};
use crate::sections::access;
use analysis::Band;

/// A run as the page shows it.
#[derive(Clone, Debug, Serialize)]
pub struct RunValues {
    pub scenes: Vec<SceneValues>,
    pub profile: Option<ProfileValues>,
    pub failures: Vec<FailureValues>,
    /// "Failures (2)".
    pub failures_title: String,
    /// "Scene (9 in this run)".
    pub scene_picker: String,
}

/// Something that failed, placed ("balls3 / bvh").
#[derive(Clone, Debug, Serialize)]
pub struct FailureValues {
    pub place: String,
    pub message: String,
}

/// An image-quality band, named and explained as the thesis's table 2 does.
#[derive(Clone, Debug, Serialize)]
pub struct BandValues {
    /// Its key in results.json (`visually_identical`), for the page's colour.
    pub key: Band,
    pub name: &'static str,
    /// "RMS band: visually identical (0 ≤ RMS < 15; thesis table 2)".
    pub title: String,
}

impl BandValues {
    pub fn of(band: Band) -> Self {
        let all = Band::ALL;
        let at = all.iter().position(|b| *b == band).unwrap_or(0);
        let low = at
            .checked_sub(1)
            .and_then(|i| all[i].upper_edge())
            .unwrap_or(0.0);
        let range = match band.upper_edge() {
            Some(high) => format!("{} ≤ RMS < {}", format::trimmed(low), format::trimmed(high)),
            None => format!("RMS ≥ {}", format::trimmed(low)),
        };
        BandValues {
            key: band,
            name: band.name(),
            title: format!("RMS band: {} ({range}; thesis table 2)", band.name()),
        }
    }
}

/// One scene of the run.
#[derive(Clone, Debug, Serialize)]
pub struct SceneValues {
    pub name: String,
    /// Pixels, for laying the images out (not shown as text).
    pub width: u32,
    pub height: u32,
    /// "balls3 (160×120, 91 primitives)", for a scene picker.
    pub option: String,
    /// "160×120 pixels · 91 primitives (1 polygon, 90 spheres) · family test".
    pub summary: String,
    pub variants: Vec<VariantValues>,
    pub counts: CountTable,
    pub pixel_maps: Vec<PixelMapSet>,
    pub hardware: Option<HardwareValues>,
}

/// One variant's picture and figures on a scene.
#[derive(Clone, Debug, Serialize)]
pub struct VariantValues {
    pub variant: String,
    pub reference: bool,
    pub image: Option<String>,
    pub heat_map: Option<String>,
    /// The median time as the report's cell writes it: "12.3 ms".
    pub median: String,
    /// Its interval: "[12.0 – 13.1]" (empty when unknown).
    pub interval: String,
    /// The speed-up over baseline as the report's matrix writes it ("2.01×"); `None`
    /// for the reference and where it is unknown.
    pub speedup: Option<String>,
    /// "95 % interval [1.98 – 2.05]".
    pub speedup_title: Option<String>,
    /// Whether the variant ran faster than baseline (for the page's colour).
    pub faster: bool,
    /// "faster", "within noise", "slower".
    pub verdict: Option<&'static str>,
    pub quality: Option<QualityValues>,
    /// An outside tracer that drew another picture: why its time is no comparison
    /// (the page shows this instead of the speed-up).
    pub not_comparable: Option<&'static str>,
    /// An outside tracer's time: what it covers ("the whole process", …).
    pub time_covers: Option<String>,
}

/// A picture's difference from baseline's.
#[derive(Clone, Debug, Serialize)]
pub struct QualityValues {
    pub band: BandValues,
    /// "RMS 0.00".
    pub rms: String,
    /// "max |Δ| 3 · SSIM 0.9999 · PSNR 45.1 dB", or "identical".
    pub detail: String,
}

/// The exact counts of every variant, baseline's column first.
#[derive(Clone, Debug, Serialize)]
pub struct CountTable {
    pub variants: Vec<String>,
    pub rows: Vec<CountRow>,
}

#[derive(Clone, Debug, Serialize)]
pub struct CountRow {
    pub key: String,
    pub cells: Vec<CountCell>,
}

/// How a count compares with baseline's, for the page's colour.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum CountTone {
    /// Baseline's own column, or the same count.
    Same,
    /// Fewer than baseline.
    Fewer,
    /// More than baseline.
    More,
    /// Work baseline does not do at all (a BVH's node visits): more of it is the
    /// point, not a cost, so it is not coloured as one.
    Own,
}

#[derive(Clone, Debug, Serialize)]
pub struct CountCell {
    pub text: String,
    pub tone: CountTone,
    /// "52.3 % of baseline (1,234)".
    pub title: Option<String>,
}

/// One variant's per-pixel maps.
#[derive(Clone, Debug, Serialize)]
pub struct PixelMapSet {
    pub variant: String,
    /// " 160 × 120 samples".
    pub detail: String,
    pub directory: String,
    pub maps: Vec<PixelMapValues>,
}

#[derive(Clone, Debug, Serialize)]
pub struct PixelMapValues {
    pub key: String,
    pub description: String,
    pub unit: String,
    pub png: String,
    /// "min 0 · mean 1.23 · max 9".
    pub stats: String,
}

/// The FPGA model on a scene.
#[derive(Clone, Debug, Serialize)]
pub struct HardwareValues {
    /// Label and value, in order.
    pub rows: Vec<[String; 2]>,
    pub fits: bool,
    pub emulator_band: BandValues,
    /// "RMS 3.21".
    pub emulator_rms: String,
    pub emulator_image: Option<String>,
    pub software_image: Option<String>,
}

/// The profile of the run's heaviest scene.
#[derive(Clone, Debug, Serialize)]
pub struct ProfileValues {
    /// "balls3, 160×120".
    pub detail: String,
    pub flames: Vec<FlameValues>,
    /// "Flat profile of baseline".
    pub flat_title: String,
    /// " top 10 of 42 by self time".
    pub flat_detail: String,
    pub flat: Vec<FlatValues>,
    /// Speedscope files (relative to results.json), with their variant.
    pub speedscope: Vec<[String; 2]>,
}

#[derive(Clone, Debug, Serialize)]
pub struct FlameValues {
    pub svg: String,
    pub caption: String,
}

#[derive(Clone, Debug, Serialize)]
pub struct FlatValues {
    pub name: String,
    pub percent: String,
    pub self_seconds: String,
    pub calls: String,
    pub noise: bool,
}

/// Rows of a flat profile the page lists.
const FLAT_ROWS: usize = 10;

/// The page's values of `r`.
pub fn run_values(r: &Results) -> RunValues {
    RunValues {
        scenes: r.scenes.iter().map(|s| scene_values(r, s)).collect(),
        profile: r.profile.as_ref().map(|p| profile_values(r, p)),
        failures: r
            .failures
            .iter()
            .map(|f| FailureValues {
                place: f.place(),
                message: f.message.clone(),
            })
            .collect(),
        failures_title: format!("Failures ({})", format::count(r.failures.len() as u64)),
        scene_picker: format!(
            "Scene ({} in this run)",
            format::count(r.scenes.len() as u64)
        ),
    }
}

/// "91 primitives", "1 primitive".
pub fn primitives(n: u64) -> String {
    format::kind_count(n, "primitives")
}

fn scene_values(r: &Results, s: &SceneResult) -> SceneValues {
    let kinds: Vec<String> = s
        .primitive_counts
        .iter()
        .filter(|(_, n)| **n > 0)
        .map(|(kind, n)| format::kind_count(*n, kind))
        .collect();
    let kinds = match kinds.is_empty() {
        true => String::new(),
        false => format!(" ({})", kinds.join(", ")),
    };
    let base = access::reference(r, s);
    SceneValues {
        name: s.name.clone(),
        width: s.width,
        height: s.height,
        option: format!(
            "{} ({}, {})",
            s.name,
            format::size(s.width, s.height),
            primitives(s.primitives)
        ),
        summary: format!(
            "{} pixels · {}{kinds} · family {}",
            format::size(s.width, s.height),
            primitives(s.primitives),
            s.family.name()
        ),
        variants: s.variants.iter().map(variant_values).collect(),
        counts: count_table(s, base),
        pixel_maps: s
            .pixel_maps
            .iter()
            .map(|set| PixelMapSet {
                variant: set.variant.to_string(),
                detail: format!(" {} samples", format::size(set.columns, set.rows)),
                directory: set.directory.clone(),
                maps: set
                    .maps
                    .iter()
                    .map(|m| PixelMapValues {
                        key: m.key.clone(),
                        description: m.description.clone(),
                        unit: m.unit.clone(),
                        png: m.png.clone(),
                        stats: format!(
                            "min {} · mean {} · max {}",
                            format::count(m.min),
                            format::quantity(m.mean),
                            format::count(m.max)
                        ),
                    })
                    .collect(),
            })
            .collect(),
        hardware: s.hardware.as_ref().map(hardware_values),
    }
}

pub(crate) fn variant_values(v: &VariantResult) -> VariantValues {
    let time = format::estimate(v.time.median, v.time.low, v.time.high);
    let reference = v.variant.is_reference();
    let speedup = v.speedup.filter(|_| !reference).map(|x| {
        let [low, high] = v.speedup_interval.unwrap_or([f64::NAN, f64::NAN]);
        format::ratio_estimate(x, low, high)
    });
    VariantValues {
        variant: v.variant.to_string(),
        reference,
        image: v.image.clone(),
        heat_map: v.heat_map.clone(),
        median: time.median,
        interval: time.interval,
        speedup_title: speedup
            .as_ref()
            .filter(|s| !s.interval.is_empty())
            .map(|s| format!("95 % interval {}", s.interval)),
        speedup: speedup.map(|s| s.median),
        faster: v.speedup.is_some_and(|x| x >= 1.0),
        verdict: v.verdict.map(|x| x.label()),
        quality: v.quality.as_ref().map(quality_values),
        not_comparable: crate::sections::outside_tracers::not_comparable(v),
        time_covers: v.outside.as_ref().map(|o| o.time_covers.clone()),
    }
}

fn quality_values(q: &Quality) -> QualityValues {
    let mut detail = vec![
        format!("max |Δ| {}", format::count(u64::from(q.max_abs_diff))),
        format!("SSIM {}", format::fixed(q.ssim, 4)),
    ];
    match q.psnr {
        Some(p) => detail.push(format!("PSNR {} dB", format::fixed(p, 1))),
        None if q.rms == 0.0 => detail.push("identical".to_string()),
        None => {}
    }
    QualityValues {
        band: BandValues::of(q.band),
        rms: format!("RMS {}", format::fixed(q.rms, 2)),
        detail: detail.join(" · "),
    }
}

fn count_table(s: &SceneResult, base: Option<&VariantResult>) -> CountTable {
    let keys: std::collections::BTreeSet<&String> =
        s.variants.iter().flat_map(|v| v.counts.keys()).collect();
    let rows = keys
        .into_iter()
        .map(|key| CountRow {
            key: key.clone(),
            cells: s
                .variants
                .iter()
                .map(|v| count_cell(v, base, key))
                .collect(),
        })
        .collect();
    CountTable {
        variants: s.variants.iter().map(|v| v.variant.to_string()).collect(),
        rows,
    }
}

fn count_cell(v: &VariantResult, base: Option<&VariantResult>, key: &str) -> CountCell {
    let Some(n) = v.counts.get(key).copied() else {
        return CountCell {
            text: format::DASH.to_string(),
            tone: CountTone::Same,
            title: None,
        };
    };
    let text = format::count(n);
    let reference = base
        .filter(|b| !std::ptr::eq(*b, v))
        .map(|b| b.counts.get(key).copied().unwrap_or(0));
    let (tone, title) = match reference {
        None => (CountTone::Same, None),
        Some(r) if r == n => (CountTone::Same, None),
        Some(0) => (
            CountTone::Own,
            Some("work baseline does not do (baseline: 0)".to_string()),
        ),
        Some(r) => (
            if n < r {
                CountTone::Fewer
            } else {
                CountTone::More
            },
            Some(format!(
                "{} of baseline ({})",
                format::percent(n as f64 / r as f64 * 100.0, 1),
                format::count(r)
            )),
        ),
    };
    CountCell { text, tone, title }
}

fn hardware_values(hw: &SceneHardware) -> HardwareValues {
    let rows = vec![
        ["Cycles".to_string(), format::count(hw.cycles)],
        ["Primitives".to_string(), format::count(hw.primitives)],
        [
            "Time on the FPGA model".to_string(),
            format::seconds(hw.seconds),
        ],
        [
            "Speed-up vs software".to_string(),
            format::speedup(hw.speedup),
        ],
        [
            "Software time (diffuse only)".to_string(),
            format::estimate(
                hw.software_seconds.median,
                hw.software_seconds.low,
                hw.software_seconds.high,
            )
            .line(),
        ],
    ];
    HardwareValues {
        rows,
        fits: hw.fits,
        emulator_band: BandValues::of(hw.emulator_band),
        emulator_rms: format!("RMS {}", format::fixed(hw.emulator_rms, 2)),
        emulator_image: hw.emulator_image.clone(),
        software_image: hw.software_image.clone(),
    }
}

/// What a profiled variant is, said as the report's summary says it: "the fastest
/// variant" only when it is the scene's fastest (the least median time).
fn profiled_as(r: &Results, p: &ProfileResult, best: &Profile) -> String {
    let scene = r.scenes.iter().find(|s| s.name == p.scene);
    let fastest = scene.and_then(access::fastest);
    let ran = scene.and_then(|s| s.variants.iter().find(|v| v.variant == best.variant));
    let speed = ran
        .and_then(|v| v.speedup)
        .map(|x| format!(", {} as fast as baseline", format::speedup(x)))
        .unwrap_or_default();
    match fastest {
        Some(f) if f.variant == best.variant => format!("the fastest variant{speed}"),
        Some(f) => format!(
            "profiled beside baseline{speed}; the fastest variant on {} was {}",
            p.scene, f.variant
        ),
        None => format!("profiled beside baseline{speed}"),
    }
}

fn profile_values(r: &Results, p: &ProfileResult) -> ProfileValues {
    let base = &p.baseline;
    let samples = |x: &Profile| format::kind_count(x.samples, "samples");
    let mut flames = vec![FlameValues {
        svg: base.flame_svg.clone(),
        caption: format!("Flamegraph of {} ({})", base.variant, samples(base)),
    }];
    if let Some(best) = &p.best {
        flames.push(FlameValues {
            svg: best.flame_svg.clone(),
            caption: format!(
                "Flamegraph of {}, {} ({})",
                best.variant,
                profiled_as(r, p, best),
                samples(best)
            ),
        });
        let pair = format!("{} → {}", base.variant, best.variant);
        if let Some(svg) = &p.diff_flame_svg {
            flames.push(FlameValues {
                svg: svg.clone(),
                caption: format!("Differential flamegraph {pair}: what grew"),
            });
        }
        if let Some(svg) = &p.diff_shrunk_flame_svg {
            flames.push(FlameValues {
                svg: svg.clone(),
                caption: format!("Differential flamegraph {pair}: what shrank"),
            });
        }
    }
    let mut flat: Vec<_> = base.flat.iter().collect();
    flat.sort_by(|a, b| b.percent.total_cmp(&a.percent));
    let speedscope = std::iter::once(base)
        .chain(p.best.iter())
        .flat_map(|x| {
            x.exports
                .iter()
                .filter(|e| e.ends_with(".json") && e.contains("speedscope"))
                .map(|e| [x.variant.to_string(), e.clone()])
        })
        .collect();
    ProfileValues {
        detail: format!("{}, {}", p.scene, format::size(p.width, p.height)),
        flames,
        flat_title: format!("Flat profile of {}", base.variant),
        flat_detail: format!(
            " top {} of {} by self time",
            format::count(flat.len().min(FLAT_ROWS) as u64),
            format::count(flat.len() as u64)
        ),
        flat: flat
            .into_iter()
            .take(FLAT_ROWS)
            .map(|row| FlatValues {
                name: row.name.clone(),
                percent: format::percent(row.percent, 1),
                self_seconds: format::seconds(row.self_seconds),
                calls: row
                    .calls
                    .map_or_else(|| format::DASH.to_string(), format::count),
                noise: row.noise,
            })
            .collect(),
        speedscope,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bands_carry_their_thesis_range() {
        let b = BandValues::of(Band::VisuallyIdentical);
        assert_eq!(
            b.title,
            "RMS band: visually identical (0 ≤ RMS < 15; thesis table 2)"
        );
        let last = *Band::ALL.last().unwrap();
        assert!(BandValues::of(last).title.contains("RMS ≥ "));
    }

    #[test]
    fn primitives_are_counted_in_the_singular_for_one() {
        assert_eq!(primitives(1), "1 primitive");
        assert_eq!(primitives(2_400), "2,400 primitives");
    }
}
