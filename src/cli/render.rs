//! `rtprof render`: uncounted render to an image file.

use super::scene_args::{SceneArgs, named_after};
use anyhow::Result;
use std::path::PathBuf;
use tracer::image_io::{ImageFormat, write_image};
use tracer::{NoCount, ShadingMode};

#[derive(clap::Args, Debug)]
pub struct RenderArgs {
    #[command(flatten)]
    scene: SceneArgs,
    /// Output image, .png or .ppm (default: the scene's name with .png, here).
    #[arg(short, long, value_name = "IMG")]
    output: Option<PathBuf>,
    /// Full shading converted to gray.
    #[arg(long)]
    gray: bool,
    /// The thesis hardware's shading: Lambert term of the first light only, gray
    /// (with or without --gray: it is gray either way).
    #[arg(long)]
    diffuse_only: bool,
}

pub fn run(args: &RenderArgs) -> Result<()> {
    let output = match &args.output {
        Some(path) => path.clone(),
        None => named_after(&args.scene.scene, "", ".png"),
    };
    // Refuse a bad output name before spending the render time.
    ImageFormat::from_path(&output)?;
    let mode = if args.diffuse_only {
        ShadingMode::DiffuseOnly
    } else if args.gray {
        ShadingMode::Gray
    } else {
        ShadingMode::Color
    };
    let run = args.scene.run::<NoCount>(mode)?;
    write_image(&output, &run.rendered.frame)?;
    eprintln!("{}", run.timing_report(&args.scene.scene));
    eprintln!(
        "wrote {} ({}x{})",
        output.display(),
        run.rendered.frame.width,
        run.rendered.frame.height
    );
    Ok(())
}
