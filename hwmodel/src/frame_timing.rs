//! Frame timing of the pipeline (thesis eq. 49).
//!
//! The screen iterator issues one pixel every 3·⌈n/K⌉ cycles: each intersection unit
//! holds a ray while its ⌈n/K⌉ primitives stream past, and the minimum-distance block
//! needs every result held for 3 cycles. With K = 1 at 640×480 and 50 MHz the issues
//! alone are 640·480·3·n / 50e6 = 0.018432·n s, the thesis's eq. 49.
//!
//! A frame's cycles are counted from the first pixel's issue (cycle 0) to the cycle the
//! last pixel's gray level is written to the frame buffer, which is what the generated
//! RTL's simulation measures: the last pixel is issued at (W·H − 1)·p (p = 3c cycles
//! per pixel, c = ⌈n/K⌉ primitives per unit), its ray is ready L_ray later, its last
//! primitive enters the intersection unit 3(c − 1) after that, and its result then
//! crosses intersection, minimum distance, the comparator tree and shading. So
//! `cycles = W·H·p + fill` with `fill = L_ray + L_int + L_min + L_tree + L_shade − 3`
//! (a few hundred cycles, µs). An empty scene still paces at 3 cycles per pixel (one
//! slot that hits nothing: the minimum-distance hold).

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
    // The last primitive slot of a pixel starts 3 cycles before the next issue.
    let fill = pipeline.fill_cycles() - 3;
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
