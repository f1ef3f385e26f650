//! `rtprof hw`: the FPGA pipeline model. `table` (the model next to the thesis's tables
//! 7 and 8), `time` (frame time, device fit and what-ifs for a scene, optionally against
//! the measured software), `render` (the image the hardware would show) and `mif` (the
//! scene memory as an Altera Memory Initialization File); `rtl`, `sim` and `synth` are
//! in `hw_rtl.rs`.

mod rtl_commands;

use super::scene_args::{SCENE_HELP, SIZE_HELP, named_after, parse_scene, parse_size};
use anyhow::Result;
use hwmodel::blocks::Pipeline;
use hwmodel::design::Design;
use hwmodel::library::{DeviceSpec, Library, find_device};
use hwmodel::table::tables;
use runner::hardware_prediction::{TimeRequest, time_report};
use runner::scene_input::SceneInput;
use std::path::PathBuf;

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
    Rtl(rtl_commands::RtlArgs),
    /// Simulate the generated RTL with Verilator: image, cycles per frame and per
    /// block, checked against the model and the emulator.
    Sim(rtl_commands::SimArgs),
    /// Synthesize the generated RTL with Yosys for Cyclone IV E: LUT4, flip-flops and
    /// memory per block beside the model and the thesis's table 8.
    Synth(rtl_commands::SynthArgs),
}

// The design's changes from the thesis's, shared by every `hw` command that takes a
// design (`table`, `time`, `rtl`, `sim`, `synth`).
#[derive(clap::Args, Debug, Clone)]
pub struct DesignFlags {
    /// What-if: the bit-trick square root (one adder, 1 cycle) instead of the IP core.
    #[arg(long)]
    fast_sqrt: bool,
    /// What-if: orthographic primary rays (no normalize; one direction for all rays).
    #[arg(long)]
    ortho: bool,
    /// What-if: shading without the inverse square root (light at infinity).
    #[arg(long)]
    no_rsqrt_shading: bool,
    /// What-if: K parallel intersection units (each with its minimum-distance block).
    #[arg(long, value_name = "K", default_value_t = 1,
          value_parser = clap::value_parser!(u32).range(1..=4096))]
    units: u32,
}

impl DesignFlags {
    pub fn design(&self) -> Design {
        Design {
            units: self.units,
            fast_sqrt: self.fast_sqrt,
            ortho: self.ortho,
            no_rsqrt_shading: self.no_rsqrt_shading,
            ..Design::thesis()
        }
    }
}

// Design changes and the device, for `table` and `time`.
#[derive(clap::Args, Debug, Clone)]
struct WhatIf {
    #[command(flatten)]
    design: DesignFlags,
    /// Device: the thesis's by default; the others are unvalidated.
    #[arg(long, value_name = "D", default_value_t = hwmodel::library::default_device_name())]
    device: String,
}

impl WhatIf {
    fn design(&self) -> Design {
        self.design.design()
    }

    fn device(&self) -> Result<(Library, DeviceSpec)> {
        Ok(find_device(&self.device)?)
    }
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
    #[arg(value_name = "SCENE", value_parser = parse_scene, help = SCENE_HELP)]
    scene: SceneInput,
    #[command(flatten)]
    what_if: WhatIf,
    /// Clock in MHz.
    #[arg(long, value_name = "MHZ", default_value_t = 50.0, value_parser = parse_clock)]
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
    #[arg(value_name = "SCENE", value_parser = parse_scene, help = SCENE_HELP)]
    scene: SceneInput,
    /// Output image, .png or .ppm [default: <scene>-hw.png, here].
    #[arg(short, long, value_name = "IMG")]
    output: Option<PathBuf>,
    #[arg(long, value_name = "WxH", value_parser = parse_size, help = SIZE_HELP)]
    size: Option<(u32, u32)>,
}

#[derive(clap::Args, Debug)]
struct MifArgs {
    #[arg(value_name = "SCENE", value_parser = parse_scene, help = SCENE_HELP)]
    scene: SceneInput,
    /// Output .mif file [default: <scene>.mif, here].
    #[arg(short, long, value_name = "FILE.mif")]
    output: Option<PathBuf>,
}

fn parse_clock(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(mhz) if mhz.is_finite() && mhz > 0.0 && mhz <= 2000.0 => Ok(mhz),
        _ => Err(format!(
            "'{text}' is not a clock: expected MHz between 0 and 2000, e.g. 50"
        )),
    }
}

pub fn run(args: &HwArgs) -> Result<()> {
    match &args.command {
        HwCommand::Table(a) => table(a),
        HwCommand::Time(a) => time(a),
        HwCommand::Render(a) => render(a),
        HwCommand::Mif(a) => mif(a),
        HwCommand::Rtl(a) => rtl_commands::rtl(a),
        HwCommand::Sim(a) => rtl_commands::simulate(a),
        HwCommand::Synth(a) => rtl_commands::synth(a),
    }
}

// ---------------------------------------------------------------------------- table

fn table(args: &TableArgs) -> Result<()> {
    let (lib, device) = args.what_if.device()?;
    let design = args.what_if.design();
    let t = tables(&lib, &design);
    if args.json {
        println!("{}", serde_json::to_string_pretty(&t)?);
        return Ok(());
    }
    print!(
        "{}",
        runner::hardware_tables::tables_text(&t, &lib, &device)
    );
    print!(
        "\n{}",
        runner::hardware_tables::synthesis_text(&lib, &design)
    );
    if args.detail {
        print!("{}", Pipeline::build(&lib, &design).detail_text());
    }
    Ok(())
}

// ----------------------------------------------------------------------------- time

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

// --------------------------------------------------------------------- render, mif

fn render(args: &RenderArgs) -> Result<()> {
    let output = match &args.output {
        Some(path) => path.clone(),
        None => named_after(&args.scene, "", "-hw.png"),
    };
    let written = runner::hardware_files::write_emulator_image(&args.scene, args.size, &output)?;
    eprintln!("{written}");
    Ok(())
}

fn mif(args: &MifArgs) -> Result<()> {
    let output = match &args.output {
        Some(path) => path.clone(),
        None => named_after(&args.scene, "", ".mif"),
    };
    eprintln!(
        "{}",
        runner::hardware_files::write_mif(&args.scene, &output)?
    );
    Ok(())
}
