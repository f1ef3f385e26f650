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

use serde::Serialize;

use crate::blocks::Pipeline;
use crate::design::Design;
use crate::library::{DeviceSpec, Library, Resources};

/// PLLs the design uses.
pub const PLLS_USED: u32 = 2;

/// Utilization of each resource, as a fraction of the device.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Utilization {
    pub le: f64,
    pub mult: f64,
    pub mem_bits: f64,
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
    pub utilization: Utilization,
    pub fits: bool,
    /// Resources that do not fit (`le`, `mem_bits`, `plls`).
    pub over: Vec<&'static str>,
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

/// Applies the multiplier rule and checks every resource against `device`.
pub fn fit(lib: &Library, device: &DeviceSpec, demand: Resources) -> Fit {
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
        plls: frac(u64::from(PLLS_USED), u64::from(device.plls)),
    };
    let mut over = Vec::new();
    if used.le > device.le {
        over.push("le");
    }
    if used.mem_bits > device.mem_bits {
        over.push("mem_bits");
    }
    if PLLS_USED > device.plls {
        over.push("plls");
    }
    Fit {
        device: device.name.clone(),
        validated: lib.validated && device.validated,
        demand,
        used,
        plls: PLLS_USED,
        soft_mult_elements: soft,
        soft_mult_le: soft * lib.soft_mult9_le,
        utilization,
        fits: over.is_empty(),
        over,
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
    let max_units = u32::try_from(primitives.max(1)).unwrap_or(u32::MAX);
    let fits = |k: u32| {
        let d = Design {
            units: k,
            ..*design
        };
        let p = Pipeline::build(lib, &d);
        fit(lib, device, demand(lib, &p, primitives, width, height)).fits
    };
    // Demand grows with K, so the fitting K form a prefix: binary search.
    if !fits(1) {
        return None;
    }
    let (mut lo, mut hi) = (1u32, max_units);
    while lo < hi {
        let mid = lo + (hi - lo).div_ceil(2);
        if fits(mid) { lo = mid } else { hi = mid - 1 }
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
        let f = fit(&lib, &device(114_480, 532, 3_981_312), demand);
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
        let f = fit(&lib, &device(114_480, 532, 3_981_312), demand);
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

    #[test]
    fn largest_units_is_the_last_k_that_fits() {
        let lib = Library::cyclone_iv_e();
        let ep4 = lib.devices[0].clone();
        let d = Design::thesis();
        if let Some(k) = largest_units(&lib, &ep4, &d, 64, 640, 480) {
            let at = |k: u32| {
                let p = Pipeline::build(&lib, &Design { units: k, ..d });
                fit(&lib, &ep4, demand(&lib, &p, 64, 640, 480)).fits
            };
            assert!(at(k));
            assert!(k == 64 || !at(k + 1));
        }
    }
}
