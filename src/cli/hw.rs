//! `rtprof hw`: the FPGA pipeline model. `table` (the model next to the thesis's tables
//! 7 and 8), `time` (frame time, device fit and what-ifs for a scene, optionally against
//! the measured software), `render` (the image the hardware would show), `mif` (the
//! scene memory as an Altera Memory Initialization File), and the generated RTL: `rtl`
//! (Verilog), `sim` (Verilator, against the model) and `synth` (Yosys). The work is
//! `runner::hardware_*`; the flags of the design and device are `hwmodel::what_if`'s.

use super::Outcome;
use super::scene_args::{SIZE_HELP, parse_size};
use anyhow::Result;
use hwmodel::what_if::{DesignFlags, WhatIf, parse_clock_mhz};
use runner::hardware_prediction::{TimeRequest, time_report};
use runner::hardware_rtl::{RtlRequest, SimRequest, synthesis_warning};
use runner::scene_input::SceneInput;
use std::path::PathBuf;
use terminal::progress::Bars;

#[derive(clap::Args, Debug)]
pub struct HwArgs {
    #[command(subcommand)]
    command: HwCommand,
}

#[derive(clap::Subcommand, Debug)]
#[command(defer = true)]
enum HwCommand {
    /// Tables 7 and 8 as the model computes them, next to the thesis's, with % errors.
    Table(TableArgs),
    /// Frame time, device fit and utilization for a scene (eq. 49), with what-ifs.
    Time(TimeArgs),
    /// The image the hardware shows: f32, spheres and cylinders, diffuse gray, one light.
    Render(RenderArgs),
    /// Write the scene memory as an Altera Memory Initialization File (.mif).
    Mif(MifArgs),
    /// Write the pipeline as Verilog generated from the model's scheduled graphs.
    Rtl(RtlArgs),
    /// Simulate the generated RTL with Verilator: image, cycles per frame and per
    /// block, checked against the model and the emulator.
    Sim(SimArgs),
    /// Synthesize the generated RTL with Yosys for Cyclone IV E: LUT4, flip-flops and
    /// memory per block beside the model and the thesis's table 8.
    Synth(SynthArgs),
}

#[derive(clap::Args, Debug)]
struct TableArgs {
    #[command(flatten)]
    what_if: WhatIf,
    /// Print JSON: {blocks: [{name, latency, le, comb, regs, mem_bits, mult, thesis, error_pct}], ops: […]}.
    #[arg(long)]
    json: bool,
    /// Also list each block's operators and delay lines.
    #[arg(long)]
    detail: bool,
}

#[derive(clap::Args, Debug)]
struct TimeArgs {
    #[arg(value_name = "SCENE", value_parser = SceneInput::parse_arg, help = SceneInput::HELP)]
    scene: SceneInput,
    #[command(flatten)]
    what_if: WhatIf,
    /// Clock in MHz.
    #[arg(long, value_name = "MHZ", default_value_t = 50.0, value_parser = parse_clock_mhz)]
    clock: f64,
    #[arg(long, value_name = "WxH", value_parser = parse_size, help = SIZE_HELP)]
    size: Option<(u32, u32)>,
    /// Time spheres and cylinders alone when the scene also has other primitives.
    #[arg(long)]
    ignore_unsupported: bool,
    /// Also render the scene in software (diffuse-only gray, baseline, same size) and
    /// report the measured time and the hardware's speed-up.
    #[arg(long)]
    vs_software: bool,
    /// Software threads for --vs-software (the thesis's software ran on one).
    #[arg(long, value_name = "N", default_value_t = 1,
          value_parser = super::scene_args::parse_threads)]
    threads: u16,
    /// Timed software renders for --vs-software (median).
    #[arg(long, value_name = "N", default_value_t = 3,
          value_parser = clap::value_parser!(u32).range(1..=1000))]
    repeats: u32,
    /// Print JSON: {primitives, units, clock_hz, cycles, seconds, fits, fit_state,
    /// utilization, …}; fit_state is fits_on_paper above the routing headroom.
    #[arg(long)]
    json: bool,
}

#[derive(clap::Args, Debug)]
struct RenderArgs {
    #[arg(value_name = "SCENE", value_parser = SceneInput::parse_arg, help = SceneInput::HELP)]
    scene: SceneInput,
    /// Output image, .png or .ppm [default: the scene's name + -hw.png, here].
    #[arg(short, long, value_name = "IMG")]
    output: Option<PathBuf>,
    #[arg(long, value_name = "WxH", value_parser = parse_size, help = SIZE_HELP)]
    size: Option<(u32, u32)>,
}

#[derive(clap::Args, Debug)]
struct MifArgs {
    #[arg(value_name = "SCENE", value_parser = SceneInput::parse_arg, help = SceneInput::HELP)]
    scene: SceneInput,
    /// Output .mif file [default: the scene's name + .mif, here].
    #[arg(short, long, value_name = "FILE.mif")]
    output: Option<PathBuf>,
}

#[derive(clap::Args, Debug)]
struct RtlArgs {
    /// A scene: size the scene memory for it and write its testbench input.
    #[arg(value_name = "SCENE", value_parser = SceneInput::parse_arg, help = SceneInput::HELP)]
    scene: Option<SceneInput>,
    #[command(flatten)]
    design: DesignFlags,
    /// Output directory for the Verilog, the testbench and the scene's input.
    #[arg(short, long, value_name = "DIR")]
    output: PathBuf,
    #[arg(long, value_name = "WxH", value_parser = parse_size, help = SIZE_HELP)]
    size: Option<(u32, u32)>,
    /// Also write the whole system (docs/rtl-system.md): the UART scene loader, the
    /// frame memory and the VGA controller at 640x480, 60 Hz, around the pipeline
    /// (raycaster_system.v), and with SCENE its upload at 640x480 (scene_upload.bin).
    #[arg(long)]
    system: bool,
}

#[derive(clap::Args, Debug)]
struct SimArgs {
    #[arg(value_name = "SCENE", value_parser = SceneInput::parse_arg, help = SceneInput::HELP)]
    scene: SceneInput,
    #[command(flatten)]
    design: DesignFlags,
    #[arg(long, value_name = "WxH", value_parser = parse_size, help = SIZE_HELP)]
    size: Option<(u32, u32)>,
    /// Output image, .png or .ppm [default: the scene's name + -rtl.png, here].
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

#[derive(clap::Args, Debug)]
struct SynthArgs {
    #[command(flatten)]
    design: DesignFlags,
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

pub fn run(args: &HwArgs) -> Result<()> {
    match &args.command {
        HwCommand::Table(a) => table(a),
        HwCommand::Time(a) => time(a),
        HwCommand::Render(a) => {
            let output = a.output.as_deref();
            let written = runner::hardware_files::write_emulator_image(&a.scene, a.size, output)?;
            eprintln!("{written}");
            Ok(())
        }
        HwCommand::Mif(a) => {
            let written = runner::hardware_files::write_mif(&a.scene, a.output.as_deref())?;
            eprintln!("{written}");
            Ok(())
        }
        HwCommand::Rtl(a) => {
            let request = RtlRequest {
                scene: a.scene.as_ref(),
                design: a.design.design(),
                output: &a.output,
                size: a.size,
                system: a.system,
            };
            let written = runner::hardware_rtl::write_rtl(&request)?;
            let scene = a.scene.as_ref().map(ToString::to_string);
            print!("{}", written.to_text(&a.output, scene.as_deref()));
            Ok(())
        }
        HwCommand::Sim(a) => simulate(a),
        HwCommand::Synth(a) => synth(a),
    }
}

fn table(args: &TableArgs) -> Result<()> {
    let (lib, device) = args.what_if.device()?;
    let design = args.what_if.design();
    if args.json {
        let tables = hwmodel::table::tables(&lib, &design);
        println!("{}", serde_json::to_string_pretty(&tables)?);
    } else {
        let text = runner::hardware_tables::table_text(&lib, &device, &design, args.detail);
        print!("{text}");
    }
    Ok(())
}

fn time(args: &TimeArgs) -> Result<()> {
    let (lib, device) = args.what_if.device()?;
    let scene = args.scene.load(&tracer::Limits::default())?;
    let request = TimeRequest {
        name: args.scene.to_string(),
        design: args.what_if.design(),
        size: args.size.unwrap_or((scene.view.width, scene.view.height)),
        clock_hz: args.clock * 1e6,
        ignore_unsupported: args.ignore_unsupported,
        software: args.vs_software.then_some((args.threads, args.repeats)),
    };
    let report = time_report(&scene, &lib, &device, &request)?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print!("{}", report.to_text());
    }
    Ok(())
}

fn simulate(args: &SimArgs) -> Result<()> {
    let request = SimRequest {
        scene: &args.scene,
        design: args.design.design(),
        size: args.size,
        image: args.output.as_deref(),
        build_dir: args.build_dir.clone(),
    };
    let check = runner::hardware_rtl::simulate(&request, &Bars::default())?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&check.summary())?);
    } else {
        print!("{}", check.to_text());
    }
    if !check.agrees() {
        // A failed check, not bad input: exit code 1.
        let message = "the simulated RTL disagrees with the model or the emulator (see above)";
        return Err(Outcome::new(Outcome::CHECK_FAILED, message).into());
    }
    Ok(())
}

fn synth(args: &SynthArgs) -> Result<()> {
    let design = args.design.design();
    let block = args.block.as_deref();
    let comparison = runner::hardware_rtl::synthesize(
        &design,
        block,
        args.work_dir.as_deref(),
        &Bars::default(),
    )?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&comparison)?);
    } else {
        let text =
            reports::sections::synthesis::synthesis_text(&comparison.synthesis, &comparison.model);
        print!("{text}");
        if let Some(warning) = synthesis_warning(&comparison) {
            eprintln!("{warning}");
        }
    }
    Ok(())
}
