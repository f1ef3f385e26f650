//! `rtprof profile`: samples a render and writes the evidence of the thesis's table 6
//! and call tree in gprof's own format, plus what gprof cannot give: folded stacks,
//! a flamegraph, a differential flamegraph against another variant, and Amdahl
//! projections. Calls come from a counted render of the same scene and variant. The
//! flags are `runner::profile_settings::ProfileSettings`.

use anyhow::{Context, Result};
use runner::pool::thread_pool;
use runner::profile_job::ProfileJob;
use runner::profile_settings::ProfileSettings;
use terminal::progress::Bars;
use tracer::VariantSet;

pub fn run(args: &ProfileSettings) -> Result<()> {
    // Check both variant lists before any work.
    let set = VariantSet::parse(&args.variant)?;
    let other = args
        .diff_with
        .as_deref()
        .map(VariantSet::parse)
        .transpose()?;
    let scene = args.scene.load(&args.render.limits)?;
    let options = args.render.options(&scene, args.shading.mode());
    let dir = args
        .output
        .clone()
        .unwrap_or_else(|| args.scene.named_after("profile-", ""));
    std::fs::create_dir_all(&dir)
        .with_context(|| format!("cannot create directory {}", dir.display()))?;
    let pool = thread_pool(args.render.threads)?;
    let name = args.scene.to_string();
    let job = ProfileJob {
        scene: &scene,
        options,
        pool: &pool,
        frequency: args.frequency,
        name: &name,
        min_samples: args.min_samples,
        stop: terminal::interrupt::install(),
    };

    let progress = Bars::delayed();
    runner::estimate::note_if_slow(&scene, &options, &set, args.render.threads, &progress)?;
    let report = job.report(&set, other.as_ref(), args.measure_overhead, &progress)?;
    let saved = report.save(&dir, "")?;
    if args.json {
        let mut json = serde_json::to_value(&report)?;
        json["files"] = serde_json::to_value(&saved)?;
        println!("{}", serde_json::to_string_pretty(&json)?);
    } else {
        print!("{}", report.to_text(&dir, &saved));
    }
    Ok(())
}
