//! `rtprof variants`: every optimization variant with a one-line description, and the
//! measured accuracy of the approximating ones (sqrt error from the exhaustive scan,
//! diffuse-term error of the sqrt-free shading).

use anyhow::Result;

#[derive(clap::Args, Debug)]
pub struct VariantsArgs {
    /// Print the list as JSON.
    #[arg(long)]
    json: bool,
}

pub fn run(args: &VariantsArgs) -> Result<()> {
    let catalogue = runner::variant_catalogue::catalogue();
    if args.json {
        println!("{}", serde_json::to_string_pretty(&catalogue.variants)?);
    } else {
        print!("{}", catalogue.to_text());
    }
    Ok(())
}
