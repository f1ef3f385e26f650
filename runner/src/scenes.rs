//! Scene resolution: a suite entry (a built-in name, a generator such as
//! `sphereflake:2`, or a path) or a directory of NFF files becomes a [`SceneSpec`]:
//! its name, where it came from, its family and its text.

use std::path::{Path, PathBuf};

use results::SceneFamily;

use crate::error::RunError;
use crate::scene_input::SceneInput;

/// A scene to run.
#[derive(Clone, Debug)]
pub struct SceneSpec {
    pub name: String,
    /// `builtin`, `generated` or the file's path.
    pub source: String,
    pub family: SceneFamily,
    pub text: String,
    pub size: (u32, u32),
    /// SPD corner sampling ((W+1)×(H+1) rays, each pixel the mean of four).
    pub spd_sampling: bool,
    /// The variants to run when not the suite's (a subset: the SPD's full frame).
    pub variants: Option<Vec<String>>,
    /// Whether the suite may pick it as the heaviest scene to profile.
    pub profile_candidate: bool,
    /// Rendered on one thread rather than the suite's (the SPD's small frames: see
    /// [`crate::definition::SpdDef::small_on_one_thread`]).
    pub one_thread: bool,
    /// The SPD's small every-variant run ([`SceneSpec::spd_pair`]).
    pub small_spd_run: bool,
    /// What the entry named (`None` for a file found in a `--scenes` directory).
    pub input: Option<SceneInput>,
}

impl SceneSpec {
    /// The variants this scene runs in `def`'s suite: its own subset, or the suite's.
    pub fn variants_in<'a>(&'a self, def: &'a crate::definition::SuiteDef) -> &'a [String] {
        self.variants.as_deref().unwrap_or(&def.variants)
    }

    /// Whether the suite's outside tracers run on it: on every scene but the SPD's
    /// small every-variant run (its frame is for brute force; the tracers draw the
    /// scene at the SPD's own frame).
    pub fn runs_tracers(&self) -> bool {
        !self.small_spd_run
    }

    /// The two runs of an SPD entry (see [`crate::definition::SpdDef`]): the accelerated
    /// variants at `full_size` with corner sampling, named as the scene, and every
    /// variant at `size`, named `NAME-small`.
    pub fn spd_pair(
        entry: &str,
        def: &crate::definition::SpdDef,
        base: &Path,
    ) -> Result<[SceneSpec; 2], RunError> {
        let full_size = (def.full_size[0], def.full_size[1]);
        let full = SceneSpec {
            spd_sampling: true,
            variants: Some(def.full_variants.clone()),
            profile_candidate: false,
            ..resolve_scene(entry, full_size, base)?
        };
        let small = SceneSpec {
            name: format!("{}-small", full.name),
            small_spd_run: true,
            size: (def.size[0], def.size[1]),
            spd_sampling: false,
            variants: None,
            one_thread: def.small_on_one_thread,
            ..full.clone()
        };
        Ok([full, small])
    }
}

/// Resolves one suite entry (see [`SceneInput`]); relative paths start at `base`.
pub fn resolve_scene(entry: &str, size: (u32, u32), base: &Path) -> Result<SceneSpec, RunError> {
    let input = SceneInput::parse(entry, base)?;
    let text = input
        .text(&tracer::Limits::default())
        .map_err(|e| match e {
            RunError::Io { path, message, .. } => RunError::Scene {
                scene: entry.to_string(),
                message: format!(
                    "not a built-in name (`rtprof scene list`) and cannot read {}: {message}",
                    path.display()
                ),
            },
            other => other,
        })?;
    Ok(SceneSpec {
        name: input.name(),
        source: input.source(),
        family: input.family(),
        text,
        size,
        spd_sampling: false,
        small_spd_run: false,
        variants: None,
        profile_candidate: true,
        one_thread: false,
        input: Some(input),
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
                small_spd_run: false,
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
                spd_sampling: false,
                variants: None,
                profile_candidate: true,
                one_thread: false,
                input: None,
            })
        })
        .collect()
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
        let spd = resolve_scene("spd:tetra:1", (8, 6), Path::new(".")).unwrap();
        assert_eq!(
            (spd.name.as_str(), spd.source.as_str(), spd.family),
            ("tetra-sf1", "spd:tetra:1", SceneFamily::Spd)
        );
        let err = resolve_scene("no-such.nff", (8, 6), Path::new("/nonexistent")).unwrap_err();
        assert!(
            err.to_string().contains("/nonexistent/no-such.nff"),
            "{err}"
        );
    }
}
