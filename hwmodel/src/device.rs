//! Device fit: what a design needs on a device, and whether it fits.
//!
//! Demand = primary ray, K × (intersection + minimum distance), the comparator tree,
//! shading and the glue blocks (screen iterator, VGA controller, serial loader), plus
//! memory for the scene (words per primitive × 32 bits × n) and the frame buffer
//! (width × height × bits per pixel), and 2 PLLs (the 50 MHz system clock and the
//! 25 MHz VGA pixel clock).
//!
//! Multiplier rule: when the design asks for more 9-bit multiplier elements than the
//! device has, every element beyond the device's count is built in logic at the
//! library's `soft_mult9_le` LEs and `soft_mult9_regs` registers each, and the fit says
//! how many it built that way. The thesis's own table 8 asks for 540 elements on a
//! 532-element device: Quartus must have done something of this kind.
//!
//! Routing-headroom rule: a design whose logic elements or memory bits fit but use more
//! than [`ROUTING_HEADROOM_PERCENT`] of the device, or more than
//! [`MEMORY_BLOCK_HEADROOM_PERCENT`] of its RAM blocks ([`crate::memory`]), fits only on
//! paper ([`FitState`]): Quartus rarely routes it, or routes it without meeting timing.
//! `fits` keeps its meaning (every resource within the device); [`Fit::state`] adds the
//! third case. [`fit_design`] is the one fit of a design that every caller uses, so the
//! verdict is the same wherever it is shown.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::blocks::Pipeline;
use crate::design::Design;
use crate::library::{DeviceSpec, Library, Resources};

/// PLLs the design uses.
pub const PLLS_USED: u32 = 2;

/// Routing headroom: the share of a device's logic elements (and of its memory bits) a
/// design may use and still be expected to route, in percent. Above it the design fits
/// on paper only ([`FitState::FitsOnPaper`]) and `rtprof hw time` and the report warn.
///
/// Why 85 %:
/// - A fitter needs free logic to place and route: Intel's Quartus Prime Standard
///   Edition User Guide: Design Optimization (UG 683230, "Routing Usage") says designs
///   with average interconnect usage over 65 % typically have difficulty meeting
///   timing and peak usage at or above 90 % is likely to have problems with timing
///   closure, and Intel's AN 906 (Stratix 10 routing and floorplan guidelines, "Logic
///   Utilization") recommends keeping logic utilization below 70 %, with a high risk of
///   missing timing above. Those figures are for fast clocks; the thesis's pipeline
///   runs at 50 MHz, far below what a Cyclone IV E's fabric reaches, so it tolerates a
///   fuller device.
/// - The thesis's own design routed and ran at 50 MHz with 78 % of the EP4CE115's
///   logic elements (its conclusions): the line must lie above that.
/// - The model's block LEs run under Quartus's (table 8: by 6 to 20 % per block), so a
///   model figure of 85 % may be 90 % or more in Quartus, where the peak-routing
///   warning above applies.
/// - Memory bits: an M9K's 9,216 bits include 1,024 parity bits a byte-wide memory (the
///   8-bit frame buffer) cannot use, so above 8/9 ≈ 88.9 % of the bits such a design may
///   run out of blocks before bits. The same 85 % applies to the bits; the blocks
///   themselves have their own rule, [`MEMORY_BLOCK_HEADROOM_PERCENT`].
/// - Not to multipliers or PLLs: the thesis's design used all 532 multiplier elements
///   and routed (the elements beyond the device go to logic, where the LE headroom
///   counts them), and PLLs are a handful of fixed blocks with their own clock routing.
///
/// Sources (addresses in docs/hardware-model.md, "Routing headroom"): UG 683230 18.1
/// §"Routing Usage"; AN 906 §"Logic Utilization"; Quartus help, FLP-10000.
pub const ROUTING_HEADROOM_PERCENT: u64 = 85;

/// The share of a device's RAM blocks (M9K) a design may use and still be expected to
/// place and route, in percent: Intel's design-assistant rule FLP-10000 (Quartus Prime
/// Pro) flags designs above 80 % of the memory blocks (its default
/// `device_ram_occupation`) as a placement and routing challenge. Blocks, not bits: each
/// memory takes whole blocks however few bits it holds ([`crate::memory`]). The thesis's
/// own design is above it on the model's count (its frame buffer alone is 300 of the
/// EP4CE115's 432 M9K) and was built and ran at 50 MHz: the rule is a warning, not a
/// wall.
pub const MEMORY_BLOCK_HEADROOM_PERCENT: u64 = 80;

/// The resources the routing headroom applies to: name, name in words, headroom in
/// percent of the device.
pub const HEADROOM_RESOURCES: [(&str, &str, u64); 3] = [
    ("le", "logic elements", ROUTING_HEADROOM_PERCENT),
    ("mem_bits", "memory bits", ROUTING_HEADROOM_PERCENT),
    ("mem_blocks", "memory blocks", MEMORY_BLOCK_HEADROOM_PERCENT),
];

/// The headroom of a resource by name, percent (the routing headroom for names without
/// their own).
pub fn headroom_percent(resource: &str) -> u64 {
    HEADROOM_RESOURCES
        .iter()
        .find(|(name, _, _)| *name == resource)
        .map_or(ROUTING_HEADROOM_PERCENT, |(_, _, percent)| *percent)
}

/// The most of `capacity` a design may use within a headroom of `percent` (rounded
/// down).
pub fn headroom_limit(capacity: u64, percent: u64) -> u64 {
    // u128: no overflow whatever the capacity.
    (u128::from(capacity) * u128::from(percent) / 100) as u64
}

/// Whether `used` of `capacity` of `resource` is above its headroom (strictly: exactly
/// at the limit is within it).
pub fn above_headroom(resource: &str, used: u64, capacity: u64) -> bool {
    used > headroom_limit(capacity, headroom_percent(resource))
}

/// The resources among logic elements, memory bits and memory blocks, each `(used,
/// capacity)`, that are above their headroom, by name (`le`, `mem_bits`,
/// `mem_blocks`). A capacity of zero blocks (a file from before blocks were counted) is
/// not checked.
pub fn resources_above_headroom(
    le: (u64, u64),
    mem_bits: (u64, u64),
    mem_blocks: (u64, u64),
) -> Vec<&'static str> {
    [
        ("le", le),
        ("mem_bits", mem_bits),
        ("mem_blocks", mem_blocks),
    ]
    .into_iter()
    .filter(|(name, (used, capacity))| {
        !(*name == "mem_blocks" && *capacity == 0) && above_headroom(name, *used, *capacity)
    })
    .map(|(name, _)| name)
    .collect()
}

/// The three verdicts of a fit.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum FitState {
    /// Every resource within the device, logic and memory within the routing headroom.
    Fits,
    /// Every resource within the device, but logic or memory above the routing
    /// headroom: fits on paper, rarely routes.
    FitsOnPaper,
    /// Some resource exceeds the device.
    DoesNotFit,
}

impl FitState {
    /// The state from whether every resource fits and which are above the headroom.
    pub fn of(fits: bool, above_headroom: &[&str]) -> FitState {
        if !fits {
            FitState::DoesNotFit
        } else if above_headroom.is_empty() {
            FitState::Fits
        } else {
            FitState::FitsOnPaper
        }
    }

    /// The verdict in a word or two, for a "fits" column: `yes`, `on paper only`, `no`.
    pub fn label(self) -> &'static str {
        match self {
            FitState::Fits => "yes",
            FitState::FitsOnPaper => "on paper only",
            FitState::DoesNotFit => "no",
        }
    }
}

/// The routing-headroom warning, one sentence, from the resources above the headroom
/// and their utilization (fractions of the device), e.g. `logic elements at 99.3 % of
/// the device (headroom 85 %): …`. The one wording of the rule for `rtprof hw time` and
/// the report. `None` when nothing is above the headroom.
pub fn headroom_warning(above: &[(&str, f64)]) -> Option<String> {
    if above.is_empty() {
        return None;
    }
    let parts: Vec<String> = above
        .iter()
        .map(|(name, utilization)| {
            let words = HEADROOM_RESOURCES
                .iter()
                .find(|(n, _, _)| n == name)
                .map_or(*name, |(_, words, _)| words);
            format!(
                "{words} at {:.1} % (headroom {} %)",
                utilization * 100.0,
                headroom_percent(name)
            )
        })
        .collect();
    Some(format!(
        "{} of the device, above the routing headroom: fits on paper, but a design this full rarely routes or meets timing",
        parts.join(" and ")
    ))
}

/// Utilization of each resource, as a fraction of the device.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Utilization {
    pub le: f64,
    pub mult: f64,
    pub mem_bits: f64,
    pub mem_blocks: f64,
    pub plls: f64,
}

/// How a design sits on a device.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Fit {
    pub device: String,
    pub validated: bool,
    /// What the design asks for before the multiplier rule.
    pub demand: Resources,
    /// After the multiplier rule: LEs include the soft multipliers, `mult` is at most
    /// the device's count.
    pub used: Resources,
    pub plls: u32,
    /// Multiplier elements built in logic.
    pub soft_mult_elements: u64,
    /// LEs those soft multipliers take.
    pub soft_mult_le: u64,
    /// RAM blocks the design's memories take ([`crate::memory`]), and the device's.
    pub mem_blocks: u64,
    pub mem_block_capacity: u64,
    pub utilization: Utilization,
    /// Every resource within the device (on paper: see `state` for the headroom).
    pub fits: bool,
    /// Resources that do not fit (`le`, `mem_bits`, `mem_blocks`, `plls`).
    pub over: Vec<&'static str>,
    /// The routing headroom as a fraction of the device, comparable to `utilization`.
    pub routing_headroom: f64,
    /// Resources above their headroom (`le`, `mem_bits`, `mem_blocks`), whether or not
    /// they fit.
    pub above_headroom: Vec<&'static str>,
    /// Fits / fits on paper only (above the routing headroom) / does not fit.
    pub state: FitState,
}

impl Fit {
    /// The utilization of a resource by name (`le`, `mult`, `mem_bits`, `plls`).
    pub fn utilization_of(&self, resource: &str) -> f64 {
        match resource {
            "le" => self.utilization.le,
            "mult" => self.utilization.mult,
            "mem_bits" => self.utilization.mem_bits,
            "mem_blocks" => self.utilization.mem_blocks,
            "plls" => self.utilization.plls,
            _ => f64::NAN,
        }
    }

    /// The routing-headroom warning ([`headroom_warning`]) when the design fits on
    /// paper only; `None` when it fits with headroom or does not fit at all.
    pub fn headroom_warning(&self) -> Option<String> {
        if self.state != FitState::FitsOnPaper {
            return None;
        }
        let above: Vec<(&str, f64)> = self
            .above_headroom
            .iter()
            .map(|r| (*r, self.utilization_of(r)))
            .collect();
        headroom_warning(&above)
    }
}

/// Memory bits the scene and the frame buffer take.
pub fn memory_bits(design: &Design, primitives: u64, width: u32, height: u32) -> u64 {
    let scene = design.words_per_primitive() * 32 * primitives.max(1);
    let frame = u64::from(width) * u64::from(height) * u64::from(design.frame_bits_per_pixel);
    scene + frame
}

/// Resources of the whole design (before the multiplier rule).
pub fn demand(
    lib: &Library,
    pipeline: &Pipeline,
    primitives: u64,
    width: u32,
    height: u32,
) -> Resources {
    let units = u64::from(pipeline.design.units);
    let per_unit = pipeline.intersection.resources() + pipeline.min_distance.resources();
    let tree = pipeline
        .min_tree
        .as_ref()
        .map_or(Resources::default(), |b| b.resources());
    let glue: Resources = lib.glue().map(|(_, g)| g.resources).sum();
    let mut total = pipeline.primary_ray.resources()
        + per_unit * units
        + tree
        + pipeline.shading.resources()
        + glue;
    total.mem_bits += memory_bits(&pipeline.design, primitives, width, height);
    total
}

/// The fit of `pipeline` on `device` for a scene of `primitives` and a `width`×`height`
/// frame: its demand ([`demand`]) and its RAM blocks ([`crate::memory::design_blocks`]).
/// The one fit of a design: every table and sentence that says whether a design fits
/// takes it from here.
pub fn fit_design(
    lib: &Library,
    device: &DeviceSpec,
    pipeline: &Pipeline,
    primitives: u64,
    width: u32,
    height: u32,
) -> Fit {
    let blocks = crate::memory::design_blocks(lib, pipeline, primitives, width, height);
    fit(
        lib,
        device,
        demand(lib, pipeline, primitives, width, height),
        blocks,
    )
}

/// Applies the multiplier rule and checks every resource against `device`, with the
/// design's RAM blocks ([`fit_design`] computes them).
pub fn fit(lib: &Library, device: &DeviceSpec, demand: Resources, mem_blocks: u64) -> Fit {
    let soft = demand.mult.saturating_sub(device.mult);
    let mut used = demand;
    used.mult = demand.mult.min(device.mult);
    used.le += soft * lib.soft_mult9_le;
    used.regs += soft * lib.soft_mult9_regs;
    let frac = |a: u64, b: u64| {
        if b == 0 {
            f64::INFINITY
        } else {
            a as f64 / b as f64
        }
    };
    let utilization = Utilization {
        le: frac(used.le, device.le),
        mult: frac(used.mult, device.mult),
        mem_bits: frac(used.mem_bits, device.mem_bits),
        mem_blocks: frac(mem_blocks, lib.memory_blocks(device)),
        plls: frac(u64::from(PLLS_USED), u64::from(device.plls)),
    };
    let mut over = Vec::new();
    if used.le > device.le {
        over.push("le");
    }
    if used.mem_bits > device.mem_bits {
        over.push("mem_bits");
    }
    let block_capacity = lib.memory_blocks(device);
    if mem_blocks > block_capacity {
        over.push("mem_blocks");
    }
    if PLLS_USED > device.plls {
        over.push("plls");
    }
    let above_headroom = resources_above_headroom(
        (used.le, device.le),
        (used.mem_bits, device.mem_bits),
        (mem_blocks, block_capacity),
    );
    let fits = over.is_empty();
    Fit {
        device: device.name.clone(),
        validated: lib.validated && device.validated,
        demand,
        used,
        plls: PLLS_USED,
        soft_mult_elements: soft,
        soft_mult_le: soft * lib.soft_mult9_le,
        mem_blocks,
        mem_block_capacity: block_capacity,
        utilization,
        fits,
        over,
        routing_headroom: ROUTING_HEADROOM_PERCENT as f64 / 100.0,
        state: FitState::of(fits, &above_headroom),
        above_headroom,
    }
}

/// The largest number of intersection units (1…n) that fits, `None` when even one
/// does not.
pub fn largest_units(
    lib: &Library,
    device: &DeviceSpec,
    design: &Design,
    primitives: u64,
    width: u32,
    height: u32,
) -> Option<u32> {
    largest_units_where(lib, device, design, (primitives, width, height), |f| f.fits)
}

/// The largest number of intersection units (1…n) that fits within the routing
/// headroom ([`FitState::Fits`]), `None` when even one does not: the K worth building,
/// where [`largest_units`] is the K that fits on paper.
pub fn largest_units_within_headroom(
    lib: &Library,
    device: &DeviceSpec,
    design: &Design,
    primitives: u64,
    width: u32,
    height: u32,
) -> Option<u32> {
    largest_units_where(lib, device, design, (primitives, width, height), |f| {
        f.state == FitState::Fits
    })
}

/// The largest K in 1…n whose fit passes `accept`, by binary search.
fn largest_units_where(
    lib: &Library,
    device: &DeviceSpec,
    design: &Design,
    (primitives, width, height): (u64, u32, u32),
    accept: impl Fn(&Fit) -> bool,
) -> Option<u32> {
    let max_units = u32::try_from(primitives.max(1)).unwrap_or(u32::MAX);
    let passes = |k: u32| {
        let d = Design {
            units: k,
            ..*design
        };
        let p = Pipeline::build(lib, &d);
        accept(&fit_design(lib, device, &p, primitives, width, height))
    };
    // Demand grows with K, so the accepted K form a prefix: binary search.
    if !passes(1) {
        return None;
    }
    let (mut lo, mut hi) = (1u32, max_units);
    while lo < hi {
        let mid = lo + (hi - lo).div_ceil(2);
        if passes(mid) { lo = mid } else { hi = mid - 1 }
    }
    Some(lo)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn device(le: u64, mult: u64, mem_bits: u64) -> DeviceSpec {
        DeviceSpec {
            name: "test".into(),
            board: String::new(),
            validated: true,
            le,
            mult,
            mem_bits,
            plls: 4,
        }
    }

    #[test]
    fn multipliers_beyond_the_device_are_built_in_logic() {
        let lib = Library::cyclone_iv_e();
        // Table 8's own total: 118 + 221 + 0 + 201 = 540 elements on 532.
        let demand = Resources {
            le: 100_000,
            mult: 540,
            ..Resources::default()
        };
        let f = fit(&lib, &device(114_480, 532, 3_981_312), demand, 0);
        assert_eq!(f.soft_mult_elements, 8);
        assert_eq!(f.used.mult, 532);
        assert_eq!(f.used.le, 100_000 + 8 * lib.soft_mult9_le);
        assert_eq!(f.soft_mult_le, 8 * 81);
        assert!(f.fits);
        assert!((f.utilization.mult - 1.0).abs() < 1e-12);
    }

    #[test]
    fn the_limiting_resource_is_named() {
        let lib = Library::cyclone_iv_e();
        let demand = Resources {
            le: 10,
            mem_bits: 7_372_800, // a 24-bit 640x480 frame, which did not fit the thesis
            ..Resources::default()
        };
        let f = fit(&lib, &device(114_480, 532, 3_981_312), demand, 0);
        assert!(!f.fits);
        assert_eq!(f.over, vec!["mem_bits"]);
        assert!((f.utilization.mem_bits - 7_372_800.0 / 3_981_312.0).abs() < 1e-12);
    }

    #[test]
    fn memory_counts_the_frame_buffer_and_nine_words_per_primitive() {
        let d = Design::thesis();
        assert_eq!(memory_bits(&d, 7, 640, 480), 7 * 9 * 32 + 640 * 480 * 8);
        let colour = Design {
            frame_bits_per_pixel: 24,
            ..d
        };
        assert_eq!(memory_bits(&colour, 1, 640, 480), 9 * 32 + 7_372_800);
    }

    /// The thesis's board: 114,480 LEs, 532 multiplier elements, 432 M9K × 9,216 bits.
    fn ep4ce115() -> DeviceSpec {
        device(114_480, 532, 3_981_312)
    }

    fn fit_le(le: u64) -> Fit {
        let demand = Resources {
            le,
            ..Resources::default()
        };
        fit(&Library::cyclone_iv_e(), &ep4ce115(), demand, 0)
    }

    #[test]
    fn a_design_at_99_percent_of_the_les_fits_on_paper_only() {
        // 99 % of 114,480 = 113,335.2; the headroom ends at 85 % = 97,308.
        let f = fit_le(113_335);
        assert!(f.fits);
        assert!(f.over.is_empty());
        assert_eq!(f.above_headroom, vec!["le"]);
        assert_eq!(f.state, FitState::FitsOnPaper);
        assert_eq!(f.state.label(), "on paper only");
        assert_eq!(
            f.headroom_warning().as_deref(),
            Some(
                "logic elements at 99.0 % (headroom 85 %) of the device, above the routing \
                 headroom: fits on paper, but a design this full rarely routes or meets \
                 timing"
            )
        );
    }

    #[test]
    fn a_design_at_half_the_les_fits_cleanly() {
        let f = fit_le(57_240);
        assert!(f.fits);
        assert!(f.above_headroom.is_empty());
        assert_eq!(f.state, FitState::Fits);
        assert_eq!(f.state.label(), "yes");
        assert_eq!(f.headroom_warning(), None);
    }

    #[test]
    fn a_design_over_the_les_does_not_fit_and_does_not_warn_about_headroom() {
        let f = fit_le(114_481);
        assert!(!f.fits);
        assert_eq!(f.over, vec!["le"]);
        assert_eq!(f.above_headroom, vec!["le"]);
        assert_eq!(f.state, FitState::DoesNotFit);
        assert_eq!(f.state.label(), "no");
        assert_eq!(f.headroom_warning(), None);
        // Exactly the device fits, on paper.
        assert_eq!(fit_le(114_480).state, FitState::FitsOnPaper);
    }

    #[test]
    fn exactly_at_the_headroom_is_within_it() {
        // 114,480 × 85 / 100 = 97,308 exactly.
        assert_eq!(headroom_limit(114_480, 85), 97_308);
        assert_eq!(fit_le(97_308).state, FitState::Fits);
        assert_eq!(fit_le(97_309).state, FitState::FitsOnPaper);
        // Memory bits: 3,981,312 × 0.85 = 3,384,115.2, rounded down.
        assert_eq!(headroom_limit(3_981_312, 85), 3_384_115);
        let mem = |mem_bits: u64| {
            let demand = Resources {
                le: 1,
                mem_bits,
                ..Resources::default()
            };
            fit(&Library::cyclone_iv_e(), &ep4ce115(), demand, 0)
        };
        assert_eq!(mem(3_384_115).state, FitState::Fits);
        let over = mem(3_384_116);
        assert_eq!(over.state, FitState::FitsOnPaper);
        assert_eq!(over.above_headroom, vec!["mem_bits"]);
        assert!(
            over.headroom_warning()
                .unwrap()
                .starts_with("memory bits at 85.0 % (headroom 85 %) of the device")
        );
        assert!(!above_headroom("le", 0, 0));
        assert!(above_headroom("le", 1, 0));
        // Blocks: 432 M9K × 80 % = 345.6, so 345 are within and 346 above.
        let blocks = |n: u64| {
            let demand = Resources {
                le: 1,
                ..Resources::default()
            };
            fit(&Library::cyclone_iv_e(), &ep4ce115(), demand, n)
        };
        assert_eq!(blocks(345).state, FitState::Fits);
        let above = blocks(346);
        assert_eq!(
            (above.state, above.above_headroom.as_slice()),
            (FitState::FitsOnPaper, ["mem_blocks"].as_slice())
        );
        assert_eq!((above.mem_blocks, above.mem_block_capacity), (346, 432));
        assert!(
            above
                .headroom_warning()
                .unwrap()
                .starts_with("memory blocks at 80.1 % (headroom 80 %) of the device")
        );
        assert_eq!(blocks(433).state, FitState::DoesNotFit);
        assert_eq!(blocks(433).over, vec!["mem_blocks"]);
    }

    #[test]
    fn the_headroom_counts_soft_multipliers_but_not_the_hard_ones() {
        let lib = Library::cyclone_iv_e();
        // All 532 hard multipliers and half the LEs: fits cleanly, as the thesis did.
        let full_mult = Resources {
            le: 57_240,
            mult: 532,
            ..Resources::default()
        };
        assert_eq!(fit(&lib, &ep4ce115(), full_mult, 0).state, FitState::Fits);
        // At the LE limit, one multiplier element too many goes to logic (81 LEs).
        let spill = Resources {
            le: 97_308,
            mult: 533,
            ..Resources::default()
        };
        let f = fit(&lib, &ep4ce115(), spill, 0);
        assert_eq!(f.used.le, 97_308 + 81);
        assert_eq!(f.state, FitState::FitsOnPaper);
    }

    #[test]
    fn the_warning_names_every_resource_above_the_headroom() {
        assert_eq!(
            headroom_warning(&[("le", 0.9), ("mem_bits", 0.95)]).as_deref(),
            Some(
                "logic elements at 90.0 % (headroom 85 %) and memory bits at 95.0 % \
                 (headroom 85 %) of the device, above the routing headroom: fits on \
                 paper, but a design this full rarely routes or meets timing"
            )
        );
        assert_eq!(headroom_warning(&[]), None);
        assert_eq!(
            resources_above_headroom((100, 100), (10, 100), (0, 0)),
            vec!["le"]
        );
        assert_eq!(
            resources_above_headroom((1, 100), (1, 100), (81, 100)),
            vec!["mem_blocks"]
        );
    }

    #[test]
    fn the_largest_k_within_headroom_is_at_most_the_largest_that_fits() {
        let lib = Library::cyclone_iv_e();
        let ep4 = lib.devices[0].clone();
        let d = Design::thesis();
        let within = largest_units_within_headroom(&lib, &ep4, &d, 64, 640, 480);
        let fits = largest_units(&lib, &ep4, &d, 64, 640, 480);
        assert!(within <= fits, "{within:?} > {fits:?}");
        if let Some(k) = within {
            let at = |k: u32| {
                let p = Pipeline::build(&lib, &Design { units: k, ..d });
                fit_design(&lib, &ep4, &p, 64, 640, 480).state
            };
            assert_eq!(at(k), FitState::Fits);
            assert!(k == 64 || at(k + 1) != FitState::Fits);
        }
    }

    #[test]
    fn largest_units_is_the_last_k_that_fits() {
        let lib = Library::cyclone_iv_e();
        let ep4 = lib.devices[0].clone();
        let d = Design::thesis();
        if let Some(k) = largest_units(&lib, &ep4, &d, 64, 640, 480) {
            let at = |k: u32| {
                let p = Pipeline::build(&lib, &Design { units: k, ..d });
                fit_design(&lib, &ep4, &p, 64, 640, 480).fits
            };
            assert!(at(k));
            assert!(k == 64 || !at(k + 1));
        }
    }
}
