//! `rtprof count`: counted render; prints a table-6-style listing or JSON, and with
//! `--pixel-stats DIR` writes the per-pixel maps of the counts and of the time
//! (`runner::pixel_maps`).

use super::scene_args::{SceneArgs, ShadingFlags};
use anyhow::{Context, Result};
use std::path::PathBuf;
use tracer::Count;

#[derive(clap::Args, Debug)]
pub struct CountArgs {
    #[command(flatten)]
    scene: SceneArgs,
    #[command(flatten)]
    shading: ShadingFlags,
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
        .run_with::<Count>(args.shading.mode(), per_sample)?;
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
        let name = args.scene.scene.to_string();
        let (variant, settings) = (&args.scene.variant, &args.scene.render);
        let written =
            runner::pixel_maps::write_maps_of_render(&run, &name, variant, settings, dir)?;
        eprintln!("{written}");
    }
    Ok(())
}
