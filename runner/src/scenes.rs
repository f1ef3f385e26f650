//! Scene resolution: a suite entry (a built-in name, a generator such as
//! `sphereflake:2`, or a path) or a directory of NFF files becomes a [`SceneSpec`]:
//! its name, where it came from, its family and its text.

use std::path::{Path, PathBuf};

use results::SceneFamily;

use crate::error::RunError;

/// A scene to run.
#[derive(Clone, Debug)]
pub struct SceneSpec {
    pub name: String,
    /// `builtin`, `generated` or the file's path.
    pub source: String,
    pub family: SceneFamily,
    pub text: String,
    pub size: (u32, u32),
}

/// Resolves one suite entry; relative paths start at `base`.
pub fn resolve_scene(entry: &str, size: (u32, u32), base: &Path) -> Result<SceneSpec, RunError> {
    let bad = |message: String| RunError::Scene {
        scene: entry.to_string(),
        message,
    };
    if let Some((kind, param)) = entry.split_once(':') {
        let n: u32 = param
            .parse()
            .map_err(|_| bad(format!("'{param}' is not a number")))?;
        let text = match kind {
            "sphereflake" => tracer::generators::sphereflake(n),
            "lattice" => tracer::generators::lattice(n),
            _ => {
                return Err(bad(format!(
                    "unknown generator '{kind}' (sphereflake, lattice)"
                )));
            }
        }
        .map_err(|e| bad(e.to_string()))?;
        return Ok(SceneSpec {
            name: format!("{kind}{n}"),
            source: "generated".into(),
            family: SceneFamily::Generated,
            text,
            size,
        });
    }
    if let Some(b) = tracer::builtin_scenes::find(entry) {
        return Ok(SceneSpec {
            name: b.name.to_string(),
            source: "builtin".into(),
            family: SceneFamily::of_builtin(b.name),
            text: b.text.to_string(),
            size,
        });
    }
    let path = base.join(entry);
    let text = std::fs::read_to_string(&path).map_err(|e| {
        bad(format!(
            "not a built-in name and cannot read {}: {e}",
            path.display()
        ))
    })?;
    Ok(SceneSpec {
        name: path
            .file_stem()
            .map_or_else(|| entry.to_string(), |s| s.to_string_lossy().into_owned()),
        source: path.display().to_string(),
        family: SceneFamily::Other,
        text,
        size,
    })
}

/// Every `.nff` file of `dir` (sorted), at `size`; a directory named `spd` is the SPD
/// family.
pub fn extra_scenes(dir: &Path, size: (u32, u32)) -> Result<Vec<SceneSpec>, RunError> {
    let entries =
        std::fs::read_dir(dir).map_err(|e| RunError::io("read the directory", dir, &e))?;
    let mut files: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x.eq_ignore_ascii_case("nff")))
        .collect();
    files.sort();
    if files.is_empty() {
        return Err(RunError::Io {
            action: "find scenes in",
            path: dir.to_path_buf(),
            message: "no .nff files there".into(),
        });
    }
    let spd = dir.file_name().is_some_and(|n| n == "spd");
    files
        .into_iter()
        .map(|path| {
            let text =
                std::fs::read_to_string(&path).map_err(|e| RunError::io("read", &path, &e))?;
            Ok(SceneSpec {
                name: path
                    .file_stem()
                    .map_or_else(String::new, |s| s.to_string_lossy().into_owned()),
                source: path.display().to_string(),
                family: if spd {
                    SceneFamily::Spd
                } else {
                    SceneFamily::Other
                },
                text,
                size,
            })
        })
        .collect()
}

/// Loads an NFF file, or a built-in scene when `path` is a bare built-in name that is
/// not also a file.
pub fn load_file_or_builtin(path: &Path) -> Result<tracer::Scene, RunError> {
    if !path.exists()
        && let Some(builtin) = path.to_str().and_then(tracer::builtin_scenes::find)
    {
        return builtin.parse().map_err(|e| RunError::Input(e.to_string()));
    }
    tracer::load_nff(path).map_err(|e| RunError::Input(e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn entries_resolve_to_builtins_generators_and_files() {
        let b = resolve_scene("both3", (8, 6), Path::new(".")).unwrap();
        assert_eq!(
            (b.source.as_str(), b.family),
            ("builtin", SceneFamily::Both)
        );
        let g = resolve_scene("sphereflake:1", (8, 6), Path::new(".")).unwrap();
        assert_eq!(
            (g.name.as_str(), g.family),
            ("sphereflake1", SceneFamily::Generated)
        );
        let err = resolve_scene("cube:2", (8, 6), Path::new(".")).unwrap_err();
        assert!(err.to_string().contains("unknown generator"), "{err}");
        let err = resolve_scene("no-such.nff", (8, 6), Path::new("/nonexistent")).unwrap_err();
        assert!(
            err.to_string().contains("/nonexistent/no-such.nff"),
            "{err}"
        );
    }
}
