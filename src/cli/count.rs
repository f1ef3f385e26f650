//! `rtprof count`: counted render; prints a table-6-style listing or JSON, and with
//! `--pixel-stats DIR` writes the per-pixel maps of the counts and of the time.

use super::scene_args::SceneArgs;
use anyhow::{Context, Result};
use runner::pixel_maps::{MapsContext, record_maps_of, write_maps, written_line};
use runner::pool::thread_pool;
use runner::render_job::SceneRender;
use runner::render_setup::RenderSetup;
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;
use tracer::{Count, ShadingMode};

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

/// The per-pixel maps of the counted render `counted` and three timed ones, into `dir`.
fn write_pixel_stats(args: &CountArgs, counted: &SceneRender<Count>, dir: &Path) -> Result<()> {
    let options = args
        .scene
        .render
        .options(&counted.scene, ShadingMode::Color);
    let pool = thread_pool(args.scene.render.threads)?;
    let name = args.scene.scene.to_string();
    let never = AtomicBool::new(false);
    let setup = RenderSetup {
        scene: &counted.scene,
        name: &name,
        options: &options,
        pool: &pool,
        counting_pool: &pool,
        stop: &never,
    };
    let maps = record_maps_of(&setup, &counted.variants, &counted.rendered)?;
    let context = MapsContext {
        scene: &name,
        variant: &args.scene.variant,
        sampling: options.sampling,
        threads: counted.threads,
        clock_resolution_ns: tracer::pixel_stats::clock_resolution().as_secs_f64() * 1e9,
    };
    let stats = write_maps(dir, &maps, &context)?;
    eprintln!("{}", written_line(&stats, dir));
    Ok(())
}
