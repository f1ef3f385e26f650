//! An outside tracer as a suite definition names it: a built-in peer, a definition
//! file, or a definition in place.

use std::path::Path;

use serde::Deserialize;

use super::definition::TracerDef;
use crate::error::RunError;

/// An outside tracer as a suite definition names it (`[[tracers]]`): a built-in peer,
/// a definition file (from the suite file's directory), or a definition in place.
#[derive(Clone, Debug, Deserialize)]
#[serde(untagged)]
pub enum TracerEntry {
    Peer { peer: String },
    File { file: std::path::PathBuf },
    InPlace(toml::Table),
}

impl TracerEntry {
    /// The definition it names; `suite` names the suite file in errors, `base` is the
    /// directory its relative paths start from, `index` its place among `[[tracers]]`.
    pub fn resolve(&self, suite: &str, base: &Path, index: usize) -> Result<TracerDef, RunError> {
        match self {
            TracerEntry::Peer { peer } => super::peers::peer(peer).unwrap_or_else(|| {
                Err(RunError::Definition {
                    file: suite.to_string(),
                    message: format!(
                        "[[tracers]] #{}: no built-in peer '{peer}' (there are: {})",
                        index + 1,
                        super::peers::PEERS.map(|(n, _)| n).join(", ")
                    ),
                })
            }),
            TracerEntry::File { file } => TracerDef::load(&base.join(file)),
            TracerEntry::InPlace(table) => {
                let text = toml::to_string(table).map_err(|e| RunError::Definition {
                    file: suite.to_string(),
                    message: format!("[[tracers]] #{}: {e}", index + 1),
                })?;
                TracerDef::parse(&text, &format!("{suite} [[tracers]] #{}", index + 1))
            }
        }
    }
}
