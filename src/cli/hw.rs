//! `rtprof hw`: the FPGA pipeline model. `table` (the model next to the thesis's tables
//! 7 and 8), `time` (frame time, device fit and what-ifs for a scene, optionally against
//! the measured software), `render` (the image the hardware would show) and `mif` (the
//! scene memory as an Altera Memory Initialization File).

use super::scene_args::{parse_size, thread_pool};
use analysis::median_with_bootstrap;
use anyhow::{Context, Result, bail};
use hwmodel::blocks::Pipeline;
use hwmodel::design::Design;
use hwmodel::device::{Fit, demand, fit, largest_units};
use hwmodel::hw_scene::HwScene;
use hwmodel::library::{DeviceSpec, Library, device_names, find_device};
use hwmodel::pipeline::{FrameTiming, frame_timing};
use hwmodel::table::{Row, Tables, tables};
use reports::sections::hardware::hw_table;
use results::HwRow;
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::time::Instant;
use tracer::{NoCount, RenderOptions, Sampling, Scene, ShadingMode, VariantSet, load_nff};

#[derive(clap::Args, Debug)]
pub struct HwArgs {
    #[command(subcommand)]
    command: HwCommand,
}

#[derive(clap::Subcommand, Debug)]
enum HwCommand {
    /// Tables 7 and 8 as the model computes them, next to the thesis's, with % errors.
    Table(TableArgs),
    /// Frame time, device fit and utilization for a scene (eq. 49), with what-ifs.
    Time(TimeArgs),
    /// The image the hardware shows: f32, spheres and cylinders, diffuse gray, one light.
    Render(RenderArgs),
    /// Write the scene memory as an Altera Memory Initialization File (.mif).
    Mif(MifArgs),
}

/// Design changes shared by `table` and `time`.
#[derive(clap::Args, Debug, Clone)]
struct WhatIf {
    /// What-if: the bit-trick square root (one adder, 1 cycle) instead of the IP core.
    #[arg(long)]
    fast_sqrt: bool,
    /// What-if: orthographic primary rays (no normalize; one direction for all rays).
    #[arg(long)]
    ortho: bool,
    /// What-if: shading without the inverse square root (light at infinity).
    #[arg(long)]
    no_rsqrt_shading: bool,
    /// What-if: K parallel intersection units.
    #[arg(long, value_name = "K", default_value_t = 1,
          value_parser = clap::value_parser!(u32).range(1..=4096))]
    units: u32,
    /// Device (default EP4CE115, the thesis's; others are unvalidated).
    #[arg(long, value_name = "D", default_value = "EP4CE115")]
    device: String,
}

impl WhatIf {
    fn design(&self) -> Design {
        Design {
            units: self.units,
            fast_sqrt: self.fast_sqrt,
            ortho: self.ortho,
            no_rsqrt_shading: self.no_rsqrt_shading,
            ..Design::thesis()
        }
    }

    fn device(&self) -> Result<(Library, DeviceSpec)> {
        find_device(&self.device).with_context(|| {
            format!(
                "unknown device '{}': known devices are {}",
                self.device,
                device_names().join(", ")
            )
        })
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
    /// NFF scene file, or the name of a built-in scene (e.g. balls3).
    scene: PathBuf,
    #[command(flatten)]
    what_if: WhatIf,
    /// Clock in MHz.
    #[arg(long, value_name = "MHZ", default_value_t = 50.0, value_parser = parse_clock)]
    clock: f64,
    /// Frame size WxH.
    #[arg(long, value_name = "WxH", default_value = "640x480", value_parser = parse_size)]
    size: (u32, u32),
    /// Time spheres and cylinders alone when the scene also has other primitives.
    #[arg(long)]
    ignore_unsupported: bool,
    /// Also render the scene in software (diffuse-only gray, baseline, same size) and
    /// report the measured time and the hardware's speed-up.
    #[arg(long)]
    vs_software: bool,
    /// Software threads for --vs-software (the thesis's software ran on one).
    #[arg(long, value_name = "N", default_value_t = 1,
          value_parser = clap::value_parser!(u16).range(1..=1024))]
    threads: u16,
    /// Timed software renders for --vs-software (median).
    #[arg(long, value_name = "N", default_value_t = 3,
          value_parser = clap::value_parser!(u32).range(1..=1000))]
    repeats: u32,
    /// Print JSON: {primitives, units, clock_hz, cycles, seconds, fits, utilization, …}.
    #[arg(long)]
    json: bool,
}

#[derive(clap::Args, Debug)]
struct RenderArgs {
    /// NFF scene file (spheres and cylinders only), or a built-in scene name.
    scene: PathBuf,
    /// Output image, .png or .ppm.
    #[arg(short, long, value_name = "IMG")]
    output: PathBuf,
    /// Image size WxH (default: the scene's resolution).
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    size: Option<(u32, u32)>,
}

#[derive(clap::Args, Debug)]
struct MifArgs {
    /// NFF scene file (spheres and cylinders only), or a built-in scene name.
    scene: PathBuf,
    /// Output .mif file.
    #[arg(short, long, value_name = "FILE.mif")]
    output: PathBuf,
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
    }
}

/// Loads an NFF file, or a built-in scene when `path` is a bare built-in name.
pub fn load_scene(path: &Path) -> Result<Scene> {
    if !path.exists()
        && let Some(name) = path.to_str()
        && let Some(builtin) = tracer::builtin_scenes::find(name)
    {
        return Ok(builtin.parse()?);
    }
    Ok(load_nff(path)?)
}

fn hw_scene(path: &Path, scene: &Scene) -> Result<HwScene> {
    HwScene::from_scene(scene).with_context(|| format!("{}", path.display()))
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
    print!("{}", format_tables(&t, &lib, &device));
    if args.detail {
        print!("{}", format_detail(&Pipeline::build(&lib, &design)));
    }
    Ok(())
}

/// One of tables 7 and 8 as the report's table model, printed in columns.
fn format_rows(rows: &[Row]) -> String {
    let rows: Vec<HwRow> = rows.iter().map(HwRow::from_model_row).collect();
    reports::text::table(&hw_table(&rows))
}

fn format_tables(t: &Tables, lib: &Library, device: &DeviceSpec) -> String {
    let mut out = format!(
        "Operator library: {}{}; device {}{}; design: {}\n\
         cells: model / thesis (error); the thesis's figures are the reference, never inputs\n\n",
        lib.family,
        if lib.validated { "" } else { " (unvalidated)" },
        device.name,
        if device.validated {
            ""
        } else {
            " (unvalidated)"
        },
        t.design,
    );
    out += "Table 7: operations (IP cores from the library; composites built from them)\n";
    out += &format_rows(&t.ops);
    out += "\nTable 8: blocks (dataflow graphs, ASAP schedule, delay-balancing)\n";
    out += &format_rows(&t.blocks);
    out += "\nThe standalone dot-product row of table 7 is a four-lane module (4 multipliers,\n\
            3 adders: 28 elements); the blocks use three lanes. See docs/hardware-model.md.\n";
    out
}

fn format_detail(p: &Pipeline) -> String {
    let mut out = String::new();
    for b in p.table_blocks() {
        let s = &b.schedule;
        out += &format!("\n{}: {} cycles\n  operators:", b.name, s.latency);
        for (op, n) in &s.op_counts {
            out += &format!(" {}×{n}", op.key());
        }
        out += "\n  delay lines (bits × cycles):";
        if s.delay_lines.is_empty() {
            out += " none";
        }
        for l in &s.delay_lines {
            out += &format!(
                "\n    {:<28} {:>3} × {:>3}{}",
                l.producer,
                l.bits,
                l.cycles,
                if l.in_memory { "  (memory)" } else { "" }
            );
        }
        out += "\n";
    }
    out
}

// ----------------------------------------------------------------------------- time

/// One design's prediction for a scene.
#[derive(Serialize)]
struct Prediction {
    design: String,
    #[serde(flatten)]
    timing: FrameTiming,
    fits: bool,
    utilization: hwmodel::device::Utilization,
    #[serde(rename = "fit")]
    detail: Fit,
    /// The largest number of intersection units that fits this device.
    largest_units: Option<u32>,
}

/// Measured software time of the same job.
#[derive(Serialize)]
struct Software {
    seconds: f64,
    low: f64,
    high: f64,
    threads: u16,
    repeats: u32,
    /// Software seconds / hardware seconds.
    speedup: f64,
}

#[derive(Serialize)]
struct TimeReport {
    scene: String,
    device: String,
    device_validated: bool,
    #[serde(flatten)]
    prediction: Prediction,
    /// The thesis's design on the same scene, when a what-if changed it.
    thesis_design: Option<Prediction>,
    software: Option<Software>,
    /// Primitives the hardware cannot hold that were left out (--ignore-unsupported).
    ignored: Option<String>,
}

fn predict(
    lib: &Library,
    device: &DeviceSpec,
    design: &Design,
    primitives: u64,
    (width, height): (u32, u32),
    clock_hz: f64,
) -> Prediction {
    let pipeline = Pipeline::build(lib, design);
    let timing = frame_timing(&pipeline, primitives, width, height, clock_hz);
    let f = fit(
        lib,
        device,
        demand(lib, &pipeline, primitives, width, height),
    );
    Prediction {
        design: design.label(),
        timing,
        fits: f.fits,
        utilization: f.utilization.clone(),
        detail: f,
        largest_units: largest_units(lib, device, design, primitives, width, height),
    }
}

fn time(args: &TimeArgs) -> Result<()> {
    let (lib, device) = args.what_if.device()?;
    let scene = load_scene(&args.scene)?;
    let (primitives, ignored) = match HwScene::from_scene(&scene) {
        Ok(hw) => (hw.primitive_count() as u64, None),
        Err(e) if args.ignore_unsupported => {
            let n = scene.spheres.len() + scene.cylinders.len();
            (n as u64, Some(e.to_string()))
        }
        Err(e) => bail!(
            "{}: {e}\n(pass --ignore-unsupported to time its spheres and cylinders alone)",
            args.scene.display()
        ),
    };
    let clock_hz = args.clock * 1e6;
    let design = args.what_if.design();
    let prediction = predict(&lib, &device, &design, primitives, args.size, clock_hz);
    let thesis_design = (!design.is_thesis()).then(|| {
        predict(
            &lib,
            &device,
            &Design::thesis(),
            primitives,
            args.size,
            clock_hz,
        )
    });
    let software = if args.vs_software {
        Some(measure_software(args, &scene, prediction.timing.seconds)?)
    } else {
        None
    };
    let report = TimeReport {
        scene: args.scene.display().to_string(),
        device: device.name.clone(),
        device_validated: lib.validated && device.validated,
        prediction,
        thesis_design,
        software,
        ignored,
    };
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print!("{}", format_time(&report));
    }
    Ok(())
}

fn measure_software(args: &TimeArgs, scene: &Scene, hw_seconds: f64) -> Result<Software> {
    let (width, height) = args.size;
    let options = RenderOptions::new(
        width,
        height,
        Sampling::PixelCenters,
        ShadingMode::DiffuseOnly,
    );
    let variants = VariantSet::parse("baseline")?;
    let pool = thread_pool(Some(args.threads))?;
    let mut samples = Vec::with_capacity(args.repeats as usize);
    for run in 0..args.repeats {
        eprint!("\rsoftware render {}/{}", run + 1, args.repeats);
        let start = Instant::now();
        pool.install(|| tracer::render_variant::<NoCount>(scene, &options, &variants, &|_| {}))
            .with_context(|| args.scene.display().to_string())?;
        samples.push(start.elapsed().as_secs_f64());
    }
    eprintln!();
    let est = median_with_bootstrap(&samples, 2000, 0.95, 0x5eed)?;
    Ok(Software {
        seconds: est.median,
        low: est.low,
        high: est.high,
        threads: args.threads,
        repeats: args.repeats,
        speedup: est.median / hw_seconds,
    })
}

fn pct(x: f64) -> String {
    format!("{:.1} %", x * 100.0)
}

fn format_prediction_column(p: &Prediction) -> Vec<String> {
    let f = &p.detail;
    vec![
        p.design.clone(),
        p.timing.units.to_string(),
        p.timing.cycles_per_pixel.to_string(),
        p.timing.fill_cycles.to_string(),
        p.timing.cycles.to_string(),
        format!(
            "{:.6} s ({:.1} fps)",
            p.timing.seconds,
            1.0 / p.timing.seconds
        ),
        format!("{} ({})", f.used.le, pct(f.utilization.le)),
        format!(
            "{} ({}){}",
            f.used.mult,
            pct(f.utilization.mult),
            if f.soft_mult_elements > 0 {
                format!(" + {} in logic", f.soft_mult_elements)
            } else {
                String::new()
            }
        ),
        format!("{} ({})", f.used.mem_bits, pct(f.utilization.mem_bits)),
        format!("{} ({})", f.plls, pct(f.utilization.plls)),
        if f.fits {
            "yes".to_string()
        } else {
            format!("no ({} over)", f.over.join(", "))
        },
        p.largest_units
            .map_or_else(|| "none".to_string(), |k| k.to_string()),
    ]
}

fn format_time(r: &TimeReport) -> String {
    let p = &r.prediction;
    let mut out = format!(
        "{}: {} primitives, {}x{} at {} MHz on {}{}\n",
        r.scene,
        p.timing.primitives,
        p.timing.width,
        p.timing.height,
        p.timing.clock_hz / 1e6,
        r.device,
        if r.device_validated {
            ""
        } else {
            " (unvalidated)"
        }
    );
    if let Some(ignored) = &r.ignored {
        out += &format!("left out: {ignored}\n");
    }
    let labels = [
        "design",
        "units K",
        "cycles per pixel",
        "fill cycles",
        "cycles",
        "frame time",
        "LEs",
        "9-bit multipliers",
        "memory bits",
        "PLLs",
        "fits",
        "largest K that fits",
    ];
    let mut columns = Vec::new();
    if let Some(t) = &r.thesis_design {
        columns.push(format_prediction_column(t));
    }
    columns.push(format_prediction_column(p));
    for (i, label) in labels.iter().enumerate() {
        out += &format!("  {label:<20}");
        for c in &columns {
            out += &format!(" {:<34}", c[i]);
        }
        out += "\n";
    }
    if let Some(t) = &r.thesis_design {
        out += &format!(
            "  what-if vs thesis: {:.2}x the frame rate, {:+.1} % LEs\n",
            t.timing.seconds / p.timing.seconds,
            (p.detail.used.le as f64 / t.detail.used.le as f64 - 1.0) * 100.0
        );
    }
    if p.detail.soft_mult_elements > 0 {
        out += &format!(
            "  multiplier rule: {} elements beyond the device's {} are built in logic ({} LEs)\n",
            p.detail.soft_mult_elements, p.detail.used.mult, p.detail.soft_mult_le
        );
    }
    if let Some(s) = &r.software {
        out += &format!(
            "  software (baseline, diffuse-only gray, {} thread{}): {:.4} s [{:.4}, {:.4}] → hardware speed-up {:.2}x{}\n",
            s.threads,
            if s.threads == 1 { "" } else { "s" },
            s.seconds,
            s.low,
            s.high,
            s.speedup,
            if s.speedup < 1.0 {
                " (the software is faster)"
            } else {
                ""
            }
        );
    }
    out
}

// --------------------------------------------------------------------- render, mif

fn render(args: &RenderArgs) -> Result<()> {
    tracer::image_io::ImageFormat::from_path(&args.output)?;
    let scene = load_scene(&args.scene)?;
    let hw = hw_scene(&args.scene, &scene)?;
    let (width, height) = args.size.unwrap_or((scene.view.width, scene.view.height));
    let image = hwmodel::emulator::render(&hw, width, height);
    hwmodel::emulator::write_image(&image, &args.output)?;
    eprintln!(
        "wrote {} ({width}x{height}, {} primitives, the hardware's diffuse gray)",
        args.output.display(),
        hw.primitive_count()
    );
    Ok(())
}

fn mif(args: &MifArgs) -> Result<()> {
    let scene = load_scene(&args.scene)?;
    let hw = hw_scene(&args.scene, &scene)?;
    let text = hwmodel::mif::to_mif(&hw);
    tracer::image_io::write_atomically(&args.output, text.as_bytes())
        .with_context(|| format!("cannot write {}", args.output.display()))?;
    eprintln!(
        "wrote {} ({} primitives, {} words of 32 bits)",
        args.output.display(),
        hw.primitive_count(),
        hw.primitive_count() * 9
    );
    Ok(())
}
