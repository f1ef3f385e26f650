//! `rtprof count`: counted render; prints a table-6-style listing or JSON.

use super::scene_args::SceneArgs;
use anyhow::{Context, Result};
use tracer::{Count, ShadingMode};

#[derive(clap::Args, Debug)]
pub struct CountArgs {
    #[command(flatten)]
    scene: SceneArgs,
    /// Print the counts as JSON (keys are the counter names: {"rays": {"primary": N, …}, …}).
    #[arg(long)]
    json: bool,
}

pub fn run(args: &CountArgs) -> Result<()> {
    let run = args.scene.run::<Count>(ShadingMode::Color)?;
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
    Ok(())
}
