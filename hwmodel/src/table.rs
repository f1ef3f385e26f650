//! The model next to the thesis's tables 7 (operations) and 8 (blocks).
//!
//! The thesis's figures here are the reference the model is judged by, not inputs to
//! it: the model computes every composite and block from the IP-core rows alone.

use std::fmt;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::blocks::{BlockFigures, Pipeline};
use crate::composites::{
    dot, normalize, vector_add_sub, vector_input, vector_output, vector_scale,
};
use crate::design::Design;
use crate::graph::{AddSubMode, Graph};
use crate::library::{Library, OpKind, Resources};

/// A row as the thesis printed it: latency, LE, comb, regs, mem bits, mult.
pub type ThesisRow = (&'static str, [u64; 6]);

/// Table 7, composite rows (the IP rows are the library itself).
/// Table 7's IP cores as the thesis measured them (Quartus II, ALTFP cores). The library
/// takes their resources; two of its latencies are rtprof's own RTL's instead (divide
/// 15 for 6, inverse square root 28 for 26: `hwmodel/data/cyclone_iv_e.toml` says why),
/// and the comparison shows both.
pub const TABLE_7_IP_CORES: [ThesisRow; 5] = [
    ("add_sub", [7, 906, 802, 415, 0, 0]),
    ("multiply", [5, 301, 222, 218, 0, 7]),
    ("sqrt", [16, 1207, 826, 670, 0, 0]),
    ("divide", [6, 352, 260, 237, 4608, 16]),
    ("inv_sqrt", [26, 1948, 1225, 1818, 0, 34]),
];

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

/// A column of tables 7 and 8.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Column {
    Latency,
    Le,
    Comb,
    Regs,
    MemBits,
    Mult,
}

impl Column {
    /// The columns in the thesis's order.
    pub const ALL: [Column; 6] = [
        Column::Latency,
        Column::Le,
        Column::Comb,
        Column::Regs,
        Column::MemBits,
        Column::Mult,
    ];

    /// The field name in [`Figures`] and [`Errors`] (and in JSON).
    pub fn key(self) -> &'static str {
        match self {
            Column::Latency => "latency",
            Column::Le => "le",
            Column::Comb => "comb",
            Column::Regs => "regs",
            Column::MemBits => "mem_bits",
            Column::Mult => "mult",
        }
    }

    /// What it measures, for a reader.
    pub fn label(self) -> &'static str {
        match self {
            Column::Latency => "latency",
            Column::Le => "logic elements",
            Column::Comb => "combinational functions",
            Column::Regs => "registers",
            Column::MemBits => "memory bits",
            Column::Mult => "multipliers",
        }
    }
}

/// One row's figures, the model's or the thesis's: latency (cycles), logic elements,
/// combinational functions, registers, memory bits, 9-bit multipliers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
// Named in the results schema as results re-exports it (`HwFigures`, …): the
// bare name says little there.
#[schemars(rename = "HwFigures")]
pub struct Figures {
    pub latency: u64,
    pub le: u64,
    pub comb: u64,
    pub regs: u64,
    pub mem_bits: u64,
    pub mult: u64,
}

impl Figures {
    /// The figures in the thesis's column order, as the tables print them.
    pub fn from_columns(c: [u64; 6]) -> Self {
        Self {
            latency: c[0],
            le: c[1],
            comb: c[2],
            regs: c[3],
            mem_bits: c[4],
            mult: c[5],
        }
    }

    /// A model row's figures (without its name).
    pub fn of_block(b: &BlockFigures) -> Self {
        Self {
            latency: u64::from(b.latency),
            le: b.le,
            comb: b.comb,
            regs: b.regs,
            mem_bits: b.mem_bits,
            mult: b.mult,
        }
    }

    pub fn get(&self, column: Column) -> u64 {
        match column {
            Column::Latency => self.latency,
            Column::Le => self.le,
            Column::Comb => self.comb,
            Column::Regs => self.regs,
            Column::MemBits => self.mem_bits,
            Column::Mult => self.mult,
        }
    }

    /// Each column with its figure, in the thesis's order.
    pub fn columns(&self) -> [(Column, u64); 6] {
        Column::ALL.map(|c| (c, self.get(c)))
    }
}

/// Percentage error of the model per column (`None` where the thesis has 0 and the
/// model does not).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[schemars(rename = "HwErrors")]
pub struct Errors {
    pub latency: Option<f64>,
    pub le: Option<f64>,
    pub comb: Option<f64>,
    pub regs: Option<f64>,
    pub mem_bits: Option<f64>,
    pub mult: Option<f64>,
}

impl Errors {
    /// The signed percentage errors of `model` against `thesis`, per column.
    pub fn of(model: &Figures, thesis: &Figures) -> Self {
        let e = |c| pct_error(model.get(c), thesis.get(c));
        Self {
            latency: e(Column::Latency),
            le: e(Column::Le),
            comb: e(Column::Comb),
            regs: e(Column::Regs),
            mem_bits: e(Column::MemBits),
            mult: e(Column::Mult),
        }
    }

    pub fn get(&self, column: Column) -> Option<f64> {
        match column {
            Column::Latency => self.latency,
            Column::Le => self.le,
            Column::Comb => self.comb,
            Column::Regs => self.regs,
            Column::MemBits => self.mem_bits,
            Column::Mult => self.mult,
        }
    }

    /// Each column with its error, in the thesis's order.
    pub fn columns(&self) -> [(Column, Option<f64>); 6] {
        Column::ALL.map(|c| (c, self.get(c)))
    }
}

/// Where a row of the tables comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
#[schemars(rename = "HwRowKind")]
pub enum RowKind {
    /// An IP core of the library (table 7's first rows; the thesis gives no figures
    /// to compare, they are the library itself).
    IpCore,
    /// A vector operation of table 7, built from IP cores.
    Composite,
    /// A pipeline block of table 8.
    Block,
}

impl RowKind {
    /// How the tables name it.
    pub fn name(self) -> &'static str {
        match self {
            RowKind::IpCore => "IP core",
            RowKind::Composite => "composite",
            RowKind::Block => "block",
        }
    }
}

impl fmt::Display for RowKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.pad(self.name())
    }
}

/// One row of the comparison: model figures (flattened: `name, latency, le, …`), the
/// thesis's, and the errors.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Row {
    #[serde(flatten)]
    pub model: BlockFigures,
    pub kind: RowKind,
    pub thesis: Option<Figures>,
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

fn compare(model: BlockFigures, kind: RowKind, thesis: Option<[u64; 6]>) -> Row {
    let thesis = thesis.map(Figures::from_columns);
    let error_pct = thesis
        .as_ref()
        .map(|t| Errors::of(&Figures::of_block(&model), t));
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
        let r = vector_add_sub(g, AddSubMode::Add, a, b, "a+b");
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
        compare(
            figures,
            RowKind::IpCore,
            thesis_row(&TABLE_7_IP_CORES, op.key()),
        )
    })
    .collect();
    ops.extend(composite_figures(lib).into_iter().map(|f| {
        let t = thesis_row(&TABLE_7_COMPOSITES, &f.name);
        compare(f, RowKind::Composite, t)
    }));
    let pipeline = Pipeline::build(lib, design);
    let blocks = pipeline
        .table_blocks()
        .into_iter()
        .map(|b| {
            let f = BlockFigures::of(b.name, b.latency(), b.resources());
            compare(f, RowKind::Block, thesis_row(&TABLE_8, b.name))
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

    #[test]
    fn table_7_s_ip_rows_show_the_thesis_s_figures_beside_the_library_s() {
        // The library takes ALTFP_DIV's and ALTFP_INV_SQRT's resources but rtprof's RTL's
        // latencies (15 and 28 cycles); table 7 says 6 and 26. Both are shown, with the
        // error: +150 % and +7.7 %; the other three IP rows are the thesis's own.
        let t = tables(&Library::cyclone_iv_e(), &Design::thesis());
        let row = |name: &str| t.ops.iter().find(|r| r.model.name == name).unwrap();
        let divide = row("divide");
        assert_eq!(
            (divide.model.latency, divide.thesis.unwrap().latency),
            (15, 6)
        );
        assert!((divide.error_pct.as_ref().unwrap().latency.unwrap() - 150.0).abs() < 1e-9);
        let inv = row("inv_sqrt");
        assert_eq!((inv.model.latency, inv.thesis.unwrap().latency), (28, 26));
        assert!((inv.error_pct.as_ref().unwrap().latency.unwrap() - 200.0 / 26.0).abs() < 1e-9);
        for name in ["add_sub", "multiply", "sqrt"] {
            let r = row(name);
            assert_eq!(r.kind, RowKind::IpCore);
            assert_eq!(Figures::of_block(&r.model), r.thesis.unwrap(), "{name}");
        }
    }
}
