//! A design through Yosys and held against the model: [`SynthPlan`] generates the
//! design's RTL into a work directory and picks the top and the blocks to report
//! (the whole design, one block alone, or the top alone with its blocks as black
//! boxes: the iterator, memory ports and control in seconds), [`synthesize_design`]
//! runs it, and
//! [`SynthComparison`] turns each block's Yosys figures and depth into the results'
//! [`Synthesis`] (with the estimated clock, [`super::fmax`]) beside the model's table 8
//! rows (`rtprof hw synth`). A whole design's synthesis is kept in a cache keyed by
//! its RTL ([`remember`], [`recall`]), where `hw table` and the suite find it.

use std::path::{Path, PathBuf};

use hwmodel::blocks::Pipeline;
use hwmodel::design::Design;
use hwmodel::library::Library;
use results::{HwRow, SynthBlock, Synthesis};
use serde::Serialize;

use super::fmax::{CYCLONE_IV_E, THESIS_CLOCK_MHZ};
use super::{BlackBox, SynthFigures, SynthReport, synthesize_around};
use crate::RtlError;
use crate::generate::{self, TOP};
use crate::operators::write_atomically;
use crate::sim::depth_bits_for;

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
    /// Which RTL ([`GeneratedRtl::hash`](crate::generate::GeneratedRtl::hash)).
    pub rtl_hash: String,
    files: Vec<PathBuf>,
    /// The blocks read by their ports only (the top alone).
    black_boxes: Vec<BlackBox>,
}

impl SynthPlan {
    /// Generates the RTL of `pipeline` (with the smallest scene memory) into `work`;
    /// `block` names one block to synthesize alone, or the top ([`TOP`]) to synthesize
    /// its own logic alone, every block a black box. An unknown block is refused
    /// before anything is written.
    pub fn prepare(
        lib: &Library,
        pipeline: &Pipeline,
        block: Option<&str>,
        work: &Path,
    ) -> Result<SynthPlan, RtlError> {
        let rtl = generate::generate(lib, pipeline, depth_bits_for(0))?;
        let names: Vec<&str> = rtl.blocks.iter().map(|b| b.name).collect();
        let top_alone = block == Some(TOP);
        let (top, blocks) = match block {
            Some(TOP) => (TOP.to_string(), vec![TOP.to_string()]),
            Some(b) => {
                let Some(name) = names.iter().find(|n| **n == b) else {
                    return Err(RtlError::UnknownBlock {
                        block: b.to_string(),
                        design: pipeline.design.label(),
                        names: format!("{}, {TOP}", names.join(", ")),
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
        let black_boxes: Vec<BlackBox> = if top_alone {
            rtl.blocks
                .iter()
                .map(|b| BlackBox {
                    module: b.module.clone(),
                    file: work.join(format!("{}.v", b.module)),
                })
                .collect()
        } else {
            Vec::new()
        };
        let files = rtl
            .files
            .iter()
            .map(|(n, _)| work.join(n))
            .filter(|f| f.extension().is_some_and(|e| e == "v"))
            .filter(|f| !black_boxes.iter().any(|b| &b.file == f))
            .collect();
        Ok(SynthPlan {
            design: pipeline.design,
            work: work.to_path_buf(),
            top,
            blocks,
            one_block: block.is_some(),
            rtl_hash: rtl.hash(),
            files,
            black_boxes,
        })
    }

    /// Runs Yosys ([`super::synthesize`]): the blocks' figures, and the longest path of
    /// each block and of the whole design.
    pub fn run(&self) -> Result<SynthReport, RtlError> {
        let blocks: Vec<&str> = self.blocks.iter().map(String::as_str).collect();
        synthesize_around(
            &self.work,
            &self.files,
            &self.black_boxes,
            &self.top,
            &blocks,
            &blocks,
        )
    }
}

/// Synthesizes `pipeline`'s design (or its `block` alone) in `work` and sets it beside
/// the model: the one way the command line and the tests run a design through Yosys.
pub fn synthesize_design(
    lib: &Library,
    pipeline: &Pipeline,
    block: Option<&str>,
    work: &Path,
) -> Result<SynthComparison, RtlError> {
    let plan = SynthPlan::prepare(lib, pipeline, block, work)?;
    let report = plan.run()?;
    SynthComparison::new(lib, pipeline, &plan, &report)
}

/// The design's RTL through Yosys beside the model (`rtprof hw synth`): the typed
/// figures the results carry, the model's table 8 rows of the same design, and what the
/// run left unclean.
#[derive(Clone, Debug, Serialize)]
pub struct SynthComparison {
    /// Yosys's figures, depth and estimated clock per block.
    pub synthesis: Synthesis,
    /// The model's (and the thesis's) rows of the same design's blocks.
    pub model: Vec<HwRow>,
    /// The whole design was synthesized (not one block alone).
    pub whole_design: bool,
    /// Cells the flow left unmapped and the problems of Yosys's `check` (none and 0 in
    /// a clean run).
    pub unmapped: Vec<super::UnmappedCells>,
    pub check_problems: u64,
    /// The Yosys log.
    pub log: PathBuf,
}

impl SynthComparison {
    /// Joins `report` (of `plan`) with the model of `pipeline`: each block's figures and
    /// longest path, the estimated clock and whether it reaches the thesis's.
    pub fn new(
        lib: &Library,
        pipeline: &Pipeline,
        plan: &SynthPlan,
        report: &SynthReport,
    ) -> Result<SynthComparison, RtlError> {
        let tables = hwmodel::table::tables(lib, &pipeline.design);
        let rule = CYCLONE_IV_E;
        let block = |name: &str, figures: SynthFigures| -> Result<SynthBlock, RtlError> {
            let module = if plan.one_block {
                plan.top.as_str()
            } else {
                name
            };
            let path = report.depth.get(module).ok_or_else(|| {
                RtlError::Synth(format!("no longest path of `{module}` in the report"))
            })?;
            let fmax_mhz = rule.fmax_mhz(path.levels);
            Ok(SynthBlock {
                name: name.to_string(),
                lut4: figures.lut4,
                mult_lut4: figures.mult_lut4,
                ff: figures.ff,
                mem_bits: figures.mem_bits,
                m9k: figures.m9k,
                levels: path.levels,
                path_from: path.from.clone(),
                path_to: path.to.clone(),
                fmax_mhz,
                closes: fmax_mhz >= THESIS_CLOCK_MHZ,
            })
        };
        let mut blocks = Vec::new();
        for name in &plan.blocks {
            let figures = report.block(name).map(|b| b.figures).ok_or_else(|| {
                RtlError::Synth(format!("no figures of the block `{name}` in the report"))
            })?;
            blocks.push(block(name, figures)?);
        }
        let total_name = if plan.one_block {
            plan.top.clone()
        } else {
            WHOLE_DESIGN.to_string()
        };
        let mut total = block(&plan.top, report.total)?;
        total.name = total_name;
        Ok(SynthComparison {
            synthesis: Synthesis {
                design: pipeline.design.label(),
                tool: report.yosys.clone(),
                flow: FLOW.to_string(),
                seconds: report.seconds,
                rtl_hash: plan.rtl_hash.clone(),
                clock_mhz: THESIS_CLOCK_MHZ,
                level_ns: rule.level_ns,
                register_ns: rule.register_ns,
                max_levels: rule.max_levels_at(THESIS_CLOCK_MHZ),
                blocks,
                total,
            },
            model: tables.blocks.iter().map(HwRow::from_model_row).collect(),
            whole_design: !plan.one_block,
            unmapped: report.unmapped.clone(),
            check_problems: report.check_problems,
            log: report.log.clone(),
        })
    }
}

/// The name of the whole design's row.
pub const WHOLE_DESIGN: &str = "whole design";

/// The flow, as the results name it.
pub const FLOW: &str = "synth_intel -family cycloneive (the default script, ABC's default LUT mapping), hierarchy kept";

/// Where whole-design syntheses are kept: `<cache>/rtprof/synth` (beside the
/// simulation's builds), one `<rtl hash>.json` per design.
pub fn cache_dir() -> PathBuf {
    crate::sim::default_build_root()
        .parent()
        .map_or_else(std::env::temp_dir, Path::to_path_buf)
        .join("synth")
}

/// Keeps a whole design's synthesis in `dir` ([`cache_dir`]), so that `hw table` and
/// the suite can show it beside the model without running Yosys again.
pub fn remember(dir: &Path, synthesis: &Synthesis) -> Result<PathBuf, RtlError> {
    let text = serde_json::to_string_pretty(synthesis)
        .map_err(|e| RtlError::Synth(format!("cannot write the synthesis as JSON: {e}")))?;
    std::fs::create_dir_all(dir).map_err(|source| RtlError::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    write_atomically(&dir.join(format!("{}.json", synthesis.rtl_hash)), &text)
}

/// The synthesis of exactly `pipeline`'s RTL kept in `dir`, if one was run (an
/// unreadable file counts as none: it is a cache).
pub fn recall(dir: &Path, lib: &Library, pipeline: &Pipeline) -> Option<Synthesis> {
    let rtl = generate::generate(lib, pipeline, depth_bits_for(0)).ok()?;
    let hash = rtl.hash();
    let text = std::fs::read_to_string(dir.join(format!("{hash}.json"))).ok()?;
    serde_json::from_str::<Synthesis>(&text)
        .ok()
        .filter(|s| s.rtl_hash == hash)
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
                 min_distance, shading, raycaster_top"
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
        assert!(all.black_boxes.is_empty());
        // The top alone: every block read by its ports, none of them as a design file.
        let top = SynthPlan::prepare(&lib, &pipeline, Some(TOP), &work).unwrap();
        assert_eq!(
            (top.top.as_str(), top.blocks.clone()),
            (TOP, vec![TOP.into()])
        );
        let boxed: Vec<&str> = top.black_boxes.iter().map(|b| b.module.as_str()).collect();
        assert_eq!(
            boxed,
            ["primary_ray", "intersection", "min_distance", "shading"]
        );
        assert!(top.black_boxes.iter().all(|b| b.file.exists()));
        assert!(
            top.files
                .iter()
                .all(|f| !top.black_boxes.iter().any(|b| &b.file == f))
        );
        assert!(top.files.iter().any(|f| f.ends_with("raycaster_top.v")));
        let _ = std::fs::remove_dir_all(&work);
    }
}
