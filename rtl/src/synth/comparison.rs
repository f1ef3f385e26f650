//! A design through Yosys and held against the model: [`SynthPlan`] generates the
//! design's RTL into a work directory and picks the top and the blocks to report
//! (the whole design, or one block alone), [`synthesize_design`] runs it, and
//! [`SynthComparison`] joins each block's Yosys figures with the model's resources and
//! the thesis's table 8 (`rtprof hw synth`).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use hwmodel::blocks::Pipeline;
use hwmodel::design::Design;
use hwmodel::library::{Library, Resources};
use hwmodel::table::Figures;

use super::{SynthFigures, SynthReport, synthesize};
use crate::RtlError;
use crate::generate::{self, TOP};
use crate::sim::depth_bits_for;

/// Why Yosys's figures are not Quartus's (the thesis's) nor the model's.
pub const SYNTH_REASONS: &str = "\
Why the columns differ:
  - Yosys's synth_intel (experimental) maps logic to LUT4s without arithmetic-mode carry
    chains: an adder or comparator costs more cells than in Quartus (one LE per bit).
  - No DSP inference: multipliers are built of LUTs (mult LUT4) where Quartus uses the
    embedded 9x9 multipliers; subtract them to compare with the LE columns.
  - These are rtprof's own operators (rtl/verilog), not the ALTFP cores the model's
    library rows (table 7) were measured on: pipelined in their stages with prefix
    adders (add/sub: 508 FF where ALTFP_ADD_SUB has 415 registers), with the divider
    and the inverse square root as digit recurrences (15 and 28 cycles) where the
    ALTFP cores use tables and embedded multipliers.
  - A logic element holds one LUT4 and one flip-flop: the design needs between
    max(LUT4, FF) and LUT4 + FF of them.
  - The minimum-distance block carries its payload 3 cycles beside the compare (the
    model holds its inputs instead), and the top adds the iterator, scene memory ports
    and control delay lines, which the table's blocks do not include.";

/// A synthesis ready to run: the design's Verilog written into `work`, the top and
/// the blocks to report.
#[derive(Clone, Debug)]
pub struct SynthPlan {
    pub design: Design,
    /// Where Yosys works (script, log, statistics) and the Verilog is written.
    pub work: PathBuf,
    /// The top module: the whole design's, or the one block's.
    pub top: String,
    /// The blocks reported, in the pipeline's order.
    pub blocks: Vec<String>,
    /// One block alone (`--block`), not the whole design.
    pub one_block: bool,
    files: Vec<PathBuf>,
}

impl SynthPlan {
    /// Generates the RTL of `pipeline` (with the smallest scene memory) into `work`;
    /// `block` names one block to synthesize alone. An unknown block is refused before
    /// anything is written.
    pub fn prepare(
        lib: &Library,
        pipeline: &Pipeline,
        block: Option<&str>,
        work: &Path,
    ) -> Result<SynthPlan, RtlError> {
        let rtl = generate::generate(lib, pipeline, depth_bits_for(0))?;
        let names: Vec<&str> = rtl.blocks.iter().map(|b| b.name).collect();
        let (top, blocks) = match block {
            Some(b) => {
                let Some(name) = names.iter().find(|n| **n == b) else {
                    return Err(RtlError::UnknownBlock {
                        block: b.to_string(),
                        design: pipeline.design.label(),
                        names: names.join(", "),
                    });
                };
                (name.to_string(), vec![name.to_string()])
            }
            None => (
                TOP.to_string(),
                names.iter().map(|n| n.to_string()).collect(),
            ),
        };
        generate::write(&rtl, work)?;
        let files = rtl
            .files
            .iter()
            .filter(|(n, _)| n.ends_with(".v"))
            .map(|(n, _)| work.join(n))
            .collect();
        Ok(SynthPlan {
            design: pipeline.design,
            work: work.to_path_buf(),
            top,
            blocks,
            one_block: block.is_some(),
            files,
        })
    }

    /// Runs Yosys ([`synthesize`]).
    pub fn run(&self) -> Result<SynthReport, RtlError> {
        let blocks: Vec<&str> = self.blocks.iter().map(String::as_str).collect();
        synthesize(&self.work, &self.files, &self.top, &blocks)
    }
}

/// Synthesizes `pipeline`'s design (or its `block` alone) in `work`: the one way the
/// command line and the tests run a design through Yosys.
pub fn synthesize_design(
    lib: &Library,
    pipeline: &Pipeline,
    block: Option<&str>,
    work: &Path,
) -> Result<SynthReport, RtlError> {
    SynthPlan::prepare(lib, pipeline, block, work)?.run()
}

/// One block's figures three ways (`None`: that source has none for it).
#[derive(Clone, Debug, PartialEq)]
pub struct ComparisonRow {
    pub name: String,
    pub yosys: Option<SynthFigures>,
    pub model: Option<Resources>,
    pub thesis: Option<Figures>,
}

/// A synthesis beside the model and the thesis.
#[derive(Clone, Debug)]
pub struct SynthComparison {
    pub design: Design,
    pub report: SynthReport,
    pub rows: Vec<ComparisonRow>,
    /// The whole design was synthesized (its total is meaningful).
    pub whole_design: bool,
}

impl SynthComparison {
    /// Joins `report` (of `plan`) with the model of `pipeline` and the thesis's table.
    pub fn new(
        lib: &Library,
        pipeline: &Pipeline,
        plan: &SynthPlan,
        report: SynthReport,
    ) -> SynthComparison {
        let tables = hwmodel::table::tables(lib, &pipeline.design);
        let blocks = pipeline.blocks_in_order();
        let rows = plan
            .blocks
            .iter()
            .map(|name| ComparisonRow {
                name: name.clone(),
                yosys: report.block(name).map(|b| b.figures),
                model: blocks
                    .iter()
                    .find(|b| b.name == name.as_str())
                    .map(|b| b.resources()),
                thesis: tables
                    .blocks
                    .iter()
                    .find(|r| r.model.name == *name)
                    .and_then(|r| r.thesis),
            })
            .collect();
        SynthComparison {
            design: pipeline.design,
            report,
            rows,
            whole_design: !plan.one_block,
        }
    }

    /// `rtprof hw synth --json`.
    pub fn to_json(&self) -> serde_json::Value {
        let blocks: Vec<_> = self
            .rows
            .iter()
            .map(|row| {
                serde_json::json!({
                    "name": row.name,
                    "yosys": row.yosys,
                    "model": row.model.map(|m| serde_json::json!({"le": m.le, "regs": m.regs, "mem_bits": m.mem_bits, "mult": m.mult})),
                    "thesis": row.thesis.map(|t| serde_json::json!({"le": t.le, "regs": t.regs, "mem_bits": t.mem_bits, "mult": t.mult})),
                })
            })
            .collect();
        let report = &self.report;
        serde_json::json!({
            "design": self.design.label(),
            "top": report.top,
            "yosys_version": report.yosys,
            "family": report.family,
            "seconds": report.seconds,
            "total": report.total,
            "unmapped": report.unmapped,
            "check_problems": report.check_problems,
            "blocks": blocks,
        })
    }

    /// `rtprof hw synth`'s table: Yosys | model | thesis per block, the whole design's
    /// total, warnings, and why the columns differ.
    pub fn to_text(&self) -> String {
        let report = &self.report;
        let mut text = String::new();
        let _ = writeln!(
            text,
            "Yosys ({}) synth_intel -family cycloneive, {} design, {:.0} s",
            report.yosys,
            self.design.label(),
            report.seconds
        );
        let _ = writeln!(
            text,
            "{:<14} {:>9} {:>9} {:>9} {:>9} | {:>9} {:>9} {:>9} | {:>9} {:>9}",
            "block",
            "LUT4",
            "mult LUT4",
            "FF",
            "mem bits",
            "model LE",
            "regs",
            "mem bits",
            "thesis LE",
            "regs"
        );
        let dash = |v: Option<u64>| v.map_or("-".to_string(), |v| v.to_string());
        for row in &self.rows {
            let (y, m, t) = (row.yosys, row.model, row.thesis);
            let _ = writeln!(
                text,
                "{:<14} {:>9} {:>9} {:>9} {:>9} | {:>9} {:>9} {:>9} | {:>9} {:>9}",
                row.name,
                dash(y.map(|y| y.lut4)),
                dash(y.map(|y| y.mult_lut4)),
                dash(y.map(|y| y.ff)),
                dash(y.map(|y| y.mem_bits)),
                dash(m.map(|m| m.le)),
                dash(m.map(|m| m.regs)),
                dash(m.map(|m| m.mem_bits)),
                dash(t.map(|t| t.le)),
                dash(t.map(|t| t.regs)),
            );
        }
        if self.whole_design {
            let total = &report.total;
            let _ = writeln!(
                text,
                "{:<14} {:>9} {:>9} {:>9} {:>9}",
                "whole design", total.lut4, total.mult_lut4, total.ff, total.mem_bits
            );
        }
        if !report.unmapped.is_empty() || report.check_problems > 0 {
            let _ = writeln!(
                text,
                "warning: {} unmapped cell kinds, {} check problems (log: {})",
                report.unmapped.len(),
                report.check_problems,
                report.log.display()
            );
        }
        let _ = writeln!(text, "{SYNTH_REASONS}");
        text
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_unknown_block_is_refused_before_anything_is_written() {
        let lib = Library::cyclone_iv_e();
        let pipeline = Pipeline::build(&lib, &Design::thesis());
        let work = std::env::temp_dir().join(format!("rtl-plan-{}", std::process::id()));
        let error = SynthPlan::prepare(&lib, &pipeline, Some("nope"), &work)
            .err()
            .map(|e| e.to_string());
        assert_eq!(
            error.as_deref(),
            Some(
                "no block 'nope' in the thesis design: one of primary_ray, intersection, \
                 min_distance, shading"
            )
        );
        assert!(!work.exists());
    }

    #[test]
    fn one_block_is_its_own_top_and_the_whole_design_reports_every_block() {
        let lib = Library::cyclone_iv_e();
        let pipeline = Pipeline::build(&lib, &Design::thesis());
        let work = std::env::temp_dir().join(format!("rtl-plan-ok-{}", std::process::id()));
        let one = SynthPlan::prepare(&lib, &pipeline, Some("shading"), &work).unwrap();
        assert_eq!(
            (one.top.as_str(), one.blocks.clone()),
            ("shading", vec!["shading".to_string()])
        );
        assert!(one.one_block);
        let all = SynthPlan::prepare(&lib, &pipeline, None, &work).unwrap();
        assert_eq!(all.top, TOP);
        assert_eq!(
            all.blocks,
            ["primary_ray", "intersection", "min_distance", "shading"]
        );
        assert!(all.files.iter().all(|f| f.exists()));
        let _ = std::fs::remove_dir_all(&work);
    }
}
