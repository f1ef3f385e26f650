//! The command-line flags that bring outside tracers into a run (`rtprof compare`,
//! `rtprof suite`): declared here, beside what they load, behind the `clap` feature.

use std::path::PathBuf;

use super::definition::TracerDef;
use crate::error::RunError;

// `--tracer FILE` (repeatable), `--spp N` and `--peers`. (A plain comment: clap would
// take a doc comment as the about of every command that flattens these flags.)
#[derive(Clone, Debug, Default)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
pub struct TracerFlags {
    /// An outside tracer's definition (TOML, docs/tracers.md), or a built-in peer's
    /// name (povray, tachyon, embree-yardstick, embree-yardstick-single, rtprof), run
    /// beside the variants; repeat for several.
    #[cfg_attr(feature = "clap", arg(long = "tracer", value_name = "FILE"))]
    pub tracers: Vec<PathBuf>,
    /// Samples per pixel of the outside tracers' timed runs ({spp}; default: each
    /// definition's own, else 1).
    #[cfg_attr(
        feature = "clap",
        arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=1_000_000))
    )]
    pub spp: Option<u32>,
    /// Also run every built-in peer that is installed (POV-Ray, Tachyon, the Embree
    /// yardstick, rtprof itself); the others are named as missing.
    #[cfg_attr(feature = "clap", arg(long))]
    pub peers: bool,
}

impl TracerFlags {
    /// Every definition named, read and checked, and with `--peers` every installed
    /// built-in peer not named already; the names of the peers not installed.
    pub fn load_with_peers(&self) -> Result<(Vec<TracerDef>, Vec<String>), RunError> {
        let mut defs = self.load()?;
        let mut missing = Vec::new();
        if self.peers {
            for (def, installed) in super::peers::peers()? {
                if defs.iter().any(|d| d.name == def.name) {
                    continue;
                }
                match installed {
                    true => defs.push(def),
                    false => missing.push(def.name),
                }
            }
        }
        Ok((defs, missing))
    }

    /// Every definition named, read and checked; two with one name are refused.
    pub fn load(&self) -> Result<Vec<TracerDef>, RunError> {
        let mut defs: Vec<TracerDef> = Vec::new();
        for path in &self.tracers {
            let builtin = path
                .to_str()
                .filter(|_| !path.exists())
                .and_then(super::peers::peer);
            let def = match builtin {
                Some(def) => def?,
                None => TracerDef::load(path)?,
            };
            if let Some(other) = defs.iter().find(|d| d.name == def.name) {
                return Err(RunError::Definition {
                    file: def.file.clone(),
                    message: format!(
                        "tracer name '{}' is also {}'s: give each its own name",
                        def.name, other.file
                    ),
                });
            }
            defs.push(def);
        }
        Ok(defs)
    }
}
