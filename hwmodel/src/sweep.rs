//! The design space behind "would the FPGA pay off?": every design the model can cost,
//! on every device of the library, at every clock given, against the software's frame
//! time, so that the answer is the best design that fits and not one design point.
//!
//! Axes:
//! - **rate**: the minimum distance's compare ([`MinDistance`]): the thesis's float
//!   compare, a primitive every 3 cycles, or the integer compare, one a cycle;
//! - **logic**: the thesis's operators, or with its three logic-saving optimizations
//!   (fast square root, orthographic rays, shading without the inverse square root),
//!   which change the picture ([`SweepPoint::relies_on`]);
//! - **units** K: the most intersection units that fit the device within the routing
//!   headroom ([`largest_units_within_headroom`]), or one unit with its verdict when
//!   not even one does;
//! - **device**: every device of every embedded library (the thesis's, the larger ones,
//!   unvalidated families marked so);
//! - **clock**: the clocks the caller gives, each with where it comes from.
//!
//! For each: the fit (one verdict: [`fit_design`] at the frame the hardware would build,
//! 640×480 for VGA), the frame time and rate at the software's frame size, RAM blocks,
//! and the break-even primitive count against the software's line on one core and on
//! all cores ([`break_even`], ⌈n/K⌉ included), with the range the line's slope interval
//! gives.

use serde::Serialize;

use crate::blocks::Pipeline;
use crate::design::{Design, MinDistance};
use crate::device::{FitState, fit_design, largest_units_within_headroom};
use crate::frame_timing::{BreakEven, break_even, frame_timing};
use crate::library::Library;

/// A software frame time that grows linearly with the primitives, `fixed + per_primitive
/// × n` seconds, with the 95 % interval of its slope and the point the fit turns about
/// (the mean of the fitted counts and times: a line with another slope through the same
/// points passes there).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SoftwareLine {
    pub fixed_s: f64,
    pub per_primitive_s: f64,
    pub per_primitive_interval: [f64; 2],
    pub centroid: (f64, f64),
    /// The primitive counts the line was fitted over.
    pub fitted_range: [u64; 2],
}

impl SoftwareLine {
    /// The line through the centroid with `slope` instead (never below zero).
    fn with_slope(&self, slope: f64) -> (f64, f64) {
        let slope = slope.max(0.0);
        (self.centroid.1 - slope * self.centroid.0, slope)
    }
}

/// A clock to run designs at, with where the figure comes from.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Clock {
    pub hz: f64,
    pub source: String,
}

/// A break-even and the range the software line's slope interval gives it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct BreakEvenRange {
    pub central: BreakEven,
    /// With the software's slope at its interval's low end (the software's own frame
    /// grows least: the pipeline wins least far) and at its high end.
    pub low: BreakEven,
    pub high: BreakEven,
}

/// The logic-saving optimizations a design may carry.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Logic {
    /// The thesis's operators.
    Thesis,
    /// Fast square root, orthographic primary rays and shading without the inverse
    /// square root (thesis 8.3.1, 8.3.2, 8.3.4).
    Saving,
}

impl Logic {
    fn apply(self, design: Design) -> Design {
        match self {
            Logic::Thesis => design,
            Logic::Saving => Design {
                fast_sqrt: true,
                ortho: true,
                no_rsqrt_shading: true,
                ..design
            },
        }
    }
}

/// One design on one device at one clock.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SweepPoint {
    pub design: Design,
    pub logic: Logic,
    pub family: String,
    pub device: String,
    /// Both the family's figures and the device are the thesis's measured ones.
    pub validated: bool,
    pub clock: Clock,
    pub fit: FitState,
    /// Logic elements and RAM blocks used, as fractions of the device.
    pub le_share: f64,
    pub mem_blocks: u64,
    pub mem_block_capacity: u64,
    /// Seconds a primitive adds to a frame of the software's size (r·W·H / (K·f)).
    pub per_primitive_s: f64,
    /// The frame of the test bench's largest scene at the software's size, and frames
    /// per second.
    pub bench_frame_s: f64,
    pub bench_fps: f64,
    pub one_core: BreakEvenRange,
    pub all_cores: BreakEvenRange,
}

impl SweepPoint {
    /// The thesis's design at the thesis's clock on its own device.
    pub fn is_thesis(&self, thesis_clock_hz: f64) -> bool {
        self.design.is_thesis() && self.validated && self.clock.hz == thesis_clock_hz
    }

    /// The software variants whose picture this design's hardware shares (the cost in
    /// picture of what it relies on), by name.
    pub fn relies_on(&self) -> Vec<&'static str> {
        match self.logic {
            Logic::Thesis => Vec::new(),
            Logic::Saving => vec!["fast-sqrt", "ortho", "no-rsqrt-shading"],
        }
    }
}

/// What the sweep is run for.
#[derive(Clone, Debug, PartialEq)]
pub struct SweepInputs {
    /// The software's frame: times are compared at this size.
    pub frame: (u32, u32),
    /// The frame the hardware would build (its frame buffer): the fit is taken at this
    /// size, with `fit_primitives` in the scene memory.
    pub fit_frame: (u32, u32),
    pub fit_primitives: u64,
    pub one_core: SoftwareLine,
    pub all_cores: SoftwareLine,
    pub clocks: Vec<Clock>,
}

/// The break-even of `pipeline` at `clock_hz` against `line`, with its range.
pub fn break_even_range(
    pipeline: &Pipeline,
    (width, height): (u32, u32),
    clock_hz: f64,
    line: &SoftwareLine,
) -> BreakEvenRange {
    let at =
        |(fixed, slope): (f64, f64)| break_even(pipeline, width, height, clock_hz, fixed, slope);
    BreakEvenRange {
        central: at((line.fixed_s, line.per_primitive_s)),
        low: at(line.with_slope(line.per_primitive_interval[0])),
        high: at(line.with_slope(line.per_primitive_interval[1])),
    }
}

/// Every design of the space on every device of `libraries` at every clock of
/// `inputs`.
pub fn sweep(libraries: &[Library], inputs: &SweepInputs) -> Vec<SweepPoint> {
    let mut out = Vec::new();
    let (fit_w, fit_h) = inputs.fit_frame;
    let (width, height) = inputs.frame;
    for lib in libraries {
        for device in &lib.devices {
            for rate in [MinDistance::FloatCompare, MinDistance::IntegerCompare] {
                for logic in [Logic::Thesis, Logic::Saving] {
                    let base = logic.apply(Design {
                        min_distance: rate,
                        ..Design::thesis()
                    });
                    let units = largest_units_within_headroom(
                        lib,
                        device,
                        &base,
                        inputs.fit_primitives,
                        fit_w,
                        fit_h,
                    )
                    .unwrap_or(1);
                    let design = Design { units, ..base };
                    let pipeline = Pipeline::build(lib, &design);
                    let fit =
                        fit_design(lib, device, &pipeline, inputs.fit_primitives, fit_w, fit_h);
                    for clock in &inputs.clocks {
                        let bench =
                            frame_timing(&pipeline, inputs.fit_primitives, width, height, clock.hz);
                        out.push(SweepPoint {
                            design,
                            logic,
                            family: lib.family.clone(),
                            device: device.name.clone(),
                            validated: fit.validated,
                            clock: clock.clone(),
                            fit: fit.state,
                            le_share: fit.utilization.le,
                            mem_blocks: fit.mem_blocks,
                            mem_block_capacity: fit.mem_block_capacity,
                            per_primitive_s: f64::from(design.cycles_per_primitive())
                                * f64::from(width)
                                * f64::from(height)
                                / f64::from(units)
                                / clock.hz,
                            bench_frame_s: bench.seconds,
                            bench_fps: 1.0 / bench.seconds,
                            one_core: break_even_range(
                                &pipeline,
                                inputs.frame,
                                clock.hz,
                                &inputs.one_core,
                            ),
                            all_cores: break_even_range(
                                &pipeline,
                                inputs.frame,
                                clock.hz,
                                &inputs.all_cores,
                            ),
                        });
                    }
                }
            }
        }
    }
    out
}

/// How far a break-even reaches, for ordering designs: never < up to n < always.
pub fn reach(b: BreakEven) -> u64 {
    match b {
        BreakEven::Never => 0,
        BreakEven::UpTo(n) => n,
        BreakEven::Always => u64::MAX,
    }
}

/// The point that fits (within the headroom) and reaches furthest against one core, on
/// the central line; ties go to the first (the thesis's family and the lower clock come
/// first in [`sweep`]'s order). `None` when nothing fits.
pub fn best_that_fits(points: &[SweepPoint]) -> Option<&SweepPoint> {
    points
        .iter()
        .filter(|p| p.fit == FitState::Fits)
        .rev()
        .max_by_key(|p| (reach(p.one_core.central), reach(p.all_cores.central)))
}

/// The clock at which `pipeline` renders a `width`×`height` frame of `n` primitives in
/// the software's time on `line`: below it the software is faster.
pub fn clock_to_match(
    pipeline: &Pipeline,
    (width, height): (u32, u32),
    n: u64,
    line: &SoftwareLine,
) -> f64 {
    // Cycles do not depend on the clock.
    let cycles = frame_timing(pipeline, n, width, height, 1.0).cycles as f64;
    cycles / (line.fixed_s + line.per_primitive_s * n as f64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame_timing::THESIS_CLOCK_HZ;

    fn line(fixed: f64, slope: f64) -> SoftwareLine {
        SoftwareLine {
            fixed_s: fixed,
            per_primitive_s: slope,
            per_primitive_interval: [slope * 0.5, slope * 1.5],
            centroid: (4.0, fixed + 4.0 * slope),
            fitted_range: [1, 7],
        }
    }

    fn inputs(one: SoftwareLine, all: SoftwareLine) -> SweepInputs {
        SweepInputs {
            frame: (640, 480),
            fit_frame: (640, 480),
            fit_primitives: 7,
            one_core: one,
            all_cores: all,
            clocks: vec![
                Clock {
                    hz: THESIS_CLOCK_HZ,
                    source: "thesis".into(),
                },
                Clock {
                    hz: 100e6,
                    source: "assumed".into(),
                },
            ],
        }
    }

    #[test]
    fn eq_49_generalised_to_the_rate_the_units_and_the_clock() {
        // A software of 7.09 ms + 334 µs a primitive at 640×480. The thesis's design
        // (3 cycles a primitive, K = 1, 50 MHz) adds 18.432 ms a primitive: never faster.
        // One primitive a cycle at 50 MHz adds 6.144 ms: at n = 1, 6.144 ms + fill
        // against 7.424 ms, won; at n = 2, 12.288 ms against 7.758 ms, lost: up to 1.
        // At 100 MHz with K = 2, a block of two primitives costs 640·480 / 100e6 =
        // 3.072 ms and the software 0.668 ms: block j is won while
        // j (3.072 − 0.668) ms < 7.09 ms − fill, j ≤ 2: up to 4 primitives.
        let lib = Library::cyclone_iv_e();
        let sw = line(0.00709, 0.000334);
        let thesis = Pipeline::build(&lib, &Design::thesis());
        assert_eq!(
            break_even_range(&thesis, (640, 480), THESIS_CLOCK_HZ, &sw).central,
            BreakEven::Never
        );
        let fast = Pipeline::build(
            &lib,
            &Design {
                min_distance: MinDistance::IntegerCompare,
                ..Design::thesis()
            },
        );
        let fill = (fast.fill_cycles() - 1) as f64 / THESIS_CLOCK_HZ;
        assert!(0.006144 + fill < 0.00709 + 0.000334);
        assert!(2.0 * 0.006144 + fill > 0.00709 + 2.0 * 0.000334);
        assert_eq!(
            break_even_range(&fast, (640, 480), THESIS_CLOCK_HZ, &sw).central,
            BreakEven::UpTo(1)
        );
        let fast2 = Pipeline::build(
            &lib,
            &Design {
                min_distance: MinDistance::IntegerCompare,
                units: 2,
                ..Design::thesis()
            },
        );
        let fill2 = (fast2.fill_cycles() - 1) as f64 / 100e6;
        let per_block = 640.0 * 480.0 / 100e6 - 2.0 * 0.000334;
        assert!(2.0 * per_block < 0.00709 - fill2 && 3.0 * per_block > 0.00709 - fill2);
        assert_eq!(
            break_even_range(&fast2, (640, 480), 100e6, &sw).central,
            BreakEven::UpTo(4)
        );
    }

    #[test]
    fn the_slope_interval_moves_the_break_even_the_right_way() {
        let lib = Library::cyclone_iv_e();
        let p = Pipeline::build(&lib, &Design::thesis());
        // 0.1 s + 4 ms a primitive: up to 6 (frame_timing's test); a steeper software
        // loses sooner to the pipeline, so the high end reaches at least as far.
        let sw = line(0.1, 0.004);
        let r = break_even_range(&p, (640, 480), THESIS_CLOCK_HZ, &sw);
        assert_eq!(r.central, BreakEven::UpTo(6));
        assert!(reach(r.low) <= reach(r.central) && reach(r.central) <= reach(r.high));
    }

    #[test]
    fn the_sweep_covers_every_device_rate_logic_and_clock_with_one_verdict() {
        let libs = Library::embedded();
        let devices: usize = libs.iter().map(|l| l.devices.len()).sum();
        let points = sweep(&libs, &inputs(line(0.0074, 0.000334), line(0.004, 0.0002)));
        assert_eq!(points.len(), devices * 2 * 2 * 2);
        for p in &points {
            // The verdict is the device fit's, at K as chosen.
            let lib = libs.iter().find(|l| l.family == p.family).unwrap();
            let device = lib.devices.iter().find(|d| d.name == p.device).unwrap();
            let pipeline = Pipeline::build(lib, &p.design);
            assert_eq!(fit_design(lib, device, &pipeline, 7, 640, 480).state, p.fit);
            // Per primitive: r W H / (K f), by hand.
            let r = f64::from(p.design.cycles_per_primitive());
            let expect = r * 640.0 * 480.0 / f64::from(p.design.units) / p.clock.hz;
            assert!((p.per_primitive_s / expect - 1.0).abs() < 1e-12);
            assert!((p.bench_fps * p.bench_frame_s - 1.0).abs() < 1e-12);
        }
        // The thesis's point is there, at one unit, 3 cycles and 50 MHz.
        let thesis: Vec<_> = points
            .iter()
            .filter(|p| p.is_thesis(THESIS_CLOCK_HZ))
            .collect();
        assert_eq!(thesis.len(), 1, "{thesis:?}");
        assert_eq!(thesis[0].design.units, 1);
    }

    #[test]
    fn the_clock_to_match_is_the_frame_cycles_over_the_software_time() {
        let lib = Library::cyclone_iv_e();
        let p = Pipeline::build(&lib, &Design::thesis());
        let sw = line(0.0074, 0.000334);
        // n = 1: (640·480·3 + fill) cycles in 7.734 ms.
        let cycles = (640 * 480 * 3 + p.fill_cycles() - 3) as f64;
        let f = clock_to_match(&p, (640, 480), 1, &sw);
        assert!((f - cycles / 0.007734).abs() < 1e-3, "{f}");
        // At that clock the pipeline's frame equals the software's.
        let t = frame_timing(&p, 1, 640, 480, f).seconds;
        assert!((t - 0.007734).abs() < 1e-12);
    }
}
