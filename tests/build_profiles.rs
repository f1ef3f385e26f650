//! The build profiles keep their rules (docs/build-times.md): dependencies build at
//! opt-level 0 without debug info except a list of hot crates at opt-level 3, the same
//! list in the test and release profiles (cargo has no shared lists, so it is written
//! twice and checked here), and every crate the lists name is one the build has (a crate
//! renamed or dropped by an upgrade would otherwise leave its entry silently unused).

use std::collections::BTreeSet;
use toml::Table;

fn manifest() -> Table {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/Cargo.toml");
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    text.parse().unwrap_or_else(|e| panic!("{path}: {e}"))
}

fn lock_names() -> BTreeSet<String> {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/Cargo.lock");
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let lock: Table = text.parse().unwrap_or_else(|e| panic!("{path}: {e}"));
    lock["package"]
        .as_array()
        .expect("Cargo.lock lists packages")
        .iter()
        .map(|p| p["name"].as_str().expect("a package has a name").to_owned())
        .collect()
}

/// The `[profile.<name>.package]` table.
fn overrides(manifest: &Table, profile: &str) -> Table {
    manifest["profile"][profile]["package"]
        .as_table()
        .unwrap_or_else(|| panic!("no [profile.{profile}.package] table"))
        .clone()
}

/// The packages a profile builds at `opt-level = 3`.
fn hot(overrides: &Table) -> BTreeSet<String> {
    overrides
        .iter()
        .filter(|(_, o)| o.get("opt-level").and_then(|v| v.as_integer()) == Some(3))
        .map(|(name, _)| name.clone())
        .collect()
}

#[test]
fn dependencies_build_unoptimized_without_debug_info_but_the_hot_ones() {
    let manifest = manifest();
    for profile in ["dev", "release"] {
        let all = &overrides(&manifest, profile)["*"];
        assert_eq!(
            all.get("opt-level").and_then(|v| v.as_integer()),
            Some(0),
            "[profile.{profile}.package] \"*\" should build dependencies at opt-level 0"
        );
        assert_eq!(
            all.get("debug").and_then(|v| v.as_bool()),
            Some(false),
            "[profile.{profile}.package] \"*\" should build dependencies without debug info"
        );
    }
    let dev = hot(&overrides(&manifest, "dev"));
    let release = hot(&overrides(&manifest, "release"));
    assert!(dev.len() >= 10, "the hot list is nearly empty: {dev:?}");
    assert_eq!(
        dev, release,
        "the hot crates differ between [profile.dev.package] and [profile.release.package]"
    );
}

#[test]
fn the_profiles_name_only_crates_the_build_has() {
    let manifest = manifest();
    let names = lock_names();
    for profile in ["dev", "release"] {
        for name in overrides(&manifest, profile).keys() {
            assert!(
                name == "*" || names.contains(name),
                "[profile.{profile}.package] names {name}, which is not in Cargo.lock"
            );
        }
    }
}

#[test]
fn rtprof_s_own_crates_keep_one_codegen_unit_and_the_profiler_s_debug_info() {
    let release = &manifest()["profile"]["release"];
    assert_eq!(release["codegen-units"].as_integer(), Some(1));
    assert_eq!(release["debug"].as_str(), Some("limited"));
    // tracer holds the renderers (tracer::RenderWith): it must not be split.
    let overrides = overrides(&manifest(), "release");
    assert!(
        overrides
            .get("tracer")
            .is_none_or(|t| t.get("codegen-units").is_none()),
        "tracer is split into several codegen units"
    );
}
