//! `rtprof suite`: the main job (the work is `runner::suite`). Writes `results.json`,
//! `report.html` and `report.pdf` through a staging directory; with `--baseline` it
//! then gates the run against an earlier one.

use super::{Exports, Format, Outcome};
use anyhow::Result;
use runner::RunError;
use runner::definition::SuiteDef;
use runner::staging::{discarded_message, save};
use runner::suite::Suite;
use runner::suite_dir::{DirRun, RunWritten, run_into_dir};
use std::path::{Path, PathBuf};
use std::time::Instant;
use terminal::progress::Bars;

#[derive(clap::Args, Debug)]
pub struct SuiteArgs {
    /// Suite definition (TOML; default: the embedded suite, scenes/suite.toml).
    suite: Option<PathBuf>,
    /// Output directory.
    #[arg(short, long, value_name = "DIR", default_value = "rtprof-suite")]
    output: PathBuf,
    /// The CI-sized run: smaller images, fewer scenes and repeats.
    #[arg(long)]
    quick: bool,
    /// Compare with an earlier results.json: exit 1 on a significant slow-down or any
    /// changed count.
    #[arg(long, value_name = "RESULTS.json")]
    baseline: Option<PathBuf>,
    #[command(flatten)]
    gate: super::gate::GateFlags,
    /// Add every .nff file of this directory (e.g. ../shared/spd).
    #[arg(long, value_name = "DIR")]
    scenes: Option<PathBuf>,
    /// Also run Intel Embree, the peer: the yardstick as its users run it (rtprof-embree,
    /// scripts/build-embree-peer.sh) and, built with `--features embree`, inside rtprof.
    #[arg(long)]
    embree: bool,
    /// Threads of the timed renders (default: the suite's `timing_threads`, one; the
    /// untimed work uses every core). docs/gate.md says why.
    #[arg(long, value_name = "N", value_parser = runner::pool::parse_threads)]
    threads: Option<u16>,
    /// Run shard I of N: every Nth scene (all its variants), for `rtprof merge`.
    #[arg(long, value_name = "I/N", value_parser = runner::shard::parse_shard)]
    shard: Option<results::Shard>,
    #[command(flatten)]
    benchmarks: runner::benchmarks::BenchmarkDirs,
    #[command(flatten)]
    pdf: runner::report_files::PdfFlag,
    #[command(flatten)]
    tracers: runner::outside::TracerFlags,
}

pub fn run(args: &SuiteArgs) -> Result<()> {
    let started = Instant::now();
    let mut def = SuiteDef::load(args.suite.as_deref())?;
    if args.embree {
        def = def.with_embree_variants();
    }
    // Check the inputs first: a bad --baseline or --criterion should fail before the work.
    args.benchmarks.check()?;
    let old = match &args.baseline {
        Some(path) => Some(results::Results::read_file(path)?),
        None => None,
    };
    let base_dir = args
        .suite
        .as_ref()
        .and_then(|p| p.parent().map(Path::to_path_buf))
        .unwrap_or_default();
    let suite = Suite::prepare(def, args.quick, &base_dir, args.scenes.as_deref())?
        .with_shard(args.shard)?
        .with_tracer_flags(&args.tracers)?
        .with_embree_yardstick(args.embree)?;
    let stop = terminal::interrupt::install();
    let pdf = args.pdf.choice();
    let run = DirRun {
        threads: args.threads,
        progress: &Bars::default(),
        stop,
        pdf,
        keep_partial: None,
    };
    let add_benchmarks = &mut |results: &mut results::Results| -> Result<(), RunError> {
        let added = args.benchmarks.add_to(results, true)?;
        added.iter().for_each(|line| eprintln!("{line}"));
        Ok(())
    };
    let written = run_into_dir(&suite, &args.output, &run, add_benchmarks);
    let RunWritten { results, pages } = written.map_err(|e| -> anyhow::Error {
        match e.stopped_scenes(suite.scenes.len()) {
            Some((done, total)) => {
                let message = discarded_message(&args.output, done, total);
                Outcome::new(Outcome::INTERRUPTED, message).into()
            }
            None => e.into(),
        }
    })?;
    let seconds = started.elapsed().as_secs_f64();
    eprint!("{}", suite.summary(&results, seconds, &args.output, pdf));
    if let Some(p) = pages {
        eprintln!("{}", reports::format::pdf_pages(p.total, p.main_body));
    }
    if let Some(old) = old {
        let gate = args.gate.gate(&old, &results)?;
        let text = gate.render(Format::Text)?;
        print!("{text}");
        for (name, form) in [
            ("gate.txt", text),
            ("gate.md", gate.render(Format::Markdown)?),
        ] {
            save(&args.output, name, form.as_bytes())?;
        }
        super::gate::outcome(&gate)?;
    }
    match Suite::failures_message(&results) {
        Some(message) => Err(Outcome::new(Outcome::PARTS_FAILED, message).into()),
        None => Ok(()),
    }
}
