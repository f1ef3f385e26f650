//! `rtprof serve`: the local web app (the work is the `serve` crate, whose `Config`
//! declares the flags). Prints where it listens, opens a browser with `--open`, and
//! stops on Ctrl-C (the running job ends as interrupted, its partial outputs kept).

use anyhow::Result;

#[derive(clap::Args, Debug)]
pub struct ServeArgs {
    #[command(flatten)]
    config: serve::Config,
    /// Open the page in the default browser (xdg-open).
    #[arg(long)]
    open: bool,
}

pub fn run(args: &ServeArgs) -> Result<()> {
    let data = args.config.data.display();
    if let Some(warning) = args.config.exposure_warning() {
        eprintln!("rtprof: warning: {warning}");
    }
    let server = serve::Server::start(&args.config)?;
    for note in server.notes() {
        eprintln!("rtprof: {note}");
    }
    eprintln!(
        "rtprof serve: {} (data in {data}; Ctrl-C stops)",
        server.url
    );
    if args.open
        && let Err(message) = server.open_in_browser()
    {
        eprintln!("rtprof: {message}");
    }
    server.serve_until(terminal::interrupt::install(), |note| eprintln!("{note}"));
    Ok(())
}
