//! Frame timing of the pipeline (thesis eq. 49).
//!
//! The screen iterator issues one pixel every 3·⌈n/K⌉ cycles: each intersection unit
//! holds a ray while its ⌈n/K⌉ primitives stream past, and the minimum-distance block
//! needs every result held for 3 cycles. A frame is W·H issues plus the pipeline fill
//! (the last pixel's trip through primary ray, intersection, minimum distance, the
//! comparator tree and shading). With K = 1 at 640×480 and 50 MHz the issues alone are
//! 640·480·3·n / 50e6 = 0.018432·n s, the thesis's eq. 49; the fill adds a few hundred
//! cycles (µs). An empty scene still paces at 3 cycles per pixel (the minimum-distance
//! hold).

use serde::Serialize;

use crate::blocks::Pipeline;

/// Cycles between two pixels entering the pipeline.
pub fn cycles_per_pixel(primitives: u64, units: u32) -> u64 {
    3 * primitives.max(1).div_ceil(u64::from(units.max(1)))
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
    let per_pixel = cycles_per_pixel(primitives, units);
    let fill = pipeline.fill_cycles() + per_pixel;
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::design::Design;
    use crate::library::Library;

    #[test]
    fn pacing_is_three_cycles_per_primitive_per_unit() {
        assert_eq!(cycles_per_pixel(7, 1), 21);
        assert_eq!(cycles_per_pixel(7, 2), 12); // ⌈7/2⌉ = 4
        assert_eq!(cycles_per_pixel(7, 7), 3);
        assert_eq!(cycles_per_pixel(7, 100), 3);
        assert_eq!(cycles_per_pixel(0, 1), 3);
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
}
