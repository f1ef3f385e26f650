//! The RTL of the thesis's FPGA ray-casting pipeline.
//!
//! - [`operators`]: the floating-point operator library the pipeline is built from:
//!   IEEE-754 single-precision operators written in Verilog-2005 by this project
//!   (`rtl/verilog/*.v`, embedded here), each with the latency of its row in hwmodel's
//!   operator library, and their Rust reference ([`float_policy`]): the exact rounding,
//!   denormal and NaN rules the operators follow, which the tests check bit for bit
//!   through Verilator (`tests/operators.rs`);
//! - [`generate`]: the whole pipeline as Verilog, written from the scheduled dataflow
//!   graphs hwmodel times (`rtprof hw rtl`), up to [`generate::MAX_UNITS`] units;
//! - [`sim`]: the generated pipeline simulated cycle by cycle with Verilator and held
//!   against the model and the emulator ([`sim::SimCheck`], `rtprof hw sim`;
//!   `tests/pipeline.rs`);
//! - [`synth`]: Yosys synthesis for Cyclone IV E, per block, beside the model and the
//!   thesis's table 8 ([`synth::SynthComparison`], `rtprof hw synth`;
//!   `tests/synthesis.rs`);
//! - [`system`]: the thesis's whole system around the pipeline: the UART scene loader
//!   and its upload's framing, the frame memory, the VGA controller (`rtprof hw rtl
//!   --system`; `tests/system.rs`, `docs/rtl-system.md`).
//!
//! The tool tests are ignored by default (`cargo test -p rtl -- --ignored`;
//! `scripts/install-rtl-tools.sh` installs Verilator, g++ and Yosys).

// What user input can reach returns an error: no unwrap, expect or panic outside tests
// (unit tests are cfg(test); integration tests, benches and examples are other crates).
#![cfg_attr(
    not(test),
    deny(clippy::unwrap_used, clippy::expect_used, clippy::panic)
)]

/// The operators' arithmetic, kept in `hwmodel` so that its emulator computes in it.
pub use hwmodel::float_policy;
pub mod generate;
pub mod operators;
pub mod sim;
pub mod synth;
pub mod system;

use std::path::PathBuf;

use thiserror::Error;

pub use operators::{Operator, SOURCES, SourceFile, write_sources};

/// What can go wrong producing RTL.
#[derive(Debug, Error)]
pub enum RtlError {
    /// A file or directory could not be written.
    #[error("{}: {source}", path.display())]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    /// An instance does not connect a module's ports correctly.
    #[error("{module}: port `{port}` {problem}")]
    Port {
        module: &'static str,
        port: String,
        problem: &'static str,
    },
    /// A tool the command needs is not installed.
    #[error("`{tool}` was not found: {hint}")]
    ToolMissing {
        tool: &'static str,
        hint: &'static str,
    },
    /// A tool ran and failed.
    #[error("{tool}: {message}")]
    Tool { tool: &'static str, message: String },
    /// The design cannot be generated as asked.
    #[error("RTL generation: {0}")]
    Generate(String),
    /// A block asked for by name that the design does not have.
    #[error("no block '{block}' in the {design} design: one of {names}")]
    UnknownBlock {
        block: String,
        design: String,
        names: String,
    },
    /// More intersection units than the generator builds ([`generate::MAX_UNITS`]).
    #[error(
        "the RTL is generated for at most {max} intersection units, not {units} (the model, `rtprof hw time --units K`, takes more)"
    )]
    TooManyUnits { units: u32, max: u32 },
    /// A synthesis that cannot be run or reported as asked.
    #[error("synthesis: {0}")]
    Synth(String),
    /// A module asked to stand in for an operator it does not implement.
    #[error("{module} does not implement the library operator `{op}`")]
    NotImplemented {
        module: &'static str,
        op: &'static str,
    },
}
