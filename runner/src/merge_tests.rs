//! Tests of [`super::merge`]: the sample run split into shards as `--shard` would split
//! it, merged back (order, profile, benchmark figures, files), and every refusal.

use std::path::{Path, PathBuf};

use results::{Results, Shard};
use testkit::{sample_results, write_sample_files};

use super::*;
use crate::shard::select;

/// A scratch directory unique to one test, emptied.
fn scratch(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rtprof-merge-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The sample split into `n` shards, each in its own directory under `dir` with the
/// sample's files; the profile and failures go with the scene they concern.
fn split(dir: &Path, n: u32) -> Vec<(PathBuf, Results)> {
    let whole = sample_results();
    (1..=n)
        .map(|index| {
            let shard = Shard { index, count: n };
            let mut part = whole.clone();
            part.suite.shard = Some(shard);
            part.scenes = select(whole.scenes.clone(), shard);
            let holds = |name: &str| part.scenes.iter().any(|s| s.name == name);
            part.profile = whole.profile.clone().filter(|p| holds(&p.scene));
            part.failures = whole
                .failures
                .iter()
                .filter(|f| f.scene.as_deref().is_some_and(holds))
                .cloned()
                .collect();
            part.created = format!("2025-11-21T17:0{index}:00Z");
            part.suite.wall_seconds = f64::from(index) * 10.0;
            let part_dir = dir.join(format!("part-{index}"));
            write_sample_files(&part_dir).unwrap();
            (part_dir.join("results.json"), part)
        })
        .collect()
}

fn refusal(parts: &[(PathBuf, Results)]) -> String {
    match merge(parts, MergeOptions::default()) {
        Ok(_) => panic!("the merge was not refused"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn shards_merge_back_into_the_whole_run_in_the_suite_order() {
    let dir = scratch("whole");
    let whole = sample_results();
    let mut parts = split(&dir, 3);
    // The order of the arguments does not matter.
    parts.rotate_left(1);
    let merged = merge(&parts, MergeOptions::default()).unwrap();
    assert!(merged.warnings.is_empty(), "{:?}", merged.warnings);
    let r = &merged.results;
    let names = |r: &Results| r.scenes.iter().map(|s| s.name.clone()).collect::<Vec<_>>();
    assert_eq!(names(r), names(&whole));
    assert_eq!(r.scenes, whole.scenes);
    assert_eq!(r.profile, whole.profile);
    assert_eq!(r.failures, whole.failures);
    // Each part carries the same benchmark figures: they appear once.
    assert_eq!(r.criterion, whole.criterion);
    assert_eq!(r.instructions, whole.instructions);
    assert_eq!(r.hardware, whole.hardware);
    assert_eq!(r.suite.shard, None);
    assert_eq!(r.created, "2025-11-21T17:01:00Z");
    assert_eq!(r.suite.wall_seconds, 30.0);
    assert_eq!(r.machine, whole.machine);

    let out = dir.join("out");
    merged.copy_files(&out).unwrap();
    let wanted = referenced_files(r);
    assert!(wanted.len() > 2 * whole.scenes.len(), "{}", wanted.len());
    for rel in &wanted {
        assert_eq!(
            std::fs::read(out.join(rel)).unwrap(),
            std::fs::read(dir.join("part-1").join(rel)).unwrap(),
            "{rel}"
        );
    }
    assert!(
        merged
            .summary(&out, crate::report_files::Pdf::Write)
            .starts_with("merged shards 1/3, 2/3, 3/3: 11 scenes × 6 variants; 1 failure;")
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_profile_of_the_heaviest_scene_is_kept_and_hostnames_are_listed() {
    let dir = scratch("profile");
    let mut parts = split(&dir, 2);
    // rings (the heaviest) sits in shard 1 (position 10); give shard 2 a profile of a
    // lighter scene.
    assert!(parts[0].1.profile.is_some() && parts[1].1.profile.is_none());
    let mut light = parts[0].1.profile.clone().unwrap();
    light.scene = parts[1].1.scenes[0].name.clone();
    parts[1].1.profile = Some(light);
    parts[1].1.machine.hostname = "bench-2".into();
    let merged = merge(&parts, MergeOptions::default()).unwrap();
    assert_eq!(merged.results.profile.unwrap().scene, "rings");
    assert_eq!(merged.results.machine.hostname, "bench-1, bench-2");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn missing_shards_are_warned_of() {
    let dir = scratch("missing");
    let mut parts = split(&dir, 3);
    parts.remove(1);
    let merged = merge(&parts, MergeOptions::default()).unwrap();
    assert_eq!(
        merged.warnings,
        vec!["shard 2/3 missing: the merged results lack its scenes".to_string()]
    );
    // Shards 1 and 3 of 11 scenes: positions 0, 3, 6, 9 and 2, 5, 8, in that order.
    let whole = sample_results();
    let expected: Vec<&str> = [0, 2, 3, 5, 6, 8, 9]
        .iter()
        .map(|&p| whole.scenes[p].name.as_str())
        .collect();
    let got: Vec<&str> = merged
        .results
        .scenes
        .iter()
        .map(|s| s.name.as_str())
        .collect();
    assert_eq!(got, expected);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn parts_that_are_not_one_split_are_always_refused() {
    let dir = scratch("split");
    let parts = split(&dir, 2);
    let allow = MergeOptions { allow_mixed: true };

    let mut whole = parts.clone();
    whole[1].1.suite.shard = None;
    let message = merge(&whole, allow).unwrap_err().to_string();
    assert!(
        message.contains("part-2/results.json is not a shard"),
        "{message}"
    );

    let twice = vec![parts[0].clone(), parts[0].clone()];
    let message = merge(&twice, allow).unwrap_err().to_string();
    assert!(message.contains("are both shard 1/2"), "{message}");

    let mut other_n = parts.clone();
    other_n[1].1.suite.shard = Some(Shard { index: 2, count: 3 });
    let message = merge(&other_n, allow).unwrap_err().to_string();
    assert!(message.contains("is shard 2/3 but"), "{message}");
    assert!(message.contains("one split into N shards"), "{message}");

    let mut overlap = parts.clone();
    let scene = overlap[0].1.scenes[0].clone();
    overlap[1].1.scenes.push(scene);
    let message = merge(&overlap, allow).unwrap_err().to_string();
    assert!(message.contains("scene 'balls1' is in both"), "{message}");

    assert!(
        merge(&[], allow)
            .unwrap_err()
            .to_string()
            .contains("no parts")
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn parts_of_different_suites_binaries_or_machines_are_refused_unless_allowed() {
    let dir = scratch("mixed");
    let parts = split(&dir, 2);
    type Edit = (&'static str, fn(&mut Results));
    let edits: [Edit; 9] = [
        ("suite.name", |r| r.suite.name = "other".into()),
        ("suite.quick", |r| r.suite.quick = true),
        ("suite.variants", |r| {
            r.suite.variants.pop();
        }),
        ("suite.timing", |r| r.suite.timing.min_repeats += 1),
        ("suite.threads", |r| r.suite.threads = 4),
        ("the built-in scenes' size", |r| {
            for s in &mut r.scenes {
                s.width = 320;
            }
        }),
        ("build.git_commit", |r| {
            r.build.git_commit = "0123abc".into()
        }),
        ("machine.cpu_model", |r| {
            r.machine.cpu_model = "other cpu".into()
        }),
        ("machine.cores", |r| r.machine.cores = 64),
    ];
    for (field, edit) in edits {
        let mut mixed = parts.clone();
        edit(&mut mixed[1].1);
        let message = refusal(&mixed);
        assert!(message.starts_with("cannot merge: "), "{message}");
        assert!(
            message.contains(&format!("part-2/results.json has {field} ")),
            "{message}"
        );
        assert!(message.contains("--allow-mixed"), "{message}");
        let merged = merge(&mixed, MergeOptions { allow_mixed: true }).unwrap();
        assert_eq!(merged.results.scenes.len(), 11, "{field}");
    }
    // The hostname and the OS are not a machine class.
    let mut hosts = parts.clone();
    hosts[1].1.machine.hostname = "bench-2".into();
    hosts[1].1.machine.os = "another os".into();
    assert!(merge(&hosts, MergeOptions::default()).is_ok());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn files_missing_or_clashing_are_refused() {
    let dir = scratch("files");
    let mut parts = split(&dir, 2);
    let image = parts[1].1.scenes[0].variants[0].image.clone().unwrap();
    std::fs::remove_file(dir.join("part-2").join(&image)).unwrap();
    let message = refusal(&parts);
    assert!(
        message.contains(&format!(
            "part-2/results.json references {image}, which is not in"
        )),
        "{message}"
    );

    // Shard 2's scene claims shard 1's image path, with other bytes in its directory.
    let claimed = parts[0].1.scenes[0].variants[0].image.clone().unwrap();
    parts[1].1.scenes[0].variants[0].image = Some(claimed.clone());
    std::fs::write(dir.join("part-2").join(&claimed), b"other").unwrap();
    let message = refusal(&parts);
    assert!(
        message.contains(&format!("both hold {claimed}, with different contents")),
        "{message}"
    );
    // The same bytes are no clash.
    std::fs::copy(
        dir.join("part-1").join(&claimed),
        dir.join("part-2").join(&claimed),
    )
    .unwrap();
    assert!(merge(&parts, MergeOptions::default()).is_ok());

    parts[1].1.scenes[0].variants[0].image = Some("../outside.png".into());
    assert!(refusal(&parts).contains("leaves its directory"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_part_is_a_results_file_or_a_directory_holding_one() {
    let dir = scratch("read");
    let results = sample_results();
    std::fs::write(
        dir.join("results.json"),
        serde_json::to_string(&results).unwrap(),
    )
    .unwrap();
    let (from_dir, r1) = read_part(&dir).unwrap();
    let (from_file, r2) = read_part(&dir.join("results.json")).unwrap();
    assert_eq!(from_dir, dir.join("results.json"));
    assert_eq!(from_file, from_dir);
    // (Read back, the file need not equal the value bit for bit: compare what a merge uses.)
    assert_eq!(r1, r2);
    assert_eq!(r1.machine, results.machine);
    assert_eq!(r1.suite.name, results.suite.name);
    let names = |r: &Results| r.scenes.iter().map(|s| s.name.clone()).collect::<Vec<_>>();
    assert_eq!(names(&r1), names(&results));
    assert!(read_part(&dir.join("none")).is_err());
    let _ = std::fs::remove_dir_all(&dir);
}
