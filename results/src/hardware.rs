//! The hardware parts of the results: the FPGA model's tables 7 and 8 with the
//! thesis's figures, the devices it fits, and the model and emulator on one scene.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

pub use hwmodel::table::{
    Column as HwColumn, Errors as HwErrors, Figures as HwFigures, RowKind as HwRowKind,
};

use analysis::{Band, Estimate};

/// One row of tables 7 or 8: the model's figures, the thesis's, the errors (%).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct HwRow {
    pub name: String,
    pub kind: HwRowKind,
    pub model: HwFigures,
    /// The thesis's figures (None for IP cores: they are the library itself).
    pub thesis: Option<HwFigures>,
    /// Signed percentage error of the model against the thesis, per column.
    pub error_pct: Option<HwErrors>,
}

impl HwRow {
    /// A row of [`hwmodel::table::tables`].
    pub fn from_model_row(row: &hwmodel::table::Row) -> Self {
        Self {
            name: row.model.name.clone(),
            kind: row.kind,
            model: HwFigures::of_block(&row.model),
            thesis: row.thesis,
            error_pct: row.error_pct,
        }
    }
}

/// Device utilization of the thesis design.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct DeviceUse {
    pub device: String,
    pub validated: bool,
    pub le: u64,
    pub le_capacity: u64,
    pub mult: u64,
    pub mult_capacity: u64,
    pub soft_mult_elements: u64,
    pub mem_bits: u64,
    pub mem_capacity: u64,
    pub plls: u32,
    pub pll_capacity: u32,
    pub fits: bool,
    pub largest_units: Option<u32>,
}

/// The FPGA model's tables and fit.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct HardwareResult {
    pub family: String,
    pub ops: Vec<HwRow>,
    pub blocks: Vec<HwRow>,
    pub devices: Vec<DeviceUse>,
}

/// A software variant's time on the hardware's job (diffuse-only gray, the scene's
/// size), on one thread and on `threads`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct SoftwarePeer {
    pub variant: crate::VariantName,
    pub one_thread: Estimate,
    pub all_threads: Estimate,
    pub threads: u32,
}

/// The FPGA model and emulator on one scene.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct SceneHardware {
    pub primitives: u64,
    pub cycles: u64,
    pub seconds: f64,
    pub fits: bool,
    /// Software time of the same job (baseline, diffuse-only gray), seconds.
    pub software_seconds: Estimate,
    /// Software seconds / hardware seconds.
    pub speedup: f64,
    /// rtprof's fastest structure on the same job, one thread and every thread (the
    /// break-even against the pipeline). `None` in older files.
    #[serde(default)]
    pub peer: Option<SoftwarePeer>,
    /// RMS between the emulator's image and the software's diffuse-only render.
    pub emulator_rms: f64,
    /// The thesis's band for `emulator_rms`.
    pub emulator_band: Band,
    /// Emulator image, relative to results.json.
    pub emulator_image: Option<String>,
    /// Software diffuse-only image, relative to results.json.
    pub software_image: Option<String>,
}
