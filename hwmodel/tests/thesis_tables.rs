//! The model against the thesis's tables 7 and 8 (acceptance of the hardware model):
//! composite latencies exactly (normalize with the library's inverse square root), block latencies within ±10 %, block LEs, registers and
//! multipliers within ±20 %. The thesis's figures are typed here from the thesis, not
//! taken from the model's own reference constants.

use hwmodel::design::Design;
use hwmodel::library::{Library, OpKind};
use hwmodel::table::tables;

/// (name, latency, LEs, comb, regs, mem bits, mult) as printed in the thesis, table 7.
const TABLE_7: [(&str, u64, u64, u64, u64, u64, u64); 4] = [
    ("dot_product", 19, 3947, 3288, 2144, 0, 28),
    ("vector_scale", 7, 883, 638, 654, 0, 21),
    ("normalize", 50, 6812, 4127, 4813, 0, 76),
    ("vector_add_sub", 7, 2719, 2411, 1246, 0, 0),
];

/// Table 8.
const TABLE_8: [(&str, u64, u64, u64, u64, u64, u64); 4] = [
    ("primary_ray", 62, 14008, 11362, 9889, 0, 118),
    ("intersection", 136, 43173, 32384, 24302, 21152, 221),
    ("min_distance", 4, 290, 254, 173, 0, 0),
    ("shading", 121, 34512, 24999, 20826, 8448, 201),
];

fn within(model: u64, thesis: u64, pct: f64) -> bool {
    (model as f64 - thesis as f64).abs() <= thesis as f64 * pct / 100.0
}

/// ALTFP_INV_SQRT's latency in table 7 (the library's inverse square root is the RTL's
/// pipelined one since issue 38, and normalize carries the difference).
const TABLE_7_INV_SQRT: u64 = 26;

#[test]
fn composite_latencies_equal_table_7() {
    let lib = Library::cyclone_iv_e();
    let t = tables(&lib, &Design::thesis());
    let inv_sqrt = u64::from(lib.op(OpKind::InvSqrt).latency);
    for (name, latency, ..) in TABLE_7 {
        let row = t.ops.iter().find(|r| r.model.name == name).unwrap();
        let want = if name == "normalize" {
            latency - TABLE_7_INV_SQRT + inv_sqrt
        } else {
            latency
        };
        assert_eq!(u64::from(row.model.latency), want, "{name}");
    }
}

#[test]
fn vector_add_sub_and_scale_resources_are_their_parts() {
    // Three adders: 3 × 906 = 2718 LEs (table 7: 2719); three multipliers: 21 elements.
    let t = tables(&Library::cyclone_iv_e(), &Design::thesis());
    let add = t
        .ops
        .iter()
        .find(|r| r.model.name == "vector_add_sub")
        .unwrap();
    assert!(within(add.model.le, 2719, 1.0) && within(add.model.regs, 1246, 1.0));
    let scale = t
        .ops
        .iter()
        .find(|r| r.model.name == "vector_scale")
        .unwrap();
    assert_eq!(scale.model.mult, 21);
    let norm = t.ops.iter().find(|r| r.model.name == "normalize").unwrap();
    assert_eq!(norm.model.mult, 76);
}

#[test]
fn block_latencies_within_10_percent_and_resources_within_20() {
    let t = tables(&Library::cyclone_iv_e(), &Design::thesis());
    for (name, latency, le, _comb, regs, _mem, mult) in TABLE_8 {
        let row = t.blocks.iter().find(|r| r.model.name == name).unwrap();
        let m = &row.model;
        eprintln!(
            "{name}: latency {}/{latency}, LEs {}/{le}, regs {}/{regs}, mult {}/{mult}",
            m.latency, m.le, m.regs, m.mult
        );
        assert!(
            within(u64::from(m.latency), latency, 10.0),
            "{name} latency"
        );
        assert!(within(m.le, le, 20.0), "{name} LEs");
        assert!(within(m.regs, regs, 20.0), "{name} registers");
        assert!(within(m.mult, mult, 20.0), "{name} multipliers");
    }
}

#[test]
fn the_json_contract_names_the_four_blocks() {
    let t = tables(&Library::cyclone_iv_e(), &Design::thesis());
    let json = serde_json::to_value(&t).unwrap();
    let names: Vec<&str> = json["blocks"]
        .as_array()
        .unwrap()
        .iter()
        .map(|b| b["name"].as_str().unwrap())
        .collect();
    assert_eq!(
        names,
        ["primary_ray", "intersection", "min_distance", "shading"]
    );
    for key in ["latency", "le", "comb", "regs", "mem_bits", "mult"] {
        assert!(json["blocks"][0][key].is_u64(), "{key}");
    }
    assert!(json["ops"].as_array().unwrap().len() >= 9);
}

#[test]
fn the_thesis_design_needs_more_multipliers_than_the_ep4ce115_has() {
    // Table 8 itself asks 540 > 532; the model's blocks ask more again, and the fit
    // builds the excess in logic and still fits (the thesis's board ran).
    use hwmodel::blocks::Pipeline;
    use hwmodel::device::{demand, fit_design};
    let lib = Library::cyclone_iv_e();
    let p = Pipeline::build(&lib, &Design::thesis());
    let d = demand(&lib, &p, 7, 640, 480);
    assert!(d.mult > 532);
    let f = fit_design(&lib, &lib.devices[0], &p, 7, 640, 480);
    assert!(f.soft_mult_elements > 0 && f.fits);
    assert_eq!(f.used.mult, 532);
}
