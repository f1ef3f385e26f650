//! `rtprof hw rtl | sim | synth`: the pipeline as generated Verilog, simulated cycle by
//! cycle with Verilator and synthesized with Yosys, held against the model.

use super::scene_args::{SCENE_HELP, SIZE_HELP, named_after, parse_scene};
use anyhow::{Context, Result, bail};
use hwmodel::blocks::Pipeline;
use hwmodel::design::Design;
use hwmodel::emulator::write_image;
use hwmodel::library::Library;
use rtl::generate;
use rtl::sim;
use runner::hardware_files::hardware_scene;
use runner::scene_input::SceneInput;
use std::path::PathBuf;

// The design the RTL is generated for: the model's design flags, within what the
// generator builds.
#[derive(clap::Args, Debug, Clone)]
pub struct RtlDesign {
    #[command(flatten)]
    flags: super::hw::DesignFlags,
}

/// Most intersection units the generator builds (the comparator tree's width).
const MAX_RTL_UNITS: u32 = 64;

impl RtlDesign {
    fn design(&self) -> Result<Design> {
        let design = self.flags.design();
        anyhow::ensure!(
            design.units <= MAX_RTL_UNITS,
            "--units {}: the RTL is generated for at most {MAX_RTL_UNITS} units \
             (`rtprof hw time --units K` models more)",
            design.units
        );
        Ok(design)
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
    #[arg(long, value_name = "WxH", value_parser = super::scene_args::parse_size, help = SIZE_HELP)]
    size: Option<(u32, u32)>,
}

#[derive(clap::Args, Debug)]
pub struct SimArgs {
    #[arg(value_name = "SCENE", value_parser = parse_scene, help = SCENE_HELP)]
    scene: SceneInput,
    #[command(flatten)]
    design: RtlDesign,
    #[arg(long, value_name = "WxH", value_parser = super::scene_args::parse_size, help = SIZE_HELP)]
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

fn cache_dir() -> PathBuf {
    if let Some(dir) = std::env::var_os("XDG_CACHE_HOME") {
        return PathBuf::from(dir).join("rtprof").join("rtl");
    }
    match std::env::var_os("HOME") {
        Some(home) => PathBuf::from(home)
            .join(".cache")
            .join("rtprof")
            .join("rtl"),
        None => std::env::temp_dir().join("rtprof-rtl"),
    }
}

pub fn rtl(args: &RtlArgs) -> Result<()> {
    let lib = Library::cyclone_iv_e();
    let design = args.design.design()?;
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
        rtl::operators::write_atomically(
            &args.output.join("sim_input.txt"),
            &sim::testbench_input(&pipeline, hw, width, height)?,
        )?;
        rtl::operators::write_atomically(
            &args.output.join("scene.mif"),
            &hwmodel::mif::to_mif(hw),
        )?;
        written += 2;
    }
    println!(
        "wrote {written} files to {} ({} design, scene memory of {} primitives)",
        args.output.display(),
        design.label(),
        1u32 << rtl.depth_bits
    );
    for b in &rtl.blocks {
        println!("  {:<14} {:>4} cycles", b.name, b.latency);
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
    let design = args.design.design()?;
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
    let root = args.build_dir.clone().unwrap_or_else(cache_dir);
    eprintln!(
        "rtprof: building the Verilator model of the {} design in {} (once per design, a minute or two)",
        design.label(),
        root.display()
    );
    let program = sim::build(&rtl, &root)?;
    let work = program
        .parent()
        .and_then(|p| p.parent())
        .map(|p| p.join("runs").join(format!("{}", std::process::id())))
        .context("the simulator has no build directory")?;
    eprintln!(
        "rtprof: simulating {width}x{height} ({} primitives)",
        hw.primitive_count()
    );
    let result = sim::run(&program, &pipeline, &hw, width, height, &work)?;
    let _ = std::fs::remove_dir_all(&work);
    write_image(&result.image, &output)?;
    let (reference, source) = sim::reference_image(&pipeline, &hw, width, height)?;
    let diff = sim::compare_images(&result.image, &reference);
    let latencies_agree = result
        .blocks
        .iter()
        .all(|b| b.simulated == Some(u64::from(b.model)));
    let agrees = diff.differing_pixels == 0
        && result.cycles == result.model_cycles
        && result.writes == u64::from(width) * u64::from(height)
        && latencies_agree;
    if args.json {
        let json = serde_json::json!({
            "scene": args.scene.to_string(),
            "design": design.label(),
            "units": design.units,
            "width": width,
            "height": height,
            "primitives": hw.primitive_count(),
            "cycles": result.cycles,
            "model_cycles": result.model_cycles,
            "writes": result.writes,
            "blocks": result.blocks,
            "image": output.display().to_string(),
            "reference": source,
            "differing_pixels": diff.differing_pixels,
            "rms": diff.rms,
            "agrees": agrees,
        });
        println!("{}", serde_json::to_string_pretty(&json)?);
    } else {
        println!(
            "{} on the {} design, {width}x{height}, {} primitives",
            args.scene,
            design.label(),
            hw.primitive_count()
        );
        println!(
            "  cycles per frame   {:>12}  model {:>12}  {}",
            result.cycles,
            result.model_cycles,
            if result.cycles == result.model_cycles {
                "equal"
            } else {
                "DIFFERENT"
            }
        );
        println!("  block latencies (first valid output after the first input):");
        for b in &result.blocks {
            let sim = b.simulated.map_or("none".to_string(), |v| v.to_string());
            println!(
                "    {:<14} {:>5}  model {:>5}  {}",
                b.name,
                sim,
                b.model,
                if b.simulated == Some(u64::from(b.model)) {
                    "equal"
                } else {
                    "DIFFERENT"
                }
            );
        }
        println!(
            "  image {}: {} of {} pixels differ from {source} (RMS {:.3})",
            output.display(),
            diff.differing_pixels,
            reference.pixels.len(),
            diff.rms
        );
    }
    if !agrees {
        // A failed check, not bad input: exit code 1.
        return Err(super::Outcome::new(
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
    /// Print JSON: {blocks: [{name, yosys: {lut4, ff, mem_bits, m9k, mult_lut4},
    /// model: {le, regs, mem_bits}, thesis: {le, regs} | null}], total, …}.
    #[arg(long)]
    json: bool,
}

/// Why Yosys's figures are not Quartus's (the thesis's) nor the model's.
const SYNTH_REASONS: &str = "\
Why the columns differ:
  - Yosys's synth_intel (experimental) maps logic to LUT4s without arithmetic-mode carry
    chains: an adder or comparator costs more cells than in Quartus (one LE per bit).
  - No DSP inference: multipliers are built of LUTs (mult LUT4) where Quartus uses the
    embedded 9x9 multipliers; subtract them to compare with the LE columns.
  - These are rtprof's own operators (rtl/verilog), not the ALTFP cores the model's
    library rows (table 7) were measured on: a combinational core followed by its
    latency in output registers (add/sub: 7 x 32 = 224 FF), where an ALTFP core
    pipelines inside (415 registers), hence fewer FF and deeper logic.
  - A logic element holds one LUT4 and one flip-flop: the design needs between
    max(LUT4, FF) and LUT4 + FF of them.
  - The minimum-distance block carries its payload 3 cycles beside the compare (the
    model holds its inputs instead), and the top adds the iterator, scene memory ports
    and control delay lines, which the table's blocks do not include.";

pub fn synth(args: &SynthArgs) -> Result<()> {
    let lib = Library::cyclone_iv_e();
    let design = args.design.design()?;
    let pipeline = Pipeline::build(&lib, &design);
    let rtl = generate::generate(&lib, &pipeline, sim::depth_bits_for(0))?;
    let work = match &args.work_dir {
        Some(dir) => dir.clone(),
        None => std::env::temp_dir().join(format!("rtprof-synth-{}", std::process::id())),
    };
    generate::write(&rtl, &work)?;
    let files: Vec<PathBuf> = rtl
        .files
        .iter()
        .filter(|(n, _)| n.ends_with(".v"))
        .map(|(n, _)| work.join(n))
        .collect();
    let names: Vec<&str> = rtl.blocks.iter().map(|b| b.name).collect();
    let (top, blocks): (&str, Vec<&str>) = match &args.block {
        Some(b) => {
            let Some(name) = names.iter().find(|n| **n == b.as_str()) else {
                bail!(
                    "no block '{b}' in the {} design: one of {}",
                    design.label(),
                    names.join(", ")
                );
            };
            (name, vec![*name])
        }
        None => (generate::TOP, names.clone()),
    };
    eprintln!(
        "rtprof: synthesizing {} of the {} design with Yosys for Cyclone IV E in {} (minutes for the square roots and dividers)",
        if args.block.is_some() {
            top
        } else {
            "every block"
        },
        design.label(),
        work.display()
    );
    let report = rtl::synth::synthesize(&work, &files, top, &blocks)?;
    let tables = hwmodel::table::tables(&lib, &design);
    let mut rows = Vec::new();
    for name in &blocks {
        let yosys = report.block(name).map(|b| b.figures);
        let block = pipeline
            .blocks_in_order()
            .into_iter()
            .find(|b| b.name == *name);
        let model = block.map(|b| b.resources());
        let thesis = tables
            .blocks
            .iter()
            .find(|r| r.model.name == *name)
            .and_then(|r| r.thesis);
        rows.push((name.to_string(), yosys, model, thesis));
    }
    if args.json {
        let blocks: Vec<_> = rows
            .iter()
            .map(|(name, y, m, t)| {
                serde_json::json!({
                    "name": name,
                    "yosys": y,
                    "model": m.map(|m| serde_json::json!({"le": m.le, "regs": m.regs, "mem_bits": m.mem_bits, "mult": m.mult})),
                    "thesis": t.map(|t| serde_json::json!({"le": t.le, "regs": t.regs, "mem_bits": t.mem_bits, "mult": t.mult})),
                })
            })
            .collect();
        let json = serde_json::json!({
            "design": design.label(),
            "top": report.top,
            "yosys_version": report.yosys,
            "family": report.family,
            "seconds": report.seconds,
            "total": report.total,
            "unmapped": report.unmapped,
            "check_problems": report.check_problems,
            "blocks": blocks,
        });
        println!("{}", serde_json::to_string_pretty(&json)?);
        return Ok(());
    }
    println!(
        "Yosys ({}) synth_intel -family cycloneive, {} design, {:.0} s",
        report.yosys,
        design.label(),
        report.seconds
    );
    println!(
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
    for (name, y, m, t) in &rows {
        println!(
            "{:<14} {:>9} {:>9} {:>9} {:>9} | {:>9} {:>9} {:>9} | {:>9} {:>9}",
            name,
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
    if args.block.is_none() {
        println!(
            "{:<14} {:>9} {:>9} {:>9} {:>9}",
            "whole design",
            report.total.lut4,
            report.total.mult_lut4,
            report.total.ff,
            report.total.mem_bits
        );
    }
    if !report.unmapped.is_empty() || report.check_problems > 0 {
        println!(
            "warning: {} unmapped cell kinds, {} check problems (log: {})",
            report.unmapped.len(),
            report.check_problems,
            report.log.display()
        );
    }
    println!("{SYNTH_REASONS}");
    Ok(())
}
