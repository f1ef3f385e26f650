//! `rtprof hw rtl | sim | synth`: the pipeline as generated Verilog, simulated cycle by
//! cycle with Verilator and synthesized with Yosys, held against the model. The
//! binary parses the flags into these requests and prints what they return.

use std::path::{Path, PathBuf};

use hwmodel::blocks::Pipeline;
use hwmodel::design::{Design, MinDistance};
use hwmodel::library::Library;
use rtl::sim::{self, SimCheck};
use rtl::synth::{self, SynthComparison};
use rtl::system::SystemConfig;

use crate::error::RunError;
use crate::hardware_files::hardware_scene;
use crate::progress::Progress;
use crate::scene_input::SceneInput;

/// What `rtprof hw rtl` writes: the design's Verilog, with a scene its test-bench
/// input, and with `system` the whole system around it.
pub struct RtlRequest<'a> {
    pub scene: Option<&'a SceneInput>,
    pub design: Design,
    pub output: &'a Path,
    /// The test-bench frame [default: the scene's resolution].
    pub size: Option<(u32, u32)>,
    pub system: bool,
}

/// What [`write_rtl`] wrote, for the user.
pub struct RtlWritten {
    pub files: usize,
    pub design: Design,
    /// Primitives the scene memory holds (a power of two).
    pub memory_primitives: u64,
    /// Each block's latency in cycles, in pipeline order.
    pub blocks: Vec<(String, u32)>,
    /// The system's VGA mode and UART bit time, when it was written.
    pub system: Option<SystemConfig>,
}

/// Generates the RTL of `req.design` into `req.output`.
pub fn write_rtl(req: &RtlRequest) -> Result<RtlWritten, RunError> {
    let lib = Library::cyclone_iv_e();
    let pipeline = Pipeline::build(&lib, &req.design);
    let scene = req.scene.map(hardware_scene).transpose()?;
    let primitives = scene.as_ref().map_or(0, |(_, hw)| hw.primitive_count());
    let rtl = rtl::generate::generate(&lib, &pipeline, sim::depth_bits_for(primitives))?;
    rtl::generate::write(&rtl, req.output)?;
    let mut files = rtl.files.len();
    if let Some((tracer_scene, hw)) = &scene {
        let (width, height) = req
            .size
            .unwrap_or((tracer_scene.view.width, tracer_scene.view.height));
        files += sim::write_scene_files(req.output, &pipeline, hw, width, height)?.len();
    }
    let system = if req.system {
        let config = SystemConfig::thesis(rtl.depth_bits)?;
        let system = rtl::system::generate_system(&lib, &pipeline, config)?;
        // The system's files hold the pipeline's again: count the new ones.
        files += rtl::system::write(&system, req.output)? - rtl.files.len();
        if let Some((_, hw)) = &scene {
            rtl::system::write_upload(&system, &pipeline, hw, req.output)?;
            files += 1;
        }
        Some(system.config)
    } else {
        None
    };
    Ok(RtlWritten {
        files,
        design: req.design,
        memory_primitives: 1u64 << rtl.depth_bits,
        blocks: rtl
            .blocks
            .iter()
            .map(|b| (b.name.to_string(), b.latency))
            .collect(),
        system,
    })
}

/// What `rtprof hw sim` checks: the generated RTL of `design` run on `scene`.
pub struct SimRequest<'a> {
    pub scene: &'a SceneInput,
    pub design: Design,
    pub size: Option<(u32, u32)>,
    /// Where the simulated picture goes (.png or .ppm; by default `<scene>-rtl.png`,
    /// here).
    pub image: Option<&'a Path>,
    /// Where Verilator builds the model [default: [`sim::default_build_root`]].
    pub build_dir: Option<PathBuf>,
}

/// Builds the Verilator model (once per design), simulates the frame, writes the
/// picture and checks it, its cycles and its latencies against the model and the
/// emulator. A disagreement is in the returned check ([`SimCheck::agrees`]), not an
/// error.
pub fn simulate(req: &SimRequest, progress: &dyn Progress) -> Result<SimCheck, RunError> {
    if req.design.ortho {
        return Err(RunError::Input(
            "--ortho is generated (rtprof hw rtl --ortho) but not simulated: neither the \
             emulator nor the graphs model the orthographic camera's set-up, so there is \
             no picture to check it against"
                .into(),
        ));
    }
    let default = req.scene.named_after("", "-rtl.png");
    let image = req.image.unwrap_or(&default);
    tracer::image_io::ImageFormat::from_path(image).map_err(|e| RunError::Input(e.to_string()))?;
    let lib = Library::cyclone_iv_e();
    let pipeline = Pipeline::build(&lib, &req.design);
    let (tracer_scene, hw) = hardware_scene(req.scene)?;
    let (width, height) = req
        .size
        .unwrap_or((tracer_scene.view.width, tracer_scene.view.height));
    let rtl = rtl::generate::generate(&lib, &pipeline, sim::depth_bits_for(hw.primitive_count()))?;
    let root = req
        .build_dir
        .clone()
        .unwrap_or_else(sim::default_build_root);
    progress.note(&format!(
        "rtprof: building the Verilator model of the {} design in {} (once per design, a minute or two)",
        req.design.label(),
        root.display()
    ));
    let program = sim::build(&rtl, &root)?;
    progress.note(&format!(
        "rtprof: simulating {width}x{height} ({} primitives)",
        hw.primitive_count()
    ));
    let name = req.scene.to_string();
    let check = SimCheck::run(&program, &pipeline, &name, &hw, (width, height), image)?;
    hwmodel::emulator::write_image(&check.result.image, image)
        .map_err(|e| RunError::Input(e.to_string()))?;
    Ok(check)
}

/// Synthesizes `design` (or its block `block` alone) with Yosys's default flow in
/// `work_dir` [default: a temporary directory]. A whole design's run is kept in the
/// synthesis cache ([`synth::remember`]), so that `hw table` and the suite show it
/// beside the model from then on.
pub fn synthesize(
    design: &Design,
    block: Option<&str>,
    work_dir: Option<&Path>,
    progress: &dyn Progress,
) -> Result<SynthComparison, RunError> {
    let lib = Library::cyclone_iv_e();
    let pipeline = Pipeline::build(&lib, design);
    let work = work_dir.map_or_else(
        || std::env::temp_dir().join(format!("rtprof-synth-{}", std::process::id())),
        Path::to_path_buf,
    );
    progress.note(&format!(
        "rtprof: synthesizing {} of the {} design with Yosys for Cyclone IV E in {} (minutes)",
        block.unwrap_or("every block"),
        design.label(),
        work.display()
    ));
    let comparison = synth::synthesize_design(&lib, &pipeline, block, &work)?;
    if comparison.whole_design {
        synth::remember(&synth::cache_dir(), &comparison.synthesis)?;
    }
    Ok(comparison)
}

/// The warning a synthesis deserves: cells left unmapped or problems found by Yosys's
/// `check`, with where its log is. `None` for a clean run.
pub fn synthesis_warning(comparison: &SynthComparison) -> Option<String> {
    (!comparison.unmapped.is_empty() || comparison.check_problems > 0).then(|| {
        format!(
            "warning: unmapped cells {:?} and {} check problems (log: {})",
            comparison.unmapped,
            comparison.check_problems,
            comparison.log.display()
        )
    })
}

impl RtlWritten {
    /// What was written, each block's latency, and how to simulate it: `rtprof hw
    /// rtl`'s report. `scene` is the scene as the user named it, if any.
    pub fn to_text(&self, output: &Path, scene: Option<&str>) -> String {
        use reports::format::{count, size};
        let mut text = format!(
            "wrote {} files to {} ({} design, scene memory of {} primitives)\n",
            count(self.files as u64),
            output.display(),
            self.design.label(),
            count(self.memory_primitives)
        );
        for (name, latency) in &self.blocks {
            text += &format!("  {name:<14} {:>6} cycles\n", count(u64::from(*latency)));
        }
        if let Some(config) = &self.system {
            let t = &config.timing;
            text += &format!(
                "system: {}.v, VGA {} with VESA timing, UART {} clock cycles a bit{}\n",
                rtl::system::SYSTEM_TOP,
                size(t.h_visible, t.v_visible),
                count(u64::from(config.clocks_per_bit)),
                if scene.is_some() {
                    format!(", the scene's upload in {}", rtl::system::UPLOAD_FILE)
                } else {
                    String::new()
                }
            );
        }
        // The flags that build this design again (hw sim refuses --ortho).
        let d = &self.design;
        let mut flags = String::new();
        for (on, flag) in [
            (d.fast_sqrt, " --fast-sqrt"),
            (d.no_rsqrt_shading, " --no-rsqrt-shading"),
            (
                d.min_distance == MinDistance::IntegerCompare,
                " --int-compare",
            ),
        ] {
            if on {
                flags += flag;
            }
        }
        if d.units > 1 {
            flags += &format!(" --units {}", d.units);
        }
        text + &format!(
            "simulate: rtprof hw sim {}{flags}\n",
            scene.unwrap_or("SCENE")
        )
    }
}
