//! Which program a tracer definition ran: its resolved path, size and GNU build id, as
//! results.json records it beside the definition, so that two runs of "the same"
//! tracer can be told apart when the program was rebuilt or replaced.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

/// A program as found on disk.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct ProgramIdentity {
    /// The file run (found on `PATH` when the definition names no path).
    pub path: PathBuf,
    /// Its size in bytes.
    pub bytes: u64,
    /// Its GNU build id in hex (`None`: not an ELF file with one, e.g. a script).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub build_id: Option<String>,
}

impl ProgramIdentity {
    /// The program a command's first word names; `None` when it cannot be found.
    pub fn of(program: &str) -> Option<Self> {
        let path = launch::resolve(std::ffi::OsStr::new(program)).ok()?;
        let path = std::fs::canonicalize(&path).unwrap_or(path);
        let bytes = std::fs::metadata(&path).ok()?.len();
        Some(ProgramIdentity {
            build_id: build_id(&path),
            path,
            bytes,
        })
    }
}

/// The ELF file's build id note, in hex.
fn build_id(path: &Path) -> Option<String> {
    use object::Object as _;
    let data = std::fs::read(path).ok()?;
    let file = object::File::parse(&*data).ok()?;
    let id = file.build_id().ok()??;
    Some(id.iter().map(|b| format!("{b:02x}")).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_program_on_path_is_found_with_its_build_id() {
        // `sh` is on every machine that runs rtprof's tests; Debian builds it with a
        // build id (20 bytes of SHA-1: 40 hex digits).
        let sh = ProgramIdentity::of("sh").unwrap();
        assert!(sh.path.is_absolute() && sh.bytes > 0, "{sh:?}");
        let id = sh.build_id.unwrap();
        assert!(
            id.len() >= 16 && id.bytes().all(|b| b.is_ascii_hexdigit()),
            "{id}"
        );
        assert!(ProgramIdentity::of("no-such-program-rtprof").is_none());
    }

    #[test]
    fn a_script_has_no_build_id() {
        let dir = std::env::temp_dir().join(format!("rtprof-identity-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let script = dir.join("tracer.sh");
        std::fs::write(&script, "#!/bin/sh\nexit 0\n").unwrap();
        use std::os::unix::fs::PermissionsExt as _;
        std::fs::set_permissions(&script, std::fs::Permissions::from_mode(0o755)).unwrap();
        let id = ProgramIdentity::of(script.to_str().unwrap()).unwrap();
        assert_eq!((id.bytes, id.build_id), (17, None));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
