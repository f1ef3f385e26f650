//! The third answer, whether the FPGA would pay off, as a hardware engineer would decide
//! it: rtprof's fastest software on the hardware's job as a line in the primitive count
//! (least squares over the thesis's test bench, with the slope's interval), against the
//! whole design space the model can cost ([`hwmodel::sweep`]: the minimum distance's
//! rate, the logic-saving optimizations, the units within the routing headroom, every
//! device, the thesis's clock and the clock of rtprof's RTL). The answer is the best
//! design that fits, beside the thesis's; what each side's time includes; the
//! optimizations' cost in picture; and the thesis's own software paired by content.

use super::family_groups::FAMILY_GROUPS;
use crate::document::{Block, Builder, Cell, Column, Section, Table, Tone};
use crate::format;
use crate::results::{Results, RtlClock, SoftwarePeer, Upload, VariantName};
use analysis::linear_fit::LineFit;
use hwmodel::design::MinDistance;
use hwmodel::device::FitState;
use hwmodel::frame_timing::{BreakEven, THESIS_CLOCK_HZ, THESIS_GAIN_ENDS};
use hwmodel::library::Library;
use hwmodel::optimizations::BENCH_PRIMITIVES;
use hwmodel::sweep::{
    BreakEvenRange, Clock, Logic, SoftwareLine, SweepInputs, SweepPoint, best_that_fits, reach,
    sweep,
};

/// The frame the hardware builds (its frame buffer, VGA): designs are fitted at it
/// whatever frame the software was timed at.
pub const BUILT_FRAME: (u32, u32) = (640, 480);

/// The thesis's own software at one end of its gains, beside rtprof's on the scene of
/// the same content.
#[derive(Clone, Debug, PartialEq)]
pub struct ThesisPair {
    pub thesis_scene: &'static str,
    pub content: &'static str,
    /// The thesis's software frame time (its gain times eq. 49), 640×480.
    pub thesis_seconds: f64,
    /// rtprof's scene with the same content, and its baseline's time on it here at
    /// 640×480: on the hardware's job (diffuse-only gray) and in full (Whitted colour,
    /// shadows), when the run timed them.
    pub ours_scene: &'static str,
    pub ours_diffuse: Option<f64>,
    pub ours_full: Option<f64>,
}

/// The answer: the software's lines, the design space and the best of it.
#[derive(Clone, Debug, PartialEq)]
pub struct FpgaAnswer {
    /// The software's frame (the hardware's timed at it too).
    pub width: u32,
    pub height: u32,
    pub peer: VariantName,
    pub threads: u32,
    pub cpu: String,
    pub one_core: LineFit,
    pub all_cores: LineFit,
    pub points: Vec<SweepPoint>,
    pub rtl_clock: Option<RtlClock>,
    pub upload: Option<Upload>,
    /// Worst RMS against baseline over the run's scenes of each optimization a design
    /// may rely on (`None`: the variant did not run).
    pub picture_cost: Vec<(&'static str, Option<f64>)>,
    pub thesis_software: Vec<ThesisPair>,
}

/// A fitted line as the sweep reads it.
fn software_line(fit: &LineFit) -> SoftwareLine {
    let n = |x: f64| x.round().max(0.0) as u64;
    SoftwareLine {
        fixed_s: fit.intercept,
        per_primitive_s: fit.slope,
        per_primitive_interval: fit.slope_interval,
        centroid: (
            (fit.x_range[0] + fit.x_range[1]) / 2.0,
            fit.at((fit.x_range[0] + fit.x_range[1]) / 2.0),
        ),
        fitted_range: [n(fit.x_range[0]), n(fit.x_range[1])],
    }
}

/// The clocks of the sweep: the thesis's board and rtprof's RTL.
fn clocks(rtl: Option<&RtlClock>) -> Vec<Clock> {
    let mut out = vec![Clock {
        hz: THESIS_CLOCK_HZ,
        source: "the thesis's board".to_string(),
    }];
    if let Some(rtl) = rtl.filter(|c| (c.mhz * 1e6 - THESIS_CLOCK_HZ).abs() > 1.0) {
        out.push(Clock {
            hz: rtl.mhz * 1e6,
            source: rtl.source.clone(),
        });
    }
    out
}

/// The worst RMS against baseline of `variant` over the run's scenes.
pub(crate) fn worst_rms(r: &Results, variant: &str) -> Option<f64> {
    r.scenes
        .iter()
        .flat_map(|s| s.variants.iter())
        .filter(|v| v.variant.as_str() == variant)
        .filter_map(|v| v.quality.as_ref().map(|q| q.rms))
        .reduce(f64::max)
}

/// The answer from a run: `None` when the run timed the peer on the hardware's job on
/// fewer than two primitive counts.
pub fn fpga_answer(r: &Results) -> Option<FpgaAnswer> {
    let bench: Vec<(&crate::results::SceneResult, &SoftwarePeer, u64)> = r
        .scenes
        .iter()
        .filter(|s| FAMILY_GROUPS[0].1.contains(&s.family))
        .filter_map(|s| {
            let h = s.hardware.as_ref()?;
            Some((s, h.peer.as_ref()?, h.primitives))
        })
        .collect();
    let (first, peer, _) = bench.first()?;
    let (width, height) = (first.width, first.height);
    let points = |pick: &dyn Fn(&SoftwarePeer) -> f64| -> Vec<(f64, f64)> {
        bench
            .iter()
            .filter(|(s, _, _)| (s.width, s.height) == (width, height))
            .map(|(_, p, n)| (*n as f64, pick(p)))
            .collect()
    };
    let one_core = LineFit::of(&points(&|p| p.one_thread.median))?;
    let all_cores = LineFit::of(&points(&|p| p.all_threads.median))?;
    let hardware = r.hardware.as_ref();
    let rtl_clock = hardware.and_then(|h| h.rtl_clock.clone());
    let inputs = SweepInputs {
        frame: (width, height),
        fit_frame: BUILT_FRAME,
        fit_primitives: BENCH_PRIMITIVES,
        one_core: software_line(&one_core),
        all_cores: software_line(&all_cores),
        clocks: clocks(rtl_clock.as_ref()),
    };
    let thesis_software = THESIS_GAIN_ENDS
        .iter()
        .map(|g| {
            let eq49 = 3.0 * 640.0 * 480.0 * g.primitives as f64 / THESIS_CLOCK_HZ;
            let scene = r
                .scenes
                .iter()
                .find(|s| s.name == g.same_content && (s.width, s.height) == (640, 480));
            let ours_diffuse =
                scene.and_then(|s| Some(s.hardware.as_ref()?.software_seconds.median));
            let ours_full = scene.and_then(|s| {
                s.variants
                    .iter()
                    .find(|v| v.variant.is_reference())
                    .map(|v| v.time.median)
            });
            ThesisPair {
                thesis_scene: g.scene,
                content: g.content,
                thesis_seconds: g.gain * eq49,
                ours_scene: g.same_content,
                ours_diffuse,
                ours_full,
            }
        })
        .collect();
    Some(FpgaAnswer {
        width,
        height,
        peer: peer.variant.clone(),
        threads: peer.threads,
        cpu: r.machine.cpu_model.clone(),
        one_core,
        all_cores,
        points: sweep(&Library::embedded(), &inputs),
        rtl_clock,
        upload: hardware.and_then(|h| h.upload.clone()),
        picture_cost: ["fast-sqrt", "ortho", "no-rsqrt-shading"]
            .into_iter()
            .map(|v| (v, worst_rms(r, v)))
            .collect(),
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

/// A break-even with the range the software line's interval gives: "up to 4 primitives
/// (2–6)", or the central text alone when the range is one value.
pub fn break_even_range_text(b: &BreakEvenRange) -> String {
    let short = |b: BreakEven| match b {
        BreakEven::Never => "0".to_string(),
        BreakEven::UpTo(n) => format::count(n),
        BreakEven::Always => "any".to_string(),
    };
    if b.low == b.high {
        break_even_text(b.central)
    } else {
        format!(
            "{} ({}–{})",
            break_even_text(b.central),
            short(b.low),
            short(b.high)
        )
    }
}

/// The break-even as a predicate: "is never faster", "is faster up to 6 primitives".
fn faster_text(b: BreakEven) -> String {
    match b {
        BreakEven::Never => "is never faster (not even with one primitive)".to_string(),
        b => format!("is faster {}", break_even_text(b)),
    }
}

/// A design in words: "3 cycles a primitive, K = 1", "1 cycle a primitive (integer
/// compare) + fast sqrt, ortho, sqrt-free shading, K = 5".
pub fn design_text(p: &SweepPoint) -> String {
    let rate = match p.design.min_distance {
        MinDistance::FloatCompare => "3 cycles a primitive",
        MinDistance::IntegerCompare => "1 cycle a primitive (integer compare)",
    };
    let logic = match p.logic {
        Logic::Thesis => "",
        Logic::Saving => " + fast sqrt, ortho, sqrt-free shading",
    };
    format!("{rate}{logic}, K = {}", p.design.units)
}

/// The clock of a point and where it comes from, short: "50 MHz (thesis)".
fn clock_text(p: &SweepPoint) -> String {
    let tag = if p.clock.hz == THESIS_CLOCK_HZ {
        "thesis"
    } else {
        "rtprof's RTL"
    };
    format!("{} ({tag})", format::megahertz(p.clock.hz))
}

/// The one wording of a fit verdict, with what it rests on.
pub fn fit_text(p: &SweepPoint) -> String {
    let blocks = format!(
        "{} of {} RAM blocks",
        format::count(p.mem_blocks),
        format::count(p.mem_block_capacity)
    );
    match p.fit {
        FitState::Fits => format!("fits ({}, {blocks})", logic_share(p)),
        FitState::FitsOnPaper => format!(
            "fits on paper only ({}, {blocks}: above the routing headroom)",
            logic_share(p)
        ),
        FitState::DoesNotFit => format!("does not fit ({}, {blocks})", logic_share(p)),
    }
}

fn logic_share(p: &SweepPoint) -> String {
    format!("{} of the logic", format::percent(p.le_share * 100.0, 0))
}

impl FpgaAnswer {
    /// The thesis's design at the thesis's clock on its device.
    pub fn thesis(&self) -> Option<&SweepPoint> {
        self.points.iter().find(|p| p.is_thesis(THESIS_CLOCK_HZ))
    }

    /// The design that fits within the headroom and reaches furthest against one core.
    pub fn best(&self) -> Option<&SweepPoint> {
        best_that_fits(&self.points)
    }

    /// The optimizations a design relies on, with their worst RMS: "fast-sqrt RMS 138.7,
    /// ortho RMS 94.8, no-rsqrt-shading not run".
    pub fn picture_cost_text(&self, p: &SweepPoint) -> String {
        let relied = p.relies_on();
        if relied.is_empty() {
            return "none".to_string();
        }
        relied
            .iter()
            .map(|v| {
                match self
                    .picture_cost
                    .iter()
                    .find(|(name, _)| name == v)
                    .and_then(|(_, rms)| *rms)
                {
                    Some(rms) => format!("{v} worst RMS {}", format::fixed(rms, 1)),
                    None => format!("{v} (not run here)"),
                }
            })
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// The answer in a few sentences, from the figures: the verdicts first (the thesis's
    /// design, the best design that fits), then what was swept, against what, and what
    /// the times include.
    pub fn sentence(&self) -> String {
        let cores = format::plural(self.threads as usize, "core");
        let against = |p: &SweepPoint| {
            if p.one_core.central == p.all_cores.central && p.one_core.low == p.all_cores.low {
                format!(
                    "{}{} against one core or {cores}",
                    faster_text(p.one_core.central),
                    range_words(&p.one_core)
                )
            } else {
                format!(
                    "{}{} against one core and {}{} against {cores}",
                    faster_text(p.one_core.central),
                    range_words(&p.one_core),
                    faster_text(p.all_cores.central),
                    range_words(&p.all_cores)
                )
            }
        };
        let mut text = String::new();
        let thesis = self.thesis();
        if let Some(t) = thesis {
            text += &format!(
                "Against rtprof's {} on this machine's {}, the thesis's design ({}, 50 MHz, {}) {}; it {}{}.",
                self.peer,
                self.cpu,
                design_text(t),
                t.device,
                against(t),
                fit_text(t),
                if t.fit == FitState::FitsOnPaper && t.validated {
                    ", though the thesis built it and ran it"
                } else {
                    ""
                }
            );
        }
        match self.best() {
            Some(b) => {
                let changes =
                    thesis.is_some_and(|t| reach(b.one_core.central) > reach(t.one_core.central));
                let cost = match b.logic {
                    Logic::Thesis => String::new(),
                    Logic::Saving => {
                        format!(", at a cost in picture ({})", self.picture_cost_text(b))
                    }
                };
                text += &format!(
                    " The best design that fits, {} on the {}{} at {}, takes {} a frame of 7 primitives ({}) and {}{cost}{}",
                    design_text(b),
                    b.device,
                    if b.validated {
                        ""
                    } else {
                        " (a library the thesis did not validate)"
                    },
                    clock_text(b),
                    format::seconds(b.bench_frame_s),
                    format::fps(b.bench_fps),
                    against(b),
                    if changes {
                        ": a faster design changes the verdict, for that many primitives only."
                    } else {
                        ": no design of the sweep changes the thesis's verdict."
                    }
                );
            }
            None => text += " No design fits within the routing headroom on any device.",
        }
        text += &format!(
            " Beyond the {} the software line was fitted on, the comparison is an extrapolation: the pipeline tests every primitive for every pixel (its frame grows linearly with n) where rtprof's BVH grows far slower, so at larger scenes the software wins anyway.",
            format::kind_count(self.one_core.x_range[1].round() as u64, "primitives")
        );
        let devices = distinct(self.points.iter().map(|p| p.device.clone()));
        let clocks = distinct(self.points.iter().map(clock_text));
        let line = |l: &LineFit| {
            format!(
                "{} + {} a primitive [{} – {}]",
                format::seconds(l.intercept),
                format::seconds(l.slope),
                format::seconds(l.slope_interval[0].max(0.0)),
                format::seconds(l.slope_interval[1])
            )
        };
        text += &format!(
            " Swept: the minimum distance at 3 cycles a primitive (the thesis's float compare) or 1 (an integer compare of the non-negative distances, built in rtprof's RTL and simulated equal to the emulator on the thesis's 21 test-bench scenes), with or without the three logic-saving optimizations, the most intersection units within the routing headroom, on the {} at {}; the software: {} on one core and {} on {cores}, fitted over {} of 1–7 primitives at {}.",
            format::join_list(&devices),
            format::join_list(&clocks),
            line(&self.one_core),
            line(&self.all_cores),
            format::plural(self.one_core.points, "scene"),
            format::size(self.width, self.height),
        );
        text += &format!(" {}", self.scope_sentence());
        text
    }

    /// What each side's time includes, in one sentence.
    pub fn scope_sentence(&self) -> String {
        let upload = self.upload.as_ref().map_or_else(String::new, |u| {
            format!(
                " (uploading {} takes {} over the serial line at {} baud)",
                format::kind_count(u.primitives, "primitives"),
                format::seconds(u.seconds),
                format::count(u64::from(u.baud))
            )
        });
        format!(
            "Times: the hardware's is the frame's render alone, from eq. 49 generalised (cycles ÷ clock), without the scene upload{upload} or reading the image back; the software's is {}'s trace on one thread and on {}, diffuse-only gray as the hardware renders, without parsing the scene or building the BVH.",
            self.peer,
            format::plural(self.threads as usize, "thread")
        )
    }
}

/// The distinct items of `items`, in their first order.
fn distinct(items: impl Iterator<Item = String>) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    for item in items {
        if !out.contains(&item) {
            out.push(item);
        }
    }
    out
}

/// " (2 to 6 primitives with the software line's interval)", or nothing when both ends
/// of the interval give the same.
fn range_words(b: &BreakEvenRange) -> String {
    let end = |b: BreakEven| match b {
        BreakEven::Never => "none".to_string(),
        BreakEven::UpTo(n) => format::count(n),
        BreakEven::Always => "any number of".to_string(),
    };
    if b.low == b.high {
        String::new()
    } else {
        format!(
            " ({} to {} primitives with the software line's interval)",
            end(b.low),
            end(b.high)
        )
    }
}

/// The first page's table: the thesis's design and, for each rate and logic, the design
/// that fits and reaches furthest.
pub(crate) fn break_even_table(a: &FpgaAnswer) -> Table {
    let mut rows: Vec<&SweepPoint> = a.thesis().into_iter().collect();
    for rate in [MinDistance::FloatCompare, MinDistance::IntegerCompare] {
        for logic in [Logic::Thesis, Logic::Saving] {
            let kind: Vec<SweepPoint> = a
                .points
                .iter()
                .filter(|p| p.design.min_distance == rate && p.logic == logic)
                .cloned()
                .collect();
            if let Some(best) = best_that_fits(&kind)
                && let Some(p) = a.points.iter().find(|p| *p == best)
                && !rows.contains(&p)
            {
                rows.push(p);
            }
        }
    }
    sweep_table(a, &rows).caption(format!(
        "The thesis's design and the best design of each kind that fits, against rtprof's {} (diffuse-only gray, as the hardware renders); frames at {}, fitted at {} (the VGA frame buffer); the break-even's range is the software line's slope interval",
        a.peer,
        format::size(a.width, a.height),
        format::size(BUILT_FRAME.0, BUILT_FRAME.1)
    ))
}

/// A table of sweep points.
pub(crate) fn sweep_table(a: &FpgaAnswer, rows: &[&SweepPoint]) -> Table {
    let mut t = Table::new(vec![
        Column::text("design"),
        Column::text("device"),
        Column::text("clock"),
        Column::text("fits"),
        Column::number("RAM blocks"),
        Column::number("frame").detail(format!("{BENCH_PRIMITIVES} primitives")),
        Column::number("rate"),
        Column::text("faster than one core"),
        Column::text(format!("faster than {} cores", a.threads)),
        Column::text("picture cost"),
    ])
    .dense();
    let cell = |b: &BreakEvenRange| {
        let tone = match b.central {
            BreakEven::Never => Tone::Bad,
            BreakEven::UpTo(_) => Tone::Fair,
            BreakEven::Always => Tone::Good,
        };
        Cell::text(break_even_range_text(b)).tone(tone)
    };
    for p in rows {
        let mut device = Cell::text(&p.device);
        if !p.validated {
            device = device.detail("(unvalidated)");
        }
        let fits = match p.fit {
            FitState::Fits => Cell::text("yes").tone(Tone::Good),
            FitState::FitsOnPaper => Cell::text("on paper only").tone(Tone::Warning),
            FitState::DoesNotFit => Cell::text("no").tone(Tone::Bad),
        };
        t.rows.push(vec![
            Cell::text(design_text(p)),
            device,
            Cell::text(clock_text(p)),
            fits,
            Cell::number(
                format::usage(p.mem_blocks, p.mem_block_capacity),
                p.mem_blocks as f64,
            ),
            Cell::number(format::seconds(p.bench_frame_s), p.bench_frame_s),
            Cell::number(format::fps(p.bench_fps), p.bench_fps),
            cell(&p.one_core),
            cell(&p.all_cores),
            Cell::text(a.picture_cost_text(p)),
        ]);
    }
    t
}

/// The thesis's own software paired with rtprof's by content, and how far apart they
/// are: the part the workload explains (rtprof's full render against its diffuse-only
/// one, both measured here) and the rest (the CPU, the implementation and what the
/// thesis timed, which the thesis does not let us separate).
pub fn thesis_software_sentence(a: &FpgaAnswer) -> Option<String> {
    if a.thesis_software.is_empty() {
        return None;
    }
    let theirs: Vec<String> = a
        .thesis_software
        .iter()
        .map(|p| {
            format!(
                "{} on its {} ({})",
                format::seconds(p.thesis_seconds),
                p.thesis_scene,
                p.content
            )
        })
        .collect();
    let mut text = format!(
        "The thesis's 4.6–18× gains were against its own software, which took (from those gains and eq. 49, 640×480) {}.",
        format::join_list(&theirs)
    );
    for p in &a.thesis_software {
        text += &match (p.ours_diffuse, p.ours_full) {
            (Some(d), Some(f)) => format!(
                " rtprof's baseline on {} (the same content) takes {} on the hardware's job and {} in full colour with shadows here: of the {} gap the workload explains {}, and {} is left to the CPU (the thesis's 2013 i5-4570 against this {}), the implementation and what the thesis timed.",
                p.ours_scene,
                format::seconds(d),
                format::seconds(f),
                format::speedup(p.thesis_seconds / d),
                format::speedup(f / d),
                format::speedup(p.thesis_seconds / f),
                a.cpu
            ),
            _ => format!(
                " rtprof's scene of the same content as the thesis's {} is its {}, not run at 640×480 here.",
                p.thesis_scene, p.ours_scene
            ),
        };
    }
    text += " The thesis does not say whether its times include parsing the scene or writing the image, nor how it shaded (a Whitted colour render is the likeliest), so those shares stay unknown.";
    Some(text)
}

/// The hardware chapter's part of the answer: every point of the sweep, and the
/// thesis's own software paired by content.
pub fn design_space(b: &mut Builder) -> Section {
    let mut s = b.section(
        "design-space",
        Some("8.3.3 (several intersection units), eq. 49, ch. 7 (the gains of 4.6 to 18)"),
    );
    let Some(a) = fpga_answer(b.results()) else {
        return s.empty(
            "No software line to set the designs against: the run timed rtprof's peer on the hardware's job on fewer than two primitive counts.",
        );
    };
    s.text(format!(
        "Each design at each clock on each device of the model's library: the minimum distance's rate, the logic-saving optimizations, and the most intersection units that fit within the routing headroom (one unit, with its verdict, where not even one does). Fitted at {} (the VGA frame buffer) with {} in the scene memory; frames and break-evens at {}, against rtprof's {} ({}). Devices marked unvalidated carry figures the thesis did not measure.",
        format::size(BUILT_FRAME.0, BUILT_FRAME.1),
        format::kind_count(BENCH_PRIMITIVES, "primitives"),
        format::size(a.width, a.height),
        a.peer,
        a.scope_sentence()
    ));
    if let Some(rtl) = &a.rtl_clock {
        s.text(format!(
            "The second clock, {}: {}.",
            format::megahertz(rtl.mhz * 1e6),
            rtl.source
        ));
    }
    let rows: Vec<&SweepPoint> = a.points.iter().collect();
    s.blocks.push(Block::Table(sweep_table(&a, &rows).sortable().caption(
        "The design space: every design, device and clock, with its fit, RAM blocks, frame, rate and break-even against one core and all cores",
    )));
    if let Some(text) = thesis_software_sentence(&a) {
        s.text(text);
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use testkit::sample::sample_results;

    #[test]
    fn a_break_even_range_reads_as_words_at_both_ends() {
        let range = |low, high| BreakEvenRange {
            central: BreakEven::UpTo(14),
            low,
            high,
        };
        assert_eq!(
            range_words(&range(BreakEven::UpTo(7), BreakEven::Always)),
            " (7 to any number of primitives with the software line's interval)"
        );
        assert_eq!(
            range_words(&range(BreakEven::Never, BreakEven::UpTo(56))),
            " (none to 56 primitives with the software line's interval)"
        );
        assert_eq!(
            range_words(&range(BreakEven::UpTo(3), BreakEven::UpTo(3))),
            ""
        );
    }

    /// The sample run with the peer at `fixed + slope n` on one thread and
    /// `fixed2 + slope2 n` on all.
    fn with_peer(fixed: f64, slope: f64, fixed2: f64, slope2: f64) -> Results {
        let mut r = sample_results();
        for scene in &mut r.scenes {
            if let Some(h) = scene.hardware.as_mut() {
                let n = h.primitives as f64;
                let peer = h.peer.as_mut().unwrap();
                peer.one_thread.median = fixed + slope * n;
                peer.all_threads.median = fixed2 + slope2 * n;
            }
        }
        r
    }

    #[test]
    fn the_lines_are_fitted_and_every_point_is_eq_49_generalised() {
        let r = with_peer(0.1, 0.004, 0.2, 0.02);
        let a = fpga_answer(&r).unwrap();
        assert!(
            (a.one_core.intercept - 0.1).abs() < 1e-12,
            "{:?}",
            a.one_core
        );
        assert!((a.one_core.slope - 0.004).abs() < 1e-12);
        assert_eq!((a.width, a.height), (640, 480));
        assert_eq!(a.peer.as_str(), "bvh+simd+packets");
        let thesis = a.thesis().unwrap();
        assert_eq!(thesis.design.units, 1);
        // Eq. 49: 0.018432 s a primitive; against 0.1 s + 4 ms a primitive the pipeline
        // wins while 0.018432 n + fill < 0.1 + 0.004 n, n ≤ 6 (frame_timing's test);
        // against 20 ms a primitive on all cores, always.
        assert!((thesis.per_primitive_s - 0.018432).abs() < 1e-15);
        assert_eq!(thesis.one_core.central, BreakEven::UpTo(6));
        assert_eq!(thesis.all_cores.central, BreakEven::Always);
        // Every point: r W H / (K f) a primitive, by hand.
        for p in &a.points {
            let r = f64::from(p.design.cycles_per_primitive());
            let expect = r * 640.0 * 480.0 / f64::from(p.design.units) / p.clock.hz;
            assert!((p.per_primitive_s / expect - 1.0).abs() < 1e-12);
        }
        // The sample's RTL clock, 1000/19 MHz, is the second clock.
        assert!(
            a.points
                .iter()
                .any(|p| (p.clock.hz - 1e9 / 19.0).abs() < 1.0)
        );
        let said = a.sentence();
        assert!(
            said.contains("is faster up to 6 primitives against one core and is faster for any count against 2 cores"),
            "{said}"
        );
    }

    #[test]
    fn the_best_design_that_fits_is_named_and_a_changed_verdict_said() {
        // The line: 7.09 ms + 334 µs a primitive. The thesis's design never wins;
        // one primitive a cycle does, for a few primitives.
        let r = with_peer(0.00709, 0.000334, 0.004, 0.0002);
        let a = fpga_answer(&r).unwrap();
        let thesis = a.thesis().unwrap();
        assert_eq!(thesis.one_core.central, BreakEven::Never);
        let best = a.best().unwrap();
        assert_eq!(best.fit, FitState::Fits);
        assert!(reach(best.one_core.central) > 0, "{best:?}");
        assert_eq!(best.design.min_distance, MinDistance::IntegerCompare);
        // No point that fits reaches further.
        assert!(
            a.points
                .iter()
                .filter(|p| p.fit == FitState::Fits)
                .all(|p| reach(p.one_core.central) <= reach(best.one_core.central))
        );
        let said = a.sentence();
        assert!(
            said.contains("The best design that fits, 1 cycle a primitive (integer compare)"),
            "{said}"
        );
        assert!(said.contains("changes the verdict"), "{said}");
        assert!(said.contains("extrapolation"), "{said}");
        // The scope: the upload of 7 primitives, 356 bytes at 115,200 baud, 30.9 ms.
        assert!(said.contains("30.9 ms over the serial line"), "{said}");
    }

    #[test]
    fn one_verdict_everywhere_the_first_page_table_agrees_with_the_points() {
        let r = with_peer(0.00709, 0.000334, 0.004, 0.0002);
        let a = fpga_answer(&r).unwrap();
        let t = break_even_table(&a);
        // The thesis's row first, with its verdict as the fit gives it.
        let thesis = a.thesis().unwrap();
        let label = match thesis.fit {
            FitState::Fits => "yes",
            FitState::FitsOnPaper => "on paper only",
            FitState::DoesNotFit => "no",
        };
        let text = crate::text::table(&t);
        let first_row = text.lines().nth(3).unwrap_or_default();
        assert!(first_row.contains(label), "{first_row}");
        assert!(fit_text(thesis).starts_with(match thesis.fit {
            FitState::Fits => "fits (",
            FitState::FitsOnPaper => "fits on paper only",
            FitState::DoesNotFit => "does not fit",
        }));
    }

    #[test]
    fn the_thesis_s_software_is_paired_by_content() {
        let r = sample_results();
        let a = fpga_answer(&r).unwrap();
        let pairs: Vec<_> = a
            .thesis_software
            .iter()
            .map(|p| (p.thesis_scene, p.content, p.ours_scene))
            .collect();
        assert_eq!(
            pairs,
            [
                ("cylinder4", "1 cylinder", "cylinder1"),
                ("balls6", "7 spheres", "balls7")
            ]
        );
        // 18 × 18.4 ms and 4.6 × 7 × 18.4 ms.
        assert!((a.thesis_software[0].thesis_seconds - 18.0 * 0.018432).abs() < 1e-12);
        assert!((a.thesis_software[1].thesis_seconds - 4.6 * 7.0 * 0.018432).abs() < 1e-12);
    }
}
