//! The model next to the thesis's tables 7 (operations) and 8 (blocks).
//!
//! The thesis's figures here are the reference the model is judged by, not inputs to
//! it: the model computes every composite and block from the IP-core rows alone.

use serde::Serialize;

use crate::blocks::{BlockFigures, Pipeline};
use crate::composites::{
    dot, normalize, vector_add_sub, vector_input, vector_output, vector_scale,
};
use crate::design::Design;
use crate::graph::Graph;
use crate::library::{Library, OpKind, Resources};

/// A row as the thesis printed it: latency, LE, comb, regs, mem bits, mult.
pub type ThesisRow = (&'static str, [u64; 6]);

/// Table 7, composite rows (the IP rows are the library itself).
pub const TABLE_7_COMPOSITES: [ThesisRow; 4] = [
    ("dot_product", [19, 3947, 3288, 2144, 0, 28]),
    ("vector_scale", [7, 883, 638, 654, 0, 21]),
    ("normalize", [50, 6812, 4127, 4813, 0, 76]),
    ("vector_add_sub", [7, 2719, 2411, 1246, 0, 0]),
];

/// Table 8.
pub const TABLE_8: [ThesisRow; 4] = [
    ("primary_ray", [62, 14008, 11362, 9889, 0, 118]),
    ("intersection", [136, 43173, 32384, 24302, 21152, 221]),
    ("min_distance", [4, 290, 254, 173, 0, 0]),
    ("shading", [121, 34512, 24999, 20826, 8448, 201]),
];

/// The thesis's figures for one row.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ThesisFigures {
    pub latency: u64,
    pub le: u64,
    pub comb: u64,
    pub regs: u64,
    pub mem_bits: u64,
    pub mult: u64,
}

/// Percentage error of the model per column (`None` where the thesis has 0 and the
/// model does not).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Errors {
    pub latency: Option<f64>,
    pub le: Option<f64>,
    pub comb: Option<f64>,
    pub regs: Option<f64>,
    pub mem_bits: Option<f64>,
    pub mult: Option<f64>,
}

/// One row of the comparison: model figures (flattened: `name, latency, le, …`), the
/// thesis's, and the errors.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Row {
    #[serde(flatten)]
    pub model: BlockFigures,
    /// Where the row comes from ("table 7 IP core", "composite", "block").
    pub kind: &'static str,
    pub thesis: Option<ThesisFigures>,
    pub error_pct: Option<Errors>,
}

/// Both tables, as `rtprof hw table --json` prints them.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Tables {
    pub family: String,
    pub design: String,
    pub blocks: Vec<Row>,
    pub ops: Vec<Row>,
}

/// Signed percentage error of `model` against `thesis`.
pub fn pct_error(model: u64, thesis: u64) -> Option<f64> {
    if thesis == 0 {
        (model == 0).then_some(0.0)
    } else {
        Some((model as f64 - thesis as f64) / thesis as f64 * 100.0)
    }
}

fn compare(model: BlockFigures, kind: &'static str, thesis: Option<[u64; 6]>) -> Row {
    let thesis = thesis.map(|t| ThesisFigures {
        latency: t[0],
        le: t[1],
        comb: t[2],
        regs: t[3],
        mem_bits: t[4],
        mult: t[5],
    });
    let error_pct = thesis.as_ref().map(|t| Errors {
        latency: pct_error(u64::from(model.latency), t.latency),
        le: pct_error(model.le, t.le),
        comb: pct_error(model.comb, t.comb),
        regs: pct_error(model.regs, t.regs),
        mem_bits: pct_error(model.mem_bits, t.mem_bits),
        mult: pct_error(model.mult, t.mult),
    });
    Row {
        model,
        kind,
        thesis,
        error_pct,
    }
}

/// The composites of table 7, each scheduled standalone.
pub fn composite_figures(lib: &Library) -> Vec<BlockFigures> {
    let build = |f: &dyn Fn(&mut Graph)| {
        let mut g = Graph::new();
        f(&mut g);
        g.schedule(lib)
    };
    let dot_s = build(&|g| {
        let a = vector_input(g, "a");
        let b = vector_input(g, "b");
        let d = dot(g, a, b, "a·b");
        g.output(d);
    });
    let scale_s = build(&|g| {
        let v = vector_input(g, "v");
        let s = g.input("s");
        let r = vector_scale(g, v, s, "v·s");
        vector_output(g, r);
    });
    let norm_s = build(&|g| {
        let v = vector_input(g, "v");
        let r = normalize(g, v, "n");
        vector_output(g, r);
    });
    let add_s = build(&|g| {
        let a = vector_input(g, "a");
        let b = vector_input(g, "b");
        let r = vector_add_sub(g, a, b, "a+b");
        vector_output(g, r);
    });
    [
        ("dot_product", dot_s),
        ("vector_scale", scale_s),
        ("normalize", norm_s),
        ("vector_add_sub", add_s),
    ]
    .into_iter()
    .map(|(name, s)| BlockFigures::of(name, s.latency, s.resources()))
    .collect()
}

/// Table 7 (IP rows as the library holds them, then the model's composites) and
/// table 8 (the model's blocks for `design`), each with the thesis's figures and the
/// errors. For a what-if design the thesis's table 8 is still the reference, so the
/// errors read as "change against the thesis's build".
pub fn tables(lib: &Library, design: &Design) -> Tables {
    let thesis_row =
        |rows: &[ThesisRow], name: &str| rows.iter().find(|(n, _)| *n == name).map(|(_, v)| *v);
    let mut ops: Vec<Row> = [
        OpKind::AddSub,
        OpKind::Multiply,
        OpKind::Sqrt,
        OpKind::Divide,
        OpKind::InvSqrt,
    ]
    .into_iter()
    .map(|op| {
        let spec = lib.op(op);
        let figures = BlockFigures::of(op.key(), spec.latency, spec.resources);
        Row {
            model: figures,
            kind: "IP core",
            thesis: None,
            error_pct: None,
        }
    })
    .collect();
    ops.extend(composite_figures(lib).into_iter().map(|f| {
        let t = thesis_row(&TABLE_7_COMPOSITES, &f.name);
        compare(f, "composite", t)
    }));
    let pipeline = Pipeline::build(lib, design);
    let blocks = pipeline
        .table_blocks()
        .into_iter()
        .map(|b| {
            let f = BlockFigures::of(b.name, b.latency(), b.resources());
            compare(f, "block", thesis_row(&TABLE_8, b.name))
        })
        .collect();
    Tables {
        family: lib.family.clone(),
        design: design.label(),
        blocks,
        ops,
    }
}

/// Sum of resources over rows (for totals).
pub fn total(rows: &[Row]) -> Resources {
    rows.iter()
        .map(|r| Resources {
            le: r.model.le,
            comb: r.model.comb,
            regs: r.model.regs,
            mem_bits: r.model.mem_bits,
            mult: r.model.mult,
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percentage_errors_are_signed_and_zero_safe() {
        assert_eq!(pct_error(110, 100), Some(10.0));
        assert_eq!(pct_error(90, 100), Some(-10.0));
        assert_eq!(pct_error(0, 0), Some(0.0));
        assert_eq!(pct_error(5, 0), None);
    }
}
