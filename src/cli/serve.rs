//! `rtprof serve`: the local web app (the work is the `serve` crate). Prints where it
//! listens, opens a browser with `--open`, and stops on Ctrl-C (the running job ends
//! as interrupted, its partial outputs kept).

use anyhow::{Result, bail};
use std::net::IpAddr;
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct ServeArgs {
    /// Port to listen on (0: any free port; the address is printed and written to
    /// DIR/server.json).
    #[arg(long, default_value_t = 8080)]
    port: u16,
    /// Open the page in the default browser (xdg-open).
    #[arg(long)]
    open: bool,
    /// Data directory: every job's outputs (jobs/ID/results.json, report.html, ...),
    /// uploaded scenes and server.json (the address and token, for scripts).
    #[arg(long, value_name = "DIR", default_value = "rtprof-data")]
    data: PathBuf,
    /// Address to listen on. Anything but a loopback address lets other machines drive
    /// this server (they still need its token to change anything).
    #[arg(long, value_name = "ADDRESS", default_value = "127.0.0.1")]
    bind: IpAddr,
    /// Largest scene upload, bytes.
    #[arg(long, value_name = "BYTES", default_value_t = serve::DEFAULT_MAX_UPLOAD_BYTES)]
    max_upload_bytes: u64,
}

pub fn run(args: &ServeArgs) -> Result<()> {
    if args.max_upload_bytes == 0 {
        bail!("--max-upload-bytes must be positive");
    }
    if !args.bind.is_loopback() {
        eprintln!(
            "rtprof: warning: listening on {}: other machines can reach this server; \
             state-changing requests still need its token (in {}/server.json)",
            args.bind,
            args.data.display()
        );
    }
    let config = serve::Config {
        bind: args.bind,
        port: args.port,
        data: args.data.clone(),
        max_upload_bytes: args.max_upload_bytes,
    };
    let server = serve::Server::start(&config)?;
    for name in &server.skipped {
        eprintln!(
            "rtprof: warning: {}/jobs/{name} is not a readable job; left alone",
            args.data.display()
        );
    }
    eprintln!(
        "rtprof serve: {} (data in {}; Ctrl-C stops)",
        server.url,
        args.data.display()
    );
    if args.open {
        let opened = std::process::Command::new("xdg-open")
            .arg(&server.url)
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn();
        if opened.is_err() {
            eprintln!(
                "rtprof: could not start a browser (xdg-open); open {} yourself",
                server.url
            );
        }
    }
    let stop = terminal::interrupt::install();
    while !stop.load(std::sync::atomic::Ordering::SeqCst) {
        std::thread::sleep(std::time::Duration::from_millis(100));
    }
    if server.busy() {
        eprintln!(
            "rtprof serve: stopping the job under way (within a sample row); it is kept as interrupted"
        );
    }
    server.stop();
    Ok(())
}
