//! `rtprof compare`: image metrics of two images, or a side-by-side run of variants on
//! one scene (time with a bootstrap interval, speed-up, image error, counts), all
//! against the first image or variant.

use super::scene_args::ShadingFlags;
use super::{Exports, Format, Outcome};
use anyhow::{Result, bail};
use runner::compare::SideBySide;
use runner::render_job::RenderSettings;
use runner::scene_input::SceneInput;
use std::path::{Path, PathBuf};
use terminal::progress::Bars;
use tracer::VariantSet;

#[derive(clap::Args, Debug)]
pub struct CompareArgs {
    /// Two images (PNG or PPM) to compare, or one scene with --variants (an NFF file,
    /// a built-in or generated name such as spd:gears; `rtprof scene list`).
    #[arg(required = true, num_args = 1..=2, value_name = "IMG_A IMG_B | SCENE")]
    inputs: Vec<PathBuf>,
    /// Variants to run on the scene, the first being the reference; combine with '+',
    /// e.g. baseline,bvh,bvh+fast-sqrt.
    #[arg(long, value_name = "A,B,…")]
    variants: Option<String>,
    /// With --variants: also render the scene with the f64 reference renderer (the ground
    /// truth, docs/reference.md) and give each variant's RMS, PSNR and largest error
    /// against it.
    #[arg(long, requires = "variants")]
    reference: bool,
    /// Timed renders per variant (median and 95 % bootstrap interval).
    #[arg(long, value_name = "N", default_value_t = 3,
          value_parser = clap::value_parser!(u32).range(1..=1000))]
    repeats: u32,
    #[command(flatten)]
    render: RenderSettings,
    #[command(flatten)]
    shading: ShadingFlags,
    #[command(flatten)]
    tracers: runner::outside::TracerFlags,
    /// Print the result as JSON (the same as --format json).
    #[arg(long)]
    json: bool,
    /// Output: a table, GitHub Markdown, CSV or JSON.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    format: Format,
    /// Images: the difference heat map (two images), or a directory for every variant's
    /// image and heat map (scene).
    #[arg(short, long, value_name = "DIFF.png | DIR")]
    output: Option<PathBuf>,
}

pub fn run(args: &CompareArgs) -> Result<()> {
    match (&args.variants, args.inputs.as_slice()) {
        (None, [a, b]) => compare_images(args, a, b),
        (Some(list), [scene]) => side_by_side(args, scene, list),
        (Some(_), [_, _]) => bail!("--variants takes one scene, not two inputs"),
        _ => bail!("give two images to compare, or a scene with --variants A,B,…"),
    }
}

fn compare_images(args: &CompareArgs, a: &Path, b: &Path) -> Result<()> {
    let format = if args.json { Format::Json } else { args.format };
    let report =
        runner::compare::compare_images(a, b, args.output.as_deref(), format == Format::Json)?;
    print!("{}", report.render(format)?);
    Ok(())
}

fn side_by_side(args: &CompareArgs, scene_arg: &Path, list: &str) -> Result<()> {
    let sets = VariantSet::parse_list(list)?;
    let input = SceneInput::parse(&scene_arg.to_string_lossy(), Path::new(""))?;
    let report = SideBySide {
        input: &input,
        sets: &sets,
        settings: &args.render,
        mode: args.shading.mode(),
        repeats: args.repeats,
        out: args.output.as_deref(),
        f64_reference: args.reference,
        tracers: &args.tracers,
    }
    .run(&Bars::default())?;
    let format = if args.json { Format::Json } else { args.format };
    print!("{}", report.render(format)?);
    match report.failure_summary() {
        Some(message) => Err(Outcome::new(Outcome::PARTS_FAILED, message).into()),
        None => Ok(()),
    }
}
