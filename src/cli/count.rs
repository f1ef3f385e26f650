//! `rtprof count`: counted render; prints a table-6-style listing or JSON, and with
//! `--pixel-stats DIR` writes the per-pixel maps of the counts and of the time.

use super::scene_args::SceneArgs;
use anyhow::{Context, Result};
use runner::pixel_maps::{MapsContext, TIMED_PASSES, maps_of, write_maps};
use std::path::{Path, PathBuf};
use tracer::{Count, NoCount, ShadingMode};

#[derive(clap::Args, Debug)]
pub struct CountArgs {
    #[command(flatten)]
    scene: SceneArgs,
    /// Print the counts as JSON (keys are the counter names: {"rays": {"primary": N, …}, …}).
    #[arg(long)]
    json: bool,
    /// Also write per-pixel maps into DIR: tests by kind, BVH nodes and leaves, shadow
    /// and secondary rays, dot products, ray-tree depth and time per sample (the least
    /// of three uncounted renders), each as KEY.npy (NumPy) and KEY.png, with
    /// pixel-stats.json.
    #[arg(long, value_name = "DIR")]
    pixel_stats: Option<PathBuf>,
}

pub fn run(args: &CountArgs) -> Result<()> {
    let per_sample = args.pixel_stats.is_some();
    let run = args
        .scene
        .run_with::<Count>(ShadingMode::Color, per_sample)?;
    let counts = run
        .rendered
        .counts()
        .context("the counted render returned no counts")?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&counts)?);
    } else {
        print!("{}", counts.to_text());
    }
    eprintln!("{}", run.timing_report(&args.scene.scene));
    for line in run.structure_lines(&counts) {
        eprintln!("{line}");
    }
    if let Some(dir) = &args.pixel_stats {
        write_pixel_stats(args, &run, dir)?;
    }
    Ok(())
}

fn write_pixel_stats(
    args: &CountArgs,
    counted: &runner::render_job::SceneRender<Count>,
    dir: &Path,
) -> Result<()> {
    let mut timed = Vec::new();
    for _ in 0..TIMED_PASSES {
        let run = args.scene.run_with::<NoCount>(ShadingMode::Color, true)?;
        timed.extend(run.rendered.samples);
    }
    let Some(counted_samples) = &counted.rendered.samples else {
        anyhow::bail!("the counted render kept no per-sample records");
    };
    let totals = tracer::Counter::totals(&counted.rendered.counter)
        .context("the counted render returned no counts")?;
    let maps = maps_of(counted_samples, &timed, &totals)?;
    let resolution = tracer::pixel_stats::clock_resolution();
    let options = args.scene.render.options(&counted.scene);
    let stats = write_maps(
        dir,
        &maps,
        &MapsContext {
            scene: &args.scene.scene.to_string(),
            variant: &args.scene.variant,
            sampling: options.sampling,
            threads: counted.threads,
            clock_resolution_ns: resolution.as_secs_f64() * 1e9,
        },
    )?;
    eprintln!(
        "wrote {} per-pixel maps ({}x{} samples) to {}: {}",
        stats.maps.len(),
        stats.columns,
        stats.rows,
        dir.display(),
        stats
            .maps
            .iter()
            .map(|m| m.key.as_str())
            .collect::<Vec<_>>()
            .join(", ")
    );
    Ok(())
}
