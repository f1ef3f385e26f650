//! The thesis's optimizations (ch. 8.3) costed in hardware: each what-if design beside
//! the thesis's, in the pipeline's own currency (fill cycles, cycles per pixel, frame
//! time) and the device's (logic elements, multipliers, memory bits, fit). The thesis
//! costed them only as ideas; the software variants of the same names cost them in CPU
//! time.

use serde::Serialize;

use crate::blocks::Pipeline;
use crate::design::Design;
use crate::device::{FitState, demand, fit_design, largest_units};
use crate::frame_timing::frame_timing;
use crate::library::{DeviceSpec, Library, Resources};

/// The thesis's test bench's largest scene (balls7, cylinder7, both7): the primitive
/// count designs are fitted and costed at, as the thesis's tables are.
pub const BENCH_PRIMITIVES: u64 = 7;

/// One design, costed.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct OptimizationCost {
    /// What changes from the thesis's design, in words.
    pub label: String,
    pub design: Design,
    /// Cycles from a pixel's issue to its gray level, less the issue slot (the fill).
    pub fill_cycles: u64,
    pub cycles_per_pixel: u64,
    pub frame_cycles: u64,
    pub frame_seconds: f64,
    /// What the design uses on the device, after the multiplier rule (LEs include the
    /// multipliers built in logic).
    pub used: Resources,
    /// 9-bit multiplier elements the design asks for (before the rule).
    pub multipliers_asked: u64,
    pub state: FitState,
}

/// The thesis's design, each of its three logic-saving optimizations alone, the
/// three together, two intersection units, and the three together with the most
/// intersection units that fit `device`, costed for a scene of `primitives` at
/// `width`×`height` at `clock_hz`.
pub fn thesis_optimizations(
    lib: &Library,
    device: &DeviceSpec,
    primitives: u64,
    width: u32,
    height: u32,
    clock_hz: f64,
) -> Vec<OptimizationCost> {
    let thesis = Design::thesis();
    let together = Design {
        fast_sqrt: true,
        ortho: true,
        no_rsqrt_shading: true,
        ..thesis
    };
    // The logic the three free is worth what it makes room for: more units.
    let most = largest_units(lib, device, &together, primitives, width, height).unwrap_or(1);
    let designs = [
        ("thesis".to_string(), thesis),
        (
            "fast square root (8.3.1)".to_string(),
            Design {
                fast_sqrt: true,
                ..thesis
            },
        ),
        (
            "orthographic camera (8.3.2)".to_string(),
            Design {
                ortho: true,
                ..thesis
            },
        ),
        (
            "sqrt-free shading (8.3.4)".to_string(),
            Design {
                no_rsqrt_shading: true,
                ..thesis
            },
        ),
        ("the three together".to_string(), together),
        (
            "two intersection units (8.3.3)".to_string(),
            Design { units: 2, ..thesis },
        ),
        (
            format!(
                "the three together, {most} intersection {} (the most that fit)",
                if most == 1 { "unit" } else { "units" }
            ),
            Design {
                units: most,
                ..together
            },
        ),
    ];
    designs
        .into_iter()
        .map(|(label, design)| {
            let pipeline = Pipeline::build(lib, &design);
            let timing = frame_timing(&pipeline, primitives, width, height, clock_hz);
            let asked = demand(lib, &pipeline, primitives, width, height);
            let fitted = fit_design(lib, device, &pipeline, primitives, width, height);
            OptimizationCost {
                label,
                design,
                fill_cycles: timing.fill_cycles,
                cycles_per_pixel: timing.cycles_per_pixel,
                frame_cycles: timing.cycles,
                frame_seconds: timing.seconds,
                used: fitted.used,
                multipliers_asked: asked.mult,
                state: fitted.state,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::library::OpKind;

    /// The thesis's device and its library.
    fn ep4ce115() -> (Library, DeviceSpec) {
        let lib = Library::cyclone_iv_e();
        let device = lib
            .validated_device()
            .cloned()
            .unwrap_or_else(|| panic!("a validated device in the library"));
        (lib, device)
    }

    fn costs() -> Vec<OptimizationCost> {
        let (lib, device) = ep4ce115();
        thesis_optimizations(&lib, &device, 7, 640, 480, 50e6)
    }

    #[test]
    fn the_frame_follows_eq_49_for_each_design() {
        let c = costs();
        // Seven primitives: one pixel every 3·7 = 21 cycles with one unit, 3·⌈7/2⌉ =
        // 12 with two.
        assert_eq!(c[0].cycles_per_pixel, 21);
        assert_eq!(c[5].cycles_per_pixel, 12);
        for row in &c {
            assert_eq!(
                row.frame_cycles,
                640 * 480 * row.cycles_per_pixel + row.fill_cycles,
                "{}",
                row.label
            );
            assert!((row.frame_seconds - row.frame_cycles as f64 / 50e6).abs() < 1e-12);
        }
        // The thesis at 7 primitives: 640·480·21 = 6,451,200 issue cycles.
        assert!(c[0].frame_cycles > 6_451_200 && c[0].frame_cycles < 6_452_200);
    }

    #[test]
    fn the_fast_square_root_trades_the_ip_core_for_an_adder() {
        let lib = Library::cyclone_iv_e();
        let c = costs();
        let (thesis, fast) = (&c[0], &c[1]);
        // Every square root of the pipeline becomes a one-cycle integer adder: the
        // logic saved is the IP core's LEs less the adder's, per root; no multiplier
        // changes (neither uses one).
        let roots = Pipeline::build(&lib, &Design::thesis())
            .blocks_in_order()
            .iter()
            .flat_map(|b| b.schedule.op_counts.iter())
            .filter(|(op, _)| *op == OpKind::Sqrt)
            .map(|(_, n)| u64::from(*n))
            .sum::<u64>();
        assert!(roots > 0, "the thesis's pipeline takes square roots");
        let core = lib.op(OpKind::Sqrt).resources.le;
        let adder = lib.op(OpKind::FastSqrt).resources.le;
        assert!(fast.used.le < thesis.used.le);
        assert_eq!(fast.used.mult, thesis.used.mult);
        // Delay-balancing registers move with the latencies, so the LEs saved are the
        // operators' difference give or take the balancing: within 25 %.
        let saved = thesis.used.le as f64 - fast.used.le as f64;
        let operators = (roots * (core - adder)) as f64;
        assert!(
            (saved / operators - 1.0).abs() < 0.25,
            "saved {saved} LEs, operators {operators}"
        );
        // And the fill shortens by the core's latency less the adder's, once per root
        // on the critical path: at least once.
        let shorter = thesis.fill_cycles - fast.fill_cycles;
        let step = u64::from(lib.op(OpKind::Sqrt).latency - lib.op(OpKind::FastSqrt).latency);
        assert!(
            shorter >= step && shorter % step == 0,
            "{shorter} vs {step}"
        );
    }

    #[test]
    fn more_units_cost_more_logic_and_the_most_that_fit_do_fit() {
        let c = costs();
        assert!(c[5].used.le > c[0].used.le);
        let most = c.last().unwrap_or_else(|| panic!("rows"));
        assert_ne!(most.state, FitState::DoesNotFit, "{}", most.label);
        assert!(most.design.fast_sqrt && most.design.ortho && most.design.no_rsqrt_shading);
        // One more unit than the most does not fit.
        let (lib, device) = ep4ce115();
        let more = Design {
            units: most.design.units + 1,
            ..most.design
        };
        let pipeline = Pipeline::build(&lib, &more);
        let fitted = fit_design(&lib, &device, &pipeline, 7, 640, 480);
        assert!(!fitted.fits, "{} units fit too", more.units);
    }

    #[test]
    fn the_labels_cite_the_thesis_s_sections() {
        // Several intersection units are the thesis's 8.3.3 (8.3.5 is pixel averaging).
        let (lib, device) = ep4ce115();
        let rows = thesis_optimizations(&lib, &device, 7, 640, 480, 50e6);
        assert!(
            rows.iter()
                .any(|r| r.label == "two intersection units (8.3.3)")
        );
        assert!(rows.iter().all(|r| !r.label.contains("8.3.5")));
    }
}
