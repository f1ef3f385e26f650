//! Small readers of the results types that the section builders share: the RMS band
//! of a quality, whether a variant is the reference, the six figures of a hardware
//! row, the scene families.

use analysis::Band;

use crate::results::{HwRow, Quality, Results, SceneHardware, SceneResult, VariantResult};

/// The RMS band of an image comparison.
pub fn band(q: &Quality) -> Band {
    band_named(&q.band, q.rms)
}

/// The RMS band of the emulator's image against the software's.
pub fn emulator_band(h: &SceneHardware) -> Band {
    band_named(&h.emulator_band, h.emulator_rms)
}

/// A band from its written name, else from the RMS it was computed from.
fn band_named(name: &str, rms: f64) -> Band {
    match name {
        "visually identical" => Band::VisuallyIdentical,
        "similar" | "visually similar" => Band::Similar,
        "notable changes" => Band::NotableChanges,
        "different" => Band::Different,
        _ => Band::of(rms),
    }
}

/// Whether `v` is the reference every other variant is compared with.
pub fn is_reference(v: &VariantResult) -> bool {
    v.variant == "baseline"
}

/// The reference variant's result on a scene, if it ran.
pub fn reference<'a>(r: &Results, scene: &'a SceneResult) -> Option<&'a VariantResult> {
    r.baseline(scene)
}

/// Whether a scene is one of the Standard Procedural Databases.
pub fn is_spd(scene: &SceneResult) -> bool {
    scene.spd || scene.family == "spd"
}

/// The six columns of tables 7 and 8: name, and the short name the command line uses.
pub const HW_COLUMNS: [(&str, &str); 6] = [
    ("latency", "latency"),
    ("logic elements", "LEs"),
    ("combinational functions", "comb"),
    ("registers", "regs"),
    ("memory bits", "mem bits"),
    ("multipliers", "mult"),
];

/// One figure of a hardware row: the model's, the thesis's and the error in %.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HwFigure {
    pub model: u64,
    pub thesis: Option<u64>,
    pub error_pct: Option<f64>,
}

/// A row of tables 7 or 8 as the table builder reads it.
#[derive(Clone, Debug, PartialEq)]
pub struct HwLine {
    pub name: String,
    /// `IP core`, `composite` or `block`.
    pub kind: String,
    /// In the order of [`HW_COLUMNS`].
    pub figures: [HwFigure; 6],
}

impl HwLine {
    /// Whether the row is one of the thesis's own IP-core figures (the model's input).
    pub fn is_ip_core(&self) -> bool {
        self.kind.contains("IP core")
    }
}

/// A results row as an [`HwLine`].
pub fn hw_line(row: &HwRow) -> HwLine {
    let figure = |c: usize| HwFigure {
        model: row.model[c],
        thesis: row.thesis.map(|t| t[c]),
        error_pct: row.error_pct.as_ref().and_then(|e| e[c]),
    };
    HwLine {
        name: row.name.clone(),
        kind: row.kind.clone(),
        figures: std::array::from_fn(figure),
    }
}
