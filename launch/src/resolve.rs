//! Finding a program the way a shell would, without one: a name with a `/` is a path,
//! any other name is looked up in `PATH`'s directories in order. Done before starting
//! it, so that "not found" and "not executable" are told apart and name the program
//! (std's spawn gives only an `io::Error`, after a fork).

use std::ffi::OsStr;
use std::os::unix::fs::PermissionsExt;
use std::path::{Path, PathBuf};

use crate::LaunchError;

/// The file `program` names, if it is there and executable.
pub fn resolve(program: &OsStr) -> Result<PathBuf, LaunchError> {
    let name = program.to_string_lossy().into_owned();
    if program.is_empty() {
        return Err(LaunchError::NotFound { program: name });
    }
    if program.as_encoded_bytes().contains(&b'/') {
        return check(Path::new(program), &name).map(|()| PathBuf::from(program));
    }
    let path = std::env::var_os("PATH").unwrap_or_default();
    let mut not_executable = None;
    for dir in std::env::split_paths(&path) {
        // An empty entry is the current directory, as in a shell.
        let dir = if dir.as_os_str().is_empty() {
            PathBuf::from(".")
        } else {
            dir
        };
        let candidate = dir.join(program);
        match check(&candidate, &name) {
            Ok(()) => return Ok(candidate),
            Err(e @ LaunchError::NotExecutable { .. }) => {
                not_executable.get_or_insert(e);
            }
            Err(_) => {}
        }
    }
    Err(not_executable.unwrap_or(LaunchError::NotFound { program: name }))
}

/// `path` is a regular file with an execute bit.
fn check(path: &Path, name: &str) -> Result<(), LaunchError> {
    let meta = std::fs::metadata(path).map_err(|_| LaunchError::NotFound {
        program: name.to_string(),
    })?;
    if meta.is_dir() || meta.permissions().mode() & 0o111 == 0 {
        return Err(LaunchError::NotExecutable {
            program: name.to_string(),
            reason: if meta.is_dir() {
                "it is a directory".into()
            } else {
                "it has no execute permission".into()
            },
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_name_is_found_on_path_and_a_missing_one_is_named() {
        let sh = resolve(OsStr::new("sh")).unwrap();
        assert!(sh.is_absolute() || sh.starts_with("."), "{}", sh.display());
        let err = resolve(OsStr::new("no-such-program-rtprof")).unwrap_err();
        assert!(
            matches!(&err, LaunchError::NotFound { program } if program == "no-such-program-rtprof")
        );
        assert!(err.to_string().contains("no-such-program-rtprof"));
    }

    #[test]
    fn a_file_without_execute_permission_and_a_directory_are_not_executable() {
        let dir = std::env::temp_dir().join(format!("launch-resolve-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("data.txt");
        std::fs::write(&file, "not a program").unwrap();
        let err = resolve(file.as_os_str()).unwrap_err();
        assert!(matches!(err, LaunchError::NotExecutable { .. }), "{err}");
        let err = resolve(dir.as_os_str()).unwrap_err();
        assert!(err.to_string().contains("directory"), "{err}");
        assert!(matches!(
            resolve(dir.join("missing").as_os_str()),
            Err(LaunchError::NotFound { .. })
        ));
        assert!(matches!(
            resolve(OsStr::new("")),
            Err(LaunchError::NotFound { .. })
        ));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
