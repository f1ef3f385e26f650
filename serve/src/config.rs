//! How to serve: address, port, data directory, the upload limit and the outside
//! tracers jobs may run (`--tracer FILE`, `--peers`: loaded and checked at start, never
//! named by a request). With the `clap` feature these are also `rtprof serve`'s flags,
//! declared here once.

use std::net::{IpAddr, Ipv4Addr};
use std::path::PathBuf;

use crate::DEFAULT_MAX_UPLOAD_BYTES;

// How to serve. (A plain comment: clap would take a doc comment as the about of the
// command that flattens these flags.)
#[derive(Clone, Debug)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
pub struct Config {
    /// Address to listen on. Anything but a loopback address lets other machines drive
    /// this server (they still need its token to change anything).
    #[cfg_attr(
        feature = "clap",
        arg(long, value_name = "ADDRESS", default_value = "127.0.0.1")
    )]
    pub bind: IpAddr,
    /// Port to listen on (0: any free port; the address is printed and written to
    /// DIR/server.json).
    #[cfg_attr(feature = "clap", arg(long, default_value_t = 8080))]
    pub port: u16,
    /// Data directory: every job's outputs (jobs/ID/results.json, report.html, ...),
    /// uploaded scenes and server.json (the address and token, for scripts).
    #[cfg_attr(
        feature = "clap",
        arg(long, value_name = "DIR", default_value = "rtprof-data")
    )]
    pub data: PathBuf,
    /// Largest scene upload, bytes.
    #[cfg_attr(feature = "clap", arg(long, value_name = "BYTES",
        default_value_t = DEFAULT_MAX_UPLOAD_BYTES,
        value_parser = clap::value_parser!(u64).range(1..)))]
    pub max_upload_bytes: u64,
    /// The outside tracers the page offers (docs/tracers.md): definition files and
    /// built-in peers, read and checked when the server starts. A job names one of
    /// them by its name; nothing a request sends is ever run as a command.
    #[cfg_attr(feature = "clap", command(flatten))]
    pub tracers: runner::outside::TracerFlags,
}

impl Default for Config {
    fn default() -> Self {
        Config {
            bind: IpAddr::V4(Ipv4Addr::LOCALHOST),
            port: 8080,
            data: PathBuf::from("rtprof-data"),
            max_upload_bytes: DEFAULT_MAX_UPLOAD_BYTES,
            tracers: runner::outside::TracerFlags::default(),
        }
    }
}

impl Config {
    /// The warning a bind beyond this machine deserves, `None` on a loopback address.
    pub fn exposure_warning(&self) -> Option<String> {
        (!self.bind.is_loopback()).then(|| {
            format!(
                "listening on {}: other machines can reach this server; state-changing \
                 requests still need its token (in {}/server.json)",
                self.bind,
                self.data.display()
            )
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_a_bind_beyond_loopback_warns() {
        assert_eq!(Config::default().exposure_warning(), None);
        let open = Config {
            bind: IpAddr::V4(Ipv4Addr::UNSPECIFIED),
            ..Config::default()
        };
        let warning = open.exposure_warning().unwrap_or_default();
        assert!(
            warning.contains("0.0.0.0") && warning.contains("rtprof-data/server.json"),
            "{warning}"
        );
    }
}
