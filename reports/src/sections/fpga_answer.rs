//! The third answer, whether the FPGA would pay off: rtprof's fastest software on the
//! hardware's job as a line in the primitive count (least squares over the thesis's
//! test bench), set against eq. 49 for the thesis design and its what-ifs, giving the
//! primitive count up to which the pipeline is faster; and the thesis's own software
//! at its gains' ends beside rtprof's baseline.

use super::family_groups::FAMILY_GROUPS;
use crate::document::{Cell, Column, Table, Tone};
use crate::format;
use crate::results::{Results, SceneHardware, SoftwarePeer, VariantName};
use hwmodel::blocks::Pipeline;
use hwmodel::design::Design;
use hwmodel::device::{demand, fit, largest_units};
use hwmodel::frame_timing::{BreakEven, THESIS_CLOCK_HZ, THESIS_GAIN_ENDS, break_even};
use hwmodel::library::Library;

/// A software frame time that grows linearly with the primitives: `fixed + per_primitive
/// × n` seconds, fitted by least squares.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SoftwareLine {
    pub fixed: f64,
    pub per_primitive: f64,
    /// Scenes fitted.
    pub scenes: usize,
}

/// The least-squares line through `(n, seconds)`; `None` with fewer than two distinct
/// counts. A negative slope (noise over a flat cost) is fitted as flat: the mean.
pub fn fit_line(points: &[(f64, f64)]) -> Option<SoftwareLine> {
    let m = points.len() as f64;
    let mean_n = points.iter().map(|p| p.0).sum::<f64>() / m;
    let mean_t = points.iter().map(|p| p.1).sum::<f64>() / m;
    let sxx: f64 = points.iter().map(|p| (p.0 - mean_n).powi(2)).sum();
    if points.len() < 2 || sxx.is_nan() || sxx <= 0.0 {
        return None;
    }
    let sxy: f64 = points.iter().map(|p| (p.0 - mean_n) * (p.1 - mean_t)).sum();
    let slope = (sxy / sxx).max(0.0);
    Some(SoftwareLine {
        fixed: mean_t - slope * mean_n,
        per_primitive: slope,
        scenes: points.len(),
    })
}

/// One hardware design of the break-even table.
#[derive(Clone, Debug, PartialEq)]
pub struct DesignRow {
    pub label: String,
    pub device: String,
    pub units: u32,
    /// Whether it fits the device (at the test bench's largest scene and the frame).
    pub fits: bool,
    /// Seconds a primitive adds to the frame (eq. 49 over K).
    pub per_primitive: f64,
    /// The frame of the test bench's largest scene (eq. 49 with the fill).
    pub bench_frame: f64,
    pub one_core: BreakEven,
    pub all_cores: BreakEven,
}

/// The answer: the software's lines and the designs against them.
#[derive(Clone, Debug, PartialEq)]
pub struct FpgaAnswer {
    pub width: u32,
    pub height: u32,
    pub peer: VariantName,
    pub threads: u32,
    pub one_core: SoftwareLine,
    pub all_cores: SoftwareLine,
    pub designs: Vec<DesignRow>,
    /// The thesis's software at its gains' ends (scene, primitives, seconds) beside
    /// rtprof's baseline on one core on the same scene here, when it ran.
    pub thesis_software: Vec<(String, u64, f64, Option<f64>)>,
}

/// The thesis design, its K = 2, the most units that fit on the validated device for it
/// and for the three logic-saving what-ifs together, and the most on the largest
/// device of the library: each with its break-even against the software lines.
pub fn fpga_answer(r: &Results) -> Option<FpgaAnswer> {
    let bench: Vec<(&crate::results::SceneResult, &SceneHardware)> = r
        .scenes
        .iter()
        .filter(|s| FAMILY_GROUPS[0].1.contains(&s.family))
        .filter_map(|s| Some((s, s.hardware.as_ref()?)))
        .filter(|(_, h)| h.peer.is_some())
        .collect();
    let (first, first_hw) = bench.first()?;
    let (width, height) = (first.width, first.height);
    let bench: Vec<_> = bench
        .iter()
        .filter(|(s, _)| (s.width, s.height) == (width, height))
        .collect();
    let points = |pick: &dyn Fn(&SoftwarePeer) -> f64| -> Vec<(f64, f64)> {
        bench
            .iter()
            .filter_map(|(_, h)| Some((h.primitives as f64, pick(h.peer.as_ref()?))))
            .collect()
    };
    let one_core = fit_line(&points(&|p| p.one_thread.median))?;
    let all_cores = fit_line(&points(&|p| p.all_threads.median))?;
    let peer = first_hw.peer.as_ref()?;
    let family = Library::cyclone_iv_e();
    let validated = family.devices.iter().find(|d| d.validated)?;
    let largest = Library::embedded()
        .into_iter()
        .flat_map(|lib| {
            lib.devices
                .clone()
                .into_iter()
                .map(move |d| (lib.clone(), d))
        })
        .max_by_key(|(_, d)| d.le)?;
    let saving = Design {
        fast_sqrt: true,
        ortho: true,
        no_rsqrt_shading: true,
        ..Design::thesis()
    };
    // The fit counts memory for the test bench's largest scene at the frame (as the
    // hardware tables do: 7 primitives).
    let fit_n = hwmodel::optimizations::BENCH_PRIMITIVES;
    let most = |lib: &Library, device: &hwmodel::library::DeviceSpec, design: &Design| {
        largest_units(lib, device, design, fit_n, width, height).unwrap_or(1)
    };
    let candidates = [
        (
            "thesis".to_string(),
            family.clone(),
            validated.clone(),
            Design::thesis(),
            1,
        ),
        (
            "thesis, K = 2".to_string(),
            family.clone(),
            validated.clone(),
            Design::thesis(),
            2,
        ),
        (
            "thesis, most units that fit".to_string(),
            family.clone(),
            validated.clone(),
            Design::thesis(),
            most(&family, validated, &Design::thesis()),
        ),
        (
            "fast sqrt + ortho + sqrt-free shading, most units".to_string(),
            family.clone(),
            validated.clone(),
            saving,
            most(&family, validated, &saving),
        ),
        (
            "thesis on the largest device, most units".to_string(),
            largest.0.clone(),
            largest.1.clone(),
            Design::thesis(),
            most(&largest.0, &largest.1, &Design::thesis()),
        ),
    ];
    let designs = candidates
        .into_iter()
        .map(|(label, lib, device, design, units)| {
            let pipeline = Pipeline::build(&lib, &Design { units, ..design });
            let line = |l: &SoftwareLine| {
                break_even(
                    &pipeline,
                    width,
                    height,
                    THESIS_CLOCK_HZ,
                    l.fixed,
                    l.per_primitive,
                )
            };
            let fits = fit(&lib, &device, demand(&lib, &pipeline, fit_n, width, height)).fits;
            DesignRow {
                label,
                device: device.name.clone(),
                units,
                fits,
                per_primitive: 3.0 * f64::from(width) * f64::from(height)
                    / f64::from(units)
                    / THESIS_CLOCK_HZ,
                bench_frame: hwmodel::frame_timing::frame_timing(
                    &pipeline,
                    fit_n,
                    width,
                    height,
                    THESIS_CLOCK_HZ,
                )
                .seconds,
                one_core: line(&one_core),
                all_cores: line(&all_cores),
            }
        })
        .collect();
    let thesis_software = THESIS_GAIN_ENDS
        .iter()
        .map(|(scene, n, gain)| {
            let eq49 = 3.0 * 640.0 * 480.0 * *n as f64 / THESIS_CLOCK_HZ;
            let ours = r
                .scenes
                .iter()
                .find(|s| s.name == *scene && (s.width, s.height) == (640, 480))
                .and_then(|s| Some(s.hardware.as_ref()?.software_seconds.median));
            (scene.to_string(), *n, gain * eq49, ours)
        })
        .collect();
    Some(FpgaAnswer {
        width,
        height,
        peer: peer.variant.clone(),
        threads: peer.threads,
        one_core,
        all_cores,
        designs,
        thesis_software,
    })
}

/// "up to 6 primitives", "never (not even one primitive)", "for any count".
pub fn break_even_text(b: BreakEven) -> String {
    match b {
        BreakEven::Never => "never (not even one primitive)".to_string(),
        BreakEven::UpTo(n) => format!("up to {}", format::kind_count(n, "primitives")),
        BreakEven::Always => "for any count".to_string(),
    }
}

/// The break-even as a predicate: "is never faster", "is faster up to 6 primitives".
fn faster_text(b: BreakEven) -> String {
    match b {
        BreakEven::Never => "is never faster (not even with one primitive)".to_string(),
        b => format!("is faster {}", break_even_text(b)),
    }
}

/// Orders break-evens: never < up to n < always.
fn reach(b: BreakEven) -> u64 {
    match b {
        BreakEven::Never => 0,
        BreakEven::UpTo(n) => n,
        BreakEven::Always => u64::MAX,
    }
}

impl FpgaAnswer {
    /// The answer in a few sentences, from the figures.
    pub fn sentence(&self) -> String {
        let thesis = &self.designs[0];
        // The design that fits and reaches furthest on one core (the first of equals).
        let best = self
            .designs
            .iter()
            .filter(|d| d.fits)
            .rev()
            .max_by_key(|d| reach(d.one_core))
            .unwrap_or(thesis);
        let frame = format::size(self.width, self.height);
        let line = |l: &SoftwareLine| {
            format!(
                "{} + {} a primitive",
                format::seconds(l.fixed),
                format::seconds(l.per_primitive)
            )
        };
        // Equal verdicts are said once.
        let verdict = if thesis.one_core == thesis.all_cores {
            format!(
                "{} against one core or all cores",
                faster_text(thesis.one_core)
            )
        } else {
            format!(
                "{} against one core and {} against all cores",
                faster_text(thesis.one_core),
                faster_text(thesis.all_cores)
            )
        };
        let mut text = format!(
            "At 50 MHz the thesis's pipeline adds {} a primitive to a {frame} frame (eq. 49); rtprof's {} takes {} on one core here ({} on {}), fitted over {} of the thesis's test bench. So the pipeline {verdict}.",
            format::seconds(thesis.per_primitive),
            self.peer,
            line(&self.one_core),
            line(&self.all_cores),
            format::plural(self.threads as usize, "core"),
            format::plural(self.one_core.scenes, "scene"),
        );
        if reach(best.one_core) > reach(thesis.one_core) {
            text.push_str(&format!(
                " The best design below that fits ({}, K = {} on the {}) {} against one core.",
                best.label,
                best.units,
                best.device,
                faster_text(best.one_core)
            ));
        } else {
            text.push_str(" No design below that fits does better.");
        }
        let thesis_sw: Vec<String> = self
            .thesis_software
            .iter()
            .map(|(scene, n, theirs, ours)| {
                let ours = ours.map_or_else(String::new, |s| {
                    format!(
                        " against rtprof's baseline's {} on one core",
                        format::seconds(s)
                    )
                });
                format!(
                    "{} on {scene} ({}){ours}",
                    format::seconds(*theirs),
                    format::kind_count(*n, "primitives")
                )
            })
            .collect();
        text.push_str(&format!(
            " The thesis's 4.6-18× gains were against its own 2019 software, which took (from those gains and eq. 49) {}: the pipeline is the same, the software is what changed.",
            format::join_list(&thesis_sw)
        ));
        text
    }
}

pub(crate) fn break_even_table(a: &FpgaAnswer) -> Table {
    let mut t = Table::new(vec![
        Column::text("design"),
        Column::text("device"),
        Column::number("K"),
        Column::text("fits"),
        Column::number("per primitive").detail(format::size(a.width, a.height)),
        Column::number("frame").detail(format!(
            "{} primitives",
            hwmodel::optimizations::BENCH_PRIMITIVES
        )),
        Column::text("faster than one core"),
        Column::text(format!("faster than {} cores", a.threads)),
    ])
    .dense()
    .caption(format!(
        "The pipeline at 50 MHz against rtprof's {} (diffuse-only gray, as the hardware renders), by primitive count",
        a.peer
    ));
    let cell = |b: BreakEven| {
        let tone = match b {
            BreakEven::Never => Tone::Bad,
            BreakEven::UpTo(_) => Tone::Fair,
            BreakEven::Always => Tone::Good,
        };
        Cell::text(break_even_text(b)).tone(tone)
    };
    for d in &a.designs {
        t.rows.push(vec![
            Cell::text(&d.label),
            Cell::text(&d.device),
            Cell::count(u64::from(d.units)),
            if d.fits {
                Cell::text("yes").tone(Tone::Good)
            } else {
                Cell::text("no").tone(Tone::Bad)
            },
            Cell::number(format::seconds(d.per_primitive), d.per_primitive),
            Cell::number(format::seconds(d.bench_frame), d.bench_frame),
            cell(d.one_core),
            cell(d.all_cores),
        ]);
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;
    use testkit::sample::sample_results;

    #[test]
    fn the_break_even_is_a_hand_computation_from_eq_49_and_the_measured_lines() {
        let mut r = sample_results();
        // The peer measured at 0.1 s + 4 ms a primitive on one thread and 0.2 s + 20 ms
        // a primitive on all threads, at 640×480.
        for scene in &mut r.scenes {
            if let Some(h) = scene.hardware.as_mut() {
                let n = h.primitives as f64;
                let peer = h.peer.as_mut().unwrap();
                for (e, t) in [
                    (&mut peer.one_thread, 0.1 + 0.004 * n),
                    (&mut peer.all_threads, 0.2 + 0.02 * n),
                ] {
                    e.median = t;
                }
            }
        }
        let a = fpga_answer(&r).unwrap();
        assert!((a.one_core.fixed - 0.1).abs() < 1e-12, "{:?}", a.one_core);
        assert!((a.one_core.per_primitive - 0.004).abs() < 1e-12);
        assert_eq!((a.width, a.height), (640, 480));
        assert_eq!(a.peer.as_str(), "bvh+simd+packets");
        let thesis = &a.designs[0];
        assert_eq!((thesis.label.as_str(), thesis.units), ("thesis", 1));
        // Eq. 49: 0.018432 s a primitive; 0.018432 n + fill < 0.1 + 0.004 n while
        // n < (0.1 - fill) / 0.014432 ≈ 6.93: up to 6 primitives. Against 20 ms a
        // primitive (more than the pipeline's 18.4 ms) the pipeline always wins.
        assert!((thesis.per_primitive - 0.018432).abs() < 1e-15);
        assert_eq!(thesis.one_core, BreakEven::UpTo(6));
        assert_eq!(thesis.all_cores, BreakEven::Always);
        // K = 2: 9.216 ms a primitive; blocks of two won while
        // j (0.018432 - 0.008) < 0.1 - fill: j ≤ 9, up to 18 primitives.
        let k2 = &a.designs[1];
        assert_eq!(k2.units, 2);
        assert_eq!(k2.one_core, BreakEven::UpTo(18));
        let said = a.sentence();
        assert!(
            said.contains("the pipeline is faster up to 6 primitives against one core"),
            "{said}"
        );
        // K = 2 does not fit the EP4CE115 (the model's second intersection unit).
        assert!(!k2.fits);
        // The thesis's software: 18 × 18.4 ms on cylinder4, 4.6 × 129 ms on balls6.
        assert!((a.thesis_software[0].2 - 18.0 * 0.018432).abs() < 1e-12);
        assert!((a.thesis_software[1].2 - 4.6 * 7.0 * 0.018432).abs() < 1e-12);
    }

    #[test]
    fn a_line_fit_recovers_an_exact_line_and_flattens_a_falling_one() {
        let exact = fit_line(&[(1.0, 3.0), (2.0, 5.0), (4.0, 9.0)]).unwrap();
        assert!((exact.fixed - 1.0).abs() < 1e-12 && (exact.per_primitive - 2.0).abs() < 1e-12);
        let falling = fit_line(&[(1.0, 3.0), (2.0, 1.0)]).unwrap();
        assert_eq!((falling.fixed, falling.per_primitive), (2.0, 0.0));
        assert_eq!(fit_line(&[(1.0, 3.0), (1.0, 4.0)]), None);
    }
}
