//! `rtprof hw rtl | sim | synth`: the pipeline as generated Verilog, simulated cycle by
//! cycle with Verilator and synthesized with Yosys, held against the model.

use crate::cli::scene_args::{SCENE_HELP, SIZE_HELP, named_after, parse_scene};
use anyhow::{Result, bail};
use hwmodel::blocks::Pipeline;
use hwmodel::design::Design;
use hwmodel::emulator::write_image;
use hwmodel::library::Library;
use reports::sections::synthesis::synthesis_text;
use rtl::generate;
use rtl::sim::{self, SimCheck};
use rtl::synth;
use rtl::system::SystemConfig;
use runner::hardware_files::hardware_scene;
use runner::scene_input::SceneInput;
use std::path::PathBuf;

// The design the RTL is generated for: the model's design flags (the generator refuses
// more units than it builds, `rtl::RtlError::TooManyUnits`).
#[derive(clap::Args, Debug, Clone)]
pub struct RtlDesign {
    #[command(flatten)]
    flags: super::DesignFlags,
}

impl RtlDesign {
    fn design(&self) -> Design {
        self.flags.design()
    }
}

#[derive(clap::Args, Debug)]
pub struct RtlArgs {
    /// A scene: size the scene memory for it and write its testbench input.
    #[arg(value_name = "SCENE", value_parser = parse_scene, help = SCENE_HELP)]
    scene: Option<SceneInput>,
    #[command(flatten)]
    design: RtlDesign,
    /// Output directory for the Verilog, the testbench and the scene's input.
    #[arg(short, long, value_name = "DIR")]
    output: PathBuf,
    #[arg(long, value_name = "WxH", value_parser = crate::cli::scene_args::parse_size, help = SIZE_HELP)]
    size: Option<(u32, u32)>,
    /// Also write the whole system (docs/rtl-system.md): the UART scene loader, the
    /// frame memory and the VGA controller at 640x480, 60 Hz, around the pipeline
    /// (raycaster_system.v), and with SCENE its upload at 640x480 (scene_upload.bin).
    #[arg(long)]
    system: bool,
}

#[derive(clap::Args, Debug)]
pub struct SimArgs {
    #[arg(value_name = "SCENE", value_parser = parse_scene, help = SCENE_HELP)]
    scene: SceneInput,
    #[command(flatten)]
    design: RtlDesign,
    #[arg(long, value_name = "WxH", value_parser = crate::cli::scene_args::parse_size, help = SIZE_HELP)]
    size: Option<(u32, u32)>,
    /// Output image, .png or .ppm [default: <scene>-rtl.png, here].
    #[arg(short, long, value_name = "IMG")]
    output: Option<PathBuf>,
    /// Where Verilator builds the model (reused per design) [default: the user's cache,
    /// ~/.cache/rtprof/rtl].
    #[arg(long, value_name = "DIR")]
    build_dir: Option<PathBuf>,
    /// Print JSON: {cycles, model_cycles, writes, blocks: [{name, simulated, model}],
    /// differing_pixels, rms, …}.
    #[arg(long)]
    json: bool,
}

pub fn rtl(args: &RtlArgs) -> Result<()> {
    let lib = Library::cyclone_iv_e();
    let design = args.design.design();
    let pipeline = Pipeline::build(&lib, &design);
    let scene = args.scene.as_ref().map(hardware_scene).transpose()?;
    let primitives = scene.as_ref().map_or(0, |(_, hw)| hw.primitive_count());
    let rtl = generate::generate(&lib, &pipeline, sim::depth_bits_for(primitives))?;
    generate::write(&rtl, &args.output)?;
    let mut written = rtl.files.len();
    if let Some((tracer_scene, hw)) = &scene {
        let (width, height) = args
            .size
            .unwrap_or((tracer_scene.view.width, tracer_scene.view.height));
        written += sim::write_scene_files(&args.output, &pipeline, hw, width, height)?.len();
    }
    let system = if args.system {
        let config = SystemConfig::thesis(rtl.depth_bits)?;
        let system = rtl::system::generate_system(&lib, &pipeline, config)?;
        // The system's files hold the pipeline's again: count the new ones.
        written += rtl::system::write(&system, &args.output)? - rtl.files.len();
        if let Some((_, hw)) = &scene {
            rtl::system::write_upload(&system, &pipeline, hw, &args.output)?;
            written += 1;
        }
        Some(system)
    } else {
        None
    };
    println!(
        "wrote {written} files to {} ({} design, scene memory of {} primitives)",
        args.output.display(),
        design.label(),
        1u32 << rtl.depth_bits
    );
    for b in &rtl.blocks {
        println!("  {:<14} {:>4} cycles", b.name, b.latency);
    }
    if let Some(system) = &system {
        let t = &system.config.timing;
        println!(
            "system: {}.v, VGA {}x{} with VESA timing, UART {} clock cycles a bit{}",
            rtl::system::SYSTEM_TOP,
            t.h_visible,
            t.v_visible,
            system.config.clocks_per_bit,
            if scene.is_some() {
                format!(", the scene's upload in {}", rtl::system::UPLOAD_FILE)
            } else {
                String::new()
            }
        );
    }
    println!(
        "simulate: rtprof hw sim {}{}",
        args.scene
            .as_ref()
            .map_or("SCENE".to_string(), ToString::to_string),
        if design.units > 1 {
            format!(" --units {}", design.units)
        } else {
            String::new()
        }
    );
    Ok(())
}

pub fn simulate(args: &SimArgs) -> Result<()> {
    let lib = Library::cyclone_iv_e();
    let design = args.design.design();
    if design.ortho {
        bail!(
            "--ortho is generated (rtprof hw rtl --ortho) but not simulated: neither the \
             emulator nor the graphs model the orthographic camera's set-up, so there is \
             no picture to check it against"
        );
    }
    let pipeline = Pipeline::build(&lib, &design);
    let (tracer_scene, hw) = hardware_scene(&args.scene)?;
    let (width, height) = args
        .size
        .unwrap_or((tracer_scene.view.width, tracer_scene.view.height));
    let output = match &args.output {
        Some(path) => path.clone(),
        None => named_after(&args.scene, "", "-rtl.png"),
    };
    tracer::image_io::ImageFormat::from_path(&output)?;
    let rtl = generate::generate(&lib, &pipeline, sim::depth_bits_for(hw.primitive_count()))?;
    let root = args
        .build_dir
        .clone()
        .unwrap_or_else(sim::default_build_root);
    eprintln!(
        "rtprof: building the Verilator model of the {} design in {} (once per design, a minute or two)",
        design.label(),
        root.display()
    );
    let program = sim::build(&rtl, &root)?;
    eprintln!(
        "rtprof: simulating {width}x{height} ({} primitives)",
        hw.primitive_count()
    );
    let name = args.scene.to_string();
    let check = SimCheck::run(&program, &pipeline, &name, &hw, (width, height), &output)?;
    write_image(&check.result.image, &output)?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&check.summary())?);
    } else {
        print!("{}", check.to_text());
    }
    if !check.agrees() {
        // A failed check, not bad input: exit code 1.
        return Err(crate::cli::Outcome::new(
            1,
            "the simulated RTL disagrees with the model or the emulator (see above)",
        )
        .into());
    }
    Ok(())
}

#[derive(clap::Args, Debug)]
pub struct SynthArgs {
    #[command(flatten)]
    design: RtlDesign,
    /// Synthesize one block alone (primary_ray, intersection, min_distance, shading,
    /// min_tree) instead of the whole design: seconds to minutes instead of tens of
    /// minutes.
    #[arg(long, value_name = "NAME")]
    block: Option<String>,
    /// Where Yosys works (script, log, statistics) [default: a temporary directory].
    #[arg(long, value_name = "DIR")]
    work_dir: Option<PathBuf>,
    /// Print JSON: {synthesis: {design, tool, flow, seconds, clock_mhz, blocks: [{name,
    /// lut4, mult_lut4, ff, mem_bits, m9k, levels, fmax_mhz, closes, …}], total},
    /// model: [table 8's rows], unmapped, check_problems, …}.
    #[arg(long)]
    json: bool,
}

pub fn synth(args: &SynthArgs) -> Result<()> {
    let lib = Library::cyclone_iv_e();
    let pipeline = Pipeline::build(&lib, &args.design.design());
    let work = match &args.work_dir {
        Some(dir) => dir.clone(),
        None => std::env::temp_dir().join(format!("rtprof-synth-{}", std::process::id())),
    };
    eprintln!(
        "rtprof: synthesizing {} of the {} design with Yosys for Cyclone IV E in {} (minutes)",
        args.block.as_deref().unwrap_or("every block"),
        pipeline.design.label(),
        work.display()
    );
    let comparison = synth::synthesize_design(&lib, &pipeline, args.block.as_deref(), &work)?;
    if comparison.whole_design {
        // `hw table` and the suite show it beside the model from now on.
        synth::remember(&synth::cache_dir(), &comparison.synthesis)?;
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&comparison)?);
    } else {
        print!(
            "{}",
            synthesis_text(&comparison.synthesis, &comparison.model)
        );
        if !comparison.unmapped.is_empty() || comparison.check_problems > 0 {
            eprintln!(
                "warning: unmapped cells {:?} and {} check problems (log: {})",
                comparison.unmapped,
                comparison.check_problems,
                comparison.log.display()
            );
        }
    }
    Ok(())
}
