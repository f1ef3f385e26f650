//! The hardware parts of the results: the FPGA model's tables 7 and 8 with the
//! thesis's figures, the devices it fits, and the model and emulator on one scene.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

pub use hwmodel::table::{
    Column as HwColumn, Errors as HwErrors, Figures as HwFigures, RowKind as HwRowKind,
};

use analysis::{Band, Estimate};
use hwmodel::device::FitState;

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
    /// RAM blocks (M9K) the design's memories take, and the device's; 0 in files
    /// written before blocks were counted.
    #[serde(default)]
    pub mem_blocks: u64,
    #[serde(default)]
    pub mem_block_capacity: u64,
    pub plls: u32,
    pub pll_capacity: u32,
    pub fits: bool,
    /// The verdict hwmodel computed: fits, on paper only (above the routing headroom)
    /// or not. `None` only in files written before the field; readers then apply
    /// hwmodel's rule to the figures above (`reports::findings::fit_state`).
    #[serde(default)]
    pub fit_state: Option<FitState>,
    pub largest_units: Option<u32>,
}

/// The FPGA model's tables and fit.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct HardwareResult {
    pub family: String,
    pub ops: Vec<HwRow>,
    pub blocks: Vec<HwRow>,
    pub devices: Vec<DeviceUse>,
    /// The generated RTL of the same design through Yosys (`rtprof hw synth`), when a
    /// synthesis of exactly this RTL has been run on the machine (`None` otherwise, and
    /// in older files).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub synthesis: Option<Synthesis>,
    /// The clock rtprof's RTL of the thesis design reaches by its depth: the synthesized
    /// longest path when a synthesis is kept, else the generator's level goal (`None`
    /// in older files).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rtl_clock: Option<RtlClock>,
    /// The scene upload over the serial line before a frame (`None` in older files).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub upload: Option<Upload>,
}

/// The clock estimated for rtprof's RTL, with where it comes from.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct RtlClock {
    pub mhz: f64,
    /// LUT levels on the longest register-to-register path.
    pub levels: u64,
    /// True when `levels` was measured on a synthesis of this RTL (Yosys), false when it
    /// is the generator's goal.
    pub synthesized: bool,
    /// How the estimate was made, as a sentence.
    pub source: String,
}

/// The scene upload: the stream's bytes for the test bench's largest scene and the
/// seconds it takes on the line.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Upload {
    pub primitives: u64,
    pub bytes: u64,
    pub baud: u32,
    pub seconds: f64,
}

/// The generated RTL of a design through Yosys's default Cyclone IV E script
/// (`rtl::synth`): each block's cells and logic depth, and the clock the depth allows.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Synthesis {
    /// The design's label (`thesis`, `K=2`, …).
    pub design: String,
    /// `yosys -V`.
    pub tool: String,
    /// The flow, as a sentence (`synth_intel -family cycloneive`, the default script,
    /// hierarchy kept).
    pub flow: String,
    /// Wall time of the Yosys run, seconds.
    pub seconds: f64,
    /// A hash of the generated Verilog: which RTL these figures are of.
    pub rtl_hash: String,
    /// The clock the depth is judged against (the thesis's 50 MHz).
    pub clock_mhz: f64,
    /// The estimate's rule: `register_ns + levels × level_ns` per path.
    pub level_ns: f64,
    pub register_ns: f64,
    /// The most LUT levels a path may have at `clock_mhz` by that rule.
    pub max_levels: u64,
    /// Each generated block, in the pipeline's order (one instance of it).
    pub blocks: Vec<SynthBlock>,
    /// The whole design: every instance and the top's own logic (iterator, scene
    /// memory, control); its depth is the longest path anywhere in the design.
    pub total: SynthBlock,
}

impl Synthesis {
    /// The blocks (and the whole design) whose estimated clock is below `clock_mhz`.
    pub fn not_closing(&self) -> Vec<&SynthBlock> {
        self.blocks
            .iter()
            .chain(std::iter::once(&self.total))
            .filter(|b| !b.closes)
            .collect()
    }
}

/// One block's Yosys figures and logic depth.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct SynthBlock {
    pub name: String,
    /// 4-input LUTs (`cycloneive_lcell_comb`, and the inverters the map leaves).
    pub lut4: u64,
    /// The part of `lut4` in multiplier arrays (where Quartus uses embedded
    /// multipliers).
    pub mult_lut4: u64,
    /// Flip-flops (`dffeas`).
    pub ff: u64,
    /// Bits of the memories the RTL declares.
    pub mem_bits: u64,
    /// M9K blocks.
    pub m9k: u64,
    /// LUT levels on the longest path between registers (or ports), flattened.
    pub levels: u64,
    /// Where that path starts and ends (Yosys's names).
    pub path_from: String,
    pub path_to: String,
    /// The estimated Fmax of `levels` by the rule above, MHz.
    pub fmax_mhz: f64,
    /// `fmax_mhz` reaches the clock.
    pub closes: bool,
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
    /// Every resource within the device (on paper: `fit_state` adds the headroom).
    pub fits: bool,
    /// The thesis design's fit on the thesis's device at this scene's size: fits, on
    /// paper only, or not (`None` in older files).
    #[serde(default)]
    pub fit_state: Option<FitState>,
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
