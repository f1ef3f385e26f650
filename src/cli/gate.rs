//! `rtprof gate OLD.json NEW.json`: the regression gate of `suite --baseline` on two
//! saved results files (for a CI that keeps its runs): exit 1 when a variant is
//! significantly slower or any count changed, 0 otherwise.

use anyhow::Result;
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct GateArgs {
    /// The earlier run's results.json (the reference).
    #[arg(value_name = "OLD.json")]
    old: PathBuf,
    /// The new run's results.json.
    #[arg(value_name = "NEW.json")]
    new: PathBuf,
    /// Slow-down tolerated beyond the intervals, in percent.
    #[arg(long, value_name = "PCT", default_value_t = 5.0,
          value_parser = super::suite::parse_threshold)]
    threshold: f64,
    /// Print the comparison as JSON instead of a table.
    #[arg(long)]
    json: bool,
}

pub fn run(args: &GateArgs) -> Result<()> {
    let old = results::Results::read_file(&args.old)?;
    let new = results::Results::read_file(&args.new)?;
    let gate = results::gate::compare_runs(&old, &new, args.threshold / 100.0);
    if args.json {
        println!("{}", serde_json::to_string_pretty(&gate)?);
    } else {
        print!("{}", gate.to_text());
    }
    if gate.failed() {
        return Err(super::Outcome::new(
            super::Outcome::CHECK_FAILED,
            "the regression gate failed",
        )
        .into());
    }
    Ok(())
}
