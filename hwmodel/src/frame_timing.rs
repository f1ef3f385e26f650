//! Frame timing of the pipeline (thesis eq. 49).
//!
//! The screen iterator issues one pixel every r·⌈n/K⌉ cycles: each intersection unit
//! holds a ray while its ⌈n/K⌉ primitives stream past, and the minimum-distance block
//! needs every result held for r cycles (r = 3 with the thesis's floating-point compare,
//! 1 with the integer compare: [`crate::design::MinDistance`]). With r = 3, K = 1 at
//! 640×480 and 50 MHz the issues alone are 640·480·3·n / 50e6 = 0.018432·n s, the
//! thesis's eq. 49.
//!
//! A frame's cycles are counted from the first pixel's issue (cycle 0) to the cycle the
//! last pixel's gray level is written to the frame buffer, which is what the generated
//! RTL's simulation measures: the last pixel is issued at (W·H − 1)·p (p = r·c cycles
//! per pixel, c = ⌈n/K⌉ primitives per unit), its ray is ready L_ray later, its last
//! primitive enters the intersection unit r(c − 1) after that, and its result then
//! crosses intersection, minimum distance, the comparator tree and shading. So
//! `cycles = W·H·p + fill` with `fill = L_ray + L_int + L_min + L_tree + L_shade − r`
//! (a few hundred cycles, µs). An empty scene still paces at r cycles per pixel (one
//! slot that hits nothing: the minimum-distance hold).

use serde::Serialize;

use crate::blocks::Pipeline;

/// Cycles between two pixels entering the pipeline, with `rate` cycles per primitive
/// per unit ([`crate::design::Design::cycles_per_primitive`]).
pub fn cycles_per_pixel(primitives: u64, units: u32, rate: u32) -> u64 {
    u64::from(rate.max(1)) * primitives.max(1).div_ceil(u64::from(units.max(1)))
}

/// Timing of one frame.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FrameTiming {
    pub primitives: u64,
    pub units: u32,
    pub clock_hz: f64,
    pub width: u32,
    pub height: u32,
    pub cycles_per_pixel: u64,
    pub fill_cycles: u64,
    pub cycles: u64,
    pub seconds: f64,
}

/// Frame time of `pipeline` for a scene of `primitives` at `width`×`height`.
pub fn frame_timing(
    pipeline: &Pipeline,
    primitives: u64,
    width: u32,
    height: u32,
    clock_hz: f64,
) -> FrameTiming {
    let units = pipeline.design.units;
    let rate = pipeline.design.cycles_per_primitive();
    let per_pixel = cycles_per_pixel(primitives, units, rate);
    // The last primitive slot of a pixel starts `rate` cycles before the next issue.
    let fill = pipeline.fill_cycles() - u64::from(rate);
    let cycles = u64::from(width) * u64::from(height) * per_pixel + fill;
    FrameTiming {
        primitives,
        units,
        clock_hz,
        width,
        height,
        cycles_per_pixel: per_pixel,
        fill_cycles: fill,
        cycles,
        seconds: cycles as f64 / clock_hz,
    }
}

/// The thesis's clock, Hz (50 MHz).
pub const THESIS_CLOCK_HZ: f64 = 50e6;

/// One end of the hardware-over-software gains the thesis measured (ch. 7, fig. 50).
/// Its software's frame time is the gain times eq. 49's.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ThesisGain {
    /// The thesis's scene name (its test bench's, not rtprof's: the names differ).
    pub scene: &'static str,
    pub primitives: u64,
    /// What the scene holds.
    pub content: &'static str,
    pub gain: f64,
    /// rtprof's built-in scene with the same content (kind and count).
    pub same_content: &'static str,
}

/// The gains at the thesis's ends: 18 on its cylinder4 (one cylinder) and 4.6 on its
/// balls6 (seven spheres). rtprof's scenes of the same names hold 4 and 6 primitives;
/// the same content is its cylinder1 and balls7.
pub const THESIS_GAIN_ENDS: [ThesisGain; 2] = [
    ThesisGain {
        scene: "cylinder4",
        primitives: 1,
        content: "1 cylinder",
        gain: 18.0,
        same_content: "cylinder1",
    },
    ThesisGain {
        scene: "balls6",
        primitives: 7,
        content: "7 spheres",
        gain: 4.6,
        same_content: "balls7",
    },
];

/// Up to which primitive count the pipeline renders a frame faster than a software
/// whose frame time grows linearly with the primitives.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum BreakEven {
    /// Not even for one primitive.
    Never,
    /// For every count from 1 up to and including this one.
    UpTo(u64),
    /// For every count: the software grows as fast or faster per primitive.
    Always,
}

/// Where `pipeline` at `clock_hz` stops beating a software that takes `fixed_s +
/// per_primitive_s × n` seconds a `width`×`height` frame.
///
/// The pipeline's frame is `(W·H·r·⌈n/K⌉ + fill) / f` ([`frame_timing`], r cycles per
/// primitive): constant over each block of K counts, so within a block it is furthest
/// ahead at the block's last count, n = jK. Block j is won when
/// `j·(rWH/f − b·K) < a − fill/f`; with a positive bracket the won blocks are
/// j < (a − fill/f) / (rWH/f − bK), and the last count won is K times the last such j.
pub fn break_even(
    pipeline: &Pipeline,
    width: u32,
    height: u32,
    clock_hz: f64,
    fixed_s: f64,
    per_primitive_s: f64,
) -> BreakEven {
    let k = f64::from(pipeline.design.units.max(1));
    let rate = pipeline.design.cycles_per_primitive();
    let block_s = f64::from(rate) * f64::from(width) * f64::from(height) / clock_hz;
    let fill_s = (pipeline.fill_cycles() - u64::from(rate)) as f64 / clock_hz;
    let slope = block_s - per_primitive_s * k;
    let headroom = fixed_s - fill_s;
    if slope <= 0.0 {
        // The software loses ground every block: once ahead, the pipeline stays ahead.
        return if slope < 0.0 || headroom > 0.0 {
            BreakEven::Always
        } else {
            BreakEven::Never
        };
    }
    let blocks = (headroom / slope).ceil() - 1.0;
    // NaN (a NaN input) reads as never.
    if blocks.is_nan() || blocks < 1.0 {
        return BreakEven::Never;
    }
    BreakEven::UpTo((blocks * k) as u64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::design::Design;
    use crate::library::Library;

    #[test]
    fn the_break_even_is_eq_49_against_the_software_line() {
        let lib = Library::cyclone_iv_e();
        let thesis = Pipeline::build(&lib, &Design::thesis());
        let fill = (thesis.fill_cycles() - 3) as f64 / 50e6;
        // Eq. 49: 0.018432 s a primitive at 640×480. A software of 0.1 s + 0.004 s a
        // primitive is beaten while 0.018432 n + fill < 0.1 + 0.004 n, i.e. up to
        // n < (0.1 - fill) / 0.014432 = 6.93 - ε: 6 primitives.
        assert!(((0.1 - fill) / 0.014432 - 6.929).abs() < 1e-3);
        assert_eq!(
            break_even(&thesis, 640, 480, 50e6, 0.1, 0.004),
            BreakEven::UpTo(6)
        );
        // A fixed cost below one primitive's frame: never.
        assert_eq!(
            break_even(&thesis, 640, 480, 50e6, 0.01, 0.004),
            BreakEven::Never
        );
        // Software slower per primitive than the pipeline: every count.
        assert_eq!(
            break_even(&thesis, 640, 480, 50e6, 0.01, 0.02),
            BreakEven::Always
        );
        // K = 4: blocks of four counts cost 0.018432 s each; against 0.1 s + 0.001 s a
        // primitive, block j is won while j (0.018432 - 0.004) < 0.1 - fill: j ≤ 6,
        // so up to 24 primitives.
        let four = Pipeline::build(
            &lib,
            &Design {
                units: 4,
                ..Design::thesis()
            },
        );
        let fill4 = (four.fill_cycles() - 3) as f64 / 50e6;
        assert!(((0.1 - fill4) / 0.014432) > 6.0 && ((0.1 - fill4) / 0.014432) < 7.0);
        assert_eq!(
            break_even(&four, 640, 480, 50e6, 0.1, 0.001),
            BreakEven::UpTo(24)
        );
    }

    #[test]
    fn pacing_is_the_rate_per_primitive_per_unit() {
        assert_eq!(cycles_per_pixel(7, 1, 3), 21);
        assert_eq!(cycles_per_pixel(7, 2, 3), 12); // ⌈7/2⌉ = 4
        assert_eq!(cycles_per_pixel(7, 7, 3), 3);
        assert_eq!(cycles_per_pixel(7, 100, 3), 3);
        assert_eq!(cycles_per_pixel(0, 1, 3), 3);
        assert_eq!(cycles_per_pixel(7, 1, 1), 7);
        assert_eq!(cycles_per_pixel(7, 2, 1), 4);
        assert_eq!(cycles_per_pixel(0, 1, 1), 1);
    }

    #[test]
    fn equation_49_holds_within_half_a_percent_for_one_to_seven_primitives() {
        let lib = Library::cyclone_iv_e();
        let p = Pipeline::build(&lib, &Design::thesis());
        for n in 1..=7u64 {
            let t = frame_timing(&p, n, 640, 480, 50e6);
            let eq49 = 640.0 * 480.0 * 3.0 * n as f64 / 50e6;
            assert!(
                (t.seconds / eq49 - 1.0).abs() < 0.005,
                "n={n}: {}",
                t.seconds
            );
            assert!(t.seconds > eq49, "the fill adds time");
        }
    }

    #[test]
    fn a_frame_ends_when_the_last_pixel_leaves_shading() {
        // Hand count, 2×1 pixels, n = 2, K = 1: p = 6. Pixel 1 is issued at 6, its ray
        // is ready at 6 + L_ray, its second primitive enters at 6 + L_ray + 3 and leaves
        // the pipeline L_int + L_min + L_shade later.
        let lib = Library::cyclone_iv_e();
        let p = Pipeline::build(&lib, &Design::thesis());
        let t = frame_timing(&p, 2, 2, 1, 50e6);
        let last_write = 6
            + p.primary_ray.latency()
            + 3
            + p.intersection.latency()
            + p.min_distance.latency()
            + p.shading.latency();
        assert_eq!(t.cycles, u64::from(last_write));
    }
}
