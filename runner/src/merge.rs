//! Shards joined: the results of `rtprof suite --shard I/N` runs (made on one machine
//! or several) merged into one results value with the scenes in the suite's order, and
//! the files they reference gathered into one directory.
//!
//! Parts must be shards of one split (same N, each index once, no scene twice): that is
//! always checked. Parts from different suites, binaries or machine classes are refused
//! unless [`MergeOptions::allow_mixed`]: their times would not be comparable.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Component, Path, PathBuf};

use results::{ProfileResult, Results, SceneResult, Shard};

use crate::error::RunError;
use crate::machine::command_line;

/// How strict a merge is.
#[derive(Clone, Copy, Debug, Default)]
pub struct MergeOptions {
    /// Merge parts from different suites, binaries or machine classes anyway.
    pub allow_mixed: bool,
}

/// The merged results, what the user should be warned of, and the files to gather.
#[derive(Debug)]
pub struct Merged {
    pub results: Results,
    /// Things that do not stop the merge (missing shards), one line each.
    pub warnings: Vec<String>,
    /// Where each file the merged results reference comes from: relative path to source.
    files: BTreeMap<String, PathBuf>,
    /// The shards merged, in index order.
    shards: Vec<Shard>,
}

/// Reads one part: a results.json file, or a directory holding one.
pub fn read_part(path: &Path) -> Result<(PathBuf, Results), RunError> {
    let file = if path.is_dir() {
        path.join("results.json")
    } else {
        path.to_path_buf()
    };
    let results = Results::read_file(&file).map_err(|e| RunError::Input(e.to_string()))?;
    Ok((file, results))
}

/// Every file `results` references, relative to its results.json: images, heat maps,
/// emulator images, per-pixel maps, profile texts, flamegraphs and exports.
pub fn referenced_files(results: &Results) -> Vec<String> {
    let mut files: Vec<String> = results.scenes.iter().flat_map(scene_files).collect();
    if let Some(profile) = &results.profile {
        files.extend(profile_files(profile));
    }
    files.extend(
        results
            .outside_profiles
            .iter()
            .flat_map(|p| p.files.iter().cloned()),
    );
    files
}

fn scene_files(scene: &SceneResult) -> Vec<String> {
    let mut files = Vec::new();
    for v in &scene.variants {
        files.extend(v.image.iter().chain(&v.heat_map).cloned());
    }
    if let Some(hw) = &scene.hardware {
        files.extend(hw.emulator_image.iter().chain(&hw.software_image).cloned());
    }
    for maps in &scene.pixel_maps {
        files.push(format!("{}/pixel-stats.json", maps.directory));
        for map in &maps.maps {
            files.push(format!("{}/{}", maps.directory, map.npy));
            files.push(format!("{}/{}", maps.directory, map.png));
        }
    }
    files
}

fn profile_files(p: &ProfileResult) -> Vec<String> {
    let mut files = Vec::new();
    for profile in std::iter::once(&p.baseline).chain(&p.best) {
        files.extend(
            [
                &profile.flat_text,
                &profile.callgraph_text,
                &profile.flame_svg,
            ]
            .map(String::clone),
        );
        if let Some(second) = &profile.second_view {
            files.extend(
                [&second.flat_text, &second.callgraph_text, &second.flame_svg].map(String::clone),
            );
        }
        files.extend(profile.exports.iter().cloned());
    }
    files.extend(
        p.diff_flame_svg
            .iter()
            .chain(&p.diff_shrunk_flame_svg)
            .cloned(),
    );
    files.retain(|f| !f.is_empty());
    files
}

/// One part with what the merge needs of it.
struct Part<'a> {
    label: String,
    dir: PathBuf,
    results: &'a Results,
    shard: Shard,
}

/// Joins `parts` (each a results.json path and its contents) into one run.
pub fn merge(parts: &[(PathBuf, Results)], options: MergeOptions) -> Result<Merged, RunError> {
    let refuse = |message: String| Err(RunError::Input(format!("cannot merge: {message}")));
    let mut shards: Vec<Part<'_>> = Vec::new();
    for (path, results) in parts {
        let label = path.display().to_string();
        let Some(shard) = results.suite.shard else {
            return refuse(format!(
                "{label} is not a shard (made without `rtprof suite --shard I/N`)"
            ));
        };
        let dir = match path.parent() {
            Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
            _ => PathBuf::from("."),
        };
        shards.push(Part {
            label,
            dir,
            results,
            shard,
        });
    }
    shards.sort_by_key(|p| p.shard.index);
    let Some(first) = shards.first() else {
        return refuse("no parts given".into());
    };
    for pair in shards.windows(2) {
        let (a, b) = (&pair[0], &pair[1]);
        if a.shard == b.shard {
            return refuse(format!(
                "{} and {} are both shard {}",
                a.label, b.label, a.shard
            ));
        }
    }
    for p in &shards[1..] {
        if p.shard.count != first.shard.count {
            return refuse(format!(
                "{} is shard {} but {} is shard {}: the parts must come from one split into N shards",
                p.label, p.shard, first.label, first.shard
            ));
        }
        if !options.allow_mixed {
            check_same_class(first, p)?;
        }
    }
    let mut owner: BTreeMap<&str, &str> = BTreeMap::new();
    for p in &shards {
        for scene in &p.results.scenes {
            if let Some(other) = owner.insert(&scene.name, &p.label) {
                return refuse(format!(
                    "scene '{}' is in both {other} and {}",
                    scene.name, p.label
                ));
            }
        }
    }

    let mut warnings = Vec::new();
    let count = first.shard.count;
    let present: BTreeSet<u32> = shards.iter().map(|p| p.shard.index).collect();
    let missing: Vec<String> = (1..=count)
        .filter(|i| !present.contains(i))
        .map(|index| Shard { index, count }.to_string())
        .collect();
    if !missing.is_empty() {
        warnings.push(format!(
            "shard{} {} missing: the merged results lack {} scenes",
            if missing.len() == 1 { "" } else { "s" },
            missing.join(", "),
            if missing.len() == 1 { "its" } else { "their" }
        ));
    }

    // Shard i's j-th scene sat at position j·N + (i − 1) of the suite's order.
    let mut placed: Vec<(usize, &SceneResult, &Part<'_>)> = shards
        .iter()
        .flat_map(|p| {
            p.results
                .scenes
                .iter()
                .enumerate()
                .map(move |(j, s)| (p.shard.position(j), s, p))
        })
        .collect();
    placed.sort_by_key(|&(position, _, _)| position);

    let profiled = heaviest_profile(&shards);
    let mut files = BTreeMap::new();
    for &(_, scene, part) in &placed {
        gather(&mut files, part, scene_files(scene))?;
    }
    if let Some((part, profile)) = profiled {
        gather(&mut files, part, profile_files(profile))?;
        // The outside tracers were recorded on the same scene as that profile.
        let recorded = part.results.outside_profiles.iter();
        gather(
            &mut files,
            part,
            recorded.flat_map(|p| p.files.clone()).collect(),
        )?;
    }

    let mut results = first.results.clone();
    results.created = shards
        .iter()
        .map(|p| p.results.created.clone())
        .min()
        .unwrap_or(results.created);
    results.command = command_line();
    let mut hostnames: Vec<&str> = Vec::new();
    for p in &shards {
        if !hostnames.contains(&p.results.machine.hostname.as_str()) {
            hostnames.push(&p.results.machine.hostname);
        }
    }
    results.machine.hostname = hostnames.join(", ");
    results.suite.shard = None;
    results.suite.wall_seconds = shards
        .iter()
        .map(|p| p.results.suite.wall_seconds)
        .fold(0.0, f64::max);
    results.scenes = placed.iter().map(|&(_, s, _)| s.clone()).collect();
    results.profile = profiled.map(|(_, profile)| profile.clone());
    results.outside_profiles = profiled
        .map(|(part, _)| part.results.outside_profiles.clone())
        .unwrap_or_default();
    results.failures = shards
        .iter()
        .flat_map(|p| p.results.failures.iter().cloned())
        .collect();
    results.criterion = unique_by_id(shards.iter().flat_map(|p| &p.results.criterion), |c| &c.id);
    results.instructions = unique_by_id(shards.iter().flat_map(|p| &p.results.instructions), |c| {
        &c.id
    });
    Ok(Merged {
        results,
        warnings,
        files,
        shards: shards.iter().map(|p| p.shard).collect(),
    })
}

/// Refuses `b` unless it ran the same suite, the same build and on the same machine
/// class as `a`; the message names the field.
fn check_same_class(a: &Part<'_>, b: &Part<'_>) -> Result<(), RunError> {
    type Field = (&'static str, fn(&Results) -> Option<String>);
    let fields: [Field; 12] = [
        ("suite.name", |r| Some(r.suite.name.clone())),
        ("suite.quick", |r| Some(r.suite.quick.to_string())),
        ("suite.variants", |r| {
            let names: Vec<&str> = r.suite.variants.iter().map(|v| v.as_str()).collect();
            Some(names.join(","))
        }),
        ("suite.timing", |r| {
            serde_json::to_string(&r.suite.timing).ok()
        }),
        ("suite.threads", |r| Some(r.suite.threads.to_string())),
        ("the built-in scenes' size", builtin_sizes),
        ("the profile's size", |r| {
            let p = r.profile.as_ref()?;
            Some(format!("{}x{}", p.width, p.height))
        }),
        ("build.rtprof_version", |r| {
            Some(r.build.rtprof_version.clone())
        }),
        ("build.git_commit", |r| Some(r.build.git_commit.clone())),
        ("build.profile", |r| Some(r.build.profile.clone())),
        ("machine.cpu_model", |r| Some(r.machine.cpu_model.clone())),
        ("machine.cores", |r| Some(r.machine.cores.to_string())),
    ];
    for (name, value) in fields {
        // A value one part cannot have (no profile, no built-in scene) is not compared.
        if let (Some(x), Some(y)) = (value(a.results), value(b.results))
            && x != y
        {
            return Err(RunError::Input(format!(
                "cannot merge: {} has {name} {y} but {} has {x}; parts must come from the same suite, binary and machine class (--allow-mixed merges them anyway)",
                b.label, a.label
            )));
        }
    }
    Ok(())
}

/// The sizes of a run's built-in and generated scenes (all at the suite's `size`; scene
/// files may be at `extra_size`), or `None` when it has none.
fn builtin_sizes(r: &Results) -> Option<String> {
    let sizes: BTreeSet<String> = r
        .scenes
        .iter()
        .filter(|s| s.source == "builtin" || s.source == "generated")
        .map(|s| format!("{}x{}", s.width, s.height))
        .collect();
    (!sizes.is_empty()).then(|| sizes.into_iter().collect::<Vec<_>>().join(", "))
}

/// The profile of the part whose profiled scene has the largest baseline median: the
/// heaviest scene of the whole suite, as an unsharded run would have profiled.
fn heaviest_profile<'a>(parts: &'a [Part<'a>]) -> Option<(&'a Part<'a>, &'a ProfileResult)> {
    let baseline = |p: &Part<'_>, profile: &ProfileResult| {
        let scene = p.results.scenes.iter().find(|s| s.name == profile.scene)?;
        Some(p.results.baseline(scene)?.time.median)
    };
    parts
        .iter()
        .filter_map(|p| Some((p, p.results.profile.as_ref()?)))
        .map(|(p, profile)| {
            (
                p,
                profile,
                baseline(p, profile).unwrap_or(f64::NEG_INFINITY),
            )
        })
        // The first of equals wins (max_by keeps the last).
        .rev()
        .max_by(|a, b| a.2.total_cmp(&b.2))
        .map(|(p, profile, _)| (p, profile))
}

/// Records `rels` of `part` to be copied; the same path from two parts must hold the
/// same bytes.
fn gather(
    files: &mut BTreeMap<String, PathBuf>,
    part: &Part<'_>,
    rels: Vec<String>,
) -> Result<(), RunError> {
    for rel in rels {
        if !Path::new(&rel)
            .components()
            .all(|c| matches!(c, Component::Normal(_)))
        {
            return Err(RunError::Input(format!(
                "cannot merge: {} references '{rel}', which leaves its directory",
                part.label
            )));
        }
        let source = part.dir.join(&rel);
        if !source.is_file() {
            return Err(RunError::Input(format!(
                "cannot merge: {} references {rel}, which is not in {}",
                part.label,
                part.dir.display()
            )));
        }
        if let Some(other) = files.get(&rel) {
            let read = |p: &Path| std::fs::read(p).map_err(|e| RunError::io("read", p, &e));
            if read(other)? != read(&source)? {
                return Err(RunError::Input(format!(
                    "cannot merge: {} and {} both hold {rel}, with different contents",
                    other.display(),
                    source.display()
                )));
            }
            continue;
        }
        files.insert(rel, source);
    }
    Ok(())
}

/// The items in order, each id once (the first kept): every shard picks up the same
/// benchmark figures.
fn unique_by_id<'a, T: Clone + 'a>(
    items: impl Iterator<Item = &'a T>,
    id: impl Fn(&T) -> &String,
) -> Vec<T> {
    let mut seen = BTreeSet::new();
    items
        .filter(|item| seen.insert(id(item).clone()))
        .cloned()
        .collect()
}

impl Merged {
    /// Writes the merged run into `output` (created if missing) as the suite writes a
    /// run: the parts' files, results.json and the reports staged, then published;
    /// report.pdf's pages when it was written.
    pub fn write_into(
        &self,
        output: &Path,
        pdf: crate::report_files::Pdf,
    ) -> Result<Option<reports::pdf::PageCount>, RunError> {
        std::fs::create_dir_all(output).map_err(|e| RunError::io("create", output, &e))?;
        let staging = crate::staging::Staging::create(output)?;
        self.copy_files(staging.dir())?;
        let pages = crate::report_files::write_run(&self.results, staging.dir(), pdf)?;
        staging.publish(output)?;
        pdf.remove_stale(output)?;
        Ok(pages)
    }

    /// Copies every file the merged results reference into `dir` (same relative path).
    pub fn copy_files(&self, dir: &Path) -> Result<(), RunError> {
        for (rel, source) in &self.files {
            let bytes = std::fs::read(source).map_err(|e| RunError::io("read", source, &e))?;
            crate::staging::save(dir, rel, &bytes)?;
        }
        Ok(())
    }

    /// What the merge did, for the user: shards, scenes, failures, where it wrote.
    pub fn summary(&self, output: &Path, pdf: crate::report_files::Pdf) -> String {
        let shards: Vec<String> = self.shards.iter().map(Shard::to_string).collect();
        let failures = self.results.failures.len();
        let mut text = format!(
            "merged shards {}: {} scenes × {} variants; {failures} failure{}; wrote {}/{{results.json, {}, variants.csv, summary.md}}\n",
            shards.join(", "),
            self.results.scenes.len(),
            self.results.suite.variants.len(),
            if failures == 1 { "" } else { "s" },
            output.display(),
            pdf.documents()
        );
        for f in &self.results.failures {
            text += &format!("  failed: {}: {}\n", f.place(), f.message);
        }
        text
    }
}

#[cfg(test)]
#[path = "merge_tests.rs"]
mod tests;
