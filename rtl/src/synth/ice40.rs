//! Real place-and-route timing: one operator, its inputs registered, through Yosys's
//! `synth_ice40` and nextpnr-ice40 on an iCE40 HX8K, and the Fmax nextpnr reports.
//!
//! An open, timing-driven flow on a smaller and slower device than the thesis's
//! Cyclone IV E (iCE40 logic cells are 4-input LUTs too, with a carry chain that
//! `synth_ice40` uses), so its Fmax is a conservative bound for the operator's logic
//! between registers, with real placement and routing delays instead of the per-level
//! estimate of [`super::fmax`].
//!
//! [`place_and_route_ice40`] writes a wrapper `pnr_top` that registers every input of
//! the operator (so that the first stage's paths start at registers, as they do in the
//! pipeline) and runs, in a directory of its own:
//!
//! ```text
//! yosys -p "read_verilog ...; synth_ice40 -top pnr_top -json pnr.json"
//! nextpnr-ice40 --hx8k --package ct256 --json pnr.json --freq <MHz> --timing-allow-fail \
//!     --seed 1 -l pnr.log
//! ```
//!
//! nextpnr places the I/O itself (no constraints file); the clock's Fmax is the last
//! `Max frequency for clock` line of its log (the one after routing). An operator
//! larger than the device is placed and routed stage by stage instead
//! ([`super::stages`]), through the same `synth_and_route`.

use std::fs;
use std::path::{Path, PathBuf};
use std::time::Duration;

use hwmodel::library::Library;
use serde::Serialize;

use super::io;
use super::run::run_limited;
use crate::RtlError;
use crate::operators::{Operator, write_atomically};

/// The device and package nextpnr places on.
pub const DEVICE: &str = "hx8k";
pub const PACKAGE: &str = "ct256";

/// The top module of every design placed and routed here.
pub(super) const TOP: &str = "pnr_top";
const JSON: &str = "pnr.json";
const YOSYS_LOG: &str = "yosys.log";
const PNR_LOG: &str = "pnr.log";

/// What nextpnr reports for one operator.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PnrReport {
    /// The operator's module.
    pub module: String,
    /// Its LATENCY.
    pub latency: u32,
    /// The clock nextpnr was asked to meet, MHz.
    pub target_mhz: f64,
    /// What the run measured: Fmax, logic cells, times, the log.
    #[serde(flatten)]
    pub routed: Routed,
}

/// Places and routes `op` at its latency in `library`, inputs registered, aiming at
/// `target_mhz`; each tool may take at most `timeout`.
pub fn place_and_route_ice40(
    op: Operator,
    library: &Library,
    dir: &Path,
    target_mhz: f64,
    timeout: Duration,
) -> Result<PnrReport, RtlError> {
    if op == Operator::Const {
        return Err(RtlError::Synth("fp_const has no clock to time".into()));
    }
    let src = dir.join("src");
    fs::create_dir_all(&src).map_err(io(&src))?;
    let mut reads = String::new();
    for file in op.files() {
        let path = write_atomically(&src.join(file.name), file.text)?;
        reads.push_str(&format!("read_verilog {}; ", quote(&path)?));
    }
    let top = write_atomically(&src.join("pnr_top.v"), &wrapper(op, library)?)?;
    reads.push_str(&format!("read_verilog {}; ", quote(&top)?));
    let routed = synth_and_route(dir, &reads, target_mhz, timeout, op.module_name())?;
    Ok(PnrReport {
        module: op.module_name().to_string(),
        latency: op.latency(library),
        target_mhz,
        routed,
    })
}

/// What one run of `synth_and_route` measured.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Routed {
    /// The Fmax after routing, MHz.
    pub fmax_mhz: f64,
    /// Logic cells used and the device's.
    pub logic_cells: u64,
    pub device_logic_cells: u64,
    /// Wall time of synthesis and of place and route, seconds.
    pub synth_seconds: f64,
    pub pnr_seconds: f64,
    /// nextpnr's log.
    pub log: PathBuf,
}

/// Runs, in `dir`, `<reads>synth_ice40 -top pnr_top` and nextpnr-ice40 on the HX8K at
/// `target_mhz` (`--timing-allow-fail`: a design that misses the target still gets its
/// Fmax), each tool within `timeout`; `what` names the design in errors. The reads
/// must define a module `pnr_top`.
pub(super) fn synth_and_route(
    dir: &Path,
    reads: &str,
    target_mhz: f64,
    timeout: Duration,
    what: &str,
) -> Result<Routed, RtlError> {
    let script = format!("{reads}synth_ice40 -top {TOP} -json {JSON}");
    let (status, synth_seconds) = run_limited(
        "yosys",
        "yosys",
        &["-q", "-l", YOSYS_LOG, "-p", &script],
        dir,
        timeout,
        &format!("synth_ice40 of `{what}`"),
    )?;
    if !status.success() {
        return Err(RtlError::Tool {
            tool: "yosys",
            message: format!(
                "synth_ice40 of `{what}` failed ({status}; log: {})",
                dir.join(YOSYS_LOG).display()
            ),
        });
    }
    let freq = format!("{target_mhz}");
    let (status, pnr_seconds) = run_limited(
        "nextpnr-ice40",
        "nextpnr-ice40",
        &[
            &format!("--{DEVICE}"),
            "--package",
            PACKAGE,
            "--json",
            JSON,
            "--freq",
            &freq,
            "--timing-allow-fail",
            "--seed",
            "1",
            "-l",
            PNR_LOG,
        ],
        dir,
        timeout,
        &format!("nextpnr-ice40 of `{what}`"),
    )?;
    let log = dir.join(PNR_LOG);
    let text = fs::read_to_string(&log).map_err(io(&log))?;
    if !status.success() {
        let errors: Vec<&str> = text.lines().filter(|l| l.contains("ERROR")).collect();
        return Err(RtlError::Tool {
            tool: "nextpnr-ice40",
            message: format!(
                "place and route of `{what}` failed ({status}; log: {}):\n{}",
                log.display(),
                errors.join("\n")
            ),
        });
    }
    let (fmax_mhz, logic_cells, device_logic_cells) =
        parse_log(&text).map_err(|problem| RtlError::Tool {
            tool: "nextpnr-ice40",
            message: format!("{}: {problem}", log.display()),
        })?;
    Ok(Routed {
        fmax_mhz,
        logic_cells,
        device_logic_cells,
        synth_seconds,
        pnr_seconds,
        log,
    })
}

pub(super) fn quote(path: &Path) -> Result<String, RtlError> {
    let absolute = std::path::absolute(path).map_err(io(path))?;
    absolute
        .to_str()
        .filter(|n| !n.contains(['"', '\n', '\r', ';', ' ']))
        .map(|n| format!("\"{n}\""))
        .ok_or_else(|| RtlError::Synth(format!("{}: unusable in a Yosys command", path.display())))
}

/// The width of one of an operator's ports (see [`Operator::ports`]).
fn port_width(op: Operator, port: &str) -> u32 {
    match (op, port) {
        (_, "clk" | "sub" | "sel" | "lt") => 1,
        (Operator::ToU8, "y") => 8,
        _ => 32,
    }
}

/// `pnr_top`: the operator at its library latency with every input registered.
pub(super) fn wrapper(op: Operator, library: &Library) -> Result<String, RtlError> {
    let ports = op.ports();
    let (output, inputs) = ports.split_last().unwrap_or((&"y", &[]));
    let data: Vec<&str> = inputs.iter().copied().filter(|p| *p != "clk").collect();
    let mut decl = vec!["input clk".to_string()];
    let mut regs = String::new();
    let mut connections: Vec<(String, String)> = vec![("clk".into(), "clk".into())];
    for p in &data {
        let w = port_width(op, p);
        decl.push(format!("input [{}:0] {p}", w - 1));
        regs.push_str(&format!(
            "    reg [{}:0] r_{p};\n    always @(posedge clk) r_{p} <= {p};\n",
            w - 1
        ));
        connections.push(((*p).to_string(), format!("r_{p}")));
    }
    let w = port_width(op, output);
    decl.push(format!("output [{}:0] {output}", w - 1));
    connections.push(((*output).to_string(), (*output).to_string()));
    let pairs: Vec<(&str, &str)> = connections
        .iter()
        .map(|(p, e)| (p.as_str(), e.as_str()))
        .collect();
    let instance = op.instance(library, "dut", &[], &pairs)?;
    Ok(format!(
        "// Written by rtl::synth::ice40 (rtprof): {} with registered inputs.\n\
         module {TOP} (\n    {}\n);\n{regs}    {instance}\nendmodule\n",
        op.module_name(),
        decl.join(",\n    ")
    ))
}

/// The Fmax after routing (the last `Max frequency for clock` line) and the logic
/// cells (`ICESTORM_LC: used/ total`) of a nextpnr-ice40 log.
fn parse_log(text: &str) -> Result<(f64, u64, u64), String> {
    let fmax = text
        .lines()
        .filter_map(|l| {
            let rest = l.split_once("Max frequency for clock")?.1;
            let mhz = rest.split_once("': ")?.1.split_once(" MHz")?.0;
            mhz.trim().parse::<f64>().ok()
        })
        .next_back()
        .ok_or("no `Max frequency for clock` line")?;
    let cells = text
        .lines()
        .find_map(|l| {
            let rest = l.split_once("ICESTORM_LC:")?.1;
            let (used, total) = rest.split_once('/')?;
            let total = total.split_whitespace().next()?;
            Some((used.trim().parse::<u64>().ok()?, total.parse::<u64>().ok()?))
        })
        .ok_or("no `ICESTORM_LC` utilisation line")?;
    Ok((fmax, cells.0, cells.1))
}

#[cfg(test)]
mod tests {
    use super::*;

    // Lines of a real nextpnr-ice40 0.4 log (fp_mul, LATENCY 5, inputs registered).
    const LOG: &str = "\
Info: Device utilisation:
Info: \t         ICESTORM_LC:  2364/ 7680    30%
Info: Max frequency for clock 'clk$SB_IO_IN_$glb_clk': 84.81 MHz (PASS at 50.00 MHz)
Info: Critical path report for clock 'clk$SB_IO_IN_$glb_clk' (posedge -> posedge):
Info: Max frequency for clock 'clk$SB_IO_IN_$glb_clk': 86.16 MHz (PASS at 50.00 MHz)
";

    #[test]
    fn the_routed_fmax_and_the_cells_are_read() {
        assert_eq!(parse_log(LOG).unwrap(), (86.16, 2364, 7680));
        assert!(parse_log("Info: nothing").is_err());
    }

    #[test]
    fn the_wrapper_registers_every_input() {
        let lib = Library::cyclone_iv_e();
        let text = wrapper(Operator::AddSub, &lib).unwrap();
        for p in ["a", "b", "sub"] {
            assert!(text.contains(&format!("r_{p} <= {p};")), "{text}");
            assert!(text.contains(&format!(".{p}(r_{p})")), "{text}");
        }
        assert!(text.contains("input [0:0] sub") && text.contains("output [31:0] y"));
        let text = wrapper(Operator::Compare, &lib).unwrap();
        assert!(text.contains("output [0:0] lt"), "{text}");
    }
}
