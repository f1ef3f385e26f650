//! `rtprof render`: uncounted render to an image file, by the tracer or (with
//! `--reference`) by the independent f64 reference renderer.

use super::scene_args::{SceneArgs, ShadingFlags};
use terminal::progress::Bars;

use anyhow::Result;
use runner::reference_job::render_reference;
use std::io::Write;
use std::path::{Path, PathBuf};
use tracer::NoCount;
use tracer::image_io::{ImageFormat, write_image};

#[derive(clap::Args, Debug)]
pub struct RenderArgs {
    #[command(flatten)]
    scene: SceneArgs,
    /// Output image, .png or .ppm (default: the scene's name with .png, here).
    #[arg(short, long, value_name = "IMG")]
    output: Option<PathBuf>,
    #[command(flatten)]
    shading: ShadingFlags,
    /// Render with the f64 reference renderer instead of the tracer: double precision,
    /// cancellation-free intersection tests, the same camera and shading rules
    /// (docs/reference.md). The ground truth to compare variants with; a few times bvh's time.
    #[arg(long, conflicts_with = "variant")]
    reference: bool,
}

pub fn run(args: &RenderArgs) -> Result<()> {
    let output = match &args.output {
        Some(path) => path.clone(),
        None => args.scene.scene.named_after("", ".png"),
    };
    // Refuse a bad output name before spending the render time.
    ImageFormat::from_path(&output)?;
    if args.reference {
        return run_reference(args, &output);
    }
    let run = args.scene.run::<NoCount>(args.shading.mode())?;
    terminal::startup::mark("render");
    terminal::startup::took("render.preprocessing", run.preprocessing);
    terminal::startup::took("render.tracing", run.tracing);
    let frame = &run.rendered.frame;
    write_image(&output, frame)?;
    let timing = run.timing_report(&args.scene.scene);
    report(&timing, &output, (frame.width, frame.height))
}

/// The timing report and the written file, after the image is written.
fn report(timing: &str, output: &Path, (width, height): (u32, u32)) -> Result<()> {
    terminal::startup::mark("image");
    // One write for the report: stderr is unbuffered, and each piece of a formatted
    // line would otherwise be its own write.
    let size = reports::format::size(width, height);
    let report = format!("{timing}\nwrote {} ({size})\n", output.display());
    std::io::stderr().lock().write_all(report.as_bytes())?;
    terminal::startup::mark("report");
    Ok(())
}

/// `--reference`: the f64 reference render to `output`.
fn run_reference(args: &RenderArgs, output: &Path) -> Result<()> {
    let run = render_reference(
        &args.scene.scene,
        &args.scene.render,
        args.shading.mode(),
        &Bars::delayed(),
    )?;
    terminal::startup::mark("render");
    write_image(output, &run.frame)?;
    let timing = run.timing_report(&args.scene.scene);
    report(&timing, output, (run.frame.width, run.frame.height))
}
