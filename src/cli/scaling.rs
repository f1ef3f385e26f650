//! `rtprof scaling`: the growth study. Each accelerator's time, tests and nodes visited
//! per ray against the primitive count of SPD scenes generated at growing size factors
//! (tens to over a million primitives), with the fitted exponent per accelerator and
//! the BVH's build time and memory. Writes scaling.json, scaling.csv, scaling.md and
//! the log-log chart scaling.svg.

use super::{Exports, Format};
use anyhow::Result;
use runner::render_job::parse_size;
use runner::scaling::{Family, ScalingPlan};
use std::path::PathBuf;
use terminal::progress::Bars;

#[derive(clap::Args, Debug)]
pub struct ScalingArgs {
    /// Output directory.
    #[arg(short, long, value_name = "DIR", default_value = "rtprof-scaling")]
    output: PathBuf,
    /// The CI-sized study: small scenes, one repeat.
    #[arg(long)]
    quick: bool,
    /// A scene family and its size factors, e.g. balls:1-6 or shells:1-13:2 (step 2);
    /// repeat for several [default: balls:1-6, shells:1-13:2, tetra:2-10:2].
    #[arg(long, value_name = "SPD:FROM-TO[:STEP]", value_parser = Family::parse)]
    family: Vec<Family>,
    /// Frame of every render, pixel centres [default: 128x128].
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    size: Option<(u32, u32)>,
    /// Timed renders per point, at least (the median is kept); more, up to 100, until
    /// 0.25 s of tracing is measured [default: 3].
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=100))]
    repeats: Option<u32>,
    /// Brute-force and SIMD renders predicted longer than this are extrapolated
    /// instead of run [default: 2].
    #[arg(long, value_name = "SECONDS")]
    budget: Option<f64>,
    /// Worker threads (default: one per core).
    #[arg(long, value_name = "N", value_parser = runner::pool::parse_threads)]
    threads: Option<u16>,
    /// What to print: a table, Markdown, CSV or JSON.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    format: Format,
}

pub fn run(args: &ScalingArgs) -> Result<()> {
    let mut plan = ScalingPlan::default_plan(args.quick);
    if !args.family.is_empty() {
        plan.families = args.family.clone();
    }
    plan.size = args.size.unwrap_or(plan.size);
    plan.repeats = args.repeats.unwrap_or(plan.repeats);
    plan.budget_seconds = args.budget.unwrap_or(plan.budget_seconds);
    let stop = terminal::interrupt::install();
    let (study, files) = plan.run_into(&args.output, args.threads, &Bars::default(), stop)?;
    print!("{}", study.render(args.format)?);
    eprintln!("wrote {}", files.line(&args.output));
    Ok(())
}
