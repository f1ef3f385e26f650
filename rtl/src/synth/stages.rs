//! Place and route stage by stage: an Fmax for an operator larger than the iCE40 HX8K
//! (`fp_div`, `fp_inv_sqrt`), from its pipeline stages placed and routed apart.
//!
//! Every operator is pipelined for real: its logic lies between registers, so its
//! Fmax is the lowest Fmax of its register-to-register stages. [`place_and_route_stages`]
//! takes the same design [`super::ice40`] places whole (the operator at its library
//! latency, every input registered), flattens it with Yosys (`proc; flatten;
//! opt -nosdff -nodffe`, `flat.json`), finds every flip-flop's register level
//! (`stage_cut`: level 1 is the input registers, level k + 1 the registers
//! after stage k) and cuts it into pieces of `stages_per_piece` consecutive stages.
//! Each piece goes through the whole-operator flow (`synth_ice40`, then nextpnr-ice40
//! on the HX8K) inside a harness `pnr_top` that registers both sides:
//!
//! ```text
//! si → shift register (the piece's launching registers) → piece → capture registers
//!    → a loadable shift register → so
//! ```
//!
//! so that the piece's paths run from register to register as in the operator, with
//! three pins instead of the hundreds of bits a stage passes on. The harness's own
//! paths (a shift, a load select) are one LUT deep; they count in the piece's Fmax,
//! which can only make it lower. Nothing of the operator is written twice: the pieces
//! are cut out of the Verilog's own netlist.
//!
//! What the figure means: a stage placed alone meets less routing congestion than it
//! would inside the whole operator (and the operator inside the whole design), so the
//! lowest piece's Fmax is an optimistic bound for that stage on the HX8K; the HX8K
//! itself is a slower, smaller device than the thesis's Cyclone IV E, which makes the
//! figure conservative against the thesis's device.

use std::fs;
use std::path::Path;
use std::time::{Duration, Instant};

use hwmodel::library::Library;
use serde::Serialize;

use super::ice40::{self, Routed, TOP};
use super::io;
use super::run::run_limited;
use super::stage_cut::{Netlist, PIECE, PIECE_CLK, PIECE_IN, PIECE_OUT};
use crate::RtlError;
use crate::operators::{Operator, write_atomically};

const FLAT: &str = "flat.json";
const FLAT_LOG: &str = "flatten.log";

/// One piece: stages `first..=last` of the operator.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StagePiece {
    pub first_stage: u32,
    pub last_stage: u32,
    /// Yosys's coarse logic cells in it (before mapping), its flip-flop bits inside
    /// (the registers between its stages), and the bits in and out.
    pub coarse_cells: usize,
    pub flip_flops: usize,
    pub inputs: usize,
    pub outputs: usize,
    /// nextpnr's figures; `None` for a stage with no logic (registers only).
    pub routed: Option<Routed>,
}

/// An operator placed and routed stage by stage.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StagedPnrReport {
    /// The operator's module and LATENCY.
    pub module: String,
    pub latency: u32,
    /// The register levels found in the flattened design, the input registers
    /// included (so `latency + 1` when every stage ends in a register).
    pub register_levels: u32,
    /// The input registers' flip-flops that have logic in front of them (none).
    pub logic_before_the_inputs: usize,
    /// The coarse logic cells of the design; those that drive nothing (kept by a
    /// `keep` attribute, on no path); and those on a path that are in no piece.
    pub coarse_cells: usize,
    pub dead_cells: usize,
    pub uncovered_cells: usize,
    /// The clock nextpnr was asked to meet, MHz.
    pub target_mhz: f64,
    pub pieces: Vec<StagePiece>,
    /// Wall time of the whole run, seconds.
    pub seconds: f64,
}

impl StagedPnrReport {
    /// The piece with the lowest Fmax, if any piece has logic.
    pub fn worst(&self) -> Option<&StagePiece> {
        self.pieces
            .iter()
            .filter(|p| p.routed.is_some())
            .min_by(|a, b| {
                let f = |p: &StagePiece| p.routed.as_ref().map_or(f64::INFINITY, |r| r.fmax_mhz);
                f(a).total_cmp(&f(b))
            })
    }

    /// The operator's Fmax: the lowest of its pieces', MHz.
    pub fn fmax_mhz(&self) -> Option<f64> {
        self.worst()
            .and_then(|p| p.routed.as_ref())
            .map(|r| r.fmax_mhz)
    }

    /// The stages the pieces cover, in order (each once when the cut is complete).
    pub fn stages_covered(&self) -> Vec<u32> {
        self.pieces
            .iter()
            .flat_map(|p| p.first_stage..=p.last_stage)
            .collect()
    }
}

/// Places and routes `op` at its latency in `library`, inputs registered, in pieces
/// of `stages_per_piece` stages, aiming at `target_mhz`; each tool run may take at
/// most `timeout`. Runs one tool at a time.
pub fn place_and_route_stages(
    op: Operator,
    library: &Library,
    dir: &Path,
    stages_per_piece: u32,
    target_mhz: f64,
    timeout: Duration,
) -> Result<StagedPnrReport, RtlError> {
    let start = Instant::now();
    if op == Operator::Const {
        return Err(RtlError::Synth("fp_const has no clock to time".into()));
    }
    if stages_per_piece == 0 {
        return Err(RtlError::Synth("a piece needs at least one stage".into()));
    }
    let src = dir.join("src");
    fs::create_dir_all(&src).map_err(io(&src))?;
    let mut reads = String::new();
    for file in op.files() {
        let path = write_atomically(&src.join(file.name), file.text)?;
        reads.push_str(&format!("read_verilog {}; ", ice40::quote(&path)?));
    }
    let top = write_atomically(&src.join("pnr_top.v"), &ice40::wrapper(op, library)?)?;
    reads.push_str(&format!("read_verilog {}; ", ice40::quote(&top)?));
    let script = format!(
        "{reads}hierarchy -top {TOP}; proc; flatten; opt -nosdff -nodffe; write_json {FLAT}"
    );
    let what = format!("the flattening of `{}`", op.module_name());
    let (status, _) = run_limited(
        "yosys",
        "yosys",
        &["-q", "-l", FLAT_LOG, "-p", &script],
        dir,
        timeout,
        &what,
    )?;
    if !status.success() {
        return Err(RtlError::Tool {
            tool: "yosys",
            message: format!(
                "{what} failed ({status}; log: {})",
                dir.join(FLAT_LOG).display()
            ),
        });
    }
    let flat = dir.join(FLAT);
    let text = fs::read_to_string(&flat).map_err(io(&flat))?;
    let netlist = Netlist::parse(&text, TOP, "clk").map_err(|problem| RtlError::Tool {
        tool: "yosys",
        message: format!("{}: {problem}", flat.display()),
    })?;
    let levels = netlist.register_levels();
    let live = netlist.live_cells();
    let before_inputs = netlist.piece(1, 1);
    let mut pieces = Vec::new();
    let mut covered = before_inputs.cells.clone();
    // Level k + 1 is the registers after stage k.
    let mut first = 1;
    while first < levels {
        let last = (first + stages_per_piece - 1).min(levels - 1);
        let piece = netlist.piece(first + 1, last + 1);
        covered.extend(piece.cells.iter().copied());
        let routed = if piece.logic_cells == 0 || piece.inputs == 0 || piece.outputs == 0 {
            None
        } else {
            let d = dir.join(format!("stages-{first}-{last}"));
            fs::create_dir_all(&d).map_err(io(&d))?;
            let json = write_atomically(&d.join("piece.json"), &piece.json)?;
            let harness =
                write_atomically(&d.join("harness.v"), &harness(piece.inputs, piece.outputs))?;
            let reads = format!(
                "read_json {}; read_verilog {}; ",
                ice40::quote(&json)?,
                ice40::quote(&harness)?
            );
            let what = format!("{} stages {first}..{last}", op.module_name());
            Some(ice40::synth_and_route(
                &d, &reads, target_mhz, timeout, &what,
            )?)
        };
        pieces.push(StagePiece {
            first_stage: first,
            last_stage: last,
            coarse_cells: piece.logic_cells,
            flip_flops: piece.flip_flops,
            inputs: piece.inputs,
            outputs: piece.outputs,
            routed,
        });
        first = last + 1;
    }
    Ok(StagedPnrReport {
        module: op.module_name().to_string(),
        latency: op.latency(library),
        register_levels: levels,
        logic_before_the_inputs: before_inputs.logic_cells,
        coarse_cells: netlist.logic_cells(),
        dead_cells: netlist.logic_cells() - live.len(),
        uncovered_cells: live.difference(&covered).count(),
        target_mhz,
        pieces,
        seconds: start.elapsed().as_secs_f64(),
    })
}

/// `pnr_top` around a piece of `inputs` bits in and `outputs` out: a shift register
/// from pin `si` launches the piece's inputs, registers capture its outputs, and a
/// shift register loaded from them (on the registered `load`) shifts them out of pin
/// `so`, so that every bit is used and every path starts and ends at a register.
fn harness(inputs: usize, outputs: usize) -> String {
    let shift = |reg: &str, width: usize, fill: &str| {
        if width == 1 {
            fill.to_string()
        } else {
            format!("{{{reg}[{}:0], {fill}}}", width - 2)
        }
    };
    format!(
        "// Written by rtl::synth::stages (rtprof): a piece of an operator, registered.\n\
         module {TOP} (input clk, input si, input load, output so);\n\
         \x20   reg [{ni}:0] launch;\n\
         \x20   always @(posedge clk) launch <= {sin};\n\
         \x20   wire [{no}:0] d;\n\
         \x20   {PIECE} piece (.{PIECE_CLK}(clk), .{PIECE_IN}(launch), .{PIECE_OUT}(d));\n\
         \x20   reg [{no}:0] capture;\n\
         \x20   always @(posedge clk) capture <= d;\n\
         \x20   reg load_r;\n\
         \x20   always @(posedge clk) load_r <= load;\n\
         \x20   reg [{no}:0] out;\n\
         \x20   always @(posedge clk) out <= load_r ? capture : {sout};\n\
         \x20   assign so = out[{no}];\n\
         endmodule\n",
        ni = inputs - 1,
        no = outputs - 1,
        sin = shift("launch", inputs, "si"),
        sout = shift("out", outputs, "1'b0"),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_harness_shifts_in_and_out() {
        let text = harness(3, 1);
        assert!(text.contains("launch <= {launch[1:0], si};"), "{text}");
        assert!(text.contains("out <= load_r ? capture : 1'b0;"), "{text}");
        assert!(text.contains(".piece_in(launch), .piece_out(d)"), "{text}");
        assert!(harness(1, 2).contains("launch <= si;"));
    }

    fn piece(first: u32, last: u32, fmax: Option<f64>) -> StagePiece {
        StagePiece {
            first_stage: first,
            last_stage: last,
            coarse_cells: 1,
            flip_flops: 0,
            inputs: 1,
            outputs: 1,
            routed: fmax.map(|fmax_mhz| Routed {
                fmax_mhz,
                logic_cells: 10,
                device_logic_cells: 7680,
                synth_seconds: 1.0,
                pnr_seconds: 1.0,
                log: "pnr.log".into(),
            }),
        }
    }

    #[test]
    fn the_operator_is_as_fast_as_its_slowest_piece() {
        let report = StagedPnrReport {
            module: "fp_div".into(),
            latency: 4,
            register_levels: 5,
            logic_before_the_inputs: 0,
            coarse_cells: 4,
            dead_cells: 0,
            uncovered_cells: 0,
            target_mhz: 50.0,
            pieces: vec![
                piece(1, 2, Some(70.0)),
                piece(3, 3, None),
                piece(4, 4, Some(60.0)),
            ],
            seconds: 3.0,
        };
        assert_eq!(report.fmax_mhz(), Some(60.0));
        assert_eq!(report.worst().map(|p| p.first_stage), Some(4));
        assert_eq!(report.stages_covered(), vec![1, 2, 3, 4]);
    }
}
