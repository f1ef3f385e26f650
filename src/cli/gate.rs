//! `rtprof gate OLD.json NEW.json`: the regression gate of `suite --baseline` on two
//! saved results files (for a CI that keeps its runs): exit 1 when a variant is
//! significantly slower or any count changed, 0 otherwise, 2 when the runs cannot be
//! compared.

use super::{Exports, Format, Outcome};
use anyhow::Result;
use results::gate::{GateOptions, GateReport};
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct GateArgs {
    /// The earlier run's results.json (the reference).
    #[arg(value_name = "OLD.json")]
    old: PathBuf,
    /// The new run's results.json.
    #[arg(value_name = "NEW.json")]
    new: PathBuf,
    #[command(flatten)]
    options: GateFlags,
    /// Output: a table, GitHub Markdown (a pull-request comment or job summary), CSV or JSON.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    format: Format,
}

// The gate's flags, shared with `suite --baseline`.
#[derive(clap::Args, Debug)]
pub struct GateFlags {
    /// Noise threshold in percent: a relative time must change by more than this (and
    /// its 95 % interval exclude no change) to be slower or faster [default: the
    /// measured run-to-run noise, 20 % (docs/gate.md); 50 % with --strict].
    #[arg(long, value_name = "PCT", value_parser = analysis::verdict::parse_threshold_percent)]
    threshold: Option<f64>,
    /// Gate runs that are not comparable (another suite, frame size, thread count or
    /// machine) anyway; the output says what differs.
    #[arg(long)]
    force: bool,
    /// Gate against a baseline kept in a repository (benches/baseline.json): instruction
    /// counts must stay within 1 % either way, every scene × variant and benchmark must
    /// be in both runs, another machine of the same kind is allowed (docs/benchmarks.md).
    #[arg(long)]
    strict: bool,
}

impl GateFlags {
    /// Gates `new` against `old`; runs that cannot be compared are an error (exit 2).
    pub fn gate(&self, old: &results::Results, new: &results::Results) -> Result<GateReport> {
        let default = match self.strict {
            true => results::gate::STRICT_THRESHOLD,
            false => results::NOISE_THRESHOLD,
        };
        let options = GateOptions {
            threshold: self.threshold.map_or(default, |pct| pct / 100.0),
            force: self.force,
            strict: self.strict,
        };
        Ok(results::gate::gate(old, new, options)?)
    }
}

/// Exit 1 when the gate failed.
pub fn outcome(gate: &GateReport) -> Result<()> {
    if gate.failed() {
        return Err(Outcome::new(Outcome::CHECK_FAILED, "the regression gate failed").into());
    }
    Ok(())
}

pub fn run(args: &GateArgs) -> Result<()> {
    let old = results::Results::read_file(&args.old)?;
    let new = results::Results::read_file(&args.new)?;
    let gate = args.options.gate(&old, &new)?;
    print!("{}", gate.render(args.format)?);
    outcome(&gate)
}
