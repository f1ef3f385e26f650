//! Synthesis with Yosys for Cyclone IV E: the logic cells, flip-flops and memory bits
//! of the RTL's blocks, each with its multiplier logic apart.
//!
//! Timing lives beside it: [`depth`] measures the longest path between registers in
//! LUT levels (Yosys's default script, flattened), [`fmax`] turns it into an estimated
//! clock, [`ice40`] places and routes an operator with nextpnr-ice40 for a measured one,
//! and [`stages`] one larger than the device, stage by stage.
//!
//! [`synthesize`] writes a Yosys script into a directory and runs
//! `yosys -q -l synth.log -s synth.ys` there: `read_verilog` of the files, then
//! `synth_intel -family cycloneive -top <top> -noflatten` with its own (default) LUT
//! mapping, so that the hierarchy is kept and every module is mapped on its own.
//! Yosys's `stat` of the mapped netlist (`stat.txt`) lists each module's own cells; the
//! report rolls the hierarchy up, so that each block asked for gets the figures of one
//! of its instances including its submodules (instance counts times the submodules'
//! figures). Then, from the saved mapped netlist, the whole design and each block asked
//! for are flattened one at a time and `ltp` finds their longest path between
//! registers ([`SynthReport::depth`], as [`depth`] does for an operator synthesized
//! alone):
//!
//! * `lut4`: 4-input look-up tables, `cycloneive_lcell_comb` cells ([`LUT4_CELL`]),
//!   and the inverters the cell map leaves as `$not` ([`INVERTER_CELL`]);
//! * `ff`: flip-flops, `dffeas` cells ([`FF_CELL`]);
//! * `mem_bits`: the bits of the memories the RTL declares (width × depth, from a `stat`
//!   taken before mapping, `stat_rtl.txt`), and `m9k`: the M9K blocks they were mapped
//!   to (`altsyncram` cells, [`M9K_CELL`]). A memory too small for an M9K is built
//!   of flip-flops and then counts in `ff` as well;
//! * `mult_lut4`: the part of `lut4` in instances of the multiplier arrays
//!   ([`MULTIPLIER_MODULES`]: `fp_mul_array`, the significand product of `fp_mul`), so
//!   that the multipliers' cost can be told apart from the rest.
//!
//! Why these numbers are not Quartus's (the thesis's figures come from Quartus with the
//! ALTFP megafunctions):
//!
//! * Yosys's `synth_intel` is experimental. It maps all logic into LUTs in normal
//!   mode (ABC, `abc -lut 4`): no arithmetic-mode carry chains, so an adder or a
//!   comparator costs more cells than in Quartus, where one logic element is one bit
//!   of an adder;
//! * no DSP inference: a `*` is built of LUTs, where Quartus uses the embedded 9 × 9 /
//!   18 × 18 multipliers (no logic cells at all). Hence `mult_lut4`: subtract it to
//!   compare with a Quartus fit;
//! * no ALTFP cores: these are the library's own operators (`rtl/verilog`), written
//!   for clarity and bit-exactness, not the hand-optimised IP cores;
//! * the hierarchy is kept, so nothing is optimised across module boundaries (a few
//!   percent), there is no register retiming (the operators' delay lines stay at
//!   their outputs) and no packing: a logic element of the device holds one LUT and
//!   one flip-flop, so the design needs between max(lut4, ff) and lut4 + ff of them;
//! * ABC's mapping is repeatable for the same input but not stable against unrelated
//!   changes: reading more files, or in another order, moves a figure by a percent or
//!   two (`fp_mul`: 1817 or 1840 LUTs), and so can another Yosys version.
//!
//! One fix-up in the flow: in Yosys 0.23, `synth_intel`'s `opt -full` after the
//! `techmap` can create a coarse `$mux` again (`opt_share`) that nothing maps any more;
//! the script runs `synth_intel` in three parts with a `techmap; opt -fast` before the
//! LUT mapping, so that the netlist is made of device cells only. Any cell that is not
//! a LUT, a flip-flop, an M9K or a module of the design is reported in
//! [`SynthReport::unmapped`].
//!
//! Run time is ABC's. Before issue 38 pipelined the operators, the default script did
//! not finish `fp_div`'s 26-step recurrence (one combinational core) in 20 minutes and
//! this flow used `abc -fast`; pipelined, the whole design goes through the default
//! script (figures in `docs/hardware-model.md`).

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use serde::Serialize;

use crate::RtlError;
use crate::operators::write_atomically;

mod comparison;
pub mod depth;
pub mod fmax;
pub mod ice40;
mod run;
mod stage_cut;
pub mod stages;
pub use comparison::{
    FLOW, SynthComparison, SynthPlan, WHOLE_DESIGN, cache_dir, recall, remember, synthesize_design,
};
pub use depth::{DepthReport, LongestPath, MAX_LUT_LEVELS, logic_depth, operator_depth};
pub use ice40::{PnrReport, place_and_route_ice40};
pub use stages::{StagePiece, StagedPnrReport, place_and_route_stages};

/// The device family passed to `synth_intel`.
pub const FAMILY: &str = "cycloneive";
/// The cell of a 4-input LUT (a logic element's combinational part).
pub const LUT4_CELL: &str = "cycloneive_lcell_comb";
/// What the Cyclone IV E cell map makes of a one-input LUT (an inverter Yosys could
/// not absorb, e.g. the sign flip of `−b` at a module port): Yosys's `$not`. In the
/// device it is one logic element's LUT, so it counts in `lut4`.
pub const INVERTER_CELL: &str = "$not";
/// The cell of a flip-flop (a logic element's register).
pub const FF_CELL: &str = "dffeas";
/// The cell of one M9K block (9216 bits with parity).
pub const M9K_CELL: &str = "altsyncram";
/// The modules whose logic counts as multiplier logic (`mult_lut4`).
pub const MULTIPLIER_MODULES: &[&str] = &["fp_mul_array"];

/// The script, the log and the two `stat` outputs, in the synthesis directory.
const SCRIPT: &str = "synth.ys";
const LOG: &str = "synth.log";
const STAT: &str = "stat.txt";
const STAT_RTL: &str = "stat_rtl.txt";

const INSTALL_HINT: &str =
    "install it with `bash scripts/install-rtl-tools.sh` (Debian: apt-get install yosys)";

/// The synthesis figures of a module, including its submodules.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct SynthFigures {
    /// 4-input LUTs ([`LUT4_CELL`]).
    pub lut4: u64,
    /// Flip-flops ([`FF_CELL`]).
    pub ff: u64,
    /// Bits of the memories the RTL declares (width × depth).
    pub mem_bits: u64,
    /// M9K blocks ([`M9K_CELL`]).
    pub m9k: u64,
    /// The LUTs of `lut4` in multiplier arrays ([`MULTIPLIER_MODULES`]).
    pub mult_lut4: u64,
}

impl SynthFigures {
    /// `self + n × other`.
    fn add_times(&mut self, n: u64, other: &SynthFigures) {
        self.lut4 += n * other.lut4;
        self.ff += n * other.ff;
        self.mem_bits += n * other.mem_bits;
        self.m9k += n * other.m9k;
        self.mult_lut4 += n * other.mult_lut4;
    }
}

/// The figures of one block asked for: one instance of its module, submodules
/// included. A block whose module is instantiated with different parameters has one
/// entry per parameter set.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct BlockFigures {
    /// The name asked for (`fp_mul`).
    pub block: String,
    /// Yosys's name of the module (`$paramod\fp_mul\LATENCY=s32'00…101` when
    /// parameterised).
    pub module: String,
    /// How many instances of the module the design has under the top.
    pub instances: u64,
    /// The figures of one instance.
    pub figures: SynthFigures,
}

/// One module of the synthesized design.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct ModuleFigures {
    /// The module's name without Yosys's parameter decoration (`fp_mul`).
    pub base: String,
    /// Instances under the top (1 for the top).
    pub instances: u64,
    /// The figures of one instance, submodules included.
    pub figures: SynthFigures,
}

/// Cells of one module that are neither a LUT, a flip-flop, an M9K nor a module of
/// the design (cells the flow left unmapped).
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct UnmappedCells {
    pub module: String,
    pub cell: String,
    pub count: u64,
}

/// The outcome of one Yosys run.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SynthReport {
    /// The top module.
    pub top: String,
    /// `synth_intel`'s family ([`FAMILY`]).
    pub family: &'static str,
    /// `yosys -V`.
    pub yosys: String,
    /// The whole design (the top, rolled up).
    pub total: SynthFigures,
    /// The blocks asked for, in the order asked.
    pub blocks: Vec<BlockFigures>,
    /// Every module under the top, by Yosys's name.
    pub modules: BTreeMap<String, ModuleFigures>,
    /// Cells left unmapped (none in a clean run).
    pub unmapped: Vec<UnmappedCells>,
    /// The longest path between registers of the whole design (the top) and of each
    /// module asked for, flattened, by module name.
    pub depth: BTreeMap<String, LongestPath>,
    /// The problems Yosys's `check` passes reported (0 in a clean run).
    pub check_problems: u64,
    /// The distinct warnings of the log (`synth_intel` always warns that it is
    /// experimental).
    pub warnings: Vec<String>,
    /// Wall time of the Yosys run, in seconds.
    pub seconds: f64,
    /// The Yosys log.
    pub log: PathBuf,
}

impl SynthReport {
    /// The figures of `block` (its first parameter set), if it was asked for.
    pub fn block(&self, block: &str) -> Option<&BlockFigures> {
        self.blocks.iter().find(|b| b.block == block)
    }
}

/// A module read as a black box: its ports only (`read_verilog -lib`), so that the
/// logic around its instances is synthesized and measured alone.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BlackBox {
    /// The module's name.
    pub module: String,
    /// The Verilog file that declares it.
    pub file: PathBuf,
}

/// Synthesizes `files` (Verilog) with `top` as the top module for Cyclone IV E in
/// `dir` (created if missing; the script, log and `stat` outputs are written there)
/// and reports the figures of the whole design and of every module named in `blocks`
/// (by plain module name: all of a module's parameter sets are reported).
///
/// Errors when Yosys is not installed ([`RtlError::ToolMissing`]), fails, or a block
/// is not in the design.
pub fn synthesize(
    dir: &Path,
    files: &[PathBuf],
    top: &str,
    blocks: &[&str],
    depth_of: &[&str],
) -> Result<SynthReport, RtlError> {
    synthesize_around(dir, files, &[], top, blocks, depth_of)
}

/// [`synthesize`] with `black_boxes` read by their ports only: their instances count
/// in no figure, and a path ends at a black box's inputs and starts at its outputs as
/// at a register's.
pub fn synthesize_around(
    dir: &Path,
    files: &[PathBuf],
    black_boxes: &[BlackBox],
    top: &str,
    blocks: &[&str],
    depth_of: &[&str],
) -> Result<SynthReport, RtlError> {
    let yosys = yosys_version("yosys")?;
    let boxed: Vec<&str> = black_boxes.iter().map(|b| b.module.as_str()).collect();
    for name in std::iter::once(&top)
        .chain(blocks)
        .chain(depth_of)
        .chain(&boxed)
    {
        if !is_identifier(name) {
            return Err(RtlError::Synth(format!(
                "`{name}` is not a plain Verilog module name"
            )));
        }
    }
    fs::create_dir_all(dir).map_err(io(dir))?;
    let mut absolute = Vec::with_capacity(files.len());
    for file in files {
        absolute.push(std::path::absolute(file).map_err(io(file))?);
    }
    let mut boxes = Vec::with_capacity(black_boxes.len());
    for b in black_boxes {
        boxes.push(BlackBox {
            module: b.module.clone(),
            file: std::path::absolute(&b.file).map_err(io(&b.file))?,
        });
    }
    let text = script(&absolute, &boxes, top, depth_of)?;
    write_atomically(&dir.join(SCRIPT), &text)?;
    let depth_modules: Vec<&str> = std::iter::once(top)
        .chain(depth_of.iter().copied().filter(|m| *m != top))
        .collect();
    let stale = [STAT.to_string(), STAT_RTL.to_string()]
        .into_iter()
        .chain(depth_modules.iter().map(|m| ltp_file(m)));
    for stale in stale {
        let path = dir.join(stale);
        match fs::remove_file(&path) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => return Err(io(&path)(e)),
            _ => {}
        }
    }

    let log = dir.join(LOG);
    let start = Instant::now();
    let out = Command::new("yosys")
        .current_dir(dir)
        .args(["-q", "-l", LOG, "-s", SCRIPT])
        .output()
        .map_err(|e| spawn_error("yosys", &e))?;
    let seconds = start.elapsed().as_secs_f64();
    let log_text = fs::read_to_string(&log).unwrap_or_default();
    if !out.status.success() {
        // The ERROR lines of the log, else the end of what Yosys printed.
        let errors: Vec<&str> = log_text.lines().filter(|l| l.contains("ERROR")).collect();
        let stderr = String::from_utf8_lossy(&out.stderr);
        let detail = if errors.is_empty() {
            let lines: Vec<&str> = stderr.lines().collect();
            lines[lines.len().saturating_sub(20)..].join("\n")
        } else {
            errors.join("\n")
        };
        return Err(RtlError::Tool {
            tool: "yosys",
            message: format!(
                "synthesis of `{top}` failed ({}; log: {}):\n{detail}",
                out.status,
                log.display()
            ),
        });
    }

    let stat = read_stat(&dir.join(STAT))?;
    let stat_rtl = read_stat(&dir.join(STAT_RTL))?;
    let mut report = report_from_stats(top, &stat, &stat_rtl, blocks, &boxed)?;
    for module in depth_modules {
        let path = dir.join(ltp_file(module));
        let text = fs::read_to_string(&path).map_err(io(&path))?;
        let longest = depth::parse_ltp(&text).map_err(|problem| RtlError::Tool {
            tool: "yosys",
            message: format!("{}: {problem}", path.display()),
        })?;
        report.depth.insert(module.to_string(), longest);
    }
    report.yosys = yosys;
    report.check_problems = check_problems(&log_text);
    report.warnings = warnings(&log_text);
    report.seconds = seconds;
    report.log = log;
    Ok(report)
}

/// The Yosys script: read the files (the black boxes' by their ports), synthesize
/// keeping the hierarchy with `synth_intel`'s default LUT mapping, `stat` before and
/// after mapping, then the longest path between registers of the whole design and of
/// each module in `depth_of` (each flattened from the saved mapped netlist,
/// [`LTP_SELECTION`], the black boxes left out like registers).
fn script(
    files: &[PathBuf],
    black_boxes: &[BlackBox],
    top: &str,
    depth_of: &[&str],
) -> Result<String, RtlError> {
    let mut text =
        String::from("# Written by rtl::synth (rtprof): Cyclone IV E, hierarchy kept.\n");
    let reads = files
        .iter()
        .map(|f| ("read_verilog", f))
        .chain(black_boxes.iter().map(|b| ("read_verilog -lib", &b.file)));
    for (read, file) in reads {
        let name = file
            .to_str()
            .ok_or_else(|| RtlError::Synth(format!("{}: not a UTF-8 path", file.display())))?;
        if name.contains(['"', '\n', '\r']) {
            return Err(RtlError::Synth(format!(
                "{}: Yosys scripts cannot name a path with quotes or line breaks",
                file.display()
            )));
        }
        text.push_str(&format!("{read} \"{name}\"\n"));
    }
    // `ltp`'s selection: a black box is an end of a path, like a register.
    let selection = black_boxes.iter().fold(
        LTP_SELECTION.trim_end_matches(" %n").to_string(),
        |sel, b| format!("{sel} t:{} %u", b.module),
    ) + " %n";
    let synth = format!("synth_intel -family {FAMILY} -top {top} -noflatten");
    text.push_str(&format!(
        "{synth} -run :coarse\n\
         tee -o {STAT_RTL} stat\n\
         {synth} -run coarse:map_luts\n\
         # Maps the coarse cells synth_intel's `opt -full` can leave after its techmap.\n\
         techmap\n\
         opt -fast\n\
         # synth_intel's own LUT mapping (ABC's default script).\n\
         abc -lut 4\n\
         clean\n\
         {synth} -run map_cells:\n\
         tee -o {STAT} stat\n\
         design -save mapped\n\
         flatten\n\
         tee -o {} ltp -noff {selection}\n",
        ltp_file(top)
    ));
    for module in depth_of.iter().filter(|m| **m != top) {
        text.push_str(&format!(
            "design -load mapped\n\
             hierarchy -top {module}\n\
             flatten\n\
             tee -o {} ltp -noff {selection}\n",
            ltp_file(module)
        ));
    }
    Ok(text)
}

/// `ltp`'s selection: every cell but the device's registers and memory blocks (`-noff`
/// knows only Yosys's own flip-flop types, and an M9K's read is registered), so that a
/// path runs from a register, memory or input to a register, memory or output and its
/// length is the number of LUTs on it.
pub(super) const LTP_SELECTION: &str = "t:dffeas t:altsyncram %u %n";

/// Where the longest path of `module` is written in the synthesis directory.
fn ltp_file(module: &str) -> String {
    format!("ltp-{module}.txt")
}

/// `yosys -V` of `program`, or why it cannot be run.
fn yosys_version(program: &str) -> Result<String, RtlError> {
    let out = Command::new(program)
        .arg("-V")
        .output()
        .map_err(|e| spawn_error("yosys", &e))?;
    if !out.status.success() {
        return Err(RtlError::Tool {
            tool: "yosys",
            message: format!("`{program} -V` failed ({})", out.status),
        });
    }
    Ok(String::from_utf8_lossy(&out.stdout).trim().to_string())
}

fn spawn_error(tool: &'static str, e: &std::io::Error) -> RtlError {
    if e.kind() == std::io::ErrorKind::NotFound {
        RtlError::ToolMissing {
            tool,
            hint: INSTALL_HINT,
        }
    } else {
        RtlError::Tool {
            tool,
            message: format!("cannot run it: {e}"),
        }
    }
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> RtlError + '_ {
    move |source| RtlError::Io {
        path: path.to_path_buf(),
        source,
    }
}

fn is_identifier(name: &str) -> bool {
    let mut chars = name.chars();
    chars
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '$')
}

/// One module's own cells, as `stat` lists them.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
struct ModuleStat {
    /// Cells by type: device cells and instances of the design's modules alike.
    cells: BTreeMap<String, u64>,
    /// `Number of memory bits`.
    memory_bits: u64,
}

fn read_stat(path: &Path) -> Result<BTreeMap<String, ModuleStat>, RtlError> {
    let text = fs::read_to_string(path).map_err(io(path))?;
    parse_stat(&text).map_err(|problem| RtlError::Tool {
        tool: "yosys",
        message: format!("{}: {problem}", path.display()),
    })
}

/// Parses the text of Yosys's `stat`: one `=== <module> ===` section per module (the
/// `design hierarchy` section is skipped), each with its `Number of memory bits` and,
/// after `Number of cells`, one `<cell type> <count>` line per cell type.
fn parse_stat(text: &str) -> Result<BTreeMap<String, ModuleStat>, String> {
    let mut modules = BTreeMap::new();
    // The module being read, and whether its cell list has begun.
    let mut current: Option<(String, ModuleStat, bool)> = None;
    for (n, line) in text.lines().enumerate() {
        let trimmed = line.trim();
        if let Some(name) = trimmed
            .strip_prefix("=== ")
            .and_then(|rest| rest.strip_suffix(" ==="))
        {
            if let Some((name, stat, _)) = current.take() {
                modules.insert(name, stat);
            }
            if name != "design hierarchy" {
                current = Some((name.to_string(), ModuleStat::default(), false));
            }
            continue;
        }
        let Some((_, stat, in_cells)) = current.as_mut() else {
            continue;
        };
        if trimmed.is_empty() {
            continue;
        }
        let (key, count) = trimmed
            .rsplit_once(char::is_whitespace)
            .ok_or_else(|| format!("line {}: no count in `{trimmed}`", n + 1))?;
        let count: u64 = count
            .parse()
            .map_err(|_| format!("line {}: `{count}` is not a count", n + 1))?;
        let key = key.trim_end();
        if let Some(field) = key.strip_suffix(':') {
            match field {
                "Number of memory bits" => stat.memory_bits = count,
                "Number of cells" => *in_cells = true,
                _ => {}
            }
        } else if *in_cells {
            *stat.cells.entry(key.to_string()).or_default() += count;
        } else {
            return Err(format!("line {}: unexpected `{trimmed}`", n + 1));
        }
    }
    if let Some((name, stat, _)) = current {
        modules.insert(name, stat);
    }
    if modules.is_empty() {
        return Err("no module statistics".into());
    }
    Ok(modules)
}

/// A module's name without Yosys's parameter decoration:
/// `$paramod\fp_mul\LATENCY=s32'…` and `$paramod$<hash>\fp_delay` are `fp_mul` and
/// `fp_delay`.
fn base_name(module: &str) -> &str {
    let module = module.strip_prefix('\\').unwrap_or(module);
    match module.strip_prefix("$paramod") {
        Some(rest) if rest.starts_with('$') => rest.split_once('\\').map_or(rest, |(_, n)| n),
        Some(rest) => {
            let rest = rest.strip_prefix('\\').unwrap_or(rest);
            rest.split_once('\\').map_or(rest, |(n, _)| n)
        }
        None => module,
    }
}

/// Rolls the final `stat` (and the memory bits of the `stat` before mapping) up from
/// `top`; the blocks are matched by plain module name; instances of `black_boxes`
/// count in no figure.
fn report_from_stats(
    top: &str,
    stat: &BTreeMap<String, ModuleStat>,
    stat_rtl: &BTreeMap<String, ModuleStat>,
    blocks: &[&str],
    black_boxes: &[&str],
) -> Result<SynthReport, RtlError> {
    if !stat.contains_key(top) {
        return Err(RtlError::Synth(format!(
            "the top module `{top}` is not in Yosys's statistics"
        )));
    }
    // Depth-first from the top: post-order (submodules before their parents).
    let mut order: Vec<&str> = Vec::new();
    let mut done: BTreeSet<&str> = BTreeSet::new();
    let mut on_path: Vec<&str> = Vec::new();
    visit(top, stat, &mut order, &mut done, &mut on_path)?;

    let mut figures: BTreeMap<&str, SynthFigures> = BTreeMap::new();
    let mut unmapped = Vec::new();
    for &module in &order {
        let cells = &stat[module].cells;
        let mut f = SynthFigures {
            mem_bits: stat_rtl.get(module).map_or(0, |s| s.memory_bits),
            ..SynthFigures::default()
        };
        for (cell, &count) in cells {
            match cell.as_str() {
                LUT4_CELL | INVERTER_CELL => f.lut4 += count,
                FF_CELL => f.ff += count,
                M9K_CELL => f.m9k += count,
                sub if stat.contains_key(sub) => f.add_times(count, &figures[sub]),
                boxed if black_boxes.contains(&base_name(boxed)) => {}
                _ => unmapped.push(UnmappedCells {
                    module: module.to_string(),
                    cell: cell.clone(),
                    count,
                }),
            }
        }
        if MULTIPLIER_MODULES.contains(&base_name(module)) {
            f.mult_lut4 = f.lut4;
        }
        figures.insert(module, f);
    }

    // Instances: from the top down (reverse post-order: parents before submodules).
    let mut instances: BTreeMap<&str, u64> = BTreeMap::from([(top, 1)]);
    for &module in order.iter().rev() {
        let n = instances.get(module).copied().unwrap_or(0);
        for (cell, &count) in &stat[module].cells {
            if let Some((sub, _)) = stat.get_key_value(cell.as_str()) {
                *instances.entry(sub.as_str()).or_default() += n * count;
            }
        }
    }

    let modules: BTreeMap<String, ModuleFigures> = order
        .iter()
        .map(|&m| {
            (
                m.to_string(),
                ModuleFigures {
                    base: base_name(m).to_string(),
                    instances: instances.get(m).copied().unwrap_or(0),
                    figures: figures[m],
                },
            )
        })
        .collect();
    let mut block_figures = Vec::new();
    for &block in blocks {
        let found: Vec<BlockFigures> = modules
            .iter()
            .filter(|(_, m)| m.base == block)
            .map(|(name, m)| BlockFigures {
                block: block.to_string(),
                module: name.clone(),
                instances: m.instances,
                figures: m.figures,
            })
            .collect();
        if found.is_empty() {
            return Err(RtlError::Synth(format!(
                "the block `{block}` is not a module of the design under `{top}`"
            )));
        }
        block_figures.extend(found);
    }
    Ok(SynthReport {
        top: top.to_string(),
        family: FAMILY,
        yosys: String::new(),
        total: figures[top],
        blocks: block_figures,
        modules,
        unmapped,
        depth: BTreeMap::new(),
        check_problems: 0,
        warnings: Vec::new(),
        seconds: 0.0,
        log: PathBuf::new(),
    })
}

/// Post-order depth-first walk of the hierarchy; errors on a cycle.
fn visit<'a>(
    module: &'a str,
    stat: &'a BTreeMap<String, ModuleStat>,
    order: &mut Vec<&'a str>,
    done: &mut BTreeSet<&'a str>,
    on_path: &mut Vec<&'a str>,
) -> Result<(), RtlError> {
    if done.contains(module) {
        return Ok(());
    }
    if on_path.contains(&module) {
        return Err(RtlError::Synth(format!(
            "the module hierarchy has a cycle through `{module}`"
        )));
    }
    let Some((module, own)) = stat.get_key_value(module) else {
        return Ok(());
    };
    on_path.push(module);
    for cell in own.cells.keys() {
        if stat.contains_key(cell.as_str()) {
            visit(cell, stat, order, done, on_path)?;
        }
    }
    on_path.pop();
    done.insert(module);
    order.push(module);
    Ok(())
}

/// The sum of the `Found and reported N problems.` lines of the log.
fn check_problems(log: &str) -> u64 {
    log.lines()
        .filter_map(|l| {
            l.trim()
                .strip_prefix("Found and reported ")?
                .strip_suffix(" problems.")?
                .parse::<u64>()
                .ok()
        })
        .sum()
}

/// The distinct `Warning:` lines of the log, in order.
fn warnings(log: &str) -> Vec<String> {
    let mut seen = BTreeSet::new();
    log.lines()
        .map(str::trim)
        .filter(|l| l.starts_with("Warning:"))
        .filter(|l| seen.insert(*l))
        .map(str::to_string)
        .collect()
}

#[cfg(test)]
mod tests;
