//! `rtprof render`: uncounted render to an image file, by the tracer or (with
//! `--reference`) by the independent f64 reference renderer.

use super::scene_args::{SceneArgs, ShadingFlags, named_after};
use terminal::progress::Bars;

use anyhow::Result;
use runner::reference_job::render_reference;
use std::io::Write;
use std::path::PathBuf;
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
        None => named_after(&args.scene.scene, "", ".png"),
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
    write_image(&output, &run.rendered.frame)?;
    terminal::startup::mark("image");
    // One write for the report: stderr is unbuffered, and each piece of a formatted
    // line would otherwise be its own write.
    let report = format!(
        "{}\nwrote {} ({}x{})\n",
        run.timing_report(&args.scene.scene),
        output.display(),
        run.rendered.frame.width,
        run.rendered.frame.height
    );
    std::io::stderr().lock().write_all(report.as_bytes())?;
    terminal::startup::mark("report");
    Ok(())
}

/// `--reference`: the f64 reference render to `output`.
fn run_reference(args: &RenderArgs, output: &std::path::Path) -> Result<()> {
    let run = render_reference(
        &args.scene.scene,
        &args.scene.render,
        args.shading.mode(),
        &Bars::delayed(),
    )?;
    terminal::startup::mark("render");
    write_image(output, &run.frame)?;
    terminal::startup::mark("image");
    let report = format!(
        "{}\nwrote {} ({}x{})\n",
        run.timing_report(&args.scene.scene),
        output.display(),
        run.frame.width,
        run.frame.height
    );
    std::io::stderr().lock().write_all(report.as_bytes())?;
    terminal::startup::mark("report");
    Ok(())
}
