//! Logic depth: the longest path between registers of one module after Yosys's default
//! Cyclone IV E synthesis, in LUT levels, with its LUT4 and flip-flop counts.
//!
//! [`logic_depth`] runs, in a directory of its own,
//!
//! ```text
//! read_verilog <files>
//! chparam -set <parameter> <value> <top>      (for each parameter asked for)
//! synth_intel -family cycloneive -top <top>   (flattened, ABC's default `abc -lut 4`)
//! tee -o stat.txt stat
//! tee -o ltp.txt ltp -noff t:dffeas %n
//! ```
//!
//! `ltp` counts the cells of the longest topological path. Its `-noff` only knows
//! Yosys's own flip-flop types, not the device's `dffeas`, so the selection leaves the
//! `dffeas` cells out: a path then starts at an input port or a register output and ends
//! at an output port or a register input, and its length is the number of LUTs on it
//! (a `$not` the cell map left is one LUT of the device, and counts). Unlike `hw synth`
//! (which maps with `abc -fast`), this is the default script: its rewriting (`dc2`)
//! trades depth for area, which is what a real flow's timing would meet.
//!
//! [`crate::synth::fmax`] turns the depth into an estimated clock.

use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};
use std::time::Duration;

use hwmodel::library::Library;
use serde::Serialize;

use super::run::run_limited;
use super::{
    FAMILY, FF_CELL, INVERTER_CELL, LTP_SELECTION, LUT4_CELL, io, is_identifier, parse_stat,
};
use crate::RtlError;
use crate::operators::{Operator, write_atomically};

/// The goal for every operator and block (issue 38): at most this many LUT levels
/// between two registers.
pub const MAX_LUT_LEVELS: u64 = 12;

const SCRIPT: &str = "depth.ys";
const LOG: &str = "depth.log";
const STAT: &str = "stat.txt";
const LTP: &str = "ltp.txt";

/// The depth and size of one synthesized module.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DepthReport {
    /// The top module.
    pub top: String,
    /// The parameters set on it (`LATENCY`).
    pub parameters: Vec<(String, i64)>,
    /// LUT levels on the longest path between registers (or ports).
    pub levels: u64,
    /// Where that path starts and ends (Yosys's names).
    pub from: String,
    pub to: String,
    /// 4-input LUTs (`cycloneive_lcell_comb` and `$not`).
    pub lut4: u64,
    /// Flip-flops (`dffeas`).
    pub ff: u64,
    /// Any other cell the flow left (none in a clean run), by type.
    pub other_cells: BTreeMap<String, u64>,
    /// Wall time of the Yosys run, in seconds.
    pub seconds: f64,
    /// The Yosys log.
    pub log: PathBuf,
}

impl DepthReport {
    /// The estimated Fmax on Cyclone IV E of this depth ([`super::fmax`]).
    pub fn estimated_fmax_mhz(&self) -> f64 {
        super::fmax::CYCLONE_IV_E.fmax_mhz(self.levels)
    }
}

/// Synthesizes `files` with `top` (its `parameters` set) in `dir` and reports the
/// longest path between registers in LUT levels. A run longer than `timeout` is
/// stopped and reported as an error.
pub fn logic_depth(
    dir: &Path,
    files: &[PathBuf],
    top: &str,
    parameters: &[(&str, i64)],
    timeout: Duration,
) -> Result<DepthReport, RtlError> {
    for name in std::iter::once(&top).chain(parameters.iter().map(|(p, _)| p)) {
        if !is_identifier(name) {
            return Err(RtlError::Synth(format!(
                "`{name}` is not a plain Verilog identifier"
            )));
        }
    }
    fs::create_dir_all(dir).map_err(io(dir))?;
    let mut text =
        String::from("# Written by rtl::synth::depth (rtprof): logic depth, Cyclone IV E.\n");
    for file in files {
        let path = std::path::absolute(file).map_err(io(file))?;
        let name = path
            .to_str()
            .filter(|n| !n.contains(['"', '\n', '\r']))
            .ok_or_else(|| {
                RtlError::Synth(format!("{}: unusable in a Yosys script", file.display()))
            })?
            .to_string();
        text.push_str(&format!("read_verilog \"{name}\"\n"));
    }
    for (p, v) in parameters {
        text.push_str(&format!("chparam -set {p} {v} {top}\n"));
    }
    text.push_str(&format!(
        "synth_intel -family {FAMILY} -top {top}\n\
         tee -o {STAT} stat\n\
         # -noff does not know dffeas: leave the registers out of the selection.\n\
         tee -o {LTP} ltp -noff {LTP_SELECTION}\n"
    ));
    write_atomically(&dir.join(SCRIPT), &text)?;
    for stale in [STAT, LTP] {
        let path = dir.join(stale);
        match fs::remove_file(&path) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => return Err(io(&path)(e)),
            _ => {}
        }
    }

    let (status, seconds) = run_limited(
        "yosys",
        "yosys",
        &["-q", "-l", LOG, "-s", SCRIPT],
        dir,
        timeout,
        &format!("the depth synthesis of `{top}`"),
    )?;
    let log = dir.join(LOG);
    if !status.success() {
        let log_text = fs::read_to_string(&log).unwrap_or_default();
        let errors: Vec<&str> = log_text.lines().filter(|l| l.contains("ERROR")).collect();
        return Err(RtlError::Tool {
            tool: "yosys",
            message: format!(
                "depth synthesis of `{top}` failed ({status}; log: {}):\n{}",
                log.display(),
                errors.join("\n")
            ),
        });
    }
    let stat_path = dir.join(STAT);
    let stat_text = fs::read_to_string(&stat_path).map_err(io(&stat_path))?;
    let ltp_path = dir.join(LTP);
    let ltp_text = fs::read_to_string(&ltp_path).map_err(io(&ltp_path))?;
    let tool_error = |message: String| RtlError::Tool {
        tool: "yosys",
        message,
    };
    let stat =
        parse_stat(&stat_text).map_err(|p| tool_error(format!("{}: {p}", stat_path.display())))?;
    let path =
        parse_ltp(&ltp_text).map_err(|p| tool_error(format!("{}: {p}", ltp_path.display())))?;
    let (mut lut4, mut ff, mut other_cells) = (0, 0, BTreeMap::new());
    // Flattened: one module.
    for module in stat.values() {
        for (cell, &count) in &module.cells {
            match cell.as_str() {
                LUT4_CELL | INVERTER_CELL => lut4 += count,
                FF_CELL => ff += count,
                _ => *other_cells.entry(cell.clone()).or_default() += count,
            }
        }
    }
    Ok(DepthReport {
        top: top.to_string(),
        parameters: parameters
            .iter()
            .map(|(p, v)| ((*p).to_string(), *v))
            .collect(),
        levels: path.levels,
        from: path.from,
        to: path.to,
        lut4,
        ff,
        other_cells,
        seconds,
        log,
    })
}

/// The depth of `op` at its latency in `library`: its sources are written to `dir`
/// and synthesized with it as the top.
pub fn operator_depth(
    op: Operator,
    library: &Library,
    dir: &Path,
    timeout: Duration,
) -> Result<DepthReport, RtlError> {
    let src = dir.join("src");
    fs::create_dir_all(&src).map_err(io(&src))?;
    let mut files = Vec::new();
    for file in op.files() {
        files.push(write_atomically(&src.join(file.name), file.text)?);
    }
    let parameters: Vec<(&str, i64)> = op
        .parameters(library)
        .into_iter()
        .map(|(p, v)| (p, i64::from(v)))
        .collect();
    logic_depth(dir, &files, op.module_name(), &parameters, timeout)
}

/// The longest path `ltp` printed: its length in LUT levels and its ends (Yosys's
/// names).
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct LongestPath {
    pub levels: u64,
    pub from: String,
    pub to: String,
}

/// Parses `ltp`'s output: `Longest topological path in <module> (length=N):` and the
/// numbered nodes of the path, `  k: <wire or cell> (via <wire>)`.
pub(super) fn parse_ltp(text: &str) -> Result<LongestPath, String> {
    let length = text
        .lines()
        .find_map(|l| {
            l.split_once("(length=")
                .and_then(|(_, rest)| rest.split_once(')'))
                .map(|(n, _)| n.to_string())
        })
        .ok_or("no `Longest topological path` line")?;
    let length: u64 = length
        .parse()
        .map_err(|_| format!("`{length}` is not a length"))?;
    let nodes: Vec<&str> = text
        .lines()
        .filter_map(|l| {
            let (index, rest) = l.trim_start().split_once(": ")?;
            index.parse::<u64>().ok()?;
            Some(rest.split(" (via ").next().unwrap_or(rest).trim())
        })
        .collect();
    if nodes.len() as u64 != length + 1 {
        return Err(format!(
            "a path of length {length} lists {} nodes, not {}",
            nodes.len(),
            length + 1
        ));
    }
    Ok(LongestPath {
        levels: length,
        from: nodes.first().map_or(String::new(), |s| s.to_string()),
        to: nodes.last().map_or(String::new(), |s| s.to_string()),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    // The `ltp` output of a real run (Yosys 0.23) on fp_compare before issue 38, cell
    // names shortened.
    const LTP_SAMPLE: &str = "
5. Executing LTP pass (find longest path).

Longest topological path in fp_compare (length=3):
    0: \\b [29]
    1: $techmap1003$abc$859.A [1] (via $abc$859$865)
    2: $techmap1005$abc$859.A [2] (via $abc$859$934)
    3: \\delay.genblk1.g_chain.r [0] (via $auto$ff.cc:266:slice$331)
";

    #[test]
    fn the_longest_path_is_read_with_its_ends() {
        let path = parse_ltp(LTP_SAMPLE).unwrap();
        assert_eq!(path.levels, 3);
        assert_eq!(path.from, "\\b [29]");
        assert_eq!(path.to, "\\delay.genblk1.g_chain.r [0]");
    }

    #[test]
    fn a_path_whose_nodes_do_not_match_its_length_is_an_error() {
        let broken = LTP_SAMPLE.replace("length=3", "length=4");
        assert!(parse_ltp(&broken).is_err());
        assert!(parse_ltp("nothing here").is_err());
    }
}
