//! An outside tracer as a suite definition names it: a built-in peer, a definition
//! file, or a definition in place; with `record = true`, its run on the suite's profile
//! scene is also recorded with perf (`rtprof record`'s profile).

use std::path::Path;

use serde::Deserialize;

use super::definition::TracerDef;
use crate::error::RunError;

/// An outside tracer as a suite definition names it (`[[tracers]]`): a built-in peer,
/// a definition file (from the suite file's directory), or a definition in place. Each
/// may say `record = true`: its run on the suite's profile scene is recorded with perf.
#[derive(Clone, Debug, Deserialize)]
#[serde(untagged)]
pub enum TracerEntry {
    Peer {
        peer: String,
        #[serde(default)]
        record: bool,
    },
    File {
        file: std::path::PathBuf,
        #[serde(default)]
        record: bool,
    },
    InPlace(toml::Table),
}

/// The key of an entry asking for a recording.
const RECORD: &str = "record";

impl TracerEntry {
    /// Whether the suite asks for its run on the profile scene to be recorded with
    /// perf (`record = true`); a value that is not a boolean is refused by
    /// [`TracerEntry::resolve`].
    pub fn record(&self) -> bool {
        match self {
            TracerEntry::Peer { record, .. } | TracerEntry::File { record, .. } => *record,
            TracerEntry::InPlace(table) => {
                table.get(RECORD).and_then(toml::Value::as_bool) == Some(true)
            }
        }
    }
}

impl TracerEntry {
    /// The definition it names; `suite` names the suite file in errors, `base` is the
    /// directory its relative paths start from, `index` its place among `[[tracers]]`.
    pub fn resolve(&self, suite: &str, base: &Path, index: usize) -> Result<TracerDef, RunError> {
        match self {
            TracerEntry::Peer { peer, .. } => super::peers::peer(peer).unwrap_or_else(|| {
                Err(RunError::Definition {
                    file: suite.to_string(),
                    message: format!(
                        "[[tracers]] #{}: no built-in peer '{peer}' (there are: {})",
                        index + 1,
                        super::peers::PEERS.map(|(n, _)| n).join(", ")
                    ),
                })
            }),
            TracerEntry::File { file, .. } => TracerDef::load(&base.join(file)),
            TracerEntry::InPlace(table) => {
                let mut table = table.clone();
                // `record` is the suite's, not the definition's.
                match table.remove(RECORD) {
                    None | Some(toml::Value::Boolean(_)) => {}
                    Some(other) => {
                        return Err(RunError::Definition {
                            file: suite.to_string(),
                            message: format!(
                                "[[tracers]] #{}: record must be true or false, not {other}",
                                index + 1
                            ),
                        });
                    }
                }
                let text = toml::to_string(&table).map_err(|e| RunError::Definition {
                    file: suite.to_string(),
                    message: format!("[[tracers]] #{}: {e}", index + 1),
                })?;
                TracerDef::parse(&text, &format!("{suite} [[tracers]] #{}", index + 1))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::definition::SuiteDef;

    const SUITE: &str = "name = \"s\"\nsize = [8, 8]\nrepeats = 1\nvariants = [\"baseline\"]\nscenes = [\"balls1\"]\nextra_size = [8, 8]\nprofile_size = [8, 8]\nhardware_repeats = 1\n";

    fn suite(more: &str) -> Result<SuiteDef, crate::RunError> {
        SuiteDef::parse(&format!("{SUITE}{more}"), "s.toml")
    }

    #[test]
    fn record_is_the_suites_on_each_kind_of_entry_and_refused_without_a_profile() {
        let place = "[[tracers]]\nname = \"t\"\ncommand = [\"t\", \"{scene}\", \"{output}\"]\nscene = \"nff\"\nimage = \"ppm\"\ntime = \"process\"\n";
        let def = suite(&format!(
            "[[tracers]]\npeer = \"tachyon\"\nrecord = true\n[[tracers]]\nfile = \"x.toml\"\n{place}record = true\n"
        ))
        .unwrap();
        let asked: Vec<bool> = def.tracers.iter().map(|t| t.record()).collect();
        assert_eq!(asked, [true, false, true]);
        // The in-place definition is read without the suite's key.
        let resolved = def.tracers[2].resolve("s.toml", std::path::Path::new("."), 2);
        assert_eq!(resolved.unwrap().name, "t");
        let e = suite(&format!("profile = false\n{place}record = true\n")).unwrap_err();
        assert!(e.to_string().contains("profile = false"), "{e}");
        let def = suite(&format!("{place}record = \"yes\"\n")).unwrap();
        let e = def.tracers[0]
            .resolve("s.toml", std::path::Path::new("."), 0)
            .unwrap_err();
        assert!(
            e.to_string().contains("record must be true or false"),
            "{e}"
        );
    }
}
